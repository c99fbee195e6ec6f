//! Compensated evaluation with a static error bound: the first, cheapest
//! stage of `precision: "exact"`.
//!
//! A [`Compensated`] `(h, l)` is the model evaluated twice at once: `h` is the
//! plain f64 evaluation, and `l` gathers the rounding errors of every step,
//! found exactly by the error-free transformations (TwoSum, FMA-based TwoProd,
//! the exact division remainder) and propagated to first order in plain f64,
//! as in the compensated algorithms of Ogita, Rump and Oishi ("Accurate sum
//! and dot product", SIAM J. Sci. Comput. 2005) and of Graillat, Langlois and
//! Louvet (compensated Horner). Unlike double-double arithmetic the pair is
//! never renormalised, so a sum costs one TwoSum and two additions, and a
//! product one TwoProd and two FMAs.
//!
//! The bound is static, in the manner of Shewchuk's predicates: each value also
//! carries `M`, an upper bound of `|x|` built like the value with every term
//! taken positive (a quotient's is the condition-weighted
//! `(M_x + |q| M_y) / |y|_low`), and a small number `λ` that depends only on
//! the shape of the computation (a root's also on its radicand's
//! conditioning, [`Compensated::sqrt`]). The invariants are, for the exact value `x`
//! and `u = 2⁻⁵³`:
//!
//! - (I1) `|x| ≤ M`,
//! - (I2) `|l| ≤ λ u M`,
//! - (I3) `|x − (h + l)| ≤ ε u² M`, with `ε = λ²`.
//!
//! Each operation derives its own `ε` from its operands' (the rule is at the
//! operation) and its `λ` so that `ε ≤ λ²` carries over; only `λ` is stored.
//! The derivations use four facts kept true at run time:
//!
//! - `M ≥ 2⁻⁹⁰⁰` or `M = 0` (every other `M` is raised to [`FLOOR`], which
//!   only loosens the bounds), so a rounding in the subnormal range (at most
//!   2⁻¹⁰⁷⁵ absolute) is far below `u² M` and is covered by the `+ 1` each rule
//!   carries for slack. `M = 0` means the value is exactly zero with `h = l = 0`
//!   (a zero input, or a product with one);
//! - `λ ≤ 2¹⁶` where a decision is made ([`LAMBDA_MAX`]; `λ` only grows, so
//!   every step before obeyed it too), so `λ³ u < 2⁻⁴`: the relative factors
//!   `1 + λu` and the like that the rules round away cost less than that `+ 1`;
//! - `M` is computed in round-to-nearest, at most a few roundings per step and
//!   fewer than 4096 along any path of the model, so the exact bound is below
//!   `M (1 + 2⁻⁴⁰)`, the factor applied where a decision is made;
//! - overflow leaves an infinity or NaN in `h` or `l`, and nothing is then
//!   certified.
//!
//! Wherever a sign or a rounding is not certified the caller repeats the
//! answer in double-double arithmetic, whose bound is tracked operation by
//! operation, and then in rationals.

use std::cmp::Ordering;

/// Unit roundoff `u = 2⁻⁵³`.
pub(super) const U: f64 = f64::EPSILON / 2.0;
/// `u²`.
const U2: f64 = U * U;
/// Every non-zero `M` is at least this (2⁻⁹⁰⁰): see the module documentation.
pub(super) const FLOOR: f64 = f64::from_bits((1023 - 900) << 52);
/// The least `|q|` of a certified quotient that is not exactly zero (2⁻⁹⁰⁰).
const QUOTIENT_MIN: f64 = FLOOR;
/// The most `λ` may reach where a decision is made (2¹⁶).
pub(super) const LAMBDA_MAX: f64 = (1u64 << 16) as f64;
/// Covers the roundings of `M` along a path (fewer than 4096 of them).
pub(super) const M_GROWTH: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;
/// The exponent field of an f64.
const EXPONENT_BITS: u64 = 0x7ff0_0000_0000_0000;
/// The fraction field of an f64.
const MANTISSA_BITS: u64 = (1 << 52) - 1;

/// `m` raised to [`FLOOR`] (a NaN stays a NaN).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn floored(m: f64) -> f64 {
    if m < FLOOR { FLOOR } else { m }
}

/// `M_x M_y` raised to [`FLOOR`], except that it is zero when a factor is (an
/// exact zero times anything finite is an exact zero), without a branch:
/// every `M` is 0 or at least [`FLOOR`] (or ∞, or a NaN: see [`max`]), so
/// `min(FLOOR, M_x, M_y)` is 0 for a zero factor and [`FLOOR`] otherwise.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn product_magnitude(mx: f64, my: f64) -> f64 {
    max(mx * my, min(FLOOR, min(mx, my)))
}

/// The larger of `a` and `b`, `b` if either is a NaN (one instruction, unlike
/// `f64::max`). A NaN dropped here cannot certify anything: an `M` or `λ`
/// becomes a NaN only from an overflow (which leaves a NaN or infinity in `h`)
/// or from `0 · ∞` between an exact zero and an overflowed `M`, whose product
/// is the exact zero it is taken for.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn max(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The smaller of `a` and `b`, `b` if either is a NaN; see [`max`].
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn min(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// `a + b = s + e` exactly (Knuth's TwoSum).
#[cfg_attr(not(debug_assertions), inline(always))]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Why a sign or a rounding was left undecided: the next stage is chosen by it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unsettled {
    /// Overflow, an ill-conditioned or tiny quotient, or `λ` past its limit:
    /// double-double with a tracked bound may still decide.
    Range,
    /// The value lies too close to zero or to a rounding midpoint for the
    /// bound: possibly exactly there, which only exact tracking decides.
    Close,
    /// A square root whose radicand is too close to zero for its
    /// conditioning (or out of range): double-double, with its tracked
    /// bound, may still decide.
    Root,
}

/// A compensated value with its static bound; see the module documentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Compensated {
    h: f64,
    l: f64,
    /// `M`: an upper bound of the exact value's magnitude.
    m: f64,
    /// `λ` in (I2); `ε = λ²` in (I3).
    lambda: f64,
}

impl Compensated {
    /// An f64, exactly (`λ = 0`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn exact(x: f64) -> Self {
        Compensated {
            h: x,
            l: 0.0,
            m: if x == 0.0 { 0.0 } else { floored(x.abs()) },
            lambda: 0.0,
        }
    }

    /// A value on which every decision is uncertain.
    const UNKNOWN: Self = Compensated {
        h: f64::NAN,
        l: f64::NAN,
        m: f64::INFINITY,
        lambda: f64::INFINITY,
    };

    /// The value as one f64, for diagnostics only.
    pub(crate) fn approx(&self) -> f64 {
        self.h + self.l
    }

    /// The sum. `h_x + h_y = s + t` exactly (TwoSum, `|t| ≤ u(|h_x| + |h_y|)`),
    /// and `l = (l_x + l_y) + t` in two roundings. With `λ = max(λ_x, λ_y)` and
    /// `M = M_x + M_y`, the first rounding is at most `u · λ u M`, the second at
    /// most `u (λ + 1) u M`, and the inherited errors at most `λ² u² M`: so
    /// `ε_s = λ² + 2λ + 2 ≤ (λ + 2)²`, and `|l| ≤ (λ + 1) u M (1 + u)`: `λ_s = λ + 2`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn add(&self, o: &Self) -> Self {
        let (s, t) = two_sum(self.h, o.h);
        Compensated {
            h: s,
            l: (self.l + o.l) + t,
            m: self.m + o.m,
            lambda: max(self.lambda, o.lambda) + 2.0,
        }
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn neg(&self) -> Self {
        Compensated {
            h: -self.h,
            l: -self.l,
            ..*self
        }
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }

    /// The product. `h_x h_y = p + t` exactly (FMA TwoProd), and
    /// `l = h_x l_y + (l_x h_y + t)` in two FMAs; the term `l_x l_y` is dropped.
    /// With `M = M_x M_y`: the dropped term is at most `λ_x λ_y u² M`, the
    /// roundings at most `(λ_x + 1) u² M` and `(λ_x + λ_y + 1) u² M`, the
    /// inherited errors at most `(λ_x² + λ_y²) u² M` (to first order; the rest is
    /// in the slack). So `ε_p = λ_x² + λ_y² + λ_x λ_y + 2λ_x + λ_y + 3
    /// ≤ (λ_x + λ_y + 2)²`, and `λ_p = λ_x + λ_y + 2`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn mul(&self, o: &Self) -> Self {
        let p = self.h * o.h;
        let t = self.h.mul_add(o.h, -p);
        Compensated {
            h: p,
            l: self.h.mul_add(o.l, self.l.mul_add(o.h, t)),
            m: product_magnitude(self.m, o.m),
            lambda: self.lambda + o.lambda + 2.0,
        }
    }

    /// The quotient `x / y`. The divisor is first renormalised, `(h_y, l_y)`
    /// with `|l_y| ≤ u |h_y|`, so `|y| ≥ |h_y| (1 − δ)` with
    /// `δ = (|l_y| + λ_y² u² M_y) / |h_y|`. With `i ≈ 1 / h_y` (one division) and
    /// `d ≥ δ` computed through it, `y_low = 1 / i_low` where
    /// `i_low = |i| (1 + 2d)(1 + 8u) ≥ 1 / |y|` (as `1 / (1 − δ) ≤ 1 + 2δ` for
    /// `δ ≤ ½`; `d ≤ ¼` is checked), and `y_low ≤ |h_y|`. Then `q = h_x / h_y`
    /// (the second division, correctly rounded), the remainder
    /// `r = h_x − q h_y` (exact, by one FMA), `N = r + l_x − q l_y`, `l = N i`, and
    /// `M_q = (M_x + |q| M_y) i_low`, which is at least `|x / y|`.
    ///
    /// `|r| ≤ u |q| |h_y|`, so `|N| ≤ (2 + λ_x) u y_low M_q` and
    /// `|l| ≤ (2 + λ_x) u M_q`. With `λ = max(λ_x, λ_y)`, the inherited errors give
    /// at most `λ² u² M_q` plus a third-order term `λ_y² (2 + λ_x) u (M_y / y_low) u² M_q`,
    /// which is at most `u² M_q` where `λ_y² (2 + λ_x) u M_y i_low ≤ ½` (checked;
    /// elsewhere nothing is certified). The two roundings in `N`, the two in
    /// `l = N i` and using `h_y` rather than `h_y + l_y` add at most
    /// `5 (2 + λ_x) u² M_q`; a remainder or `N` in the subnormal range is off by
    /// at most 2⁻¹⁰⁷⁵ each, far below `u² M_x ≤ u² y_low M_q`. So
    /// `ε_q = λ² + 5λ_x + 12 ≤ (λ + 4)²`, and `λ_q = λ + 4`.
    ///
    /// An exactly zero dividend gives an exact zero; a quotient below
    /// [`QUOTIENT_MIN`] or a divisor above 2¹⁰²² (whose roundings are not
    /// relative) certifies nothing.
    pub(crate) fn div(&self, o: &Self) -> Self {
        if self.m == 0.0 {
            return Compensated::exact(0.0);
        }
        let (yh, yl) = two_sum(o.h, o.l);
        let inv = 1.0 / yh;
        let q = self.h / yh;
        let eps_y = o.lambda * o.lambda;
        let d = (yl.abs() + eps_y * U2 * o.m * M_GROWTH) * inv.abs() * (1.0 + 8.0 * U);
        let inv_low = inv.abs() * (1.0 + 2.0 * d) * (1.0 + 8.0 * U);
        let third_order = eps_y * (2.0 + self.lambda) * U * o.m * inv_low;
        // A normal reciprocal is within u of 1 / h_y relative (not so above 2¹⁰²²).
        let certified = d <= 0.25
            && third_order <= 0.5
            && inv.abs() >= f64::MIN_POSITIVE
            && q.abs() >= QUOTIENT_MIN
            && q.is_finite();
        if !certified {
            // Nothing is decided on it (M = λ = ∞); the quotient of the
            // operands' approximations stays for diagnostics (a refusal's
            // payload may name it).
            return Compensated {
                h: self.approx() / o.approx(),
                l: 0.0,
                ..Self::UNKNOWN
            };
        }
        let r = (-q).mul_add(yh, self.h);
        let n = (-q).mul_add(yl, r + self.l);
        Compensated {
            h: q,
            l: n * inv,
            m: floored(q.abs().mul_add(o.m, self.m) * inv_low),
            lambda: max(self.lambda, o.lambda) + 4.0,
        }
    }

    /// The square root of a value whose exact value `x` the model has
    /// decided non-negative. `s = √h` correctly rounded, `r = h − s²` exact
    /// (one FMA: the remainder of a correctly rounded root is a double for
    /// `h ≥ 2⁻⁹⁰⁰`), and `l = (r + l_x) / (2s)`, the first-order term of
    /// `√(s² + t) = s + t / (2s) − R` with `t = x − s² = r + l_x + δ`,
    /// `|δ| ≤ λ² u² M_x`, `|r| ≤ 2u h`.
    ///
    /// With the radicand's conditioning `K = M_x / h` and
    /// `(λ + 2) u K ≤ 2⁻¹⁰` (checked), `|t| ≤ (λ + 2) u M_x` to first order,
    /// so `a = t / s² ≤ 2⁻¹⁰`: `√x ≥ s (1 − 2⁻⁹)`, and `M_q = M_x / (s (1 − 2⁻⁹))`
    /// is at least `M_x / √x ≥ √x` and at least `M_x / s`; and
    /// `0 ≤ R ≤ s a² / 8 · (1 − a)^(−3/2) ≤ (λ + 2)² K u² M_q / 7`. The roundings
    /// of `r + l_x` and of the quotient add at most `(λ + 2) u² M_q`, and
    /// `δ / (2s)` at most `λ² u² M_q / 2`; `|l| ≤ (λ + 2) u M_q / 2`. So
    /// `ε_q ≤ λ² / 2 + λ + 3 + (λ + 2)² K / 7 ≤ ((λ + 3)(1 + √K))²` and
    /// `λ_q = (λ + 3)(1 + √K)`: the one rule whose `λ` reads the data (it
    /// still only grows). An exact zero's root is the exact zero. A radicand
    /// the check refuses (`h` below 2⁻⁹⁰⁰ or not positive, `K` too large,
    /// out of range) is [`Unsettled::Root`]: double-double decides it.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn sqrt(&self) -> Result<Self, Unsettled> {
        if self.m == 0.0 {
            return Ok(Compensated::exact(0.0));
        }
        let conditioning = self.m / self.h * (1.0 + 4.0 * U);
        // (A NaN or non-positive h fails the first test.)
        let certified = self.h >= FLOOR
            && self.m.is_finite()
            && self.lambda <= LAMBDA_MAX
            && (self.lambda + 2.0) * U * conditioning <= 1.0 / 1024.0;
        if !certified {
            return Err(Unsettled::Root);
        }
        let s = self.h.sqrt();
        let r = (-s).mul_add(s, self.h);
        Ok(Compensated {
            h: s,
            l: (r + self.l) / (2.0 * s),
            m: floored(self.m / (s * (1.0 - 1.0 / 512.0)) * (1.0 + 4.0 * U)),
            lambda: (self.lambda + 3.0) * (1.0 + conditioning.sqrt()),
        })
    }

    /// `h + l` renormalised, and the bound `λ² u² M` on its distance from the
    /// exact value (zero only when `h + l` is exact: `λ = 0` or `M = 0`, as a
    /// non-zero `M ≥ 2⁻⁹⁰⁰` and `λ ≥ 2` keep the product above the subnormal
    /// range); [`Unsettled::Range`] when nothing can be certified (overflow,
    /// or `λ` past [`LAMBDA_MAX`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn settled(&self) -> Result<(f64, f64, f64), Unsettled> {
        let (s, c) = two_sum(self.h, self.l);
        let bound = self.lambda * self.lambda * U2 * self.m * M_GROWTH;
        let usable = s.is_finite() && c.is_finite() && bound.is_finite() && self.lambda <= LAMBDA_MAX;
        if usable {
            Ok((s, c, bound))
        } else {
            Err(Unsettled::Range)
        }
    }

    /// The exact value's sign, unless the bound cannot decide it.
    #[inline]
    pub(crate) fn sign(&self) -> Result<Ordering, Unsettled> {
        let (s, c, bound) = self.settled()?;
        if bound == 0.0 {
            // s + c is the exact value, and s has its sign (or both are zero).
            return s.partial_cmp(&0.0).ok_or(Unsettled::Range);
        }
        let lower = (s.abs() - c.abs()) * (1.0 - 4.0 * U);
        if lower > bound {
            Ok(if s > 0.0 {
                Ordering::Greater
            } else {
                Ordering::Less
            })
        } else {
            Err(Unsettled::Close)
        }
    }

    /// The exact value rounded to the nearest f64, unless the bound does not
    /// fit inside one rounding interval. An exact zero is `+0.0`.
    #[inline]
    pub(crate) fn round(&self) -> Result<f64, Unsettled> {
        let (s, c, bound) = self.settled()?;
        if bound == 0.0 {
            // s + c is the exact value and TwoSum rounded it to nearest-even.
            return Ok(if s == 0.0 { 0.0 } else { s });
        }
        if s == 0.0 {
            return Err(Unsettled::Close);
        }
        // The exact value is within |c| + bound of s; s is its rounding when
        // that is under half the smaller gap to s's neighbours: 2^(e − 52) for
        // 2^e < |s|, half that for |s| = 2^e (taken as 0 for a subnormal s,
        // which is then not certified).
        let bits = s.to_bits();
        let ulp = f64::from_bits(bits & EXPONENT_BITS) * f64::EPSILON;
        let gap = if bits & MANTISSA_BITS == 0 { 0.5 * ulp } else { ulp };
        let slack = (c.abs() + bound) * (1.0 + 4.0 * U);
        if 2.0 * slack < gap {
            Ok(s)
        } else if gap == 0.0 {
            Err(Unsettled::Range)
        } else {
            Err(Unsettled::Close)
        }
    }
}

#[cfg(test)]
mod tests;
