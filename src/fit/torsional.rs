//! The torsional bilinear model (section 4, Eqs 28–31) fitted to measured impacts.

use super::{Estimate, FitError, through_origin};
use crate::model::torsional::{self as model, Torsion};
use crate::outcome::{TorsionalOutcome, TorsionalRegime};

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
    // Residuals and regimes are the model's own answers for the fitted
    // coefficients (evaluated as they are, even outside their ranges).
    let predicted: Vec<Option<TorsionalOutcome>> = observations
        .iter()
        .map(|o| {
            let torsion = Torsion {
                m: o.mass,
                i_n: o.normal_inertia,
                vn: o.normal_velocity,
                w: o.spin,
                e: restitution.value,
                ez,
                mu_z: muz.unwrap_or(0.0),
                rho: o.pitch_radius,
            };
            let mut outcome = TorsionalOutcome::default();
            model::torsional::<f64>(&torsion, false, &mut outcome)
                .ok()
                .map(|()| outcome)
        })
        .collect();
    let sliding: Vec<bool> = predicted
        .iter()
        .zip(&sliding)
        .map(|(p, &split)| p.map_or(split, |p| p.regime == TorsionalRegime::Sliding))
        .collect();
    let residuals: Vec<f64> = observations
        .iter()
        .zip(&predicted)
        .map(|(o, p)| p.map_or(f64::NAN, |p| o.final_spin - p.final_spin))
        .collect();
    let estimates = [Some(restitution), Some(torsional_restitution), torsional_friction];
    if estimates.iter().flatten().any(|k| !k.value.is_finite()) {
        return Err(FitError::Degenerate(
            "the observations' magnitudes overflow double precision",
        ));
    }
    let r_squared = super::r_squared(observations.iter().map(|o| o.final_spin), &residuals);
    Ok(TorsionalFit {
        restitution,
        torsional_restitution,
        torsional_friction,
        sliding,
        residuals,
        r_squared,
    })
}

#[cfg(test)]
mod torsional_tests {
    use super::*;
    use crate::impact::{Precision, TorsionalImpact, solve};
    use crate::outcome::Outputs;

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
                let o = solve(&impact, Outputs::MINIMAL, Precision::Fast).unwrap();
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
