//! The impact model, written once over a [`Field`], from the momentum
//! equations (Eqs A-1…A-3) closed by Eq 1 and one tangential law: the laws in
//! the plane (`contact.rs`: frictionless, prescribed ratio, Coulomb friction,
//! tangential restitution, the two phases), which one lamina against a
//! barrier (`barrier.rs`, the paper's frame, the point mass too) and laminae
//! in world axes (`bodies.rs`) evaluate; the contact in space (`spatial/`),
//! which reads every law as the same branches ([`crate::law::Reading`]); and
//! the torsional law (`torsional.rs`).
//!
//! The same code answers both precisions: evaluated in `f64` it is the `fast`
//! mode; evaluated in the exact arithmetics of [`crate::arith`] every output is
//! formed as its exact value and rounded once, and every regime decision is
//! the exact sign of a value. Forms are chosen for the f64 evaluation (fused
//! contact velocities, `(1 − e) v_cn` rather than `v_cn + V_cn`, quotients
//! that cannot overflow in between); any algebraically equal form has the same
//! exact value, so the choice costs the exact mode nothing in correctness.
//!
//! A physics change goes here, once; [`crate::impact`] validates the inputs
//! and chooses the arithmetic.

pub(crate) mod barrier;
pub(crate) mod bodies;
pub(crate) mod contact;
pub(crate) mod spatial;
pub(crate) mod torsional;
mod vector;

use std::cmp::Ordering;

use crate::arith::Field;
use crate::error::{ImpactError, Output};

/// Why the model gave no answer in a field whose undecided signs and
/// roundings are reported as `U` ([`Field::Undecided`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Fail<U> {
    /// A sign or a rounding the field could not decide.
    Undecided(U),
    /// The model's own refusal (the same in every field).
    Refused(ImpactError),
}

impl<U> From<ImpactError> for Fail<U> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn from(e: ImpactError) -> Self {
        Fail::Refused(e)
    }
}

/// The model's result in the field `N`.
pub(crate) type Exact<N, T> = Result<T, Fail<<N as Field>::Undecided>>;

#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn sign<N: Field>(x: &N) -> Exact<N, Ordering> {
    x.sign().map_err(Fail::Undecided)
}

#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn abs<N: Field>(x: &N) -> Exact<N, N> {
    Ok(if sign(x)? == Ordering::Less {
        x.neg()
    } else {
        x.clone()
    })
}

/// The output correctly rounded (an exact zero as `+0.0`; in `fast`, within
/// the promised error, [`crate::accuracy`]), or its refusal when it rounds
/// beyond the f64 range.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn out<N: Field>(output: Output, x: &N) -> Exact<N, f64> {
    let v = x.round_output(output.scale_kind()).map_err(Fail::Undecided)?;
    finite_output(output, v)
}

/// [`out`] of each of `L` lanes ([`Field::lanes_output`]; `[out]` for a
/// field of one point).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn outs<N: Field, const L: usize>(output: Output, x: &N) -> Exact<N, [f64; L]> {
    let mut values = [0.0; L];
    x.lanes_output(output.scale_kind(), &mut values)
        .map_err(Fail::Undecided)?;
    for v in values {
        finite_output::<N::Undecided>(output, v)?;
    }
    Ok(values)
}

/// `v`, or the refusal of `output` beyond the f64 range.
#[cfg_attr(not(debug_assertions), inline(always))]
fn finite_output<U>(output: Output, v: f64) -> Result<f64, Fail<U>> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ImpactError::OutputNotFinite { output }.into())
    }
}

/// `x √y` correctly rounded (in `fast`, within the promised error), or its
/// refusal beyond the f64 range, of each of `L` lanes
/// ([`Field::lanes_output_times_sqrt`]; `[x √y]` for a field of one point).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn outs_times_sqrt<N: Field, const L: usize>(output: Output, x: &N, y: &N) -> Exact<N, [f64; L]> {
    let mut values = [0.0; L];
    x.lanes_output_times_sqrt(y, output.scale_kind(), &mut values)
        .map_err(Fail::Undecided)?;
    for v in values {
        finite_output::<N::Undecided>(output, v)?;
    }
    Ok(values)
}

#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn half<N: Field>() -> N {
    N::of(0.5)
}
