//! Sweeps of the torsional case.

use super::{Cell, SweepCase};
use crate::error::{ImpactError, Input, Result};
use crate::exact::{self, Precision};
use crate::sweep::planar::in_fast_range;
use crate::torsional::{self, TorsionalImpact, TorsionalOutcome};

/// The inputs of the torsional case an axis can set.
pub const TORSIONAL_INPUTS: [Input; 8] = [
    Input::Mass,
    Input::NormalInertia,
    Input::NormalVelocity,
    Input::Spin,
    Input::Restitution,
    Input::TorsionalRestitution,
    Input::TorsionalFriction,
    Input::PitchRadius,
];

/// An output of a torsional impact that a column can show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TorsionalColumn {
    /// `V_n`.
    FinalNormalVelocity,
    /// `Ω_n`.
    FinalSpin,
    /// `P_n`.
    NormalImpulse,
    /// `M_n`.
    TorsionalImpulse,
    /// The regime's name.
    Regime,
    /// `ω_s` (Eq 31).
    SwitchSpin,
    /// Initial rotational energy.
    InitialEnergy,
    /// Final rotational energy.
    FinalEnergy,
    /// Rotational energy lost.
    EnergyLoss,
}

impl TorsionalColumn {
    fn needs_energy(self) -> bool {
        matches!(
            self,
            TorsionalColumn::InitialEnergy | TorsionalColumn::FinalEnergy | TorsionalColumn::EnergyLoss
        )
    }

    /// The column's value; `energy` is the outcome's energies (zero when not computed).
    fn cell(self, o: &TorsionalOutcome, energy: &crate::torsional::RotationalEnergy) -> Cell {
        Cell::Number(match self {
            TorsionalColumn::FinalNormalVelocity => o.final_normal_velocity,
            TorsionalColumn::FinalSpin => o.final_spin,
            TorsionalColumn::NormalImpulse => o.normal_impulse,
            TorsionalColumn::TorsionalImpulse => o.torsional_impulse,
            TorsionalColumn::Regime => return Cell::Text(o.regime.as_str()),
            TorsionalColumn::SwitchSpin => o.switch_spin,
            TorsionalColumn::InitialEnergy => energy.initial,
            TorsionalColumn::FinalEnergy => energy.r#final,
            TorsionalColumn::EnergyLoss => energy.loss,
        })
    }
}

/// Solves one torsional impact in `precision`; `energy` chooses whether energies are computed.
pub fn solve_torsional(
    impact: &TorsionalImpact,
    energy: bool,
    precision: Precision,
) -> Result<TorsionalOutcome> {
    let in_range = [
        impact.mass,
        impact.normal_inertia,
        impact.normal_velocity,
        impact.spin,
        impact.restitution,
        impact.torsional_restitution,
        impact.torsional_friction,
        impact.pitch_radius,
    ]
    .into_iter()
    .all(in_fast_range);
    match precision {
        // As for the planar cases: extreme inputs and overflowing outputs go to the exact evaluator.
        Precision::Fast if in_range => match torsional::solve(impact, energy) {
            Err(ImpactError::OutputNotFinite { .. }) => exact::solve_torsional(impact, energy),
            answer => answer,
        },
        _ => exact::solve_torsional(impact, energy),
    }
}

/// The torsional case prepared for a sweep: energies only when a column needs them.
#[derive(Debug, Clone)]
pub struct TorsionalSweep {
    columns: Vec<TorsionalColumn>,
    energy: bool,
    precision: Precision,
}

impl TorsionalSweep {
    /// Prepares a sweep computing only what `columns` need.
    pub fn new(columns: Vec<TorsionalColumn>) -> Self {
        let energy = columns.iter().any(|c| c.needs_energy());
        TorsionalSweep {
            columns,
            energy,
            precision: Precision::Fast,
        }
    }

    /// The same sweep answered in `precision`.
    pub fn with_precision(self, precision: Precision) -> Self {
        TorsionalSweep { precision, ..self }
    }
}

impl SweepCase for TorsionalSweep {
    type Point = TorsionalImpact;
    type Param = Input;

    /// Sets a torsional input; planar-only inputs are not part of a torsional
    /// impact (callers choose axes from [`TORSIONAL_INPUTS`]) and leave it unchanged.
    fn set(p: &mut TorsionalImpact, input: Input, v: f64) {
        match input {
            Input::Mass => p.mass = v,
            Input::NormalInertia => p.normal_inertia = v,
            Input::NormalVelocity => p.normal_velocity = v,
            Input::Spin => p.spin = v,
            Input::Restitution => p.restitution = v,
            Input::TorsionalRestitution => p.torsional_restitution = v,
            Input::TorsionalFriction => p.torsional_friction = v,
            Input::PitchRadius => p.pitch_radius = v,
            _ => {}
        }
    }

    fn columns(&self) -> usize {
        self.columns.len()
    }

    fn evaluate(&self, p: &TorsionalImpact, cells: &mut [Cell]) -> std::result::Result<(), ImpactError> {
        let outcome = solve_torsional(p, self.energy, self.precision)?;
        let energy = outcome.energy.unwrap_or_default();
        for (cell, column) in cells.iter_mut().zip(&self.columns) {
            *cell = column.cell(&outcome, &energy);
        }
        Ok(())
    }
}
