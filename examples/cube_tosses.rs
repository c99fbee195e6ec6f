//! Bounces out of the ContactNets cube tosses (`tests/data/
//! contactnets_cube_tosses_0-399.csv.gz`): the table of bounces by class,
//! the cube's inertia from the angular-momentum balance of single-corner
//! impacts with its uncertainty, and the balance's residuals against the
//! data's noise; then the prediction of held-out tosses (two folds by toss)
//! with each contact model, and where the point model stops following
//! (edge and face impacts); the coefficients with their standard errors
//! from the library's spatial fit. The method and these numbers are in
//! `docs/tosses.md`. It also draws the figures of `docs/validation.md`'s
//! "Real cube tosses" (`docs/validation/contactnets_tosses_*.svg`; the same
//! bytes on every run).
//!
//! `cargo run --example cube_tosses`

use restitution::plot::{Color, Curve, Dash, Figure, LegendEntry, Line, Marker, Markers, Scale, Shape};
use restitution_testkit::tosses::{self, Bounce, Class, Detection, Model, Skip};
use std::collections::BTreeMap;

/// Where the figures go.
const PLOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation");

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
    prediction(&distinct);
}

/// Coefficients as `name value` pairs.
fn coefficients(model: Model, p: &[f64]) -> String {
    if model == Model::Authors {
        return "e 0.125, f 0.18".into();
    }
    let names = model.parameters();
    if names.is_empty() {
        return "–".into();
    }
    names
        .iter()
        .zip(p)
        .map(|(n, v)| format!("{n} {v:.3}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The two-fold prediction of held-out tosses.
fn prediction(distinct: &[Bounce]) {
    const SEED: u64 = 34;
    let folds = tosses::fold_of_tosses(distinct, SEED);
    let in_fold = |k: usize, c: Class| {
        distinct
            .iter()
            .filter(|b| folds[&b.toss] == k && b.class == c)
            .count()
    };
    println!("\n## Prediction of held-out tosses\n");
    println!(
        "Distinct tosses with a bounce split in two folds by toss (seed {SEED}): {} and {} tosses; \
         single-corner impacts {} and {}, edge {} and {}, face {} and {}. Each fold's I0 and coefficients \
         are fitted on the other fold's single-corner impacts (least squares of the post-impact \
         velocities of G and of the contact point; the rows marked LM by restitution::fit::spatial, \
         weighted least squares of the measured changes of velocity and angular velocity); every \
         bounce is predicted once, and the table pools both held-out folds. Twist pitch radius {} mm.\n",
        folds.values().filter(|&&k| k == 0).count(),
        folds.values().filter(|&&k| k == 1).count(),
        in_fold(0, Class::Corner),
        in_fold(1, Class::Corner),
        in_fold(0, Class::Edge),
        in_fold(1, Class::Edge),
        in_fold(0, Class::Face),
        in_fold(1, Class::Face),
        tosses::PITCH_RADIUS * 1e3
    );
    let results = tosses::held_out(distinct, &Model::ALL, SEED);
    println!(
        "I0 per fold (fitted on its training tosses): {:.4}, {:.4} m h²\n",
        mh2(results[0].inertia[0]),
        mh2(results[0].inertia[1])
    );
    let refused_training: usize = results
        .iter()
        .flat_map(|h| h.train.iter().map(|t| t.refused))
        .sum();
    println!(
        "Refusals at the fitted coefficients on the training folds, all models: {refused_training}; \
         held out: in the tables.\n"
    );
    let change = results[0].corner.rms_changes();
    println!(
        "RMS of the measured change (single-corner, held out): G {:.3} m/s, contact point {:.3} m/s, \
         ω {:.2} rad/s, G and contact point {:.3} m/s.\n",
        change[0], change[1], change[2], change[3]
    );
    for (title, class) in [
        ("Single-corner impacts", Class::Corner),
        ("Edge impacts (contact at the edge's midpoint)", Class::Edge),
        (
            "Face impacts (contact at the touching corners' mean)",
            Class::Face,
        ),
    ] {
        let pick = |h: &tosses::HeldOut| match class {
            Class::Corner => h.corner,
            Class::Edge => h.edge,
            Class::Face => h.face,
        };
        println!("### {title}, held out\n");
        println!(
            "| model | fit for fold 1 (on fold 2) | fit for fold 2 (on fold 1) | G m/s (rel) | contact m/s (rel) | ω rad/s (rel) | G+contact m/s (rel) | refused |\n\
             |---|---|---|---|---|---|---|---|"
        );
        for h in &results {
            let s = pick(h);
            println!(
                "| {} | {} | {} | {} |",
                h.model.name(),
                coefficients(h.model, &h.coefficients[0]),
                coefficients(h.model, &h.coefficients[1]),
                error_cells(&s)
            );
        }
        println!();
    }
    // Where the point model stops following: the fitted Coulomb law's
    // held-out errors by how close a second corner came to the board.
    let coulomb = results
        .iter()
        .find(|h| h.model == Model::Coulomb)
        .expect("the Coulomb row");
    println!("### Fitted Coulomb, held out, by the clearance of the next-lowest corner\n");
    println!(
        "| impacts | clearance | n | G (rel) | contact (rel) | ω (rel) | G+contact m/s (rel) |\n|---|---|---|---|---|---|---|"
    );
    let bins: [(&str, Class, f64, f64); 5] = [
        ("edge", Class::Edge, 0.0, f64::INFINITY),
        ("corner", Class::Corner, 0.005, 0.010),
        ("corner", Class::Corner, 0.010, 0.020),
        ("corner", Class::Corner, 0.020, 0.040),
        ("corner", Class::Corner, 0.040, f64::INFINITY),
    ];
    for (name, class, lo, hi) in bins {
        let mut s = tosses::Score::default();
        for k in 0..2 {
            let part: Vec<&Bounce> = distinct
                .iter()
                .filter(|b| folds[&b.toss] == k && b.class == class && b.clearance >= lo && b.clearance < hi)
                .collect();
            s = s.plus(&tosses::score(
                &part,
                coulomb.inertia[k],
                Model::Coulomb,
                &coulomb.coefficients[k],
            ));
        }
        let rel = s.relative();
        let range = if class == Class::Edge {
            "(two corners within 5 mm)".to_string()
        } else if hi.is_finite() {
            format!("{:.0}–{:.0} mm", lo * 1e3, hi * 1e3)
        } else {
            format!("≥ {:.0} mm", lo * 1e3)
        };
        println!(
            "| {name} | {range} | {} | {:.3} | {:.3} | {:.3} | {:.3} ({:.3}) |",
            s.n,
            rel[0],
            rel[1],
            rel[2],
            s.rms_gc(),
            rel[3]
        );
    }
    println!();
    // The edges' angular velocity errors, about the edge, across it and about
    // the normal: a line contact's spread of normal force has a moment
    // about the axis across the edge, which a point at its midpoint cannot give.
    let mut error = [0.0; 3];
    let mut change = [0.0; 3];
    let mut n = 0;
    for b in distinct.iter().filter(|b| b.class == Class::Edge) {
        let k = folds[&b.toss];
        let Ok(p) = tosses::predict(b, coulomb.inertia[k], Model::Coulomb, &coulomb.coefficients[k]) else {
            continue;
        };
        let u = tosses::edge_axis(b).expect("an edge");
        let e = tosses::edge_components(std::array::from_fn(|i| p.omega[i] - b.post.omega[i]), u);
        let c = tosses::edge_components(b.domega(), u);
        for (i, (e, c)) in e.into_iter().zip(c).enumerate() {
            error[i] += e * e;
            change[i] += c * c;
        }
        n += 1;
    }
    let rms = |x: f64| (x / n.max(1) as f64).sqrt();
    println!(
        "Edge impacts' angular velocity (fitted Coulomb, held out, {n}): RMS error (measured change) about \
         the edge {:.2} ({:.2}) rad/s, across it {:.2} ({:.2}), about the normal {:.2} ({:.2}).\n",
        rms(error[0]),
        rms(change[0]),
        rms(error[1]),
        rms(change[1]),
        rms(error[2]),
        rms(change[2])
    );
    // The authors' coefficients with their simulator's inertia (no fit,
    // every single-corner impact).
    let corners: Vec<&Bounce> = distinct.iter().filter(|b| b.class == Class::Corner).collect();
    let header = tosses::score(&corners, tosses::header_inertia(), Model::Authors, &[]);
    println!(
        "The authors' coefficients at the header's inertia 0.797 m h² instead of I0 (all {} single-corner \
         impacts): G {:.3} m/s ({:.3}), contact {:.3} m/s ({:.3}), ω {:.2} rad/s ({:.3}), G+contact {:.3} m/s \
         ({:.3}), {} refused.\n",
        header.n,
        header.rms_g(),
        header.relative()[0],
        header.rms_c(),
        header.relative()[1],
        header.rms_w(),
        header.relative()[2],
        header.rms_gc(),
        header.relative()[3],
        header.refused
    );
    // In-sample: every single-corner impact, I0 of them all.
    let inertia = tosses::fit_inertia(distinct, 0, SEED).inertia;
    println!(
        "### In sample: fitted on all {} single-corner impacts (I0 {:.4} m h²)\n",
        corners.len(),
        mh2(inertia)
    );
    println!(
        "| model | fit | G m/s (rel) | contact m/s (rel) | ω rad/s (rel) | G+contact m/s (rel) | refused |\n|---|---|---|---|---|---|---|"
    );
    let (coulomb, _) = tosses::fit_model(&corners, inertia, Model::Coulomb, None);
    for model in Model::ALL {
        let (p, s) = tosses::fit_model(&corners, inertia, model, Some(&coulomb));
        println!(
            "| {} | {} | {} |",
            model.name(),
            coefficients(model, &p),
            error_cells(&s)
        );
    }
    standard_errors(&corners, inertia);
    figures(distinct, &folds, &results);
}

/// The Coulomb and two-phase laws fitted on every single-corner impact
/// through `restitution::fit::spatial`, with their standard errors.
fn standard_errors(corners: &[&Bounce], inertia: f64) {
    println!(
        "\n### Standard errors: restitution::fit::spatial on all {} single-corner impacts (I0 {:.4} m h²)\n",
        corners.len(),
        mh2(inertia)
    );
    println!(
        "Weighted least squares of the measured ΔV and Δω (σ(Δω) = σ(ΔV)/(√3 h)); standard errors from the \
         covariance at σ(ΔV) scaled so that χ² equals its degrees of freedom (the residuals' scatter), \
         each impact's six components taken as independent.\n"
    );
    println!(
        "| model | coefficients ± standard error | σ(ΔV) m/s | G m/s (rel) | contact m/s (rel) | ω rad/s (rel) | G+contact m/s (rel) | refused |\n\
         |---|---|---|---|---|---|---|---|"
    );
    for model in [Model::Coulomb, Model::TwoPhase, Model::CoulombApproach] {
        let fit = tosses::fit_spatial(corners, inertia, model)
            .unwrap_or_else(|why| panic!("{}: {why}", model.name()));
        let cells: Vec<String> = fit
            .estimates
            .iter()
            .map(|(name, value, se)| format!("{name} {value:.4} ± {se:.4}"))
            .collect();
        let s = tosses::score(corners, inertia, model, &fit.values());
        println!(
            "| {} | {} | {:.3} | {} |",
            model.name(),
            cells.join(", "),
            fit.sigma_v,
            error_cells(&s)
        );
    }
    println!();
}

/// `a − b`.
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| a[i] - b[i])
}

/// A model's name in a figure (the plot's markup: `_x` a subscript).
fn plot_name(model: Model) -> &'static str {
    match model {
        Model::NoImpact => "no impact",
        Model::Frictionless => "frictionless, e fitted",
        Model::Authors => "Coulomb, authors' e 0.125, f 0.18",
        Model::Coulomb => "Coulomb, e, f fitted",
        Model::Bilinear => "bilinear, e, f, e_t fitted",
        Model::Twist => "Coulomb + twist, e, f, e_z, μ_z fitted",
        Model::TwoPhase => "two-phase, R, μ_A, μ_R fitted",
        Model::CoulombApproach => "two-phase, Coulomb approach, R, f_A, μ_R fitted",
    }
}

/// Each single-corner impact of `distinct` with its held-out prediction by
/// `h` (a refusal predicted as no impact, as in the tables).
fn held_out_predictions<'a>(
    distinct: &'a [Bounce],
    folds: &BTreeMap<usize, usize>,
    h: &tosses::HeldOut,
) -> Vec<(&'a Bounce, tosses::State)> {
    distinct
        .iter()
        .filter(|b| b.class == Class::Corner)
        .map(|b| {
            let k = folds[&b.toss];
            let p = tosses::predict(b, h.inertia[k], h.model, &h.coefficients[k]).unwrap_or(b.pre);
            (b, p)
        })
        .collect()
}

/// The figures: predicted against measured post-impact contact-point
/// velocity (x, y, z) for the best fitted law held out and the authors'
/// coefficients, and the distribution of the per-impact error of every
/// model, held out. Written to `docs/validation/contactnets_tosses_*.svg`.
fn figures(distinct: &[Bounce], folds: &BTreeMap<usize, usize>, results: &[tosses::HeldOut]) {
    let of = |m: Model| results.iter().find(|h| h.model == m).expect("every model");
    let fitted = [
        Model::Frictionless,
        Model::Coulomb,
        Model::Bilinear,
        Model::Twist,
        Model::TwoPhase,
        Model::CoulombApproach,
    ];
    let best = fitted
        .into_iter()
        .min_by(|a, b| of(*a).corner.relative()[3].total_cmp(&of(*b).corner.relative()[3]))
        .expect("fitted models");
    let n = of(best).corner.n;
    println!("## Figures (docs/validation/)\n");
    println!(
        "Best fitted law held out (G+contact, single-corner impacts): {} ({:.3} m/s).\n",
        best.name(),
        of(best).corner.rms_gc()
    );
    // The normal law's reach: the measured ratio of the contact point's
    // normal velocities after and before, per single-corner impact.
    let ratios: Vec<(f64, f64)> = distinct
        .iter()
        .filter(|b| b.class == Class::Corner)
        .map(|b| {
            (
                b.normal_velocity_pre(),
                -b.normal_velocity_post() / b.normal_velocity_pre(),
            )
        })
        .collect();
    let slow = ratios.iter().filter(|(v, _)| *v > -0.1).count();
    let above_one = ratios.iter().filter(|(_, r)| *r > 1.0).count();
    println!(
        "Measured −V_Cz/v_Cz (single-corner impacts): above 1 in {above_one} of {}; {slow} approach slower than \
         0.1 m/s at the inferred impact instant.\n",
        ratios.len()
    );
    std::fs::create_dir_all(PLOTS).expect("docs/validation");
    let write = |name: &str, svg: String| {
        std::fs::write(format!("{PLOTS}/{name}"), svg).expect("a figure");
        println!("- {name}");
    };
    // Predicted against measured contact-point velocity, per component.
    let sets = [
        (best, Marker::hollow(Shape::Circle, Color(0, 114, 178))),
        (Model::Authors, Marker::hollow(Shape::Triangle, Color(213, 94, 0))),
    ];
    let predictions: Vec<Vec<([f64; 3], [f64; 3])>> = sets
        .iter()
        .map(|(m, _)| {
            held_out_predictions(distinct, folds, of(*m))
                .into_iter()
                .map(|(b, p)| {
                    (
                        tosses::contact_point_velocity(&b.post, b.r),
                        tosses::contact_point_velocity(&p, b.r),
                    )
                })
                .collect()
        })
        .collect();
    for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
        let all = predictions.iter().flatten().flat_map(|(m, p)| [m[i], p[i]]);
        let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        let diagonal = Curve {
            label: "predicted = measured".into(),
            segments: vec![vec![(lo, lo), (hi, hi)]],
            line: Some(Line {
                color: Color(77, 77, 77),
                width: 1.2,
                dash: Dash::Dashed,
            }),
        };
        let markers: Vec<Markers> = sets
            .iter()
            .zip(&predictions)
            .map(|((m, marker), points)| {
                let rms = (points.iter().map(|(a, b)| (b[i] - a[i]).powi(2)).sum::<f64>()
                    / points.len() as f64)
                    .sqrt();
                Markers {
                    label: format!("{}: RMS error {rms:.3} m/s", plot_name(*m)),
                    points: points.iter().map(|(a, b)| (a[i], b[i])).collect(),
                    marker: Some(*marker),
                }
            })
            .collect();
        let mut legend = vec![LegendEntry::Heading("Held out".into())];
        legend.extend(
            markers
                .iter()
                .map(|m| LegendEntry::Marker(m.marker.expect("a marker"), m.label.clone())),
        );
        legend.push(LegendEntry::Line(
            diagonal.line.expect("a line"),
            diagonal.label.clone(),
        ));
        let svg = Figure {
            title: format!("Contact-point velocity after impact, {axis}"),
            subtitle: format!(
                "ContactNets cube tosses, {n} single-corner impacts, each predicted from the other fold's fit"
            ),
            x_name: format!("measured V_{{C,{axis}}} (m/s)"),
            y_name: format!("predicted V_{{C,{axis}}} (m/s)"),
            curves: vec![diagonal],
            markers,
            legend: Some(legend),
            size: Some((900.0, 620.0)),
            ..Figure::default()
        }
        .render();
        write(&format!("contactnets_tosses_contact_velocity_{axis}.svg"), svg);
    }
    // The distribution of the per-impact error, every model.
    let mut models = vec![
        Model::NoImpact,
        Model::Frictionless,
        Model::Authors,
        Model::Coulomb,
        Model::TwoPhase,
        Model::CoulombApproach,
    ];
    if !models.contains(&best) {
        models.push(best);
    }
    let styles = [
        Line {
            color: Color(77, 77, 77),
            width: 2.0,
            dash: Dash::Dashed,
        },
        Line {
            color: Color(140, 81, 10),
            width: 2.0,
            dash: Dash::Dotted,
        },
        Line {
            color: Color(213, 94, 0),
            width: 2.0,
            dash: Dash::DashDot,
        },
        Line::solid(Color(0, 114, 178)),
        Line::solid(Color(17, 119, 51)),
        Line {
            color: Color(170, 51, 119),
            width: 2.0,
            dash: Dash::Dashed,
        },
        Line {
            color: Color(51, 34, 136),
            width: 2.0,
            dash: Dash::Dotted,
        },
    ];
    let curves: Vec<Curve> = models
        .iter()
        .zip(styles)
        .map(|(&m, line)| {
            let mut errors: Vec<f64> = held_out_predictions(distinct, folds, of(m))
                .into_iter()
                .map(|(b, p)| {
                    let g = sub(p.velocity, b.post.velocity);
                    let c = sub(
                        tosses::contact_point_velocity(&p, b.r),
                        tosses::contact_point_velocity(&b.post, b.r),
                    );
                    (tosses::dot(g, g) + tosses::dot(c, c)).sqrt()
                })
                .collect();
            errors.sort_by(f64::total_cmp);
            let count = errors.len() as f64;
            let median = errors[errors.len() / 2];
            // The empirical distribution function as a staircase.
            let mut steps = Vec::with_capacity(2 * errors.len());
            for (k, e) in errors.iter().enumerate() {
                steps.push((*e, k as f64 / count));
                steps.push((*e, (k + 1) as f64 / count));
            }
            Curve {
                label: format!("{}: median {median:.3} m/s", plot_name(m)),
                segments: vec![steps],
                line: Some(line),
            }
        })
        .collect();
    let svg = Figure {
        title: "Per-impact error of the post-impact velocities, held out".into(),
        subtitle: format!(
            "ContactNets cube tosses, {n} single-corner impacts: fraction predicted within a given error"
        ),
        x_name: "error of G and contact point, √(|e_G|² + |e_C|²) (m/s)".into(),
        y_name: "fraction of impacts".into(),
        x_scale: Scale::Log,
        curves,
        size: Some((900.0, 620.0)),
        ..Figure::default()
    }
    .render();
    write("contactnets_tosses_error_distribution.svg", svg);
    println!();
}

/// A score's cells: the RMS errors of G, the contact point, ω and G with the
/// contact point, each with its fraction of the measured change, and the
/// refusals.
fn error_cells(s: &tosses::Score) -> String {
    let rel = s.relative();
    format!(
        "{:.3} ({:.3}) | {:.3} ({:.3}) | {:.2} ({:.3}) | {:.3} ({:.3}) | {} of {}",
        s.rms_g(),
        rel[0],
        s.rms_c(),
        rel[1],
        s.rms_w(),
        rel[2],
        s.rms_gc(),
        rel[3],
        s.refused,
        s.n
    )
}
