//! The general planar case: body A against body B or a fixed barrier, in
//! world axes, with one tangential law (the `planar` endpoint). The model is
//! `src/model/bodies.rs` reduced to the contact space the laws of
//! `src/model/contact.rs` are written in.

use std::fmt;

use super::approach::{approach_bound, approaches};
use super::{Arithmetic, Case, LANES, Model, Stage, StaticBounds, TightFast, evaluate_contact};
use crate::accuracy::{ErrorScales, ScalesOf};
use crate::arith::{Compensated, Field, Fraction, Radical, SharedLanes};
use crate::error::{ImpactError, Input, Output, Result, finite, positive};
use crate::input::{BodiesImpact, Lamina, Law};
use crate::model::Exact;
use crate::model::bodies::{Geometry, approach, bodies, bodies_lanes};
use crate::outcome::{BODY_OUTPUTS, BodiesOutcome, Outputs};

/// The inputs of each body, in request order: parts of the case's declaration.
const BODY_INPUTS: [[Input; 7]; 2] = [
    crate::quantity::part(<BodiesImpact as Case>::INPUTS, 0),
    crate::quantity::part(<BodiesImpact as Case>::INPUTS, 7),
];

/// The fast evaluation's range for this case, `2^±60`: its longest products
/// (`det W̃`, the outputs formed from it) multiply up to sixteen inputs,
/// which then stay normal doubles.
fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (2f64.powi(-60)..=2f64.powi(60)).contains(&x.abs())
}

/// Whether every one of `values` is in this case's fast range.
fn all_in_range(values: &[f64]) -> bool {
    values.iter().all(|&x| in_fast_range(x))
}

impl Lamina {
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
        let (approaching, certain) = approaches(
            approach::<f64>(self),
            || self.approach_error_bound(),
            || approach::<Fraction>(self),
        );
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
        approach_bound(terms, 16.0)
    }
}

/// What a sweep validates once: the contact's geometry, when no axis
/// changes it (in `fast`'s first field, the compensated stage's, and lanes
/// of `fast`'s first field), and the law, when no axis changes it.
#[derive(Clone)]
pub struct Fixed {
    /// Boxed: a sweep holds one.
    geometry: Option<Box<Prepared>>,
    lanes: Option<Box<Geometry<SharedLanes<LANES>>>>,
    law: Option<Result<Law>>,
}

/// The geometry a sweep forms once.
type Prepared = super::Prepared<Geometry<TightFast>, Geometry<Compensated>>;

impl fmt::Debug for Fixed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Fixed")
            .field("geometry", &self.geometry.as_ref().map(|_| "formed"))
            .field("law", &self.law)
            .finish()
    }
}

impl BodiesImpact {
    /// The inputs the geometry reads: each body's mass, inertia and
    /// position, the contact point and the normal.
    fn geometry_inputs(&self) -> impl Iterator<Item = Input> + '_ {
        let bodies = if self.b.is_some() { 2 } else { 1 };
        BODY_INPUTS[..bodies]
            .iter()
            .flat_map(|inputs| inputs[..4].iter().copied())
            .chain([Input::ContactX, Input::ContactY, Input::NormalX, Input::NormalY])
    }

    /// Whether the bodies and the contact are in this case's fast range.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_this_range(&self) -> bool {
        all_in_range(&self.a.values())
            && self.b.is_none_or(|b| all_in_range(&b.values()))
            && all_in_range(&self.contact.point)
            && all_in_range(&self.contact.normal)
    }

    /// The geometry in both fields if the inputs it reads are valid and in
    /// this case's fast range, else `None`.
    fn prepared(&self) -> Option<Box<Prepared>> {
        let mut copy = *self;
        let inputs: Vec<f64> = self
            .geometry_inputs()
            .filter_map(|i| copy.input_mut(i).map(|x| *x))
            .collect();
        let valid = [Some(&self.a), self.b.as_ref()]
            .into_iter()
            .flatten()
            .all(|l| l.mass > 0.0 && l.inertia > 0.0)
            && inputs.iter().all(|x| x.is_finite())
            && all_in_range(&inputs)
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
struct Pair<'a> {
    impact: &'a BodiesImpact,
    prepared: Option<&'a Prepared>,
    outputs: Outputs,
}

impl Model<BodiesOutcome> for Pair<'_> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn run<N: Radical>(&self, out: &mut BodiesOutcome) -> Exact<N, ()> {
        let prepared = self.prepared.and_then(Prepared::get::<Geometry<N>>);
        bodies::<N>(self.impact, prepared, self.outputs, out)
    }
}

impl Case for BodiesImpact {
    type Outcome = BodiesOutcome;
    type Fixed = Fixed;

    reads!(|impact, input| {
        MassA => Some(&mut impact.a.mass),
        InertiaA => Some(&mut impact.a.inertia),
        PositionAX => Some(&mut impact.a.position[0]),
        PositionAY => Some(&mut impact.a.position[1]),
        VelocityAX => Some(&mut impact.a.velocity[0]),
        VelocityAY => Some(&mut impact.a.velocity[1]),
        AngularVelocityA => Some(&mut impact.a.angular_velocity),
        MassB => impact.b.as_mut().map(|b| &mut b.mass),
        InertiaB => impact.b.as_mut().map(|b| &mut b.inertia),
        PositionBX => impact.b.as_mut().map(|b| &mut b.position[0]),
        PositionBY => impact.b.as_mut().map(|b| &mut b.position[1]),
        VelocityBX => impact.b.as_mut().map(|b| &mut b.velocity[0]),
        VelocityBY => impact.b.as_mut().map(|b| &mut b.velocity[1]),
        AngularVelocityB => impact.b.as_mut().map(|b| &mut b.angular_velocity),
        ContactX => Some(&mut impact.contact.point[0]),
        ContactY => Some(&mut impact.contact.point[1]),
        NormalX => Some(&mut impact.contact.normal[0]),
        NormalY => Some(&mut impact.contact.normal[1]),
        law => impact.law.input_mut(input),
    });

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

    fn error_scales(&self) -> ErrorScales {
        let p = self.contact.point;
        let body = |scales: ScalesOf, b: &Lamina| {
            let r = [p[0] - b.position[0], p[1] - b.position[1]];
            scales.body(
                b.mass,
                &b.velocity,
                &[b.angular_velocity],
                r[0].mul_add(r[0], r[1] * r[1]).sqrt(),
            )
        };
        let scales = body(ScalesOf::new(), &self.a);
        match &self.b {
            Some(b) => body(scales, b),
            None => scales,
        }
        .scales()
    }

    fn describe(&self) -> &'static str {
        match self.b {
            Some(_) => "two bodies",
            None => "a body against a barrier",
        }
    }

    fn fix(&self, swept: &[Input]) -> Fixed {
        // A single solve (nothing swept) forms its geometry in the field it runs in.
        let geometry_swept = self.geometry_inputs().any(|i| swept.contains(&i));
        let geometry = (!swept.is_empty() && !geometry_swept)
            .then(|| self.prepared())
            .flatten();
        let law_swept = swept.iter().any(|&i| self.law.clone().input_mut(i).is_some());
        Fixed {
            // Formed as the others are (`Geometry::new` of the same
            // inputs), so each lane is `fast`'s first field's geometry.
            lanes: geometry
                .as_ref()
                .map(|_| Box::new(crate::kernels::run(|| Geometry::new(self)))),
            geometry,
            law: (!swept.is_empty() && !law_swept).then(|| self.law.validate()),
        }
    }

    /// A geometry and a law no axis changes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_lanes(fixed: &Fixed) -> bool {
        fixed.lanes.is_some() && matches!(fixed.law, Some(Ok(_)))
    }

    /// The points of a geometry and a law no axis changes, in lanes: each
    /// validated as its single solve validates it, its approach decided in
    /// f64 and every input in this case's fast range (else the points are
    /// solved one by one).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_lanes(
        impacts: &[Self; LANES],
        fixed: &Fixed,
        outputs: Outputs,
        out: &mut [BodiesOutcome; LANES],
    ) -> bool {
        let (Some(geometry), Some(Ok(law))) = (&fixed.lanes, &fixed.law) else {
            return false;
        };
        let mut scales = [ErrorScales::UNPROMISED; LANES];
        for (scale, impact) in scales.iter_mut().zip(impacts) {
            if !matches!(impact.validate(), Ok((_, true))) || !impact.in_this_range() {
                return false;
            }
            *scale = impact.error_scales();
        }
        crate::arith::measure_lanes_against(&scales);
        // A compiled body of its own, as the one lamina's lanes
        // (`impact::barrier`).
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || bodies_lanes::<SharedLanes<LANES>, LANES>(impacts, law, geometry, outputs, out),
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
        out: &mut BodiesOutcome,
    ) -> (Result<()>, Stage) {
        let stage = arithmetic.validating_stage();
        match self.validate() {
            Ok((law, certain)) => {
                let impact = BodiesImpact { law, ..*self };
                let in_range = in_range && self.in_this_range();
                evaluate_contact(
                    arithmetic,
                    in_range,
                    certain,
                    || self.error_scales(),
                    StaticBounds::Tight,
                    Pair {
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
mod tests {
    use super::*;
    use crate::input::PlanarContact;

    fn lamina(seed: f64) -> Lamina {
        Lamina {
            mass: seed,
            inertia: seed + 0.125,
            position: [seed + 0.25, seed + 0.375],
            velocity: [seed + 0.5, seed + 0.625],
            angular_velocity: seed + 0.75,
        }
    }

    /// A sweep's geometry formed once (in `fast`'s first field and the
    /// compensated stage's) answers every point as the geometry formed per
    /// point does, in both precisions: the same bits, regimes and refusals
    /// (a separating contact, a law that creates energy), in every law, with
    /// and without body B; an axis on a geometry input forms it per point.
    #[test]
    fn a_geometry_formed_once_answers_as_one_formed_per_point() {
        let car = |mass: f64, x: f64, vx: f64| Lamina {
            mass,
            inertia: mass * 1.6,
            position: [x, -0.4],
            velocity: [vx, 0.5],
            angular_velocity: 0.3,
        };
        let laws = crate::impact::testing::one_law_of_each_kind();
        let axes: [(Input, &[f64]); 3] = [
            (Input::VelocityAX, &[-20.0, -2.0, 0.0, 3.0, 15.0]),
            (Input::VelocityAY, &[-8.0, 0.0, 0.5, 6.0]),
            (Input::AngularVelocityA, &[-4.0, 0.0, 0.3]),
        ];
        let mut answered = 0;
        for b in [None, Some(car(1200.0, 3.0, -2.0))] {
            for law in laws {
                let base = BodiesImpact {
                    a: car(1500.0, 0.0, 15.0),
                    b,
                    contact: PlanarContact {
                        point: [2.2, -0.6],
                        normal: [-1.0, 0.25],
                    },
                    law,
                };
                answered += crate::impact::testing::formed_once_answers_as_per_point(
                    &base,
                    &axes,
                    Input::PositionAY,
                    |fixed: &Fixed| fixed.geometry.is_some(),
                );
            }
        }
        assert!(answered >= 400, "{answered}");
    }

    /// A lamina's values in request order are the slots the declaration
    /// names; a barrier impact reads no input of body B.
    #[test]
    fn body_values_are_the_declared_slots_in_order() {
        let impact = BodiesImpact {
            a: lamina(1.0),
            b: Some(lamina(2.0)),
            contact: PlanarContact {
                point: [0.0, 0.0],
                normal: [1.0, 0.0],
            },
            law: Law::Friction {
                restitution: 0.5,
                friction: 0.25,
            },
        };
        for (k, b) in [impact.a, impact.b.unwrap()].iter().enumerate() {
            for (i, &input) in BODY_INPUTS[k].iter().enumerate() {
                assert_eq!(impact.input(input), Some(b.values()[i]), "{input:?}");
            }
        }
        let barrier = BodiesImpact { b: None, ..impact };
        assert!(BODY_INPUTS[1].iter().all(|&i| barrier.input(i).is_none()));
        assert_eq!(barrier.reads().len(), 7 + 4 + 2);
    }
}

#[cfg(test)]
mod lanes {
    use super::*;
    use crate::impact::testing::{block_answers_as_single_solves, one_law_of_each_kind};
    use crate::impact::{Precision, Solver, solve};
    use crate::input::PlanarContact;

    /// The two cars of `examples/planar_car_to_car_sweep.json` (or car A
    /// against a barrier), car B moving at `vy`, under `law`.
    fn cars(vy: f64, with_b: bool, law: Law) -> BodiesImpact {
        let car = |mass: f64, inertia: f64, position: [f64; 2], velocity: [f64; 2]| Lamina {
            mass,
            inertia,
            position,
            velocity,
            angular_velocity: 0.0,
        };
        BodiesImpact {
            a: car(1500.0, 2500.0, [0.0, 0.0], [15.0, 0.0]),
            b: with_b.then(|| car(1200.0, 1800.0, [3.0, -1.5], [0.0, vy])),
            contact: PlanarContact {
                point: [2.2, -0.6],
                normal: [-1.0, 0.0],
            },
            law,
        }
    }

    /// Blocks through the sweep's door, under a law of each kind, with and
    /// without body B: each point's answer or refusal is its single solve's,
    /// whether in lanes (most points) or one by one (lanes that disagree, a
    /// refusal, a tail).
    #[test]
    fn a_block_answers_each_point_as_its_single_solve() {
        let (mut together, mut points_seen) = (0, 0);
        for law in one_law_of_each_kind() {
            for with_b in [true, false] {
                let base = cars(12.0, with_b, law);
                let swept = [Input::VelocityBY, Input::VelocityAX, Input::AngularVelocityA];
                let solver = Solver::new(&base, &swept, Outputs::ALL, Precision::Fast);
                assert!(solver.in_lanes());
                let points: Vec<BodiesImpact> = (0..23)
                    .map(|k| {
                        let mut p = cars(-30.0 + 2.75 * k as f64, with_b, law);
                        p.a.velocity[0] = if k == 9 { -3.0 } else { 15.0 - 0.5 * k as f64 };
                        p.a.angular_velocity = if k == 14 { 1e300 } else { 0.0 };
                        p
                    })
                    .collect();
                // Point 9 separates; point 14's spin leaves the f64 range.
                let refused = block_answers_as_single_solves(&solver, &points);
                assert!(refused.starts_with(&[9, 14]), "{refused:?} under {law:?}");
                // How many groups of four the lanes answered together.
                let fixed = base.fix(&swept);
                for group in points.chunks_exact(LANES) {
                    let group: &[BodiesImpact; LANES] = group.try_into().expect("four");
                    let mut out = [BodiesOutcome::default(); LANES];
                    if BodiesImpact::evaluate_lanes(group, &fixed, Outputs::ALL, &mut out) {
                        together += 1;
                        for (impact, outcome) in group.iter().zip(&out) {
                            let single = solve(impact, Outputs::ALL, Precision::Fast);
                            assert_eq!(format!("{single:?}"), format!("{:?}", Ok::<_, ()>(outcome)));
                        }
                    }
                    points_seen += LANES;
                }
            }
        }
        assert!(
            together * LANES * 3 > points_seen,
            "{together} groups of {points_seen} points"
        );
    }

    /// Lanes answer a geometry and a law no axis changes, in `fast`, alone.
    #[test]
    fn which_solvers_run_lanes() {
        let base = cars(12.0, true, one_law_of_each_kind()[2]);
        let solver = |swept: &[Input], precision| Solver::new(&base, swept, Outputs::ALL, precision);
        assert!(solver(&[Input::VelocityBY], Precision::Fast).in_lanes());
        assert!(!solver(&[Input::VelocityBY], Precision::Exact).in_lanes());
        assert!(!solver(&[Input::Friction], Precision::Fast).in_lanes());
        assert!(!solver(&[Input::VelocityBY, Input::MassB], Precision::Fast).in_lanes());
        assert!(!solver(&[Input::ContactX], Precision::Fast).in_lanes());
    }
}
