//! Identification of a planar contact (what accident reconstruction is for):
//! from the pre-impact scene and the measured velocity changes of the bodies,
//! the impulse, and from it `e`, `μ` and, if asked, the normal's direction.
//!
//! The velocity changes are linear in the impulse `P` on A (momentum
//! equations): `ΔV_A = P/m_A`, `ΔΩ_A = (r_A × P)/I_A`, and the opposite over
//! `m_B`, `I_B` for B. So `P` is the weighted least-squares solution of
//! `y = G P` (weights `1/σ²`, the stated uncertainties taken as standard
//! deviations), with covariance `(Gᵀ Σ⁻¹ G)⁻¹`. Then, with `U = u + W P` the
//! final relative contact velocity (`W` of `docs/physics.md`):
//! `μ = P·t̂ / P·n̂` and `e = −U·n̂ / u·n̂` for a given normal; for a fitted
//! normal the contact is taken to end sticking (`U·t̂ = 0`, the common
//! velocity of reconstruction's "full" impact), so `n̂ = U/|U|` and
//! `e = |U|² / (−u·U)`, `μ = μ_c`. Standard errors propagate the covariance of
//! `P` through these functions (central differences).

use nalgebra::{Matrix2, Vector2};

use super::{Estimate, FitError};
use crate::impact::{BodiesImpact, Lamina, Law, PlanarContact, Precision, solve};
use crate::outcome::Outputs;

/// A measured value and its standard uncertainty (`> 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// The value.
    pub value: f64,
    /// Its standard uncertainty.
    pub uncertainty: f64,
}

/// The measured change of one body's motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredChange {
    /// `ΔV = V − v` of the mass centre, x and y.
    pub velocity_change: [Measured; 2],
    /// `ΔΩ = Ω − ω`.
    pub angular_velocity_change: Measured,
}

/// The identified contact.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarFit {
    /// `e = −U_n / u_n`.
    pub restitution: Estimate,
    /// `μ = P_t / P_n` along `t̂ = ẑ × n̂`.
    pub impulse_ratio: Estimate,
    /// The fitted normal (a unit vector) and its angle from `x` in radians,
    /// when asked for.
    pub normal: Option<([f64; 2], Estimate)>,
    /// The impulse on A in world axes.
    pub impulse: [f64; 2],
    /// Its standard errors.
    pub impulse_standard_error: [f64; 2],
    /// Measured minus fitted, in the order body, `x`, `y`, angular.
    pub residuals: Vec<f64>,
    /// `Σ (residual/σ)²`.
    pub chi_squared: f64,
    /// Measurements minus fitted parameters.
    pub degrees_of_freedom: usize,
}

/// The velocity-change rows of one body: `ΔV_x`, `ΔV_y`, `ΔΩ` per unit `P`.
fn rows(l: &Lamina, point: [f64; 2], sign: f64) -> [[f64; 2]; 3] {
    let r = [point[0] - l.position[0], point[1] - l.position[1]];
    [
        [sign / l.mass, 0.0],
        [0.0, sign / l.mass],
        // r × P = r_x P_y − r_y P_x
        [-sign * r[1] / l.inertia, sign * r[0] / l.inertia],
    ]
}

/// Fits the contact of `bodies` (one: against a barrier) at `contact` to the
/// `measured` changes (one per body). The given `contact.normal` is used
/// unless `fit_normal`; then the fitted normal follows from the final
/// relative contact velocity (the given one only checks the approach).
pub fn planar(
    bodies: &[Lamina],
    contact: PlanarContact,
    measured: &[MeasuredChange],
    fit_normal: bool,
) -> Result<PlanarFit, FitError> {
    if bodies.is_empty() || bodies.len() > 2 || measured.len() != bodies.len() {
        return Err(FitError::Undetermined {
            parameter: "impulse",
            why: format!(
                "give 1 or 2 bodies and one measured change per body, not {} bodies and {} changes",
                bodies.len(),
                measured.len()
            ),
        });
    }
    let scene = BodiesImpact {
        a: bodies[0],
        b: bodies.get(1).copied(),
        contact,
        law: Law::Frictionless { restitution: 0.0 },
    };
    // The scene must be an impact (valid bodies, approaching along the given normal).
    if let Err(e) = solve(&scene, Outputs::MINIMAL, Precision::Exact) {
        return Err(FitError::NotAnImpact {
            index: 0,
            why: e.to_string(),
        });
    }
    let mut g = Vec::new();
    let mut y = Vec::new();
    for (k, (l, m)) in bodies.iter().zip(measured).enumerate() {
        let sign = if k == 0 { 1.0 } else { -1.0 };
        let values = [
            m.velocity_change[0],
            m.velocity_change[1],
            m.angular_velocity_change,
        ];
        for (row, v) in rows(l, contact.point, sign).into_iter().zip(values) {
            if !(v.value.is_finite() && v.uncertainty.is_finite() && v.uncertainty > 0.0) {
                return Err(FitError::NotAnImpact {
                    index: k,
                    why: "every measured value needs a finite value and a positive, finite uncertainty"
                        .into(),
                });
            }
            g.push(row);
            y.push(v);
        }
    }
    // Normal equations of the weighted problem.
    let mut normal = Matrix2::zeros();
    let mut rhs = Vector2::zeros();
    for (row, v) in g.iter().zip(&y) {
        let w = 1.0 / (v.uncertainty * v.uncertainty);
        let a = Vector2::new(row[0], row[1]);
        normal += a * a.transpose() * w;
        rhs += a * (v.value * w);
    }
    let covariance = normal
        .try_inverse()
        .filter(|c| c.iter().all(|x| x.is_finite()))
        .ok_or(FitError::Undetermined {
            parameter: "impulse",
            why: "the measured changes do not determine both components of the impulse".into(),
        })?;
    let p = covariance * rhs;
    let residuals: Vec<f64> = g
        .iter()
        .zip(&y)
        .map(|(row, v)| v.value - (row[0] * p[0] + row[1] * p[1]))
        .collect();
    let chi_squared = residuals
        .iter()
        .zip(&y)
        .map(|(r, v)| (r / v.uncertainty).powi(2))
        .sum();

    let geometry = Geometry::new(bodies, contact);
    let parameters = |p: Vector2<f64>| geometry.parameters(p, fit_normal);
    let [e, mu, angle] = parameters(p)?;
    // Standard errors: the covariance of P through each function (central differences).
    let step = 1e-6 * p.norm().max(f64::MIN_POSITIVE);
    let mut gradients = [[0.0; 2]; 3];
    for axis in 0..2 {
        let mut plus = p;
        let mut minus = p;
        plus[axis] += step;
        minus[axis] -= step;
        let (hi, lo) = (parameters(plus)?, parameters(minus)?);
        for (k, gradient) in gradients.iter_mut().enumerate() {
            let mut d = hi[k] - lo[k];
            if k == 2 {
                d = (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
            }
            gradient[axis] = d / (2.0 * step);
        }
    }
    let error = |gradient: [f64; 2]| {
        let g = Vector2::new(gradient[0], gradient[1]);
        (g.transpose() * covariance * g)[0].max(0.0).sqrt()
    };
    let fitted = if fit_normal { 3 } else { 2 };
    Ok(PlanarFit {
        restitution: Estimate {
            value: e,
            standard_error: error(gradients[0]),
        },
        impulse_ratio: Estimate {
            value: mu,
            standard_error: error(gradients[1]),
        },
        normal: fit_normal.then(|| {
            (
                [angle.cos(), angle.sin()],
                Estimate {
                    value: angle,
                    standard_error: error(gradients[2]),
                },
            )
        }),
        impulse: [p[0], p[1]],
        impulse_standard_error: [covariance[(0, 0)].sqrt(), covariance[(1, 1)].sqrt()],
        residuals,
        chi_squared,
        degrees_of_freedom: y.len().saturating_sub(fitted),
    })
}

/// What turns an impulse into `e`, `μ` and the normal: the initial relative
/// contact velocity `u` and the world `W` (`ΔU = W P`).
struct Geometry {
    u: Vector2<f64>,
    w: Matrix2<f64>,
    normal: Vector2<f64>,
}

impl Geometry {
    fn new(bodies: &[Lamina], contact: PlanarContact) -> Self {
        let mut u = Vector2::zeros();
        let mut w = Matrix2::zeros();
        for (k, l) in bodies.iter().enumerate() {
            let sign = if k == 0 { 1.0 } else { -1.0 };
            let r = [contact.point[0] - l.position[0], contact.point[1] - l.position[1]];
            let perp = Vector2::new(-r[1], r[0]);
            u += (Vector2::new(l.velocity[0], l.velocity[1]) + perp * l.angular_velocity) * sign;
            w += Matrix2::identity() / l.mass + perp * perp.transpose() / l.inertia;
        }
        Geometry {
            u,
            w,
            normal: Vector2::new(contact.normal[0], contact.normal[1]).normalize(),
        }
    }

    /// `[e, μ, angle of n̂]` of impulse `p`.
    fn parameters(&self, p: Vector2<f64>, fit_normal: bool) -> Result<[f64; 3], FitError> {
        let final_velocity = self.u + self.w * p;
        let n = if fit_normal {
            let norm = final_velocity.norm();
            if norm.is_nan() || norm <= 0.0 || self.u.dot(&final_velocity) >= 0.0 {
                return Err(FitError::Undetermined {
                    parameter: "normal",
                    why: "the fitted final relative contact velocity is zero or not a rebound, so it does not fix the normal"
                        .into(),
                });
            }
            final_velocity / norm
        } else {
            self.normal
        };
        let t = Vector2::new(-n[1], n[0]);
        let (pn, pt) = (p.dot(&n), p.dot(&t));
        if pn.is_nan() || pn <= 0.0 {
            return Err(FitError::Undetermined {
                parameter: "impulse_ratio",
                why: format!("the fitted normal impulse {pn:e} is not positive, so no ratio P_t/P_n exists"),
            });
        }
        let un = self.u.dot(&n);
        if un.is_nan() || un >= 0.0 {
            return Err(FitError::Undetermined {
                parameter: "restitution",
                why: "the contact does not approach along the fitted normal".into(),
            });
        }
        Ok([-final_velocity.dot(&n) / un, pt / pn, n[1].atan2(n[0])])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cars() -> (Vec<Lamina>, PlanarContact) {
        let lamina = |mass, inertia, position, velocity| Lamina {
            mass,
            inertia,
            position,
            velocity,
            angular_velocity: 0.0,
        };
        (
            vec![
                lamina(1500.0, 2500.0, [0.0, 0.0], [15.0, 0.0]),
                lamina(1200.0, 1800.0, [3.0, -1.5], [0.0, 12.0]),
            ],
            PlanarContact {
                point: [2.2, -0.6],
                normal: [-1.0, 0.0],
            },
        )
    }

    /// The solver's own answer, measured with uncertainty `sigma`.
    fn measured(bodies: &[Lamina], contact: PlanarContact, law: Law, sigma: f64) -> Vec<MeasuredChange> {
        let impact = BodiesImpact {
            a: bodies[0],
            b: bodies.get(1).copied(),
            contact,
            law,
        };
        let o = solve(&impact, Outputs::ALL, Precision::Exact).unwrap();
        let m = |value| Measured {
            value,
            uncertainty: sigma,
        };
        o.bodies[..bodies.len()]
            .iter()
            .map(|b| MeasuredChange {
                velocity_change: [m(b.velocity_change[0]), m(b.velocity_change[1])],
                angular_velocity_change: m(b.angular_velocity_change),
            })
            .collect()
    }

    #[test]
    fn the_coefficients_of_a_solved_crash_are_recovered() {
        let (bodies, contact) = cars();
        for (e, mu) in [(0.2, -0.3), (0.5, 0.1), (0.0, -0.45)] {
            let law = Law::ImpulseRatio {
                restitution: e,
                impulse_ratio: mu,
            };
            let fit = planar(&bodies, contact, &measured(&bodies, contact, law, 0.05), false).unwrap();
            assert!((fit.restitution.value - e).abs() < 1e-9, "{fit:?}");
            assert!((fit.impulse_ratio.value - mu).abs() < 1e-9, "{fit:?}");
            assert!(fit.chi_squared < 1e-12 && fit.degrees_of_freedom == 4);
            assert!(fit.restitution.standard_error > 0.0 && fit.impulse_ratio.standard_error > 0.0);
        }
        // A sticking crash also gives its normal back.
        let law = Law::Friction {
            restitution: 0.2,
            friction: 0.9,
        };
        let fit = planar(&bodies, contact, &measured(&bodies, contact, law, 0.05), true).unwrap();
        let (n, angle) = fit.normal.unwrap();
        assert!((n[0] + 1.0).abs() < 1e-9 && n[1].abs() < 1e-9, "{fit:?}");
        assert!((angle.value.abs() - std::f64::consts::PI).abs() < 1e-9);
        assert!((fit.restitution.value - 0.2).abs() < 1e-9, "{fit:?}");
        assert_eq!(fit.degrees_of_freedom, 3);
    }

    #[test]
    fn undetermined_parameters_are_named() {
        let (bodies, contact) = cars();
        // A plastic sticking impact leaves no final relative velocity to fix a normal.
        let law = Law::Friction {
            restitution: 0.0,
            friction: 0.9,
        };
        let data = measured(&bodies, contact, law, 0.05);
        match planar(&bodies, contact, &data, true) {
            Err(FitError::Undetermined { parameter, .. }) => assert_eq!(parameter, "normal"),
            other => panic!("{other:?}"),
        }
        // Velocity changes that push A into B: no positive normal impulse.
        let mut reversed = data.clone();
        for m in &mut reversed {
            for v in &mut m.velocity_change {
                v.value = -v.value;
            }
            m.angular_velocity_change.value = -m.angular_velocity_change.value;
        }
        match planar(&bodies, contact, &reversed, false) {
            Err(FitError::Undetermined { parameter, .. }) => assert_eq!(parameter, "impulse_ratio"),
            other => panic!("{other:?}"),
        }
    }
}
