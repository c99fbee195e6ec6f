//! Time per solve of each method on one typical non-central impact (Coulomb
//! friction, every output): the fast closed forms, the nalgebra 3×3 LU solve,
//! the adaptive exact mode and the pure rational evaluation.
//!
//! `cargo bench --bench precision`. The errors, and times over whole typical
//! and stress sets, come from `cargo run --release --example accuracy_report`
//! (docs/accuracy.md).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use restitution::exact;
use restitution::linear::{TangentialClosure, solve_momentum};
use restitution::sweep::planar::{PlanarLaw, PlanarPoint, solve_point};
use restitution::{Body, Contact, Outputs, PlanarScene, PlanarVelocity, Precision};

fn point() -> PlanarPoint {
    PlanarPoint {
        mass: 1.3,
        inertia: 0.021,
        contact: Contact {
            tangential_offset: 0.07,
            normal_offset: 0.11,
        },
        velocity: PlanarVelocity {
            normal: -1.7,
            tangential: 0.9,
            angular: 2.3,
        },
        restitution: 0.8,
        friction: 0.3,
        ..PlanarPoint::default()
    }
}

fn methods(c: &mut Criterion) {
    let p = point();
    let law = PlanarLaw::Friction;
    let mut group = c.benchmark_group("coulomb_all_outputs");
    group.bench_function("fast", |b| {
        b.iter(|| solve_point(law, black_box(&p), Outputs::ALL, Precision::Fast))
    });
    let scene = PlanarScene::new(Body::new(p.mass, p.inertia).unwrap(), p.contact, p.velocity).unwrap();
    let answer = solve_point(law, &p, Outputs::ALL, Precision::Exact).unwrap();
    let closure = TangentialClosure::ImpulseRatio(answer.impulse_ratio);
    group.bench_function("nalgebra", |b| {
        b.iter(|| solve_momentum(black_box(&scene), black_box(p.restitution), closure))
    });
    group.bench_function("exact", |b| {
        b.iter(|| exact::solve_planar(law, black_box(&p), Outputs::ALL))
    });
    group.sample_size(20);
    group.bench_function("rational", |b| {
        b.iter(|| exact::solve_planar_rational(law, black_box(&p), Outputs::ALL))
    });
    group.finish();
}

criterion_group!(benches, methods);
criterion_main!(benches);
