//! One point contact in space: body A against body B or a fixed barrier,
//! with full inertia tensors, slip in any direction and an optional twist
//! about the normal (section 4 generalised).
//!
//! Each body `b` has mass `m_b`, inertia tensor `I_b` about its mass centre
//! (world axes), velocity `v_b`, angular velocity `ω_b` and `r_b = C − G_b`;
//! the normal `n` (from B into A) is not normalised. The unknowns are the
//! impulse `P` on A (`−P` on B) and the couple `κ n` about the normal
//! (`κ = M/|n|`); the velocities they change are the relative contact-point
//! velocity `u = Σ± (v_b + ω_b × r_b)` and the scaled relative spin
//! `s̃ = (ω_A − ω_B)·n = |n| s`. Then
//!
//! ```text
//! Δu = W P + w κ,   Δs̃ = wᵀ P + k κ,
//! W = Σ_b (1/m_b + [r_b]×ᵀ I_b⁻¹ [r_b]×),  w = Σ_b (I_b⁻¹ n) × r_b,  k = Σ_b nᵀ I_b⁻¹ n,
//! ```
//!
//! the symmetric positive definite 4×4 contact matrix `𝒲̃` (`J = |n|²/k`).
//! With `ν = |n|²`, the normal part of a vector `x` is `(x·n)/ν n`, so every
//! law but sliding is rational in the inputs:
//!
//! - kept tangential branch (stick, or `e_t` restitution): `Δu = q n/ν − (1 + e_t) u_t`,
//!   `q = −(1 + e) u·n` (Eqs 1, 20);
//! - sliding (and a prescribed ratio `μ`): `P = p̃ (n + c √(ν/|w_s|²) w_s)` with
//!   `c = f` (or `μ`), `w_s = −u_t` (or the sticking impulse's `P_t` when
//!   `u_t = 0`): one square root per answer, held exactly by [`crate::arith::Surd`];
//! - twist restitution: `Δs̃ = −(1 + e_z) s̃` (Eq 28); twist sliding:
//!   `κ = −e_z s̃/k + τ μ_z ρ_p (P·n)/ν` (Eqs 29–30 divided by `|n|`), `τ = −sgn s̃`
//!   (or the sign of the restitution branch's couple when `s̃ = 0`).
//!
//! When both laws have two branches, the answer is the one combination in
//! which each kept branch holds its cap and each sliding branch is taken only
//! where its kept branch (with the same partner) fails; none or several:
//! refused as not unique (conventions, rules 1–8).

mod kinetic;
mod law;
mod scene;

use std::cmp::Ordering;

use super::{Exact, Fail, abs, half, outs, outs_times_sqrt, sign};
use crate::arith::{Field, Radical};
use crate::error::{ImpactError, Input, Output};
use crate::input::{RigidBody, SpatialImpact, Twist};
use crate::law::{Approach, Phases, Reading};
use crate::outcome::{
    Outputs, PlanarEnergy, Regime, SPATIAL_BODY_OUTPUTS, SpatialBodyOutcome, SpatialContactVelocities,
    SpatialContactVelocity, SpatialImpulse, SpatialOutcome, TorsionalRegime,
};

use self::kinetic::kinetic;
use self::law::*;
pub(crate) use self::scene::Geometry;
use self::scene::*;
use super::vector::*;

/// The leading principal minors `I_xx`, `I_xx I_yy − I_xy²` and `det I` of a
/// tensor `[xx, yy, zz, xy, xz, yz]`: it is positive definite when all three
/// are positive (Sylvester's criterion).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn leading_minors<N: Field>(tensor: &[f64; 6]) -> [N; 3] {
    let m = sym::<N>(tensor);
    let second = m[0].mul_add(&m[1], &m[3].mul(&m[3]).neg());
    let (_, det) = adjugate(&m);
    [m[0].clone(), second, det]
}

/// The relative normal contact velocity `u·n` (unnormalised), by the same
/// operations as the scene: what validation decides the approach on.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn approach<N: Field>(impact: &SpatialImpact) -> N {
    let c: V3<N> = vector(impact.contact.point);
    let n = vector(impact.contact.normal);
    // Only the velocities: no tensor inverse, which the decision does not need.
    let velocity = |b: &RigidBody| {
        let r = sub(&c, &vector(b.position));
        point_velocity(&vector(b.velocity), &vector(b.angular_velocity), &r)
    };
    let mut u = velocity(&impact.a);
    if let Some(b) = &impact.b {
        u = sub(&u, &velocity(b));
    }
    dot(&u, &n)
}

fn three(o: &[Output], from: usize) -> [Output; 3] {
    [o[from], o[from + 1], o[from + 2]]
}

/// A validated spatial contact in the field `N`: refused unless it
/// approaches (`u·n < 0`, decided exactly in the exact fields). `prepared`
/// is its geometry in `N` when a sweep formed it once (the same values
/// [`Geometry::new`] forms).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn spatial<N: Radical>(
    impact: &SpatialImpact,
    prepared: Option<&Geometry<N>>,
    outputs: Outputs,
    outcome: &mut SpatialOutcome,
) -> Exact<N, ()> {
    spatial_lanes::<N, 1>(
        std::array::from_ref(impact),
        prepared,
        outputs,
        std::array::from_mut(outcome),
    )
}

/// The validated contacts of `L` points in a field of `L` lanes
/// ([`crate::arith::Lanes`]): points of one sweep that differ in the
/// bodies' velocities alone, the law read from the first. Every outcome
/// written, or an error (in lanes, that the points are to be solved one by
/// one); each output of every lane is tested, in [`spatial`]'s order,
/// before any outcome is written.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn spatial_lanes<N: Radical, const L: usize>(
    impacts: &[SpatialImpact; L],
    prepared: Option<&Geometry<N>>,
    outputs: Outputs,
    outcome: &mut [SpatialOutcome; L],
) -> Exact<N, ()> {
    debug_assert_eq!(N::LANES, L);
    // Lanes share one geometry, formed once for the sweep: only a single
    // point (L = 1) forms its own here, from its own impact.
    debug_assert!(L == 1 || prepared.is_some());
    let formed;
    let geometry = match prepared {
        Some(geometry) => geometry,
        None => {
            formed = Geometry::new(&impacts[0]);
            &formed
        }
    };
    let mut sc = Scene::<N>::new(impacts, geometry);
    if sign(&sc.un)? != Ordering::Less {
        return Err(ImpactError::NotApproaching {
            input: Input::VelocityA,
            normal_contact_velocity: sc.un.approx() / sc.g.nu.approx().sqrt(),
        }
        .into());
    }
    if let Some(phases) = sc.law.phases {
        return kinetic(&mut sc, phases, outputs, outcome);
    }
    let (t, z, found) = sc.choose()?;
    let (regime, pointer) = match t {
        Tangential::Kept => (sc.law.regimes.0, sc.law.pointers.0),
        Tangential::Sliding => (sc.law.regimes.1, sc.law.pointers.1),
    };
    let no_impulse = || Fail::Refused(ImpactError::NoImpulse { input: pointer });
    let s = found.ok_or_else(no_impulse)?;
    if sign(&s.pn)? != Ordering::Greater {
        return Err(no_impulse());
    }
    let one = N::of(1.0);
    let e = N::of(sc.law.e);
    // Δu = W P + w κ, Δs̃ = wᵀ P + k κ.
    let du = axpy(&s.kappa, &sc.g.w, &sym_mul(&sc.g.w_matrix, &s.p));
    let dspin = sc.g.k.mul_add(&s.kappa, &dot(&sc.g.w, &s.p));
    let (final_ut, slip_sum) = match t {
        Tangential::Kept => {
            let et = N::of(sc.law.kept.unwrap_or(0.0));
            (
                map(
                    &sc.ut,
                    #[cfg_attr(not(debug_assertions), inline(always))]
                    |x| et.mul(x).neg(),
                ),
                map(
                    &sc.ut,
                    #[cfg_attr(not(debug_assertions), inline(always))]
                    |x| one.sub(&et).mul(x),
                ),
            )
        }
        Tangential::Sliding => sc.slip_after(&du),
    };
    let (final_spin, spin_sum) = match (z, sc.twist) {
        (Spin::Restitution, Some(tw)) => {
            let ez = N::of(tw.restitution);
            (ez.mul(&sc.s).neg(), one.sub(&ez).mul(&sc.s))
        }
        _ => (sc.s.add(&dspin), N::of(2.0).mul_add(&sc.s, &dspin)),
    };
    let work = sc.work(&s, &e, &slip_sum, &spin_sum);
    if sign(&work)? == Ordering::Greater {
        return Err(ImpactError::EnergyCreated {
            input: pointer,
            energy_loss: -0.5 * work.approx(),
        }
        .into());
    }
    let impulse_ratio = match t {
        Tangential::Kept => sc.ratio::<L>(&s, Output::ImpulseRatio)?.unwrap_or([0.0; L]),
        // |P_t| = c P_n exactly, unless there is no direction to slide in.
        Tangential::Sliding if sign(&norm2(&s.pt))? == Ordering::Equal => [0.0; L],
        Tangential::Sliding => outs::<N, L>(Output::ImpulseRatio, &N::of(sc.law.c))?,
    };
    let critical_impulse_ratio = if outputs.critical_impulse_ratio || regime == Regime::Sticking {
        let stick = sc.solve(Tangential::Kept, z, 0.0)?;
        match stick {
            Some(stick) => sc.ratio::<L>(&stick, Output::CriticalImpulseRatio)?,
            None => None,
        }
    } else {
        None
    };
    let answer = Written {
        s,
        e,
        final_ut,
        final_spin,
        work,
        impulse_ratio,
        critical_impulse_ratio,
        regime,
        torsional_regime: match z {
            Spin::Off => None,
            Spin::Restitution => Some(TorsionalRegime::Restitution),
            Spin::Sliding => Some(TorsionalRegime::Sliding),
        },
    };
    write(&sc, answer, outputs, outcome)
}

/// An answer ready to be written: the impulse and what the law says of it
/// (its ratios in each of `L` lanes).
struct Written<N, const L: usize> {
    s: Solution<N>,
    /// `e`, or the equivalent `e = −U_n/u_n` of the two-phase law.
    e: N,
    final_ut: V3<N>,
    final_spin: N,
    /// `P·(u + U) + κ (s̃ + S̃)`, checked `≤ 0`.
    work: N,
    impulse_ratio: [f64; L],
    critical_impulse_ratio: Option<[f64; L]>,
    regime: Regime,
    torsional_regime: Option<TorsionalRegime>,
}

/// `x` on body A (`index` 0), `−x` on body B, which the impulse acts on reversed.
#[cfg_attr(not(debug_assertions), inline(always))]
fn on_body<N: Field>(index: usize, x: N) -> N {
    if index == 0 { x } else { x.neg() }
}

/// Writes an answer's outputs to each lane's `outcome`, whole or not at all.
#[cfg_attr(not(debug_assertions), inline(always))]
fn write<N: Radical, const L: usize>(
    sc: &Scene<'_, N>,
    answer: Written<N, L>,
    outputs: Outputs,
    outcome: &mut [SpatialOutcome; L],
) -> Exact<N, ()> {
    let Written {
        s,
        e,
        final_ut,
        final_spin,
        work,
        impulse_ratio,
        critical_impulse_ratio,
        regime,
        torsional_regime,
    } = answer;
    let mut bodies = [[SpatialBodyOutcome::default(); 2]; L];
    let p2 = norm2(&s.p);
    for (index, (b, motion)) in sc.g.bodies.iter().zip(&sc.motion).enumerate() {
        let names = &SPATIAL_BODY_OUTPUTS[index];
        let dv = map(
            &s.p,
            #[cfg_attr(not(debug_assertions), inline(always))]
            |x| on_body(index, x.mul(&b.inv_m)),
        );
        let moment = axpy(&s.kappa, &sc.g.n, &cross(&b.r, &s.p));
        let dw = map(
            &sym_mul(&b.inv_i, &moment),
            #[cfg_attr(not(debug_assertions), inline(always))]
            |x| on_body(index, x.clone()),
        );
        let velocity = Scene::<N>::vector_out::<L>(three(names, 0), &add(&motion.v, &dv))?;
        let angular_velocity = Scene::<N>::vector_out::<L>(three(names, 3), &add(&motion.w, &dw))?;
        let velocity_change = Scene::<N>::vector_out::<L>(three(names, 6), &dv)?;
        let delta_v = outs_times_sqrt::<N, L>(names[9], &b.inv_m, &p2)?;
        let angular_velocity_change = Scene::<N>::vector_out::<L>(three(names, 10), &dw)?;
        for (lane, body) in bodies.iter_mut().enumerate() {
            body[index] = SpatialBodyOutcome {
                velocity: velocity[lane],
                angular_velocity: angular_velocity[lane],
                velocity_change: velocity_change[lane],
                delta_v: delta_v[lane],
                angular_velocity_change: angular_velocity_change[lane],
            };
        }
    }
    let initial = sc.contact_velocity_at::<L>(
        [
            Output::InitialNormalContactVelocity,
            Output::InitialTangentialContactVelocityX,
            Output::InitialTangentialContactVelocityY,
            Output::InitialTangentialContactVelocityZ,
            Output::InitialContactSpin,
        ],
        &sc.un,
        &sc.ut,
        &sc.s,
    )?;
    let r#final = sc.contact_velocity_at::<L>(
        [
            Output::FinalNormalContactVelocity,
            Output::FinalTangentialContactVelocityX,
            Output::FinalTangentialContactVelocityY,
            Output::FinalTangentialContactVelocityZ,
            Output::FinalContactSpin,
        ],
        &e.mul(&sc.un).neg(),
        &final_ut,
        &final_spin,
    )?;
    let normal = sc.along::<L>(Output::NormalImpulse, &s.pn)?;
    let tangential = Scene::<N>::vector_out::<L>(
        [
            Output::TangentialImpulseX,
            Output::TangentialImpulseY,
            Output::TangentialImpulseZ,
        ],
        &s.pt,
    )?;
    let torsional = outs_times_sqrt::<N, L>(Output::TorsionalImpulse, &s.kappa, &sc.g.nu)?;
    let x = outs::<N, L>(Output::ImpulseX, &s.p[0])?;
    let y = outs::<N, L>(Output::ImpulseY, &s.p[1])?;
    let z = outs::<N, L>(Output::ImpulseZ, &s.p[2])?;
    let energy = if outputs.energy {
        let initial = sc.initial_energy();
        let loss = half::<N>().mul(&work).neg();
        let max_loss = sc.max_loss();
        Some([
            outs::<N, L>(Output::InitialEnergy, &initial)?,
            outs::<N, L>(Output::FinalEnergy, &initial.sub(&loss))?.map(|x| x.max(0.0)),
            outs::<N, L>(Output::EnergyLoss, &loss)?,
            outs::<N, L>(Output::MaxEnergyLoss, &max_loss)?,
            outs::<N, L>(Output::NormalizedEnergyLoss, &loss.div(&max_loss))?.map(|x| x.min(1.0)),
        ])
    } else {
        None
    };
    let restitution = outs::<N, L>(Output::Restitution, &e)?;
    for (lane, outcome) in outcome.iter_mut().enumerate() {
        *outcome = SpatialOutcome {
            body_count: sc.g.bodies.len(),
            bodies: bodies[lane],
            contact_velocity: SpatialContactVelocities {
                initial: initial[lane],
                r#final: r#final[lane],
            },
            impulse: SpatialImpulse {
                normal: normal[lane],
                tangential: tangential[lane],
                torsional: torsional[lane],
                x: x[lane],
                y: y[lane],
                z: z[lane],
            },
            impulse_ratio: impulse_ratio[lane],
            critical_impulse_ratio: critical_impulse_ratio.map(|ratio| ratio[lane]),
            restitution: restitution[lane],
            regime,
            torsional_regime,
            energy: energy.map(
                |[initial, r#final, loss, max_loss, normalized_loss]| PlanarEnergy {
                    initial: initial[lane],
                    r#final: r#final[lane],
                    loss: loss[lane],
                    max_loss: max_loss[lane],
                    normalized_loss: normalized_loss[lane],
                },
            ),
        };
    }
    Ok(())
}
