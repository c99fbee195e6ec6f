//! Sweeps of the planar cases (normal, oblique, tangential restitution).

use super::{Cell, SweepCase};
use crate::error::{ImpactError, Input, Result};
use crate::exact::{self, Precision};
use crate::normal::{self, NormalImpact};
use crate::oblique::{self, KineticRestitution, TangentialLaw};
use crate::planar::{Outputs, PlanarOutcome};
use crate::scene::{Body, Contact, PlanarScene, PlanarVelocity};
use crate::tangential;

/// Which planar model and tangential law a sweep evaluates; fixed for the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlanarLaw {
    /// Normal impact of a point mass (no inertia, contact or spin).
    PointMass,
    /// Normal impact of a rigid body on a frictionless contact.
    Frictionless,
    /// A prescribed impulse ratio `μ`.
    ImpulseRatio,
    /// Coulomb friction `f`.
    Friction,
    /// The bilinear tangential-restitution model (`f`, `e_t`).
    TangentialRestitution,
    /// The Appendix's two-phase kinetic model (`R`, `μ_A`, `μ_R`).
    KineticRestitution,
}

impl PlanarLaw {
    /// Whether the law reads `input` (never a torsional-only input).
    pub fn reads(self, input: Input) -> bool {
        use Input as I;
        match input {
            I::Mass | I::NormalVelocity | I::TangentialVelocity | I::AngularVelocity => true,
            I::Inertia | I::TangentialOffset | I::NormalOffset => self != PlanarLaw::PointMass,
            I::Restitution => self != PlanarLaw::KineticRestitution,
            I::Friction => matches!(self, PlanarLaw::Friction | PlanarLaw::TangentialRestitution),
            I::ImpulseRatio => self == PlanarLaw::ImpulseRatio,
            I::TangentialRestitution => self == PlanarLaw::TangentialRestitution,
            I::KineticRestitution | I::ApproachImpulseRatio | I::ReboundImpulseRatio => {
                self == PlanarLaw::KineticRestitution
            }
            I::NormalInertia | I::Spin | I::TorsionalRestitution | I::TorsionalFriction | I::PitchRadius => {
                false
            }
        }
    }

    /// The law's name, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            PlanarLaw::PointMass => "a point mass",
            PlanarLaw::Frictionless => "a frictionless rigid body",
            PlanarLaw::ImpulseRatio => "a prescribed impulse ratio",
            PlanarLaw::Friction => "Coulomb friction",
            PlanarLaw::TangentialRestitution => "tangential restitution",
            PlanarLaw::KineticRestitution => "two-phase kinetic restitution",
        }
    }
}

/// Every input of a planar impact; a law reads the ones it needs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarPoint {
    /// Mass `m`.
    pub mass: f64,
    /// Centroidal moment of inertia `I` (unused for a point mass).
    pub inertia: f64,
    /// Contact geometry.
    pub contact: Contact,
    /// Initial velocities.
    pub velocity: PlanarVelocity,
    /// Kinematic coefficient of restitution `e`.
    pub restitution: f64,
    /// Coulomb friction `f`.
    pub friction: f64,
    /// Prescribed impulse ratio `μ`.
    pub impulse_ratio: f64,
    /// Tangential coefficient of restitution `e_t`.
    pub tangential_restitution: f64,
    /// The two-phase kinetic model.
    pub kinetic: KineticRestitution,
}

impl PlanarPoint {
    /// The point as a normal impact of a point mass (no inertia, no contact
    /// offsets), the form `PlanarLaw::PointMass` is solved in.
    pub fn point_mass_impact(&self) -> NormalImpact {
        NormalImpact {
            mass: self.mass,
            inertia: None,
            contact: None,
            velocity: self.velocity,
            restitution: self.restitution,
        }
    }
}

/// The inputs of the planar cases an axis can set.
pub const PLANAR_INPUTS: [Input; 14] = [
    Input::Mass,
    Input::Inertia,
    Input::TangentialOffset,
    Input::NormalOffset,
    Input::NormalVelocity,
    Input::TangentialVelocity,
    Input::AngularVelocity,
    Input::Restitution,
    Input::Friction,
    Input::ImpulseRatio,
    Input::TangentialRestitution,
    Input::KineticRestitution,
    Input::ApproachImpulseRatio,
    Input::ReboundImpulseRatio,
];

/// Whether an input is part of the scene (body, contact, velocity).
fn is_scene(input: Input) -> bool {
    matches!(
        input,
        Input::Mass
            | Input::Inertia
            | Input::TangentialOffset
            | Input::NormalOffset
            | Input::NormalVelocity
            | Input::TangentialVelocity
            | Input::AngularVelocity
    )
}

/// An output of a planar impact that a column can show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PlanarColumn {
    /// `V_n`.
    FinalNormalVelocity,
    /// `V_t`.
    FinalTangentialVelocity,
    /// `Ω`.
    FinalAngularVelocity,
    /// `v_cn`.
    InitialContactNormal,
    /// `v_ct`.
    InitialContactTangential,
    /// `V_cn`.
    FinalContactNormal,
    /// `V_ct`.
    FinalContactTangential,
    /// `P_n`.
    NormalImpulse,
    /// `P_t`.
    TangentialImpulse,
    /// `μ`.
    ImpulseRatio,
    /// `μ_c`.
    CriticalImpulseRatio,
    /// `e`.
    Restitution,
    /// `R`.
    KineticRestitution,
    /// The regime's name.
    Regime,
    /// Initial kinetic energy.
    InitialEnergy,
    /// Final kinetic energy.
    FinalEnergy,
    /// `T_L`.
    EnergyLoss,
    /// `T_M`.
    MaxEnergyLoss,
    /// `T_L*`.
    NormalizedEnergyLoss,
}

impl PlanarColumn {
    fn needs_energy(self) -> bool {
        matches!(
            self,
            PlanarColumn::InitialEnergy
                | PlanarColumn::FinalEnergy
                | PlanarColumn::EnergyLoss
                | PlanarColumn::MaxEnergyLoss
                | PlanarColumn::NormalizedEnergyLoss
        )
    }

    /// The column's value; `energy` is the outcome's energies (zero when not computed).
    fn cell(self, o: &PlanarOutcome, energy: &crate::energy::PlanarEnergy) -> Cell {
        Cell::Number(match self {
            PlanarColumn::FinalNormalVelocity => o.final_velocity.normal,
            PlanarColumn::FinalTangentialVelocity => o.final_velocity.tangential,
            PlanarColumn::FinalAngularVelocity => o.final_velocity.angular,
            PlanarColumn::InitialContactNormal => o.contact_velocity.initial.normal,
            PlanarColumn::InitialContactTangential => o.contact_velocity.initial.tangential,
            PlanarColumn::FinalContactNormal => o.contact_velocity.r#final.normal,
            PlanarColumn::FinalContactTangential => o.contact_velocity.r#final.tangential,
            PlanarColumn::NormalImpulse => o.impulse.normal,
            PlanarColumn::TangentialImpulse => o.impulse.tangential,
            PlanarColumn::ImpulseRatio => o.impulse_ratio,
            PlanarColumn::CriticalImpulseRatio => o.critical_impulse_ratio.unwrap_or(f64::NAN),
            PlanarColumn::Restitution => o.restitution,
            PlanarColumn::KineticRestitution => o.kinetic_restitution,
            PlanarColumn::Regime => return Cell::Text(o.regime.as_str()),
            PlanarColumn::InitialEnergy => energy.initial,
            PlanarColumn::FinalEnergy => energy.r#final,
            PlanarColumn::EnergyLoss => energy.loss,
            PlanarColumn::MaxEnergyLoss => energy.max_loss,
            PlanarColumn::NormalizedEnergyLoss => energy.normalized_loss,
        })
    }
}

/// A planar case prepared for a sweep: the law, the outputs its columns need,
/// the precision, and (fast mode) the scene when no axis changes it
/// (validated once, not per point).
#[derive(Debug, Clone)]
pub struct PlanarSweep {
    law: PlanarLaw,
    columns: Vec<PlanarColumn>,
    outputs: Outputs,
    precision: Precision,
    fixed_scene: Option<Result<PlanarScene>>,
    /// The inputs whose range the fast mode checks per point: the swept ones
    /// when every fixed input is in range, else all the law reads.
    range_checked: Vec<Input>,
}

impl PlanarSweep {
    /// Prepares `law` for a sweep from `base` in which the axes set `swept`,
    /// computing only what `columns` need.
    pub fn new(law: PlanarLaw, base: &PlanarPoint, swept: &[Input], columns: Vec<PlanarColumn>) -> Self {
        let outputs = Outputs {
            critical_impulse_ratio: columns.contains(&PlanarColumn::CriticalImpulseRatio),
            energy: columns.iter().any(|c| c.needs_energy()),
        };
        let fixed_in_range =
            read_inputs(law).all(|input| swept.contains(&input) || in_fast_range(get(base, input)));
        let range_checked = read_inputs(law)
            .filter(|input| !fixed_in_range || swept.contains(input))
            .collect();
        // Out of range, the exact evaluator builds its own scene per point.
        let fixed_scene =
            (law != PlanarLaw::PointMass && fixed_in_range && !swept.iter().any(|&p| is_scene(p)))
                .then(|| scene(base));
        PlanarSweep {
            law,
            columns,
            outputs,
            precision: Precision::Fast,
            fixed_scene,
            range_checked,
        }
    }

    /// The same sweep answered in `precision`.
    pub fn with_precision(self, precision: Precision) -> Self {
        PlanarSweep { precision, ..self }
    }

    /// The optional outputs the columns need.
    pub fn outputs(&self) -> Outputs {
        self.outputs
    }

    /// Whether the scene is prepared once for the whole sweep.
    pub fn has_fixed_scene(&self) -> bool {
        self.fixed_scene.is_some()
    }

    /// Solves one point with every output the columns need.
    pub fn solve(&self, p: &PlanarPoint) -> Result<PlanarOutcome> {
        if self.precision == Precision::Exact {
            return exact::solve_planar(self.law, p, self.outputs);
        }
        match &self.fixed_scene {
            Some(Ok(scene)) => escalate(
                self.law,
                p,
                self.range_checked.iter().copied(),
                self.outputs,
                || solve_in_scene(self.law, scene, p, self.outputs),
            ),
            Some(Err(e)) => Err(e.clone()),
            None => escalate(
                self.law,
                p,
                self.range_checked.iter().copied(),
                self.outputs,
                || closed_forms(self.law, p, self.outputs),
            ),
        }
    }
}

/// Solves one planar impact under `law` in `precision`, computing the optional `outputs`.
pub fn solve_point(
    law: PlanarLaw,
    p: &PlanarPoint,
    outputs: Outputs,
    precision: Precision,
) -> Result<PlanarOutcome> {
    match precision {
        Precision::Fast => solve_fast(law, p, outputs),
        Precision::Exact => exact::solve_planar(law, p, outputs),
    }
}

/// The largest and smallest magnitudes (2^±200) the fast closed forms take:
/// products of up to five such inputs stay normal doubles, so no intermediate
/// overflows or loses bits to underflow.
const FAST_RANGE: (f64, f64) = (
    1.0 / (1u128 << 100) as f64 / (1u128 << 100) as f64,
    (1u128 << 100) as f64 * (1u128 << 100) as f64,
);

/// Whether the fast closed forms take `x` (zero, or a magnitude in [`FAST_RANGE`]).
pub(crate) fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (FAST_RANGE.0..=FAST_RANGE.1).contains(&x.abs())
}

/// The value of one planar input of a point.
fn get(p: &PlanarPoint, input: Input) -> f64 {
    match input {
        Input::Mass => p.mass,
        Input::Inertia => p.inertia,
        Input::TangentialOffset => p.contact.tangential_offset,
        Input::NormalOffset => p.contact.normal_offset,
        Input::NormalVelocity => p.velocity.normal,
        Input::TangentialVelocity => p.velocity.tangential,
        Input::AngularVelocity => p.velocity.angular,
        Input::Restitution => p.restitution,
        Input::Friction => p.friction,
        Input::ImpulseRatio => p.impulse_ratio,
        Input::TangentialRestitution => p.tangential_restitution,
        Input::KineticRestitution => p.kinetic.value,
        Input::ApproachImpulseRatio => p.kinetic.approach_impulse_ratio,
        Input::ReboundImpulseRatio => p.kinetic.rebound_impulse_ratio,
        _ => 0.0,
    }
}

/// The fast mode's answer: the closed forms when every input the law reads is
/// in [`FAST_RANGE`]; otherwise, and to confirm an output that overflows, the
/// exact evaluator, which neither overflows nor underflows in between.
///
/// `checked` are the inputs whose range is checked here; a sweep checks only
/// its swept inputs per point, having checked the rest once.
fn escalate(
    law: PlanarLaw,
    p: &PlanarPoint,
    checked: impl IntoIterator<Item = Input>,
    outputs: Outputs,
    closed_forms: impl FnOnce() -> Result<PlanarOutcome>,
) -> Result<PlanarOutcome> {
    if !checked.into_iter().all(|input| in_fast_range(get(p, input))) {
        return exact::solve_planar(law, p, outputs);
    }
    match closed_forms() {
        Err(ImpactError::OutputNotFinite { .. }) => exact::solve_planar(law, p, outputs),
        answer => answer,
    }
}

/// Solves one planar impact in the fast mode.
fn solve_fast(law: PlanarLaw, p: &PlanarPoint, outputs: Outputs) -> Result<PlanarOutcome> {
    escalate(law, p, read_inputs(law), outputs, || {
        closed_forms(law, p, outputs)
    })
}

/// The inputs `law` reads.
fn read_inputs(law: PlanarLaw) -> impl Iterator<Item = Input> {
    PLANAR_INPUTS.into_iter().filter(move |&input| law.reads(input))
}

/// Solves one planar impact by the f64 closed forms.
fn closed_forms(law: PlanarLaw, p: &PlanarPoint, outputs: Outputs) -> Result<PlanarOutcome> {
    if law == PlanarLaw::PointMass {
        return normal::solve(&p.point_mass_impact(), outputs);
    }
    solve_in_scene(law, &scene(p)?, p, outputs)
}

/// Solves `law` in a scene already built from `p`'s body, contact and velocity.
fn solve_in_scene(
    law: PlanarLaw,
    scene: &PlanarScene,
    p: &PlanarPoint,
    outputs: Outputs,
) -> Result<PlanarOutcome> {
    match law {
        PlanarLaw::PointMass | PlanarLaw::Frictionless => normal::solve_scene(scene, p.restitution, outputs),
        PlanarLaw::ImpulseRatio => oblique::solve(
            scene,
            p.restitution,
            TangentialLaw::ImpulseRatio(p.impulse_ratio),
            outputs,
        ),
        PlanarLaw::Friction => {
            oblique::solve(scene, p.restitution, TangentialLaw::Friction(p.friction), outputs)
        }
        PlanarLaw::TangentialRestitution => tangential::solve(
            scene,
            p.restitution,
            p.friction,
            p.tangential_restitution,
            outputs,
        ),
        PlanarLaw::KineticRestitution => oblique::solve_kinetic(scene, p.kinetic, outputs),
    }
}

fn scene(p: &PlanarPoint) -> Result<PlanarScene> {
    PlanarScene::new(Body::new(p.mass, p.inertia)?, p.contact, p.velocity)
}

impl SweepCase for PlanarSweep {
    type Point = PlanarPoint;
    type Param = Input;

    /// Sets a planar input; torsional-only inputs are not part of a planar
    /// point (callers choose axes from [`PLANAR_INPUTS`]) and leave it unchanged.
    fn set(p: &mut PlanarPoint, input: Input, v: f64) {
        match input {
            Input::Mass => p.mass = v,
            Input::Inertia => p.inertia = v,
            Input::TangentialOffset => p.contact.tangential_offset = v,
            Input::NormalOffset => p.contact.normal_offset = v,
            Input::NormalVelocity => p.velocity.normal = v,
            Input::TangentialVelocity => p.velocity.tangential = v,
            Input::AngularVelocity => p.velocity.angular = v,
            Input::Restitution => p.restitution = v,
            Input::Friction => p.friction = v,
            Input::ImpulseRatio => p.impulse_ratio = v,
            Input::TangentialRestitution => p.tangential_restitution = v,
            Input::KineticRestitution => p.kinetic.value = v,
            Input::ApproachImpulseRatio => p.kinetic.approach_impulse_ratio = v,
            Input::ReboundImpulseRatio => p.kinetic.rebound_impulse_ratio = v,
            Input::NormalInertia
            | Input::Spin
            | Input::TorsionalRestitution
            | Input::TorsionalFriction
            | Input::PitchRadius => {}
        }
    }

    fn columns(&self) -> usize {
        self.columns.len()
    }

    fn evaluate(&self, p: &PlanarPoint, cells: &mut [Cell]) -> std::result::Result<(), ImpactError> {
        let outcome = self.solve(p)?;
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
    use crate::sweep::{Axis, AxisValues, Combine, Sweep};

    fn maw() -> PlanarPoint {
        PlanarPoint {
            mass: 1.0,
            inertia: 0.5 * 0.05 * 0.05,
            contact: Contact::central(0.05),
            velocity: PlanarVelocity {
                normal: -1.0,
                tangential: 2.0,
                angular: 0.0,
            },
            restitution: 0.93,
            friction: 0.123,
            tangential_restitution: 0.34,
            ..PlanarPoint::default()
        }
    }

    #[test]
    fn a_fixed_scene_gives_the_same_answers_as_one_built_per_point() {
        let base = maw();
        let columns = vec![PlanarColumn::FinalContactTangential, PlanarColumn::EnergyLoss];
        let fixed = PlanarSweep::new(
            PlanarLaw::TangentialRestitution,
            &base,
            &[Input::Friction],
            columns.clone(),
        );
        let per_point = PlanarSweep::new(
            PlanarLaw::TangentialRestitution,
            &base,
            &[Input::TangentialVelocity],
            columns,
        );
        assert!(fixed.has_fixed_scene() && !per_point.has_fixed_scene());
        assert!(fixed.outputs().energy && !fixed.outputs().critical_impulse_ratio);
        for f in [0.0, 0.05, 0.123, 0.5] {
            let p = PlanarPoint { friction: f, ..base };
            assert_eq!(fixed.solve(&p), per_point.solve(&p));
            assert_eq!(
                fixed.solve(&p).unwrap(),
                tangential::solve(&scene(&p).unwrap(), 0.93, f, 0.34, fixed.outputs()).unwrap()
            );
        }
    }

    #[test]
    fn invalid_points_fail_alone() {
        let case = PlanarSweep::new(
            PlanarLaw::Friction,
            &maw(),
            &[Input::NormalVelocity],
            vec![PlanarColumn::Regime],
        );
        let axes = vec![Axis {
            param: Input::NormalVelocity,
            values: AxisValues::List(vec![-1.0, 0.5, -2.0]),
        }];
        let sweep = Sweep::new(case, maw(), axes, Combine::Product, 10).unwrap();
        let mut outcomes = Vec::new();
        sweep.for_each_in(0..3, |row| {
            outcomes.push(row.outcome.map(|c| c.to_vec()).map_err(|e| e.title()))
        });
        assert_eq!(outcomes[0], Ok(vec![Cell::Text("sliding")]));
        assert_eq!(outcomes[1], Err("Contact is not approaching"));
        assert_eq!(outcomes[2], Ok(vec![Cell::Text("sliding")]));
    }
}
