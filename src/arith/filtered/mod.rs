//! The `fast` precision's arithmetic: plain f64 values, each carrying error
//! bounds so that every decision the model takes on them is the exact one or
//! is reported undecided, and every output is within the promised error or
//! is reported inaccurate (a filter, as in Shewchuk's adaptive
//! predicates). An undecided decision sends the whole impact to the exact
//! stages ([`crate::impact`]); a decided one costs a comparison.
//!
//! A [`Filtered`] `(h, M, λ)` holds `h`, the value exactly as the plain f64
//! evaluation forms it (the same operations, the same fused multiply-adds and
//! quotients, so `fast` outputs are the bits they were without the filter),
//! `M`, an upper bound of the exact value's magnitude built like the value
//! with every term taken positive (a quotient's is the condition-weighted
//! `(M_x + |q| M_y) / |y|_low`, a root's `M_x / √x_low`), and a small number
//! `λ` that depends only on the shape of the computation. For the exact value
//! `x` of the same expression in the inputs, and `u = 2⁻⁵³`:
//!
//! - (F1) `|x| ≤ M`,
//! - (F2) `|x − h| ≤ λ u M`,
//!
//! each up to the slack described below. Beside them it carries `E`, a
//! running bound formed from the values as they are computed (Wilkinson's
//! running error analysis: `E_x + E_y + u |h|` for a sum,
//! `(|h_x| + E_x) E_y + |h_y| E_x + u |h|` for a product, and so on):
//!
//! - (F3) `|x − h| ≤ E`.
//!
//! Decisions and outputs read the smaller of (F2) and (F3) (a root's and a
//! divisor's certification read (F2)); an evaluation may carry (F2) alone or
//! (F3) alone instead (the `RUNNING` and `STATIC` parameters of
//! [`Filtered`]), where the other would decide little or cost much. (F2)'s
//! `M` multiplies the conditioning of each factor along a chain of products
//! and quotients,
//! where (F3) adds their relative errors, so a long chain (a contact in
//! space) is bounded by (F3) far more tightly: on 5,000 random spatial
//! impacts, (F2) alone left 602 decisions too close to tell, (F3) none.
//! Each operation's rule (at the
//! operation) derives its `λ` from its operands' `λ` alone, never from the
//! values (an exact zero is told by `M = 0`, an uncertain quotient by
//! `M = ∞`): inputs have `λ = 0`, so along each path of the model every `λ`
//! is a constant, which the compiler can fold with the choice between a
//! rule's forms for exact operands and for rounded ones (where two paths
//! that meet carry different `λ`, it stays a run-time value). `M` is dead where no
//! decision reads it: an output that is only rounded costs what it cost in
//! plain f64, and the compiler drops the bookkeeping for it.
//!
//! Slack. The rules drop second-order terms of relative size `λ u ≤ 2⁻³⁷`
//! (`λ ≤` [`LAMBDA_MAX`] `= 2¹⁶` is checked where a decision is made; `λ` only
//! grows, so every step before obeyed it too) and `M` is itself rounded to
//! nearest, at most a few times per step and fewer than 4096 times along any
//! path of the model: together far less than the factor `1 + 2⁻¹⁰` applied to
//! the bound where a decision is made. As in the compensated stage, every
//! non-zero `M` is at least 2⁻⁹⁰⁰ ([`floored`]), so a rounding in the subnormal
//! range (at most 2⁻¹⁰⁷⁵ absolute) is far below `u M`; `M = 0` means the value
//! is exactly zero with `h = 0`. Overflow leaves an infinity or NaN in `h`
//! or `M`, and then nothing is decided.

use std::cmp::Ordering;

use super::compensated::{FLOOR, LAMBDA_MAX, M_GROWTH, U, floored, max, product_magnitude};
use crate::accuracy::{ErrorScales, PROMISED_RELATIVE_ERROR, ScaleKind};

/// The factor applied to `λ u M` where a decision is made: covers the rules'
/// dropped second-order terms and the roundings of `M` (module documentation).
const SLACK: f64 = (1.0 + 1.0 / 1024.0) * M_GROWTH;

/// `1 + 2u`, rounded up: `|x| ≤ |h| (1 + 2u)` for a correctly rounded `h` of `x`.
const ONE_PLUS_2U: f64 = 1.0 + 4.0 * U;

/// Why a decision in `fast` precision was left to the exact stages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Uncertain {
    /// The value left the f64 range (an infinity or a NaN on the way), a
    /// quotient's divisor or a root's radicand was too uncertain, or `λ` passed
    /// its limit.
    Range,
    /// The value lies within its error bound of zero: its sign is the exact
    /// stages' to decide.
    Close,
    /// An output's error bound exceeds the promised error
    /// ([`PROMISED_RELATIVE_ERROR`] of its magnitude or scale): its value is
    /// the exact stages' to give.
    Inaccurate,
}

/// The bound an output is answered with: with `p` the promise,
/// `|x − h| ≤ (p/2) max(|h|, S)` gives `|x − h| ≤ (p/2) (max(|x|, S) + |x − h|)`,
/// so `|x − h| ≤ (p/2) / (1 − p/2) max(|x|, S)`, within [`PROMISED_RELATIVE_ERROR`].
const ACCEPTED_RELATIVE_BOUND: f64 = 0.5 * PROMISED_RELATIVE_ERROR;

/// The factor applied to the running bound `E` where it is read, and to an
/// operand's `E` where a rule uses it other than linearly (a divisor's low
/// end, a factor's magnitude, a root's radicand): covers the roundings of
/// `E`'s own few operations per step (below `(1 + u)⁴` each, along fewer
/// than 4096 steps, so far below `2⁻¹⁰` in all).
const RUNNING_SLACK: f64 = 1.0 + 1.0 / 1024.0;

/// What a rounding in the subnormal range may add beside `u |h|` (at most
/// 2⁻¹⁰⁷⁵), covered by the smallest normal: a subnormal constant here would
/// make every operation take the CPU's slow path for subnormal operands
/// (a microcode assist on x86, about 20× the cost of the whole f64 model).
const UNDERFLOW: f64 = f64::MIN_POSITIVE;

/// `|x y − h_x h_y| ≤ (|h_x| + E_x) E_y + |h_y| E_x`, plus `E_z` of an added
/// term. (The true bounds are at most [`RUNNING_SLACK`] times the `e`
/// carried: where a bound enters other than linearly, here `E_x` beside
/// `|h_x|`, it is taken grown by that factor, so the factor does not
/// compound from step to step.)
#[cfg_attr(not(debug_assertions), inline(always))]
fn product_error<const R: bool, const S: bool>(x: &Filtered<R, S>, y: &Filtered<R, S>, e_z: f64) -> f64 {
    x.e.mul_add(RUNNING_SLACK, x.h.abs())
        .mul_add(y.e, y.h.abs().mul_add(x.e, e_z))
}

/// A rounded result's running bound: the operands' error `carried` plus the
/// rounding `u |h|` and an underflow; an exact zero (`M = 0`) has none.
#[cfg_attr(not(debug_assertions), inline(always))]
fn rounded_error(m: f64, carried: f64, h: f64) -> f64 {
    if m == 0.0 {
        0.0
    } else {
        carried + U.mul_add(h.abs(), UNDERFLOW)
    }
}

/// `x` where `keep`, else `otherwise`, by masks rather than a select, which
/// the compiler may turn into a branch around an expensive operand (the
/// static bound's quotient, in `Filtered::static_quotient_magnitude`):
/// one branch per lane of `super::Lanes`. With masks, Figure 2's sweep in
/// lanes takes 4–5 % fewer instructions a point (callgrind,
/// docs/performance-log.md, 2026-12-07 (later)); the running bound's
/// rules, with masks, took 8–10 % more in space, so they keep their selects.
#[cfg_attr(not(debug_assertions), inline(always))]
fn kept_or(keep: bool, x: f64, otherwise: f64) -> f64 {
    let mask = u64::from(keep).wrapping_neg();
    f64::from_bits((x.to_bits() & mask) | (otherwise.to_bits() & !mask))
}

thread_local! {
    /// The scales of the impact being evaluated ([`ErrorScales::by_kind`]),
    /// set by [`measure_against`] before each `fast` evaluation; zeros (the
    /// promise relative to each output itself) until then.
    static SCALES: std::cell::Cell<[f64; 6]> = const { std::cell::Cell::new([0.0; 6]) };
}

/// Sets the scales the outputs of the next `fast` evaluation on this thread
/// are measured against: called by the one function that runs it,
/// `impact::fast_or_exact`, with the impact's own scales.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn measure_against(scales: &ErrorScales) {
    SCALES.with(|s| s.set(scales.by_kind()));
}

/// The scale of outputs of `kind` in the impact being evaluated.
#[cfg_attr(not(debug_assertions), inline(always))]
fn scale_of(kind: ScaleKind) -> f64 {
    SCALES.with(|s| s.get()[kind as usize])
}

/// `M` of `h`, one correct rounding of an exact value where no underflow
/// lost bits (or the exact zero it then is): `|x| ≤ |h| (1 + 2u)` and
/// `|x − h| ≤ u |x|`, so `λ = 1` (any `λ` for a zero, whose `M` is 0).
#[cfg_attr(not(debug_assertions), inline(always))]
fn once_rounded(h: f64) -> f64 {
    if h == 0.0 {
        0.0
    } else {
        floored(h.abs() * ONE_PLUS_2U)
    }
}

/// An f64 value with its static error bound (with `STATIC`) and its
/// running one (with `RUNNING`); see the module documentation. Without
/// `RUNNING`, `E` is not formed (each rule tests `RUNNING`, rather than
/// leaving the dead bookkeeping to the optimiser, which removed it in one
/// compiled copy of the model and not in another: the service binary's
/// Figure 2 sweep takes 22 % less time without it, docs/performance-log.md
/// 2026-11-29): (F2)
/// alone, for a short computation where it decides nearly everything at a
/// fraction of the cost. Without `STATIC`, `M` only tells an exact zero
/// (`0`) from any other value (`1`: a flag, not a magnitude, which nothing
/// reads as one) and (F2) is not formed: (F3) alone, for a long computation
/// where the running bound decides what the static one would and the
/// magnitudes' bookkeeping costs 20–40 % more (docs/performance-log.md). (One of the two is
/// always on.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Filtered<const RUNNING: bool = true, const STATIC: bool = true> {
    /// The plain f64 evaluation.
    h: f64,
    /// `M`: an upper bound of the exact value's magnitude.
    m: f64,
    /// `λ` in (F2).
    lambda: f64,
    /// `E`: a running bound of `|x − h|` (F3), formed from the values.
    e: f64,
}

/// `M` without `STATIC`: `0` for an exact zero, else `1` (a flag, not a
/// magnitude), so that a product's is the factors' product and a sum's
/// their maximum.
#[cfg_attr(not(debug_assertions), inline(always))]
fn zero_flag(zero: bool) -> f64 {
    if zero { 0.0 } else { 1.0 }
}

impl<const RUNNING: bool, const STATIC: bool> Filtered<RUNNING, STATIC> {
    /// An f64 input, exactly (`λ = 0`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn exact(x: f64) -> Self {
        Filtered {
            h: x,
            m: if !STATIC {
                zero_flag(x == 0.0)
            } else if x == 0.0 {
                0.0
            } else {
                floored(x.abs())
            },
            lambda: 0.0,
            e: 0.0,
        }
    }

    /// The plain f64 value.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn value(&self) -> f64 {
        self.h
    }

    /// The sum. `|x − h| ≤ E_x + E_y + u |h_x + h_y|` with
    /// `|h_x + h_y| ≤ M (1 + λu)`, `M = M_x + M_y`: `λ_s = max(λ_x, λ_y) + 1`.
    ///
    /// Of two exact operands (`λ = 0`) the sum is one correct rounding, exact
    /// when it is zero or subnormal: `M = |h| (1 + 2u)` (`0` for a zero), which
    /// decides the sign of every such sum (a cancelled difference of two
    /// inputs is an exact zero); its `λ = 1` is the general rule's.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn add(&self, o: &Self) -> Self {
        let h = self.h + o.h;
        // λ depends on the path alone (module documentation), and so does
        // the choice of the rule for M.
        let m = if !STATIC {
            // Of two exact operands an exact zero sum is `h = 0`.
            if self.lambda + o.lambda == 0.0 {
                zero_flag(h == 0.0)
            } else {
                max(self.m, o.m)
            }
        } else if self.lambda + o.lambda == 0.0 {
            once_rounded(h)
        } else {
            self.m + o.m
        };
        Filtered {
            h,
            m,
            lambda: max(self.lambda, o.lambda) + 1.0,
            // A sum does not underflow: its rounding is at most u |h|.
            e: if RUNNING {
                (self.e + o.e) + U * h.abs()
            } else {
                0.0
            },
        }
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn neg(&self) -> Self {
        Filtered { h: -self.h, ..*self }
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }

    /// The product. `|x y − h| ≤ |x| E_y + |h_y| E_x + u |h|` with
    /// `|h_y| ≤ M_y (1 + λ_y u)` and `M = M_x M_y` (zero when a factor is an
    /// exact zero): `λ_p = λ_x + λ_y + 1`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn mul(&self, o: &Self) -> Self {
        let h = self.h * o.h;
        let m = if STATIC {
            product_magnitude(self.m, o.m)
        } else {
            self.m * o.m
        };
        Filtered {
            h,
            m,
            lambda: self.lambda + o.lambda + 1.0,
            e: if RUNNING {
                rounded_error(m, product_error(self, o, 0.0), h)
            } else {
                0.0
            },
        }
    }

    /// `x y + z` with one rounding, as the f64 evaluation forms it.
    /// `|x y + z − h| ≤ (λ_x + λ_y) u M_x M_y + λ_z u M_z + u |h|` to first
    /// order, so with `M = M_x M_y + M_z`, `λ = max(λ_x + λ_y, λ_z) + 1`.
    /// Of exact operands with a normal result it is one correct rounding:
    /// `M = |h| (1 + 2u)` (with the rule's `λ = 1`), which decides its sign
    /// however much cancels.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn mul_add(&self, b: &Self, c: &Self) -> Self {
        let h = self.h.mul_add(b.h, c.h);
        let exact = self.lambda + b.lambda + c.lambda == 0.0 && h.abs() >= f64::MIN_POSITIVE;
        let m = if !STATIC {
            if exact { 1.0 } else { max(self.m * b.m, c.m) }
        } else if exact {
            once_rounded(h)
        } else {
            product_magnitude(self.m, b.m) + c.m
        };
        Filtered {
            h,
            m,
            lambda: max(self.lambda + b.lambda, c.lambda) + 1.0,
            e: if RUNNING {
                rounded_error(m, product_error(self, b, c.e), h)
            } else {
                0.0
            },
        }
    }

    /// The quotient `x / y`, `q = h_x / h_y` as f64 forms it. With
    /// `|y| ≥ y_low = |h_y| − E_y` (at least `|h_y| / 2`, checked: else nothing
    /// is decided), `|x/y − h_x/h_y| ≤ (E_x + |h_x/h_y| E_y) / y_low`, plus the
    /// rounding `u |q|`. With `M_q = (M_x + |q| M_y) / y_low`, which is at least
    /// `|x / y|`, `λ_q = max(λ_x, λ_y) + 2` (one for the rounding, one for the
    /// difference between `|h_x/h_y|` and `|q|` and the roundings of `y_low`).
    /// An exactly zero dividend gives an exact zero (`M = 0`). An uncertain
    /// divisor gives `M = ∞`, which decides nothing (the running bound is
    /// certified on the same terms, its own divisor bound at most half of
    /// `|h_y|`, else infinite); the model divides only
    /// by values whose exact value is not zero (the exact stages could not
    /// divide otherwise), so the quotient's exact value is a real number and
    /// its product with an exact zero the exact zero it is taken for.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn div(&self, o: &Self) -> Self {
        let q = self.h / o.h;
        let m = if STATIC {
            self.static_quotient_magnitude(o, q)
        } else {
            self.m
        };
        // (E_x + |h_x/h_y| E_y) / |y|, with |y| ≥ |h_y| − E_y taken with
        // E_y grown by its slack and certified, as (F2)'s divisor is, only
        // when that keeps at least half of |h_y| (a NaN fails the test);
        // |h_x/h_y| ≤ |q| (1 + 2u) plus an underflow. Else no finite bound.
        let e = if RUNNING {
            let low = (o.h.abs() - o.e * RUNNING_SLACK) * (1.0 - 4.0 * U);
            let carried = if low >= 0.5 * o.h.abs() && low > 0.0 {
                q.abs().mul_add(ONE_PLUS_2U, UNDERFLOW).mul_add(o.e, self.e) / low
            } else {
                f64::INFINITY
            };
            rounded_error(m, carried, q)
        } else {
            0.0
        };
        Filtered {
            h: q,
            m,
            lambda: max(self.lambda, o.lambda) + 2.0,
            e,
        }
    }

    /// `M` of the quotient `q` of `self` by `o` ([`Filtered::div`]): zero
    /// for an exact zero dividend, `∞` for an uncertain divisor.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn static_quotient_magnitude(&self, o: &Self, q: f64) -> f64 {
        let error_y = (o.lambda * (U * SLACK)) * o.m;
        let y_low = (o.h.abs() - error_y) * (1.0 - 4.0 * U);
        let certified = y_low >= 0.5 * o.h.abs() && y_low > 0.0;
        let m = floored(q.abs().mul_add(o.m, self.m) * (1.0 + 4.0 * U) / y_low);
        // Masks rather than branches: the bookkeeping stays straight-line.
        kept_or(self.m != 0.0, kept_or(certified, m, f64::INFINITY), 0.0)
    }

    /// The quotient of two f64 inputs, `rounded` being their f64 quotient:
    /// one rounding of an exact value (or an exact zero).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn quotient_of(num: f64, rounded: f64) -> Self {
        // A subnormal or underflowed quotient is off by at most 2⁻¹⁰⁷⁵, far
        // below u M for the floored M.
        Filtered {
            h: rounded,
            m: if !STATIC {
                zero_flag(num == 0.0)
            } else if num == 0.0 {
                0.0
            } else {
                floored(rounded.abs() * ONE_PLUS_2U)
            },
            lambda: 1.0,
            e: if num == 0.0 || !RUNNING {
                0.0
            } else {
                rounded_error(1.0, 0.0, rounded)
            },
        }
    }

    /// `√x` of a value whose exact value is decided non-negative: with
    /// `x_low = h − E > 0`, `|√x − √h| ≤ E / (√x_low + √h)` and the rounding
    /// `u √h`; `M = M_x / √x_low ≥ √M_x ≥ √x`, `λ = λ_x + 2`. An interval
    /// reaching zero decides nothing ([`Uncertain::Close`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn sqrt(&self) -> Result<Self, Uncertain> {
        let s = self.h.sqrt();
        if self.m == 0.0 {
            return Ok(Filtered {
                h: s,
                m: 0.0,
                lambda: self.lambda + 2.0,
                e: 0.0,
            });
        }
        let grown = self.e * RUNNING_SLACK;
        let m = if STATIC {
            let low = (self.h - (self.lambda * (U * SLACK)) * self.m) * (1.0 - 4.0 * U);
            if !(self.h.is_finite() && self.m.is_finite() && self.lambda <= LAMBDA_MAX) {
                return Err(Uncertain::Range);
            }
            // (A NaN `low` came from an infinite M, refused above.)
            if low < FLOOR {
                return Err(Uncertain::Close);
            }
            floored(self.m * (1.0 + 4.0 * U) / (low.sqrt() * (1.0 - 4.0 * U)))
        } else {
            // The running bound certifies the radicand instead: the same
            // refusals, read off (F3).
            if !(self.h.is_finite() && grown.is_finite() && self.lambda <= LAMBDA_MAX) {
                return Err(Uncertain::Range);
            }
            if (self.h - grown) * (1.0 - 4.0 * U) < FLOOR {
                return Err(Uncertain::Close);
            }
            1.0
        };
        // |√x − √h| = |x − h| / (√x + √h) ≤ E / (√(h − E) + √h), and at
        // most √E however much of h is uncertain (a NaN E stays a NaN).
        let e = if !RUNNING {
            0.0
        } else if grown < self.h {
            self.e / ((self.h - grown).sqrt() + s) + U * s
        } else {
            self.e.sqrt() + U * s
        };
        Ok(Filtered {
            h: s,
            m,
            lambda: self.lambda + 2.0,
            e,
        })
    }

    /// A bound of `|x − h|`: the smaller of the static (F2) and the running
    /// (F3) one, each grown by its slack (a NaN running bound leaves the
    /// static one); without `RUNNING`, the static one; without `STATIC`,
    /// the running one.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn error_bound(&self) -> f64 {
        let running = self.e * RUNNING_SLACK;
        if !STATIC {
            return running;
        }
        let fixed = (self.lambda * (U * SLACK)) * self.m;
        if !RUNNING {
            return fixed;
        }
        if running < fixed { running } else { fixed }
    }

    /// Whether the bound decides the sign from the magnitude alone (`λ`
    /// within its limit, `|h|` finite and above the bound), and whether
    /// `h > 0`: [`Filtered::sign`]'s common path, without a branch (so that
    /// lanes decide theirs together).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn clear_sign(&self) -> (bool, bool) {
        let magnitude = self.h.abs();
        // A finite |h| above the bound makes the bound finite too (a NaN
        // compares false).
        let clear =
            (self.lambda <= LAMBDA_MAX) & (magnitude > self.error_bound()) & (magnitude < f64::INFINITY);
        (clear, self.h > 0.0)
    }

    /// The exact value's sign, unless the bound cannot decide it.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn sign(&self) -> Result<Ordering, Uncertain> {
        let (clear, positive) = self.clear_sign();
        if clear {
            return Ok(if positive {
                Ordering::Greater
            } else {
                Ordering::Less
            });
        }
        // (λ is a sum and maximum of small constants, never a NaN.)
        if self.lambda > LAMBDA_MAX {
            return Err(Uncertain::Range);
        }
        let bound = self.error_bound();
        if !(self.h.is_finite() && bound.is_finite()) {
            Err(Uncertain::Range)
        } else if bound == 0.0 {
            // λ = 0 (an input) or M = 0 (an exact zero), or E = 0 without
            // the static bound: h is the exact value.
            Ok(if self.h > 0.0 {
                Ordering::Greater
            } else if self.h < 0.0 {
                Ordering::Less
            } else {
                Ordering::Equal
            })
        } else {
            Err(Uncertain::Close)
        }
    }
}

mod outputs;
mod parts;
mod shared;

pub(crate) use shared::SharedLanes;
#[cfg(test)]
mod tests;
