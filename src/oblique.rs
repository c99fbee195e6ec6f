//! Oblique planar impact (sections 2 and 2.2, Eqs 1–19) with one tangential law:
//! a prescribed impulse ratio `μ` (Eq 2), Coulomb friction `f` capped by the
//! critical ratio `μ_c`, or the Appendix's two-phase kinetic restitution `R`.

use crate::error::{ImpactError, Input, Result, finite, in_range};
use crate::planar::{
    Outputs, PlanarOutcome, Regime, Solution, assemble, general_ratio_path, no_impulse_solution,
    ratio_solution,
};
use crate::scene::{ContactVelocity, PlanarScene};
use crate::tangential::bilinear;

/// The tangential law closing the planar equations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialLaw {
    /// A prescribed impulse ratio `μ = P_t / P_n` (Eqs 2, 4). Refused when it
    /// gives `D ≤ 0` or creates energy; the error states the admissible interval.
    ImpulseRatio(f64),
    /// Coulomb friction `f ≥ 0`: `μ = μ_c` when `|μ_c| ≤ f` (sticking, `V_ct = 0`),
    /// otherwise `|μ| = f` opposing the initial slip (sliding through separation).
    Friction(f64),
}

/// The Appendix's kinetic restitution: `R = P_n^R / P_n^A` (Eq 9) with the
/// approach and rebound impulse ratios `μ_A`, `μ_R` (Eqs 12, 13).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KineticRestitution {
    /// `R`, in `[0, 1]`.
    pub value: f64,
    /// `μ_A = P_t^A / P_n^A`.
    pub approach_impulse_ratio: f64,
    /// `μ_R = P_t^R / P_n^R`.
    pub rebound_impulse_ratio: f64,
}

/// Solves an oblique impact with kinematic restitution `e ∈ [0, 1]` and one tangential law.
pub fn solve(
    scene: &PlanarScene,
    restitution: f64,
    law: TangentialLaw,
    outputs: Outputs,
) -> Result<PlanarOutcome> {
    let e = in_range(Input::Restitution, restitution, 0.0, 1.0)?;
    match law {
        TangentialLaw::ImpulseRatio(mu) => {
            let mu = finite(Input::ImpulseRatio, mu)?;
            let sol = ratio_solution(scene, e, mu, Input::ImpulseRatio)?;
            assemble(
                scene,
                e,
                e,
                Regime::Prescribed,
                &sol,
                None,
                outputs,
                Input::ImpulseRatio,
            )
        }
        TangentialLaw::Friction(f) => {
            let f = in_range(Input::Friction, f, 0.0, f64::INFINITY)?;
            bilinear(scene, e, f, 0.0, Regime::Sticking, outputs)
        }
    }
}

/// Solves the two-phase model of the Appendix (Eqs A-1…A-16).
///
/// Approach ends at `v̄_cn = 0`: `P_n^A D(μ_A) = −m v_cn`.
/// Rebound: `P_n^R = R P_n^A`, and A-13 gives `V_cn = R D(μ_R) / D(μ_A) · (−v_cn)`,
/// so the equivalent kinematic coefficient is `e = R D(μ_R) / D(μ_A)` (Eq 11, A-16).
/// The reported impulse ratio is the overall `μ = (μ_A + R μ_R) / (1 + R)`.
pub fn solve_kinetic(
    scene: &PlanarScene,
    kinetic: KineticRestitution,
    outputs: Outputs,
) -> Result<PlanarOutcome> {
    let r = in_range(Input::KineticRestitution, kinetic.value, 0.0, 1.0)?;
    let mu_a = finite(Input::ApproachImpulseRatio, kinetic.approach_impulse_ratio)?;
    let mu_r = finite(Input::ReboundImpulseRatio, kinetic.rebound_impulse_ratio)?;
    let d_a = scene.dk2(mu_a);
    if d_a <= 0.0 || !d_a.is_finite() {
        return Err(no_impulse_solution(scene, mu_a, Input::ApproachImpulseRatio));
    }
    let d_r = scene.dk2(mu_r);
    if r > 0.0 && (d_r <= 0.0 || !d_r.is_finite()) {
        return Err(no_impulse_solution(scene, mu_r, Input::ReboundImpulseRatio));
    }
    let e = if r == 0.0 { 0.0 } else { r * (d_r / d_a) };
    if !e.is_finite() {
        return Err(ImpactError::OutputNotFinite {
            output: crate::error::Output::Restitution,
        });
    }
    let c = scene.contact_velocity;
    let s = -c.normal;
    // Each phase is a ratio answer: approach with "1 + e" = 1, rebound scaled by R.
    let (dn_a, dt_a, dw_a, dvct_a) = general_ratio_path(scene, s, mu_a, Input::ApproachImpulseRatio)?;
    let (dn_r, dt_r, dw_r, dvct_r) = if r == 0.0 {
        (0.0, 0.0, 0.0, 0.0)
    } else {
        let rebound_scale = r * s * (d_r / d_a);
        let (dn, dt, dw, dvct) = general_ratio_path(scene, rebound_scale, mu_r, Input::ReboundImpulseRatio)?;
        (dn, dt, dw, dvct)
    };
    let dn = dn_a + dn_r;
    let dt = dt_a + dt_r;
    let d_vct = dvct_a + dvct_r;
    let sol = Solution {
        dn,
        dt,
        d_omega: dw_a + dw_r,
        impulse_ratio: dt / dn,
        final_contact: ContactVelocity {
            normal: -e * c.normal,
            tangential: c.tangential + d_vct,
        },
        normal_sum: (1.0 - e) * c.normal,
        tangential_sum: 2.0f64.mul_add(c.tangential, d_vct),
    };
    assemble(
        scene,
        e,
        r,
        Regime::Prescribed,
        &sol,
        None,
        outputs,
        Input::KineticRestitution,
    )
}
