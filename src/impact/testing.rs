//! What the cases' unit tests share.

use super::{Case, Outputs, Precision, Solver, solve};
use crate::error::Input;

/// For the cases' unit tests: a sweep of `base` over `axes` (each input with
/// its values, every combination) whose geometry is formed once (`formed`
/// tells it from the case's [`Case::Fixed`]) answers every point as a
/// geometry formed per point (with `geometry_input` swept too, which forms
/// it per point) and as a single solve does, in both precisions: the same
/// bits, regimes and refusals. Returns the number of answered points.
pub(crate) fn formed_once_answers_as_per_point<C: Case>(
    base: &C,
    axes: &[(Input, &[f64])],
    geometry_input: Input,
    formed: impl Fn(&C::Fixed) -> bool,
) -> usize {
    let swept: Vec<Input> = axes.iter().map(|(input, _)| *input).collect();
    // A single solve forms its own, in the field it runs in.
    assert!(!formed(&base.fix(&[])));
    let mut points = vec![*base];
    for (input, values) in axes {
        points = points
            .iter()
            .flat_map(|p| {
                values.iter().map(move |&x| {
                    let mut q = *p;
                    *q.input_mut(*input).expect("an input of the case") = x;
                    q
                })
            })
            .collect();
    }
    let mut answered = 0;
    for precision in [Precision::Fast, Precision::Exact] {
        let once = Solver::new(base, &swept, Outputs::ALL, precision);
        assert!(formed(&once.fixed));
        let per_point = Solver::new(
            base,
            &[&swept[..], &[geometry_input]].concat(),
            Outputs::ALL,
            precision,
        );
        assert!(!formed(&per_point.fixed));
        for p in &points {
            let got = format!("{:?}", once.solve(p));
            assert_eq!(got, format!("{:?}", per_point.solve(p)), "{p:?}");
            let single = solve(p, Outputs::ALL, precision);
            assert_eq!(got, format!("{single:?}"), "{p:?}");
            answered += usize::from(single.is_ok());
        }
    }
    answered
}

/// For the cases' unit tests: `points` through `solver`'s block entry
/// ([`Solver::solve_block_into`], in lanes where the case runs them) are
/// answered or refused each as its single solve in `fast` (for the solver's
/// outputs, bit for bit). Returns the refused points' positions.
pub(crate) fn block_answers_as_single_solves<C: Case>(solver: &Solver<C>, points: &[C]) -> Vec<usize> {
    let mut outs = vec![C::Outcome::default(); points.len()];
    let mut refused = Vec::new();
    solver.solve_block_into(points, &mut outs, |k, e| refused.push((k, e)));
    for (k, (point, outcome)) in points.iter().zip(&outs).enumerate() {
        let single = solve(point, solver.outputs(), Precision::Fast);
        match refused.iter().find(|(i, _)| *i == k) {
            Some((_, e)) => assert_eq!(
                format!("{:?}", Err::<(), _>(e)),
                format!("{:?}", single.map(|_| ())),
                "{k}"
            ),
            None => assert_eq!(
                format!("{single:?}"),
                format!("{:?}", Ok::<_, ()>(outcome)),
                "{k}: {point:?}"
            ),
        }
    }
    refused.into_iter().map(|(k, _)| k).collect()
}

/// One law of each kind, for the cases' unit tests.
pub(crate) fn one_law_of_each_kind() -> [crate::input::Law; 6] {
    use crate::input::Law;
    [
        Law::Frictionless { restitution: 0.6 },
        Law::ImpulseRatio {
            restitution: 0.5,
            impulse_ratio: 0.2,
        },
        Law::Friction {
            restitution: 0.75,
            friction: 0.6,
        },
        Law::TangentialRestitution {
            restitution: 0.5,
            friction: 0.3,
            tangential_restitution: 0.2,
        },
        Law::KineticRestitution {
            value: 0.5,
            approach_impulse_ratio: 0.2,
            rebound_impulse_ratio: 0.1,
        },
        Law::KineticFriction {
            value: 0.5,
            approach_friction: 0.3,
            rebound_impulse_ratio: 0.0,
        },
    ]
}
