//! [`SharedLanes`]: `L` points of a sweep in `fast`'s static bound (F2)
//! alone, the first field of one and two laminae ([`Filtered<false, true>`]),
//! with one magnitude `M` for all of them.
//!
//! A value is its lanes' values `h`, each formed by the operations its
//! point's single solve forms it by, and one `M` that is at least each
//! lane's own: every rule forms `M` from its operands' as
//! [`Filtered`]'s rule does, by operations that never decrease when an
//! operand grows (sums, products, fused multiply-adds and quotients of
//! non-negative numbers, each rounded to nearest, which is monotone), and
//! where a lane's value enters (an exact operation's rounding, a
//! quotient's `|q|` and divisor) takes the largest (the smallest divisor)
//! over the lanes. `λ` is the path's, one for all as in
//! [`super::super::Lanes`]. So each lane's bound `λ u M` is at least the
//! one its single solve reads, and a sign or an output this field accepts
//! for every lane, its single solve accepts in its first field, with the
//! same `h`: a point answered here is its single solve, bit for bit. Where
//! the shared bound is too loose for a lane (lanes of very different
//! magnitudes, a lane's exact zero among others), nothing is lost but
//! time: the points are solved one by one.
//!
//! The per-point work is the f64 evaluation itself, lane by lane over
//! arrays, which the compiler packs into vectors; the bookkeeping of `M`
//! and `λ` is done once for the lanes.

use std::cmp::Ordering;

use super::super::lanes::{Diverged, lane_scales};
use super::{
    ACCEPTED_RELATIVE_BOUND, Filtered, LAMBDA_MAX, ONE_PLUS_2U, SLACK, U, floored, max, product_magnitude,
};
use crate::accuracy::ScaleKind;

/// `L` points' values of one expression, with one static bound; see the
/// module documentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SharedLanes<const L: usize> {
    /// The lanes' f64 values.
    h: [f64; L],
    /// `M`, at least every lane's own.
    m: f64,
    /// `λ`, the path's.
    lambda: f64,
}

/// `f(i)` lane by lane, in an explicit loop over the lanes.
#[cfg_attr(not(debug_assertions), inline(always))]
fn lanewise<const L: usize>(f: impl Fn(usize) -> f64) -> [f64; L] {
    let mut out = [0.0; L];
    for (i, o) in out.iter_mut().enumerate() {
        *o = f(i);
    }
    out
}

/// The largest of `x`, a NaN if one is (a NaN `M` decides nothing).
#[cfg_attr(not(debug_assertions), inline(always))]
fn largest<const L: usize>(x: [f64; L]) -> f64 {
    let mut m = x[0];
    for &v in &x[1..] {
        m = if v <= m { m } else { v };
    }
    m
}

/// [`super::once_rounded`] of each lane's value, the largest.
#[cfg_attr(not(debug_assertions), inline(always))]
fn once_rounded<const L: usize>(h: &[f64; L]) -> f64 {
    largest(lanewise::<L>(|i| {
        if h[i] == 0.0 {
            0.0
        } else {
            floored(h[i].abs() * ONE_PLUS_2U)
        }
    }))
}

impl<const L: usize> SharedLanes<L> {
    /// The static error bound `λ u M`, grown by its slack: every lane's
    /// ([`Filtered::error_bound`] without `RUNNING`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn error_bound(&self) -> f64 {
        (self.lambda * (U * SLACK)) * self.m
    }

    /// A value whose lanes are the exact inputs `h`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn inputs(h: [f64; L]) -> Self {
        SharedLanes {
            m: largest(lanewise::<L>(|i| Filtered::<false, true>::exact(h[i]).parts().1)),
            h,
            lambda: 0.0,
        }
    }
}

impl<const L: usize> super::super::Field for SharedLanes<L> {
    type Undecided = Diverged;

    const LANES: usize = L;

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of(x: f64) -> Self {
        let (_, m, lambda, _) = Filtered::<false, true>::exact(x).parts();
        SharedLanes { h: [x; L], m, lambda }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of_lanes(x: impl Fn(usize) -> f64) -> Self {
        Self::inputs(lanewise(x))
    }
    /// Each lane's `M` is [`Filtered::quotient_of`]'s: `|q| (1 + 2u)`, or
    /// zero for a zero dividend.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of_lanes(q: impl Fn(usize) -> (f64, f64, f64)) -> Self {
        let parts: [(f64, f64, f64); L] = std::array::from_fn(q);
        SharedLanes {
            h: lanewise(|i| parts[i].2),
            m: largest(lanewise::<L>(|i| {
                Filtered::<false, true>::quotient_of(parts[i].0, parts[i].2)
                    .parts()
                    .1
            })),
            lambda: 1.0,
        }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of(num: f64, den: f64, rounded: f64) -> Self {
        let _ = den;
        let (_, m, lambda, _) = Filtered::<false, true>::quotient_of(num, rounded).parts();
        SharedLanes {
            h: [rounded; L],
            m,
            lambda,
        }
    }
    /// [`Filtered::add`]: `M = M_x + M_y`, or of two exact operands the
    /// largest lane's once-rounded `|h|`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(&self, o: &Self) -> Self {
        let h = lanewise(|i| self.h[i] + o.h[i]);
        SharedLanes {
            m: if self.lambda + o.lambda == 0.0 {
                once_rounded(&h)
            } else {
                self.m + o.m
            },
            h,
            lambda: max(self.lambda, o.lambda) + 1.0,
        }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }
    /// [`Filtered::mul`]: `M = M_x M_y` (zero for an exact zero factor).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(&self, o: &Self) -> Self {
        SharedLanes {
            h: lanewise(|i| self.h[i] * o.h[i]),
            m: product_magnitude(self.m, o.m),
            lambda: self.lambda + o.lambda + 1.0,
        }
    }
    /// [`Filtered::mul_add`]: `M = M_x M_y + M_z`, or of exact operands the
    /// once-rounded `|h|` of each lane whose value is normal (the general
    /// rule's of a lane that is not).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul_add(&self, b: &Self, c: &Self) -> Self {
        let h = lanewise(|i| self.h[i].mul_add(b.h[i], c.h[i]));
        let general = product_magnitude(self.m, b.m) + c.m;
        let m = if self.lambda + b.lambda + c.lambda == 0.0 {
            largest(lanewise::<L>(|i| {
                if h[i].abs() >= f64::MIN_POSITIVE {
                    floored(h[i].abs() * ONE_PLUS_2U)
                } else {
                    general
                }
            }))
        } else {
            general
        };
        SharedLanes {
            h,
            m,
            lambda: max(self.lambda + b.lambda, c.lambda) + 1.0,
        }
    }
    /// [`Filtered::div`]: `M = (M_x + |q| M_y) / y_low` with the largest
    /// lane's `|q|` and the smallest lane's `y_low`, each lane's divisor
    /// certified against the shared bound (`∞` where one is not); zero for
    /// an exact zero dividend.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn div(&self, o: &Self) -> Self {
        let q = lanewise(|i| self.h[i] / o.h[i]);
        let error_y = (o.lambda * (U * SLACK)) * o.m;
        let y_low = lanewise::<L>(|i| (o.h[i].abs() - error_y) * (1.0 - 4.0 * U));
        let mut certified = true;
        for (low, y) in y_low.iter().zip(&o.h) {
            certified &= *low >= 0.5 * y.abs() && *low > 0.0;
        }
        let smallest_low = -largest(lanewise::<L>(|i| -y_low[i]));
        let largest_q = largest(lanewise::<L>(|i| q[i].abs()));
        let m = floored(largest_q.mul_add(o.m, self.m) * (1.0 + 4.0 * U) / smallest_low);
        SharedLanes {
            h: q,
            m: if self.m == 0.0 {
                0.0
            } else if certified {
                m
            } else {
                f64::INFINITY
            },
            lambda: max(self.lambda, o.lambda) + 2.0,
        }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn neg(&self) -> Self {
        SharedLanes {
            h: lanewise(|i| -self.h[i]),
            ..*self
        }
    }
    /// The sign every lane decides against the shared bound
    /// ([`Filtered::sign`]), or [`Diverged`].
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sign(&self) -> Result<Ordering, Diverged> {
        let bound = self.error_bound();
        let (mut clear, mut positive, mut negative) = (self.lambda <= LAMBDA_MAX, true, true);
        for &h in &self.h {
            // A finite |h| above the bound makes the bound finite too (a
            // NaN compares false).
            clear &= (h.abs() > bound) & (h.abs() < f64::INFINITY);
            positive &= h > 0.0;
            negative &= h < 0.0;
        }
        if clear && positive {
            return Ok(Ordering::Greater);
        }
        if clear && negative {
            return Ok(Ordering::Less);
        }
        // A zero bound (an input, an exact zero) leaves each lane's own
        // value exact: a sign they all share, zero included.
        let first = self.h[0].partial_cmp(&0.0);
        let mut same = bound == 0.0 && self.lambda <= LAMBDA_MAX;
        for &h in &self.h {
            same &= h.is_finite() && h.partial_cmp(&0.0) == first;
        }
        match first {
            Some(sign) if same => Ok(sign),
            _ => Err(Diverged),
        }
    }
    no_one_value!();
    /// Every lane's output `h + 0`, each tested against the shared bound
    /// and its lane's scale ([`Filtered::output_test`]), together.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output(&self, kind: ScaleKind, out: &mut [f64]) -> Result<(), Diverged> {
        let scales = lane_scales(kind);
        let bound = self.error_bound();
        let mut accepted = self.lambda <= LAMBDA_MAX;
        for (i, value) in out[..L].iter_mut().enumerate() {
            let v = self.h[i] + 0.0;
            *value = v;
            accepted &= v.is_finite() & (bound <= ACCEPTED_RELATIVE_BOUND * max(v.abs(), scales[i]));
        }
        if accepted { Ok(()) } else { Err(Diverged) }
    }
    /// Every lane's output `x √y`, accepted where its single solve's first
    /// form of the bound ([`Filtered::output_times_sqrt_against`]), with
    /// the shared bounds, is within the promise: `h_y` above its bound and
    /// `h_x` not zero in every lane (else the points are solved one by one).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output_times_sqrt(&self, y: &Self, kind: ScaleKind, out: &mut [f64]) -> Result<(), Diverged> {
        let scales = lane_scales(kind);
        let (error_x, error_y) = (self.error_bound(), y.error_bound());
        let mut accepted = self.lambda <= LAMBDA_MAX && y.lambda <= LAMBDA_MAX;
        // An exact zero factor in every lane: each lane's exact zero.
        let zero = self.m == 0.0 || y.m == 0.0;
        for (i, value) in out[..L].iter_mut().enumerate() {
            let v = self.h[i] * y.h[i].sqrt() + 0.0;
            *value = v;
            let (a, b) = (error_x / self.h[i].abs(), error_y / y.h[i]);
            let bound = v.abs() * (a.mul_add(b, a + b) + 2.0 * U);
            let bound = bound * (1.0 + 1.0 / 1024.0) + f64::MIN_POSITIVE;
            let first_form = (y.h[i] > error_y)
                & (self.h[i] != 0.0)
                & (bound <= ACCEPTED_RELATIVE_BOUND * max(v.abs(), scales[i]));
            accepted &= v.is_finite() & (zero | first_form);
        }
        if accepted { Ok(()) } else { Err(Diverged) }
    }
    fn approx(&self) -> f64 {
        self.h[0]
    }
}
