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

use super::{Exact, abs, half, out, sign};
use crate::arith::Field;
use crate::error::Output;
use crate::outcome::{RotationalEnergy, TorsionalOutcome, TorsionalRegime};

/// The validated inputs of a torsional impact.
#[derive(Debug, Clone, Copy, PartialEq)]
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
#[inline(always)]
pub(crate) fn torsional<N: Field>(v: &Torsion, energy: bool, outcome: &mut TorsionalOutcome) -> Exact<N, ()> {
    let one = N::of(1.0);
    let (m, i_n, vn, w, e, ez) = (
        N::of(v.m),
        N::of(v.i_n),
        N::of(v.vn),
        N::of(v.w),
        N::of(v.e),
        N::of(v.ez),
    );
    let qn = one.add(&e).mul(&vn.neg());
    let switch = N::of(v.mu_z).mul(&N::of(v.rho)).mul(&qn).mul(&m.div(&i_n));
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
        let signed = |x: N| if v.w < 0.0 { x.neg() } else { x };
        (
            TorsionalRegime::Sliding,
            signed(remaining),
            signed(change),
            signed(sum),
        )
    };
    let energy = if energy {
        let half_i = half::<N>().mul(&i_n);
        Some(RotationalEnergy {
            initial: out(Output::InitialEnergy, &half_i.mul(&w.mul(&w)))?,
            r#final: out(Output::FinalEnergy, &half_i.mul(&spin.mul(&spin)))?,
            loss: out(Output::EnergyLoss, &half_i.mul(&change).mul(&sum))?,
        })
    } else {
        None
    };
    *outcome = TorsionalOutcome {
        final_normal_velocity: out(Output::FinalNormalVelocity, &e.mul(&vn).neg())?,
        final_spin: out(Output::FinalSpin, &spin)?,
        normal_impulse: out(Output::NormalImpulse, &m.mul(&qn))?,
        torsional_impulse: out(Output::TorsionalImpulse, &i_n.mul(&change).neg())?,
        regime,
        switch_spin: out(Output::SwitchSpin, &switch)?,
        energy,
    };
    Ok(())
}
