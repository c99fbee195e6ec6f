//! The sweep's door for one lamina: points answered together in lanes
//! (`arith::SharedLanes`) are each their single solve.

use super::*;
use crate::impact::{Precision, Solver, solve};

/// Figure 2's scene (`examples/figure2_coulomb_friction.json`) at `v_t`.
fn figure2(vt: f64) -> BarrierImpact {
    BarrierImpact::rigid(
        1.0,
        0.00125,
        Contact {
            tangential_offset: 0.0,
            normal_offset: 0.05,
        },
        PlanarVelocity {
            normal: -1.0,
            tangential: vt,
            angular: 0.0,
        },
        Law::Friction {
            restitution: 0.93,
            friction: 0.123,
        },
    )
}

/// A block through the sweep's door: each point's answer or refusal is
/// its single solve's, in lanes and one by one alike (a point refused,
/// one outside the fast range, lanes that disagree, a tail of fewer
/// than four).
#[test]
fn a_block_answers_each_point_as_its_single_solve() {
    let swept = [Input::TangentialVelocity, Input::NormalVelocity];
    let solver = Solver::new(&figure2(0.0), &swept, Outputs::ALL, Precision::Fast);
    assert!(solver.in_lanes());
    let points: Vec<BarrierImpact> = [
        (2.0, -1.0),
        (2.5, -1.0),
        (3.0, -1.0),
        (3.5, -1.0),
        (2.0, -1.0),
        (2.5, 0.5),
        (3.0, -1.0),
        (1e300, -1.0),
        (0.01, -1.0),
        (0.02, -1.0),
        (0.03, -2.0),
        (0.04, -3.0),
        (-4.0, -1.0),
        (-4.5, -1.0),
        (0.0, -1.0),
    ]
    .into_iter()
    .map(|(vt, vn)| {
        let mut p = figure2(vt);
        p.velocity.normal = vn;
        p
    })
    .collect();
    // Not approaching, and an energy beyond the f64 range.
    let refused = crate::impact::testing::block_answers_as_single_solves(&solver, &points);
    assert_eq!(refused, [5, 7]);
    // Lanes answer a law no axis changes, in `fast`, alone.
    let law_swept = Solver::new(&figure2(0.0), &[Input::Friction], Outputs::ALL, Precision::Fast);
    let exact = Solver::new(&figure2(0.0), &swept, Outputs::ALL, Precision::Exact);
    let point = BarrierImpact::point_mass(1.0, -1.0, 0.5, 0.5);
    let point_mass = Solver::new(
        &point,
        &[Input::TangentialVelocity],
        Outputs::ALL,
        Precision::Fast,
    );
    assert!(!law_swept.in_lanes() && !exact.in_lanes() && !point_mass.in_lanes());
}

/// Random groups of four points of one body under one law, their
/// velocities nearby or of unrelated magnitudes: each group the lanes
/// answer (with one magnitude for the four, `arith::SharedLanes`) is
/// four single solves, bit for bit, and the lanes answer most groups of
/// nearby points.
#[test]
fn random_groups_answered_in_lanes_are_single_solves() {
    let mut rng = crate::rng::Rng::new(33);
    let laws = crate::impact::testing::one_law_of_each_kind();
    let swept = [
        Input::NormalVelocity,
        Input::TangentialVelocity,
        Input::AngularVelocity,
    ];
    let (mut nearby, mut answered) = ([0; 2], [0; 2]);
    for round in 0..3000 {
        let mass = rng.log_uniform(-1.0, 2.0);
        let offset = |rng: &mut crate::rng::Rng| {
            if rng.chance(0.25) {
                0.0
            } else {
                rng.range(-0.1, 0.1)
            }
        };
        let contact = Contact {
            tangential_offset: offset(&mut rng),
            normal_offset: offset(&mut rng),
        };
        let velocity = PlanarVelocity {
            normal: -rng.log_uniform(-2.0, 2.0),
            tangential: rng.sign() * rng.log_uniform(-3.0, 2.0),
            angular: rng.range(-50.0, 50.0),
        };
        let base = BarrierImpact::rigid(
            mass,
            mass * rng.log_uniform(-4.0, 0.0),
            contact,
            velocity,
            rng.pick(&laws),
        );
        let fixed = base.fix(&swept);
        let close = round % 2 == 0;
        let impacts: [BarrierImpact; LANES] = std::array::from_fn(|_| {
            let mut p = base;
            let mut vary = |v: f64| {
                if close {
                    v * (1.0 + rng.range(-1e-3, 1e-3))
                } else {
                    v * rng.log_uniform(-3.0, 3.0)
                }
            };
            p.velocity = PlanarVelocity {
                normal: vary(velocity.normal),
                tangential: vary(velocity.tangential),
                angular: vary(velocity.angular),
            };
            p
        });
        for outputs in [Outputs::ALL, Outputs::MINIMAL] {
            let mut out = [BarrierOutcome::default(); LANES];
            nearby[usize::from(close)] += 1;
            if BarrierImpact::evaluate_lanes(&impacts, &fixed, outputs, &mut out) {
                answered[usize::from(close)] += 1;
                for (impact, outcome) in impacts.iter().zip(&out) {
                    let single = solve(impact, outputs, Precision::Fast);
                    assert_eq!(
                        format!("{single:?}"),
                        format!("{:?}", Ok::<_, ()>(outcome)),
                        "{impact:?}"
                    );
                }
            }
        }
    }
    assert!(2 * answered[1] > nearby[1], "{answered:?} of {nearby:?}");
    assert!(answered[0] > 0, "{answered:?} of {nearby:?}");
}

/// Four points that take one path are answered together, each as its
/// single solve; four that do not (one sticks, three slide) are left to
/// be solved one by one.
#[test]
fn points_on_one_path_are_answered_in_lanes_as_single_solves() {
    let fixed = figure2(0.0).fix(&[Input::TangentialVelocity]);
    let cases: [([f64; LANES], bool); 4] = [
        ([2.0, 2.5, 3.0, 4.75], true),
        ([-2.0, -2.5, -3.0, -4.75], true),
        ([0.01, 0.02, 0.03, 0.04], true),
        ([0.0, 3.0, 4.0, 5.0], false),
    ];
    for (vts, together) in cases {
        let impacts = vts.map(figure2);
        let mut out = [BarrierOutcome::default(); LANES];
        let answered = BarrierImpact::evaluate_lanes(&impacts, &fixed, Outputs::ALL, &mut out);
        assert_eq!(answered, together, "{vts:?}");
        if answered {
            for (impact, outcome) in impacts.iter().zip(&out) {
                let single = solve(impact, Outputs::ALL, Precision::Fast);
                assert_eq!(format!("{single:?}"), format!("{:?}", Ok::<_, ()>(outcome)));
            }
        }
    }
}
