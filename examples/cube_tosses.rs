//! Bounces out of the ContactNets cube tosses (`tests/data/
//! contactnets_cube_tosses_0-399.csv.gz`): the table of bounces by class,
//! the cube's inertia from the angular-momentum balance of single-corner
//! impacts with its uncertainty, and the balance's residuals against the
//! data's noise. The method and these numbers are in `docs/tosses.md`.
//!
//! `cargo run --example cube_tosses`

use restitution_testkit::tosses::{self, Bounce, Class, Detection, Skip};
use std::collections::BTreeMap;

/// `I₀` (kg m²) as `I/(m h²)`.
fn mh2(inertia: f64) -> f64 {
    tosses::in_mh2(inertia)
}

fn main() {
    let all = tosses::read().expect("the toss data (tests/data)");
    let d = Detection::measured(&all);
    let samples: usize = all.iter().map(|t| t.samples.len()).sum();
    let repeats = tosses::repeats(&all);
    println!("# Bounces of the ContactNets cube tosses\n");
    println!(
        "{} tosses, {samples} samples; {} tosses repeat another (same trajectory, turned about z): {:?}",
        all.len(),
        repeats.len(),
        repeats
    );
    println!(
        "board level in the data {:.2} mm (median resting lowest corner); contact within {} mm, \
         touching within {} mm of the lowest corner, pre sample c−{}, post sample c+{}",
        d.board * 1e3,
        d.contact * 1e3,
        d.touching * 1e3,
        d.before,
        d.after
    );

    let mut by_class: BTreeMap<Class, usize> = BTreeMap::new();
    let mut by_touching: BTreeMap<usize, usize> = BTreeMap::new();
    let mut skipped: BTreeMap<Skip, usize> = BTreeMap::new();
    let mut bounces: Vec<Bounce> = Vec::new();
    let mut with_bounce = 0;
    for toss in &all {
        let found = tosses::bounces(toss, &d);
        with_bounce += usize::from(!found.bounces.is_empty());
        for b in &found.bounces {
            *by_class.entry(b.class).or_default() += 1;
            *by_touching.entry(b.corners.len()).or_default() += 1;
        }
        for (_, s) in &found.skipped {
            *skipped.entry(*s).or_default() += 1;
        }
        bounces.extend(found.bounces);
    }
    let distinct = tosses::distinct_bounces(&all, &d);
    let count = |bs: &[Bounce], c: Class| bs.iter().filter(|b| b.class == c).count();
    println!("\n## Bounces by class\n");
    println!(
        "{} bounces in {with_bounce} of {} tosses.\n",
        bounces.len(),
        all.len()
    );
    println!("| class | corners touching | all tosses | distinct tosses |\n|---|---|---|---|");
    for c in [Class::Corner, Class::Edge, Class::Face] {
        let touching: Vec<String> = by_touching
            .iter()
            .filter(|(k, _)| match c {
                Class::Corner => **k == 1,
                Class::Edge => **k == 2,
                Class::Face => **k >= 3,
            })
            .map(|(k, n)| format!("{k}: {n}"))
            .collect();
        println!(
            "| {} | {} | {} | {} |",
            c.name(),
            touching.join(", "),
            by_class.get(&c).copied().unwrap_or(0),
            count(&distinct, c)
        );
    }
    println!("\nContacts not taken:");
    for (s, n) in &skipped {
        println!("- {}: {n}", s.name());
    }
    let pre: Vec<f64> = bounces.iter().map(|b| b.normal_velocity_pre()).collect();
    let post: Vec<f64> = bounces.iter().map(|b| b.normal_velocity_post()).collect();
    let range = |v: &[f64]| {
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    println!(
        "\nContact point's normal velocity before {:.3}..{:.3} m/s, after {:.3}..{:.3} m/s.",
        range(&pre).0,
        range(&pre).1,
        range(&post).0,
        range(&post).1
    );

    let fit = tosses::fit_inertia(&distinct, 4000, 34);
    let header = tosses::header_inertia();
    let solid = tosses::solid_cube_inertia();
    println!("\n## Inertia from the balance I0 Δω = r × m Δv (single-corner impacts of distinct tosses)\n");
    println!("{} impacts.\n", fit.n);
    println!("| | kg m² | I/(m h²) |\n|---|---|---|");
    println!("| fitted I0 | {:.4e} | {:.4} |", fit.inertia, mh2(fit.inertia));
    println!(
        "| standard error (residuals) | {:.1e} | {:.4} |",
        fit.standard_error,
        mh2(fit.standard_error)
    );
    println!(
        "| bootstrap sd (tosses, 4000 draws) | {:.1e} | {:.4} |",
        fit.bootstrap_sd,
        mh2(fit.bootstrap_sd)
    );
    println!(
        "| bootstrap 95 % | {:.4e} – {:.4e} | {:.4} – {:.4} |",
        fit.bootstrap_95.0,
        fit.bootstrap_95.1,
        mh2(fit.bootstrap_95.0),
        mh2(fit.bootstrap_95.1)
    );
    println!(
        "| reverse regression (Δω on r × m Δv) | {:.4e} | {:.4} |",
        fit.reverse,
        mh2(fit.reverse)
    );
    println!(
        "| header (authors' simulator) | {header:.4e} | {:.4} |",
        mh2(header)
    );
    println!("| solid uniform cube m a²/6 | {solid:.4e} | {:.4} |", mh2(solid));
    println!(
        "| thin-walled hollow cube 5 m a²/18 | {:.4e} | {:.4} |",
        10.0 / 9.0 * tosses::MASS * tosses::HALF_WIDTH.powi(2),
        10.0 / 9.0
    );
    let sigma = fit.standard_error.max(fit.bootstrap_sd);
    println!(
        "\nHeader − fitted = {:.1} σ; solid cube − fitted = {:.1} σ (σ = the larger of the two uncertainties).",
        (header - fit.inertia) / sigma,
        (solid - fit.inertia) / sigma
    );

    let offset = tosses::fit_inertia_and_offset(&distinct);
    let (faces, rest) = tosses::resting_faces(&all);
    println!(
        "\nWith the centre of mass unknown too (offset δ from the geometric centre, body frame): \
         I0 = {:.4e} ± {:.1e} kg m² = {:.4} ± {:.4} m h², δ = ({:.2}, {:.2}, {:.2}) ± ({:.2}, {:.2}, {:.2}) mm, \
         relative residual {:.3}.",
        offset.inertia,
        offset.inertia_se,
        mh2(offset.inertia),
        mh2(offset.inertia_se),
        offset.offset[0] * 1e3,
        offset.offset[1] * 1e3,
        offset.offset[2] * 1e3,
        offset.offset_se[0] * 1e3,
        offset.offset_se[1] * 1e3,
        offset.offset_se[2] * 1e3,
        offset.residual
    );
    println!(
        "Faces the tosses end on [−x, +x, −y, +y, −z, +z]: {faces:?} (a centre of mass towards +z favours +z down); \
         the tracked centre's median resting height on each (mm): {:?}.",
        rest.map(|h| (h * 1e4).round() / 10.0)
    );
    let (tensor, tensor_residual) = tosses::fit_inertia_tensor(&distinct);
    println!(
        "A general inertia tensor (body frame) instead of I0·1: diagonal {:.3}, {:.3}, {:.3}, \
         off-diagonal {:.3}, {:.3}, {:.3} m h², relative residual {tensor_residual:.3}.",
        mh2(tensor[0]),
        mh2(tensor[1]),
        mh2(tensor[2]),
        mh2(tensor[3]),
        mh2(tensor[4]),
        mh2(tensor[5])
    );
    let (velocity_noise, windows) = tosses::free_flight_noise(&all, &d, fit.inertia, 0.03);
    let noise = tosses::noise_residual(&distinct, velocity_noise);
    println!("\n## Residuals of the balance\n");
    println!(
        "Relative residual sqrt(Σ|I0 Δω − r × m Δv|² / Σ|r × m Δv|²) over the {} impacts; RMS |r × m Δv| = {:.3e} N m s.\n",
        fit.n,
        tosses::rms_angular_impulse(&distinct)
    );
    println!("| I0 | I/(m h²) | relative residual | median per impact |\n|---|---|---|---|");
    for (name, i0) in [
        ("fitted", fit.inertia),
        ("header", header),
        ("solid cube", solid),
        ("fitted × 3", 3.0 * fit.inertia),
        ("fitted / 3", fit.inertia / 3.0),
        ("0 (Δω ignored)", 0.0),
    ] {
        println!(
            "| {name} | {:.4} | {:.3} | {:.3} |",
            mh2(i0),
            tosses::balance_residual(&distinct, i0),
            tosses::median_relative_residual(&distinct, i0)
        );
    }
    println!(
        "\nThe data's noise: free flight over {windows} windows of {} samples gives |I0 Δω − r × m Δv| = {velocity_noise:.2e} N m s RMS \
         (velocities alone, {:.3} of the impacts' RMS); with the contact point's error (|r − r_after|/√2 per impact) \
         the noise alone leaves a relative residual of {noise:.3}.",
        d.before + d.after,
        velocity_noise / tosses::rms_angular_impulse(&distinct)
    );

    println!("\n## Sensitivity\n");
    println!(
        "| variant | bounces | corner | I/(m h²) | bootstrap sd | residual | noise residual |\n|---|---|---|---|---|---|---|"
    );
    let variants: Vec<(String, Detection)> = vec![
        ("as above".into(), d),
        (
            "pre c−2, post c+2 (contaminated)".into(),
            Detection {
                before: 2,
                after: 2,
                ..d
            },
        ),
        (
            "pre c−2, post c+3".into(),
            Detection {
                before: 2,
                after: 3,
                ..d
            },
        ),
        (
            "pre c−4, post c+5".into(),
            Detection {
                before: 4,
                after: 5,
                ..d
            },
        ),
        (
            "touching 2.5 mm".into(),
            Detection {
                touching: 0.0025,
                ..d
            },
        ),
        ("touching 10 mm".into(), Detection { touching: 0.010, ..d }),
        ("contact 7 mm".into(), Detection { contact: 0.007, ..d }),
        ("contact 15 mm".into(), Detection { contact: 0.015, ..d }),
    ];
    for (name, v) in variants {
        let b = tosses::distinct_bounces(&all, &v);
        let f = tosses::fit_inertia(&b, 400, 34);
        let (vn, _) = tosses::free_flight_noise(&all, &v, f.inertia, 0.03);
        println!(
            "| {name} | {} | {} | {:.4} | {:.4} | {:.3} | {:.3} |",
            b.len(),
            f.n,
            mh2(f.inertia),
            mh2(f.bootstrap_sd),
            tosses::balance_residual(&b, f.inertia),
            tosses::noise_residual(&b, vn)
        );
    }
    let after_view: Vec<Bounce> = distinct
        .iter()
        .map(|b| Bounce {
            r: b.r_after,
            ..b.clone()
        })
        .collect();
    let f = tosses::fit_inertia(&after_view, 400, 34);
    println!(
        "| r from the post-impact orientation | {} | {} | {:.4} | {:.4} | {:.3} | |",
        distinct.len(),
        f.n,
        mh2(f.inertia),
        mh2(f.bootstrap_sd),
        tosses::balance_residual(&after_view, f.inertia)
    );
}
