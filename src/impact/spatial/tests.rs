//! The spatial case's unit tests: its declaration, its sweeps' prepared
//! geometry and tensor checks.

use super::*;
use crate::impact::{Precision, Solver};
use crate::input::SpatialContact;

fn body(seed: f64) -> RigidBody {
    let x = |i: f64| seed + i / 16.0;
    RigidBody {
        mass: x(1.0),
        inertia: [x(2.0), x(3.0), x(4.0), x(5.0), x(6.0), x(7.0)],
        position: [x(8.0), x(9.0), x(10.0)],
        velocity: [x(11.0), x(12.0), x(13.0)],
        angular_velocity: [x(14.0), x(15.0), x(16.0)],
    }
}

fn impact(b: Option<RigidBody>, torsion: Option<Twist>) -> SpatialImpact {
    SpatialImpact {
        a: body(1.0),
        b,
        contact: SpatialContact {
            point: [0.1, 0.2, 0.3],
            normal: [0.4, 0.5, 0.6],
        },
        law: Law::TangentialRestitution {
            restitution: 0.5,
            friction: 0.25,
            tangential_restitution: 0.125,
        },
        torsion,
    }
}

/// A sweep's geometry formed once (in `fast`'s first field and the
/// compensated stage's) answers every point as the geometry formed per
/// point does, in both precisions: the same bits, regimes and refusals, in
/// every law, with and without body B and a twist law; an axis on a
/// geometry input forms it per point.
#[test]
fn a_geometry_formed_once_answers_as_one_formed_per_point() {
    let laws = crate::impact::testing::one_law_of_each_kind();
    let twist = Twist {
        restitution: 0.1,
        friction: 0.2,
        pitch_radius: 0.004,
    };
    let axes: [(Input, &[f64]); 3] = [
        (Input::VelocityAX, &[-3.0, 0.0, 0.5, 20.0]),
        (Input::VelocityAZ, &[-10.0, -1e-3, 0.0, 1.0]),
        (Input::AngularVelocityAY, &[-900.0, 0.0, 300.0]),
    ];
    let mut answered = 0;
    for base in scenes() {
        for law in laws {
            for torsion in [None, Some(twist)] {
                let base = SpatialImpact { law, torsion, ..base };
                answered += crate::impact::testing::formed_once_answers_as_per_point(
                    &base,
                    &axes,
                    Input::PositionAZ,
                    |fixed: &Fixed| fixed.geometry.is_some(),
                );
            }
        }
    }
    // Half the points approach (2,304 in all, both precisions), and most
    // of those are answered (the two-phase laws refuse a twist law); the
    // rest are refused alike.
    assert!(answered >= 800, "{answered}");
}

/// Blocks of sweeps over the bodies' velocities through the sweep's door
/// ([`Solver::solve_block_into`]), in both scenes, under a law of each
/// kind, with and without a twist law, with every output and the fewest:
/// each point's answer or refusal is its single solve's, whether answered
/// in lanes (most groups of four) or one by one (lanes that disagree, a
/// refusal, a spin beyond the fast range, a tail).
#[test]
fn a_block_answers_each_point_as_its_single_solve() {
    use crate::impact::testing::block_answers_as_single_solves;
    let twist = Twist {
        restitution: 0.1,
        friction: 0.2,
        pitch_radius: 0.004,
    };
    let swept = [Input::VelocityAX, Input::VelocityAZ, Input::AngularVelocityAY];
    let (mut together, mut groups) = (0, 0);
    for base in scenes() {
        for law in crate::impact::testing::one_law_of_each_kind() {
            for torsion in [None, Some(twist)] {
                let base = SpatialImpact { law, torsion, ..base };
                let points: Vec<SpatialImpact> = (0..27)
                    .map(|k| {
                        let mut p = base;
                        let k = k as f64;
                        // Forward slip that falls to none and turns back.
                        p.a.velocity[0] = 20.0 - 1.5 * k;
                        p.a.angular_velocity[1] = 300.0 - 12.5 * k;
                        match k as usize {
                            5 => p.a.velocity[2] = 30.0,
                            11 => p.a.velocity[0] = f64::NAN,
                            17 => p.a.angular_velocity[1] = 1e300,
                            20 => p.a.velocity[0] = 0.0,
                            _ => {}
                        }
                        p
                    })
                    .collect();
                for outputs in [Outputs::ALL, Outputs::MINIMAL] {
                    let solver = Solver::new(&base, &swept, outputs, Precision::Fast);
                    assert!(solver.in_lanes());
                    let refused = block_answers_as_single_solves(&solver, &points);
                    let two_phases =
                        matches!(law, Law::KineticRestitution { .. } | Law::KineticFriction { .. });
                    if two_phases && torsion.is_some() {
                        // A two-phase law refuses a twist law, at every point.
                        assert_eq!(refused.len(), points.len());
                        continue;
                    }
                    // Point 5 separates; point 11's velocity is not a number.
                    assert!(refused.starts_with(&[5, 11]), "{refused:?} under {law:?}");
                    for group in points.chunks_exact(LANES) {
                        let group: &[SpatialImpact; LANES] = group.try_into().expect("four");
                        let mut out = [SpatialOutcome::default(); LANES];
                        if SpatialImpact::evaluate_lanes(group, &solver.fixed, outputs, &mut out) {
                            together += 1;
                        }
                        groups += 1;
                    }
                }
            }
        }
    }
    // The groups with points 5, 11 and 17 (three of six) never run
    // together; of the others, four in five or more do (108 of 120).
    assert!(
        together * 5 >= groups * 2,
        "{together} of {groups} groups together"
    );
}

/// Lanes answer a sweep over the bodies' velocities alone, its geometry
/// formed once, in `fast` alone.
#[test]
fn which_solvers_run_lanes() {
    let [ball, blocks] = scenes();
    let solver = |base: &SpatialImpact, swept: &[Input], precision| {
        Solver::new(base, swept, Outputs::ALL, precision).in_lanes()
    };
    assert!(solver(
        &ball,
        &[Input::VelocityAX, Input::AngularVelocityAY],
        Precision::Fast
    ));
    assert!(solver(
        &blocks,
        &[Input::VelocityBZ, Input::AngularVelocityAX],
        Precision::Fast
    ));
    assert!(!solver(&ball, &[Input::VelocityAX], Precision::Exact));
    assert!(!solver(
        &ball,
        &[Input::VelocityAX, Input::Friction],
        Precision::Fast
    ));
    assert!(!solver(
        &ball,
        &[Input::VelocityAX, Input::MassA],
        Precision::Fast
    ));
    assert!(!solver(
        &blocks,
        &[Input::VelocityAX, Input::PitchRadius],
        Precision::Fast
    ));
    assert!(!solver(&ball, &[], Precision::Fast));
}

/// A tennis ball on a level court, and a block on a plate on a tilted
/// normal, under a law the tests replace.
fn scenes() -> [SpatialImpact; 2] {
    let sphere = 2.0 / 3.0 * 0.057 * 0.033 * 0.033;
    let ball = RigidBody {
        mass: 0.057,
        inertia: [sphere, sphere, sphere, 0.0, 0.0, 0.0],
        position: [0.0, 0.0, 0.033],
        velocity: [20.0, 0.0, -10.0],
        angular_velocity: [0.0, 300.0, 0.0],
    };
    let block = RigidBody {
        mass: 2.5,
        inertia: [0.012, 0.018, 0.009, 0.001, -0.002, 0.0005],
        position: [0.0, 0.0, 0.12],
        velocity: [0.3, 0.1, -0.8],
        angular_velocity: [1.0, -2.0, 0.5],
    };
    let plate = RigidBody {
        mass: 4.0,
        inertia: [0.05, 0.04, 0.06, 0.0, 0.0, 0.0],
        position: [0.05, -0.02, -0.1],
        velocity: [0.0, 0.0, 0.1],
        angular_velocity: [0.0, 0.0, 0.0],
    };
    let law = Law::Friction {
        restitution: 0.75,
        friction: 0.6,
    };
    let scene = |a, b, point, normal| SpatialImpact {
        a,
        b,
        contact: SpatialContact { point, normal },
        law,
        torsion: None,
    };
    [
        scene(ball, None, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        scene(block, Some(plate), [0.01, 0.0, 0.0], [0.1, 0.0, 1.0]),
    ]
}

/// A tensor checked once for a sweep gives its refusal at every point,
/// after the point's own inputs, as a single solve does.
#[test]
fn a_tensor_checked_once_refuses_as_a_single_solve_does() {
    let mut base = impact(None, None);
    base.a.inertia = [1.0, 1.0, 3.0, 0.0, 0.0, 0.0];
    base.a.velocity = [0.0, 0.0, -1.0];
    let solver = Solver::new(&base, &[Input::VelocityAX], Outputs::ALL, Precision::Fast);
    assert!(matches!(solver.fixed.tensors[0], Some(Err(_))));
    assert!(solver.fixed.geometry.is_none());
    for vx in [0.0, f64::NAN] {
        let mut p = base;
        p.a.velocity[0] = vx;
        let single = crate::impact::solve(&p, Outputs::ALL, Precision::Fast);
        assert!(single.is_err());
        assert_eq!(format!("{:?}", solver.solve(&p)), format!("{single:?}"));
    }
}

/// A body's values in request order are the slots the declaration names.
#[test]
fn body_values_are_the_declared_slots_in_order() {
    let both = impact(Some(body(3.0)), None);
    for (k, b) in [both.a, both.b.unwrap()].iter().enumerate() {
        for (i, &input) in BODY_INPUTS[k].iter().enumerate() {
            assert_eq!(both.input(input), Some(b.values()[i]), "{input:?}");
        }
    }
}

/// The inputs read: body B's only with a body B, the twist law's only
/// with one, each law's own coefficients; each input once.
#[test]
fn reads_follow_the_bodies_and_laws_present() {
    let twist = Twist {
        restitution: 0.5,
        friction: 0.25,
        pitch_radius: 0.01,
    };
    let full = impact(Some(body(3.0)), Some(twist));
    // Every input but the impulse ratio and the kinetic law's, which
    // tangential restitution does not read.
    let kinetic = [
        Input::KineticRestitution,
        Input::ApproachImpulseRatio,
        Input::ApproachFriction,
        Input::ReboundImpulseRatio,
    ];
    let all_but_ratio: Vec<Input> = SpatialImpact::INPUTS
        .iter()
        .copied()
        .filter(|&i| i != Input::ImpulseRatio && !kinetic.contains(&i))
        .collect();
    assert_eq!(full.reads(), all_but_ratio);
    let barrier = impact(None, None).reads();
    assert_eq!(barrier.len(), all_but_ratio.len() - 16 - 3);
    assert!(!barrier.contains(&Input::MassB) && !barrier.contains(&Input::PitchRadius));
    assert_eq!(full.input(Input::KineticRestitution), None);
    let mut two_phase = impact(None, None);
    two_phase.law = Law::KineticRestitution {
        value: 0.5,
        approach_impulse_ratio: 0.25,
        rebound_impulse_ratio: 0.125,
    };
    let reads = two_phase.reads();
    assert_eq!(reads[reads.len() - 3..], [kinetic[0], kinetic[1], kinetic[3]]);
    assert_eq!(two_phase.input(Input::ReboundImpulseRatio), Some(0.125));
    for (i, input) in SpatialImpact::INPUTS.iter().enumerate() {
        assert!(!SpatialImpact::INPUTS[i + 1..].contains(input), "{input:?} twice");
    }
}
