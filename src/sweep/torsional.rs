//! Sweeps of the torsional case.

use super::{Cell, SweepCase};
use crate::error::{ImpactError, Input, Result};
use crate::exact::{self, Precision};
use crate::sweep::planar::in_fast_range;
use crate::torsional::{self, TorsionalImpact, TorsionalOutcome};

/// The inputs of the torsional case: every one it reads, and an axis can set each.
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

/// The value of one of the [`TORSIONAL_INPUTS`] (every input a torsional impact reads).
fn get(p: &TorsionalImpact, input: Input) -> f64 {
    match input {
        Input::Mass => p.mass,
        Input::NormalInertia => p.normal_inertia,
        Input::NormalVelocity => p.normal_velocity,
        Input::Spin => p.spin,
        Input::Restitution => p.restitution,
        Input::TorsionalRestitution => p.torsional_restitution,
        Input::TorsionalFriction => p.torsional_friction,
        _ => p.pitch_radius,
    }
}

/// Solves one torsional impact in `precision`; `energy` chooses whether energies are computed.
pub fn solve_torsional(
    impact: &TorsionalImpact,
    energy: bool,
    precision: Precision,
) -> Result<TorsionalOutcome> {
    let in_range = TORSIONAL_INPUTS
        .iter()
        .all(|&input| in_fast_range(get(impact, input)));
    solve_checked(impact, energy, precision, in_range)
}

/// As [`solve_torsional`], told whether every input is in the fast range.
#[inline]
fn solve_checked(
    impact: &TorsionalImpact,
    energy: bool,
    precision: Precision,
    in_range: bool,
) -> Result<TorsionalOutcome> {
    match precision {
        // As for the planar cases: extreme inputs and overflowing outputs go to the exact evaluator.
        Precision::Fast if in_range => match torsional::solve(impact, energy) {
            Err(ImpactError::OutputNotFinite { .. }) => solve_exact(impact, energy),
            answer => answer,
        },
        _ => solve_exact(impact, energy),
    }
}

/// The exact evaluator, kept out of line so the fast path's loop stays small.
#[inline(never)]
fn solve_exact(impact: &TorsionalImpact, energy: bool) -> Result<TorsionalOutcome> {
    exact::solve_torsional(impact, energy)
}

/// The torsional case prepared for a sweep: energies only when a column needs
/// them, and the fast range of the fixed inputs checked once.
#[derive(Debug, Clone)]
pub struct TorsionalSweep {
    columns: Vec<TorsionalColumn>,
    energy: bool,
    precision: Precision,
    /// Whether every input no axis sets is in the fast range.
    fixed_in_range: bool,
    /// The inputs whose range is checked per point: the swept ones.
    swept: Vec<Input>,
}

impl TorsionalSweep {
    /// Prepares a sweep from `base` in which the axes set `swept`, computing
    /// only what `columns` need.
    pub fn new(base: &TorsionalImpact, swept: &[Input], columns: Vec<TorsionalColumn>) -> Self {
        let energy = columns.iter().any(|c| c.needs_energy());
        let fixed_in_range = TORSIONAL_INPUTS
            .iter()
            .all(|&input| swept.contains(&input) || in_fast_range(get(base, input)));
        TorsionalSweep {
            columns,
            energy,
            precision: Precision::Fast,
            fixed_in_range,
            swept: TORSIONAL_INPUTS
                .into_iter()
                .filter(|input| swept.contains(input))
                .collect(),
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
        let in_range = self.fixed_in_range && self.swept.iter().all(|&input| in_fast_range(get(p, input)));
        let outcome = solve_checked(p, self.energy, self.precision, in_range)?;
        let energy = outcome.energy.unwrap_or_default();
        for (cell, column) in cells.iter_mut().zip(&self.columns) {
            *cell = column.cell(&outcome, &energy);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::{Axis, AxisValues, Cell, Combine, Sweep};

    fn base() -> TorsionalImpact {
        TorsionalImpact {
            mass: 0.6,
            normal_inertia: 0.003456,
            normal_velocity: -3.0,
            spin: 0.0,
            restitution: 0.7,
            torsional_restitution: 0.2,
            torsional_friction: 0.3,
            pitch_radius: 0.01,
        }
    }

    /// Final spins of a spin sweep from `base` over `spins`.
    fn swept(base: TorsionalImpact, spins: Vec<f64>) -> Vec<f64> {
        let case = TorsionalSweep::new(&base, &[Input::Spin], vec![TorsionalColumn::FinalSpin]);
        let axes = vec![Axis {
            param: Input::Spin,
            values: AxisValues::List(spins),
        }];
        let sweep = Sweep::new(case, base, axes, Combine::Product, u64::MAX).expect("a sweep");
        let mut out = Vec::new();
        sweep.for_each_in(0..sweep.points(), |row| match row.outcome {
            Ok([Cell::Number(x)]) => out.push(*x),
            other => panic!("{other:?}"),
        });
        out
    }

    /// Out-of-range inputs, fixed or swept, are answered as `solve_torsional` answers them.
    #[test]
    fn extreme_fixed_and_swept_inputs_escalate_as_single_solves_do() {
        let spins = vec![20.0, 1e250, -3e-250, 0.0];
        for b in [
            base(),
            TorsionalImpact {
                mass: 1e-250,
                ..base()
            },
        ] {
            let got = swept(b, spins.clone());
            for (spin, got) in spins.iter().zip(got) {
                let one = solve_torsional(&TorsionalImpact { spin: *spin, ..b }, false, Precision::Fast)
                    .expect("an answer");
                assert_eq!(
                    got.to_bits(),
                    one.final_spin.to_bits(),
                    "spin {spin}, mass {}",
                    b.mass
                );
            }
        }
    }
}
