//! The outputs of a [`Filtered`] value: each accepted only where its error
//! bound is within the promise, against its kind's scale.

use super::{ACCEPTED_RELATIVE_BOUND, Filtered, LAMBDA_MAX, U, Uncertain, max, scale_of};
use crate::accuracy::ScaleKind;

impl<const RUNNING: bool, const STATIC: bool> Filtered<RUNNING, STATIC> {
    /// The output of unit class `kind`: `h` (written `+0.0` for a zero), when
    /// its error bound is within [`ACCEPTED_RELATIVE_BOUND`] of the larger of
    /// `|h|` and the kind's scale `S`. An exact zero (`M = 0`) and an input
    /// (`λ = 0`) are exact; a larger bound (a cancellation below the scale,
    /// a nearly singular solve) is [`Uncertain::Inaccurate`], and a value out
    /// of the f64 range or `λ` past its limit [`Uncertain::Range`].
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn output(&self, kind: ScaleKind) -> Result<f64, Uncertain> {
        self.output_against(scale_of(kind))
    }

    /// [`Filtered::output`] against the scale `scale` of its kind, given
    /// (for one point of several evaluated together, `super::Lanes`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn output_against(&self, scale: f64) -> Result<f64, Uncertain> {
        let (v, accepted) = self.output_test(scale);
        if accepted {
            Ok(v)
        } else if !v.is_finite() || self.lambda > LAMBDA_MAX {
            Err(Uncertain::Range)
        } else {
            Err(Uncertain::Inaccurate)
        }
    }

    /// [`Filtered::output_against`]'s value and whether it is accepted,
    /// without a branch (so that lanes test theirs together).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn output_test(&self, scale: f64) -> (f64, bool) {
        let v = self.h + 0.0;
        // (Tested on the returned value, so that the caller's test of the
        // same value, `crate::model::out`, is known true and folded away.)
        // An exact zero or input has a zero bound; a NaN or infinite bound
        // compares false.
        let within = self.error_bound() <= ACCEPTED_RELATIVE_BOUND * max(v.abs(), scale);
        (v, v.is_finite() & (self.lambda <= LAMBDA_MAX) & within)
    }

    /// `x √y` of unit class `kind` as f64 forms it, `h_x · √h_y`, for `y`
    /// decided non-negative. With `E` the bounds: where `h_y > E_y` and
    /// `h_x ≠ 0`, `|√y − √h_y| = |y − h_y| / (√y + √h_y) ≤ E_y / √h_y`, so the
    /// error is at most `|h| (E_x/|h_x| + E_y/h_y + 2u)` and second-order
    /// terms; elsewhere (a cancelled `y` or `x`) at most
    /// `|x| √y + |h| ≤ (|h_x| + E_x) √(max(h_y, 0) + E_y) + |h|`. Each is
    /// grown by `1 + 2⁻¹⁰` (the dropped terms and this bound's own
    /// roundings) and the smallest normal (a product that underflowed), and
    /// accepted as [`Filtered::output`]'s.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn output_times_sqrt(&self, y: &Self, kind: ScaleKind) -> Result<f64, Uncertain> {
        self.output_times_sqrt_against(y, scale_of(kind))
    }

    /// [`Filtered::output_times_sqrt`] against the scale `scale` of its
    /// kind, given (for one point of several evaluated together,
    /// `super::super::Lanes`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn output_times_sqrt_against(&self, y: &Self, scale: f64) -> Result<f64, Uncertain> {
        let v = self.h * y.h.sqrt() + 0.0;
        if !v.is_finite() || self.lambda > LAMBDA_MAX || y.lambda > LAMBDA_MAX {
            return Err(Uncertain::Range);
        }
        if self.m == 0.0 || y.m == 0.0 {
            // An exact zero factor: the exact zero, `+0.0`.
            return Ok(v);
        }
        let error_x = self.error_bound();
        let error_y = y.error_bound();
        let bound = if y.h > error_y && self.h != 0.0 {
            // (1 + a)(1 + b) − 1 = a + b + a b: the cross term is not
            // second-order where a bound is near its value.
            {
                let (a, b) = (error_x / self.h.abs(), error_y / y.h);
                v.abs() * (a.mul_add(b, a + b) + 2.0 * U)
            }
        } else {
            (self.h.abs() + error_x) * (y.h.max(0.0) + error_y).sqrt() + v.abs()
        };
        let bound = bound * (1.0 + 1.0 / 1024.0) + f64::MIN_POSITIVE;
        // A NaN or infinite bound compares false.
        if bound <= ACCEPTED_RELATIVE_BOUND * max(v.abs(), scale) {
            Ok(v)
        } else {
            Err(Uncertain::Inaccurate)
        }
    }
}
