//! Normal impact (section 2.1): a point mass, or a rigid body on a
//! frictionless contact (`μ = 0`), with the kinematic coefficient `e` (Eq 1).
//! With no tangential impulse the approach and rebound ratios are both 0, so
//! by Eq 11 the kinetic coefficient `R` equals `e`.

use crate::energy::PlanarEnergy;
use crate::error::{ImpactError, Input, Output, Result, finite, finite_output, in_range, positive};
use crate::planar::{ContactVelocities, Impulse, Outputs, PlanarOutcome, Regime, assemble, ratio_solution};
use crate::scene::{Body, Contact, ContactVelocity, PlanarScene, PlanarVelocity};

/// A normal impact request. Without `inertia` the body is a point mass: it has
/// no contact offset and no rotation (a non-zero `velocity.angular` or any
/// `contact` is refused).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalImpact {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Centroidal moment of inertia `I > 0`, or `None` for a point mass.
    pub inertia: Option<f64>,
    /// Contact geometry (rigid body only); `None` means `d_c = d_d = 0`.
    pub contact: Option<Contact>,
    /// Initial velocities.
    pub velocity: PlanarVelocity,
    /// Kinematic coefficient of restitution `e ∈ [0, 1]`.
    pub restitution: f64,
}

/// Solves a normal (frictionless) impact.
pub fn solve(impact: &NormalImpact, outputs: Outputs) -> Result<PlanarOutcome> {
    match impact.inertia {
        Some(inertia) => {
            let body = Body::new(impact.mass, inertia)?;
            let scene = PlanarScene::new(body, impact.contact.unwrap_or_default(), impact.velocity)?;
            solve_scene(&scene, impact.restitution, outputs)
        }
        None => point_mass(impact, outputs),
    }
}

/// Solves a frictionless impact of a rigid body in a validated scene.
pub fn solve_scene(scene: &PlanarScene, restitution: f64, outputs: Outputs) -> Result<PlanarOutcome> {
    let e = in_range(Input::Restitution, restitution, 0.0, 1.0)?;
    let sol = ratio_solution(scene, e, 0.0, Input::Restitution)?;
    assemble(
        scene,
        e,
        e,
        Regime::Frictionless,
        &sol,
        None,
        outputs,
        Input::Restitution,
    )
}

/// The validated inputs of a point-mass impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PointMass {
    pub mass: f64,
    pub vn: f64,
    pub vt: f64,
    pub e: f64,
}

impl PointMass {
    /// Checks a point-mass request: no contact, no spin, approaching, `e ∈ [0, 1]`.
    pub(crate) fn validate(impact: &NormalImpact) -> Result<Self> {
        let mass = positive(Input::Mass, impact.mass)?;
        if impact.contact.is_some() {
            return Err(ImpactError::NeedsInertia {
                input: Input::TangentialOffset,
            });
        }
        let v = impact.velocity;
        let vn = finite(Input::NormalVelocity, v.normal)?;
        let vt = finite(Input::TangentialVelocity, v.tangential)?;
        if finite(Input::AngularVelocity, v.angular)? != 0.0 {
            return Err(ImpactError::NeedsInertia {
                input: Input::AngularVelocity,
            });
        }
        if vn >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: vn,
            });
        }
        let e = in_range(Input::Restitution, impact.restitution, 0.0, 1.0)?;
        Ok(PointMass { mass, vn, vt, e })
    }

    /// The outcome from its computed outputs: the tangential velocity is
    /// unchanged, there is no spin and no tangential impulse.
    pub(crate) fn outcome(
        &self,
        final_normal: f64,
        normal_impulse: f64,
        critical_impulse_ratio: Option<f64>,
        energy: Option<PlanarEnergy>,
    ) -> PlanarOutcome {
        let PointMass { vn, vt, e, .. } = *self;
        PlanarOutcome {
            final_velocity: PlanarVelocity {
                normal: final_normal,
                tangential: vt,
                angular: 0.0,
            },
            contact_velocity: ContactVelocities {
                initial: ContactVelocity {
                    normal: vn,
                    tangential: vt,
                },
                r#final: ContactVelocity {
                    normal: final_normal,
                    tangential: vt,
                },
            },
            impulse: Impulse {
                normal: normal_impulse,
                tangential: 0.0,
            },
            impulse_ratio: 0.0,
            critical_impulse_ratio,
            restitution: e,
            kinetic_restitution: e,
            regime: Regime::Frictionless,
            energy,
        }
    }
}

/// A point mass: `V_n = −e v_n`, `P_n = m (1 + e) |v_n|`, `V_t = v_t`.
/// `T_M` is the whole initial energy (the mass stops), `T_L = ½ m (1 − e)(1 + e) v_n²`,
/// and `μ_c = v_t / ((1 + e) v_n)`, the limit of Eq 14 for `k → ∞`.
fn point_mass(impact: &NormalImpact, outputs: Outputs) -> Result<PlanarOutcome> {
    let PointMass { mass: m, vn, vt, e } = PointMass::validate(impact)?;
    let final_normal = finite_output(Output::FinalNormalVelocity, -e * vn)?;
    let dn = (1.0 + e) * -vn;
    let normal_impulse = finite_output(Output::NormalImpulse, m * dn)?;
    let critical_impulse_ratio = if outputs.critical_impulse_ratio {
        Some(finite_output(
            Output::CriticalImpulseRatio,
            vt / ((1.0 + e) * vn),
        )?)
    } else {
        None
    };
    let energy = if outputs.energy {
        let initial = finite_output(Output::InitialEnergy, 0.5 * m * vn.mul_add(vn, vt * vt))?;
        let r#final = finite_output(
            Output::FinalEnergy,
            0.5 * m * final_normal.mul_add(final_normal, vt * vt),
        )?;
        let loss = finite_output(
            Output::EnergyLoss,
            0.5 * m * ((1.0 - e) * -vn) * ((1.0 + e) * -vn),
        )?
        .max(0.0);
        let normalized_loss = finite_output(Output::NormalizedEnergyLoss, (loss / initial).min(1.0))?;
        Some(PlanarEnergy {
            initial,
            r#final,
            loss,
            max_loss: initial,
            normalized_loss,
        })
    } else {
        None
    };
    Ok(
        PointMass { mass: m, vn, vt, e }.outcome(
            final_normal,
            normal_impulse,
            critical_impulse_ratio,
            energy,
        ),
    )
}
