//! The bare closed form of the oblique Coulomb sweep: the same 200,000 points,
//! inputs and formulas as `benches/scripts/numpy_peer.py` (`oblique_coulomb`
//! and `final_tangential_contact_velocity`), in the same order of operations,
//! so that its columns are bit-identical to numpy's. Nothing is validated and
//! no decision is checked (the sticking test is one comparison, turned into a
//! select); every output goes into a preallocated column, the constant ones
//! (v_cn, V_cn, e, e_kinetic) included. Best-of-N timings in M points/s.
//!
//! Usage: bare-oblique [--repetitions N] [--dump FILE]
//! `--dump` writes the columns (f64, little-endian, column after column, in
//! the order of `NAMES`) for `benches/scripts/bare_oblique_check.py`.

use std::hint::black_box;
use std::io::Write;
use std::time::Instant;

const POINTS: usize = 200_000;
const START: f64 = -5.0;
const STOP: f64 = 5.0;

#[derive(Clone, Copy)]
struct Scene {
    m: f64,
    inertia: f64,
    dc: f64,
    dd: f64,
    vn: f64,
    w: f64,
    e: f64,
    f: f64,
}

const SCENE: Scene = Scene {
    m: 1.0,
    inertia: 0.00125,
    dc: 0.01,
    dd: 0.05,
    vn: -1.0,
    w: 2.0,
    e: 0.93,
    f: 0.123,
};

/// The numpy peer's column names, in the dump's order ("/velocity/tangential" first).
const NAMES: [&str; 20] = [
    "/velocity/tangential",
    "/final_velocity/normal",
    "/final_velocity/tangential",
    "/final_velocity/angular",
    "/contact_velocity/initial/normal",
    "/contact_velocity/initial/tangential",
    "/contact_velocity/final/normal",
    "/contact_velocity/final/tangential",
    "/impulse/normal",
    "/impulse/tangential",
    "/impulse_ratio",
    "/critical_impulse_ratio",
    "/restitution",
    "/kinetic_restitution",
    "/regime",
    "/energy/initial",
    "/energy/final",
    "/energy/loss",
    "/energy/max_loss",
    "/energy/normalized_loss",
];

type Columns<'a> = [&'a mut [f64]; 20];

/// Elements between the starts of two columns: the points and one cache line,
/// so that the 20 columns written together start in different cache sets
/// (separate 1.6 MB allocations all start at the same offset in their pages,
/// and 20 streams in one set of an 8-way L1 evict each other: 3.5x slower here).
const STRIDE: usize = POINTS + 8;

/// numpy's linspace: i * step + start (two roundings), the last point exactly
/// `STOP`; the loops run to the last but one and then do the last alone, so the
/// loop body has no branch.
#[inline(always)]
fn point(i: usize, step: f64) -> f64 {
    i as f64 * step + START
}

#[inline(always)]
fn all_outputs(s: Scene, out: &mut Columns<'_>) {
    let Scene { m, inertia, dc, dd, vn, w, e, f } = s;
    let step = (STOP - START) / (POINTS - 1) as f64;
    // Per scene, as numpy computes its scalars.
    let k2 = inertia / m;
    let vcn = vn + dc * w;
    let ddw = dd * w;
    let qn = -(1.0 + e) * vcn;
    let (a, b, c) = (k2 + dc * dc, -dc * dd, k2 + dd * dd);
    let s_ = a + dd * dd;
    let cqn = c * qn;
    let nbqn = -b * qn;
    let vcn_final = -e * vcn;
    let half_m = 0.5 * m;
    let vn2 = vn * vn;
    let rot = 0.5 * inertia * w * w;
    let slip_work = (1.0 - e) * vcn;
    let neg_half_m = -0.5 * m;
    let ddvcn = dd * vcn;
    let vcn2 = vcn * vcn;

    let [c_vt, c_vnf, c_vtf, c_wf, c_vcn, c_vct, c_vcnf, c_vctf, c_pn, c_pt, c_mu, c_muc, c_e, c_ek, c_reg, c_t0, c_t1, c_tl, c_tm, c_tn] =
        out;
    let n = POINTS;
    let (c_vt, c_vnf, c_vtf, c_wf, c_vcn, c_vct, c_vcnf, c_vctf, c_pn, c_pt) = (
        &mut c_vt[..n], &mut c_vnf[..n], &mut c_vtf[..n], &mut c_wf[..n], &mut c_vcn[..n],
        &mut c_vct[..n], &mut c_vcnf[..n], &mut c_vctf[..n], &mut c_pn[..n], &mut c_pt[..n],
    );
    let (c_mu, c_muc, c_e, c_ek, c_reg, c_t0, c_t1, c_tl, c_tm, c_tn) = (
        &mut c_mu[..n], &mut c_muc[..n], &mut c_e[..n], &mut c_ek[..n], &mut c_reg[..n],
        &mut c_t0[..n], &mut c_t1[..n], &mut c_tl[..n], &mut c_tm[..n], &mut c_tn[..n],
    );
    let mut at =
    |i: usize, vt: f64| {
        let vct = vt - ddw;
        let det_dn = cqn + b * vct;
        let det_dt = nbqn - a * vct;
        let mu_c = det_dt / det_dn;
        let sticking = mu_c.abs() <= f;
        let mu = if sticking { mu_c } else { -f.copysign(vct) };
        let per = qn / (a + mu * b);
        let dn = k2 * per;
        let dt = mu * dn;
        let vct_final = if sticking { 0.0 } else { vct + (b + mu * c) * per };
        let initial = half_m * (vn2 + vt * vt) + rot;
        let work = dn * slip_work + dt * (vct + vct_final);
        let loss = neg_half_m * work;
        let lever = ddvcn + dc * vct;
        let max_loss = half_m * (k2 * (vcn2 + vct * vct) + lever * lever) / s_;
        c_vt[i] = vt;
        c_vnf[i] = vn + dn;
        c_vtf[i] = vt + dt;
        c_wf[i] = w + (dc - mu * dd) * per;
        c_vcn[i] = vcn;
        c_vct[i] = vct;
        c_vcnf[i] = vcn_final;
        c_vctf[i] = vct_final;
        c_pn[i] = m * dn;
        c_pt[i] = m * dt;
        c_mu[i] = mu;
        c_muc[i] = mu_c;
        c_e[i] = e;
        c_ek[i] = e;
        c_reg[i] = if sticking { 1.0 } else { 0.0 };
        c_t0[i] = initial;
        c_t1[i] = initial - loss;
        c_tl[i] = loss;
        c_tm[i] = max_loss;
        c_tn[i] = loss / max_loss;
    };
    for i in 0..n - 1 {
        at(i, point(i, step));
    }
    at(n - 1, STOP);
}

#[inline(always)]
fn one_output(s: Scene, out: &mut [f64]) {
    let Scene { m, inertia, dc, dd, vn, w, e, f } = s;
    let step = (STOP - START) / (POINTS - 1) as f64;
    let k2 = inertia / m;
    let ddw = dd * w;
    let qn = -(1.0 + e) * (vn + dc * w);
    let (a, b, c) = (k2 + dc * dc, -dc * dd, k2 + dd * dd);
    let (bqn, cqn) = (b * qn, c * qn);
    let out = &mut out[..POINTS];
    let at =
    |vt: f64| {
        let vct = vt - ddw;
        let sticking = (bqn + a * vct).abs() <= f * (cqn + b * vct).abs();
        let mu = -f.copysign(vct);
        let slid = vct + (b + mu * c) * qn / (a + mu * b);
        if sticking { 0.0 } else { slid }
    };
    let (last, body) = out.split_last_mut().expect("points");
    for (i, o) in body.iter_mut().enumerate() {
        *o = at(point(i, step));
    }
    *last = at(STOP);
}

fn time(repetitions: usize, mut run: impl FnMut()) -> (f64, f64) {
    run();
    let mut seconds: Vec<f64> = (0..repetitions)
        .map(|_| {
            let start = Instant::now();
            run();
            start.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    (seconds[0], seconds[seconds.len() / 2])
}

fn main() {
    let mut repetitions = 20;
    let mut dump = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--repetitions" => repetitions = args.next().and_then(|n| n.parse().ok()).expect("--repetitions N"),
            "--dump" => dump = Some(args.next().expect("--dump FILE")),
            _ => {
                eprintln!("usage: bare-oblique [--repetitions N] [--dump FILE]");
                std::process::exit(2);
            }
        }
    }
    let repetitions = repetitions.max(1);
    let features = if cfg!(target_feature = "avx2") && cfg!(target_feature = "fma") {
        "x86-64-v3 (AVX2, FMA)"
    } else {
        "baseline x86-64"
    };
    println!("bare closed form, compiled for {features}, {POINTS} points, best of {repetitions}, one thread");

    let mut storage = vec![0.0; STRIDE * NAMES.len()];
    let mut chunks = storage.chunks_exact_mut(STRIDE).map(|chunk| &mut chunk[..POINTS]);
    let mut columns: Columns<'_> = std::array::from_fn(|_| chunks.next().expect("20 columns"));
    let (best, median) = time(repetitions, || all_outputs(black_box(SCENE), black_box(&mut columns)));
    report("all outputs", best, median);
    let mut one = vec![0.0; POINTS];
    let (best, median) = time(repetitions, || one_output(black_box(SCENE), black_box(&mut one)));
    report("one output", best, median);

    if let Some(path) = dump {
        all_outputs(SCENE, &mut columns);
        one_output(SCENE, &mut one);
        let mut file = std::io::BufWriter::new(std::fs::File::create(&path).expect("dump file"));
        for column in columns.iter().map(|c| &**c).chain(std::iter::once(&one[..])) {
            for x in column {
                file.write_all(&x.to_le_bytes()).expect("dump");
            }
        }
        file.flush().expect("dump");
        println!("dumped {} columns ({}, then V_ct of the one-output loop) to {path}", NAMES.len() + 1, NAMES.join(", "));
    }
}

fn report(label: &str, best: f64, median: f64) {
    println!(
        "{label}: {:.1} M points/s best ({:.2} ms), {:.1} M points/s median ({:.2} ms)",
        POINTS as f64 / best / 1e6,
        best * 1e3,
        POINTS as f64 / median / 1e6,
        median * 1e3
    );
}
