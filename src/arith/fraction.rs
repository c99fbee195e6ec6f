//! Exact fractions (`Fraction`), the rational stage's numbers, and the
//! correct rounding of a quotient of big integers to an f64.

use std::cmp::Ordering;
use std::convert::Infallible;

use num_bigint::{BigInt, BigUint};
#[cfg(test)]
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::field::Field;

/// An exact rational `num / den` (`den > 0`), kept unreduced but for common
/// factors of two: every input is dyadic, so dividing out powers of two keeps
/// most values small, and no gcd is ever computed (normalising by gcd after
/// every operation, as `BigRational` does, is far dearer here).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fraction {
    num: BigInt,
    den: BigInt,
}

impl Fraction {
    /// An integer.
    pub(super) fn integer(n: &BigInt) -> Self {
        Fraction::new(n.clone(), BigInt::one())
    }

    /// `n / 2^k` (`k` of either sign).
    pub(super) fn dyadic(n: BigInt, k: i64) -> Self {
        if k >= 0 {
            Fraction::new(n, BigInt::one() << (k as u64))
        } else {
            Fraction::new(n << ((-k) as u64), BigInt::one())
        }
    }

    /// `num / den` (`den > 0`).
    pub(super) fn from_parts(num: BigInt, den: BigInt) -> Self {
        Fraction::new(num, den)
    }

    /// The numerator and the (positive) denominator.
    pub(super) fn parts(&self) -> (&BigInt, &BigInt) {
        (&self.num, &self.den)
    }

    /// The fraction in lowest terms once its parts pass `bits` bits together
    /// (the last stage's values would otherwise grow with every quotient).
    pub(super) fn reduced(self, bits: u64) -> Self {
        if self.num.bits() + self.den.bits() <= bits {
            return self;
        }
        let g = num_integer::Integer::gcd(&self.num, &self.den);
        if g.is_one() {
            self
        } else {
            Fraction {
                num: &self.num / &g,
                den: &self.den / &g,
            }
        }
    }

    /// `log₂ |x|` within one (`x ≠ 0`): the difference of the bit lengths.
    pub(super) fn log2_estimate(&self) -> i64 {
        self.num.bits() as i64 - self.den.bits() as i64
    }

    fn new(num: BigInt, den: BigInt) -> Self {
        if num.is_zero() {
            return Fraction {
                num,
                den: BigInt::one(),
            };
        }
        let twos = num
            .trailing_zeros()
            .unwrap_or(0)
            .min(den.trailing_zeros().unwrap_or(0));
        if twos == 0 {
            Fraction { num, den }
        } else {
            Fraction {
                num: num >> twos,
                den: den >> twos,
            }
        }
    }
}

impl Field for Fraction {
    type Undecided = Infallible;
    fn of(x: f64) -> Self {
        // Every finite f64 is m·2^k; the model only sees finite inputs.
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        let (mantissa, k) = if exponent == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1u64 << 52), exponent - 1075)
        };
        let signed = if x.is_sign_negative() {
            -BigInt::from(mantissa)
        } else {
            BigInt::from(mantissa)
        };
        if !x.is_finite() {
            return Fraction::new(BigInt::zero(), BigInt::one());
        }
        if k >= 0 {
            Fraction::new(signed << (k as u64), BigInt::one())
        } else {
            Fraction::new(signed, BigInt::one() << ((-k) as u64))
        }
    }
    fn add(&self, o: &Self) -> Self {
        if self.den == o.den {
            Fraction::new(&self.num + &o.num, self.den.clone())
        } else {
            Fraction::new(&self.num * &o.den + &o.num * &self.den, &self.den * &o.den)
        }
    }
    fn sub(&self, o: &Self) -> Self {
        self.add(&o.neg())
    }
    fn mul(&self, o: &Self) -> Self {
        Fraction::new(&self.num * &o.num, &self.den * &o.den)
    }
    fn div(&self, o: &Self) -> Self {
        if o.num.is_zero() {
            // Unreachable by construction (see the trait); never panic in a server.
            return Fraction::new(BigInt::zero(), BigInt::one());
        }
        let (num, den) = (&self.num * &o.den, &self.den * &o.num);
        if den.is_negative() {
            Fraction::new(-num, -den)
        } else {
            Fraction::new(num, den)
        }
    }
    fn neg(&self) -> Self {
        Fraction {
            num: -&self.num,
            den: self.den.clone(),
        }
    }
    fn sign(&self) -> Result<Ordering, Infallible> {
        Ok(self.num.sign().cmp(&num_bigint::Sign::NoSign))
    }
    fn round(&self) -> Result<f64, Infallible> {
        Ok(round_quotient(&self.num, &self.den))
    }
    fn approx(&self) -> f64 {
        round_quotient(&self.num, &self.den)
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
#[cfg(test)]
pub(crate) fn round_rational(x: &BigRational) -> f64 {
    round_quotient(x.numer(), x.denom())
}

/// `num / den` (`den ≠ 0`, any common factors) correctly rounded to the nearest
/// f64 (ties to even), `±∞` beyond the largest finite double, `+0.0` for zero.
pub(crate) fn round_quotient(num: &BigInt, den: &BigInt) -> f64 {
    if num.is_zero() {
        return 0.0;
    }
    let negative = num.is_negative() != den.is_negative();
    let n: BigUint = num.magnitude().clone();
    let d: BigUint = den.magnitude().clone();
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

    fn as_ratio(f: &Fraction) -> BigRational {
        BigRational::new(f.num.clone(), f.den.clone())
    }

    #[test]
    fn fractions_agree_with_reduced_rationals() {
        let values = [
            0.1,
            -0.93,
            3.0,
            1e-300,
            -2.5e300,
            5e-324,
            0.0,
            7.0 / 3.0,
            -1.0,
            1e15 + 0.5,
        ];
        let of = |x: f64| BigRational::from_float(x).unwrap();
        for &a in &values {
            let fa = Fraction::of(a);
            assert_eq!(as_ratio(&fa), of(a), "{a}");
            for &b in &values {
                let fb = Fraction::of(b);
                assert_eq!(as_ratio(&fa.add(&fb)), of(a) + of(b), "{a} + {b}");
                assert_eq!(as_ratio(&fa.sub(&fb)), of(a) - of(b), "{a} - {b}");
                assert_eq!(as_ratio(&fa.mul(&fb)), of(a) * of(b), "{a} * {b}");
                if b != 0.0 {
                    let q = fa.div(&fb);
                    assert!(q.den.is_positive());
                    assert_eq!(as_ratio(&q), of(a) / of(b), "{a} / {b}");
                    assert_eq!(q.round(), Ok(round_rational(&(of(a) / of(b)))), "{a} / {b}");
                }
                assert_eq!(
                    fa.sub(&fb).sign(),
                    Ok(if a == b { Ordering::Equal } else { a.total_cmp(&b) })
                );
            }
        }
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
