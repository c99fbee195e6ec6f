//! A value taken apart and put together again, for
//! [`super::super::Lanes`], which keeps each part lane by lane.

use super::Filtered;

impl<const RUNNING: bool, const STATIC: bool> Filtered<RUNNING, STATIC> {
    /// `(h, M, λ, E)` (`E` is `0` without `RUNNING`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(in crate::arith) fn parts(&self) -> (f64, f64, f64, f64) {
        (self.h, self.m, self.lambda, self.e)
    }

    /// The value whose [`Filtered::parts`] are `(h, m, lambda, e)`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(in crate::arith) fn of_parts(h: f64, m: f64, lambda: f64, e: f64) -> Self {
        Filtered { h, m, lambda, e }
    }
}
