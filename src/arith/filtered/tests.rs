//! The bounds of `Filtered` checked against exact rationals.
use super::*;
use crate::rng::Rng;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// Most tests read both bounds (the static one alone is the same code);
/// the random trees check the running one alone too.
type Filtered = super::Filtered<true>;

fn of(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

/// Checks (F1), (F2) and (F3) of a computed value against its exact value
/// (without the static bound, `M` is `0` for an exact zero and `∞` otherwise).
fn holds<const S: bool>(v: &super::Filtered<true, S>, exact: &BigRational, what: &str) {
    if !S {
        assert!(v.m == 0.0 || v.m == 1.0, "{what}: M is not a zero flag: {v:?}");
    }
    if !(v.h.is_finite() && v.lambda.is_finite()) {
        return; // nothing decided
    }
    let error = (of(v.h) - exact).abs();
    if S && v.m.is_finite() && v.m != 0.0 {
        let m = of(v.m * SLACK);
        assert!(exact.abs() <= m, "{what}: |x| > M: {v:?} {}", exact);
        assert!(
            error <= of(v.lambda * U * v.m * SLACK),
            "{what}: |x − h| > λuM: {v:?}"
        );
    }
    if v.e.is_finite() {
        assert!(error <= of(v.e * RUNNING_SLACK), "{what}: |x − h| > E: {v:?}");
    }
    if v.m == 0.0 {
        assert!(
            exact.is_zero() && v.h == 0.0,
            "{what}: M = 0 but not an exact zero"
        );
    }
}

/// A random value of magnitude up to `2^±span`, either sign.
fn draw(rng: &mut Rng, span: f64) -> f64 {
    (rng.unit() - 0.5) * 2f64.powf((rng.unit() - 0.5) * 2.0 * span)
}

/// Random expression trees of sums, fused products, products, quotients
/// and roots, each node's bound and decided sign checked against exact
/// rationals, with values near cancellation (sums of a value and its
/// one-ulp neighbour's negation) and across ranges that reach the floor
/// and overflow; the plain f64 value is unchanged by the bookkeeping.
#[test]
fn the_bounds_hold_and_decided_signs_are_exact_on_random_expression_trees() {
    random_trees::<true>(0xf11e);
}

/// The same with the running bound alone, which decides the signs the two
/// together decide but for a few (the static bound's exact forms of
/// products of inputs).
#[test]
fn the_running_bound_alone_holds_and_decides_on_random_expression_trees() {
    let both = random_trees::<true>(0x5e1f);
    let running = random_trees::<false>(0x5e1f);
    assert!(
        running.0 >= both.0 * 99 / 100,
        "the running bound alone decided {} signs, both {}",
        running.0,
        both.0
    );
}

/// The random trees of the tests above with the static bound (`S`) or
/// without; the signs decided and left close.
fn random_trees<const S: bool>(seed: u64) -> (usize, usize) {
    type F<const S: bool> = super::Filtered<true, S>;
    let mut rng = Rng::new(seed);
    let (mut decided, mut close, mut roots) = (0, 0, 0);
    let (mut answered, mut answered_roots) = (0, 0);
    for case in 0..6_000 {
        let span = [4.0, 60.0, 600.0][case % 3];
        let mut pool: Vec<(F<S>, BigRational, f64)> = (0..4)
            .map(|k| {
                let x = if k == 0 && case % 7 == 0 {
                    0.0
                } else {
                    draw(&mut rng, span)
                };
                (F::<S>::exact(x), of(x), x)
            })
            .collect();
        for step in 0..14 {
            let pick = |rng: &mut Rng, n: usize| (rng.unit() * n as f64) as usize;
            let (a, ea, fa) = pool[pick(&mut rng, pool.len())].clone();
            let (b, eb, fb) = pool[pick(&mut rng, pool.len())].clone();
            let (c, ec, fc) = pool[pick(&mut rng, pool.len())].clone();
            let (v, exact, plain) = match (rng.unit() * 7.0) as u32 {
                0 => (a.add(&b), &ea + &eb, fa + fb),
                1 => (a.sub(&b), &ea - &eb, fa - fb),
                2 => (a.mul(&b), &ea * &eb, fa * fb),
                3 => (a.mul_add(&b, &c), &ea * &eb + &ec, fa.mul_add(fb, fc)),
                4 => {
                    // A near-cancellation: x minus a neighbour of its f64 value.
                    let near = F::<S>::exact(fa.next_up());
                    (a.sub(&near), &ea - of(fa.next_up()), fa - fa.next_up())
                }
                5 => {
                    if eb.is_zero() {
                        continue;
                    }
                    (a.div(&b), &ea / &eb, fa / fb)
                }
                _ => match a.abs_for_test().sqrt() {
                    // (`abs_for_test` leaves an undecided value as it is.)
                    Ok(r) if r.m == 0.0 || r.error_bound().is_finite() => {
                        roots += 1;
                        // The exact root is irrational in general: check
                        // the bound by squaring an enclosure.
                        let x = ea.abs();
                        let h = of(r.h);
                        let e = of(r.error_bound());
                        let (lo, hi) = (&h - &e, &h + &e);
                        if S {
                            assert!(of(r.m * SLACK).pow(2) >= x, "case {case}: root M");
                        }
                        assert!(
                            (lo <= BigRational::zero() || &lo * &lo <= x) && &hi * &hi >= x,
                            "case {case}: root bound {r:?}"
                        );
                        assert_eq!(r.h.to_bits(), a.abs_for_test().h.sqrt().to_bits());
                        continue;
                    }
                    _ => continue,
                },
            };
            assert_eq!(
                v.h.to_bits(),
                plain.to_bits(),
                "case {case} step {step}: h is not f64's"
            );
            holds(&v, &exact, &format!("case {case} step {step}"));
            match v.sign() {
                Ok(s) => {
                    decided += 1;
                    assert_eq!(
                        s,
                        exact.cmp(&BigRational::zero()),
                        "case {case} step {step}: {v:?}"
                    );
                }
                Err(Uncertain::Close) => close += 1,
                Err(Uncertain::Range) => {}
                Err(Uncertain::Inaccurate) => unreachable!("a sign is never inaccurate"),
            }
            if let Ok(answer) = v.output(ScaleKind::Velocity) {
                answered += 1;
                within_promise(answer, &exact, &format!("case {case} step {step}: {v:?}"));
            }
            // x √y of the value and an earlier non-negative one.
            let (w, ew, _) = &pool[pick(&mut rng, pool.len())];
            if ew >= &BigRational::zero()
                && let Ok(answer) = v.output_times_sqrt(w, ScaleKind::Velocity)
            {
                answered_roots += 1;
                // |answer − x√y| ≤ p |x√y| ⟺ (1 − p)² x²y ≤ answer² ≤ (1 + p)² x²y,
                // with the sign of x (or zero).
                let target = &exact * &exact * ew;
                let p = of(PROMISED_RELATIVE_ERROR);
                let one = BigRational::from_integer(1.into());
                let square = of(answer) * of(answer);
                let what = format!("case {case} step {step}: {v:?} √{w:?} = {answer}");
                assert!(square <= (&one + &p).pow(2) * &target, "{what}");
                assert!(square >= (&one - &p).pow(2) * &target, "{what}");
                assert!(answer == 0.0 || (answer > 0.0) == exact.is_positive(), "{what}");
            }
            if v.h.is_finite() && v.error_bound().is_finite() {
                pool.push((v, exact, plain));
            }
        }
    }
    assert!(
        decided > 40_000 && close > 500 && roots > 2_000,
        "{decided} {close} {roots}"
    );
    assert!(
        answered > 30_000 && answered_roots > 5_000,
        "{answered} {answered_roots}"
    );
    (decided, close)
}

/// An output answered in `fast` is within the promised relative error of
/// its exact value (an exact zero answered `+0.0`).
fn within_promise(answer: f64, exact: &BigRational, what: &str) {
    let error = (of(answer) - exact).abs();
    assert!(
        error <= exact.abs() * of(PROMISED_RELATIVE_ERROR),
        "{what}: {answer} is off by more than the promise"
    );
    if exact.is_zero() {
        assert_eq!(answer.to_bits(), 0.0f64.to_bits(), "{what}");
    }
}

impl<const S: bool> super::Filtered<true, S> {
    /// `|x|` of a value whose sign is decided (else itself).
    fn abs_for_test(&self) -> Self {
        match self.sign() {
            Ok(Ordering::Less) => self.neg(),
            _ => *self,
        }
    }
}

#[test]
fn exact_operations_on_inputs_decide_their_signs() {
    let x = Filtered::exact(0.1);
    // A sum of two inputs that cancels exactly is an exact zero.
    assert_eq!(x.sub(&x).sign(), Ok(Ordering::Equal));
    // One fused multiply-add of inputs: its sign is exact however small.
    let (a, b) = (0.1f64, 3.0f64);
    let c = -(a * b);
    let v = Filtered::exact(a).mul_add(&Filtered::exact(b), &Filtered::exact(c));
    assert_eq!(
        v.sign(),
        Ok(if a.mul_add(b, c) > 0.0 {
            Ordering::Greater
        } else {
            Ordering::Less
        })
    );
    // A product with an exact zero is an exact zero.
    let third = Filtered::exact(1.0).div(&Filtered::exact(3.0));
    assert_eq!(Filtered::exact(0.0).mul(&third).sign(), Ok(Ordering::Equal));
    // A rounded value minus its own rounding is not decided here.
    let back = third.mul(&Filtered::exact(3.0)).sub(&Filtered::exact(1.0));
    assert_eq!(back.sign(), Err(Uncertain::Close));
    // Overflow decides nothing.
    let big = Filtered::exact(1e300);
    assert_eq!(big.mul(&big).sign(), Err(Uncertain::Range));
}
