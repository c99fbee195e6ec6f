//! The case in space: body A against body B or a fixed barrier, with full
//! inertia tensors, one tangential law and an optional twist law (the
//! `spatial` endpoint). The model is `src/model/spatial/`.

use std::cmp::Ordering;
use std::fmt;

use super::approach::{approach_bound, approaches};
use super::{Arithmetic, Case, LANES, LooseFast, Model, Stage, StaticBounds, evaluate_contact};
use crate::accuracy::{ErrorScales, ScalesOf};
use crate::arith::{Compensated, Field, Fraction, Lanes, Radical};
use crate::error::{ImpactError, Input, Output, Result, finite, in_range, positive};
use crate::input::{Law, RigidBody, SpatialImpact, Twist};
use crate::model::Exact;
use crate::model::spatial::{Geometry, approach, leading_minors, spatial, spatial_lanes};
use crate::outcome::{Outputs, SPATIAL_BODY_OUTPUTS, SpatialOutcome};

/// The inputs of each body, in request order: parts of the case's declaration.
const BODY_INPUTS: [[Input; 16]; 2] = [
    crate::quantity::part(<SpatialImpact as Case>::INPUTS, 0),
    crate::quantity::part(<SpatialImpact as Case>::INPUTS, 16),
];

/// The tensors as a whole, for refusals.
const TENSORS: [Input; 2] = [Input::InertiaA, Input::InertiaB];

/// The fast evaluation's range for this case, `2^±50`: its longest products
/// (`det W`, the adjugates and the energies of the couple) multiply up to
/// twenty inputs, which then stay normal doubles.
fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (2f64.powi(-50)..=2f64.powi(50)).contains(&x.abs())
}

/// Whether every one of `values` is in this case's fast range.
fn all_in_range(values: &[f64]) -> bool {
    values.iter().all(|&x| in_fast_range(x))
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

    fn values(&self) -> [f64; 16] {
        let mut copy = *self;
        std::array::from_fn(|i| *copy.slot(i))
    }

    /// Every input in request order, then the tensor ([`RigidBody::check_tensor`],
    /// or its result `checked` once for a sweep).
    fn validate(&self, k: usize, checked: Option<&Result<()>>) -> Result<()> {
        let names = &BODY_INPUTS[k];
        positive(names[0], self.mass)?;
        for (i, x) in self.values().into_iter().enumerate().skip(1) {
            finite(names[i], x)?;
        }
        match checked {
            Some(result) => result.clone(),
            None => self.check_tensor(k),
        }
    }

    /// The tensor of a body whose inputs are finite: symmetric by
    /// construction, positive definite by its leading minors (decided
    /// exactly where the f64 ones are too close to zero for their bound),
    /// and a rigid body's.
    fn check_tensor(&self, k: usize) -> Result<()> {
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
        self.check_triangle_inequality(k)
    }

    /// The principal moments of a rigid body obey the triangle inequality
    /// (each is at most the sum of the other two: `I = tr(S) E − S` with the
    /// second-moment tensor `S = ∫ r rᵀ dm ⪰ 0`, so `2 λ_max ≤ tr I`). A tensor
    /// written in decimal is accepted within a relative tolerance of `1e-9`
    /// of its trace (a lamina's `I_z = I_x + I_y` rounds either way); the
    /// eigenvalues' own error, about `1e-16` of the trace, is far below it.
    fn check_triangle_inequality(&self, k: usize) -> Result<()> {
        const TOLERANCE: f64 = 1e-9;
        let [xx, yy, zz, xy, xz, yz] = self.inertia;
        // Gershgorin's bound on λ_max decides at once where it suffices (every
        // diagonal tensor, most rotated ones), without the eigenvalues.
        let bound = (xx + xy.abs() + xz.abs())
            .max(yy + xy.abs() + yz.abs())
            .max(zz + xz.abs() + yz.abs());
        let trace = xx + yy + zz;
        if 2.0 * bound - trace <= TOLERANCE * trace {
            return Ok(());
        }
        let tensor = nalgebra::Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
        let mut moments: [f64; 3] = tensor.symmetric_eigenvalues().into();
        moments.sort_by(f64::total_cmp);
        let [small, middle, largest] = moments;
        let others = small + middle;
        if largest - others > TOLERANCE * (largest + others) {
            return Err(ImpactError::NotRigidInertia {
                input: TENSORS[k],
                moments,
                largest,
                others,
            });
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
}

impl SpatialImpact {
    fn bodies(&self) -> impl Iterator<Item = &RigidBody> {
        std::iter::once(&self.a).chain(self.b.as_ref())
    }

    /// Checks every input in request order (each body's tensor as `fixed`
    /// checked it, if it did), the laws, and whether the contact approaches,
    /// exactly. Returns the validated law and whether the f64 evaluation
    /// decides the approach the same way.
    fn validate(&self, fixed: &Fixed) -> Result<(Law, bool)> {
        for (k, body) in self.bodies().enumerate() {
            body.validate(k, fixed.tensors[k].as_ref())?;
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
        let law = self.law.validate_spatial(self.torsion.is_some())?;
        if let Some(twist) = &self.torsion {
            twist.validate()?;
        }
        let fast = approach::<f64>(self);
        let (approaching, certain) = approaches(
            fast,
            || self.approach_error_bound(),
            || approach::<Fraction>(self),
        );
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
        approach_bound(terms, 32.0)
    }
}

/// What a sweep's points share, formed once: each body's tensor checks
/// when no axis changes that tensor, and the geometry ([`Prepared`]) when
/// axes change inputs but no mass, tensor, position, the contact point or
/// the normal, and those are valid and in the fast range (and in lanes of
/// `fast`'s first field too, when the axes change only the bodies'
/// velocities, so that lanes share the law as well).
#[derive(Clone)]
pub struct Fixed {
    tensors: [Option<Result<()>>; 2],
    /// Boxed: a sweep holds one, and it is larger than the rest of the sweep.
    geometry: Option<Box<Prepared>>,
    lanes: Option<Box<Geometry<MotionLanes>>>,
}

/// The geometry a sweep forms once.
type Prepared = super::Prepared<Geometry<LooseFast>, Geometry<Compensated>>;

/// Lanes of [`LooseFast`], the field `fast` evaluates a contact in space in first.
type MotionLanes = Lanes<LANES, true, false>;

/// Whether `input` is a velocity or an angular velocity of either body.
fn is_motion(input: Input) -> bool {
    BODY_INPUTS.iter().any(|body| body[10..].contains(&input))
}

impl fmt::Debug for Fixed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Fixed")
            .field("tensors", &self.tensors)
            .field("geometry", &self.geometry.as_ref().map(|_| "formed"))
            .finish()
    }
}

impl SpatialImpact {
    /// The inputs the geometry reads: each body's mass, tensor and
    /// position, the contact point and the normal.
    fn geometry_inputs(&self) -> impl Iterator<Item = Input> + '_ {
        self.bodies()
            .enumerate()
            .flat_map(|(k, _)| BODY_INPUTS[k][..10].iter().copied())
            .chain([Input::ContactX, Input::ContactY, Input::ContactZ])
            .chain([Input::NormalX, Input::NormalY, Input::NormalZ])
    }

    /// The geometry in both fields if the inputs it reads are valid (each
    /// tensor's check being `tensors`) and in the fast range, else `None`.
    fn prepared(&self, tensors: &[Option<Result<()>>; 2]) -> Option<Box<Prepared>> {
        let mut copy = *self;
        let inputs: Vec<f64> = self
            .geometry_inputs()
            .filter_map(|i| copy.input_mut(i).map(|x| *x))
            .collect();
        let valid = self.bodies().all(|b| b.mass > 0.0)
            && inputs.iter().all(|x| x.is_finite())
            && all_in_range(&inputs)
            && tensors
                .iter()
                .take(self.bodies().count())
                .all(|t| matches!(t, Some(Ok(()))))
            && self.contact.normal.iter().any(|&x| x != 0.0);
        valid.then(|| {
            Box::new(crate::kernels::run(|| Prepared {
                fast: Geometry::new(self),
                compensated: Geometry::new(self),
            }))
        })
    }
}

/// The model of a validated contact, with its geometry when a sweep formed
/// it once.
struct Space<'a> {
    impact: &'a SpatialImpact,
    prepared: Option<&'a Prepared>,
    outputs: Outputs,
}

impl Model<SpatialOutcome> for Space<'_> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn run<N: Radical>(&self, out: &mut SpatialOutcome) -> Exact<N, ()> {
        let prepared = self.prepared.and_then(Prepared::get::<Geometry<N>>);
        spatial::<N>(self.impact, prepared, self.outputs, out)
    }
}

impl Case for SpatialImpact {
    type Outcome = SpatialOutcome;
    type Fixed = Fixed;

    reads!(|impact, input| {
        MassA => Some(&mut impact.a.mass),
        InertiaAXX => Some(&mut impact.a.inertia[0]),
        InertiaAYY => Some(&mut impact.a.inertia[1]),
        InertiaAZZ => Some(&mut impact.a.inertia[2]),
        InertiaAXY => Some(&mut impact.a.inertia[3]),
        InertiaAXZ => Some(&mut impact.a.inertia[4]),
        InertiaAYZ => Some(&mut impact.a.inertia[5]),
        PositionAX => Some(&mut impact.a.position[0]),
        PositionAY => Some(&mut impact.a.position[1]),
        PositionAZ => Some(&mut impact.a.position[2]),
        VelocityAX => Some(&mut impact.a.velocity[0]),
        VelocityAY => Some(&mut impact.a.velocity[1]),
        VelocityAZ => Some(&mut impact.a.velocity[2]),
        AngularVelocityAX => Some(&mut impact.a.angular_velocity[0]),
        AngularVelocityAY => Some(&mut impact.a.angular_velocity[1]),
        AngularVelocityAZ => Some(&mut impact.a.angular_velocity[2]),
        MassB => impact.b.as_mut().map(|b| &mut b.mass),
        InertiaBXX => impact.b.as_mut().map(|b| &mut b.inertia[0]),
        InertiaBYY => impact.b.as_mut().map(|b| &mut b.inertia[1]),
        InertiaBZZ => impact.b.as_mut().map(|b| &mut b.inertia[2]),
        InertiaBXY => impact.b.as_mut().map(|b| &mut b.inertia[3]),
        InertiaBXZ => impact.b.as_mut().map(|b| &mut b.inertia[4]),
        InertiaBYZ => impact.b.as_mut().map(|b| &mut b.inertia[5]),
        PositionBX => impact.b.as_mut().map(|b| &mut b.position[0]),
        PositionBY => impact.b.as_mut().map(|b| &mut b.position[1]),
        PositionBZ => impact.b.as_mut().map(|b| &mut b.position[2]),
        VelocityBX => impact.b.as_mut().map(|b| &mut b.velocity[0]),
        VelocityBY => impact.b.as_mut().map(|b| &mut b.velocity[1]),
        VelocityBZ => impact.b.as_mut().map(|b| &mut b.velocity[2]),
        AngularVelocityBX => impact.b.as_mut().map(|b| &mut b.angular_velocity[0]),
        AngularVelocityBY => impact.b.as_mut().map(|b| &mut b.angular_velocity[1]),
        AngularVelocityBZ => impact.b.as_mut().map(|b| &mut b.angular_velocity[2]),
        ContactX => Some(&mut impact.contact.point[0]),
        ContactY => Some(&mut impact.contact.point[1]),
        ContactZ => Some(&mut impact.contact.point[2]),
        NormalX => Some(&mut impact.contact.normal[0]),
        NormalY => Some(&mut impact.contact.normal[1]),
        NormalZ => Some(&mut impact.contact.normal[2]),
        law => impact.law.input_mut(input),
        TorsionalRestitution => impact.torsion.as_mut().map(|t| &mut t.restitution),
        TorsionalFriction => impact.torsion.as_mut().map(|t| &mut t.friction),
        PitchRadius => impact.torsion.as_mut().map(|t| &mut t.pitch_radius),
    });

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

    /// Each body's velocity and spin components with its lever arm `|C − G|`;
    /// the pitch radius of a twist law is a lever arm of the couple.
    fn error_scales(&self) -> ErrorScales {
        let c = self.contact.point;
        let mut scales = ScalesOf::new();
        for b in self.bodies() {
            let r = [0, 1, 2].map(|i| c[i] - b.position[i]);
            let arm = r[0].mul_add(r[0], r[1].mul_add(r[1], r[2] * r[2])).sqrt();
            scales = scales.body(b.mass, &b.velocity, &b.angular_velocity, arm);
        }
        match &self.torsion {
            Some(twist) => scales.lever(twist.pitch_radius),
            None => scales,
        }
        .scales()
    }

    fn describe(&self) -> &'static str {
        match self.b {
            Some(_) => "two bodies in space",
            None => "a body against a barrier in space",
        }
    }

    fn fix(&self, swept: &[Input]) -> Fixed {
        let tensors = std::array::from_fn(|k| {
            let body = if k == 0 { Some(&self.a) } else { self.b.as_ref() }?;
            let tensor = &BODY_INPUTS[k][1..7];
            let finite = body.inertia.iter().all(|x| x.is_finite());
            (finite && !swept.iter().any(|i| tensor.contains(i))).then(|| body.check_tensor(k))
        });
        // A single solve (nothing swept) forms its geometry in the field it runs in.
        let geometry_swept = self.geometry_inputs().any(|i| swept.contains(&i));
        let geometry = if swept.is_empty() || geometry_swept {
            None
        } else {
            self.prepared(&tensors)
        };
        // Formed as the others are (`Geometry::new` of the same inputs),
        // so each lane is `fast`'s first field's geometry.
        let lanes = match &geometry {
            Some(_) if swept.iter().all(|&i| is_motion(i)) => {
                Some(Box::new(crate::kernels::run(|| Geometry::new(self))))
            }
            _ => None,
        };
        Fixed {
            tensors,
            geometry,
            lanes,
        }
    }

    /// A sweep over the bodies' velocities alone, its geometry formed once.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_lanes(fixed: &Fixed) -> bool {
        fixed.lanes.is_some()
    }

    /// The points of a sweep over the bodies' velocities, in lanes: each
    /// validated as its single solve validates it, its approach decided in
    /// f64 and every input of the bodies in this case's fast range (else
    /// the points are solved one by one).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_lanes(
        impacts: &[Self; LANES],
        fixed: &Fixed,
        outputs: Outputs,
        out: &mut [SpatialOutcome; LANES],
    ) -> bool {
        let Some(geometry) = fixed.lanes.as_deref() else {
            return false;
        };
        let mut valid = *impacts;
        let mut scales = [ErrorScales::UNPROMISED; LANES];
        for ((point, scale), impact) in valid.iter_mut().zip(&mut scales).zip(impacts) {
            debug_assert_eq!(impact.b.is_some(), impacts[0].b.is_some());
            match impact.validate(fixed) {
                Ok((law, true)) if impact.bodies().all(|b| all_in_range(&b.values())) => point.law = law,
                _ => return false,
            }
            *scale = impact.error_scales();
        }
        crate::arith::measure_lanes_against(&scales);
        // A compiled body of its own, as the laminae's lanes
        // (`impact::barrier`).
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || spatial_lanes::<MotionLanes, LANES>(&valid, Some(geometry), outputs, out),
        )
        .is_ok()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate(
        &self,
        fixed: &Fixed,
        outputs: Outputs,
        arithmetic: Arithmetic,
        in_range: bool,
        out: &mut SpatialOutcome,
    ) -> (Result<()>, Stage) {
        let stage = arithmetic.validating_stage();
        match self.validate(fixed) {
            Ok((law, certain)) => {
                let impact = SpatialImpact { law, ..*self };
                let in_range = in_range
                    && self.bodies().all(|b| all_in_range(&b.values()))
                    && all_in_range(&self.contact.point)
                    && all_in_range(&self.contact.normal);
                evaluate_contact(
                    arithmetic,
                    in_range,
                    certain,
                    || self.error_scales(),
                    StaticBounds::Loose,
                    Space {
                        impact: &impact,
                        prepared: fixed.geometry.as_deref(),
                        outputs,
                    },
                    out,
                )
            }
            Err(e) => (Err(e), stage),
        }
    }
}

#[cfg(test)]
mod tests;
