//! A sweep's rows are the single solves of its points, bit for bit, in
//! `fast` and in `exact`: over random Coulomb scenes swept through both
//! regimes, zero slip, central contacts, G on the normal, and values that
//! are outside the fast range or invalid. (The adversarial sets at every
//! switch of every case are swept too, in `tests/decisions.rs`.) So are the
//! answers of `solve_many`, on the adversarial scenes of every case.

use crate::common::Rng;
use crate::common::sweep_rows::sweep_is_single_solves;
use crate::promise::{lamina_on_barrier, slender_in_space, slender_pair, torsional_edges, two_phase_law};
use restitution::{
    BarrierImpact, BodiesImpact, Case, Contact, Input, Law, Outputs, PlanarVelocity, Precision, solve,
    solve_many,
};

fn lamina(rng: &mut Rng, n: usize) -> BarrierImpact {
    let dyadic = n % 2 == 0;
    let mut draw = |lo: f64, hi: f64| {
        let x = rng.range(lo, hi);
        if dyadic { (x * 8.0).round() / 8.0 } else { x }
    };
    let mass = draw(0.125, 4.0).max(0.125);
    BarrierImpact::rigid(
        mass,
        mass * draw(0.01, 2.0).max(0.125),
        Contact {
            tangential_offset: if n % 5 == 1 { 0.0 } else { draw(-1.5, 1.5) },
            normal_offset: if n % 7 == 3 { 0.0 } else { draw(-1.5, 1.5) },
        },
        PlanarVelocity {
            normal: -draw(0.125, 5.0),
            tangential: draw(-5.0, 5.0),
            angular: draw(-3.0, 3.0),
        },
        Law::Friction {
            restitution: draw(0.0, 1.0),
            friction: draw(0.0, 1.5),
        },
    )
}

/// A grid of `count` values over `[lo, hi]` with, now and then, a value the
/// fast path refuses to take (out of its range, or invalid).
fn values(rng: &mut Rng, lo: f64, hi: f64, count: usize, odd: &[f64]) -> Vec<f64> {
    (0..count)
        .map(|k| {
            if rng.unit() < 0.03 {
                odd[k % odd.len()]
            } else {
                lo + (hi - lo) * k as f64 / (count - 1) as f64
            }
        })
        .collect()
}

#[test]
fn coulomb_sweeps_are_single_solves_bit_for_bit() {
    let mut rng = Rng::new(0x5eeb);
    let (mut rows, mut answered) = (0, 0);
    for n in 0..120 {
        let base = lamina(&mut rng, n);
        let far = [1e-250, 3e250, -1e300, 0.0];
        let sweeps = [
            (Input::TangentialVelocity, values(&mut rng, -6.0, 6.0, 97, &far)),
            (Input::AngularVelocity, values(&mut rng, -40.0, 40.0, 97, &far)),
            (
                Input::Friction,
                values(&mut rng, 0.0, 2.0, 97, &[-0.5, 1e300, 1e-240]),
            ),
            (
                Input::Restitution,
                values(&mut rng, 0.0, 1.0, 41, &[1.5, -0.0, 1e-300]),
            ),
            (
                Input::NormalVelocity,
                values(&mut rng, -3.0, 1.0, 41, &[0.0, -1e-280]),
            ),
            (Input::Mass, values(&mut rng, 0.1, 5.0, 41, &[0.0, -1.0, 1e250])),
            (
                Input::TangentialOffset,
                values(&mut rng, -1.0, 1.0, 41, &[0.0, -0.0, 1e-210]),
            ),
            (
                Input::NormalOffset,
                values(&mut rng, -1.0, 1.0, 41, &[0.0, 1e210]),
            ),
        ];
        for (input, values) in sweeps {
            rows += values.len();
            answered += sweep_is_single_solves(&base, input, &values);
        }
    }
    // The sweeps cross both regimes; most points are answered, the rest refused alike.
    assert!(answered * 2 > rows, "{answered} of {rows}");
}

/// `solve_many` over `impacts` answers each as `solve` does, bit for bit
/// (`Debug` prints every f64 so that it reads back to its bits), in both
/// precisions; returns how many it answered.
fn many_are_single_solves<C: Case>(impacts: &[C]) -> usize {
    let mut answered = 0;
    for precision in [Precision::Fast, Precision::Exact] {
        for outputs in [Outputs::ALL, Outputs::MINIMAL] {
            let many = solve_many(impacts, outputs, precision);
            assert_eq!(many.len(), impacts.len());
            for (impact, batch) in impacts.iter().zip(&many) {
                let single = solve(impact, outputs, precision);
                assert_eq!(
                    format!("{batch:?}"),
                    format!("{single:?}"),
                    "{impact:?} in {precision:?}"
                );
                answered += usize::from(batch.is_ok());
            }
        }
    }
    answered
}

#[test]
fn solve_many_answers_each_impact_as_solve_does() {
    let mut rng = Rng::new(0xba7c);
    let draw = |rng: &mut Rng, make: &dyn Fn(&mut Rng) -> BarrierImpact| {
        (0..300).map(|_| make(rng)).collect::<Vec<_>>()
    };
    let laminae = draw(&mut rng, &lamina_on_barrier);
    let two_phase: Vec<BarrierImpact> = draw(&mut rng, &|rng| BarrierImpact {
        law: two_phase_law(rng),
        ..lamina_on_barrier(rng)
    });
    let pairs: Vec<BodiesImpact> = (0..300).map(|_| slender_pair(&mut rng)).collect();
    let space: Vec<_> = (0..150).map(|_| slender_in_space(&mut rng)).collect();
    let torsional: Vec<_> = (0..300).map(|_| torsional_edges(&mut rng)).collect();
    let answered = [
        many_are_single_solves(&laminae),
        many_are_single_solves(&two_phase),
        many_are_single_solves(&pairs),
        many_are_single_solves(&space),
        many_are_single_solves(&torsional),
    ];
    assert!(answered.iter().all(|&n| n > 100), "answered {answered:?}");
    assert!(solve_many::<BarrierImpact>(&[], Outputs::ALL, Precision::Fast).is_empty());
}

/// The barrier case's earlier names (`PlanarImpact`, `PlanarBody`,
/// `PlanarOutcome`, `PlanarScene`) still name its types, at the crate root
/// and in their modules, for callers written before the rename.
#[test]
#[allow(deprecated)]
fn the_barrier_case_keeps_its_earlier_names_for_callers() {
    use restitution::impact::PlanarImpact as ModulePath;
    use restitution::{PlanarBody, PlanarImpact, PlanarOutcome, PlanarScene};
    let old = PlanarImpact {
        body: PlanarBody::Rigid {
            mass: 1.0,
            inertia: 0.00125,
            contact: Contact::central(0.05),
        },
        velocity: PlanarVelocity {
            normal: -1.0,
            tangential: 0.4,
            angular: 0.0,
        },
        law: Law::Friction {
            restitution: 0.93,
            friction: 0.123,
        },
    };
    let new: BarrierImpact = old;
    let via_module: ModulePath = new;
    let scene: PlanarScene = via_module.scene().expect("a scene");
    assert_eq!(BarrierImpact::in_scene(&scene, old.law), old);
    let outcome: PlanarOutcome = solve(&old, Outputs::ALL, Precision::Exact).expect("an answer");
    assert_eq!(outcome, solve(&new, Outputs::ALL, Precision::Exact).unwrap());
}
