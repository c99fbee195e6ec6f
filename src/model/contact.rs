//! The laws of one point contact, written once in contact space for every
//! scene: one lamina against a barrier (`barrier.rs`) and two laminae, or one
//! against a barrier, in world axes (`bodies.rs`).
//!
//! A scene reduces to its contact space: the approach velocity `s = −u_n > 0`,
//! the slip `u_t`, and the symmetric positive definite matrix `W̃` with
//! `Δu = W̃ q` (Eqs A-1…A-3 with `ΔU = W P`), each in the scene's own scaling
//! (the one body's per-unit-mass `k²`-scaled forms; two bodies' unnormalised
//! normal). Every law is then one or two of two answers with a decision between
//! them: a given impulse ratio `μ` ([`ratio_answer`], Eqs 5–7, `q_t = μ q_n`,
//! `q_n (W̃_nn + μ W̃_nt) = (1 + e) s`) or a given final contact velocity
//! ([`target_answer`], Eqs 1, 20 and 3: `q = W̃⁻¹ Δu`). The scene turns the
//! answer's impulse into its bodies' outputs ([`ContactSpace::assemble`]).

use std::cmp::Ordering;

use super::{Exact, abs, sign};
use crate::arith::Field;
use crate::error::{ImpactError, Input, Output};
use crate::law::{Approach, Law, Phases, Reading};
use crate::outcome::{Outputs, Regime};

/// A scene's contact space in the field `N`: the approach and the slip, and
/// `W̃ = [[A, B], [B, C]]` in `(n, t)` order.
pub(crate) struct Reduced<N> {
    /// `u_n < 0`.
    pub un: N,
    /// `u_t`.
    pub ut: N,
    /// `s = −u_n > 0`.
    pub s: N,
    /// `A = W̃_nn`.
    pub wnn: N,
    /// `B = W̃_nt`.
    pub wnt: N,
    /// `C = W̃_tt`.
    pub wtt: N,
}

/// A scene reduced to its contact space, in the field `N`.
///
/// `W̃ = [[A, B], [B, C]]` in `(n, t)` order; `q` is the impulse in the scene's
/// unit, `Δn`/`Δt` its parts as the scene carries them.
pub(crate) trait ContactSpace<N: Field> {
    /// What the scene carries beside the impulse per answer (the one body's
    /// spin change; nothing for bodies in world axes, whose spins follow from `q`).
    type Turn: Clone;
    /// The outcome the scene answers.
    type Outcome;
    /// The scene's approach, slip and `W̃`.
    fn reduced(&self) -> &Reduced<N>;
    /// `A + μ B` (the scaled `D(μ)`, after Eq 7) and the turn per unit of it.
    fn ratio_coefficient(&self, mu: f64) -> (N, Self::Turn);
    /// The refusal of ratio `μ` whose `A + μ B ≤ 0`.
    fn no_impulse_solution(&self, mu: f64, law: Input) -> ImpactError;
    /// `Δn` for ratio answers, `per = q_n / (A + μ B)` being given with the
    /// asked change `q_n` of `u_n`.
    fn ratio_normal(&self, qn: &N, per: &N) -> N;
    /// The turn of a ratio answer.
    fn ratio_turn(&self, lever: &Self::Turn, per: &N) -> Self::Turn;
    /// `1 / det W̃` in the scene's unit of `Δ`.
    fn inv_det(&self) -> N;
    /// `Δn` of a target answer: `(C q_n + B q_t) / det`, given as `sdn`.
    fn target_normal(&self, qn: &N, sdn: &N, inv_det: &N) -> N;
    /// The turn of a target answer that changes `u_n` by `q_n` and `u_t` by `−q_t`.
    fn target_turn(&self, qn: &N, qt: &N, inv_det: &N) -> Self::Turn;
    /// The refusal of an answer whose `work` (`Δn (u_n + U_n) + Δt (u_t + U_t)`)
    /// is positive: it would create energy.
    fn creates_energy(&self, e: &N, mu: &N, work: &N, law: Input) -> ImpactError;
    /// The turn of two phases together.
    fn add_turns(a: &Self::Turn, b: &Self::Turn) -> Self::Turn;
    /// Writes the outcome of one answer (see [`Assembly`]) to `out`, whole
    /// or not at all (written in place: a returned outcome would be copied
    /// through every caller's result).
    fn assemble(&self, answer: &Assembly<'_, N, Self::Turn>, out: &mut Self::Outcome) -> Exact<N, ()>;
}

/// One answer in the field: impulse parts, turn, final contact velocity, the
/// sums `u + U` the work needs, and the impulse ratio (absent when `Δn = 0`).
#[derive(Clone)]
pub(crate) struct Answer<N, T> {
    /// `q_n = (1 + e) s`, the change of `u_n` restitution asks.
    pub qn: N,
    pub dn: N,
    pub dt: N,
    pub turn: T,
    /// `U_n`.
    pub un: N,
    /// `U_t`.
    pub ut: N,
    /// `u_n + U_n`, formed as `(1 − e) u_n` (no cancellation for `e → 1`).
    pub normal_sum: N,
    /// `u_t + U_t`, formed without cancellation where the law allows.
    pub tangential_sum: N,
    pub mu: Option<N>,
}

/// The target's impulse ([`target_impulse`]): `q_t`, `det·Δn`, `det·Δt`, `μ`.
struct TargetImpulse<N> {
    qt: N,
    sdn: N,
    sdt: N,
    mu: Option<N>,
}

/// What a scene assembles an outcome from: the answer and the law's reports.
pub(crate) struct Assembly<'a, N, T> {
    /// Restitution `e` (the equivalent `e` of the kinetic law).
    pub e: &'a N,
    /// `R` under the kinetic law.
    pub kinetic_restitution: Option<f64>,
    pub regime: Regime,
    pub answer: &'a Answer<N, T>,
    /// The impulse ratio, checked present.
    pub mu: &'a N,
    /// `Δn (u_n + U_n) + Δt (u_t + U_t)`, checked `≤ 0` (no energy created).
    pub work: N,
    /// `μ_c`, when asked for or known: `None` inside when its `Δn = 0`.
    pub critical: Option<Option<N>>,
    pub outputs: Outputs,
}

/// The law's answer in a scene. The law is read as branches once for the
/// plane and space ([`Reading`]): a single ratio `c` (frictionless, a
/// prescribed `μ`), a kept target `U_t = −e_t u_t` capped by `f` with sliding
/// beyond it, or two phases.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn under_law<N: Field, S: ContactSpace<N>>(
    sc: &S,
    law: &Law,
    outputs: Outputs,
    out: &mut S::Outcome,
) -> Exact<N, ()> {
    let law = Reading::of(law, false);
    if let Some(phases) = &law.phases {
        return kinetic(sc, phases, outputs, out);
    }
    let e = N::of(law.e);
    match law.kept {
        None => {
            let answer = ratio_answer(sc, &e, &normal_target(sc, &e), law.c, law.pointers.0)?;
            finish(
                sc,
                &e,
                None,
                law.regimes.0,
                &answer,
                None,
                outputs,
                law.pointers.0,
                out,
            )
        }
        Some(et) => bilinear(sc, &e, et, &law, outputs, out),
    }
}

/// `q_n = (1 + e) s`: the change of `u_n` that restitution `e` asks (Eq 1).
#[cfg_attr(not(debug_assertions), inline(always))]
fn normal_target<N: Field, S: ContactSpace<N>>(sc: &S, e: &N) -> N {
    let cs = sc.reduced();
    N::of(1.0).add(e).mul(&cs.s)
}

/// `A + μ B` with its turn, refused (naming `law`) unless positive.
#[cfg_attr(not(debug_assertions), inline(always))]
fn positive_coefficient<N: Field, S: ContactSpace<N>>(sc: &S, mu: f64, law: Input) -> Exact<N, (S::Turn, N)> {
    let (d, lever) = sc.ratio_coefficient(mu);
    if sign(&d)? == Ordering::Greater {
        Ok((lever, d))
    } else {
        Err(sc.no_impulse_solution(mu, law).into())
    }
}

/// `(Δn, Δt, turn, ΔU_t)` for ratio `μ` changing `u_n` by `q_n` (Eqs 5–7):
/// `q_n = (A + μ B) Δ_n`, `ΔU_t = (B + μ C) q_n / (A + μ B)`.
#[cfg_attr(not(debug_assertions), inline(always))]
fn ratio_parts<N: Field, S: ContactSpace<N>>(
    sc: &S,
    qn: &N,
    mu: f64,
    lever: &S::Turn,
    d: &N,
) -> (N, N, S::Turn, N) {
    let cs = sc.reduced();
    let mu = N::of(mu);
    let per = qn.div(d);
    let dn = sc.ratio_normal(qn, &per);
    let dt = mu.mul(&dn);
    let turn = sc.ratio_turn(lever, &per);
    let dut = mu.mul_add(&cs.wtt, &cs.wnt).mul(&per);
    (dn, dt, turn, dut)
}

/// The answer for a prescribed ratio `μ` with restitution `e` (`q_n` its
/// [`normal_target`]).
#[cfg_attr(not(debug_assertions), inline(always))]
fn ratio_answer<N: Field, S: ContactSpace<N>>(
    sc: &S,
    e: &N,
    qn: &N,
    mu: f64,
    law: Input,
) -> Exact<N, Answer<N, S::Turn>> {
    let cs = sc.reduced();
    let (lever, d) = positive_coefficient(sc, mu, law)?;
    let (dn, dt, turn, dut) = ratio_parts(sc, qn, mu, &lever, &d);
    Ok(Answer {
        qn: qn.clone(),
        dn,
        dt,
        turn,
        un: e.mul(&cs.un).neg(),
        normal_sum: N::of(1.0).sub(e).mul(&cs.un),
        tangential_sum: N::of(2.0).mul_add(&cs.ut, &dut),
        ut: cs.ut.add(&dut),
        mu: Some(N::of(mu)),
    })
}

/// `det·Δn = C q_n + B q_t` and `det·Δt = −B q_n − A q_t`: the impulse
/// (`adj W̃ Δu`) that changes `u_n` by `q_n` and `u_t` by `−q_t`.
#[cfg_attr(not(debug_assertions), inline(always))]
fn scaled_impulses<N: Field, S: ContactSpace<N>>(sc: &S, qn: &N, qt: &N) -> (N, N) {
    let cs = sc.reduced();
    (
        cs.wtt.mul_add(qn, &cs.wnt.mul(qt)),
        cs.wnt.neg().mul_add(qn, &cs.wnn.mul(qt).neg()),
    )
}

/// The target's impulse `U_n = −e u_n`, `U_t = −e_t u_t` (Eqs 1, 20, 3),
/// `q_t = (1 + e_t) u_t`, scaled: `det·Δn` and `det·Δt`, whose signs and
/// ratio decide the bilinear law without a quotient, and its ratio `μ`
/// (absent when `Δn = 0`).
#[cfg_attr(not(debug_assertions), inline(always))]
fn target_impulse<N: Field, S: ContactSpace<N>>(sc: &S, qn: &N, et: f64) -> Exact<N, TargetImpulse<N>> {
    let qt = N::of(1.0).add(&N::of(et)).mul(&sc.reduced().ut);
    let (sdn, sdt) = scaled_impulses(sc, qn, &qt);
    let mu = (sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn));
    Ok(TargetImpulse { qt, sdn, sdt, mu })
}

/// The target answer of [`target_impulse`], formed only where the law
/// keeps it; for one body with `d_c = 0` these are Eqs 21–23 and 25.
#[cfg_attr(not(debug_assertions), inline(always))]
fn target_answer<N: Field, S: ContactSpace<N>>(
    sc: &S,
    e: &N,
    qn: &N,
    et: f64,
    target: &TargetImpulse<N>,
) -> Answer<N, S::Turn> {
    let cs = sc.reduced();
    let inv = &sc.inv_det();
    Answer {
        un: e.mul(&cs.un).neg(),
        ut: N::of(et).mul(&cs.ut).neg(),
        normal_sum: N::of(1.0).sub(e).mul(&cs.un),
        tangential_sum: N::of(1.0).sub(&N::of(et)).mul(&cs.ut),
        dn: sc.target_normal(qn, &target.sdn, inv),
        dt: target.sdt.mul(inv),
        turn: sc.target_turn(qn, &target.qt, inv),
        qn: qn.clone(),
        mu: target.mu.clone(),
    }
}

/// `μ_c`: the ratio `Δt / Δn` of the answer that ends with `U_t = 0`
/// (`q_t = u_t`) and changes `u_n` by `q_n` (Eq 14 for one body with
/// `d_c = 0`), `None` if its `Δn = 0`.
#[cfg_attr(not(debug_assertions), inline(always))]
fn critical_ratio<N: Field, S: ContactSpace<N>>(sc: &S, qn: &N) -> Exact<N, Option<N>> {
    let cs = sc.reduced();
    let (sdn, sdt) = scaled_impulses(sc, qn, &cs.ut);
    Ok((sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn)))
}

/// The bilinear law (section 3; Coulomb friction for `e_t = 0`): the
/// target answer `U_t = −e_t u_t` when its ratio satisfies `|μ| ≤ f` (`f`
/// the law's cap; the law's first regime), else sliding through separation
/// with `|μ| = f` opposing the initial slip.
#[cfg_attr(not(debug_assertions), inline(always))]
fn bilinear<N: Field, S: ContactSpace<N>>(
    sc: &S,
    e: &N,
    et: f64,
    law: &Reading,
    outputs: Outputs,
    out: &mut S::Outcome,
) -> Exact<N, ()> {
    let cs = sc.reduced();
    let f = law.cap;
    let (kept, sliding) = law.pointers;
    let qn = normal_target(sc, e);
    let target = target_impulse(sc, &qn, et)?;
    let (sdn, sdt) = (&target.sdn, &target.sdt);
    // For e_t = 0 the target ratio is the critical ratio μ_c itself.
    let known_critical = (et == 0.0).then(|| target.mu.clone());
    if let Some(mu_target) = &target.mu {
        // |det Δt| ≤ f |det Δn|, i.e. |μ_target| ≤ f, decided without a quotient.
        let room = N::of(f).mul(&abs(sdn)?).sub(&abs(sdt)?);
        if sign(&room)? != Ordering::Less {
            if sign(sdn)? == Ordering::Less {
                return Err(sc.no_impulse_solution(mu_target.approx(), kept).into());
            }
            return finish(
                sc,
                e,
                None,
                law.regimes.0,
                &target_answer(sc, e, &qn, et, &target),
                known_critical,
                outputs,
                kept,
                out,
            );
        }
    }
    // Sliding opposes the slip; with no initial slip it follows μ_target
    // (which exists then: u_t = 0 gives Δn > 0).
    let direction = match sign(&cs.ut)? {
        Ordering::Greater => -1.0,
        Ordering::Less => 1.0,
        Ordering::Equal => match (sign(sdt)?, sign(sdn)?) {
            (Ordering::Less, Ordering::Greater) | (Ordering::Greater, Ordering::Less) => -1.0,
            _ => 1.0,
        },
    };
    let answer = ratio_answer(sc, e, &qn, direction * f + 0.0, sliding)?;
    finish(
        sc,
        e,
        None,
        law.regimes.1,
        &answer,
        known_critical,
        outputs,
        sliding,
        out,
    )
}

/// The Appendix's two phases: approach to `ū_n = 0`, rebound
/// `P_n^R = R P_n^A` with `μ_R`; `e = R D(μ_R) P_n^A / s` (Eq 11, A-16; with
/// a ratio approach `e = R D(μ_R) / D(μ_A)`). The approach takes the
/// prescribed ratio `μ_A`, or Coulomb friction `f_A` (conventions, rule 7):
/// the impulse that ends the approach with `U = 0` when its `|μ| ≤ f_A`,
/// else `|μ| = f_A` opposing the slip; the rebound's ratio `μ_R` is then a
/// magnitude along the approach's tangential impulse, as in space. The
/// reported ratio is the overall `μ = P_t / P_n`.
#[cfg_attr(not(debug_assertions), inline(always))]
fn kinetic<N: Field, S: ContactSpace<N>>(
    sc: &S,
    phases: &Phases,
    outputs: Outputs,
    out: &mut S::Outcome,
) -> Exact<N, ()> {
    let cs = sc.reduced();
    let r = phases.r;
    let (approach, normal, mu_r, regime) = match phases.approach {
        Approach::Ratio(mu_a) => {
            let (lever_a, d_a) = positive_coefficient(sc, mu_a, Input::ApproachImpulseRatio)?;
            let approach = ratio_parts(sc, &cs.s, mu_a, &lever_a, &d_a);
            (
                approach,
                ApproachNormal::Ratio(d_a),
                phases.rebound,
                Regime::Prescribed,
            )
        }
        Approach::Friction(f_a) => coulomb_approach(sc, f_a, r > 0.0, phases.rebound)?,
    };
    let rebound = if r > 0.0 {
        Some(positive_coefficient(sc, mu_r, Input::ReboundImpulseRatio)?)
    } else {
        None
    };
    let e = match (&rebound, &normal) {
        (Some((_, d_r)), ApproachNormal::Ratio(d_a)) => N::of(r).mul(&d_r.div(d_a)),
        (Some((_, d_r)), ApproachNormal::Stick(q_na)) => N::of(r).mul(&d_r.mul(q_na).div(&cs.s)),
        (None, _) => N::of(0.0),
    };
    let (dn, dt, turn, dut) = match &rebound {
        Some((lever_r, d_r)) => {
            let rebound = ratio_parts(sc, &e.mul(&cs.s), mu_r, lever_r, d_r);
            (
                approach.0.add(&rebound.0),
                approach.1.add(&rebound.1),
                S::add_turns(&approach.2, &rebound.2),
                approach.3.add(&rebound.3),
            )
        }
        None => approach,
    };
    let answer = Answer {
        qn: normal_target(sc, &e),
        mu: Some(dt.div(&dn)),
        un: e.mul(&cs.un).neg(),
        normal_sum: N::of(1.0).sub(&e).mul(&cs.un),
        tangential_sum: N::of(2.0).mul_add(&cs.ut, &dut),
        ut: cs.ut.add(&dut),
        dn,
        dt,
        turn,
    };
    finish(
        sc,
        &e,
        Some(r),
        regime,
        &answer,
        None,
        outputs,
        Input::KineticRestitution,
        out,
    )
}

/// The approach's normal impulse, as `e` reads it: `1/D(μ_A)` per unit of
/// `s` for a ratio approach, the sticking impulse's `q_n` otherwise.
enum ApproachNormal<N> {
    Ratio(N),
    Stick(N),
}

/// An approach under Coulomb friction `f_A`: its parts, its normal impulse,
/// the rebound's signed ratio (`μ_R` along the approach's tangential
/// impulse) and the regime (sticking or sliding).
#[allow(clippy::type_complexity)] // the parts of one phase, named where they are read
#[cfg_attr(not(debug_assertions), inline(always))]
fn coulomb_approach<N: Field, S: ContactSpace<N>>(
    sc: &S,
    f_a: f64,
    rebound: bool,
    mu_r: f64,
) -> Exact<N, ((N, N, S::Turn, N), ApproachNormal<N>, f64, Regime)> {
    let cs = sc.reduced();
    // The impulse that ends the approach with U = 0 (q_n = s, q_t = u_t).
    let (sdn, sdt) = scaled_impulses(sc, &cs.s, &cs.ut);
    let normal = sign(&sdn)?;
    let sticks =
        normal != Ordering::Equal && sign(&N::of(f_a).mul(&abs(&sdn)?).sub(&abs(&sdt)?))? != Ordering::Less;
    // The tangential impulse's sign along t̂: the sticking impulse's when the
    // approach sticks or nothing slips, else against the slip.
    let slip = sign(&cs.ut)?;
    let along = match (sticks, slip) {
        (false, Ordering::Greater) => Some(-1.0),
        (false, Ordering::Less) => Some(1.0),
        _ => match sign(&sdt)? {
            Ordering::Greater => Some(1.0),
            Ordering::Less => Some(-1.0),
            Ordering::Equal => None,
        },
    };
    if along.is_none() && rebound && mu_r > 0.0 {
        return Err(ImpactError::NoSlipDirection {
            input: Input::ReboundImpulseRatio,
        }
        .into());
    }
    let mu_r = along.map_or(0.0, |a| a * mu_r + 0.0);
    if sticks {
        if normal != Ordering::Greater {
            return Err(ImpactError::NoImpulse {
                input: Input::ApproachFriction,
            }
            .into());
        }
        let inv = &sc.inv_det();
        let parts = (
            sc.target_normal(&cs.s, &sdn, inv),
            sdt.mul(inv),
            sc.target_turn(&cs.s, &cs.ut, inv),
            cs.ut.neg(),
        );
        return Ok((parts, ApproachNormal::Stick(sdn.mul(inv)), mu_r, Regime::Sticking));
    }
    let mu_a = along.map_or(0.0, |a| a * f_a + 0.0);
    let (lever_a, d_a) = positive_coefficient(sc, mu_a, Input::ApproachFriction)?;
    let parts = ratio_parts(sc, &cs.s, mu_a, &lever_a, &d_a);
    Ok((parts, ApproachNormal::Ratio(d_a), mu_r, Regime::Sliding))
}

/// Checks one answer and hands it to the scene: the ratio must exist, the
/// work `Δn (u_n + U_n) + Δt (u_t + U_t)` (the loss is `−½` of it in the
/// scene's unit: Kelvin and Tait, as in the Appendix) must not be positive,
/// and `μ_c` is formed when asked for.
#[allow(clippy::too_many_arguments)] // each argument is one named part of the answer
#[cfg_attr(not(debug_assertions), inline(always))]
fn finish<N: Field, S: ContactSpace<N>>(
    sc: &S,
    e: &N,
    kinetic_restitution: Option<f64>,
    regime: Regime,
    a: &Answer<N, S::Turn>,
    known_critical: Option<Option<N>>,
    outputs: Outputs,
    law: Input,
    out: &mut S::Outcome,
) -> Exact<N, ()> {
    let mu = a.mu.as_ref().ok_or(ImpactError::OutputNotFinite {
        output: Output::ImpulseRatio,
    })?;
    let work = a.dn.mul_add(&a.normal_sum, &a.dt.mul(&a.tangential_sum));
    if sign(&work)? == Ordering::Greater {
        return Err(sc.creates_energy(e, mu, &work, law).into());
    }
    let critical = match known_critical {
        Some(known) if outputs.critical_impulse_ratio || known.is_some() => Some(known),
        None if outputs.critical_impulse_ratio => Some(critical_ratio(sc, &a.qn)?),
        _ => None,
    };
    sc.assemble(
        &Assembly {
            e,
            kinetic_restitution,
            regime,
            answer: a,
            mu,
            work,
            critical,
            outputs,
        },
        out,
    )
}

/// `μ_c` as each of `L` lanes' output (`None` when not asked for), refused
/// when its `Δn = 0`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn critical_output<N: Field, const L: usize>(
    critical: &Option<Option<N>>,
) -> Exact<N, [Option<f64>; L]> {
    match critical {
        Some(Some(mu_c)) => Ok(super::outs::<N, L>(Output::CriticalImpulseRatio, mu_c)?.map(Some)),
        Some(None) => Err(ImpactError::OutputNotFinite {
            output: Output::CriticalImpulseRatio,
        }
        .into()),
        None => Ok([None; L]),
    }
}
