//! Tangential restitution (section 3, Eqs 20–27): the bilinear model.
//!
//! The impulse ratio `μ_et` that gives `V_ct = −e_t v_ct` (Eq 20) is used when
//! `|μ_et| ≤ f` (regime `restitution`); otherwise the contact slides through
//! separation with `|μ| = f` opposing the initial slip (regime `sliding`).
//! With `e_t = 0` this is Coulomb friction with the critical ratio `μ_c`
//! (see [`crate::oblique`]). For `d_c = 0` the switch lies at
//! `f = (1 + e_t) |μ_c|` (Eq 24: `μ_et = (1 + e_t) μ_c`); the printed Eq 26 swaps
//! its two ranges and Eq 23 prints `(1 + e)` for `(1 + e_t)` (see `docs/physics.md`).

use crate::error::{Input, Result, in_range};
use crate::planar::{
    Outputs, PlanarOutcome, Regime, assemble, no_impulse_solution, ratio_solution, target_solution,
};
use crate::scene::PlanarScene;

/// Solves an impact with friction `f ≥ 0` and tangential restitution
/// `−1 ≤ e_t ≤ 1` (`e_t = −1` means no tangential impulse from restitution).
pub fn solve(
    scene: &PlanarScene,
    restitution: f64,
    friction: f64,
    tangential_restitution: f64,
    outputs: Outputs,
) -> Result<PlanarOutcome> {
    let e = in_range(Input::Restitution, restitution, 0.0, 1.0)?;
    let f = in_range(Input::Friction, friction, 0.0, f64::INFINITY)?;
    let et = in_range(Input::TangentialRestitution, tangential_restitution, -1.0, 1.0)?;
    bilinear(scene, e, f, et, Regime::Restitution, outputs)
}

/// The bilinear law shared by Coulomb friction (`e_t = 0`, capped regime
/// `sticking`) and tangential restitution (capped regime `restitution`).
pub(crate) fn bilinear(
    scene: &PlanarScene,
    e: f64,
    f: f64,
    et: f64,
    capped_regime: Regime,
    outputs: Outputs,
) -> Result<PlanarOutcome> {
    let target = target_solution(scene, e, et);
    let mu_target = target.impulse_ratio;
    // For e_t = 0 the target ratio is the critical ratio μ_c itself.
    let known_critical = (et == 0.0).then(|| Some(mu_target).filter(|mu| target.dn != 0.0 && mu.is_finite()));
    if target.dn != 0.0 && mu_target.abs() <= f {
        if target.dn < 0.0 {
            return Err(no_impulse_solution(scene, mu_target, Input::Friction));
        }
        return assemble(
            scene,
            e,
            e,
            capped_regime,
            &target,
            known_critical,
            outputs,
            Input::Friction,
        );
    }
    let slip = scene.contact_velocity.tangential;
    let direction = if slip != 0.0 {
        -slip.signum()
    } else {
        mu_target.signum()
    };
    let mu = direction * f + 0.0;
    let sliding = ratio_solution(scene, e, mu, Input::Friction)?;
    assemble(
        scene,
        e,
        e,
        Regime::Sliding,
        &sliding,
        known_critical,
        outputs,
        Input::Friction,
    )
}
