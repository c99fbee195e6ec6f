//! The arithmetic the model is written in, [`Field`], and its implementations
//! for plain `f64` and for exact [`Fraction`]s of big integers (the
//! compensated and double-double ones are in their own files).

use std::cmp::Ordering;

use super::bounded::Bounded;
use super::compensated::{Compensated, Unsettled};
use super::filtered::{Filtered, Uncertain};
use crate::accuracy::ScaleKind;

/// A number the exact model can be evaluated in.
pub(crate) trait Field: Clone {
    /// How an undecided sign or rounding is reported: [`Unsettled`] (with its
    /// cause) in compensated arithmetic, [`Undecided`] in double-double;
    /// uninhabited ([`Infallible`]) in exact arithmetic,
    /// which decides every sign and rounding.
    type Undecided;
    /// How many points a value holds: one, but in [`super::Lanes`].
    const LANES: usize = 1;
    /// An f64 input, exactly.
    fn of(x: f64) -> Self;
    /// An input whose value at lane `i` is `x(i)`, exactly ([`Field::of`]
    /// of `x(0)` in a field of one point).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of_lanes(x: impl Fn(usize) -> f64) -> Self {
        Self::of(x(0))
    }
    /// [`Field::quotient_of`] of `(num, den, rounded) = q(i)` at lane `i`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of_lanes(q: impl Fn(usize) -> (f64, f64, f64)) -> Self {
        let (num, den, rounded) = q(0);
        Self::quotient_of(num, den, rounded)
    }
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    /// `self · b + c`: one rounding in `f64` (a fused multiply-add), the exact
    /// value in the exact fields. The model uses it where a fused form keeps
    /// the f64 evaluation's sign or accuracy.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul_add(&self, b: &Self, c: &Self) -> Self {
        self.mul(b).add(c)
    }
    /// Division; the model only divides by values whose sign it has decided non-zero.
    fn div(&self, o: &Self) -> Self;
    /// The quotient of two f64 inputs, `rounded` being their f64 quotient
    /// already formed: `f64` takes it as it is (no second division), the exact
    /// fields form the exact one.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of(num: f64, den: f64, rounded: f64) -> Self {
        let _ = rounded;
        Self::of(num).div(&Self::of(den))
    }
    fn neg(&self) -> Self;
    /// The sign of the exact value.
    fn sign(&self) -> Result<Ordering, Self::Undecided>;
    /// The exact value correctly rounded to f64 (`±∞` beyond the range).
    fn round(&self) -> Result<f64, Self::Undecided>;
    /// An output of unit class `kind`: [`Field::round`], except in `fast`
    /// arithmetic, which answers its own value when its error bound is
    /// within the promise ([`crate::accuracy`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_output(&self, kind: ScaleKind) -> Result<f64, Self::Undecided> {
        let _ = kind;
        self.round()
    }
    /// An output `x √y` of unit class `kind`, as [`Field::round_output`].
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_output_times_sqrt(&self, y: &Self, kind: ScaleKind) -> Result<f64, Self::Undecided> {
        let _ = kind;
        self.round_times_sqrt(y)
    }
    /// Every lane's output of unit class `kind`, lane `i`'s in `out[i]`
    /// (`out[0]` is [`Field::round_output`] in a field of one point).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output(&self, kind: ScaleKind, out: &mut [f64]) -> Result<(), Self::Undecided> {
        out[0] = self.round_output(kind)?;
        Ok(())
    }
    /// Every lane's output `x √y` of unit class `kind`, as
    /// [`Field::lanes_output`] (`out[0]` is
    /// [`Field::round_output_times_sqrt`] in a field of one point).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output_times_sqrt(
        &self,
        y: &Self,
        kind: ScaleKind,
        out: &mut [f64],
    ) -> Result<(), Self::Undecided> {
        out[0] = self.round_output_times_sqrt(y, kind)?;
        Ok(())
    }
    /// A nearby f64 for diagnostics (error payloads), never for answers.
    fn approx(&self) -> f64;
    /// `x √y` (`y ≥ 0`) correctly rounded: the exact fields decide it from
    /// `z = x² y` by comparing `z` with the squares of the midpoints around a
    /// candidate (ties to even), after scaling `z` by a power of four into
    /// the middle of the range (a result below the normal range is rounded
    /// twice, there).
    fn round_times_sqrt(&self, y: &Self) -> Result<f64, Self::Undecided> {
        let negative = match self.sign()? {
            Ordering::Equal => return Ok(0.0),
            sign => sign == Ordering::Less,
        };
        if y.sign()? == Ordering::Equal {
            return Ok(0.0);
        }
        let mut z = self.mul(self).mul(y);
        let mut scale = 1.0;
        let mut rounded = z.round()?;
        for _ in 0..64 {
            if rounded > 2f64.powi(600) {
                z = z.mul(&Self::of(2f64.powi(-1000)));
                scale *= 2f64.powi(500);
            } else if rounded < 2f64.powi(-600) {
                z = z.mul(&Self::of(2f64.powi(1000)));
                scale *= 2f64.powi(-500);
            } else {
                break;
            }
            rounded = z.round()?;
        }
        let half = Self::of(0.5);
        let above = |a: f64, b: f64| -> Result<Ordering, Self::Undecided> {
            let mid = Self::of(a).add(&Self::of(b)).mul(&half);
            z.sub(&mid.mul(&mid)).sign()
        };
        let mut s = rounded.sqrt();
        for _ in 0..4 {
            let up = s.next_up();
            match above(s, up)? {
                Ordering::Greater => {
                    s = up;
                    continue;
                }
                Ordering::Equal => {
                    if s.to_bits() & 1 == 1 {
                        s = up;
                    }
                    break;
                }
                Ordering::Less => {}
            }
            let down = s.next_down();
            match above(down, s)? {
                Ordering::Less => s = down,
                Ordering::Equal => {
                    if s.to_bits() & 1 == 1 {
                        s = down;
                    }
                    break;
                }
                Ordering::Greater => break,
            }
        }
        let v = s * scale;
        Ok(if negative { -v } else { v })
    }
}

/// `Field`'s constructor and ring operations (`of`, `add`, `sub`, `mul`,
/// `neg`) as the implementing type's inherent methods of the same names
/// (`exact` for `of`), each under the given inline attribute.
macro_rules! forward_ring {
    (#[$inline:meta]) => {
        #[$inline]
        fn of(x: f64) -> Self {
            Self::exact(x)
        }
        #[$inline]
        fn add(&self, o: &Self) -> Self {
            Self::add(self, o)
        }
        #[$inline]
        fn sub(&self, o: &Self) -> Self {
            Self::sub(self, o)
        }
        #[$inline]
        fn mul(&self, o: &Self) -> Self {
            Self::mul(self, o)
        }
        #[$inline]
        fn neg(&self) -> Self {
            Self::neg(self)
        }
    };
}

impl Field for Compensated {
    type Undecided = Unsettled;
    forward_ring!(#[cfg_attr(not(debug_assertions), inline(always))]);
    #[inline]
    fn div(&self, o: &Self) -> Self {
        Self::div(self, o)
    }
    #[inline]
    fn sign(&self) -> Result<Ordering, Unsettled> {
        Self::sign(self)
    }
    #[inline]
    fn round(&self) -> Result<f64, Unsettled> {
        Self::round(self)
    }
    fn approx(&self) -> f64 {
        Self::approx(self)
    }
}

impl<const RUNNING: bool, const STATIC: bool> Field for Filtered<RUNNING, STATIC> {
    type Undecided = Uncertain;
    forward_ring!(#[cfg_attr(not(debug_assertions), inline(always))]);
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul_add(&self, b: &Self, c: &Self) -> Self {
        Self::mul_add(self, b, c)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn div(&self, o: &Self) -> Self {
        Self::div(self, o)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of(num: f64, den: f64, rounded: f64) -> Self {
        debug_assert_eq!(rounded.to_bits(), (num / den).to_bits());
        Self::quotient_of(num, rounded)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sign(&self) -> Result<Ordering, Uncertain> {
        Self::sign(self)
    }
    /// The f64 value itself (`fast` outputs are not rounded again), with a
    /// zero written `+0.0`, when its error bound is within the promise of a
    /// dimensionless number relative to itself (the model's outputs go
    /// through [`Field::round_output`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round(&self) -> Result<f64, Uncertain> {
        self.output(ScaleKind::Dimensionless)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_times_sqrt(&self, y: &Self) -> Result<f64, Uncertain> {
        self.output_times_sqrt(y, ScaleKind::Dimensionless)
    }
    /// The f64 value itself when its error bound is within the promise
    /// ([`Filtered::output`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_output(&self, kind: ScaleKind) -> Result<f64, Uncertain> {
        self.output(kind)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_output_times_sqrt(&self, y: &Self, kind: ScaleKind) -> Result<f64, Uncertain> {
        self.output_times_sqrt(y, kind)
    }
    fn approx(&self) -> f64 {
        self.value()
    }
}

/// An `f64` evaluation that left the f64 range (an infinity or a NaN on the
/// way): its signs and roundings are not trusted, and the caller answers in
/// exact arithmetic instead.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct OutOfRange;

impl Field for f64 {
    type Undecided = OutOfRange;
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of(x: f64) -> Self {
        x
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul_add(&self, b: &Self, c: &Self) -> Self {
        f64::mul_add(*self, *b, *c)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn div(&self, o: &Self) -> Self {
        self / o
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of(num: f64, den: f64, rounded: f64) -> Self {
        debug_assert_eq!(rounded.to_bits(), (num / den).to_bits());
        rounded
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn neg(&self) -> Self {
        -self
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sign(&self) -> Result<Ordering, OutOfRange> {
        if self.is_finite() {
            Ok(if *self > 0.0 {
                Ordering::Greater
            } else if *self < 0.0 {
                Ordering::Less
            } else {
                Ordering::Equal
            })
        } else {
            Err(OutOfRange)
        }
    }
    /// The value itself, with a zero written `+0.0`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round(&self) -> Result<f64, OutOfRange> {
        // Tested on the returned value, as `Filtered`'s.
        let v = self + 0.0;
        if v.is_finite() { Ok(v) } else { Err(OutOfRange) }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn round_times_sqrt(&self, y: &Self) -> Result<f64, OutOfRange> {
        Field::round(&(self * y.sqrt()))
    }
    fn approx(&self) -> f64 {
        *self
    }
}

/// A sign or rounding the double-double bound could not decide.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Undecided;

impl<const TRACK: bool> Field for Bounded<TRACK> {
    type Undecided = Undecided;
    forward_ring!(#[inline]);
    #[inline]
    fn div(&self, o: &Self) -> Self {
        Self::div(self, o)
    }
    #[inline]
    fn sign(&self) -> Result<Ordering, Undecided> {
        Self::sign(self).ok_or(Undecided)
    }
    #[inline]
    fn round(&self) -> Result<f64, Undecided> {
        Self::round(self).ok_or(Undecided)
    }
    fn approx(&self) -> f64 {
        Self::approx(self)
    }
}
