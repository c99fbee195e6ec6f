//! The torsional model (section 4, Eqs 28–31): the bilinear law of the spin
//! `ω_n` about the contact normal.
//!
//! The normal impact is that of the body's centre (`V_n = −e v_n`,
//! `P_n = m (1 + e) |v_n|`). Low spin, `|ω_n| ≤ ω_s`: `Ω_n = −e_z ω_n` (Eq 28).
//! High spin: rotational sliding continues through separation and Eq 29 gives
//! `Ω_n = (1 − e_z) ω_n − sgn(ω_n) μ_z ρ_p m (1 + e) |v_n| / I_n` (Eq 30, with the
//! friction impulse opposing the spin and `ρ_D` read as `ρ_p`). The branches
//! meet at `ω_s = μ_z ρ_p m (1 + e) |v_n| / I_n` (Eq 31). As in the paper, the
//! restitution moment `−e_z I_n ω_n` of Eq 29 acts outside the friction cap.

use std::cmp::Ordering;

use super::{Exact, abs, half, outs, sign};
use crate::arith::Field;
use crate::error::Output;
use crate::outcome::{RotationalEnergy, TorsionalOutcome, TorsionalRegime};

/// The validated inputs of a torsional impact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Torsion {
    pub m: f64,
    pub i_n: f64,
    pub vn: f64,
    pub w: f64,
    pub e: f64,
    pub ez: f64,
    pub mu_z: f64,
    pub rho: f64,
}

/// The torsional model in the field `N`. The change `ω_n − Ω_n` and the sum
/// `ω_n + Ω_n` are each formed from their branch's formula, so the loss
/// `½ I_n (ω_n − Ω_n)(ω_n + Ω_n)` never subtracts two nearly equal energies.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn torsional<N: Field>(v: &Torsion, energy: bool, outcome: &mut TorsionalOutcome) -> Exact<N, ()> {
    torsional_lanes::<N, 1>(std::array::from_ref(v), energy, std::array::from_mut(outcome))
}

/// The impacts of `L` points in a field of `L` lanes
/// ([`crate::arith::Lanes`]), each with its own inputs: every outcome
/// written, or an error (in lanes, that the points are to be solved one by
/// one). Each output of every lane is tested in [`torsional`]'s order before
/// any outcome is written.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn torsional_lanes<N: Field, const L: usize>(
    v: &[Torsion; L],
    energy: bool,
    outcome: &mut [TorsionalOutcome; L],
) -> Exact<N, ()> {
    debug_assert_eq!(N::LANES, L);
    let one = N::of(1.0);
    let input = |x: fn(&Torsion) -> f64| N::of_lanes(|i| x(&v[i]));
    let (m, i_n, vn, w, e, ez) = (
        input(|v| v.m),
        input(|v| v.i_n),
        input(|v| v.vn),
        input(|v| v.w),
        input(|v| v.e),
        input(|v| v.ez),
    );
    let qn = one.add(&e).mul(&vn.neg());
    let switch = input(|v| v.mu_z)
        .mul(&input(|v| v.rho))
        .mul(&qn)
        .mul(&m.div(&i_n));
    // Every lane's spin has the sign `abs` decided (the same in all lanes).
    let magnitude = abs(&w)?;
    let (regime, spin, change, sum) = if sign(&switch.sub(&magnitude))? != Ordering::Less {
        (
            TorsionalRegime::Restitution,
            ez.mul(&w).neg(),
            one.add(&ez).mul(&w),
            one.sub(&ez).mul(&w),
        )
    } else {
        let change = ez.mul_add(&magnitude, &switch);
        let remaining = one.sub(&ez).mul_add(&magnitude, &switch.neg());
        let sum = N::of(2.0).sub(&ez).mul_add(&magnitude, &switch.neg());
        // Sliding needs `|ω_n| > ω_s ≥ 0`: every lane's spin is non-zero,
        // of the one sign.
        let signed = |x: N| if v[0].w < 0.0 { x.neg() } else { x };
        (
            TorsionalRegime::Sliding,
            signed(remaining),
            signed(change),
            signed(sum),
        )
    };
    let energy = if energy {
        let half_i = half::<N>().mul(&i_n);
        Some((
            outs::<N, L>(Output::InitialEnergy, &half_i.mul(&w.mul(&w)))?,
            outs::<N, L>(Output::FinalEnergy, &half_i.mul(&spin.mul(&spin)))?,
            outs::<N, L>(Output::EnergyLoss, &half_i.mul(&change).mul(&sum))?,
        ))
    } else {
        None
    };
    let final_normal_velocity = outs::<N, L>(Output::FinalNormalVelocity, &e.mul(&vn).neg())?;
    let final_spin = outs::<N, L>(Output::FinalSpin, &spin)?;
    let normal_impulse = outs::<N, L>(Output::NormalImpulse, &m.mul(&qn))?;
    let torsional_impulse = outs::<N, L>(Output::TorsionalImpulse, &i_n.mul(&change).neg())?;
    let switch_spin = outs::<N, L>(Output::SwitchSpin, &switch)?;
    for (lane, outcome) in outcome.iter_mut().enumerate() {
        *outcome = TorsionalOutcome {
            final_normal_velocity: final_normal_velocity[lane],
            final_spin: final_spin[lane],
            normal_impulse: normal_impulse[lane],
            torsional_impulse: torsional_impulse[lane],
            regime,
            switch_spin: switch_spin[lane],
            energy: energy.map(|(initial, r#final, loss)| RotationalEnergy {
                initial: initial[lane],
                r#final: r#final[lane],
                loss: loss[lane],
            }),
        };
    }
    Ok(())
}
