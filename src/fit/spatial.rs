//! The coefficients of a spatial law fitted to measured impacts (one body on
//! a barrier or two bodies, each impact its own scene): weighted least
//! squares on the measured velocity changes, predicted through
//! [`crate::impact::solve`], by Levenberg–Marquardt over the coefficients
//! held in their ranges.
//!
//! The residual of one measured component is `(measured − predicted)/σ`;
//! `χ² = Σ` of their squares. The Jacobian is taken by central differences
//! (one-sided at a range's end); the covariance is `(Jᵀ J)⁻¹`, the stated
//! uncertainties being standard deviations. A coefficient none of the
//! predictions depends on at the fitted values (friction when every impact
//! sticks, a rebound ratio when `R = 0`), or one that only a combination with
//! others determines (`Jᵀ J` singular), is refused, named.

use nalgebra::{DMatrix, DVector};

use super::{Estimate, FitError, Measured};
use crate::error::Input;
use crate::impact::{Law, Precision, RigidBody, SpatialContact, SpatialImpact, Twist, solve};
use crate::outcome::{Outputs, Regime, SpatialOutcome, TorsionalRegime};

/// The spatial laws that can be fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpatialLaw {
    /// `e` and Coulomb `f`.
    Friction,
    /// `e` and a prescribed ratio `μ ≥ 0`.
    ImpulseRatio,
    /// `e`, `f` and `e_t` (section 3).
    TangentialRestitution,
    /// The two-phase law: `R`, `μ_A`, `μ_R` (Appendix).
    KineticRestitution,
    /// The two-phase law with Coulomb `f_A` in the approach: `R`, `f_A`, `μ_R`.
    KineticFriction,
}

impl SpatialLaw {
    /// The coefficients, in the order of [`SpatialLaw::law`]'s arguments.
    pub fn parameters(self) -> &'static [Input] {
        match self {
            SpatialLaw::Friction => &[Input::Restitution, Input::Friction],
            SpatialLaw::ImpulseRatio => &[Input::Restitution, Input::ImpulseRatio],
            SpatialLaw::TangentialRestitution => {
                &[Input::Restitution, Input::Friction, Input::TangentialRestitution]
            }
            SpatialLaw::KineticRestitution => &[
                Input::KineticRestitution,
                Input::ApproachImpulseRatio,
                Input::ReboundImpulseRatio,
            ],
            SpatialLaw::KineticFriction => &[
                Input::KineticRestitution,
                Input::ApproachFriction,
                Input::ReboundImpulseRatio,
            ],
        }
    }

    /// The law with coefficients `c` (in [`SpatialLaw::parameters`] order).
    pub fn law(self, c: &[f64]) -> Law {
        match self {
            SpatialLaw::Friction => Law::Friction {
                restitution: c[0],
                friction: c[1],
            },
            SpatialLaw::ImpulseRatio => Law::ImpulseRatio {
                restitution: c[0],
                impulse_ratio: c[1],
            },
            SpatialLaw::TangentialRestitution => Law::TangentialRestitution {
                restitution: c[0],
                friction: c[1],
                tangential_restitution: c[2],
            },
            SpatialLaw::KineticRestitution => Law::KineticRestitution {
                value: c[0],
                approach_impulse_ratio: c[1],
                rebound_impulse_ratio: c[2],
            },
            SpatialLaw::KineticFriction => Law::KineticFriction {
                value: c[0],
                approach_friction: c[1],
                rebound_impulse_ratio: c[2],
            },
        }
    }
}

/// The range of a coefficient (conventions, rule 10; ratios are magnitudes in space).
fn range(input: Input) -> (f64, f64) {
    match input {
        Input::TangentialRestitution => (-1.0, 1.0),
        Input::Restitution | Input::KineticRestitution | Input::TorsionalRestitution => (0.0, 1.0),
        _ => (0.0, f64::INFINITY),
    }
}

/// One body's measured change of motion; the angular one may be unmeasured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialChange {
    /// `ΔV = V − v` of the mass centre.
    pub velocity_change: [Measured; 3],
    /// `Δω = Ω − ω`, if measured.
    pub angular_velocity_change: Option<[Measured; 3]>,
}

/// One measured impact: the scene before it and each body's measured change.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialObservation {
    /// Body A.
    pub a: RigidBody,
    /// Body B, unless A hit a barrier.
    pub b: Option<RigidBody>,
    /// The contact point and the normal from B into A.
    pub contact: SpatialContact,
    /// One change per body, A first.
    pub measured: Vec<SpatialChange>,
}

/// What the fitted law answers for one impact.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpactFit {
    /// The branch of the tangential law.
    pub regime: Regime,
    /// The branch of the twist law, with one.
    pub torsional_regime: Option<TorsionalRegime>,
    /// Measured minus fitted, per body: `ΔV` x, y, z, then `Δω` x, y, z if measured.
    pub residuals: Vec<f64>,
}

/// The fitted law.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialFit {
    /// The law with the fitted coefficients.
    pub law: Law,
    /// The twist law with its fitted coefficients, when fitted.
    pub torsion: Option<Twist>,
    /// Each coefficient (by its request member) and its standard error.
    pub estimates: Vec<(Input, Estimate)>,
    /// Each impact under the fitted law, in input order.
    pub impacts: Vec<ImpactFit>,
    /// `Σ (residual/σ)²`.
    pub chi_squared: f64,
    /// Measured values minus fitted coefficients.
    pub degrees_of_freedom: usize,
}

/// The problem: observations, the law, and the twist's pitch radius if fitted.
struct Problem<'a> {
    observations: &'a [SpatialObservation],
    law: SpatialLaw,
    pitch_radius: Option<f64>,
    parameters: Vec<Input>,
}

impl Problem<'_> {
    fn impact(&self, o: &SpatialObservation, c: &[f64]) -> SpatialImpact {
        let k = self.law.parameters().len();
        SpatialImpact {
            a: o.a,
            b: o.b,
            contact: o.contact,
            law: self.law.law(c),
            torsion: self.pitch_radius.map(|pitch_radius| Twist {
                restitution: c[k],
                friction: c[k + 1],
                pitch_radius,
            }),
        }
    }

    /// The predicted changes, in the order of the measured ones.
    fn predict(o: &SpatialObservation, outcome: &SpatialOutcome) -> Vec<f64> {
        let mut out = Vec::new();
        for (k, m) in o.measured.iter().enumerate() {
            let b = &outcome.bodies[k];
            out.extend(b.velocity_change);
            if m.angular_velocity_change.is_some() {
                out.extend(b.angular_velocity_change);
            }
        }
        out
    }

    /// The weighted residuals at `c`, or the first impact the law refuses there.
    fn residuals(
        &self,
        c: &[f64],
        outputs: Outputs,
    ) -> Result<(DVector<f64>, Vec<SpatialOutcome>), FitError> {
        let mut r = Vec::new();
        let mut outcomes = Vec::new();
        for (index, o) in self.observations.iter().enumerate() {
            let outcome =
                solve(&self.impact(o, c), outputs, Precision::Fast).map_err(|e| FitError::NotAnImpact {
                    index,
                    why: e.to_string(),
                })?;
            for (value, m) in Self::predict(o, &outcome).into_iter().zip(measured(o)) {
                r.push((m.value - value) / m.uncertainty);
            }
            outcomes.push(outcome);
        }
        Ok((DVector::from_vec(r), outcomes))
    }

    fn chi_squared(&self, c: &[f64]) -> f64 {
        self.residuals(c, Outputs::MINIMAL)
            .map_or(f64::INFINITY, |(r, _)| r.norm_squared())
    }

    /// `∂r/∂c` from each side, by one-sided differences (`None` past a
    /// range's end, or where the law refuses an impact).
    fn sides(&self, c: &[f64], r: &DVector<f64>) -> Vec<[Option<DVector<f64>>; 2]> {
        self.parameters
            .iter()
            .enumerate()
            .map(|(i, &input)| {
                let (low, high) = range(input);
                let h = 1e-6 * c[i].abs().max(1.0);
                let at = |x: f64| {
                    let mut moved = c.to_vec();
                    moved[i] = x;
                    self.residuals(&moved, Outputs::MINIMAL)
                        .ok()
                        .map(|(q, _)| (q - r) / (x - c[i]))
                };
                [
                    (c[i] + h <= high).then(|| at(c[i] + h)).flatten(),
                    (c[i] - h >= low).then(|| at(c[i] - h)).flatten(),
                ]
            })
            .collect()
    }

    /// `∂r/∂c`: the mean of the two sides (central differences), or the one side there is.
    fn jacobian(&self, c: &[f64], r: &DVector<f64>) -> DMatrix<f64> {
        let mut j = DMatrix::zeros(r.len(), c.len());
        for (i, [up, down]) in self.sides(c, r).into_iter().enumerate() {
            let column = match (up, down) {
                (Some(u), Some(d)) => (u + d) / 2.0,
                (Some(one), None) | (None, Some(one)) => one,
                (None, None) => DVector::zeros(r.len()),
            };
            j.set_column(i, &column);
        }
        j
    }

    fn clamp(&self, c: &mut [f64]) {
        for (x, &input) in c.iter_mut().zip(&self.parameters) {
            let (low, high) = range(input);
            *x = x.clamp(low, high);
        }
    }

    /// Levenberg–Marquardt from `start`: the coefficients and their `χ²`.
    fn descend(&self, start: Vec<f64>) -> (Vec<f64>, f64) {
        let mut c = start;
        self.clamp(&mut c);
        let mut cost = self.chi_squared(&c);
        // A start the law refuses somewhere: shrink the friction-like
        // coefficients towards the frictionless law, which answers every impact.
        for _ in 0..60 {
            if cost.is_finite() {
                break;
            }
            for (x, &input) in c.iter_mut().zip(&self.parameters) {
                if !matches!(
                    input,
                    Input::Restitution | Input::KineticRestitution | Input::TorsionalRestitution
                ) {
                    *x /= 2.0;
                }
            }
            cost = self.chi_squared(&c);
        }
        let mut lambda = 1e-3;
        for _ in 0..200 {
            let Ok((r, _)) = self.residuals(&c, Outputs::MINIMAL) else {
                break;
            };
            let j = self.jacobian(&c, &r);
            // r(c + δ) ≈ r + J δ: minimise |r + J δ|².
            let a = j.transpose() * &j;
            let g = -(j.transpose() * &r);
            let mut improved = false;
            while lambda < 1e12 {
                let mut damped = a.clone();
                for i in 0..c.len() {
                    damped[(i, i)] += lambda * a[(i, i)].max(1e-12);
                }
                let Some(step) = damped.cholesky().map(|ch| ch.solve(&g)) else {
                    lambda *= 4.0;
                    continue;
                };
                let mut next: Vec<f64> = c.iter().zip(step.iter()).map(|(x, d)| x + d).collect();
                self.clamp(&mut next);
                let next_cost = self.chi_squared(&next);
                if next_cost < cost {
                    let moved = c
                        .iter()
                        .zip(&next)
                        .map(|(x, y)| (x - y).abs())
                        .fold(0.0, f64::max);
                    let gain = cost - next_cost;
                    c = next;
                    cost = next_cost;
                    lambda = (lambda / 3.0).max(1e-12);
                    improved = moved > 1e-15 && gain > 1e-15 * cost.max(f64::MIN_POSITIVE);
                    break;
                }
                lambda *= 4.0;
            }
            if !improved {
                break;
            }
        }
        (c, cost)
    }
}

/// Every measured value of an observation, in the order of the predictions.
fn measured(o: &SpatialObservation) -> Vec<Measured> {
    let mut out = Vec::new();
    for m in &o.measured {
        out.extend(m.velocity_change);
        if let Some(w) = m.angular_velocity_change {
            out.extend(w);
        }
    }
    out
}

/// Starting values from the measured impulses `P = m_A ΔV_A`: their ratio
/// `|P_t|/P_n` (mean, and largest for friction), and `e` from `P_n` against
/// the normal impulse of a plastic frictionless impact (`(1 + e)` times it
/// without friction); `e_t = 0`, `e_z = 0.5`, `μ_z = 0.3`.
fn start(problem: &Problem<'_>) -> Vec<f64> {
    let (mut ratios, mut es) = (Vec::new(), Vec::new());
    let zeros = vec![0.0; problem.parameters.len()];
    for o in problem.observations {
        let Ok(free) = solve(&problem.impact(o, &zeros), Outputs::MINIMAL, Precision::Fast) else {
            continue;
        };
        let n = o.contact.normal;
        let size = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let p = o.measured[0].velocity_change.map(|m| m.value * o.a.mass);
        let pn = (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / size;
        let pt = [0, 1, 2].map(|i| p[i] - pn * n[i] / size);
        if pn > 0.0 {
            ratios.push((pt[0] * pt[0] + pt[1] * pt[1] + pt[2] * pt[2]).sqrt() / pn);
        }
        // With e = 0 and no friction U_n = 0: the normal impulse scales with 1 + e.
        if free.impulse.normal > 0.0 {
            es.push(pn / free.impulse.normal - 1.0);
        }
    }
    let mean = |v: &[f64], default: f64| {
        if v.is_empty() {
            default
        } else {
            v.iter().sum::<f64>() / v.len() as f64
        }
    };
    let e = mean(&es, 0.5).clamp(0.0, 1.0);
    let mu = mean(&ratios, 0.2);
    let most = ratios.iter().copied().fold(0.0, f64::max).max(mu);
    let mut c: Vec<f64> = problem
        .parameters
        .iter()
        .map(|&input| match input {
            Input::Restitution | Input::KineticRestitution => e,
            Input::Friction => most,
            Input::ApproachFriction => most * (1.0 + e),
            Input::TangentialRestitution => 0.0,
            Input::TorsionalRestitution => 0.5,
            Input::TorsionalFriction => 0.3,
            _ => mu,
        })
        .collect();
    problem.clamp(&mut c);
    c
}

/// Fits `law` (and, with `pitch_radius`, the twist law's `e_z`, `μ_z`) to
/// the `observations`.
pub fn spatial(
    observations: &[SpatialObservation],
    law: SpatialLaw,
    pitch_radius: Option<f64>,
) -> Result<SpatialFit, FitError> {
    let mut parameters = law.parameters().to_vec();
    if pitch_radius.is_some() {
        parameters.extend([Input::TorsionalRestitution, Input::TorsionalFriction]);
    }
    for (index, o) in observations.iter().enumerate() {
        let bodies = 1 + usize::from(o.b.is_some());
        if o.measured.len() != bodies {
            return Err(FitError::NotAnImpact {
                index,
                why: format!(
                    "give one measured change per body: {bodies} bodies, {} changes",
                    o.measured.len()
                ),
            });
        }
        if measured(o)
            .iter()
            .any(|m| !(m.value.is_finite() && m.uncertainty.is_finite() && m.uncertainty > 0.0))
        {
            return Err(FitError::NotAnImpact {
                index,
                why: "every measured value needs a finite value and a positive, finite uncertainty".into(),
            });
        }
    }
    let count: usize = observations.iter().map(|o| measured(o).len()).sum();
    if count < parameters.len() {
        return Err(FitError::TooFewPoints {
            needed: parameters.len(),
            got: count,
        });
    }
    let problem = Problem {
        observations,
        law,
        pitch_radius,
        parameters,
    };
    let first = start(&problem);
    // A second start with the ratios and friction halved: a start where
    // every impact sticks has no gradient along friction.
    let halved: Vec<f64> = first
        .iter()
        .zip(&problem.parameters)
        .map(|(&x, &input)| {
            if range(input).0 == 0.0 && range(input).1.is_infinite() {
                x / 2.0
            } else {
                x
            }
        })
        .collect();
    let (c, _) = [first, halved]
        .into_iter()
        .map(|s| problem.descend(s))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("two starts");
    let (r, outcomes) = problem.residuals(&c, Outputs::ALL)?;
    // A coefficient is determined only if the predictions move when it moves
    // either way (friction with every impact sticking moves them downwards only).
    let sides = problem.sides(&c, &r);
    let norms: Vec<[Option<f64>; 2]> = sides
        .iter()
        .map(|pair| [0, 1].map(|k| pair[k].as_ref().map(|v| v.norm())))
        .collect();
    let largest = norms.iter().flatten().flatten().copied().fold(0.0, f64::max);
    for (i, &input) in problem.parameters.iter().enumerate() {
        let flat = |n: &Option<f64>| n.is_some_and(|n| n <= 1e-9 * largest.max(f64::MIN_POSITIVE));
        if norms[i].iter().all(Option::is_none) || norms[i].iter().any(flat) {
            return Err(FitError::Undetermined {
                parameter: input.path(),
                why: format!(
                    "the predicted velocity changes do not depend on {} on {} side of its fitted value {} \
                     (friction: every impact sticks there; a rebound ratio: R = 0), so the data bound it at most",
                    input.name(),
                    if norms[i].iter().all(flat) {
                        "either"
                    } else {
                        "one"
                    },
                    c[i]
                ),
            });
        }
    }
    let j = problem.jacobian(&c, &r);
    let information = j.transpose() * &j;
    let covariance = information
        .clone()
        .try_inverse()
        .filter(|m| m.iter().all(|x| x.is_finite()) && (0..c.len()).all(|i| m[(i, i)] > 0.0))
        .filter(|_| condition(&information) < 1e12)
        .ok_or_else(|| {
            // The coefficient most involved in the direction the data leave open.
            let eigen = information.clone().symmetric_eigen();
            let weakest = eigen.eigenvalues.imin();
            let v = eigen.eigenvectors.column(weakest);
            let i = v.iamax();
            FitError::Undetermined {
                parameter: problem.parameters[i].path(),
                why: format!(
                    "the measured changes determine {} only together with the other coefficients",
                    problem.parameters[i].name()
                ),
            }
        })?;
    let mut impacts = Vec::new();
    let mut offset = 0;
    for (o, outcome) in observations.iter().zip(&outcomes) {
        let values = measured(o);
        let residuals = Problem::predict(o, outcome)
            .iter()
            .zip(&values)
            .map(|(p, m)| m.value - p)
            .collect();
        offset += values.len();
        impacts.push(ImpactFit {
            regime: outcome.regime,
            torsional_regime: outcome.torsional_regime,
            residuals,
        });
    }
    debug_assert_eq!(offset, r.len());
    let impact = problem.impact(&observations[0], &c);
    Ok(SpatialFit {
        law: impact.law,
        torsion: impact.torsion,
        estimates: problem
            .parameters
            .iter()
            .enumerate()
            .map(|(i, &input)| {
                (
                    input,
                    Estimate {
                        value: c[i],
                        standard_error: covariance[(i, i)].sqrt(),
                    },
                )
            })
            .collect(),
        impacts,
        chi_squared: r.norm_squared(),
        degrees_of_freedom: count - c.len(),
    })
}

/// The ratio of the largest to the smallest eigenvalue of a symmetric matrix.
fn condition(m: &DMatrix<f64>) -> f64 {
    let e = m.clone().symmetric_eigenvalues();
    let (low, high) = (e.min(), e.max());
    if low > 0.0 { high / low } else { f64::INFINITY }
}
