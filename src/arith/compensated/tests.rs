//! The invariants of `Compensated` checked against exact rationals.
use super::*;
use crate::rng::Rng;
use num_rational::BigRational;
use num_traits::Signed;

fn of(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

/// On every `M` the rules can form (0, at least [`FLOOR`], ∞, a NaN),
/// `product_magnitude` is the floored product it stands for: zero when a
/// factor is zero, at least [`FLOOR`] and at least `M_x M_y` otherwise,
/// and exactly `M_x M_y` where that product is itself at least [`FLOOR`].
#[test]
fn product_magnitude_is_the_floored_product_or_an_exact_zero() {
    let mut ms = vec![
        0.0,
        FLOOR,
        f64::INFINITY,
        f64::NAN,
        1.0,
        2f64.powi(-450),
        2f64.powi(600),
    ];
    let mut rng = Rng::new(0x9a9);
    for _ in 0..200 {
        ms.push(FLOOR * 2f64.powf(rng.unit() * 1800.0) * (1.0 + rng.unit()));
    }
    for &mx in &ms {
        for &my in &ms {
            let p = product_magnitude(mx, my);
            // The form it replaces (which scaled min(M_x, M_y) by 2⁹⁰⁰),
            // bit for bit, NaNs included.
            let before = max(mx * my, min(FLOOR, min(mx, my) * 2f64.powi(900)));
            assert_eq!(p.to_bits(), before.to_bits(), "{mx:e} {my:e}");
            let exact = mx * my;
            if mx.is_nan() || my.is_nan() {
                // An overflowed M: nothing is certified from it.
                continue;
            } else if mx == 0.0 || my == 0.0 {
                assert_eq!(p.to_bits(), 0f64.to_bits(), "{mx:e} {my:e}");
            } else if exact >= FLOOR {
                assert_eq!(p.to_bits(), exact.to_bits(), "{mx:e} {my:e}");
            } else {
                assert_eq!(p, FLOOR, "{mx:e} {my:e}");
            }
        }
    }
}

/// A quotient too small to certify decides nothing, alone or in later
/// operations, yet still approximates its value for a refusal's payload
/// (it was a NaN there).
#[test]
fn an_uncertified_quotient_decides_nothing_but_approximates_its_value() {
    let q = Compensated::exact(1e-300).div(&Compensated::exact(1e300));
    assert_eq!(q.approx(), 1e-300 / 1e300);
    // The operands' compensated parts count: ((1 + 2⁻⁶⁰) − 1) / 2¹⁰⁰ is
    // 2⁻¹⁶⁰, though the plain parts' quotient is 0.
    let one = Compensated::exact(1.0);
    let tiny = one.add(&Compensated::exact(2f64.powi(-60))).sub(&one);
    let r = tiny.div(&Compensated::exact(2f64.powi(100)));
    assert_eq!(r.approx(), 2f64.powi(-160));
    assert!(r.sign().is_err());
    assert!(q.sign().is_err() && q.round().is_err());
    let sum = q.add(&Compensated::exact(1.0));
    assert!(sum.sign().is_err() && sum.round().is_err());
    assert!(q.mul(&Compensated::exact(2.0)).sign().is_err());
}

/// Checks (I1)–(I3) of a computed value against its exact value.
fn holds(v: &Compensated, exact: &BigRational, what: &str) {
    if !(v.h.is_finite() && v.l.is_finite() && v.m.is_finite()) {
        return; // nothing certified
    }
    let m = of(v.m * M_GROWTH);
    assert!(exact.abs() <= m, "{what}: |x| > M: {v:?}");
    assert!(
        of(v.l).abs() <= of(v.lambda * U * v.m * M_GROWTH),
        "{what}: |l| > λuM: {v:?}"
    );
    let error = (of(v.h) + of(v.l) - exact).abs();
    let eps = v.lambda * v.lambda;
    assert!(
        error <= of(eps * U2 * v.m * M_GROWTH),
        "{what}: error past λ²u²M: {v:?}"
    );
}

/// A random value of magnitude up to `2^±span`, either sign.
fn draw(rng: &mut Rng, span: f64) -> f64 {
    (rng.unit() - 0.5) * 2f64.powf((rng.unit() - 0.5) * 2.0 * span)
}

/// Random expression trees of sums, products and quotients, each node's
/// invariants checked against exact rationals, across exponent ranges that
/// reach the floor and overflow.
#[test]
fn the_invariants_hold_on_random_expression_trees() {
    let mut rng = Rng::new(0x5eed);
    let (mut certified, mut quotients, mut roots) = (0, 0, 0);
    for case in 0..4_000 {
        let span = [8.0, 120.0, 600.0][case % 3];
        let mut pool: Vec<(Compensated, BigRational)> = (0..4)
            .map(|k| {
                let x = if k == 0 && case % 7 == 0 {
                    0.0
                } else {
                    draw(&mut rng, span)
                };
                (Compensated::exact(x), of(x))
            })
            .collect();
        for step in 0..12 {
            let i = (rng.unit() * pool.len() as f64) as usize;
            let j = (rng.unit() * pool.len() as f64) as usize;
            let (a, ea) = pool[i].clone();
            let (b, eb) = pool[j].clone();
            let (v, exact) = match (rng.unit() * 5.0) as u32 {
                0 => (a.add(&b), &ea + &eb),
                1 => (a.sub(&b), &ea - &eb),
                2 => (a.mul(&b), &ea * &eb),
                3 => {
                    // The root of |a| (its sign taken from the exact value,
                    // as the model decides it before a root).
                    let radicand = if ea < of(0.0) { a.neg() } else { a };
                    if let Ok(r) = radicand.sqrt() {
                        roots += 1;
                        root_holds(&r, &ea.abs(), &format!("case {case} step {step}"));
                    }
                    continue;
                }
                _ => {
                    if eb == of(0.0) {
                        continue;
                    }
                    let q = a.div(&b);
                    if q.h.is_finite() {
                        quotients += 1;
                    }
                    (q, &ea / &eb)
                }
            };
            if !v.h.is_finite() || !v.m.is_finite() {
                continue;
            }
            holds(&v, &exact, &format!("case {case} step {step}"));
            if let Ok(r) = v.round() {
                certified += 1;
                assert_eq!(
                    r,
                    crate::arith::fraction::round_rational(&exact),
                    "case {case} step {step}"
                );
            }
            if let Ok(s) = v.sign() {
                assert_eq!(s, exact.cmp(&of(0.0)), "case {case} step {step}");
            }
            pool.push((v, exact));
        }
    }
    assert!(
        certified > 15_000 && quotients > 4_000 && roots > 2_000,
        "{certified} {quotients} {roots}"
    );
}

/// (I1)–(I3) of a root `r` of the exact `x ≥ 0` (irrational in general:
/// checked by squaring an enclosure), and its rounding, where certified,
/// the correctly rounded root (`x` between the squares of the midpoints
/// around it).
fn root_holds(r: &Compensated, x: &BigRational, what: &str) {
    assert!(
        r.h.is_finite() && r.l.is_finite() && r.m.is_finite(),
        "{what}: {r:?}"
    );
    assert!(of(r.m * M_GROWTH).pow(2) >= *x, "{what}: √x > M: {r:?}");
    assert!(
        of(r.l).abs() <= of(r.lambda * U * r.m * M_GROWTH),
        "{what}: |l| > λuM: {r:?}"
    );
    let value = of(r.h) + of(r.l);
    let bound = of(r.lambda * r.lambda * U2 * r.m * M_GROWTH);
    let (lo, hi) = (&value - &bound, &value + &bound);
    assert!(
        (lo <= of(0.0) || &lo * &lo <= *x) && &hi * &hi >= *x,
        "{what}: √x outside h + l ± λ²u²M: {r:?}"
    );
    if let Ok(v) = r.round() {
        if v == 0.0 {
            assert_eq!(*x, of(0.0), "{what}: √x rounded to zero: {r:?}");
            return;
        }
        let half = |w: f64| (of(v) + of(w)) / BigRational::from_integer(2.into());
        let (below, above) = (half(v.next_down()), half(v.next_up()));
        assert!(
            &below * &below <= *x && &above * &above >= *x,
            "{what}: {v} is not √x rounded: {r:?}"
        );
    }
}

#[test]
fn roots_of_exact_and_rounded_values_are_certified_or_left_to_double_double() {
    // √4 is exact, √2 correctly rounded.
    assert_eq!(Compensated::exact(4.0).sqrt().unwrap().round(), Ok(2.0));
    assert_eq!(Compensated::exact(2.0).sqrt().unwrap().round(), Ok(2f64.sqrt()));
    assert_eq!(Compensated::exact(0.0).sqrt().unwrap().m, 0.0);
    // A sum of squares (a slip's length), checked against the enclosure.
    let (a, b) = (0.3, 0.7);
    let square = Compensated::exact(a)
        .mul(&Compensated::exact(a))
        .add(&Compensated::exact(b).mul(&Compensated::exact(b)));
    let x = of(a) * of(a) + of(b) * of(b);
    root_holds(&square.sqrt().unwrap(), &x, "√(a² + b²)");
    // A radicand cancelled far below its magnitude is not certified here.
    let third = Compensated::exact(1.0).div(&Compensated::exact(3.0));
    let cancelled = third
        .mul(&Compensated::exact(3.0))
        .sub(&Compensated::exact(1.0 - f64::EPSILON));
    assert_eq!(cancelled.sqrt(), Err(Unsettled::Root));
    // Nor a non-positive or subnormal approximation.
    let tiny = Compensated::exact(f64::from_bits(1 << 20));
    assert_eq!(tiny.sqrt(), Err(Unsettled::Root));
}

#[test]
fn inputs_are_exact_and_operations_are_not_assumed_exact() {
    let a = Compensated::exact(0.1);
    assert_eq!(a.round(), Ok(0.1));
    assert_eq!(Compensated::exact(0.0).sign(), Ok(Ordering::Equal));
    assert_eq!(Compensated::exact(-0.0).round(), Ok(0.0));
    // An exact cancellation is not decided here (the tracked stage decides it).
    let s = a.add(&Compensated::exact(0.2));
    assert_eq!(s.sub(&s).sign(), Err(Unsettled::Close));
    // 0.1 + 0.2 is exactly halfway between two doubles: a tie is never certified.
    assert_eq!(s.round(), Err(Unsettled::Close));
    let t = a.add(&Compensated::exact(0.7));
    assert_eq!(t.round(), Ok(0.1 + 0.7));
    let third = Compensated::exact(1.0).div(&Compensated::exact(3.0));
    assert_eq!(third.round(), Ok(1.0 / 3.0));
    // A product with a zero input is exactly zero (a sticking V_ct = −0 · v_ct).
    let zero = Compensated::exact(0.0).mul(&third);
    assert_eq!(zero.m, 0.0);
    assert_eq!((zero.round(), zero.sign()), (Ok(0.0), Ok(Ordering::Equal)));
    assert_eq!(zero.add(&third).round(), Ok(1.0 / 3.0));
    assert_eq!(zero.div(&third).round(), Ok(0.0));
}

#[test]
fn overflow_and_tiny_quotients_certify_nothing() {
    let big = Compensated::exact(1e300);
    assert_eq!(big.mul(&big).round(), Err(Unsettled::Range));
    assert_eq!(big.mul(&big).sign(), Err(Unsettled::Range));
    let q = Compensated::exact(1e-300).div(&Compensated::exact(1e300));
    assert_eq!(q.round(), Err(Unsettled::Range));
    let nearly_zero = Compensated::exact(1.0)
        .div(&Compensated::exact(3.0))
        .mul(&Compensated::exact(3.0))
        .sub(&Compensated::exact(1.0));
    assert_eq!(
        Compensated::exact(1.0).div(&nearly_zero).round(),
        Err(Unsettled::Range)
    );
    // Subnormal dividend and divisor: the remainder underflows, and the
    // answer is either certified right or not certified.
    let tiny = f64::from_bits(1 << 14); // 2⁻¹⁰⁶⁰
    let (x, y) = (3.0 * tiny, 7.0 * tiny);
    let q = Compensated::exact(x)
        .mul(&Compensated::exact(1.1))
        .div(&Compensated::exact(y));
    let exact = of(x) * of(1.1) / of(y);
    if let Ok(r) = q.round() {
        assert_eq!(r, crate::arith::fraction::round_rational(&exact));
    }
    holds(&q, &exact, "subnormal quotient");
    // A divisor near the top of the range has a subnormal reciprocal.
    let q = Compensated::exact(3.0e300).div(&Compensated::exact(1.5e308));
    assert_eq!(q.round(), Err(Unsettled::Range));
    let q = Compensated::exact(3.0e300).div(&Compensated::exact(1.5e300));
    assert_eq!(q.round(), Ok(2.0));
}
