//! Machinery shared by the planar cases: the two ways an answer is fixed
//! (a given impulse ratio, or a given final tangential contact velocity), the
//! critical impulse ratio, the admissible interval of impulse ratios, and the
//! assembly of a [`PlanarOutcome`] with its energies.
//!
//! Everything is derived from the momentum equations (Eqs A-1…A-3)
//!
//! ```text
//! m (V_n − v_n) = P_n,   m (V_t − v_t) = P_t,   I (Ω − ω) = d_c P_n − d_d P_t
//! ```
//!
//! which give the contact-point velocity change `ΔV_c = W P` with
//! `W = [[k² + d_c², −d_c d_d], [−d_c d_d, k² + d_d²]] / (m k²)` in `(n, t)` order.
//! Internally impulses are carried per unit mass (`Δn = P_n / m`, `Δt = P_t / m`)
//! and every formula is scaled by `k²` so that no `1/k²` can overflow.

use crate::energy::{self, PlanarEnergy};
use crate::error::{AdmissibleInterval, ImpactError, Input, Output, Result, finite_output};
use crate::scene::{ContactVelocity, PlanarScene, PlanarVelocity};

/// Which tangential law produced a planar answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Regime {
    /// No tangential impulse (`μ = 0`).
    Frictionless,
    /// A prescribed impulse ratio `μ`, or the two-phase ratios `μ_A`, `μ_R`.
    Prescribed,
    /// Coulomb sliding through separation, `|μ| = f`.
    Sliding,
    /// Coulomb friction stops the slip: `μ = μ_c`, `V_ct = 0` ("rolling").
    Sticking,
    /// Tangential restitution: `V_ct = −e_t v_ct` (Eq 20), `|μ| ≤ f`.
    Restitution,
}

impl Regime {
    /// The regime's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            Regime::Frictionless => "frictionless",
            Regime::Prescribed => "prescribed",
            Regime::Sliding => "sliding",
            Regime::Sticking => "sticking",
            Regime::Restitution => "restitution",
        }
    }
}

/// Impulses the barrier applies to the body at the contact point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Impulse {
    /// Normal impulse `P_n ≥ 0`.
    pub normal: f64,
    /// Tangential impulse `P_t`.
    pub tangential: f64,
}

/// Initial and final contact-point velocities.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactVelocities {
    /// `(v_cn, v_ct)`.
    pub initial: ContactVelocity,
    /// `(V_cn, V_ct)`.
    pub r#final: ContactVelocity,
}

/// Which optional outputs a caller wants. The solver skips the rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Outputs {
    /// Compute the critical impulse ratio `μ_c` even where the law does not need it.
    pub critical_impulse_ratio: bool,
    /// Compute the energies (initial, final, `T_M`, `T_L*`). The sign of `T_L`
    /// is always checked, because no answer may create energy.
    pub energy: bool,
}

impl Outputs {
    /// Every output.
    pub const ALL: Outputs = Outputs {
        critical_impulse_ratio: true,
        energy: true,
    };
    /// Only what every answer carries (velocities, impulses, `μ`, `e`, `R`, regime).
    pub const MINIMAL: Outputs = Outputs {
        critical_impulse_ratio: false,
        energy: false,
    };
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs::ALL
    }
}

/// The outcome of a planar impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarOutcome {
    /// Final velocities `V_n`, `V_t`, `Ω`.
    pub final_velocity: PlanarVelocity,
    /// Initial and final contact-point velocities.
    pub contact_velocity: ContactVelocities,
    /// Impulses `P_n`, `P_t`.
    pub impulse: Impulse,
    /// Applied impulse ratio `μ = P_t / P_n` (Eq 4).
    pub impulse_ratio: f64,
    /// Critical impulse ratio `μ_c` (the ratio that ends with `V_ct = 0`),
    /// when asked for or needed by the law.
    pub critical_impulse_ratio: Option<f64>,
    /// Kinematic coefficient of restitution `e` (Eq 1).
    pub restitution: f64,
    /// Kinetic coefficient of restitution `R` (Eq 9).
    pub kinetic_restitution: f64,
    /// The law that produced the answer.
    pub regime: Regime,
    /// Energies, when asked for.
    pub energy: Option<PlanarEnergy>,
}

/// One answer of the planar model, per unit mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Solution {
    /// `Δn = P_n / m`.
    pub dn: f64,
    /// `Δt = P_t / m`.
    pub dt: f64,
    /// `ΔΩ = Ω − ω`.
    pub d_omega: f64,
    /// `μ = P_t / P_n`.
    pub impulse_ratio: f64,
    /// `(V_cn, V_ct)`.
    pub final_contact: ContactVelocity,
    /// `v_cn + V_cn`, formed without cancellation.
    pub normal_sum: f64,
    /// `v_ct + V_ct`, formed without cancellation where the law allows.
    pub tangential_sum: f64,
}

/// The answer for a given impulse ratio `μ` (Eqs 5–7): `P_n = m (1 + e) s / D(μ)`
/// with `s = −v_cn`, `P_t = μ P_n`.
///
/// `law` names the input refused when `D(μ) ≤ 0`.
pub(crate) fn ratio_solution(scene: &PlanarScene, e: f64, mu: f64, law: Input) -> Result<Solution> {
    let c = scene.contact_velocity;
    let qn = (1.0 + e) * -c.normal;
    let (dn, dt, d_omega, d_vct) = if mu == 0.0 {
        frictionless_ratio_path(scene, qn, law)?
    } else if scene.is_central() {
        central_ratio_path(scene, qn, mu)
    } else {
        general_ratio_path(scene, qn, mu, law)?
    };
    let final_tangential = c.tangential + d_vct;
    Ok(Solution {
        dn,
        dt,
        d_omega,
        impulse_ratio: mu,
        final_contact: ContactVelocity {
            normal: -e * c.normal,
            tangential: final_tangential,
        },
        normal_sum: (1.0 - e) * c.normal,
        tangential_sum: 2.0f64.mul_add(c.tangential, d_vct),
    })
}

/// `(Δn, Δt, ΔΩ, ΔV_ct)` for any geometry and ratio.
pub(crate) fn general_ratio_path(
    scene: &PlanarScene,
    qn: f64,
    mu: f64,
    law: Input,
) -> Result<(f64, f64, f64, f64)> {
    let (dc, dd, k2) = geometry(scene);
    let dk2 = scene.dk2(mu);
    if dk2 <= 0.0 || !dk2.is_finite() {
        return Err(no_impulse_solution(scene, mu, law));
    }
    let dn = qn * (k2 / dk2);
    let dt = mu * dn;
    let d_omega = qn * ((-mu).mul_add(dd, dc) / dk2);
    let d_vct = qn * (mu.mul_add(dd.mul_add(dd, k2), -(dc * dd)) / dk2);
    Ok((dn, dt, d_omega, d_vct))
}

/// Central contact (`d_c = 0`): `D = 1`, so `Δn = (1 + e) s` exactly (Eqs 15–18).
fn central_ratio_path(scene: &PlanarScene, qn: f64, mu: f64) -> (f64, f64, f64, f64) {
    let (_, dd, k2) = geometry(scene);
    let dt = mu * qn;
    let d_omega = -dd * dt / k2;
    let d_vct = dt * (dd.mul_add(dd, k2) / k2);
    (qn, dt, d_omega, d_vct)
}

/// Frictionless contact (`μ = 0`): `D = 1 + d_c²/k² > 0` always, no tangential impulse.
fn frictionless_ratio_path(scene: &PlanarScene, qn: f64, law: Input) -> Result<(f64, f64, f64, f64)> {
    let (dc, dd, k2) = geometry(scene);
    let dk2 = dc.mul_add(dc, k2);
    if !dk2.is_finite() {
        return Err(no_impulse_solution(scene, 0.0, law));
    }
    let dn = qn * (k2 / dk2);
    let d_omega = qn * (dc / dk2);
    let d_vct = -qn * (dc * dd / dk2);
    Ok((dn, 0.0, d_omega, d_vct))
}

/// The answer whose final tangential contact velocity is `V_ct = −e_t v_ct`
/// (Eqs 1, 20 and 3 solved together), with the impulse ratio it needs.
///
/// With `q_n = (1 + e) s`, `q_t = (1 + e_t) v_ct` and `S = k² + d_c² + d_d²`:
/// `Δn = [(k² + d_d²) q_n − d_c d_d q_t] / S`,
/// `Δt = [d_c d_d q_n − (k² + d_c²) q_t] / S`,
/// `ΔΩ = [d_c q_n + d_d q_t] / S`.
/// For `d_c = 0` these reduce to Eqs 21–23 (with `λ = ρ²/k²`) and Eq 25.
///
/// `Δn` may come out `≤ 0` on a non-central contact: the caller refuses such
/// an answer when it would be used.
pub(crate) fn target_solution(scene: &PlanarScene, e: f64, et: f64) -> Solution {
    let c = scene.contact_velocity;
    let qn = (1.0 + e) * -c.normal;
    let qt = (1.0 + et) * c.tangential;
    let (dn, dt, d_omega) = if scene.is_central() {
        central_target_path(scene, qn, qt)
    } else {
        general_target_path(scene, qn, qt)
    };
    Solution {
        dn,
        dt,
        d_omega,
        impulse_ratio: dt / dn,
        final_contact: ContactVelocity {
            normal: -e * c.normal,
            tangential: if et == 0.0 { 0.0 } else { -et * c.tangential },
        },
        normal_sum: (1.0 - e) * c.normal,
        tangential_sum: (1.0 - et) * c.tangential,
    }
}

/// `(Δn, Δt, ΔΩ)` of the target answer for any geometry.
pub(crate) fn general_target_path(scene: &PlanarScene, qn: f64, qt: f64) -> (f64, f64, f64) {
    let (dc, dd, k2) = geometry(scene);
    let s = dc.mul_add(dc, dd.mul_add(dd, k2));
    let w_nn = dd.mul_add(dd, k2) / s;
    let w_tt = dc.mul_add(dc, k2) / s;
    let w_nt = dc * dd / s;
    let dn = w_nn.mul_add(qn, -(w_nt * qt));
    let dt = w_nt.mul_add(qn, -(w_tt * qt));
    let d_omega = (dc / s).mul_add(qn, (dd / s) * qt);
    (dn, dt, d_omega)
}

/// Central contact: `Δn = q_n` exactly, `Δt = −q_t / (1 + λ)` (Eq 25), `λ = d_d²/k²`.
fn central_target_path(scene: &PlanarScene, qn: f64, qt: f64) -> (f64, f64, f64) {
    let (_, dd, k2) = geometry(scene);
    let s = dd.mul_add(dd, k2);
    let dt = -qt * (k2 / s);
    let d_omega = qt * (dd / s);
    (qn, dt, d_omega)
}

/// Critical impulse ratio `μ_c` for the general geometry: the ratio whose
/// answer ends with `V_ct = 0` (Eq 14 for `d_c = 0`, with `λ = ρ²/k²`):
///
/// `μ_c = [d_c d_d q_n − (k² + d_c²) v_ct] / [(k² + d_d²) q_n − d_c d_d v_ct]`,
/// `q_n = (1 + e) s`.
///
/// `None` when the denominator vanishes (no finite ratio stops the slip).
pub(crate) fn critical_ratio(scene: &PlanarScene, e: f64) -> Option<f64> {
    let sol = target_solution(scene, e, 0.0);
    if sol.dn == 0.0 {
        None
    } else {
        Some(sol.impulse_ratio).filter(|mu| mu.is_finite())
    }
}

/// The interval of impulse ratios `μ` whose answer is physical: `D(μ) > 0`
/// and `T_L(μ) ≥ 0`. It always contains `μ = 0`.
///
/// `T_L(μ) D(μ)² k² · 2 / (m (1 + e) s)` is the quadratic
/// `Q(μ) = (1 − e) s (k² + d_c²) + 2 μ [e s d_c d_d − v_ct (k² + d_c²)]
///        + μ² [2 v_ct d_c d_d − (1 + e) s (k² + d_d²)]`,
/// and `D` has its single root at `μ* = (k² + d_c²) / (d_c d_d)` where `Q < 0`,
/// so the set is one interval (possibly unbounded on one side).
pub fn admissible_interval(scene: &PlanarScene, e: f64) -> AdmissibleInterval {
    let (dc, dd, k2) = geometry(scene);
    let s = -scene.contact_velocity.normal;
    let vct = scene.contact_velocity.tangential;
    let a = dc.mul_add(dc, k2);
    let b = dc * dd;
    let c = dd.mul_add(dd, k2);
    let c0 = (1.0 - e) * s * a;
    let c1 = 2.0 * (e * s).mul_add(b, -(vct * a));
    let c2 = (2.0 * vct).mul_add(b, -((1.0 + e) * s * c));
    let mut lower = f64::NEG_INFINITY;
    let mut upper = f64::INFINITY;
    if b != 0.0 {
        let mu_star = a / b;
        if mu_star > 0.0 {
            upper = upper.min(mu_star);
        } else {
            lower = lower.max(mu_star);
        }
    }
    if c2 != 0.0 {
        let disc = c1.mul_add(c1, -4.0 * c2 * c0).max(0.0);
        let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
        let (mut r1, mut r2) = if q == 0.0 { (0.0, 0.0) } else { (q / c2, c0 / q) };
        if r1 > r2 {
            std::mem::swap(&mut r1, &mut r2);
        }
        if c2 < 0.0 {
            lower = lower.max(r1);
            upper = upper.min(r2);
        } else if r1 >= 0.0 {
            upper = upper.min(r1);
        } else {
            lower = lower.max(r2);
        }
    } else if c1 > 0.0 {
        lower = lower.max(-c0 / c1);
    } else if c1 < 0.0 {
        upper = upper.min(-c0 / c1);
    }
    AdmissibleInterval {
        lower: Some(lower).filter(|x| x.is_finite()),
        upper: Some(upper).filter(|x| x.is_finite()),
    }
}

/// The error for an answer with `D(μ) ≤ 0`.
pub(crate) fn no_impulse_solution(scene: &PlanarScene, mu: f64, law: Input) -> ImpactError {
    ImpactError::NoImpulseSolution {
        input: law,
        impulse_ratio: mu,
        d: scene.d(mu),
    }
}

/// Builds the outcome from one answer: refuses answers that create energy,
/// computes only the requested optional outputs, and refuses non-finite outputs.
///
/// `T_L` is the work of the impulses (Kelvin and Tait, as in the Appendix):
/// `T_L = −½ [P_n (v_cn + V_cn) + P_t (v_ct + V_ct)]`, which never subtracts
/// two nearly equal energies.
#[allow(clippy::too_many_arguments)] // each argument is one named part of the answer
pub(crate) fn assemble(
    scene: &PlanarScene,
    restitution: f64,
    kinetic_restitution: f64,
    regime: Regime,
    sol: &Solution,
    known_critical: Option<Option<f64>>,
    outputs: Outputs,
    law: Input,
) -> Result<PlanarOutcome> {
    let m = scene.body.mass();
    let work = sol.dn.mul_add(sol.normal_sum, sol.dt * sol.tangential_sum);
    if work > 0.0 {
        return Err(ImpactError::CreatesEnergy {
            input: law,
            impulse_ratio: sol.impulse_ratio,
            energy_loss: -0.5 * m * work,
            admissible: admissible_interval(scene, restitution),
        });
    }
    let v = scene.velocity;
    let final_velocity = PlanarVelocity {
        normal: finite_output(Output::FinalNormalVelocity, v.normal + sol.dn)?,
        tangential: finite_output(Output::FinalTangentialVelocity, v.tangential + sol.dt)?,
        angular: finite_output(Output::FinalAngularVelocity, v.angular + sol.d_omega)?,
    };
    finite_output(Output::FinalNormalContactVelocity, sol.final_contact.normal)?;
    finite_output(
        Output::FinalTangentialContactVelocity,
        sol.final_contact.tangential,
    )?;
    let impulse = Impulse {
        normal: finite_output(Output::NormalImpulse, m * sol.dn)?,
        tangential: finite_output(Output::TangentialImpulse, m * sol.dt)?,
    };
    let impulse_ratio = finite_output(Output::ImpulseRatio, sol.impulse_ratio)?;
    let critical_impulse_ratio = match known_critical {
        Some(known) if outputs.critical_impulse_ratio || known.is_some() => Some(known),
        None if outputs.critical_impulse_ratio => Some(critical_ratio(scene, restitution)),
        _ => None,
    }
    .map(|mu_c| {
        mu_c.ok_or(ImpactError::OutputNotFinite {
            output: Output::CriticalImpulseRatio,
        })
    })
    .transpose()?;
    let energy = if outputs.energy {
        Some(energy::planar(scene, &final_velocity, -0.5 * work)?)
    } else {
        None
    };
    Ok(PlanarOutcome {
        final_velocity,
        contact_velocity: ContactVelocities {
            initial: scene.contact_velocity,
            r#final: sol.final_contact,
        },
        impulse,
        impulse_ratio,
        critical_impulse_ratio,
        restitution: finite_output(Output::Restitution, restitution)?,
        kinetic_restitution,
        regime,
        energy,
    })
}

fn geometry(scene: &PlanarScene) -> (f64, f64, f64) {
    (
        scene.contact.tangential_offset,
        scene.contact.normal_offset,
        scene.k2,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Body, Contact};

    fn scenes() -> impl Iterator<Item = PlanarScene> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut unit = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..2000).map(move |_| {
            let k = 0.01 + unit();
            let dd = 2.0 * unit() - 1.0;
            let w = 4.0 * unit() - 2.0;
            PlanarScene::new(
                Body::new(1.0, k * k).unwrap(),
                Contact::central(dd),
                PlanarVelocity {
                    normal: -0.01 - unit(),
                    tangential: 4.0 * unit() - 2.0,
                    angular: w,
                },
            )
            .unwrap()
        })
    }

    fn within(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 4.0 * f64::EPSILON * scale.max(a.abs()).max(b.abs())
    }

    #[test]
    fn central_and_frictionless_paths_agree_with_the_general_path() {
        for scene in scenes() {
            let qn = 1.93 * -scene.contact_velocity.normal;
            for mu in [0.0, 0.1, -0.3, 0.7] {
                let general = general_ratio_path(&scene, qn, mu, Input::ImpulseRatio).unwrap();
                let special = if mu == 0.0 {
                    frictionless_ratio_path(&scene, qn, Input::ImpulseRatio).unwrap()
                } else {
                    central_ratio_path(&scene, qn, mu)
                };
                let scale = qn * (1.0 + mu.abs()) * (1.0 + 1.0 / scene.k2);
                assert!(within(general.0, special.0, scale));
                assert!(within(general.1, special.1, scale));
                assert!(within(general.2, special.2, scale));
                assert!(within(general.3, special.3, scale));
            }
            for et in [-1.0, 0.0, 0.34, 1.0] {
                let qt = (1.0 + et) * scene.contact_velocity.tangential;
                let general = general_target_path(&scene, qn, qt);
                let special = central_target_path(&scene, qn, qt);
                let scale = (qn.abs() + qt.abs()) * (1.0 + 1.0 / scene.contact.normal_offset.abs().max(1e-3));
                assert!(within(general.0, special.0, scale));
                assert!(within(general.1, special.1, scale));
                assert!(within(general.2, special.2, scale));
            }
        }
    }

    #[test]
    fn the_admissible_interval_contains_zero_and_its_bounds_lose_no_energy() {
        for scene in scenes() {
            for e in [0.0, 0.5, 1.0] {
                let interval = admissible_interval(&scene, e);
                assert!(interval.contains(0.0));
                for bound in [interval.lower, interval.upper].into_iter().flatten() {
                    let inside = bound * (1.0 - 1e-9);
                    let sol = ratio_solution(&scene, e, inside, Input::ImpulseRatio).unwrap();
                    let work = sol.dn.mul_add(sol.normal_sum, sol.dt * sol.tangential_sum);
                    assert!(work <= 1e-9 * (sol.dn * scene.contact_velocity.normal).abs());
                }
            }
        }
    }
}
