//! Coefficient identification from measured impacts: least squares on the
//! bilinear tangential model (section 3).
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

use thiserror::Error;

use crate::planar::{Outputs, Regime};
use crate::scene::{Body, Contact, PlanarScene, PlanarVelocity};
use crate::tangential;

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

/// An estimated coefficient and its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The least-squares value.
    pub value: f64,
    /// Its standard error (0 when the points fit exactly; `NaN` from a single point).
    pub standard_error: f64,
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

/// Why a set of observations cannot be fitted.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FitError {
    /// Fewer observations than coefficients.
    #[error("at least {needed} observations are needed, got {got}")]
    TooFewPoints {
        /// The minimum.
        needed: usize,
        /// How many were given.
        got: usize,
    },
    /// An observation is not an impact of the model (invalid body, not
    /// approaching, no positive normal impulse, non-finite numbers).
    #[error("observation {index} is not an impact: {why}")]
    NotAnImpact {
        /// Its index.
        index: usize,
        /// Why.
        why: String,
    },
    /// The data cannot determine the coefficients (all initial contact
    /// velocities tangentially zero, for instance).
    #[error("the observations cannot determine the coefficients: {0}")]
    Degenerate(&'static str),
}

/// What one observation contributes.
struct Point {
    scene: PlanarScene,
    vcn: f64,
    vct: f64,
    final_vcn: f64,
    final_vct: f64,
    /// `−sgn(v_ct) μ`: the friction coefficient if the point slides.
    slide: f64,
}

fn prepare(index: usize, o: &Observation) -> Result<Point, FitError> {
    let bad = |why: String| FitError::NotAnImpact { index, why };
    let scene = PlanarScene::new(o.body, o.contact, o.initial).map_err(|e| bad(e.to_string()))?;
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

/// Least squares of `y = −k x` through the origin: `(k, standard error)`.
fn through_origin(pairs: impl Iterator<Item = (f64, f64)> + Clone) -> Option<Estimate> {
    let (sxy, sxx, n) = pairs.clone().fold((0.0, 0.0, 0usize), |(a, b, n), (x, y)| {
        (a + x * y, b + x * x, n + 1)
    });
    if n == 0 || sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let k = -sxy / sxx;
    let ss: f64 = pairs.map(|(x, y)| (y + k * x).powi(2)).sum();
    let se = if n > 1 {
        (ss / (n - 1) as f64 / sxx).sqrt()
    } else {
        f64::NAN
    };
    Some(Estimate {
        value: k,
        standard_error: se,
    })
}

fn mean(values: &[f64]) -> Option<Estimate> {
    if values.is_empty() {
        return None;
    }
    let n = values.len() as f64;
    let m = values.iter().sum::<f64>() / n;
    let se = if values.len() > 1 {
        (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt()
    } else {
        f64::NAN
    };
    Some(Estimate {
        value: m,
        standard_error: se,
    })
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
            .map(|p| {
                tangential::solve(&p.scene, e, f, et.clamp(-1.0, 1.0), Outputs::MINIMAL)
                    .map_or(Regime::Sliding, |o| o.regime)
            })
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
            tangential::solve(&p.scene, e, f, et.clamp(-1.0, 1.0), Outputs::MINIMAL)
                .map_or(f64::NAN, |o| p.final_vct - o.contact_velocity.r#final.tangential)
        })
        .collect();
    let mean_vct = points.iter().map(|p| p.final_vct).sum::<f64>() / points.len() as f64;
    let ss_tot: f64 = points.iter().map(|p| (p.final_vct - mean_vct).powi(2)).sum();
    let ss_res: f64 = residuals.iter().map(|r| r * r).sum();
    Ok(TangentialFit {
        restitution,
        friction,
        tangential_restitution,
        regimes,
        residuals,
        r_squared: if ss_tot > 0.0 {
            1.0 - ss_res / ss_tot
        } else {
            f64::NAN
        },
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
        let mut state = 0x1234_5678_u64;
        let mut jitter = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * noise
        };
        (0..40)
            .map(|i| {
                let initial = PlanarVelocity {
                    normal: -1.0,
                    tangential: 0.05 + 0.06 * f64::from(i),
                    angular: 0.0,
                };
                let scene = PlanarScene::new(body, contact, initial).unwrap();
                let o = tangential::solve(&scene, e, f, et, Outputs::MINIMAL).unwrap();
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

/// One measured torsional impact: a body of known mass, inertia about the
/// normal and pitch radius, its normal velocity and spin before and after.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionalObservation {
    /// Mass `m`.
    pub mass: f64,
    /// Moment of inertia about the normal `I_n`.
    pub normal_inertia: f64,
    /// Pitch radius `ρ_p` of the torsional friction impulse.
    pub pitch_radius: f64,
    /// `v_n < 0`.
    pub normal_velocity: f64,
    /// `ω_n`.
    pub spin: f64,
    /// `V_n`.
    pub final_normal_velocity: f64,
    /// `Ω_n`.
    pub final_spin: f64,
}

/// The least-squares fit of the torsional model for one split of the points.
struct SplitFit {
    ez: f64,
    muz: Option<f64>,
    inverse: nalgebra::Matrix2<f64>,
    sigma2: f64,
    ss: f64,
}

/// The fitted torsional bilinear model (Eqs 28–31).
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionalFit {
    /// `e`.
    pub restitution: Estimate,
    /// `e_z`.
    pub torsional_restitution: Estimate,
    /// `μ_z`, when at least one point slides.
    pub torsional_friction: Option<Estimate>,
    /// Whether each observation slides (`|ω_n| > ω_s`) under the fitted model.
    pub sliding: Vec<bool>,
    /// Observed minus fitted `Ω_n`, in input order.
    pub residuals: Vec<f64>,
    /// `1 − SS_res/SS_tot` of `Ω_n`.
    pub r_squared: f64,
}

/// Fits `e`, `e_z` and `μ_z` of the torsional model to at least three observations.
///
/// Given which points slide, `Ω_n` is linear in `(e_z, μ_z)`: restitution
/// points `Ω_n = −e_z ω_n` (Eq 28), sliding points
/// `Ω_n − ω_n = −e_z ω_n − μ_z sgn(ω_n) q` with `q = ρ_p m (1 + e)|v_n| / I_n`
/// (Eq 30); the 2×2 normal equations are solved with nalgebra and the
/// standard errors come from `σ² (XᵀX)⁻¹`. Every split of the points by
/// `|ω_n|/q` (the branches meet at `ω_s = μ_z q`, Eq 31) is tried and the one
/// with the least squared residual is the answer.
pub fn torsional(observations: &[TorsionalObservation]) -> Result<TorsionalFit, FitError> {
    use nalgebra::{Matrix2, Vector2};
    if observations.len() < 3 {
        return Err(FitError::TooFewPoints {
            needed: 3,
            got: observations.len(),
        });
    }
    for (index, o) in observations.iter().enumerate() {
        let bad = |why: &str| FitError::NotAnImpact {
            index,
            why: why.to_owned(),
        };
        let all = [
            o.mass,
            o.normal_inertia,
            o.pitch_radius,
            o.normal_velocity,
            o.spin,
            o.final_normal_velocity,
            o.final_spin,
        ];
        if !all.iter().all(|x| x.is_finite()) {
            return Err(bad("a number is not finite"));
        }
        if o.mass <= 0.0 || o.normal_inertia <= 0.0 || o.pitch_radius <= 0.0 {
            return Err(bad("mass, normal inertia and pitch radius must be positive"));
        }
        if o.normal_velocity >= 0.0 {
            return Err(bad("the body is not approaching (v_n ≥ 0)"));
        }
    }
    let restitution = through_origin(
        observations
            .iter()
            .map(|o| (o.normal_velocity, o.final_normal_velocity)),
    )
    .ok_or(FitError::Degenerate("no normal approach velocity"))?;
    let e = restitution.value.clamp(0.0, 1.0);
    if observations.iter().all(|o| o.spin == 0.0) {
        return Err(FitError::Degenerate(
            "every initial spin is 0, so no torsional coefficient shows",
        ));
    }
    let q: Vec<f64> = observations
        .iter()
        .map(|o| o.pitch_radius * o.mass * (1.0 + e) * -o.normal_velocity / o.normal_inertia)
        .collect();
    let sign = |w: f64| if w < 0.0 { -1.0 } else { 1.0 };
    // Rows (target, [x_ez, x_muz]) for a classification.
    let rows = |sliding: &[bool]| -> Vec<(f64, [f64; 2])> {
        observations
            .iter()
            .zip(sliding)
            .zip(&q)
            .map(|((o, &s), &q)| {
                if s {
                    (o.final_spin - o.spin, [-o.spin, -sign(o.spin) * q])
                } else {
                    (o.final_spin, [-o.spin, 0.0])
                }
            })
            .collect()
    };
    // The least-squares solution for one classification: (e_z, μ_z, (XᵀX)⁻¹, σ², SS).
    let solve = |sliding: &[bool]| -> Option<SplitFit> {
        let rows = rows(sliding);
        let any_sliding = sliding.iter().any(|&s| s);
        let mut xtx = Matrix2::zeros();
        let mut xty = Vector2::zeros();
        for (y, x) in &rows {
            let x = Vector2::new(x[0], x[1]);
            xtx += x * x.transpose();
            xty += x * *y;
        }
        let (ez, muz, inverse) = if any_sliding {
            let inverse = xtx.try_inverse()?;
            let beta = inverse * xty;
            (beta[0], Some(beta[1]), inverse)
        } else {
            let sxx = xtx[(0, 0)];
            if sxx.is_nan() || sxx <= 0.0 {
                return None;
            }
            (xty[0] / sxx, None, Matrix2::new(1.0 / sxx, 0.0, 0.0, 0.0))
        };
        let ss: f64 = rows
            .iter()
            .map(|(y, x)| (y - x[0] * ez - x[1] * muz.unwrap_or(0.0)).powi(2))
            .sum();
        let unknowns = if muz.is_some() { 2 } else { 1 };
        let sigma2 = if rows.len() > unknowns {
            ss / (rows.len() - unknowns) as f64
        } else {
            f64::NAN
        };
        Some(SplitFit {
            ez,
            muz,
            inverse,
            sigma2,
            ss,
        })
    };
    // The branches split the points by |ω_n| / q at the switch μ_z (Eq 31). As in
    // threshold regression, every split is tried and the one with the least
    // squared residual wins: a global, order-free search rather than an
    // iteration that can settle on a wrong split.
    let ratio: Vec<f64> = observations
        .iter()
        .zip(&q)
        .map(|(o, q)| o.spin.abs() / q)
        .collect();
    let mut thresholds: Vec<f64> = ratio.clone();
    thresholds.push(-1.0);
    thresholds.sort_by(f64::total_cmp);
    thresholds.dedup();
    let mut best: Option<(Vec<bool>, SplitFit)> = None;
    for t in thresholds {
        let split: Vec<bool> = ratio.iter().map(|r| *r > t).collect();
        let Some(candidate) = solve(&split) else {
            continue;
        };
        if best.as_ref().is_none_or(|(_, b)| candidate.ss < b.ss) {
            best = Some((split, candidate));
        }
    }
    let Some((sliding, solution)) = best else {
        return Err(FitError::Degenerate("the spins cannot separate e_z from μ_z"));
    };
    let SplitFit {
        ez,
        muz,
        inverse,
        sigma2,
        ..
    } = solution;
    let torsional_restitution = Estimate {
        value: ez,
        standard_error: (sigma2 * inverse[(0, 0)]).sqrt(),
    };
    let torsional_friction = muz.map(|m| Estimate {
        value: m,
        standard_error: (sigma2 * inverse[(1, 1)]).sqrt(),
    });
    let residuals: Vec<f64> = observations
        .iter()
        .zip(&sliding)
        .zip(&q)
        .map(|((o, &s), &q)| {
            let fitted = if s {
                (1.0 - ez) * o.spin - sign(o.spin) * muz.unwrap_or(0.0) * q
            } else {
                -ez * o.spin
            };
            o.final_spin - fitted
        })
        .collect();
    let estimates = [Some(restitution), Some(torsional_restitution), torsional_friction];
    if estimates.iter().flatten().any(|k| !k.value.is_finite()) {
        return Err(FitError::Degenerate(
            "the observations' magnitudes overflow double precision",
        ));
    }
    let n = observations.len() as f64;
    let mean = observations.iter().map(|o| o.final_spin).sum::<f64>() / n;
    let ss_tot: f64 = observations.iter().map(|o| (o.final_spin - mean).powi(2)).sum();
    let ss_res: f64 = residuals.iter().map(|r| r * r).sum();
    Ok(TorsionalFit {
        restitution,
        torsional_restitution,
        torsional_friction,
        sliding,
        residuals,
        r_squared: if ss_tot > 0.0 {
            1.0 - ss_res / ss_tot
        } else {
            f64::NAN
        },
    })
}

#[cfg(test)]
mod torsional_tests {
    use super::*;
    use crate::torsional::{self, TorsionalImpact};

    fn observations(noise: f64) -> Vec<TorsionalObservation> {
        (0..25)
            .map(|i| {
                let spin = -60.0 + 5.0 * f64::from(i);
                let impact = TorsionalImpact {
                    mass: 0.1,
                    normal_inertia: 3.6e-5,
                    normal_velocity: -3.0,
                    spin,
                    restitution: 0.8,
                    torsional_restitution: 0.2,
                    torsional_friction: 0.3,
                    pitch_radius: 0.005,
                };
                let o = torsional::solve(&impact, false).unwrap();
                TorsionalObservation {
                    mass: 0.1,
                    normal_inertia: 3.6e-5,
                    pitch_radius: 0.005,
                    normal_velocity: -3.0,
                    spin,
                    final_normal_velocity: o.final_normal_velocity,
                    final_spin: o.final_spin + noise * (f64::from(i) * 1.7).sin(),
                }
            })
            .collect()
    }

    #[test]
    fn torsional_coefficients_are_recovered() {
        let fit = torsional(&observations(0.0)).unwrap();
        assert!((fit.restitution.value - 0.8).abs() < 1e-12);
        assert!((fit.torsional_restitution.value - 0.2).abs() < 1e-9);
        assert!((fit.torsional_friction.unwrap().value - 0.3).abs() < 1e-9);
        assert!(fit.sliding.iter().any(|&s| s) && fit.sliding.iter().any(|&s| !s));
        let noisy = torsional(&observations(0.2)).unwrap();
        for (estimate, truth) in [
            (noisy.torsional_restitution, 0.2),
            (noisy.torsional_friction.unwrap(), 0.3),
        ] {
            assert!(
                (estimate.value - truth).abs() <= 3.0 * estimate.standard_error,
                "{estimate:?} vs {truth}"
            );
        }
        assert!(matches!(
            torsional(&observations(0.0)[..2]),
            Err(FitError::TooFewPoints { .. })
        ));
    }
}
