//! Exact numbers with one square root, `a + b √g` (`a`, `b` rational, `g` a
//! positive integer that is not a perfect square): the last stage of `exact`
//! precision, which decides every sign and every rounding of the model.
//!
//! An impact in space slides along `n − f √γ u_t` (`γ = |n|²/|u_t|²`), so its
//! answer lives in `ℚ(√γ)`: one root per answer, entered by
//! [`Radical::sqrt`] of a rational. Signs are decided exactly by squaring
//! (`a + b √g` with `a`, `b` of opposite signs has the sign of the larger of
//! `a²` and `b² g`). Rounding follows Ziv's strategy: the value is enclosed
//! with `√g` to `k` bits (an integer square root), and the rounding stands
//! when both ends of the enclosure round alike; the first `k` is the
//! optimistic one (no cancellation between `a` and `b √g`), the second the
//! one a root-separation bound (`|a + b √g| = |a² − b² g| / |a − b √g|`)
//! guarantees to narrow the enclosure below a thousandth of an ulp. When even
//! that enclosure holds a rounding boundary, the value is compared with the
//! boundary exactly (by the sign test): a value exactly on a midpoint rounds
//! to even, which no loop of increasing precision would ever decide. A root
//! that is rational (`g` a perfect square) is never formed: `sqrt` returns the
//! rational itself. Time and memory are bounded by the size of the inputs,
//! since both precisions are computed from it.

use std::cmp::Ordering;
use std::convert::Infallible;
use std::rc::Rc;

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

use super::field::Field;
use super::fraction::Fraction;

/// Parts are brought to lowest terms past this many bits: without it the
/// numerators and denominators of a spatial answer (a tensor's inverse, the
/// contact matrix's adjugate, conjugates) multiply into millions of bits.
const REDUCE_ABOVE: u64 = 4096;

/// The irrational part `b √g` of a [`Surd`] (`b ≠ 0`).
#[derive(Debug, Clone, PartialEq)]
struct Root {
    b: Fraction,
    /// `g > 1`, not a perfect square; shared by every value of one answer.
    g: Rc<BigInt>,
}

/// An exact `a + b √g`; see the module documentation.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Surd {
    a: Fraction,
    root: Option<Root>,
}

impl Surd {
    fn rational(a: Fraction) -> Self {
        Surd {
            a: a.reduced(REDUCE_ABOVE),
            root: None,
        }
    }

    /// `a + b √g`, with the root dropped when `b = 0`.
    fn with(a: Fraction, b: Fraction, g: &Rc<BigInt>) -> Self {
        let root = (b.sign() != Ok(Ordering::Equal)).then(|| Root {
            b: b.reduced(REDUCE_ABOVE),
            g: Rc::clone(g),
        });
        Surd {
            a: a.reduced(REDUCE_ABOVE),
            root,
        }
    }

    /// The conjugate `a − b √g`.
    fn conjugate(&self) -> Self {
        Surd {
            a: self.a.clone(),
            root: self.root.as_ref().map(|r| Root {
                b: r.b.neg(),
                g: Rc::clone(&r.g),
            }),
        }
    }

    /// `a² − b² g`, the norm (non-zero unless the value is).
    fn norm(&self) -> Fraction {
        match &self.root {
            None => self.a.mul(&self.a),
            Some(r) => self
                .a
                .mul(&self.a)
                .sub(&r.b.mul(&r.b).mul(&Fraction::integer(&r.g))),
        }
    }

    /// The enclosure `[L, H]` of the value with `√g` to `k` bits (`k` may
    /// be negative): `R = ⌊√(g 4^k)⌋` gives `R ≤ √g 2^k < R + 1`.
    fn enclosure(a: &Fraction, r: &Root, k: i64) -> (Fraction, Fraction) {
        let scaled = if k >= 0 {
            &*r.g << (2 * k as u64)
        } else {
            &*r.g >> (2 * (-k) as u64)
        };
        let root = scaled.sqrt();
        let below = Fraction::dyadic(root.clone(), k);
        let above = Fraction::dyadic(root + BigInt::one(), k);
        let (x, y) = (a.add(&r.b.mul(&below)), a.add(&r.b.mul(&above)));
        if r.b.sign() == Ok(Ordering::Less) {
            (y, x)
        } else {
            (x, y)
        }
    }

    /// The precisions Ziv's loop tries: the optimistic one and the one the
    /// separation bound guarantees (`log₂` estimates carry 4 bits of margin).
    fn precisions(&self, r: &Root) -> [i64; 2] {
        let log_b = r.b.log2_estimate();
        let log_root = (r.g.bits() as i64) / 2;
        let log_a = if self.a.sign() == Ok(Ordering::Equal) {
            i64::MIN / 4
        } else {
            self.a.log2_estimate()
        };
        let largest = log_a.max(log_b + log_root);
        // The enclosure's width is |b| 2^−k; ask for 2^−72 of the value.
        let optimistic = log_b - largest + 76;
        let same_signs = self.a.sign() == Ok(Ordering::Equal) || self.a.sign() == r.b.sign();
        let smallest = if same_signs {
            log_b + log_root - 4
        } else {
            // |a + b√g| = |a² − b²g| / |a − b√g| ≥ |norm| / 2^(largest + 2).
            self.norm().log2_estimate() - largest - 6
        };
        [optimistic, log_b - smallest + 76]
    }
}

impl Field for Surd {
    type Undecided = Infallible;

    fn of(x: f64) -> Self {
        Surd::rational(Fraction::of(x))
    }
    fn add(&self, o: &Self) -> Self {
        let a = self.a.add(&o.a);
        match (&self.root, &o.root) {
            (None, None) => Surd::rational(a),
            (Some(r), None) | (None, Some(r)) => Surd {
                a,
                root: Some(r.clone()),
            },
            (Some(x), Some(y)) => {
                debug_assert!(Rc::ptr_eq(&x.g, &y.g) || x.g == y.g, "two roots in one answer");
                Surd::with(a, x.b.add(&y.b), &x.g)
            }
        }
    }
    fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }
    fn mul(&self, o: &Self) -> Self {
        match (&self.root, &o.root) {
            (None, None) => Surd::rational(self.a.mul(&o.a)),
            (Some(r), None) => Surd::with(self.a.mul(&o.a), r.b.mul(&o.a), &r.g),
            (None, Some(r)) => Surd::with(self.a.mul(&o.a), r.b.mul(&self.a), &r.g),
            (Some(x), Some(y)) => {
                debug_assert!(Rc::ptr_eq(&x.g, &y.g) || x.g == y.g, "two roots in one answer");
                let g = Fraction::integer(&x.g);
                let a = self.a.mul(&o.a).add(&x.b.mul(&y.b).mul(&g));
                let b = self.a.mul(&y.b).add(&x.b.mul(&o.a));
                Surd::with(a, b, &x.g)
            }
        }
    }
    /// `(a + b√g) / (c + d√g) = (a + b√g)(c − d√g) / (c² − d² g)`.
    fn div(&self, o: &Self) -> Self {
        let (num, den) = match &o.root {
            None => (self.clone(), o.a.clone()),
            Some(_) => (self.mul(&o.conjugate()), o.norm()),
        };
        match num.root {
            None => Surd::rational(num.a.div(&den)),
            Some(r) => Surd::with(num.a.div(&den), r.b.div(&den), &r.g),
        }
    }
    fn neg(&self) -> Self {
        Surd {
            a: self.a.neg(),
            root: self.root.as_ref().map(|r| Root {
                b: r.b.neg(),
                g: Rc::clone(&r.g),
            }),
        }
    }
    fn sign(&self) -> Result<Ordering, Infallible> {
        let Some(r) = &self.root else {
            return self.a.sign();
        };
        let (sa, sb) = (self.a.sign()?, r.b.sign()?);
        if sa == Ordering::Equal || sa == sb {
            return Ok(sb);
        }
        // Opposite signs: the larger of a² and b² g wins (never equal: g is
        // not a square).
        Ok(match self.norm().sign()? {
            Ordering::Greater => sa,
            _ => sb,
        })
    }
    fn round(&self) -> Result<f64, Infallible> {
        let Some(r) = &self.root else {
            return self.a.round();
        };
        if self.sign()? == Ordering::Equal {
            return Ok(0.0);
        }
        let mut ends = (0.0, 0.0);
        for k in self.precisions(r) {
            let (low, high) = Surd::enclosure(&self.a, r, k);
            ends = (low.round()?, high.round()?);
            if ends.0 == ends.1 {
                return Ok(ends.0);
            }
        }
        // The enclosure (narrower than a thousandth of an ulp) holds the
        // boundary between two neighbours: compare exactly.
        let (low, high) = ends;
        let boundary = if high.is_infinite() {
            Fraction::of(f64::MAX).add(&Fraction::of(2f64.powi(970)))
        } else if low.is_infinite() {
            Fraction::of(f64::MIN).sub(&Fraction::of(2f64.powi(970)))
        } else {
            Fraction::of(low).add(&Fraction::of(high)).mul(&Fraction::of(0.5))
        };
        Ok(match self.sub(&Surd::rational(boundary)).sign()? {
            Ordering::Less => low,
            Ordering::Greater => high,
            Ordering::Equal if low.is_finite() && low.to_bits() & 1 == 0 => low,
            Ordering::Equal => high,
        })
    }
    fn approx(&self) -> f64 {
        self.round().unwrap_or_else(|never| match never {})
    }
}

/// A [`Field`] that can take the square root of a value the model formed
/// without one (`|n|`, `|u_t|`): the spatial laws' sliding direction.
pub(crate) trait Radical: Field + 'static {
    /// `√x` of a non-negative `x`: approximately in f64; with a rigorous
    /// bound in double-double; exactly (as a [`Surd`]) in the last stage.
    /// The compensated stage's static bound does not cover roots: it gives
    /// way to double-double.
    fn sqrt(&self) -> Result<Self, Self::Undecided>;
}

impl Radical for f64 {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sqrt(&self) -> Result<f64, super::OutOfRange> {
        Ok(f64::sqrt(*self))
    }
}

impl<const RUNNING: bool, const STATIC: bool> Radical for super::Filtered<RUNNING, STATIC> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sqrt(&self) -> Result<Self, super::Uncertain> {
        super::Filtered::sqrt(self)
    }
}

impl Radical for super::Compensated {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sqrt(&self) -> Result<Self, super::Unsettled> {
        super::Compensated::sqrt(self)
    }
}

impl<const TRACK: bool> Radical for super::Bounded<TRACK> {
    /// The double-double root with its bound (undecided when the value's
    /// interval reaches zero: then its sign, hence its root, is not known).
    fn sqrt(&self) -> Result<Self, super::Undecided> {
        let root = super::Bounded::sqrt(self);
        match root.sign() {
            Some(_) => Ok(root),
            None => Err(super::Undecided),
        }
    }
}

impl Radical for Surd {
    /// The root of a rational `p/q ≥ 0` is `√(p q) / q`: rational when `p q`
    /// is a perfect square, else `b √g` with the factors of four of `p q`
    /// moved into `b`. (The model never takes the root of a value with a
    /// root; such a value is rounded first, in debug builds an assertion.)
    fn sqrt(&self) -> Result<Self, Infallible> {
        debug_assert!(self.root.is_none(), "a root of a root");
        debug_assert!(self.a.sign() != Ok(Ordering::Less), "a root of a negative value");
        if self.root.is_some() {
            return Ok(Surd::of(self.approx().sqrt()));
        }
        let (p, q) = self.a.parts();
        let product = (p * q).abs();
        if product.is_zero() {
            return Ok(Surd::of(0.0));
        }
        let floor = product.sqrt();
        if &floor * &floor == product {
            return Ok(Surd::rational(Fraction::from_parts(floor, q.clone())));
        }
        let fours = product.trailing_zeros().unwrap_or(0) / 2;
        let g = Rc::new(product >> (2 * fours));
        let b = Fraction::from_parts(BigInt::one() << fours, q.clone());
        Ok(Surd {
            a: Fraction::of(0.0),
            root: Some(Root { b, g }),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    /// `a + b √g` rounded by brute force: `√g` to 4000 bits, then the
    /// rational enclosure's ends, which must agree at that width.
    fn reference(a: f64, b: f64, g: u64) -> f64 {
        let k = 4000i64;
        let root = (BigInt::from(g) << (2 * k as u64)).sqrt();
        let fa = Fraction::of(a);
        let fb = Fraction::of(b);
        let lo = fa.add(&fb.mul(&Fraction::dyadic(root.clone(), k)));
        let hi = fa.add(&fb.mul(&Fraction::dyadic(root + 1, k)));
        let (x, y) = (lo.round().unwrap(), hi.round().unwrap());
        assert_eq!(x, y, "reference enclosure too wide");
        x
    }

    fn surd(a: f64, b: f64, g: u64) -> Surd {
        Surd::of(a).add(&Surd::of(b).mul(&Surd::of(g as f64).sqrt().unwrap()))
    }

    #[test]
    fn rounds_like_a_wide_reference_including_cancellation() {
        let cases = [
            (0.0, 1.0, 2),
            (1.0, 1.0, 2),
            (-1.0, 1.0, 2),
            (1e300, -1e-300, 3),
            (-std::f64::consts::SQRT_2, 1.0, 2),
            (-std::f64::consts::SQRT_2.next_down(), 1.0, 2),
            (3f64.sqrt(), -1.0, 3),
            (3.0, -2.0, 2),
            (5e-324, 1e-320, 7),
            (-2.5, 0.5, 24),
        ];
        for (a, b, g) in cases {
            assert_eq!(
                surd(a, b, g).round().unwrap(),
                reference(a, b, g),
                "{a} + {b} √{g}"
            );
        }
    }

    #[test]
    fn rational_roots_stay_rational_and_exact_products_cancel() {
        let r = Surd::of(2.25).sqrt().unwrap();
        assert!(r.root.is_none());
        assert_eq!(r.round().unwrap(), 1.5);
        let s = Surd::of(2.0).sqrt().unwrap();
        assert_eq!(s.mul(&s).round().unwrap(), 2.0);
        assert!(s.mul(&s).root.is_none());
        assert_eq!(s.sub(&s).sign().unwrap(), Ordering::Equal);
        let q = Surd::of(1.0).div(&Surd::of(1.0).add(&s));
        // 1/(1 + √2) = √2 − 1
        assert_eq!(q.round().unwrap(), reference(-1.0, 1.0, 2));
        assert_eq!(
            Surd::of(8.0).sqrt().unwrap().root.as_ref().unwrap().g.as_ref(),
            &BigInt::from(2)
        );
    }

    #[test]
    fn signs_are_exact_next_to_cancellation() {
        // √2 lies strictly between these neighbours.
        let s = Surd::of(2.0).sqrt().unwrap();
        assert_eq!(
            s.sub(&Surd::of(std::f64::consts::SQRT_2)).sign().unwrap(),
            Ordering::Less
        );
        assert_eq!(
            s.sub(&Surd::of(std::f64::consts::SQRT_2.next_down()))
                .sign()
                .unwrap(),
            Ordering::Greater
        );
    }

    #[test]
    fn a_value_exactly_on_a_midpoint_rounds_to_even() {
        // (1 + 2^−53) + (√2 − √2): formed as a surd whose root cancels.
        let s = Surd::of(2.0).sqrt().unwrap();
        let mid = Surd::of(1.0).add(&Surd::of(2f64.powi(-53)));
        assert_eq!(mid.add(&s).sub(&s).round().unwrap(), 1.0);
        // A tie that keeps its root through the enclosure: x = m + ε√2 with
        // ε so small that the enclosure cannot separate it from m at the
        // first width; the exact comparison decides.
        let tiny = Surd::of(2f64.powi(-1000)).mul(&s);
        let above = mid.add(&tiny);
        assert_eq!(above.round().unwrap(), 1.0 + f64::EPSILON);
        let below = mid.sub(&tiny);
        assert_eq!(below.round().unwrap(), 1.0);
    }
}
