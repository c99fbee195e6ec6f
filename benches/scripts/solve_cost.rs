//! The driver of `benches/scripts/solve-cost`: single solves of the precision
//! bench's scenes, each timed as the best of seven runs of `n` solves, in
//! `fast`, `exact` and plain f64 without bounds (`unfiltered`, the peer).
//! Prints one line per arithmetic: ns per solve for each scene, then one
//! line of sweeps in `fast` (`restitution::sweep` over one input, one
//! core): ns per point with every output and with one. Built with
//! `--features many` and run with `--batch` (benches/scripts/batch-cost), it
//! times instead each scene solved `n` times by a caller's loop over `solve`
//! and by one `solve_many` over a slice, in `fast` and `exact`.

use std::hint::black_box;
use std::time::Instant;

use restitution::impact::{Arithmetic, solve_in};
use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{
    BodiesImpact, Case, Contact, Input, Lamina, Law, Output, Outputs, PlanarContact, BarrierImpact, PlanarVelocity,
    Precision, RigidBody, SpatialContact, SpatialImpact, Twist,
};

fn oblique() -> BarrierImpact {
    BarrierImpact::rigid(
        1.3,
        0.021,
        Contact { tangential_offset: 0.07, normal_offset: 0.11 },
        PlanarVelocity { normal: -1.7, tangential: 0.9, angular: 2.3 },
        Law::Friction { restitution: 0.8, friction: 0.3 },
    )
}

fn laminae(two: bool) -> BodiesImpact {
    let lamina = |x: f64, vy: f64| Lamina {
        mass: 1.3,
        inertia: 0.021,
        position: [x, 0.11],
        velocity: [0.9, vy],
        angular_velocity: 2.3,
    };
    BodiesImpact {
        a: lamina(0.07, -1.7),
        b: two.then(|| lamina(-0.05, 0.4)),
        contact: PlanarContact { point: [0.0, 0.0], normal: [0.0, 2.0] },
        law: Law::Friction { restitution: 0.8, friction: 0.3 },
    }
}

fn space(two: bool, twist: bool) -> SpatialImpact {
    let body = |x: f64, vz: f64, spin: [f64; 3]| RigidBody {
        mass: 0.057,
        inertia: [3.5e-5, 3.1e-5, 3.3e-5, 1e-6, -2e-6, 0.5e-6],
        position: [x, 0.002, 0.033],
        velocity: [20.0, 3.0, vz],
        angular_velocity: spin,
    };
    SpatialImpact {
        a: body(0.01, -10.0, [10.0, -300.0, 40.0]),
        b: two.then(|| RigidBody { position: [0.3, 0.1, -0.2], ..body(0.3, 3.0, [0.0; 3]) }),
        contact: SpatialContact { point: [0.0; 3], normal: [0.1, 0.2, 2.0] },
        law: Law::Friction { restitution: 0.8, friction: 0.6 },
        torsion: twist.then_some(Twist { restitution: 0.3, friction: 0.2, pitch_radius: 0.01 }),
    }
}

/// A tennis ball with topspin on a level court (a sphere on a plane along an axis).
fn tennis() -> SpatialImpact {
    let i = 2.0 / 3.0 * 0.057 * 0.033 * 0.033;
    SpatialImpact {
        a: RigidBody {
            mass: 0.057,
            inertia: [i, i, i, 0.0, 0.0, 0.0],
            position: [0.0, 0.0, 0.033],
            velocity: [20.0, 0.0, -10.0],
            angular_velocity: [0.0, 300.0, 0.0],
        },
        b: None,
        contact: SpatialContact { point: [0.0; 3], normal: [0.0, 0.0, 1.0] },
        law: Law::Friction { restitution: 0.75, friction: 0.6 },
        torsion: None,
    }
}

fn best_of_seven(n: u32, mut solve: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..7 {
        let start = Instant::now();
        for _ in 0..n {
            solve();
        }
        best = best.min(start.elapsed().as_secs_f64() / f64::from(n));
    }
    best * 1e9
}

/// ns per impact of `n` copies of `impact` answered by a loop over `solve`
/// and by `solve_many`, each collecting the answers into one vector.
#[cfg(feature = "many")]
fn loop_and_many<C: restitution::Case>(impact: &C, n: u32, precision: restitution::Precision) -> [f64; 2] {
    use restitution::{solve, solve_many};
    let impacts = vec![*impact; n as usize];
    let looped = best_of_seven(1, || {
        let answers: Vec<_> = black_box(&impacts).iter().map(|i| solve(i, Outputs::ALL, precision)).collect();
        drop(black_box(answers));
    });
    let many = best_of_seven(1, || drop(black_box(solve_many(black_box(&impacts), Outputs::ALL, precision))));
    [looped / f64::from(n), many / f64::from(n)]
}

#[cfg(feature = "many")]
fn batch(n: u32) {
    use restitution::Precision;
    let (p, b2, s2, t) = (oblique(), laminae(true), space(true, false), tennis());
    for (name, precision) in [("fast", Precision::Fast), ("exact", Precision::Exact)] {
        let m = if precision == Precision::Exact { n / 10 } else { n };
        let row = [
            ("oblique", loop_and_many(&p, m, precision)),
            ("two_laminae", loop_and_many(&b2, m, precision)),
            ("space_two", loop_and_many(&s2, m / 4, precision)),
            ("tennis", loop_and_many(&t, m / 4, precision)),
        ];
        print!("{name:>6}");
        for (scene, [looped, many]) in row {
            print!("  {scene} loop {looped:.0} many {many:.0}");
        }
        println!();
    }
}

/// ns per point of a `fast` sweep of `base` over `input` in `[start, stop]`
/// (`points` points, one core), reading `outputs` (all of the case's when
/// empty).
fn sweep_ns<C: Case>(base: &C, input: Input, range: [f64; 2], points: u64, outputs: &[Output]) -> f64 {
    let outputs = if outputs.is_empty() { C::OUTPUTS.to_vec() } else { outputs.to_vec() };
    let case = CaseSweep::new(base, &[input], outputs, Precision::Fast).expect("an input of the case");
    let values = AxisValues::Linspace { start: range[0], stop: range[1], count: points };
    let sweep = Sweep::new(case, *base, vec![Axis { param: input, values }], Combine::Product, u64::MAX)
        .expect("a valid sweep");
    best_of_seven(1, || {
        let mut sum = 0.0;
        sweep.for_each_in(0..points, |row| {
            if let Ok([Cell::Number(x), ..]) = row.outcome {
                sum += x;
            }
        });
        let _ = black_box(sum);
    }) / points as f64
}

fn sweeps() {
    let (p, b2, s2) = (oblique(), laminae(true), space(true, false));
    let row = [
        ("oblique_all", sweep_ns(&p, Input::TangentialVelocity, [-5.0, 5.0], 200_000, &[])),
        (
            "oblique_one",
            sweep_ns(&p, Input::TangentialVelocity, [-5.0, 5.0], 200_000, &[Output::FinalTangentialContactVelocity]),
        ),
        ("two_laminae_all", sweep_ns(&b2, Input::VelocityAX, [-5.0, 5.0], 200_000, &[])),
        ("space_two_all", sweep_ns(&s2, Input::VelocityAX, [-20.0, 20.0], 50_000, &[])),
    ];
    print!("{:>10}", "sweep");
    for (scene, ns) in row {
        print!("  {scene} {ns:.0}");
    }
    println!();
}

fn main() {
    let n: u32 = std::env::args().nth(1).map_or(100_000, |s| s.parse().expect("a count"));
    #[cfg(feature = "many")]
    if std::env::args().any(|a| a == "--batch") {
        return batch(n);
    }
    let (p, b1, b2) = (oblique(), laminae(false), laminae(true));
    let (s1, s2, s3, t) = (space(false, false), space(true, false), space(true, true), tennis());
    for (name, a) in [
        ("fast", Arithmetic::Fast),
        ("exact", Arithmetic::Exact),
        ("unfiltered", Arithmetic::Unfiltered),
    ] {
        let m = if a == Arithmetic::Exact { n / 10 } else { n };
        let row = [
            ("oblique", best_of_seven(m, || drop(black_box(solve_in(black_box(&p), Outputs::ALL, a))))),
            ("laminae_barrier", best_of_seven(m, || drop(black_box(solve_in(black_box(&b1), Outputs::ALL, a))))),
            ("two_laminae", best_of_seven(m, || drop(black_box(solve_in(black_box(&b2), Outputs::ALL, a))))),
            ("space_barrier", best_of_seven(m / 4, || drop(black_box(solve_in(black_box(&s1), Outputs::ALL, a))))),
            ("space_two", best_of_seven(m / 4, || drop(black_box(solve_in(black_box(&s2), Outputs::ALL, a))))),
            ("space_twist", best_of_seven(m / 4, || drop(black_box(solve_in(black_box(&s3), Outputs::ALL, a))))),
            ("tennis", best_of_seven(m / 4, || drop(black_box(solve_in(black_box(&t), Outputs::ALL, a))))),
        ];
        print!("{name:>10}");
        for (scene, ns) in row {
            print!("  {scene} {ns:.0}");
        }
        println!();
    }
    sweeps();
}
