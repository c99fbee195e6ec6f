//! The torsional case (section 4): spin about the contact normal.

use super::{Arithmetic, Case, Model, Stage, evaluate};
use crate::arith::Radical;
use crate::error::{ImpactError, Input, Output, Result, finite, in_range, positive};
use crate::model::Exact;
use crate::model::torsional::{Torsion, torsional};
use crate::outcome::{Outputs, TorsionalOutcome};
use crate::quantity::Value;

/// A torsional impact: a body spinning about the contact normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionalImpact {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Moment of inertia about the normal axis `I_n > 0`.
    pub normal_inertia: f64,
    /// Initial normal velocity `v_n < 0`.
    pub normal_velocity: f64,
    /// Initial spin about the normal `ω_n`.
    pub spin: f64,
    /// Kinematic coefficient of restitution `e ∈ [0, 1]`.
    pub restitution: f64,
    /// Torsional coefficient of restitution `e_z ∈ [0, 1]`.
    pub torsional_restitution: f64,
    /// Torsional friction coefficient `μ_z ≥ 0` (a magnitude).
    pub torsional_friction: f64,
    /// Pitch radius `ρ_p > 0` of the torsional friction impulse.
    pub pitch_radius: f64,
}

impl TorsionalImpact {
    /// Checks every input's range and that the body approaches (`v_n < 0`).
    fn validate(&self) -> Result<Torsion> {
        let m = positive(Input::Mass, self.mass)?;
        let i_n = positive(Input::NormalInertia, self.normal_inertia)?;
        let vn = finite(Input::NormalVelocity, self.normal_velocity)?;
        let w = finite(Input::Spin, self.spin)?;
        let e = in_range(Input::Restitution, self.restitution, 0.0, 1.0)?;
        let ez = in_range(Input::TorsionalRestitution, self.torsional_restitution, 0.0, 1.0)?;
        let mu_z = in_range(
            Input::TorsionalFriction,
            self.torsional_friction,
            0.0,
            f64::INFINITY,
        )?;
        let rho = positive(Input::PitchRadius, self.pitch_radius)?;
        if vn >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: vn + 0.0,
            });
        }
        Ok(Torsion {
            m,
            i_n,
            vn,
            w,
            e,
            ez,
            mu_z,
            rho,
        })
    }
}

struct TorsionModel {
    torsion: Torsion,
    energy: bool,
}

impl Model<TorsionalOutcome> for TorsionModel {
    #[inline(always)]
    fn run<N: Radical>(&self, out: &mut TorsionalOutcome) -> Exact<N, ()> {
        torsional::<N>(&self.torsion, self.energy, out)
    }
}

impl Case for TorsionalImpact {
    type Outcome = TorsionalOutcome;
    type Fixed = ();

    const INPUTS: &'static [Input] = &[
        Input::Mass,
        Input::NormalInertia,
        Input::NormalVelocity,
        Input::Spin,
        Input::Restitution,
        Input::TorsionalRestitution,
        Input::TorsionalFriction,
        Input::PitchRadius,
    ];

    const OUTPUTS: &'static [Output] = &[
        Output::FinalNormalVelocity,
        Output::FinalSpin,
        Output::NormalImpulse,
        Output::TorsionalImpulse,
        Output::Regime,
        Output::SwitchSpin,
        Output::InitialEnergy,
        Output::FinalEnergy,
        Output::EnergyLoss,
    ];

    #[inline]
    fn input_mut(&mut self, input: Input) -> Option<&mut f64> {
        Some(match input {
            Input::Mass => &mut self.mass,
            Input::NormalInertia => &mut self.normal_inertia,
            Input::NormalVelocity => &mut self.normal_velocity,
            Input::Spin => &mut self.spin,
            Input::Restitution => &mut self.restitution,
            Input::TorsionalRestitution => &mut self.torsional_restitution,
            Input::TorsionalFriction => &mut self.torsional_friction,
            Input::PitchRadius => &mut self.pitch_radius,
            Input::Inertia
            | Input::TangentialOffset
            | Input::NormalOffset
            | Input::TangentialVelocity
            | Input::AngularVelocity
            | Input::Friction
            | Input::ImpulseRatio
            | Input::TangentialRestitution
            | Input::KineticRestitution
            | Input::ApproachImpulseRatio
            | Input::ReboundImpulseRatio
            | Input::MassA
            | Input::InertiaA
            | Input::PositionAX
            | Input::PositionAY
            | Input::VelocityAX
            | Input::VelocityAY
            | Input::AngularVelocityA
            | Input::InertiaAXX
            | Input::InertiaAYY
            | Input::InertiaAZZ
            | Input::InertiaAXY
            | Input::InertiaAXZ
            | Input::InertiaAYZ
            | Input::PositionAZ
            | Input::VelocityAZ
            | Input::AngularVelocityAX
            | Input::AngularVelocityAY
            | Input::AngularVelocityAZ
            | Input::InertiaBXX
            | Input::InertiaBYY
            | Input::InertiaBZZ
            | Input::InertiaBXY
            | Input::InertiaBXZ
            | Input::InertiaBYZ
            | Input::PositionBZ
            | Input::VelocityBZ
            | Input::AngularVelocityBX
            | Input::AngularVelocityBY
            | Input::AngularVelocityBZ
            | Input::ContactZ
            | Input::NormalZ
            | Input::Torsion
            | Input::MassB
            | Input::InertiaB
            | Input::PositionBX
            | Input::PositionBY
            | Input::VelocityBX
            | Input::VelocityBY
            | Input::AngularVelocityB
            | Input::ContactX
            | Input::ContactY
            | Input::NormalX
            | Input::NormalY
            | Input::VelocityA
            | Input::Normal => return None,
        })
    }

    fn describe(&self) -> &'static str {
        "a torsional impact"
    }

    fn output(o: &TorsionalOutcome, output: Output) -> Value {
        let energy = o.energy;
        Value::Number(match output {
            Output::FinalNormalVelocity => o.final_normal_velocity,
            Output::FinalSpin => o.final_spin,
            Output::NormalImpulse => o.normal_impulse,
            Output::TorsionalImpulse => o.torsional_impulse,
            Output::Regime => return Value::Text(o.regime.as_str()),
            Output::SwitchSpin => o.switch_spin,
            Output::InitialEnergy => energy.map_or(f64::NAN, |e| e.initial),
            Output::FinalEnergy => energy.map_or(f64::NAN, |e| e.r#final),
            Output::EnergyLoss => energy.map_or(f64::NAN, |e| e.loss),
            Output::FinalTangentialVelocity
            | Output::FinalAngularVelocity
            | Output::InitialNormalContactVelocity
            | Output::InitialTangentialContactVelocity
            | Output::FinalNormalContactVelocity
            | Output::FinalTangentialContactVelocity
            | Output::TangentialImpulse
            | Output::ImpulseRatio
            | Output::CriticalImpulseRatio
            | Output::Restitution
            | Output::KineticRestitution
            | Output::MaxEnergyLoss
            | Output::NormalizedEnergyLoss
            | Output::ImpulseX
            | Output::ImpulseY
            | Output::FinalVelocityAX
            | Output::FinalVelocityAY
            | Output::FinalAngularVelocityA
            | Output::VelocityChangeAX
            | Output::VelocityChangeAY
            | Output::DeltaVA
            | Output::AngularVelocityChangeA
            | Output::FinalVelocityBX
            | Output::FinalVelocityBY
            | Output::FinalAngularVelocityB
            | Output::VelocityChangeBX
            | Output::VelocityChangeBY
            | Output::DeltaVB
            | Output::AngularVelocityChangeB
            | Output::FinalVelocityAZ
            | Output::FinalAngularVelocityAX
            | Output::FinalAngularVelocityAY
            | Output::FinalAngularVelocityAZ
            | Output::VelocityChangeAZ
            | Output::AngularVelocityChangeAX
            | Output::AngularVelocityChangeAY
            | Output::AngularVelocityChangeAZ
            | Output::FinalVelocityBZ
            | Output::FinalAngularVelocityBX
            | Output::FinalAngularVelocityBY
            | Output::FinalAngularVelocityBZ
            | Output::VelocityChangeBZ
            | Output::AngularVelocityChangeBX
            | Output::AngularVelocityChangeBY
            | Output::AngularVelocityChangeBZ
            | Output::InitialTangentialContactVelocityX
            | Output::InitialTangentialContactVelocityY
            | Output::InitialTangentialContactVelocityZ
            | Output::InitialContactSpin
            | Output::FinalTangentialContactVelocityX
            | Output::FinalTangentialContactVelocityY
            | Output::FinalTangentialContactVelocityZ
            | Output::FinalContactSpin
            | Output::TangentialImpulseX
            | Output::TangentialImpulseY
            | Output::TangentialImpulseZ
            | Output::ImpulseZ
            | Output::TorsionalRegime => f64::NAN,
        })
    }

    fn fix(&self, _swept: &[Input]) {}

    #[inline(always)]
    fn evaluate(
        &self,
        _fixed: &(),
        outputs: Outputs,
        arithmetic: Arithmetic,
        in_range: bool,
        out: &mut TorsionalOutcome,
    ) -> (Result<()>, Stage) {
        match self.validate() {
            Ok(torsion) => evaluate(
                arithmetic,
                in_range,
                TorsionModel {
                    torsion,
                    energy: outputs.energy,
                },
                out,
            ),
            Err(e) => (Err(e), arithmetic.validating_stage()),
        }
    }
}
