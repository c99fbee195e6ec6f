//! A sweep's rows are the single solves of its points, bit for bit: over
//! random Coulomb scenes swept through both regimes, zero slip, central
//! contacts, G on the normal, and values that are outside the fast range or
//! invalid. (The adversarial sets at every switch are swept too, in
//! `tests/decisions.rs`.)

use crate::common::Rng;
use crate::common::sweep_rows::sweep_is_single_solves;
use restitution::{Contact, Input, Law, PlanarImpact, PlanarVelocity};

fn lamina(rng: &mut Rng, n: usize) -> PlanarImpact {
    let dyadic = n % 2 == 0;
    let mut draw = |lo: f64, hi: f64| {
        let x = rng.range(lo, hi);
        if dyadic { (x * 8.0).round() / 8.0 } else { x }
    };
    let mass = draw(0.125, 4.0).max(0.125);
    PlanarImpact::rigid(
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
