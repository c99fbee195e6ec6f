//! The static bound's value taken apart and put together again, for
//! [`super::super::Lanes`], which keeps each part lane by lane.

use super::Filtered;

impl Filtered<false, true> {
    /// `(h, M, λ)`.
    #[inline(always)]
    pub(in crate::arith) fn parts(&self) -> (f64, f64, f64) {
        (self.h, self.m, self.lambda)
    }

    /// The value whose [`Filtered::parts`] are `(h, m, lambda)`.
    #[inline(always)]
    pub(in crate::arith) fn of_parts(h: f64, m: f64, lambda: f64) -> Self {
        Filtered { h, m, lambda, e: 0.0 }
    }
}
