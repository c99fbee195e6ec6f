//! Sweep throughput in process: points per second on one core for the oblique
//! (Coulomb friction) case with every output, with one output, with one output
//! and the scene prepared once, beside a bare loop over the closed form with no
//! validation (this machine's limit for the model); the same sweeps with the
//! decisions taken on the f64 values as they are (`Arithmetic::Unfiltered`:
//! what the error bound of `fast` costs); and on every core.
//!
//! The torsional case (spin swept, every output) beside a bare loop over
//! `restitution::solve`: the cost of the sweep's per-point checks.
//!
//! `cargo bench --bench sweep` (figures in docs/performance.md, their history in docs/performance-log.md);
//! `RESTITUTION_KERNELS=portable cargo bench --bench sweep` runs the portable
//! copy of the solver instead of the x86-64-v3 one (`restitution::kernels`).

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use restitution::impact::Arithmetic;
use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{
    BarrierBody, BarrierImpact, Case, Contact, Input, Law, Output, Outputs, PlanarVelocity, Precision,
    TorsionalImpact, solve,
};

const POINTS: u64 = 200_000;

/// Every planar output.
const ALL: &[Output] = BarrierImpact::OUTPUTS;

/// A non-central lamina (d_c ≠ 0) so that no special path applies.
fn base() -> BarrierImpact {
    BarrierImpact::rigid(
        1.0,
        0.00125,
        Contact {
            tangential_offset: 0.01,
            normal_offset: 0.05,
        },
        PlanarVelocity {
            normal: -1.0,
            tangential: 0.0,
            angular: 2.0,
        },
        Law::Friction {
            restitution: 0.93,
            friction: 0.123,
        },
    )
}

fn sweep(param: Input, columns: &[Output], points: u64) -> Sweep<CaseSweep<BarrierImpact>> {
    sweep_in(param, columns, points, Arithmetic::Fast)
}

/// The same in one arithmetic.
fn sweep_in(
    param: Input,
    columns: &[Output],
    points: u64,
    arithmetic: Arithmetic,
) -> Sweep<CaseSweep<BarrierImpact>> {
    let (start, stop) = match param {
        Input::Friction => (0.0, 1.0),
        _ => (-5.0, 5.0),
    };
    let case = CaseSweep::in_arithmetic(&base(), &[param], columns.to_vec(), arithmetic)
        .expect("an input of the law");
    let axes = vec![Axis {
        param,
        values: AxisValues::Linspace {
            start,
            stop,
            count: points,
        },
    }];
    Sweep::new(case, base(), axes, Combine::Product, u64::MAX).expect("a valid sweep")
}

/// Sums the first numeric cell of every row so nothing is optimised away.
fn drive(s: &Sweep<CaseSweep<BarrierImpact>>, range: std::ops::Range<u64>) -> f64 {
    let mut sum = 0.0;
    s.for_each_in(range, |row| {
        if let Ok([Cell::Number(x), ..]) = row.outcome {
            sum += x;
        }
    });
    sum
}

/// The Coulomb-friction closed form with no validation, no error paths and no
/// special cases: the model's arithmetic alone (inlined into each compiled
/// copy of the loop).
#[inline(always)]
fn bare(p: &BarrierImpact) -> [f64; 9] {
    let BarrierBody::Rigid {
        mass: m,
        inertia,
        contact,
    } = p.body
    else {
        return [f64::NAN; 9];
    };
    let Law::Friction {
        restitution: e,
        friction: f,
    } = p.law
    else {
        return [f64::NAN; 9];
    };
    let k2 = inertia / m;
    let (dc, dd) = (contact.tangential_offset, contact.normal_offset);
    let (vn, vt, w) = (p.velocity.normal, p.velocity.tangential, p.velocity.angular);
    let vcn = dc.mul_add(w, vn);
    let vct = (-dd).mul_add(w, vt);
    let qn = -(1.0 + e) * vcn;
    let (a, b, c) = (k2 + dc * dc, -dc * dd, k2 + dd * dd);
    let det = a * c - b * b;
    let dn_stick = k2 * (c * qn + b * vct) / det;
    let dt_stick = -k2 * (a * vct + b * qn) / det;
    let mu_c = dt_stick / dn_stick;
    let (dn, dt, mu) = if mu_c.abs() <= f {
        (dn_stick, dt_stick, mu_c)
    } else {
        let mu = -f.copysign(vct);
        let dn = k2 * qn / (a + b * mu);
        (dn, mu * dn, mu)
    };
    let vn1 = vn + dn;
    let vt1 = vt + dt;
    let w1 = w + (dc * dn - dd * dt) / k2;
    let t0 = 0.5 * m * (vn * vn + vt * vt + k2 * w * w);
    let t1 = 0.5 * m * (vn1 * vn1 + vt1 * vt1 + k2 * w1 * w1);
    [
        vn1,
        vt1,
        w1,
        vn1 + dc * w1,
        vt1 - dd * w1,
        m * dn,
        m * dt,
        mu,
        t0 - t1,
    ]
}

/// The bare closed form over the sweep's points, compiled for x86-64-v3
/// when the solver's kernels are (as the sweep's loop is), so that the two
/// use the same instructions (hardware FMA rather than the software call).
fn bare_sweep() -> f64 {
    #[cfg(target_arch = "x86_64")]
    if restitution::kernels::selected() == restitution::kernels::Kernels::X86_64V3 {
        // SAFETY: the solver's kernels are x86-64-v3 only on a CPU with
        // every one of these features.
        return unsafe { bare_sweep_v3() };
    }
    bare_sweep_here()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,movbe,f16c,popcnt")]
fn bare_sweep_v3() -> f64 {
    bare_sweep_here()
}

#[inline(always)]
fn bare_sweep_here() -> f64 {
    let mut p = base();
    let mut sum = 0.0;
    for i in 0..POINTS {
        p.velocity.tangential = (i as f64).mul_add(10.0 / (POINTS - 1) as f64, -5.0);
        // The whole answer is kept (black_box), not only the summed element.
        sum += black_box(bare(black_box(&p)))[4];
    }
    sum
}

/// The kernels the environment asks for (`RESTITUTION_KERNELS=portable`), as the binary does.
fn select_kernels() {
    if std::env::var("RESTITUTION_KERNELS").as_deref() == Ok("portable") {
        restitution::kernels::force_portable();
    }
    eprintln!("kernels: {}", restitution::kernels::selected().as_str());
}

fn single_core(c: &mut Criterion) {
    select_kernels();
    let mut group = c.benchmark_group("sweep_oblique_one_core");
    group.throughput(Throughput::Elements(POINTS));
    group.sample_size(20);
    let all = sweep(Input::TangentialVelocity, ALL, POINTS);
    let one = sweep(
        Input::TangentialVelocity,
        &[Output::FinalTangentialContactVelocity],
        POINTS,
    );
    let fixed = sweep(Input::Friction, &[Output::FinalTangentialContactVelocity], POINTS);
    group.bench_function("all_outputs", |b| b.iter(|| drive(&all, 0..POINTS)));
    group.bench_function("one_output", |b| b.iter(|| drive(&one, 0..POINTS)));
    group.bench_function("one_output_fixed_scene", |b| b.iter(|| drive(&fixed, 0..POINTS)));
    group.bench_function("bare_closed_form", |b| b.iter(bare_sweep));
    group.finish();

    // The same sweeps with every decision taken on the f64 value as it is
    // (no error bound): what the filter of `fast` costs, and the model's
    // own cost beside the bare loop.
    let mut group = c.benchmark_group("sweep_oblique_one_core_unfiltered");
    group.throughput(Throughput::Elements(POINTS));
    group.sample_size(20);
    let all = sweep_in(Input::TangentialVelocity, ALL, POINTS, Arithmetic::Unfiltered);
    let one = sweep_in(
        Input::TangentialVelocity,
        &[Output::FinalTangentialContactVelocity],
        POINTS,
        Arithmetic::Unfiltered,
    );
    let fixed = sweep_in(
        Input::Friction,
        &[Output::FinalTangentialContactVelocity],
        POINTS,
        Arithmetic::Unfiltered,
    );
    group.bench_function("all_outputs", |b| b.iter(|| drive(&all, 0..POINTS)));
    group.bench_function("one_output", |b| b.iter(|| drive(&one, 0..POINTS)));
    group.bench_function("one_output_fixed_scene", |b| b.iter(|| drive(&fixed, 0..POINTS)));
    group.finish();
}

fn all_cores(c: &mut Criterion) {
    select_kernels();
    let points = 2_000_000;
    let mut group = c.benchmark_group("sweep_oblique_all_cores");
    group.throughput(Throughput::Elements(points));
    group.sample_size(10);
    for (name, columns) in [
        ("all_outputs", ALL),
        ("one_output", &[Output::FinalTangentialContactVelocity][..]),
    ] {
        let s = sweep(Input::TangentialVelocity, columns, points);
        group.bench_with_input(BenchmarkId::new("run_parallel", name), &s, |b, s| {
            b.iter(|| {
                let mut total = 0.0;
                s.run_parallel(
                    4096,
                    |r| drive(s, r),
                    |x| {
                        total += x;
                        true
                    },
                );
                total
            })
        });
    }
    group.finish();
}

fn torsional_base() -> TorsionalImpact {
    TorsionalImpact {
        mass: 0.6,
        normal_inertia: 0.003456,
        normal_velocity: -3.0,
        spin: 0.0,
        restitution: 0.7,
        torsional_restitution: 0.2,
        torsional_friction: 0.3,
        pitch_radius: 0.01,
    }
}

fn torsional_one_core(c: &mut Criterion) {
    select_kernels();
    let mut group = c.benchmark_group("sweep_torsional_one_core");
    group.throughput(Throughput::Elements(POINTS));
    group.sample_size(20);
    let columns = TorsionalImpact::OUTPUTS.to_vec();
    let axes = vec![Axis {
        param: Input::Spin,
        values: AxisValues::Linspace {
            start: -50.0,
            stop: 50.0,
            count: POINTS,
        },
    }];
    let s = Sweep::new(
        CaseSweep::new(&torsional_base(), &[Input::Spin], columns, Precision::Fast)
            .expect("a torsional input"),
        torsional_base(),
        axes,
        Combine::Product,
        u64::MAX,
    )
    .expect("a valid sweep");
    group.bench_function("all_outputs", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            s.for_each_in(0..POINTS, |row| {
                if let Ok([Cell::Number(x), ..]) = row.outcome {
                    sum += x;
                }
            });
            black_box(sum)
        })
    });
    group.bench_function("bare_solve", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            let mut impact = torsional_base();
            for i in 0..POINTS {
                impact.spin = -50.0 + 100.0 * i as f64 / (POINTS - 1) as f64;
                if let Ok(o) = solve(black_box(&impact), Outputs::ALL, Precision::Fast) {
                    sum += o.final_spin;
                }
            }
            black_box(sum)
        })
    });
    group.finish();
}

criterion_group!(benches, single_core, all_cores, torsional_one_core);
criterion_main!(benches);
