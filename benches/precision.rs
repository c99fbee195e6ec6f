//! Time per solve of each method on one typical non-central impact (Coulomb
//! friction, every output): the fast closed forms (and the same model with its
//! decisions unfiltered, taken on the f64 values), the nalgebra 3×3 LU solve,
//! the adaptive exact mode and the pure rational evaluation; then the general
//! planar contact (world axes) against a barrier and between two bodies;
//! the contact in space (fast, exact, and its last exact stage alone).
//!
//! `cargo bench --bench precision`. The errors, and times over whole typical
//! and stress sets, come from `cargo run --release --example accuracy_report`
//! (docs/accuracy.md).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use linear::{TangentialClosure, solve_momentum};
use restitution::impact::{Arithmetic, solve_in};
use restitution::{
    BarrierImpact, BodiesImpact, Contact, Lamina, Law, Outputs, PlanarContact, PlanarVelocity, Precision,
    RigidBody, SpatialContact, SpatialImpact, Twist, solve,
};

use restitution_testkit::linear;

fn impact() -> BarrierImpact {
    BarrierImpact::rigid(
        1.3,
        0.021,
        Contact {
            tangential_offset: 0.07,
            normal_offset: 0.11,
        },
        PlanarVelocity {
            normal: -1.7,
            tangential: 0.9,
            angular: 2.3,
        },
        Law::Friction {
            restitution: 0.8,
            friction: 0.3,
        },
    )
}

fn methods(c: &mut Criterion) {
    let p = impact();
    let mut group = c.benchmark_group("coulomb_all_outputs");
    group.bench_function("fast", |b| {
        b.iter(|| solve(black_box(&p), Outputs::ALL, Precision::Fast))
    });
    // Every decision on the f64 value as it is: the model without the
    // filter that makes `fast`'s decisions exact (what the filter costs).
    group.bench_function("unfiltered", |b| {
        b.iter(|| solve_in(black_box(&p), Outputs::ALL, Arithmetic::Unfiltered))
    });
    let scene = p.scene().unwrap();
    let answer = solve(&p, Outputs::ALL, Precision::Exact).unwrap();
    let closure = TangentialClosure::ImpulseRatio(answer.impulse_ratio);
    group.bench_function("nalgebra", |b| {
        b.iter(|| solve_momentum(black_box(&scene), black_box(0.8), closure))
    });
    group.bench_function("exact", |b| {
        b.iter(|| solve(black_box(&p), Outputs::ALL, Precision::Exact))
    });
    group.sample_size(20);
    group.bench_function("rational", |b| {
        b.iter(|| solve_in(black_box(&p), Outputs::ALL, Arithmetic::Rational))
    });
    group.finish();
}

/// The same body and law in world axes against a barrier (normal `(0, 2)`),
/// and two such bodies: the general contact's cost.
fn world(two: bool) -> BodiesImpact {
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
        contact: PlanarContact {
            point: [0.0, 0.0],
            normal: [0.0, 2.0],
        },
        law: Law::Friction {
            restitution: 0.8,
            friction: 0.3,
        },
    }
}

fn general(c: &mut Criterion) {
    let mut group = c.benchmark_group("planar_contact_all_outputs");
    for (name, impact) in [("barrier", world(false)), ("two_bodies", world(true))] {
        group.bench_function(format!("{name}_fast"), |b| {
            b.iter(|| solve(black_box(&impact), Outputs::ALL, Precision::Fast))
        });
        group.bench_function(format!("{name}_exact"), |b| {
            b.iter(|| solve(black_box(&impact), Outputs::ALL, Precision::Exact))
        });
    }
    group.finish();
}

/// A spinning ball against a barrier and two rigid bodies in space with
/// rotated tensors, under Coulomb friction (sliding), with and without twist.
fn space(two: bool, torsion: bool) -> SpatialImpact {
    let body = |x: f64, vz: f64, spin: [f64; 3]| RigidBody {
        mass: 0.057,
        inertia: [3.5e-5, 3.1e-5, 3.3e-5, 1e-6, -2e-6, 0.5e-6],
        position: [x, 0.002, 0.033],
        velocity: [20.0, 3.0, vz],
        angular_velocity: spin,
    };
    SpatialImpact {
        a: body(0.01, -10.0, [10.0, -300.0, 40.0]),
        b: two.then(|| RigidBody {
            position: [0.3, 0.1, -0.2],
            ..body(0.3, 3.0, [0.0; 3])
        }),
        contact: SpatialContact {
            point: [0.0; 3],
            normal: [0.1, 0.2, 2.0],
        },
        law: Law::Friction {
            restitution: 0.8,
            friction: 0.6,
        },
        torsion: torsion.then_some(Twist {
            restitution: 0.3,
            friction: 0.2,
            pitch_radius: 0.01,
        }),
    }
}

fn spatial(c: &mut Criterion) {
    let mut group = c.benchmark_group("spatial_contact_all_outputs");
    for (name, impact) in [
        ("barrier", space(false, false)),
        ("two_bodies", space(true, false)),
        ("two_bodies_twist", space(true, true)),
    ] {
        group.bench_function(format!("{name}_fast"), |b| {
            b.iter(|| solve(black_box(&impact), Outputs::ALL, Precision::Fast))
        });
        group.bench_function(format!("{name}_exact"), |b| {
            b.iter(|| solve(black_box(&impact), Outputs::ALL, Precision::Exact))
        });
    }
    group.finish();
    // The last exact stage alone (exact fractions with one square root, Ziv
    // rounding): what an `exact` answer costs when no earlier stage certifies it.
    let mut group = c.benchmark_group("spatial_contact_last_stage_alone");
    group.sample_size(10);
    for (name, impact) in [
        ("barrier", space(false, false)),
        ("two_bodies", space(true, false)),
        ("two_bodies_twist", space(true, true)),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| solve_in(black_box(&impact), Outputs::ALL, Arithmetic::Rational))
        });
    }
    group.finish();
}

criterion_group!(benches, methods, general, spatial);
criterion_main!(benches);
