//! The Appendix's two-phase kinetic law in space (Eqs 9–13 and A-1…A-16 with
//! `Δu = W P`; conventions, rule 7). The approach impulse `P^A` ends the
//! approach (`U_n = 0`); the rebound adds `P^R` with `P^R·n = R P^A·n`. Both
//! phases' tangential impulses act along one direction `w`, opposing the
//! initial slip (`w = −u_t`; where `u_t = 0`, the approach's sticking
//! impulse's `P_t`, as the prescribed ratio's rule 4), with magnitudes `μ_A`
//! and `μ_R` times their normal ones:
//!
//! ```text
//! P^A = α (n + μ_A ρ w),  P^R = R α (n + μ_R ρ w),  ρ = √(ν/|w|²),
//! α = −u·n / D_A,  D = nᵀ W (n + μ ρ w),  e = −U_n/u_n = R D_R / D_A (A-16).
//! ```
//!
//! One fixed direction keeps one root per answer (the sliding law's `ρ`),
//! and in a planar scene it is the planar law with `μ_R` of `μ_A`'s sign.
//! With Coulomb friction `f_A` in the approach, the approach sticks when
//! `W P = −u` has `|P_t| ≤ f_A P_n` (`P^A` that impulse, `w` its `P_t`), else
//! slides as the ratio `μ_A = f_A`; the regime names the approach's branch.
//! (A rebound that opposed the slip left by the approach would need the
//! root of a number holding `ρ`: no longer one root per answer.)

use super::*;

/// The answer of the two-phase law: regime `prescribed`, no couple.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn kinetic<N: Radical, const L: usize>(
    sc: &mut Scene<'_, N>,
    phases: Phases,
    outputs: Outputs,
    outcome: &mut [SpatialOutcome; L],
) -> Exact<N, ()> {
    let (r, mu_r) = (phases.r, phases.rebound);
    let rebound = r > 0.0;
    let refuse = |error: ImpactError| -> Exact<N, ()> { Err(Fail::Refused(error)) };
    let zero = N::of(0.0);
    // The approach's sticking impulse (W P = −u: it ends with U = 0).
    let stick = map(
        &sym_mul(&sc.g.adj, &sc.u),
        #[cfg_attr(not(debug_assertions), inline(always))]
        |x| x.div(&sc.g.det).neg(),
    );
    let stick = sc.solution(stick, zero.clone());
    let (pointer, mu_a, kept) = match phases.approach {
        Approach::Ratio(mu) => (Input::ApproachImpulseRatio, mu, false),
        Approach::Friction(f) => (
            Input::ApproachFriction,
            f,
            sc.tangential_holds(&Some(stick.clone()))?,
        ),
    };
    // The direction: the sticking impulse's P_t if the approach sticks;
    // else against the slip, or that P_t where there is no slip.
    let slip = norm2(&sc.ut);
    let w = if !kept && sign(&slip)? == Ordering::Greater {
        Some((neg(&sc.ut), slip))
    } else {
        let size = norm2(&stick.pt);
        (sign(&size)? == Ordering::Greater).then(|| (stick.pt.clone(), size))
    };
    let prescribed = pointer == Input::ApproachImpulseRatio;
    if w.is_none() {
        if prescribed && mu_a > 0.0 {
            return refuse(ImpactError::NoSlipDirection { input: pointer });
        }
        if rebound && mu_r > 0.0 {
            return refuse(ImpactError::NoSlipDirection {
                input: Input::ReboundImpulseRatio,
            });
        }
    }
    // ρ w, the tangential direction scaled to |n|, where a phase uses it.
    let sliding = !kept && mu_a > 0.0;
    let along = match &w {
        Some((w, size)) if sliding || (rebound && mu_r > 0.0) => {
            let rho = sc.g.nu.div(size).sqrt().map_err(Fail::Undecided)?;
            Some(scale(&rho, w))
        }
        _ => None,
    };
    // D (scaled by ν) = nᵀ W n + μ (W n)·(ρ w).
    let wn = sym_mul(&sc.g.w_matrix, &sc.g.n);
    let nwn = dot(&sc.g.n, &wn);
    let coefficient = |mu: f64| match &along {
        Some(a) if mu > 0.0 => N::of(mu).mul_add(&dot(&wn, a), &nwn),
        _ => nwn.clone(),
    };
    // The approach P^A = α n + (its tangential part), with α = P^A·n/ν.
    let (alpha, approach_t) = if kept {
        if sign(&stick.pn)? != Ordering::Greater {
            return refuse(ImpactError::NoImpulse { input: pointer });
        }
        (stick.pn.div(&sc.g.nu), stick.pt.clone())
    } else {
        let d_a = coefficient(mu_a);
        if sign(&d_a)? != Ordering::Greater {
            return refuse(ImpactError::NoImpulse { input: pointer });
        }
        let alpha = sc.un.neg().div(&d_a);
        let tangential = match &along {
            Some(a) if sliding => map(a, |x| N::of(mu_a).mul(&alpha).mul(x)),
            _ => [zero.clone(), zero.clone(), zero.clone()],
        };
        (alpha, tangential)
    };
    let d_r = coefficient(mu_r);
    if rebound && sign(&d_r)? != Ordering::Greater {
        return refuse(ImpactError::NoImpulse {
            input: Input::ReboundImpulseRatio,
        });
    }
    // The rebound R α (n + μ_R ρ w); e = −U_n/u_n = R α D_R / (−u·n) (A-16).
    let beta = N::of(r).mul(&alpha);
    let e = if rebound {
        beta.mul(&d_r).div(&sc.un.neg())
    } else {
        zero.clone()
    };
    let pt = match &along {
        Some(a) if rebound && mu_r > 0.0 => {
            let k = N::of(mu_r).mul(&beta);
            zip(
                &approach_t,
                a,
                #[cfg_attr(not(debug_assertions), inline(always))]
                |x, y| k.mul_add(y, x),
            )
        }
        _ => approach_t,
    };
    let normal = alpha.add(&beta);
    let s = Solution {
        p: axpy(&normal, &sc.g.n, &pt),
        pn: normal.mul(&sc.g.nu),
        pt,
        kappa: zero.clone(),
    };
    let du = sym_mul(&sc.g.w_matrix, &s.p);
    let (final_ut, slip_sum) = sc.slip_after(&du);
    let work = sc.work(&s, &e, &slip_sum, &zero);
    if sign(&work)? == Ordering::Greater {
        return refuse(ImpactError::EnergyCreated {
            input: Input::KineticRestitution,
            energy_loss: -0.5 * work.approx(),
        });
    }
    // |P_t| / P_n: (μ_A + R μ_R) / (1 + R) along the one direction; of the
    // impulse itself after a sticking approach.
    let impulse_ratio = if kept {
        sc.ratio::<L>(&s, Output::ImpulseRatio)?.unwrap_or([0.0; L])
    } else if along.is_some() {
        let one = N::of(1.0);
        let mu_a = if sliding { mu_a } else { 0.0 };
        let ratio = N::of(r)
            .mul_add(&N::of(if rebound { mu_r } else { 0.0 }), &N::of(mu_a))
            .div(&one.add(&N::of(r)));
        outs::<N, L>(Output::ImpulseRatio, &ratio)?
    } else {
        [0.0; L]
    };
    // μ_c of the sticking impulse with the equivalent e (rule 5).
    let critical_impulse_ratio = if outputs.critical_impulse_ratio {
        let q = N::of(1.0).add(&e).mul(&sc.un).neg();
        let target = axpy(&q.div(&sc.g.nu), &sc.g.n, &neg(&sc.ut));
        let stick = divide(&sym_mul(&sc.g.adj, &target), &sc.g.det);
        sc.ratio::<L>(&sc.solution(stick, zero), Output::CriticalImpulseRatio)?
    } else {
        None
    };
    let final_spin = sc.s.add(&dot(&sc.g.w, &s.p));
    let answer = Written {
        s,
        e,
        final_ut,
        final_spin,
        work,
        impulse_ratio,
        critical_impulse_ratio,
        regime: match phases.approach {
            Approach::Ratio(_) => Regime::Prescribed,
            Approach::Friction(_) if kept => Regime::Sticking,
            Approach::Friction(_) => Regime::Sliding,
        },
        torsional_regime: None,
    };
    write(sc, answer, outputs, outcome)
}
