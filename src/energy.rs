//! Kinetic energies of the planar and torsional answers.
//!
//! The loss `T_L` is never formed as `T_initial − T_final` (which cancels
//! catastrophically for `e → 1`, `μ → 0`): the planar loss is the work of the
//! impulses (see [`crate::planar`]), the torsional loss is `½ I_n (ω_n − Ω_n)(ω_n + Ω_n)`
//! with both factors formed from the branch formulas.

use crate::error::{Output, Result, finite_output};
use crate::scene::{PlanarScene, PlanarVelocity};

/// Kinetic energies of a planar answer.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarEnergy {
    /// Initial kinetic energy `½ m (v_n² + v_t²) + ½ I ω²`.
    pub initial: f64,
    /// Final kinetic energy `½ m (V_n² + V_t²) + ½ I Ω²`.
    pub r#final: f64,
    /// Energy loss `T_L` (Eq 8 in work form), `≥ 0` for every accepted answer.
    pub loss: f64,
    /// Maximum loss `T_M`: the loss when the contact point stops (`e = 0`, `V_ct = 0`).
    pub max_loss: f64,
    /// `T_L* = T_L / T_M` (Appendix), in `[0, 1]` for every accepted answer.
    pub normalized_loss: f64,
}

/// Kinetic energy per unit mass `½ (v_n² + v_t² + k² ω²)` of a planar motion.
pub fn planar_kinetic_per_mass(k2: f64, v: &PlanarVelocity) -> f64 {
    let sum = v.normal.mul_add(
        v.normal,
        v.tangential.mul_add(v.tangential, k2 * v.angular * v.angular),
    );
    0.5 * sum
}

/// `T_M`, the largest loss any impulse at C can produce: the contact point
/// ends at rest, `P = −W⁻¹ v_c`, so
/// `T_M / m = [k² (v_cn² + v_ct²) + (d_d v_cn + d_c v_ct)²] / (2 (k² + d_c² + d_d²))`,
/// a sum of non-negative terms. It bounds `T_L` because `T_L(P)` is a concave
/// quadratic in `P` with its maximum there, hence `T_L* ≤ 1`.
pub fn max_loss_per_mass(scene: &PlanarScene) -> f64 {
    let dc = scene.contact.tangential_offset;
    let dd = scene.contact.normal_offset;
    let k2 = scene.k2;
    let c = scene.contact_velocity;
    let s = dc.mul_add(dc, dd.mul_add(dd, k2));
    let speed2 = c.normal.mul_add(c.normal, c.tangential * c.tangential);
    let h = dd.mul_add(c.normal, dc * c.tangential);
    0.5 * (k2 / s).mul_add(speed2, h * (h / s))
}

/// Energies of a planar answer given its final velocity and its loss per unit mass.
///
/// Everything is formed per unit mass and multiplied by `m` last, so `T_L*`
/// never divides two underflowed energies. `T_L*` is clamped to 1: the exact
/// value cannot exceed it (see [`max_loss_per_mass`]), only rounding can.
pub(crate) fn planar(
    scene: &PlanarScene,
    final_velocity: &PlanarVelocity,
    loss_per_mass: f64,
) -> Result<PlanarEnergy> {
    let m = scene.body.mass();
    let max_per_mass = max_loss_per_mass(scene);
    let initial = m * planar_kinetic_per_mass(scene.k2, &scene.velocity);
    let r#final = m * planar_kinetic_per_mass(scene.k2, final_velocity);
    Ok(PlanarEnergy {
        initial: finite_output(Output::InitialEnergy, initial)?,
        r#final: finite_output(Output::FinalEnergy, r#final)?,
        loss: finite_output(Output::EnergyLoss, m * loss_per_mass + 0.0)?,
        max_loss: finite_output(Output::MaxEnergyLoss, m * max_per_mass)?,
        normalized_loss: finite_output(
            Output::NormalizedEnergyLoss,
            (loss_per_mass / max_per_mass).min(1.0) + 0.0,
        )?,
    })
}
