//! The bilinear tangential model (section 3) fitted to measured planar impacts.
//!
//! Each observation gives the initial and final velocities of a body of known
//! geometry. With `Δn = V_n − v_n = P_n/m`, `Δt = V_t − v_t = P_t/m`:
//!
//! - `e` from `V_cn = −e v_cn` (Eq 1), least squares through the origin;
//! - a sliding point has `μ = P_t/P_n = −f sgn(v_ct)`, so `s = −sgn(v_ct) Δt/Δn`
//!   estimates `f` (its mean over the sliding points);
//! - a restitution point has `V_ct = −e_t v_ct` (Eq 20), least squares through
//!   the origin over the restitution points.
//!
//! Which points slide is itself decided by the model: starting from the median
//! of `s`, the points are classified with the current `(e, f, e_t)` (the
//! bilinear switch `|μ_et| ≤ f`) and the coefficients refitted until the
//! classification no longer changes. The result does not depend on the order
//! of the observations beyond rounding.

use super::{Estimate, FitError, mean, through_origin};
use crate::impact::{BarrierImpact, Law, Precision, solve};
use crate::outcome::{BarrierOutcome, Outputs, Regime};
use crate::scene::{BarrierScene, Body, Contact, PlanarVelocity};

/// One measured planar impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// The body.
    pub body: Body,
    /// Contact geometry.
    pub contact: Contact,
    /// Velocities before the impact.
    pub initial: PlanarVelocity,
    /// Velocities after the impact.
    pub r#final: PlanarVelocity,
}

/// The fitted bilinear model.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentialFit {
    /// `e`.
    pub restitution: Estimate,
    /// `f`, when at least one point slides.
    pub friction: Option<Estimate>,
    /// `e_t`, when at least one point is in the restitution regime.
    pub tangential_restitution: Option<Estimate>,
    /// The regime of each observation under the fitted model, in input order.
    pub regimes: Vec<Regime>,
    /// Observed minus fitted `V_ct`, in input order.
    pub residuals: Vec<f64>,
    /// `1 − SS_res/SS_tot` of `V_ct`.
    pub r_squared: f64,
    /// Classification rounds until the regimes settled.
    pub iterations: usize,
}

/// What one observation contributes.
struct Point {
    scene: BarrierScene,
    vcn: f64,
    vct: f64,
    final_vcn: f64,
    final_vct: f64,
    /// `−sgn(v_ct) μ`: the friction coefficient if the point slides.
    slide: f64,
}

fn prepare(index: usize, o: &Observation) -> Result<Point, FitError> {
    let bad = |why: String| FitError::NotAnImpact { index, why };
    let scene = BarrierScene::new(o.body, o.contact, o.initial).map_err(|e| bad(e.to_string()))?;
    let f = o.r#final;
    if ![f.normal, f.tangential, f.angular].iter().all(|x| x.is_finite()) {
        return Err(bad("a final velocity is not finite".to_owned()));
    }
    let c = scene.contact_velocity();
    let d = o.contact;
    let final_vcn = d.tangential_offset.mul_add(f.angular, f.normal);
    let final_vct = (-d.normal_offset).mul_add(f.angular, f.tangential);
    let dn = f.normal - o.initial.normal;
    let dt = f.tangential - o.initial.tangential;
    if dn.is_nan() || dn <= 0.0 {
        return Err(bad(format!("the normal impulse P_n/m = {dn} is not positive")));
    }
    let sign = if c.tangential < 0.0 { -1.0 } else { 1.0 };
    Ok(Point {
        scene,
        vcn: c.normal,
        vct: c.tangential,
        final_vcn,
        final_vct,
        slide: -sign * dt / dn,
    })
}

/// The model's answer for a measured scene under fitted coefficients.
fn predict(scene: &BarrierScene, e: f64, f: f64, et: f64) -> crate::error::Result<BarrierOutcome> {
    let impact = BarrierImpact::in_scene(
        scene,
        Law::TangentialRestitution {
            restitution: e,
            friction: f,
            tangential_restitution: et,
        },
    );
    solve(&impact, Outputs::MINIMAL, Precision::Fast)
}

/// Fits `e`, `f` and `e_t` of the bilinear tangential model to `observations`
/// (at least three).
pub fn tangential(observations: &[Observation]) -> Result<TangentialFit, FitError> {
    if observations.len() < 3 {
        return Err(FitError::TooFewPoints {
            needed: 3,
            got: observations.len(),
        });
    }
    let points = observations
        .iter()
        .enumerate()
        .map(|(i, o)| prepare(i, o))
        .collect::<Result<Vec<_>, _>>()?;
    let restitution = through_origin(points.iter().map(|p| (p.vcn, p.final_vcn)))
        .ok_or(FitError::Degenerate("no normal approach velocity"))?;
    if points.iter().all(|p| p.vct == 0.0) {
        return Err(FitError::Degenerate(
            "every initial tangential contact velocity is 0, so no tangential coefficient shows",
        ));
    }
    let e = restitution.value.clamp(0.0, 1.0);

    // Start: the median of the per-point friction estimates, e_t from the points below it.
    let mut slides: Vec<f64> = points.iter().map(|p| p.slide).collect();
    slides.sort_by(f64::total_cmp);
    let mut f = slides[slides.len() / 2].max(0.0);
    let mut et = through_origin(
        points
            .iter()
            .filter(|p| p.slide < f)
            .map(|p| (p.vct, p.final_vct)),
    )
    .map_or(0.0, |k| k.value);
    let mut regimes = vec![Regime::Sliding; points.len()];
    let mut iterations = 0;
    let (mut friction, mut tangential_restitution);
    loop {
        iterations += 1;
        let classified: Vec<Regime> = points
            .iter()
            .map(|p| predict(&p.scene, e, f, et.clamp(-1.0, 1.0)).map_or(Regime::Sliding, |o| o.regime))
            .collect();
        let sliding: Vec<f64> = points
            .iter()
            .zip(&classified)
            .filter(|(_, r)| **r == Regime::Sliding)
            .map(|(p, _)| p.slide)
            .collect();
        friction = mean(&sliding);
        tangential_restitution = through_origin(
            points
                .iter()
                .zip(&classified)
                .filter(|(_, r)| **r != Regime::Sliding)
                .map(|(p, _)| (p.vct, p.final_vct)),
        );
        let settled = classified == regimes;
        regimes = classified;
        if let Some(k) = friction {
            f = k.value.max(0.0);
        } else if let Some(max) = slides.last() {
            // No point slides: f is only bounded below; keep every point capped.
            f = f.max(*max);
        }
        if let Some(k) = tangential_restitution {
            et = k.value;
        }
        if settled || iterations >= 50 {
            break;
        }
    }
    let estimates = [Some(restitution), friction, tangential_restitution];
    if estimates
        .iter()
        .flatten()
        .any(|k| !k.value.is_finite() || k.standard_error.is_infinite())
    {
        return Err(FitError::Degenerate(
            "the observations' magnitudes overflow double precision",
        ));
    }
    let residuals: Vec<f64> = points
        .iter()
        .map(|p| {
            predict(&p.scene, e, f, et.clamp(-1.0, 1.0))
                .map_or(f64::NAN, |o| p.final_vct - o.contact_velocity.r#final.tangential)
        })
        .collect();
    let r_squared = super::r_squared(points.iter().map(|p| p.final_vct), &residuals);
    Ok(TangentialFit {
        restitution,
        friction,
        tangential_restitution,
        regimes,
        residuals,
        r_squared,
        iterations,
    })
}

/// The impulse ratio read off the sliding line's intercept, as Brach does for
/// Maw's disc (section 3): for a central contact (`d_c = 0`) the sliding line
/// is `V_ct/|v_n| = v_ct/|v_n| + μ (1 + e)(1 + λ)` (Eq 18 with `v_n < 0`), so an
/// intercept `a` gives `|μ| = −a / ((1 + e)(1 + λ))`, `λ = d_d²/k²`.
pub fn impulse_ratio_from_intercept(intercept: f64, restitution: f64, lambda: f64) -> f64 {
    -intercept / ((1.0 + restitution) * (1.0 + lambda))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A disc like Maw's, sliding and sticking across a sweep of v_t, with noise.
    fn synthetic(e: f64, f: f64, et: f64, noise: f64) -> Vec<Observation> {
        let body = Body::new(1.0, 0.00125).unwrap();
        let contact = Contact::central(0.05);
        let mut rng = crate::rng::Rng::new(0x1234_5678);
        let mut jitter = move || rng.range(-noise, noise);
        (0..40)
            .map(|i| {
                let initial = PlanarVelocity {
                    normal: -1.0,
                    tangential: 0.05 + 0.06 * f64::from(i),
                    angular: 0.0,
                };
                let scene = BarrierScene::new(body, contact, initial).unwrap();
                let o = predict(&scene, e, f, et).unwrap();
                let v = o.final_velocity;
                Observation {
                    body,
                    contact,
                    initial,
                    r#final: PlanarVelocity {
                        normal: v.normal + jitter(),
                        tangential: v.tangential + jitter(),
                        angular: v.angular + 20.0 * jitter(),
                    },
                }
            })
            .collect()
    }

    #[test]
    fn exact_data_give_back_the_coefficients() {
        let fit = tangential(&synthetic(0.93, 0.123, 0.34, 0.0)).unwrap();
        assert!((fit.restitution.value - 0.93).abs() < 1e-12);
        assert!((fit.friction.unwrap().value - 0.123).abs() < 1e-12);
        assert!((fit.tangential_restitution.unwrap().value - 0.34).abs() < 1e-12);
        assert!(fit.residuals.iter().all(|r| r.abs() < 1e-12));
        assert!(fit.regimes.contains(&Regime::Sliding) && fit.regimes.contains(&Regime::Restitution));
    }

    #[test]
    fn noisy_data_recover_the_coefficients_within_their_standard_errors() {
        let fit = tangential(&synthetic(0.93, 0.123, 0.34, 0.002)).unwrap();
        for (estimate, truth) in [
            (fit.restitution, 0.93),
            (fit.friction.unwrap(), 0.123),
            (fit.tangential_restitution.unwrap(), 0.34),
        ] {
            assert!(
                (estimate.value - truth).abs() <= 3.0 * estimate.standard_error,
                "{estimate:?} vs {truth}"
            );
            assert!(estimate.standard_error > 0.0);
        }
        assert!(fit.r_squared > 0.99);
        // The order of the observations does not matter.
        let mut reversed = synthetic(0.93, 0.123, 0.34, 0.002);
        reversed.reverse();
        let again = tangential(&reversed).unwrap();
        assert!((again.friction.unwrap().value - fit.friction.unwrap().value).abs() < 1e-12);
    }

    #[test]
    fn too_few_or_degenerate_observations_are_refused() {
        let data = synthetic(0.93, 0.123, 0.34, 0.0);
        assert_eq!(
            tangential(&data[..2]),
            Err(FitError::TooFewPoints { needed: 3, got: 2 })
        );
        let mut normal = data[..5].to_vec();
        for o in &mut normal {
            o.initial.tangential = 0.0;
            o.r#final.tangential = 0.0;
        }
        assert!(matches!(tangential(&normal), Err(FitError::Degenerate(_))));
        let mut separating = data[..5].to_vec();
        separating[3].initial.normal = 1.0;
        assert!(matches!(
            tangential(&separating),
            Err(FitError::NotAnImpact { index: 3, .. })
        ));
    }

    #[test]
    fn maw_intercept_gives_brachs_impulse_ratio() {
        // Intercept −0.72 at e = 0.93 for a disc (λ = 2): μ = 0.124.
        let mu = impulse_ratio_from_intercept(-0.72, 0.93, 2.0);
        assert!((mu - 0.124).abs() < 5e-4, "{mu}");
    }
}
