//! The planar case: a rigid lamina or a point mass against a barrier, with
//! one tangential law (the normal, oblique and tangential endpoints).

use super::{Arithmetic, Case, LANES, Model, Stage, StaticBounds, evaluate};
use crate::accuracy::{ErrorScales, ScalesOf};
use crate::arith::{Radical, SharedLanes};
use crate::error::{ImpactError, Input, Result, finite, in_range, positive};
use crate::input::{BarrierBody, BarrierImpact, Law};
use crate::model::Exact;
use crate::model::barrier::{self as model, PointMass};
use crate::outcome::{BarrierOutcome, Outputs};
use crate::scene::{BarrierScene, Body, Contact, Placed, PlanarVelocity};

impl BarrierImpact {
    /// A rigid body's impact.
    pub fn rigid(mass: f64, inertia: f64, contact: Contact, velocity: PlanarVelocity, law: Law) -> Self {
        BarrierImpact {
            body: BarrierBody::Rigid {
                mass,
                inertia,
                contact,
            },
            velocity,
            law,
        }
    }

    /// The rigid body's impact in a scene already validated, under `law`.
    pub fn in_scene(scene: &BarrierScene, law: Law) -> Self {
        let body = scene.body();
        BarrierImpact::rigid(
            body.mass(),
            body.inertia(),
            scene.contact(),
            scene.velocity(),
            law,
        )
    }

    /// A point mass's normal impact with restitution `e`.
    pub fn point_mass(mass: f64, normal_velocity: f64, tangential_velocity: f64, restitution: f64) -> Self {
        BarrierImpact {
            body: BarrierBody::PointMass { mass },
            velocity: PlanarVelocity {
                normal: normal_velocity,
                tangential: tangential_velocity,
                angular: 0.0,
            },
            law: Law::Frictionless { restitution },
        }
    }

    /// The validated scene of a rigid body: finite inputs, an approaching contact.
    pub fn scene(&self) -> Result<BarrierScene> {
        match self.body {
            BarrierBody::Rigid {
                mass,
                inertia,
                contact,
            } => BarrierScene::new(Body::new(mass, inertia)?, contact, self.velocity),
            BarrierBody::PointMass { .. } => Err(ImpactError::NeedsInertia {
                input: Input::TangentialOffset,
            }),
        }
    }

    /// The rigid body at its contact, validated as [`BarrierImpact::scene`]
    /// validates it, with its lever arm for the scales.
    fn placed(&self) -> Result<FixedBody> {
        match self.body {
            BarrierBody::Rigid {
                mass,
                inertia,
                contact,
            } => Ok(FixedBody {
                placed: Placed::new(Body::new(mass, inertia)?, contact)?,
                arm: lever_arm(&contact),
            }),
            BarrierBody::PointMass { .. } => Err(ImpactError::NeedsInertia {
                input: Input::TangentialOffset,
            }),
        }
    }

    /// [`BarrierImpact::scene`], the body validated once where it is fixed.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn scene_with(&self, fixed: &Fixed) -> Result<BarrierScene> {
        match fixed.body.as_deref() {
            Some(Ok(body)) => body.placed.moving(self.velocity),
            Some(Err(e)) => Err(e.clone()),
            None => self.scene(),
        }
    }

    /// [`Case::error_scales`], the lever arm formed once where it is fixed.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn error_scales_with(&self, fixed: &Fixed) -> ErrorScales {
        match fixed.body.as_deref() {
            Some(Ok(body)) => rigid_scales(body.placed.body().mass(), body.arm, &self.velocity),
            _ => self.error_scales(),
        }
    }

    /// Checks a point mass: positive mass, no spin, an approaching normal
    /// velocity, a frictionless law with `e ∈ [0, 1]`.
    fn point_mass_inputs(&self, mass: f64) -> Result<PointMass> {
        let mass = positive(Input::Mass, mass)?;
        let v = self.velocity;
        let vn = finite(Input::NormalVelocity, v.normal)?;
        let vt = finite(Input::TangentialVelocity, v.tangential)?;
        if finite(Input::AngularVelocity, v.angular)? != 0.0 {
            return Err(ImpactError::NeedsInertia {
                input: Input::AngularVelocity,
            });
        }
        let Law::Frictionless { restitution } = self.law else {
            return Err(ImpactError::NeedsInertia {
                input: law_input(&self.law),
            });
        };
        if vn >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: vn + 0.0,
            });
        }
        let e = in_range(Input::Restitution, restitution, 0.0, 1.0)?;
        Ok(PointMass { mass, vn, vt, e })
    }
}

/// The first coefficient a law reads that only a rigid body can use.
fn law_input(law: &Law) -> Input {
    match law {
        Law::Frictionless { .. } => Input::Restitution,
        Law::ImpulseRatio { .. } => Input::ImpulseRatio,
        Law::Friction { .. } | Law::TangentialRestitution { .. } => Input::Friction,
        Law::KineticRestitution { .. } | Law::KineticFriction { .. } => Input::KineticRestitution,
    }
}

/// What a sweep's points share, validated once: a rigid body's scene when no
/// axis changes it, the body at its contact when no axis changes them, and
/// its law when no axis changes that.
#[derive(Debug, Clone)]
pub struct Fixed {
    scene: Option<Result<BarrierScene>>,
    /// Boxed: only a sweep over velocities forms it.
    body: Option<Box<Result<FixedBody>>>,
    law: Option<Result<Law>>,
}

/// A rigid body at its contact, validated, and its lever arm.
#[derive(Debug, Clone, Copy)]
struct FixedBody {
    placed: Placed,
    arm: f64,
}

/// The lever arm `√(d_c² + d_d²)` from the centre of mass to the contact.
#[cfg_attr(not(debug_assertions), inline(always))]
fn lever_arm(contact: &Contact) -> f64 {
    let (c, d) = (contact.tangential_offset, contact.normal_offset);
    c.mul_add(c, d * d).sqrt()
}

/// A rigid body's scales: its mass, velocity and spin, and its lever arm.
#[cfg_attr(not(debug_assertions), inline(always))]
fn rigid_scales(mass: f64, arm: f64, v: &PlanarVelocity) -> ErrorScales {
    ScalesOf::new()
        .body(mass, &[v.normal, v.tangential], &[v.angular], arm)
        .scales()
}

/// A validated rigid-body impact, ready to run in any field.
struct Rigid<'a> {
    scene: &'a BarrierScene,
    law: Law,
    outputs: Outputs,
}

impl Model<BarrierOutcome> for Rigid<'_> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn run<N: Radical>(&self, out: &mut BarrierOutcome) -> Exact<N, ()> {
        model::rigid::<N>(self.scene, &self.law, self.outputs, out)
    }
}

struct Point {
    mass: PointMass,
    outputs: Outputs,
}

impl Model<BarrierOutcome> for Point {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn run<N: Radical>(&self, out: &mut BarrierOutcome) -> Exact<N, ()> {
        model::point_mass::<N>(&self.mass, self.outputs, out)
    }
}

impl Case for BarrierImpact {
    type Outcome = BarrierOutcome;
    type Fixed = Fixed;

    reads!(|impact, input| {
        Mass => match &mut impact.body {
            BarrierBody::PointMass { mass } | BarrierBody::Rigid { mass, .. } => Some(mass),
        },
        Inertia => match &mut impact.body {
            BarrierBody::Rigid { inertia, .. } => Some(inertia),
            BarrierBody::PointMass { .. } => None,
        },
        TangentialOffset => match &mut impact.body {
            BarrierBody::Rigid { contact, .. } => Some(&mut contact.tangential_offset),
            BarrierBody::PointMass { .. } => None,
        },
        NormalOffset => match &mut impact.body {
            BarrierBody::Rigid { contact, .. } => Some(&mut contact.normal_offset),
            BarrierBody::PointMass { .. } => None,
        },
        NormalVelocity => Some(&mut impact.velocity.normal),
        TangentialVelocity => Some(&mut impact.velocity.tangential),
        AngularVelocity => match impact.body {
            BarrierBody::Rigid { .. } => Some(&mut impact.velocity.angular),
            BarrierBody::PointMass { .. } => None,
        },
        // A point mass's law is frictionless: it reads `e` alone.
        law => match impact.body {
            BarrierBody::PointMass { .. } if input != Input::Restitution => None,
            _ => impact.law.input_mut(input),
        },
    });

    /// Every field at once (a point mass's unread angular velocity too: at
    /// worst an impact goes to the exact stages, which answer it the same).
    #[inline]
    fn all_in_fast_range(&self) -> bool {
        let body = match self.body {
            BarrierBody::PointMass { mass } => [mass, 0.0, 0.0, 0.0],
            BarrierBody::Rigid {
                mass,
                inertia,
                contact,
            } => [mass, inertia, contact.tangential_offset, contact.normal_offset],
        };
        let v = self.velocity;
        body.into_iter()
            .chain([v.normal, v.tangential, v.angular])
            .chain(self.law.coefficients())
            .all(super::in_fast_range)
    }

    fn error_scales(&self) -> ErrorScales {
        let (mass, arm) = match self.body {
            BarrierBody::PointMass { mass } => (mass, 0.0),
            BarrierBody::Rigid { mass, contact, .. } => (mass, lever_arm(&contact)),
        };
        rigid_scales(mass, arm, &self.velocity)
    }

    fn describe(&self) -> &'static str {
        match self.body {
            BarrierBody::PointMass { .. } => "a point mass",
            BarrierBody::Rigid { .. } => self.law.describe(),
        }
    }

    fn fix(&self, swept: &[Input]) -> Self::Fixed {
        const BODY: [Input; 4] = [
            Input::Mass,
            Input::Inertia,
            Input::TangentialOffset,
            Input::NormalOffset,
        ];
        const VELOCITY: [Input; 3] = [
            Input::NormalVelocity,
            Input::TangentialVelocity,
            Input::AngularVelocity,
        ];
        let rigid = matches!(self.body, BarrierBody::Rigid { .. });
        // Every other input of the case is the law's.
        let (body_swept, velocity_swept, law_swept) = (
            swept.iter().any(|i| BODY.contains(i)),
            swept.iter().any(|i| VELOCITY.contains(i)),
            swept.iter().any(|i| !BODY.contains(i) && !VELOCITY.contains(i)),
        );
        Fixed {
            scene: (rigid && !body_swept && !velocity_swept).then(|| self.scene()),
            // Only where the scene is not fixed whole: a single solve forms
            // its scene once, and would form the body twice.
            body: (rigid && !body_swept && velocity_swept).then(|| Box::new(self.placed())),
            law: (rigid && !law_swept).then(|| self.law.validate()),
        }
    }

    /// A rigid body under a law no axis changes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_lanes(fixed: &Fixed) -> bool {
        matches!(fixed.law, Some(Ok(_)))
    }

    /// A rigid body's points under a law no axis changes, in lanes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_lanes(
        impacts: &[Self; LANES],
        fixed: &Fixed,
        outputs: Outputs,
        out: &mut [BarrierOutcome; LANES],
    ) -> bool {
        let Some(Ok(law)) = &fixed.law else {
            return false;
        };
        // The law is fixed, so an axis sets a scene input: each point's
        // scene is validated (a refusal is left to the single solve). Where
        // the body is fixed, only its velocities are checked, each scene
        // formed in place (a `Result` of each, copied in, took about a tenth
        // of the sweep's time by `perf`).
        let scenes = match fixed.body.as_deref() {
            Some(Ok(body)) => {
                let scenes = std::array::from_fn(|i| body.placed.moving_unchecked(impacts[i].velocity));
                let mut valid = true;
                for scene in &scenes {
                    valid &= scene.check_velocity().is_ok();
                }
                if !valid {
                    return false;
                }
                scenes
            }
            _ => {
                let Ok(first) = impacts[0].scene() else {
                    return false;
                };
                let mut scenes = [first; LANES];
                for (scene, impact) in scenes.iter_mut().zip(impacts).skip(1) {
                    match impact.scene() {
                        Ok(s) => *scene = s,
                        Err(_) => return false,
                    }
                }
                scenes
            }
        };
        let mut scales = [ErrorScales::UNPROMISED; LANES];
        for (scale, impact) in scales.iter_mut().zip(impacts) {
            *scale = impact.error_scales_with(fixed);
        }
        crate::arith::measure_lanes_against(&scales);
        // A compiled body of its own (as `fast`'s single solve has,
        // `super::run_fast`), not inlined into each sweep's loop: the loop
        // around it, which also solves points one by one, stays small (with
        // the model in lanes inlined, it spilled its own values across the
        // model's frame and took half as long again per point).
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || model::rigid_lanes::<SharedLanes<LANES>, LANES>(&scenes, law, outputs, out),
        )
        .is_ok()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate(
        &self,
        fixed: &Self::Fixed,
        outputs: Outputs,
        arithmetic: Arithmetic,
        in_range: bool,
        out: &mut BarrierOutcome,
    ) -> (Result<()>, Stage) {
        let stage = arithmetic.validating_stage();
        let refused = |e| (Err(e), stage);
        match self.body {
            BarrierBody::PointMass { mass } => match self.point_mass_inputs(mass) {
                Ok(mass) => evaluate(
                    arithmetic,
                    in_range,
                    || self.error_scales(),
                    StaticBounds::Tight,
                    Point { mass, outputs },
                    out,
                ),
                Err(e) => refused(e),
            },
            BarrierBody::Rigid { .. } => {
                let built;
                let scene = match &fixed.scene {
                    Some(Ok(scene)) => scene,
                    Some(Err(e)) => return refused(e.clone()),
                    None => match self.scene_with(fixed) {
                        Ok(scene) => {
                            built = scene;
                            &built
                        }
                        Err(e) => return refused(e),
                    },
                };
                let law = match &fixed.law {
                    Some(law) => law.clone(),
                    None => self.law.validate(),
                };
                match law {
                    Ok(law) => evaluate(
                        arithmetic,
                        in_range,
                        || self.error_scales_with(fixed),
                        StaticBounds::Tight,
                        Rigid { scene, law, outputs },
                        out,
                    ),
                    Err(e) => refused(e),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point mass reads its mass, its two velocities and `e`; a rigid body
    /// under each law reads its body and exactly that law's coefficients.
    #[test]
    fn reads_follow_the_body_and_the_law() {
        let point = BarrierImpact::point_mass(2.0, -1.0, 0.5, 0.75);
        assert_eq!(
            point.reads(),
            [
                Input::Mass,
                Input::NormalVelocity,
                Input::TangentialVelocity,
                Input::Restitution
            ]
        );
        let velocity = PlanarVelocity {
            normal: -1.0,
            tangential: 0.5,
            angular: 2.0,
        };
        let laws = [
            (Law::Frictionless { restitution: 0.5 }, vec![Input::Restitution]),
            (
                Law::KineticRestitution {
                    value: 0.5,
                    approach_impulse_ratio: 0.25,
                    rebound_impulse_ratio: 0.125,
                },
                vec![
                    Input::KineticRestitution,
                    Input::ApproachImpulseRatio,
                    Input::ReboundImpulseRatio,
                ],
            ),
            (
                Law::TangentialRestitution {
                    restitution: 0.5,
                    friction: 0.25,
                    tangential_restitution: 0.125,
                },
                vec![Input::Restitution, Input::Friction, Input::TangentialRestitution],
            ),
        ];
        for (law, coefficients) in laws {
            let rigid = BarrierImpact::rigid(1.0, 0.5, Contact::central(0.25), velocity, law);
            let reads = rigid.reads();
            assert_eq!(reads[..7], BarrierImpact::INPUTS[..7]);
            assert_eq!(reads[7..], coefficients);
        }
    }
}

#[cfg(test)]
mod lanes;
