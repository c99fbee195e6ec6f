//! The general planar case: body A against body B or a fixed barrier, in
//! world axes, with one tangential law (the `planar` endpoint). The model is
//! `src/model/bodies.rs` reduced to the contact space the laws of
//! `src/model/contact.rs` are written in.

use super::planar::Law;
use super::{Arithmetic, Case, Model, Stage, evaluate};
use crate::arith::{Field, Fraction, Radical};
use crate::error::{ImpactError, Input, Output, Result, finite, positive};
use crate::model::Exact;
use crate::model::bodies::{BODY_OUTPUTS, approach, bodies};
use crate::outcome::{BodiesOutcome, Outputs};
use crate::quantity::Value;

/// A lamina in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lamina {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Moment of inertia about the mass centre, `I > 0`.
    pub inertia: f64,
    /// Position of the mass centre `G`.
    pub position: [f64; 2],
    /// Velocity of the mass centre.
    pub velocity: [f64; 2],
    /// Angular velocity, counter-clockwise positive.
    pub angular_velocity: f64,
}

/// The contact point and the normal from B into A (any non-zero length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarContact {
    /// The contact point `C`.
    pub point: [f64; 2],
    /// The normal `n`, from B into A (out of the barrier).
    pub normal: [f64; 2],
}

/// One point contact between body A and body B, or A and a fixed barrier
/// (`b: None`), under one law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodiesImpact {
    /// Body A.
    pub a: Lamina,
    /// Body B; `None` for a barrier.
    pub b: Option<Lamina>,
    /// The contact.
    pub contact: PlanarContact,
    /// The tangential law with its coefficients.
    pub law: Law,
}

/// The inputs of each body, in request order.
const BODY_INPUTS: [[Input; 7]; 2] = [
    [
        Input::MassA,
        Input::InertiaA,
        Input::PositionAX,
        Input::PositionAY,
        Input::VelocityAX,
        Input::VelocityAY,
        Input::AngularVelocityA,
    ],
    [
        Input::MassB,
        Input::InertiaB,
        Input::PositionBX,
        Input::PositionBY,
        Input::VelocityBX,
        Input::VelocityBY,
        Input::AngularVelocityB,
    ],
];

/// The fast evaluation's range for this case, `2^±60`: its longest products
/// (`det W̃`, the outputs formed from it) multiply up to sixteen inputs,
/// which then stay normal doubles.
fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (2f64.powi(-60)..=2f64.powi(60)).contains(&x.abs())
}

impl Lamina {
    fn input_mut(&mut self, k: usize, input: Input) -> Option<&mut f64> {
        let names = &BODY_INPUTS[k];
        let slot = names.iter().position(|&i| i == input)?;
        Some(match slot {
            0 => &mut self.mass,
            1 => &mut self.inertia,
            2 => &mut self.position[0],
            3 => &mut self.position[1],
            4 => &mut self.velocity[0],
            5 => &mut self.velocity[1],
            _ => &mut self.angular_velocity,
        })
    }

    fn validate(&self, k: usize) -> Result<()> {
        let names = &BODY_INPUTS[k];
        positive(names[0], self.mass)?;
        positive(names[1], self.inertia)?;
        finite(names[2], self.position[0])?;
        finite(names[3], self.position[1])?;
        finite(names[4], self.velocity[0])?;
        finite(names[5], self.velocity[1])?;
        finite(names[6], self.angular_velocity)?;
        Ok(())
    }

    fn values(&self) -> [f64; 7] {
        [
            self.mass,
            self.inertia,
            self.position[0],
            self.position[1],
            self.velocity[0],
            self.velocity[1],
            self.angular_velocity,
        ]
    }
}

impl BodiesImpact {
    /// Checks every input in request order and the law's coefficients; then
    /// whether the contact approaches, exactly. Returns whether the f64
    /// evaluation decides the approach the same way (else only the exact
    /// arithmetic may answer).
    fn validate(&self) -> Result<(Law, bool)> {
        self.a.validate(0)?;
        if let Some(b) = &self.b {
            b.validate(1)?;
        }
        finite(Input::ContactX, self.contact.point[0])?;
        finite(Input::ContactY, self.contact.point[1])?;
        finite(Input::NormalX, self.contact.normal[0])?;
        finite(Input::NormalY, self.contact.normal[1])?;
        if self.contact.normal[0] == 0.0 && self.contact.normal[1] == 0.0 {
            return Err(ImpactError::ZeroVector { input: Input::Normal });
        }
        let law = self.law.validate()?;
        let fast = approach::<f64>(self);
        let certain = fast.is_finite() && fast.abs() > self.approach_error_bound();
        let approaching = if certain {
            fast < 0.0
        } else {
            approach::<Fraction>(self).sign() == Ok(std::cmp::Ordering::Less)
        };
        if !approaching {
            let nn = self.contact.normal[0].hypot(self.contact.normal[1]);
            return Err(ImpactError::NotApproaching {
                input: Input::VelocityA,
                normal_contact_velocity: approach::<Fraction>(self).approx() / nn + 0.0,
            });
        }
        Ok((law, certain))
    }

    /// A bound on the error of the f64 `ũ_n` (a few roundings, each relative
    /// to the terms it combines, with room to spare), or `∞` where a term
    /// leaves the normal range.
    fn approach_error_bound(&self) -> f64 {
        let [nx, ny] = self.contact.normal;
        let [cx, cy] = self.contact.point;
        let terms: f64 = std::iter::once(&self.a)
            .chain(self.b.as_ref())
            .map(|l| {
                let w = l.angular_velocity.abs();
                (l.velocity[0] * nx).abs()
                    + (l.velocity[1] * ny).abs()
                    + w * (cy.abs() + l.position[1].abs()) * nx.abs()
                    + w * (cx.abs() + l.position[0].abs()) * ny.abs()
            })
            .sum();
        if terms.is_finite() && terms > 2f64.powi(-900) {
            16.0 * f64::EPSILON * terms
        } else {
            f64::INFINITY
        }
    }
}

struct Pair<'a> {
    impact: &'a BodiesImpact,
    outputs: Outputs,
}

impl Model<BodiesOutcome> for Pair<'_> {
    #[inline(always)]
    fn run<N: Radical>(&self, out: &mut BodiesOutcome) -> Exact<N, ()> {
        bodies::<N>(self.impact, self.outputs, out)
    }
}

impl Case for BodiesImpact {
    type Outcome = BodiesOutcome;
    type Fixed = ();

    const INPUTS: &'static [Input] = &[
        Input::MassA,
        Input::InertiaA,
        Input::PositionAX,
        Input::PositionAY,
        Input::VelocityAX,
        Input::VelocityAY,
        Input::AngularVelocityA,
        Input::MassB,
        Input::InertiaB,
        Input::PositionBX,
        Input::PositionBY,
        Input::VelocityBX,
        Input::VelocityBY,
        Input::AngularVelocityB,
        Input::ContactX,
        Input::ContactY,
        Input::NormalX,
        Input::NormalY,
        Input::Restitution,
        Input::Friction,
        Input::ImpulseRatio,
        Input::TangentialRestitution,
        Input::KineticRestitution,
        Input::ApproachImpulseRatio,
        Input::ReboundImpulseRatio,
    ];

    const OUTPUTS: &'static [Output] = &[
        Output::FinalVelocityAX,
        Output::FinalVelocityAY,
        Output::FinalAngularVelocityA,
        Output::VelocityChangeAX,
        Output::VelocityChangeAY,
        Output::DeltaVA,
        Output::AngularVelocityChangeA,
        Output::FinalVelocityBX,
        Output::FinalVelocityBY,
        Output::FinalAngularVelocityB,
        Output::VelocityChangeBX,
        Output::VelocityChangeBY,
        Output::DeltaVB,
        Output::AngularVelocityChangeB,
        Output::InitialNormalContactVelocity,
        Output::InitialTangentialContactVelocity,
        Output::FinalNormalContactVelocity,
        Output::FinalTangentialContactVelocity,
        Output::NormalImpulse,
        Output::TangentialImpulse,
        Output::ImpulseX,
        Output::ImpulseY,
        Output::ImpulseRatio,
        Output::CriticalImpulseRatio,
        Output::Restitution,
        Output::KineticRestitution,
        Output::Regime,
        Output::InitialEnergy,
        Output::FinalEnergy,
        Output::EnergyLoss,
        Output::MaxEnergyLoss,
        Output::NormalizedEnergyLoss,
    ];

    #[inline]
    fn input_mut(&mut self, input: Input) -> Option<&mut f64> {
        let slot = match input {
            Input::ContactX => &mut self.contact.point[0],
            Input::ContactY => &mut self.contact.point[1],
            Input::NormalX => &mut self.contact.normal[0],
            Input::NormalY => &mut self.contact.normal[1],
            _ => {
                return match self.a.input_mut(0, input) {
                    Some(slot) => Some(slot),
                    None => match &mut self.b {
                        Some(b) => match b.input_mut(1, input) {
                            Some(slot) => Some(slot),
                            None => self.law.input_mut(input),
                        },
                        None => self.law.input_mut(input),
                    },
                };
            }
        };
        Some(slot)
    }

    /// The law's coefficients in the general fast range; the bodies and the
    /// contact are held to this case's narrower one in [`Case::evaluate`].
    #[inline]
    fn all_in_fast_range(&self) -> bool {
        self.law.coefficients().into_iter().all(super::in_fast_range)
    }

    /// Body B's outputs only when there is a body B.
    fn answers(&self, output: Output) -> bool {
        self.b.is_some() || !BODY_OUTPUTS[1].contains(&output)
    }

    fn describe(&self) -> &'static str {
        match self.b {
            Some(_) => "two bodies",
            None => "a body against a barrier",
        }
    }

    fn output(o: &BodiesOutcome, output: Output) -> Value {
        let body = |k: usize| o.bodies.get(k).filter(|_| k < o.body_count);
        let of = |k: usize, f: fn(&crate::outcome::BodyOutcome) -> f64| body(k).map_or(f64::NAN, f);
        Value::Number(match output {
            Output::FinalVelocityAX => of(0, |b| b.velocity[0]),
            Output::FinalVelocityAY => of(0, |b| b.velocity[1]),
            Output::FinalAngularVelocityA => of(0, |b| b.angular_velocity),
            Output::VelocityChangeAX => of(0, |b| b.velocity_change[0]),
            Output::VelocityChangeAY => of(0, |b| b.velocity_change[1]),
            Output::DeltaVA => of(0, |b| b.delta_v),
            Output::AngularVelocityChangeA => of(0, |b| b.angular_velocity_change),
            Output::FinalVelocityBX => of(1, |b| b.velocity[0]),
            Output::FinalVelocityBY => of(1, |b| b.velocity[1]),
            Output::FinalAngularVelocityB => of(1, |b| b.angular_velocity),
            Output::VelocityChangeBX => of(1, |b| b.velocity_change[0]),
            Output::VelocityChangeBY => of(1, |b| b.velocity_change[1]),
            Output::DeltaVB => of(1, |b| b.delta_v),
            Output::AngularVelocityChangeB => of(1, |b| b.angular_velocity_change),
            Output::InitialNormalContactVelocity => o.contact_velocity.initial.normal,
            Output::InitialTangentialContactVelocity => o.contact_velocity.initial.tangential,
            Output::FinalNormalContactVelocity => o.contact_velocity.r#final.normal,
            Output::FinalTangentialContactVelocity => o.contact_velocity.r#final.tangential,
            Output::NormalImpulse => o.impulse.normal,
            Output::TangentialImpulse => o.impulse.tangential,
            Output::ImpulseX => o.impulse.x,
            Output::ImpulseY => o.impulse.y,
            Output::ImpulseRatio => o.impulse_ratio,
            Output::CriticalImpulseRatio => o.critical_impulse_ratio.unwrap_or(f64::NAN),
            Output::Restitution => o.restitution,
            Output::KineticRestitution => o.kinetic_restitution,
            Output::Regime => return Value::Text(o.regime.as_str()),
            Output::InitialEnergy => o.energy.map_or(f64::NAN, |e| e.initial),
            Output::FinalEnergy => o.energy.map_or(f64::NAN, |e| e.r#final),
            Output::EnergyLoss => o.energy.map_or(f64::NAN, |e| e.loss),
            Output::MaxEnergyLoss => o.energy.map_or(f64::NAN, |e| e.max_loss),
            Output::NormalizedEnergyLoss => o.energy.map_or(f64::NAN, |e| e.normalized_loss),
            Output::FinalNormalVelocity
            | Output::FinalTangentialVelocity
            | Output::FinalAngularVelocity
            | Output::FinalSpin
            | Output::TorsionalImpulse
            | Output::SwitchSpin
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
        out: &mut BodiesOutcome,
    ) -> (Result<()>, Stage) {
        let stage = arithmetic.validating_stage();
        match self.validate() {
            Ok((law, certain)) => {
                let impact = BodiesImpact { law, ..*self };
                let in_range = in_range
                    && certain
                    && self.a.values().into_iter().all(in_fast_range)
                    && self.b.is_none_or(|b| b.values().into_iter().all(in_fast_range))
                    && self
                        .contact
                        .point
                        .into_iter()
                        .chain(self.contact.normal)
                        .all(in_fast_range);
                let arithmetic = match arithmetic {
                    // The f64 evaluation may only answer where its approach decision is certain.
                    Arithmetic::Plain | Arithmetic::Unfiltered if !certain => Arithmetic::Exact,
                    other => other,
                };
                evaluate(
                    arithmetic,
                    in_range,
                    Pair {
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
