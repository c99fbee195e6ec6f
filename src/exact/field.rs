//! The arithmetic the exact model is written in, implemented twice: by
//! [`Bounded`] double-doubles (fast, may be undecided) and by big rationals
//! (slow, always decided).

use std::cmp::Ordering;

use num_bigint::BigUint;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::bounded::Bounded;

/// A number the exact model can be evaluated in.
pub(crate) trait Field: Clone {
    /// An f64 input, exactly.
    fn of(x: f64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    /// Division; the model only divides by values whose sign it has decided non-zero.
    fn div(&self, o: &Self) -> Self;
    fn neg(&self) -> Self;
    /// The sign of the exact value, `None` if undecided.
    fn sign(&self) -> Option<Ordering>;
    /// The exact value correctly rounded to f64 (`±∞` beyond the range), `None` if undecided.
    fn round(&self) -> Option<f64>;
    /// A nearby f64 for diagnostics (error payloads), never for answers.
    fn approx(&self) -> f64;
}

impl Field for Bounded {
    #[inline]
    fn of(x: f64) -> Self {
        Bounded::exact(x)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Bounded::add(self, o)
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Bounded::sub(self, o)
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        Bounded::mul(self, o)
    }
    #[inline]
    fn div(&self, o: &Self) -> Self {
        Bounded::div(self, o)
    }
    #[inline]
    fn neg(&self) -> Self {
        Bounded::neg(self)
    }
    #[inline]
    fn sign(&self) -> Option<Ordering> {
        Bounded::sign(self)
    }
    #[inline]
    fn round(&self) -> Option<f64> {
        Bounded::round(self)
    }
    fn approx(&self) -> f64 {
        Bounded::approx(self)
    }
}

impl Field for BigRational {
    fn of(x: f64) -> Self {
        // Every finite f64 is a dyadic rational; the model only sees finite inputs.
        BigRational::from_float(x).unwrap_or_else(BigRational::zero)
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn div(&self, o: &Self) -> Self {
        if o.is_zero() {
            // Unreachable by construction (see the trait); never panic in a server.
            return BigRational::zero();
        }
        self / o
    }
    fn neg(&self) -> Self {
        -self
    }
    fn sign(&self) -> Option<Ordering> {
        Some(self.cmp(&BigRational::zero()))
    }
    fn round(&self) -> Option<f64> {
        Some(round_rational(self))
    }
    fn approx(&self) -> f64 {
        round_rational(self)
    }
}

/// `2^k` for `k ∈ [−1074, 1023]`, exactly.
fn pow2(k: i64) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// The rational correctly rounded to the nearest f64 (ties to even), `±∞` when
/// it rounds beyond the largest finite double, `+0.0` for zero.
pub(crate) fn round_rational(x: &BigRational) -> f64 {
    if x.is_zero() {
        return 0.0;
    }
    let negative = x.is_negative();
    let n: BigUint = x.numer().magnitude().clone();
    let d: BigUint = x.denom().magnitude().clone();
    // Find k with 2^52 ≤ n / (d 2^k) < 2^53, or k = −1074 for subnormals.
    let mut k = n.bits() as i64 - d.bits() as i64 - 53;
    let (mut q, mut r, mut den);
    loop {
        k = k.max(-1074);
        let (num, dd) = if k >= 0 {
            (n.clone(), &d << (k as u64))
        } else {
            (&n << ((-k) as u64), d.clone())
        };
        q = &num / &dd;
        r = &num - &q * &dd;
        den = dd;
        if q.bits() > 53 {
            k += 1;
        } else if q.bits() < 53 && k > -1074 {
            k -= 1;
        } else {
            break;
        }
    }
    let twice = &r << 1u32;
    let odd = q.bit(0);
    if twice > den || (twice == den && odd) {
        q += BigUint::one();
    }
    if q.bits() > 53 {
        q >>= 1u32;
        k += 1;
    }
    let magnitude = if k > 971 {
        f64::INFINITY
    } else {
        let digits = q.iter_u64_digits().next().unwrap_or(0) as f64;
        digits * pow2(k)
    };
    if negative { -magnitude } else { magnitude }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    fn int(x: i64) -> BigInt {
        BigInt::from(x)
    }

    fn ratio(a: i64, b: i64) -> BigRational {
        BigRational::new(int(a), int(b))
    }

    #[test]
    fn conversion_is_correctly_rounded() {
        for (a, b) in [
            (1, 3),
            (2, 3),
            (-7, 10),
            (1, 10),
            (123_456_789, 1000),
            (1, 1 << 40),
        ] {
            assert_eq!(round_rational(&ratio(a, b)), a as f64 / b as f64, "{a}/{b}");
        }
        for x in [0.1, -1e300, 1e-300, 5e-324, f64::MAX, f64::MIN_POSITIVE, 2.5e-310] {
            assert_eq!(round_rational(&BigRational::from_float(x).unwrap()), x);
        }
    }

    #[test]
    fn ties_go_to_even_and_overflow_and_underflow_round_as_ieee_does() {
        let one = BigRational::one();
        let half_ulp = BigRational::from_float(f64::EPSILON / 2.0).unwrap();
        assert_eq!(round_rational(&(&one + &half_ulp)), 1.0);
        let three_halves = BigRational::from_float(1.0 + f64::EPSILON).unwrap() + &half_ulp;
        assert_eq!(round_rational(&three_halves), 1.0 + 2.0 * f64::EPSILON);
        let max = BigRational::from_float(f64::MAX).unwrap();
        let half_max_ulp = BigRational::from_float(2f64.powi(970)).unwrap();
        assert_eq!(round_rational(&(&max + &half_max_ulp)), f64::INFINITY);
        assert_eq!(
            round_rational(&(&max + &half_max_ulp - BigRational::from_float(1.0).unwrap())),
            f64::MAX
        );
        let smallest = BigRational::from_float(5e-324).unwrap();
        assert_eq!(round_rational(&(&smallest / int(2))), 0.0);
        assert_eq!(round_rational(&(&smallest * ratio(3, 4))), 5e-324);
        assert_eq!(round_rational(&(&smallest * ratio(3, 2))), 1e-323);
    }
}
