//! Impacts out of the ContactNets cube tosses (`testkit/src/tosses.rs`,
//! `docs/tosses.md`): the reader, the bounce detector and its classes, the
//! pre- and post-impact states, and the physics that checks them: for a
//! single-corner impact the change of angular momentum about G equals
//! `r × m Δv` whatever the contact law, which also identifies the cube's
//! inertia. Then the contact models' prediction of held-out tosses: the
//! split, the fitted Coulomb coefficients, and the held-out errors against
//! no impact and the data's authors' coefficients.
//!
//! The balance's bound. Measurement noise alone, measured in the data (the
//! same balance over free flight, where it must vanish, plus the contact
//! point's error from its two independent estimates), leaves a relative
//! residual `ε ≈ 0.09`. The observed residual at the fitted inertia is
//! about 3.5 ε (0.31): part of the excess is the cube's centre of mass,
//! ~5 mm off its middle (fitted below; the resting faces agree), the rest is
//! not explained. The bound is 4 ε: it admits that excess, and a wrong
//! inertia (×3 gives ≈ 1.9, 20 ε) fails it.

use crate::common::tosses::{self, Bounce, Class, Detection, Model, Toss};
use std::sync::OnceLock;

struct Data {
    tosses: Vec<Toss>,
    detection: Detection,
    /// Every toss's bounces.
    bounces: Vec<Bounce>,
    /// The bounces of distinct tosses (repeats once).
    distinct: Vec<Bounce>,
    fit: tosses::InertiaFit,
}

fn data() -> &'static Data {
    static DATA: OnceLock<Data> = OnceLock::new();
    DATA.get_or_init(|| {
        let tosses = tosses::read().expect("tests/data/contactnets_cube_tosses_0-399.csv.gz");
        let detection = Detection::measured(&tosses);
        let bounces = tosses::all_bounces(&tosses, &detection);
        let distinct = tosses::distinct_bounces(&tosses, &detection);
        let fit = tosses::fit_inertia(&distinct, 500, 34);
        Data {
            tosses,
            detection,
            bounces,
            distinct,
            fit,
        }
    })
}

/// Corner `i`'s body coordinates.
fn corner(i: usize) -> [f64; 3] {
    tosses::CORNERS[i]
}

#[test]
fn reads_every_toss_in_si_units() {
    let d = data();
    assert_eq!(d.tosses.len(), 400);
    for (i, t) in d.tosses.iter().enumerate() {
        assert_eq!(t.id, i);
        assert!(t.samples.len() >= 30, "toss {i}: {} samples", t.samples.len());
        for (k, s) in t.samples.iter().enumerate() {
            assert_eq!(s.k, k);
            assert!((s.t - k as f64 / 148.0).abs() < 1e-12);
            let q = s.quaternion.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!((q - 1.0).abs() < 1e-6, "toss {i} sample {k}: |q| = {q}");
        }
    }
    assert_eq!(d.tosses.iter().map(|t| t.samples.len()).sum::<usize>(), 41390);
    // At rest on a face the centre is a half-width (52.4 mm) up: the scaling
    // to metres. The board sits within a few mm of z = 0.
    let mut rest: Vec<f64> = d
        .tosses
        .iter()
        .map(|t| t.samples.last().unwrap().position[2])
        .collect();
    rest.sort_by(f64::total_cmp);
    let median = rest[rest.len() / 2];
    assert!(
        (median - tosses::HALF_WIDTH).abs() < 0.003,
        "resting centre height {median} m"
    );
    assert!(
        d.detection.board.abs() < 0.005,
        "board level {} m",
        d.detection.board
    );
}

/// In free flight a corner's height changes by its normal velocity
/// `v_z + (ω × r)_z` over a sample: this holds with the body-frame angular
/// velocity rotated into the world, and not without.
#[test]
fn angular_velocity_is_rotated_into_the_world() {
    let d = data();
    let (mut world, mut body, mut n) = (0.0, 0.0, 0usize);
    for t in &d.tosses {
        for w in t.samples.windows(2).skip(2) {
            let (a, b) = (&w[0], &w[1]);
            if a.lowest().1 < 0.03 || b.lowest().1 < 0.03 {
                continue;
            }
            for i in 0..8 {
                // The velocities are backward differences: b's are over (a, b).
                let rate = (b.corner_height(i) - a.corner_height(i)) / tosses::DT;
                let r = b.corner_offset(i);
                world += (rate - b.velocity[2] - tosses::cross(b.omega, r)[2]).powi(2);
                body += (rate - b.velocity[2] - tosses::cross(b.omega_body, r)[2]).powi(2);
                n += 1;
            }
        }
    }
    let (world, body) = ((world / n as f64).sqrt(), (body / n as f64).sqrt());
    println!(
        "corner height rate vs normal velocity over {n}: RMS {world:.4} m/s (world ω), {body:.4} (body ω)"
    );
    assert!(n > 10_000);
    assert!(world < 0.05, "RMS {world} m/s");
    assert!(body > 5.0 * world, "body-frame ω fits as well: {body} vs {world}");
}

#[test]
fn finds_bounces_in_most_tosses() {
    let d = data();
    let with: std::collections::BTreeSet<usize> = d.bounces.iter().map(|b| b.toss).collect();
    println!(
        "{} bounces in {} of {} tosses",
        d.bounces.len(),
        with.len(),
        d.tosses.len()
    );
    assert!(
        with.len() * 10 >= d.tosses.len() * 6,
        "bounces in {} tosses",
        with.len()
    );
    assert!(d.bounces.len() >= 300);
    // A repeated toss (same trajectory turned about z) gives the same bounces.
    let repeats = tosses::repeats(&d.tosses);
    assert_eq!(repeats.len(), 12);
    for (a, b) in repeats {
        let of = |id: usize| -> Vec<(usize, Class)> {
            d.bounces
                .iter()
                .filter(|x| x.toss == id)
                .map(|x| (x.contact_sample, x.class))
                .collect()
        };
        assert_eq!(of(a), of(b), "tosses {a} and {b}");
    }
}

#[test]
fn classifies_bounces_plausibly() {
    let d = data();
    let count = |c: Class| d.bounces.iter().filter(|b| b.class == c).count();
    let (corner_n, edge_n, face_n) = (count(Class::Corner), count(Class::Edge), count(Class::Face));
    println!("corner {corner_n}, edge {edge_n}, face {face_n}");
    // Tumbling cubes land on a corner mostly, seldom flat.
    assert!(corner_n * 2 > d.bounces.len());
    assert!(corner_n > edge_n && edge_n > face_n && face_n > 0);
    for b in &d.bounces {
        let shared = (0..3)
            .filter(|&a| b.corners.iter().all(|&i| corner(i)[a] == corner(b.corners[0])[a]))
            .count();
        match b.class {
            Class::Corner => {
                assert_eq!(b.corners.len(), 1);
                assert!(b.clearance >= d.detection.touching);
            }
            // Two corners touching are the ends of an edge (two coordinates
            // shared), never a face's or the body's diagonal.
            Class::Edge => assert_eq!(
                (b.corners.len(), shared),
                (2, 2),
                "toss {} {:?}",
                b.toss,
                b.corners
            ),
            // Three or four are of one face (one coordinate shared).
            Class::Face => {
                assert!(
                    b.corners.len() >= 3 && shared == 1,
                    "toss {} {:?}",
                    b.toss,
                    b.corners
                )
            }
        }
        // The contact point is a corner (or the mean of several) of the cube.
        let reach = tosses::norm(b.r) / tosses::HALF_WIDTH;
        let expected = match b.corners.len() {
            1 => 3f64.sqrt(),
            2 => 2f64.sqrt(),
            _ => 1.0,
        };
        if b.corners.len() != 3 {
            assert!(
                (reach - expected).abs() < 1e-9,
                "toss {}: |r| = {reach} h",
                b.toss
            );
        }
    }
}

#[test]
fn pre_impact_states_approach_and_post_impact_states_separate() {
    let d = data();
    for b in &d.bounces {
        let id = (b.toss, b.contact_sample);
        assert!(b.normal_velocity_pre() < 0.0, "{id:?} does not approach");
        assert!(b.normal_velocity_post() > 0.0, "{id:?} does not separate");
        // The board pushes up.
        assert!(b.impulse()[2] > 0.0, "{id:?}: impulse {:?}", b.impulse());
        assert_eq!(b.pre_sample + d.detection.before, b.contact_sample);
        assert_eq!(b.contact_sample + d.detection.after, b.post_sample);
        let (t_pre, t_post) = (
            b.pre_sample as f64 * tosses::DT,
            b.post_sample as f64 * tosses::DT,
        );
        assert!(
            b.t_impact >= t_pre && b.t_impact <= t_post,
            "{id:?}: impact at {}",
            b.t_impact
        );
        assert!((b.gap() - 7.0 * tosses::DT).abs() < 1e-12);
        // The gravity correction: between the samples free fall alone
        // changes v_z by −g·gap; the states referred to the impact differ by
        // the impulse only.
        let raw = &d.tosses[b.toss].samples;
        let dvz_raw = raw[b.post_sample].velocity[2] - raw[b.pre_sample].velocity[2];
        assert!((b.dv()[2] - (dvz_raw + tosses::GRAVITY * b.gap())).abs() < 1e-12);
    }
}

#[test]
fn inertia_from_single_corner_impacts_has_a_finite_standard_error() {
    let d = data();
    let f = d.fit;
    let mh2 = tosses::in_mh2;
    println!(
        "I0 = {:.4} ± {:.4} (se) ± {:.4} (bootstrap) m h² over {} impacts; reverse {:.4}; header {:.4}, solid {:.4}",
        mh2(f.inertia),
        mh2(f.standard_error),
        mh2(f.bootstrap_sd),
        f.n,
        mh2(f.reverse),
        mh2(tosses::header_inertia()),
        mh2(tosses::solid_cube_inertia())
    );
    assert!(f.n >= 150, "{} single-corner impacts", f.n);
    assert!(f.standard_error.is_finite() && f.standard_error > 0.0);
    assert!(f.bootstrap_sd.is_finite() && f.bootstrap_sd > 0.0);
    // Any mass inside the cube: 0 < I < 2 m h² (all of it on the edges
    // parallel to the axis).
    assert!(mh2(f.inertia) > 0.0 && mh2(f.inertia) < 2.0, "{}", mh2(f.inertia));
    let sigma = f.standard_error.max(f.bootstrap_sd);
    assert!(sigma < 0.05 * f.inertia, "I0 uncertain to {sigma}");
    // Noise in both Δω and r × m Δv: the reverse regression brackets the
    // forward one from above, not far off.
    assert!(
        f.reverse >= f.inertia && f.reverse < 1.25 * f.inertia,
        "{} vs {}",
        f.reverse,
        f.inertia
    );
}

#[test]
fn inertia_is_isotropic() {
    let d = data();
    let (t, residual) = tosses::fit_inertia_tensor(&d.distinct);
    let i0 = d.fit.inertia;
    println!("tensor {:?} m h², residual {residual:.3}", t.map(tosses::in_mh2));
    for k in 0..3 {
        assert!(
            (t[k] - i0).abs() < 0.1 * i0,
            "diagonal {:?}",
            t.map(tosses::in_mh2)
        );
        assert!(
            t[3 + k].abs() < 0.05 * i0,
            "off-diagonal {:?}",
            t.map(tosses::in_mh2)
        );
    }
    // Six parameters instead of one buy almost nothing.
    assert!(residual > 0.95 * tosses::balance_residual(&d.distinct, i0));
}

#[test]
fn balance_closes_at_the_fitted_inertia_and_fails_at_a_wrong_one() {
    let d = data();
    let i0 = d.fit.inertia;
    let (velocity_noise, windows) = tosses::free_flight_noise(&d.tosses, &d.detection, i0, 0.03);
    assert!(windows > 100);
    let noise = tosses::noise_residual(&d.distinct, velocity_noise);
    let bound = 4.0 * noise;
    let at = |i: f64| tosses::balance_residual(&d.distinct, i);
    println!(
        "noise alone {noise:.3}, bound {bound:.3}; residual at fitted {:.3}, header {:.3}, solid {:.3}, ×3 {:.3}, /3 {:.3}",
        at(i0),
        at(tosses::header_inertia()),
        at(tosses::solid_cube_inertia()),
        at(3.0 * i0),
        at(i0 / 3.0)
    );
    assert!(noise > 0.0 && noise < 0.2, "noise residual {noise}");
    assert!(
        at(i0) < bound,
        "residual {} at the fitted inertia, bound {bound}",
        at(i0)
    );
    assert!(at(3.0 * i0) > 2.0 * bound, "×3: {}", at(3.0 * i0));
    assert!(at(i0 / 3.0) > bound, "/3: {}", at(i0 / 3.0));
    // The least-squares minimum: the header's and a solid cube's values do worse.
    assert!(at(tosses::header_inertia()) > at(i0));
    assert!(at(tosses::solid_cube_inertia()) > at(tosses::header_inertia()));
}

/// The residual's largest understood part: the centre of mass is off the
/// geometric centre (which the tracking follows: the resting height is the
/// same on every face) along body +z, and the tosses end on the +z face
/// about twice as often as on −z.
#[test]
fn centre_of_mass_offset_agrees_with_the_resting_faces() {
    let d = data();
    let o = tosses::fit_inertia_and_offset(&d.distinct);
    let (faces, rest) = tosses::resting_faces(&d.tosses);
    println!(
        "I0 {:.4} m h², δ = {:?} ± {:?} mm, residual {:.3}; faces {faces:?}",
        tosses::in_mh2(o.inertia),
        o.offset.map(|x| (x * 1e4).round() / 10.0),
        o.offset_se.map(|x| (x * 1e4).round() / 10.0),
        o.residual
    );
    assert!(o.residual < tosses::balance_residual(&d.distinct, d.fit.inertia));
    assert!(
        o.offset[2] > 10.0 * o.offset_se[2] && o.offset[2] < 0.01,
        "δz = {}",
        o.offset[2]
    );
    for a in 0..2 {
        assert!(
            o.offset[a].abs() < 3.0 * o.offset_se[a] + 0.001,
            "δ = {:?}",
            o.offset
        );
    }
    // +z down (index 5) against −z down (4): binomial, more than 3 σ.
    let (plus, minus) = (faces[5] as f64, faces[4] as f64);
    assert!(plus - minus > 3.0 * (plus + minus).sqrt(), "faces {faces:?}");
    // The tracked point is the geometric centre: the same resting height
    // on opposite faces (a 4.8 mm offset of it would show as ±4.8 mm).
    assert!((rest[5] - rest[4]).abs() < 0.001, "resting heights {rest:?}");
    // I0 hardly moves.
    assert!((o.inertia - d.fit.inertia).abs() < 3.0 * d.fit.bootstrap_sd.max(d.fit.standard_error));
}

/// The single-corner impacts of distinct tosses.
fn corner_impacts(d: &Data) -> Vec<&Bounce> {
    d.distinct.iter().filter(|b| b.class == Class::Corner).collect()
}

/// The two folds hold each physical toss once: every distinct toss with a
/// bounce in exactly one fold, the halves balanced, the split reproducible.
#[test]
fn folds_split_the_distinct_tosses_in_two() {
    let d = data();
    let folds = tosses::fold_of_tosses(&d.distinct, 34);
    let mut ids: Vec<usize> = d.distinct.iter().map(|b| b.toss).collect();
    ids.dedup();
    assert_eq!(folds.len(), ids.len());
    let ones = folds.values().filter(|&&k| k == 1).count();
    assert!(
        ones.abs_diff(folds.len() - ones) <= 1,
        "{ones} of {}",
        folds.len()
    );
    assert_eq!(folds, tosses::fold_of_tosses(&d.distinct, 34));
    // No repeat's second copy is among them.
    for (_, repeat) in tosses::repeats(&d.tosses) {
        assert!(!folds.contains_key(&repeat), "toss {repeat} is a repeat");
    }
}

/// Coulomb's `e` and `f` fitted on every single-corner impact (at the fitted
/// `I₀`), least squares of the post-impact velocities of G and of the contact
/// point: e = 0.277, f = 0.168 (`docs/tosses.md`). The tolerance, ±0.02 on
/// each, is about twice the spread between the two folds' fits (0.273–0.282,
/// 0.165–0.172). The fit is a minimum (a step of 0.02 either way in either
/// coefficient costs), and no impact is refused.
#[test]
fn coulomb_fit_on_all_single_corner_impacts_is_pinned() {
    let d = data();
    let corners = corner_impacts(d);
    let (p, s) = tosses::fit_model(&corners, d.fit.inertia, Model::Coulomb, None);
    println!(
        "e {:.4}, f {:.4}, G+contact {:.4} m/s, relative {:?}",
        p[0],
        p[1],
        s.rms_gc(),
        s.relative()
    );
    assert_eq!(s.n, corners.len());
    assert_eq!(s.refused, 0);
    assert!((p[0] - 0.277).abs() < 0.02, "e = {}", p[0]);
    assert!((p[1] - 0.168).abs() < 0.02, "f = {}", p[1]);
    let cost = |q: &[f64]| {
        let s = tosses::score(&corners, d.fit.inertia, Model::Coulomb, q);
        s.g + s.c
    };
    let best = s.g + s.c;
    for (de, df) in [(0.02, 0.0), (-0.02, 0.0), (0.0, 0.02), (0.0, -0.02)] {
        assert!(cost(&[p[0] + de, p[1] + df]) > best, "not a minimum at {p:?}");
    }
}

/// Coulomb's `e` and `f` fitted on every single-corner impact through the
/// library's spatial fit (`restitution::fit::spatial`, the fit behind
/// `POST /v1/fits/spatial`: weighted least squares of the measured `ΔV` and
/// `Δω`), with standard errors from its covariance at the residuals' scatter
/// (`tosses::fit_spatial`): pinned to the committed values of
/// `docs/tosses.md` within two standard errors, the standard errors
/// themselves within a factor 1.5. The check has teeth: a value five
/// standard errors off, the authors' coefficients, and the other fit's `e`
/// (least squares of the post-impact velocities instead) all fail it.
#[test]
fn coulomb_spatial_fit_is_pinned_within_its_standard_errors() {
    /// Committed `(value, standard error)`.
    const E: (f64, f64) = (0.2623, 0.0060);
    const F: (f64, f64) = (0.1722, 0.0021);
    let d = data();
    let corners = corner_impacts(d);
    let fit = tosses::fit_spatial(&corners, d.fit.inertia, Model::Coulomb).expect("a Coulomb fit");
    let ([e, f], [se_e, se_f]) = (
        <[f64; 2]>::try_from(fit.values()).expect("e, f"),
        <[f64; 2]>::try_from(fit.standard_errors()).expect("two errors"),
    );
    println!(
        "e {e:.5} ± {se_e:.5}, f {f:.5} ± {se_f:.5}; χ² {:.4} over {} degrees of freedom, σ(ΔV) {:.4} m/s",
        fit.chi_squared, fit.degrees_of_freedom, fit.sigma_v
    );
    assert_eq!(fit.n, corners.len());
    assert_eq!(fit.degrees_of_freedom, 6 * corners.len() - 2);
    // Within two standard errors of a committed value; a standard error within a factor 1.5.
    let pinned = |value: f64, committed: (f64, f64), se: f64| (value - committed.0).abs() <= 2.0 * se;
    let loosely = |se: f64, committed: (f64, f64)| se > committed.1 / 1.5 && se < committed.1 * 1.5;
    assert!(loosely(se_e, E), "se(e) = {se_e}, committed {}", E.1);
    assert!(loosely(se_f, F), "se(f) = {se_f}, committed {}", F.1);
    assert!(pinned(e, E, se_e), "e = {e} ± {se_e}, committed {}", E.0);
    assert!(pinned(f, F, se_f), "f = {f} ± {se_f}, committed {}", F.0);
    // Teeth.
    for wrong in [E.0 + 5.0 * E.1, E.0 - 5.0 * E.1, tosses::AUTHORS[0], 0.277] {
        assert!(!pinned(e, (wrong, E.1), se_e), "e passes at {wrong}");
    }
    for wrong in [F.0 + 5.0 * F.1, F.0 - 5.0 * F.1, tosses::AUTHORS[1]] {
        assert!(!pinned(f, (wrong, F.1), se_f), "f passes at {wrong}");
    }
    assert!(!loosely(2.0 * E.1, E) && !loosely(E.1 / 2.0, E));
}

/// Held-out tosses (two folds by toss, fitted on one, predicted on the
/// other, both ways): the fitted Coulomb law predicts the post-impact
/// velocities of G and of the contact point far better than no impact
/// (relative error 0.15 of the measured change) and better than the
/// authors' coefficients (e 0.125, f 0.18: 0.19); the folds' fits agree with
/// each other. Edge impacts, taken at their midpoint, are where the point
/// model cannot follow: their angular velocity is predicted more than twice
/// as badly as a corner's.
#[test]
fn fitted_coulomb_predicts_held_out_tosses_better_than_no_impact_and_the_authors() {
    let d = data();
    let results = tosses::held_out(
        &d.distinct,
        &[Model::NoImpact, Model::Authors, Model::Coulomb],
        34,
    );
    let [none, authors, coulomb] = [0, 1, 2].map(|i| &results[i]);
    for h in &results {
        println!(
            "{}: {:?}, corner {:?}, edge {:?}",
            h.model.name(),
            h.coefficients,
            h.corner.relative(),
            h.edge.relative()
        );
        assert_eq!(h.corner.n, corner_impacts(d).len());
        assert_eq!(h.corner.refused + h.edge.refused + h.face.refused, 0);
    }
    assert_eq!(none.corner.relative(), [1.0; 4]);
    let gc = |h: &tosses::HeldOut| h.corner.relative()[3];
    assert!(gc(coulomb) < 0.25, "fitted Coulomb {}", gc(coulomb));
    assert!(
        gc(coulomb) < gc(authors),
        "fitted {} vs authors' {}",
        gc(coulomb),
        gc(authors)
    );
    assert!(gc(authors) < 0.5 * gc(none));
    let [a, b] = &coulomb.coefficients;
    assert!(
        (a[0] - b[0]).abs() < 0.03 && (a[1] - b[1]).abs() < 0.03,
        "folds {a:?} {b:?}"
    );
    assert!(coulomb.edge.relative()[2] > 2.0 * coulomb.corner.relative()[2]);
    assert!(coulomb.edge.relative()[3] > coulomb.corner.relative()[3]);
}

/// The two-phase laws fitted through `restitution::fit::spatial`
/// (Levenberg–Marquardt, weighted least squares of the measured `ΔV` and
/// `Δω`): the held-out prediction of the same folds, beside fitted Coulomb.
/// Both predict held-out tosses far better than no impact and no impact is
/// refused; the measured numbers are in `docs/tosses.md`.
#[test]
fn two_phase_laws_fitted_through_the_spatial_fit_predict_held_out_tosses() {
    let d = data();
    let results = tosses::held_out(
        &d.distinct,
        &[Model::Coulomb, Model::TwoPhase, Model::CoulombApproach],
        34,
    );
    let gc = |h: &tosses::HeldOut| h.corner.relative()[3];
    for h in &results {
        println!(
            "{}: {:?}, corner G+contact {:.4} m/s {:?}, edge {:?}",
            h.model.name(),
            h.coefficients,
            h.corner.rms_gc(),
            h.corner.relative(),
            h.edge.relative()
        );
        assert_eq!(h.corner.n, corner_impacts(d).len());
        assert_eq!(h.corner.refused + h.edge.refused + h.face.refused, 0);
        assert!(gc(h) < 0.3, "{}: {}", h.model.name(), gc(h));
        for p in &h.coefficients {
            let (low, high) = (h.model.bounds(), p);
            for (x, (lo, hi)) in high.iter().zip(low) {
                assert!((lo..=hi).contains(x), "{}: {p:?}", h.model.name());
            }
        }
    }
}

/// A bounce as a spatial impact is the measured one: the solver's initial
/// contact velocity is the bounce's (approaching along +z, the board below),
/// and the contact-point velocity the scores use is the solver's final one;
/// the outcome's impulse is the change of momentum the prediction makes.
#[test]
fn bounces_as_spatial_impacts_match_the_solver_contact_velocities() {
    use restitution::{Law, Outputs, Precision, solve};
    let d = data();
    for b in corner_impacts(d).into_iter().take(20) {
        let law = Law::Friction {
            restitution: 0.277,
            friction: 0.168,
        };
        let o = solve(
            &tosses::spatial_impact(b, d.fit.inertia, law, None),
            Outputs::ALL,
            Precision::Fast,
        )
        .expect("a bounce is an approaching contact");
        let initial = tosses::contact_point_velocity(&b.pre, b.r);
        assert!((o.contact_velocity.initial.normal - initial[2]).abs() < 1e-12);
        assert!((o.contact_velocity.initial.normal - b.normal_velocity_pre()).abs() < 1e-12);
        let p = tosses::predict(b, d.fit.inertia, Model::Coulomb, &[0.277, 0.168]).unwrap();
        let after = tosses::contact_point_velocity(&p, b.r);
        let t = o.contact_velocity.r#final.tangential;
        for (i, expected) in [t[0], t[1], o.contact_velocity.r#final.normal]
            .into_iter()
            .enumerate()
        {
            assert!(
                (after[i] - expected).abs() < 1e-9,
                "{after:?} vs {:?}",
                o.contact_velocity.r#final
            );
        }
        assert!((o.contact_velocity.r#final.normal + 0.277 * initial[2]).abs() < 1e-9);
        let impulse = [o.impulse.x, o.impulse.y, o.impulse.z];
        for (i, j) in impulse.into_iter().enumerate() {
            assert!((tosses::MASS * (p.velocity[i] - b.pre.velocity[i]) - j).abs() < 1e-12);
        }
    }
}
