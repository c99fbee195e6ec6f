//! The case in space: body A against body B or a fixed barrier, with full
//! inertia tensors, one tangential law and an optional twist law (the
//! `spatial` endpoint). The model is `src/model/spatial.rs`.

use std::cmp::Ordering;

use super::planar::Law;
use super::{Arithmetic, Case, Model, Stage, evaluate};
use crate::arith::{Field, Fraction, Radical};
use crate::error::{ImpactError, Input, Output, Result, finite, in_range, positive};
use crate::model::Exact;
use crate::model::spatial::{SPATIAL_BODY_OUTPUTS, approach, leading_minors, spatial};
use crate::outcome::{Outputs, SpatialOutcome};
use crate::quantity::Value;

/// A rigid body in space, in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass `m > 0`.
    pub mass: f64,
    /// The inertia tensor about the mass centre, `[I_xx, I_yy, I_zz, I_xy,
    /// I_xz, I_yz]`, the matrix's own entries (`I_xy = −∫ x y dm`);
    /// symmetric positive definite.
    pub inertia: [f64; 6],
    /// Position of the mass centre `G`.
    pub position: [f64; 3],
    /// Velocity of `G`.
    pub velocity: [f64; 3],
    /// Angular velocity.
    pub angular_velocity: [f64; 3],
}

/// The contact point and the normal from B into A (any non-zero length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialContact {
    /// The contact point `C`.
    pub point: [f64; 3],
    /// The normal `n` from B into A.
    pub normal: [f64; 3],
}

/// The twist law about the normal (section 4 generalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Twist {
    /// `e_z ∈ [0, 1]`.
    pub restitution: f64,
    /// `μ_z ≥ 0`.
    pub friction: f64,
    /// `ρ_p > 0`.
    pub pitch_radius: f64,
}

/// One point contact in space between body A and body B, or A and a fixed
/// barrier (`b: None`), under one tangential law and optionally a twist law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialImpact {
    /// Body A.
    pub a: RigidBody,
    /// Body B; `None` for a barrier.
    pub b: Option<RigidBody>,
    /// The contact.
    pub contact: SpatialContact,
    /// The tangential law (not the planar kinetic one). A prescribed
    /// `impulse_ratio` is a magnitude `μ ≥ 0` opposing the slip.
    pub law: Law,
    /// The twist law, if any.
    pub torsion: Option<Twist>,
}

/// The inputs of each body, in request order.
const BODY_INPUTS: [[Input; 16]; 2] = [
    [
        Input::MassA,
        Input::InertiaAXX,
        Input::InertiaAYY,
        Input::InertiaAZZ,
        Input::InertiaAXY,
        Input::InertiaAXZ,
        Input::InertiaAYZ,
        Input::PositionAX,
        Input::PositionAY,
        Input::PositionAZ,
        Input::VelocityAX,
        Input::VelocityAY,
        Input::VelocityAZ,
        Input::AngularVelocityAX,
        Input::AngularVelocityAY,
        Input::AngularVelocityAZ,
    ],
    [
        Input::MassB,
        Input::InertiaBXX,
        Input::InertiaBYY,
        Input::InertiaBZZ,
        Input::InertiaBXY,
        Input::InertiaBXZ,
        Input::InertiaBYZ,
        Input::PositionBX,
        Input::PositionBY,
        Input::PositionBZ,
        Input::VelocityBX,
        Input::VelocityBY,
        Input::VelocityBZ,
        Input::AngularVelocityBX,
        Input::AngularVelocityBY,
        Input::AngularVelocityBZ,
    ],
];

/// The tensors as a whole, for refusals.
const TENSORS: [Input; 2] = [Input::InertiaA, Input::InertiaB];

/// The fast evaluation's range for this case, `2^±50`: its longest products
/// (`det W`, the adjugates and the energies of the couple) multiply up to
/// twenty inputs, which then stay normal doubles.
fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (2f64.powi(-50)..=2f64.powi(50)).contains(&x.abs())
}

impl RigidBody {
    fn slot(&mut self, index: usize) -> &mut f64 {
        match index {
            0 => &mut self.mass,
            1..=6 => &mut self.inertia[index - 1],
            7..=9 => &mut self.position[index - 7],
            10..=12 => &mut self.velocity[index - 10],
            _ => &mut self.angular_velocity[index - 13],
        }
    }

    fn input_mut(&mut self, k: usize, input: Input) -> Option<&mut f64> {
        let index = BODY_INPUTS[k].iter().position(|&i| i == input)?;
        Some(self.slot(index))
    }

    fn values(&self) -> [f64; 16] {
        let mut copy = *self;
        std::array::from_fn(|i| *copy.slot(i))
    }

    /// Every input in request order, then the tensor: symmetric by
    /// construction, positive definite by its leading minors (decided
    /// exactly where the f64 ones are too close to zero for their bound).
    fn validate(&self, k: usize) -> Result<()> {
        let names = &BODY_INPUTS[k];
        positive(names[0], self.mass)?;
        for (i, x) in self.values().into_iter().enumerate().skip(1) {
            finite(names[i], x)?;
        }
        let fast = leading_minors::<f64>(&self.inertia);
        let [xx, yy, zz, xy, xz, yz] = self.inertia.map(f64::abs);
        // Each minor's terms, to bound its rounding error.
        let terms = [
            xx,
            xx * yy + xy * xy,
            xx * (yy * zz + yz * yz) + xy * (xy * zz + xz * yz) + xz * (xy * yz + yy * xz),
        ];
        for order in 0..3 {
            let bound = 16.0 * f64::EPSILON * terms[order];
            let certain =
                fast[order].is_finite() && bound.is_finite() && fast[order].abs() > bound || order == 0;
            let positive = if certain {
                fast[order] > 0.0
            } else {
                leading_minors::<Fraction>(&self.inertia)[order].sign() == Ok(Ordering::Greater)
            };
            if !positive {
                return Err(ImpactError::NotPositiveDefinite {
                    input: TENSORS[k],
                    order: order as u8 + 1,
                    minor: leading_minors::<Fraction>(&self.inertia)[order].approx(),
                });
            }
        }
        Ok(())
    }
}

impl Twist {
    fn validate(&self) -> Result<()> {
        in_range(Input::TorsionalRestitution, self.restitution, 0.0, 1.0)?;
        in_range(Input::TorsionalFriction, self.friction, 0.0, f64::INFINITY)?;
        positive(Input::PitchRadius, self.pitch_radius)?;
        Ok(())
    }

    fn input_mut(&mut self, input: Input) -> Option<&mut f64> {
        match input {
            Input::TorsionalRestitution => Some(&mut self.restitution),
            Input::TorsionalFriction => Some(&mut self.friction),
            Input::PitchRadius => Some(&mut self.pitch_radius),
            _ => None,
        }
    }
}

impl SpatialImpact {
    fn bodies(&self) -> impl Iterator<Item = &RigidBody> {
        std::iter::once(&self.a).chain(self.b.as_ref())
    }

    /// Checks every input in request order, the laws, and whether the
    /// contact approaches, exactly. Returns the validated law and whether the
    /// f64 evaluation decides the approach the same way.
    fn validate(&self) -> Result<(Law, bool)> {
        for (k, body) in self.bodies().enumerate() {
            body.validate(k)?;
        }
        let point = [Input::ContactX, Input::ContactY, Input::ContactZ];
        let normal = [Input::NormalX, Input::NormalY, Input::NormalZ];
        for (input, x) in point.into_iter().zip(self.contact.point) {
            finite(input, x)?;
        }
        for (input, x) in normal.into_iter().zip(self.contact.normal) {
            finite(input, x)?;
        }
        if self.contact.normal.iter().all(|&x| x == 0.0) {
            return Err(ImpactError::ZeroVector { input: Input::Normal });
        }
        let law = self.law.validate()?;
        match law {
            Law::ImpulseRatio { impulse_ratio, .. } => {
                in_range(Input::ImpulseRatio, impulse_ratio, 0.0, f64::INFINITY)?;
            }
            Law::KineticRestitution { .. } => {
                return Err(ImpactError::PlanarOnly {
                    input: Input::KineticRestitution,
                });
            }
            _ => {}
        }
        if let Some(twist) = &self.torsion {
            twist.validate()?;
        }
        let fast = approach::<f64>(self);
        let certain = fast.is_finite() && fast.abs() > self.approach_error_bound();
        let approaching = if certain {
            fast < 0.0
        } else {
            approach::<Fraction>(self).sign() == Ok(Ordering::Less)
        };
        if !approaching {
            let size = self.contact.normal.iter().map(|x| x * x).sum::<f64>().sqrt();
            let along = if certain {
                fast
            } else {
                approach::<Fraction>(self).approx()
            };
            return Err(ImpactError::NotApproaching {
                input: Input::VelocityA,
                normal_contact_velocity: along / size + 0.0,
            });
        }
        Ok((law, certain))
    }

    /// A bound on the error of the f64 `u·n`: a few roundings relative to
    /// the terms it combines, with room to spare (`∞` outside the normal range).
    fn approach_error_bound(&self) -> f64 {
        let n = self.contact.normal.map(f64::abs);
        let c = self.contact.point.map(f64::abs);
        let terms: f64 = self
            .bodies()
            .map(|b| {
                let w = b.angular_velocity.map(f64::abs);
                let r = [0, 1, 2].map(|i| c[i] + b.position[i].abs());
                let turn = [
                    w[1] * r[2] + w[2] * r[1],
                    w[2] * r[0] + w[0] * r[2],
                    w[0] * r[1] + w[1] * r[0],
                ];
                (0..3)
                    .map(|i| (b.velocity[i].abs() + turn[i]) * n[i])
                    .sum::<f64>()
            })
            .sum();
        if terms.is_finite() && terms > 2f64.powi(-900) {
            32.0 * f64::EPSILON * terms
        } else {
            f64::INFINITY
        }
    }
}

struct Space<'a> {
    impact: &'a SpatialImpact,
    outputs: Outputs,
}

impl Model<SpatialOutcome> for Space<'_> {
    #[inline(always)]
    fn run<N: Radical>(&self, out: &mut SpatialOutcome) -> Exact<N, ()> {
        spatial::<N>(self.impact, self.outputs, out)
    }
}

impl Case for SpatialImpact {
    type Outcome = SpatialOutcome;
    type Fixed = ();

    const INPUTS: &'static [Input] = &[
        Input::MassA,
        Input::InertiaAXX,
        Input::InertiaAYY,
        Input::InertiaAZZ,
        Input::InertiaAXY,
        Input::InertiaAXZ,
        Input::InertiaAYZ,
        Input::PositionAX,
        Input::PositionAY,
        Input::PositionAZ,
        Input::VelocityAX,
        Input::VelocityAY,
        Input::VelocityAZ,
        Input::AngularVelocityAX,
        Input::AngularVelocityAY,
        Input::AngularVelocityAZ,
        Input::MassB,
        Input::InertiaBXX,
        Input::InertiaBYY,
        Input::InertiaBZZ,
        Input::InertiaBXY,
        Input::InertiaBXZ,
        Input::InertiaBYZ,
        Input::PositionBX,
        Input::PositionBY,
        Input::PositionBZ,
        Input::VelocityBX,
        Input::VelocityBY,
        Input::VelocityBZ,
        Input::AngularVelocityBX,
        Input::AngularVelocityBY,
        Input::AngularVelocityBZ,
        Input::ContactX,
        Input::ContactY,
        Input::ContactZ,
        Input::NormalX,
        Input::NormalY,
        Input::NormalZ,
        Input::Restitution,
        Input::Friction,
        Input::ImpulseRatio,
        Input::TangentialRestitution,
        Input::TorsionalRestitution,
        Input::TorsionalFriction,
        Input::PitchRadius,
    ];

    const OUTPUTS: &'static [Output] = &[
        Output::FinalVelocityAX,
        Output::FinalVelocityAY,
        Output::FinalVelocityAZ,
        Output::FinalAngularVelocityAX,
        Output::FinalAngularVelocityAY,
        Output::FinalAngularVelocityAZ,
        Output::VelocityChangeAX,
        Output::VelocityChangeAY,
        Output::VelocityChangeAZ,
        Output::DeltaVA,
        Output::AngularVelocityChangeAX,
        Output::AngularVelocityChangeAY,
        Output::AngularVelocityChangeAZ,
        Output::FinalVelocityBX,
        Output::FinalVelocityBY,
        Output::FinalVelocityBZ,
        Output::FinalAngularVelocityBX,
        Output::FinalAngularVelocityBY,
        Output::FinalAngularVelocityBZ,
        Output::VelocityChangeBX,
        Output::VelocityChangeBY,
        Output::VelocityChangeBZ,
        Output::DeltaVB,
        Output::AngularVelocityChangeBX,
        Output::AngularVelocityChangeBY,
        Output::AngularVelocityChangeBZ,
        Output::InitialNormalContactVelocity,
        Output::InitialTangentialContactVelocityX,
        Output::InitialTangentialContactVelocityY,
        Output::InitialTangentialContactVelocityZ,
        Output::InitialContactSpin,
        Output::FinalNormalContactVelocity,
        Output::FinalTangentialContactVelocityX,
        Output::FinalTangentialContactVelocityY,
        Output::FinalTangentialContactVelocityZ,
        Output::FinalContactSpin,
        Output::NormalImpulse,
        Output::TangentialImpulseX,
        Output::TangentialImpulseY,
        Output::TangentialImpulseZ,
        Output::TorsionalImpulse,
        Output::ImpulseX,
        Output::ImpulseY,
        Output::ImpulseZ,
        Output::ImpulseRatio,
        Output::CriticalImpulseRatio,
        Output::Restitution,
        Output::Regime,
        Output::TorsionalRegime,
        Output::InitialEnergy,
        Output::FinalEnergy,
        Output::EnergyLoss,
        Output::MaxEnergyLoss,
        Output::NormalizedEnergyLoss,
    ];

    #[inline]
    fn input_mut(&mut self, input: Input) -> Option<&mut f64> {
        let point = [Input::ContactX, Input::ContactY, Input::ContactZ];
        let normal = [Input::NormalX, Input::NormalY, Input::NormalZ];
        if let Some(i) = point.iter().position(|&p| p == input) {
            return Some(&mut self.contact.point[i]);
        }
        if let Some(i) = normal.iter().position(|&p| p == input) {
            return Some(&mut self.contact.normal[i]);
        }
        if let Some(slot) = self.a.input_mut(0, input) {
            return Some(slot);
        }
        if let Some(slot) = self.b.as_mut().and_then(|b| b.input_mut(1, input)) {
            return Some(slot);
        }
        if let Some(slot) = self.torsion.as_mut().and_then(|t| t.input_mut(input)) {
            return Some(slot);
        }
        self.law.input_mut(input)
    }

    /// The laws' coefficients in the general fast range; the bodies and the
    /// contact are held to this case's narrower one in [`Case::evaluate`].
    #[inline]
    fn all_in_fast_range(&self) -> bool {
        self.law.coefficients().into_iter().all(super::in_fast_range)
            && self.torsion.is_none_or(|t| {
                [t.restitution, t.friction, t.pitch_radius]
                    .into_iter()
                    .all(super::in_fast_range)
            })
    }

    /// Body B's outputs only with a body B; the twist regime only with a twist law.
    fn answers(&self, output: Output) -> bool {
        (self.b.is_some() || !SPATIAL_BODY_OUTPUTS[1].contains(&output))
            && (self.torsion.is_some() || output != Output::TorsionalRegime)
    }

    fn describe(&self) -> &'static str {
        match self.b {
            Some(_) => "two bodies in space",
            None => "a body against a barrier in space",
        }
    }

    fn output(o: &SpatialOutcome, output: Output) -> Value {
        let body = |k: usize| o.bodies.get(k).filter(|_| k < o.body_count);
        let of =
            |k: usize, f: &dyn Fn(&crate::outcome::SpatialBodyOutcome) -> f64| body(k).map_or(f64::NAN, f);
        let energy = |f: fn(&crate::outcome::PlanarEnergy) -> f64| o.energy.as_ref().map_or(f64::NAN, f);
        let (initial, last) = (&o.contact_velocity.initial, &o.contact_velocity.r#final);
        if let Some(k) = SPATIAL_BODY_OUTPUTS
            .iter()
            .position(|names| names.contains(&output))
        {
            let i = SPATIAL_BODY_OUTPUTS[k]
                .iter()
                .position(|&n| n == output)
                .unwrap_or(0);
            return Value::Number(of(k, &|b| match i {
                0..=2 => b.velocity[i],
                3..=5 => b.angular_velocity[i - 3],
                6..=8 => b.velocity_change[i - 6],
                9 => b.delta_v,
                _ => b.angular_velocity_change[i - 10],
            }));
        }
        Value::Number(match output {
            Output::InitialNormalContactVelocity => initial.normal,
            Output::InitialTangentialContactVelocityX => initial.tangential[0],
            Output::InitialTangentialContactVelocityY => initial.tangential[1],
            Output::InitialTangentialContactVelocityZ => initial.tangential[2],
            Output::InitialContactSpin => initial.spin,
            Output::FinalNormalContactVelocity => last.normal,
            Output::FinalTangentialContactVelocityX => last.tangential[0],
            Output::FinalTangentialContactVelocityY => last.tangential[1],
            Output::FinalTangentialContactVelocityZ => last.tangential[2],
            Output::FinalContactSpin => last.spin,
            Output::NormalImpulse => o.impulse.normal,
            Output::TangentialImpulseX => o.impulse.tangential[0],
            Output::TangentialImpulseY => o.impulse.tangential[1],
            Output::TangentialImpulseZ => o.impulse.tangential[2],
            Output::TorsionalImpulse => o.impulse.torsional,
            Output::ImpulseX => o.impulse.x,
            Output::ImpulseY => o.impulse.y,
            Output::ImpulseZ => o.impulse.z,
            Output::ImpulseRatio => o.impulse_ratio,
            Output::CriticalImpulseRatio => o.critical_impulse_ratio.unwrap_or(f64::NAN),
            Output::Restitution => o.restitution,
            Output::Regime => return Value::Text(o.regime.as_str()),
            Output::TorsionalRegime => {
                return match o.torsional_regime {
                    Some(r) => Value::Text(r.as_str()),
                    None => Value::Number(f64::NAN),
                };
            }
            Output::InitialEnergy => energy(|e| e.initial),
            Output::FinalEnergy => energy(|e| e.r#final),
            Output::EnergyLoss => energy(|e| e.loss),
            Output::MaxEnergyLoss => energy(|e| e.max_loss),
            Output::NormalizedEnergyLoss => energy(|e| e.normalized_loss),
            // Planar and one-body outputs, and the body outputs handled above.
            Output::FinalNormalVelocity
            | Output::FinalTangentialVelocity
            | Output::FinalAngularVelocity
            | Output::FinalSpin
            | Output::InitialTangentialContactVelocity
            | Output::FinalTangentialContactVelocity
            | Output::TangentialImpulse
            | Output::KineticRestitution
            | Output::SwitchSpin
            | Output::FinalAngularVelocityA
            | Output::AngularVelocityChangeA
            | Output::FinalAngularVelocityB
            | Output::AngularVelocityChangeB
            | Output::FinalVelocityAX
            | Output::FinalVelocityAY
            | Output::FinalVelocityAZ
            | Output::FinalAngularVelocityAX
            | Output::FinalAngularVelocityAY
            | Output::FinalAngularVelocityAZ
            | Output::VelocityChangeAX
            | Output::VelocityChangeAY
            | Output::VelocityChangeAZ
            | Output::DeltaVA
            | Output::AngularVelocityChangeAX
            | Output::AngularVelocityChangeAY
            | Output::AngularVelocityChangeAZ
            | Output::FinalVelocityBX
            | Output::FinalVelocityBY
            | Output::FinalVelocityBZ
            | Output::FinalAngularVelocityBX
            | Output::FinalAngularVelocityBY
            | Output::FinalAngularVelocityBZ
            | Output::VelocityChangeBX
            | Output::VelocityChangeBY
            | Output::VelocityChangeBZ
            | Output::DeltaVB
            | Output::AngularVelocityChangeBX
            | Output::AngularVelocityChangeBY
            | Output::AngularVelocityChangeBZ => f64::NAN,
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
        out: &mut SpatialOutcome,
    ) -> (Result<()>, Stage) {
        let stage = arithmetic.validating_stage();
        match self.validate() {
            Ok((law, certain)) => {
                let impact = SpatialImpact { law, ..*self };
                let in_range = in_range
                    && certain
                    && self.bodies().all(|b| b.values().into_iter().all(in_fast_range))
                    && self
                        .contact
                        .point
                        .into_iter()
                        .chain(self.contact.normal)
                        .all(in_fast_range);
                let arithmetic = match arithmetic {
                    Arithmetic::Plain | Arithmetic::Unfiltered if !certain => Arithmetic::Exact,
                    other => other,
                };
                evaluate(
                    arithmetic,
                    in_range,
                    Space {
                        impact: &impact,
                        outputs,
                    },
                    out,
                )
            }
            Err(e) => (Err(e), stage),
        }
    }
}
