//! Validation against experiment and published benchmarks: Kharaz, Gorham &
//! Salman (2001) (experiment, three digitizations) and Chung & Ooi (2011)
//! Tests 4–6 (DEM reference curves). Datasets and the model (a sphere in the
//! planar model, computed by the sweep engine) are in
//! `testkit/src/validation.rs`; the tables and plots in `docs/validation.md`
//! come from `cargo run --release --example validation_report`. Kharaz's
//! impact is also solved through the spatial model (a sphere in space, as is
//! and turned to arbitrary orientations) and must give the planar answers.
//!
//! Bounds. Where the model slides, it and every source share Coulomb's law,
//! so the deviations there should be digitization scatter. That scatter is
//! measured, not assumed: Chung & Ooi's Test 6 curve was digitized twice (the
//! Test 6 file and the Test 8 file's `sphere_vs_plane_test6` block), and their
//! RMS difference as a fraction of the curve's span is the scatter of one
//! digitization of these figures. DEM curves must stay within 3× that
//! fraction of each quantity's span. The experiment states its own scatter
//! (0.3°, 0.003, 5 rad/s) and, since the incidence angle itself scatters and
//! spin is measured, gets 10× that.

use crate::common::rotation::Rotation;
use crate::common::validation::{self, Dataset, Deviation, Point, Quantity};
use restitution::{BarrierOutcome, Outputs, PlanarVelocity, Precision, SpatialOutcome, solve};

fn digitization_scatter() -> f64 {
    validation::digitization_scatter().expect("Test 6 and Test 8 data")
}

/// The span of every series of `quantity` together.
fn quantity_span(d: &Dataset, quantity: Quantity) -> f64 {
    let points: Vec<Point> = d.of(quantity).flat_map(|s| s.points.iter().copied()).collect();
    validation::span(&points)
}

fn deviation(d: &Dataset, et: f64, min_x: f64, quantity: Quantity, regime: &str) -> Deviation {
    d.deviations(et, min_x)
        .into_iter()
        .find(|((q, r), _)| *q == quantity && *r == regime)
        .map(|(_, dev)| dev)
        .unwrap_or_else(|| panic!("{}: no {} points in {regime}", d.key, quantity.name()))
}

/// Deviations of `quantity` over every point at abscissa `≥ min_x`, both regimes.
fn overall(d: &Dataset, et: f64, min_x: f64, quantity: Quantity) -> Deviation {
    let mut all = Deviation::default();
    for ((q, _), dev) in d.deviations(et, min_x) {
        if q == quantity {
            all.sum_squares += dev.sum_squares;
            all.max = all.max.max(dev.max);
            all.count += dev.count;
        }
    }
    all
}

#[test]
fn every_dataset_is_present_with_its_sources() {
    let kharaz = validation::kharaz().expect("Kharaz data");
    let mut sources: Vec<&str> = kharaz.series.iter().map(|s| s.source.as_str()).collect();
    sources.sort();
    sources.dedup();
    assert_eq!(sources, ["kratos_chung_ooi", "lethe", "mfix_dem05"]);
    let count = |d: &Dataset| d.series.iter().map(|s| s.points.len()).sum::<usize>();
    assert_eq!(count(&kharaz), 79);
    let test4 = validation::chung_ooi_test4().expect("Test 4 data");
    assert_eq!((test4.series.len(), count(&test4)), (5, 65));
    let test5 = validation::chung_ooi_test5().expect("Test 5 data");
    assert_eq!((test5.series.len(), count(&test5)), (2, 30));
    let test6 = validation::chung_ooi_test6().expect("Test 6 data");
    assert_eq!((test6.series.len(), count(&test6)), (3, 51));
}

#[test]
fn the_two_digitizations_of_one_figure_agree_to_under_one_percent_of_its_span() {
    let scatter = digitization_scatter();
    assert!(scatter > 0.0 && scatter < 0.01, "scatter {scatter}");
}

/// Coulomb sliding is common to the model and every source: deviations there
/// stay within the scatter bounds, for every quantity of every dataset.
#[test]
fn where_the_model_slides_it_follows_every_dataset() {
    let scatter = digitization_scatter();
    for d in validation::datasets().expect("data") {
        for quantity in d.quantities() {
            let dev = deviation(&d, 0.0, f64::NEG_INFINITY, quantity, "sliding");
            let bound = if d.key == "kharaz2001" {
                10.0 * match quantity {
                    Quantity::ReboundAngleCentroid | Quantity::ReboundAngleContactPoint => 0.3,
                    Quantity::CentroidRatio => 0.003,
                    Quantity::SpinMagnitude => 5.0,
                    other => panic!("{other:?} is not a Kharaz quantity"),
                }
            } else {
                3.0 * scatter * quantity_span(&d, quantity)
            };
            assert!(
                dev.rms() < bound,
                "{} {}: sliding RMS {} ≥ {bound} over {} points",
                d.key,
                quantity.name(),
                dev.rms(),
                dev.count
            );
        }
    }
}

/// Kharaz: near-normal incidence the measured `V_t/v_t` lies above what the
/// model gives for any `e_t ≥ 0` (`1 − (1 + e_t)/3.5 ≤ 0.714`): the contact
/// point does not reverse there. Least squares on `V_t/v_t` with those points
/// gives a small `e_t`; without them it rises towards the 0.3–0.4 the
/// literature reports, and the rebound angles and spin improve on Coulomb
/// friction alone.
#[test]
fn kharaz_tangential_restitution_and_where_the_model_cannot_follow() {
    let d = validation::kharaz().expect("data");
    let near_normal: Vec<f64> = d
        .of(Quantity::CentroidRatio)
        .flat_map(|s| s.points.iter())
        .filter(|p| p.x > 0.0 && p.x < 4.0)
        .map(|p| p.value)
        .collect();
    assert!(!near_normal.is_empty());
    assert!(
        near_normal.iter().all(|&v| v > 1.0 - 1.0 / 3.5),
        "{near_normal:?}"
    );

    let all = d.fit_et(f64::NEG_INFINITY);
    let above_5 = d.fit_et(5.0);
    assert!((0.0..0.15).contains(&all), "e_t fitted to all incidences: {all}");
    assert!((0.2..0.35).contains(&above_5), "e_t fitted at ≥ 5°: {above_5}");
    for quantity in [Quantity::ReboundAngleCentroid, Quantity::SpinMagnitude] {
        let coulomb = overall(&d, 0.0, 5.0, quantity).rms();
        let bilinear = overall(&d, above_5, 5.0, quantity).rms();
        assert!(
            bilinear < 0.7 * coulomb,
            "{}: e_t = {above_5} gives {bilinear}, Coulomb {coulomb}",
            quantity.name()
        );
    }
}

/// The identification through the coefficient fit behind `POST
/// /v1/fits/tangential`, which regresses `V_ct` on `v_ct` (Eq 20) over the
/// points the model does not slide: `f` is the experiment's 0.092 within its
/// standard error, and `e_t` is in the 0.3–0.4 the literature reports, with
/// or without the near-normal points. It differs from the fit to `V_t/v_t`
/// (0.05) by weighting: Eq 20's residuals grow with `v_ct`, so the larger
/// incidences dominate, where the ratio gives every incidence the same weight.
#[test]
fn kharaz_through_the_coefficient_fit_gives_the_literature_e_t() {
    let d = validation::kharaz().expect("data");
    for min_deg in [0.0, 5.0] {
        let observations = validation::kharaz_observations(&d, min_deg);
        assert!(observations.len() >= 20);
        let fit = restitution::fit::tangential(&observations).expect("a fit");
        let f = fit.friction.expect("sliding points");
        assert!((f.value - 0.092).abs() < 3.0 * f.standard_error, "{f:?}");
        let et = fit.tangential_restitution.expect("non-sliding points");
        assert!((0.3..0.4).contains(&et.value), "incidence ≥ {min_deg}°: {et:?}");
        assert!(et.standard_error < 0.06, "{et:?}");
        assert!(fit.r_squared > 0.99, "{}", fit.r_squared);
    }
}

/// Test 5 (steel, `e = 1`): below the switch the DEM contact point reverses
/// with `V_ct ≈ −0.79 v_ct`, which Coulomb sticking (`V_ct = 0`) misses by up
/// to 2.8 and the bilinear model with the fitted `e_t` follows, over all
/// points, to within five digitization scatters.
#[test]
fn chung_ooi_test5_is_followed_by_tangential_restitution() {
    let d = validation::chung_ooi_test5().expect("data");
    let et = d.fit_et(f64::NEG_INFINITY);
    assert!((0.75..0.83).contains(&et), "fitted e_t = {et}");
    let scatter = digitization_scatter();
    for quantity in [Quantity::RecoilOverFriction, Quantity::SpinOverFriction] {
        let coulomb = overall(&d, 0.0, f64::NEG_INFINITY, quantity);
        let bilinear = overall(&d, et, f64::NEG_INFINITY, quantity);
        let bound = 5.0 * scatter * quantity_span(&d, quantity);
        assert!(coulomb.rms() > 1.0, "{}: Coulomb {coulomb:?}", quantity.name());
        assert!(
            bilinear.rms() < bound,
            "{}: {bilinear:?} ≥ {bound}",
            quantity.name()
        );
    }
}

/// Tests 4 and 6: in the restitution regime the DEM curves are shaped by the
/// contact's tangential compliance, which no single `e_t` reproduces: Test 6's
/// β is positive just past the switch (`f/μ_c` of 1–2.5) and negative beyond
/// (no reversal), so the fitted `e_t` stays near zero and the deviations stay
/// many scatters wide. Asserted so that a change that hides this is noticed.
#[test]
fn chung_ooi_tests_4_and_6_show_what_one_e_t_cannot_follow() {
    let scatter = digitization_scatter();
    let test6 = validation::chung_ooi_test6().expect("data");
    let et6 = test6.fit_et(f64::NEG_INFINITY);
    assert!(et6.abs() < 0.1, "Test 6 fitted e_t = {et6}");
    let beta: Vec<&Point> = test6.of(Quantity::Beta).flat_map(|s| s.points.iter()).collect();
    assert!(beta.iter().any(|p| p.x > 1.1 && p.x < 2.5 && p.value > 0.05));
    assert!(beta.iter().any(|p| p.x > 5.0 && p.value < -0.1));
    let dev = deviation(&test6, et6, f64::NEG_INFINITY, Quantity::Beta, "restitution");
    assert!(
        dev.rms() > 10.0 * scatter * quantity_span(&test6, Quantity::Beta),
        "{dev:?}"
    );

    let test4 = validation::chung_ooi_test4().expect("data");
    let et4 = test4.fit_et(f64::NEG_INFINITY);
    assert!((0.0..0.2).contains(&et4), "Test 4 fitted e_t = {et4}");
    let coulomb = deviation(
        &test4,
        0.0,
        f64::NEG_INFINITY,
        Quantity::SpinMagnitude,
        "restitution",
    );
    let bilinear = deviation(
        &test4,
        et4,
        f64::NEG_INFINITY,
        Quantity::SpinMagnitude,
        "restitution",
    );
    assert!(bilinear.rms() < coulomb.rms(), "{bilinear:?} vs {coulomb:?}");
}

/// Kharaz's model variants as the report draws them: (a) `e_t = 0`, (b) and
/// (c) `e_t` fitted to `V_t/v_t` over all incidences and at ≥ 5°, (d) `e_t`
/// from the coefficient fit.
fn kharaz_variants(d: &Dataset) -> Vec<f64> {
    let fit = restitution::fit::tangential(&validation::kharaz_observations(d, 0.0)).expect("a fit");
    vec![
        0.0,
        d.fit_et(f64::NEG_INFINITY),
        d.fit_et(5.0),
        fit.tangential_restitution.expect("non-sliding points").value,
    ]
}

/// Incidences at which the Kharaz comparison evaluates the model: each data
/// point's, and `curve_points` evenly spaced over each quantity's range (the
/// report draws its curves through 241).
fn kharaz_incidences(d: &Dataset, curve_points: usize) -> Vec<f64> {
    let mut xs = Vec::new();
    for quantity in d.quantities() {
        let data: Vec<f64> = d
            .of(quantity)
            .flat_map(|s| s.points.iter().map(|p| p.x))
            .collect();
        let lo = data.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = data.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        xs.extend(data);
        let last = (curve_points - 1) as f64;
        xs.extend((0..curve_points).map(|i| lo + (hi - lo) * (i as f64 / last)));
    }
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs
}

/// The scale each output is compared on in a rotated scene: the impact's
/// own (rounding the inputs moves each output by a few `ε` of these, however
/// small the output itself, e.g. the spin near normal incidence).
#[derive(Debug, Clone, Copy)]
struct Scales {
    /// `|v|`, for velocities.
    speed: f64,
    /// `|v| / R`, for angular velocities.
    spin: f64,
    /// `m |v|`, for impulses.
    impulse: f64,
    /// The initial kinetic energy, for energies.
    energy: f64,
    /// `f`, for `|μ|`; `T_L*` is on `[0, 1]`.
    ratio: f64,
}

/// The outputs the planar and the spatial answer share, as (name, planar,
/// spatial, scale) in the planar frame: the spatial world vectors are turned
/// back by `rotation` first.
fn shared_outputs(
    p: &BarrierOutcome,
    s: &SpatialOutcome,
    rotation: Option<&Rotation>,
    k: Scales,
) -> Vec<(&'static str, f64, f64, f64)> {
    let back = |v: [f64; 3]| rotation.map_or(v, |r| crate::common::rotation::rotate_back(r, v));
    let body = &s.bodies[0];
    let (pe, se) = (p.energy.expect("energies"), s.energy.expect("energies"));
    let mut rows = Vec::new();
    let mut vector = |names: [&'static str; 3], planar: [f64; 3], world: [f64; 3], scale: f64| {
        let v = back(world);
        for i in 0..3 {
            rows.push((names[i], planar[i], v[i], scale));
        }
    };
    let (vf, cf, ci) = (
        p.final_velocity,
        p.contact_velocity.r#final,
        p.contact_velocity.initial,
    );
    vector(
        ["V_t", "V_y", "V_n"],
        [vf.tangential, 0.0, vf.normal],
        body.velocity,
        k.speed,
    );
    vector(
        ["Ω_x", "Ω", "Ω_z"],
        [0.0, vf.angular, 0.0],
        body.angular_velocity,
        k.spin,
    );
    vector(
        ["ΔV_t", "ΔV_y", "ΔV_n"],
        [p.impulse.tangential, 0.0, p.impulse.normal],
        body.velocity_change,
        k.speed,
    );
    vector(
        ["P_t", "P_y", "P_t along n"],
        [p.impulse.tangential, 0.0, 0.0],
        s.impulse.tangential,
        k.impulse,
    );
    vector(
        ["V_ct", "V_cy", "V_ct along n"],
        [cf.tangential, 0.0, 0.0],
        s.contact_velocity.r#final.tangential,
        k.speed,
    );
    vector(
        ["v_ct", "v_cy", "v_ct along n"],
        [ci.tangential, 0.0, 0.0],
        s.contact_velocity.initial.tangential,
        k.speed,
    );
    rows.extend([
        ("P_n", p.impulse.normal, s.impulse.normal, k.impulse),
        ("V_cn", cf.normal, s.contact_velocity.r#final.normal, k.speed),
        ("v_cn", ci.normal, s.contact_velocity.initial.normal, k.speed),
        ("|μ|", p.impulse_ratio.abs(), s.impulse_ratio, k.ratio),
        ("T_initial", pe.initial, se.initial, k.energy),
        ("T_final", pe.r#final, se.r#final, k.energy),
        ("T_L", pe.loss, se.loss, k.energy),
        ("T_M", pe.max_loss, se.max_loss, k.energy),
        ("T_L*", pe.normalized_loss, se.normalized_loss, 1.0),
    ]);
    rows
}

/// The scales of Kharaz's impact at initial velocities `v` (no spin, unit mass).
fn scales(d: &Dataset, v: &PlanarVelocity) -> Scales {
    let speed = v.normal.hypot(v.tangential);
    Scales {
        speed,
        spin: speed / d.radius,
        impulse: speed,
        energy: 0.5 * speed * speed,
        ratio: d.friction,
    }
}

/// Kharaz through the spatial endpoint: every data point and every point of
/// the model curves (a)–(d), solved as a sphere in space (the motion in the
/// x–z plane, `n` along z, `I = 2/5 m R²` as a tensor), gives the planar
/// answer bit for bit in exact precision, on every output the two share
/// (final velocities and spin, velocity changes, impulses, contact-point
/// velocities, `|μ|`, energies) and in the regime; and the spatial answer's
/// quantities are the ones the tables and plots were drawn from.
#[test]
fn kharaz_through_the_spatial_endpoint_is_the_planar_answer_bit_for_bit() {
    let d = validation::kharaz().expect("data");
    let xs = kharaz_incidences(&d, 241);
    assert!(xs.len() > 300, "{} incidences", xs.len());
    let drive = d.drive(Quantity::CentroidRatio).0;
    let mut regimes = std::collections::BTreeSet::new();
    for et in kharaz_variants(&d) {
        for &x in &xs {
            let v = d.velocity(drive, x);
            let p = solve(&d.planar(v, et), Outputs::ALL, Precision::Exact).expect("a planar answer");
            let s = solve(&d.spatial(v, et, None), Outputs::ALL, Precision::Exact).expect("a spatial answer");
            assert_eq!(p.regime, s.regime, "e_t = {et}, incidence {x}°");
            regimes.insert(p.regime.as_str());
            for (name, a, b, _) in shared_outputs(&p, &s, None, scales(&d, &v)) {
                assert!(
                    a.to_bits() == b.to_bits() || (a == 0.0 && b == 0.0),
                    "{name}: planar {a:e}, spatial {b:e} at e_t = {et}, incidence {x}°"
                );
            }
        }
        // The tables' numbers (the sweep engine, fast precision) are the spatial answer's.
        for quantity in d.quantities() {
            for series in d.of(quantity) {
                let at: Vec<f64> = series.points.iter().map(|p| p.x).collect();
                for (&x, predicted) in at.iter().zip(d.predict(quantity, et, &at)) {
                    let Some(predicted) = predicted else { continue };
                    let v = d.velocity(drive, x);
                    let s =
                        solve(&d.spatial(v, et, None), Outputs::ALL, Precision::Exact).expect("an answer");
                    let last = PlanarVelocity {
                        normal: s.bodies[0].velocity[2],
                        tangential: s.bodies[0].velocity[0],
                        angular: s.bodies[0].angular_velocity[1],
                    };
                    let value = d.value(quantity, &v, &last, s.contact_velocity.r#final.tangential[0]);
                    assert!(
                        (value - predicted.value).abs() <= 1e-12 * predicted.value.abs().max(1.0),
                        "{}: space {value}, sweep {} at e_t = {et}, incidence {x}°",
                        quantity.name(),
                        predicted.value
                    );
                }
            }
        }
    }
    // Both branches of the bilinear law are crossed.
    assert_eq!(
        regimes.into_iter().collect::<Vec<_>>(),
        ["restitution", "sliding"]
    );
}

/// The bound of [`kharaz_in_a_rotated_scene_is_the_planar_answer_to_a_few_ulps`],
/// in units of `ε = 2⁻⁵²` of each output's [`Scales`]. Rounding the turned
/// inputs (three-term sums, a few `ε` of `|v|`) and turning the answer back
/// gave at most about 5 `ε` here (4 rotations, 241 curve points); 16 leaves room.
const ROTATED_BOUND: f64 = 16.0;

/// The same with the whole scene turned to an arbitrary orientation (one
/// rotation per variant; velocities, spin, contact point, normal and the
/// tensor `r I rᵀ` are turned, each input rounded): after turning the spatial
/// vectors back, every shared output is within [`ROTATED_BOUND`] `ε` of the
/// impact's own scale (speed `|v|`, spin `|v|/R`, impulse `m|v|`, initial
/// energy, `f` for `|μ|`, 1 for `T_L*`), and the regime is the same. Exact
/// precision, so the model adds no rounding of its own. Every data point, and
/// the curves through 31 points each (exact solves of rounded inputs are slower).
#[test]
fn kharaz_in_a_rotated_scene_is_the_planar_answer_to_a_few_ulps() {
    let d = validation::kharaz().expect("data");
    let xs = kharaz_incidences(&d, 31);
    let drive = d.drive(Quantity::CentroidRatio).0;
    let quaternions = [
        [0.3, -0.5, 0.7, 0.2],
        [0.9, 0.1, -0.3, 0.6],
        [-0.2, 0.8, 0.4, -0.5],
        [0.5, 0.5, -0.6, -0.1],
    ];
    for (et, q) in kharaz_variants(&d).into_iter().zip(quaternions) {
        let r = crate::common::rotation::from_quaternion(q);
        for &x in &xs {
            let v = d.velocity(drive, x);
            let p = solve(&d.planar(v, et), Outputs::ALL, Precision::Exact).expect("a planar answer");
            let s =
                solve(&d.spatial(v, et, Some(&r)), Outputs::ALL, Precision::Exact).expect("a spatial answer");
            assert_eq!(p.regime, s.regime, "e_t = {et}, incidence {x}°");
            for (name, a, b, scale) in shared_outputs(&p, &s, Some(&r), scales(&d, &v)) {
                let error = (a - b).abs() / (f64::EPSILON * scale);
                let error = if a == b { 0.0 } else { error };
                assert!(
                    error <= ROTATED_BOUND,
                    "{name}: planar {a:e}, spatial {b:e} ({error:.1} ε of {scale:e}) at e_t = {et}, incidence {x}°"
                );
            }
        }
    }
}
