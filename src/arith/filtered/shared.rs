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
    ACCEPTED_RELATIVE_BOUND, Filtered, LAMBDA_MAX, SLACK, U, floored, max, once_rounded, product_magnitude,
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

/// [`once_rounded`] of each lane's value, the largest.
#[cfg_attr(not(debug_assertions), inline(always))]
fn largest_once_rounded<const L: usize>(h: &[f64; L]) -> f64 {
    largest(lanewise::<L>(|i| once_rounded(h[i])))
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
                largest_once_rounded(&h)
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
                    once_rounded(h[i])
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
        let scales = lane_scales::<L>(kind);
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
        let scales = lane_scales::<L>(kind);
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

#[cfg(test)]
mod tests {
    use super::super::super::Field;
    use super::*;
    use crate::rng::Rng;

    type One = Filtered<false, true>;

    /// Four lanes of inputs: nearby values, values of unrelated magnitudes
    /// and signs, or either with exact zeros among them.
    fn inputs(rng: &mut Rng) -> [f64; 4] {
        let base = rng.sign() * rng.log_uniform(-3.0, 3.0);
        let close = rng.chance(0.5);
        let zeros = rng.chance(0.2);
        std::array::from_fn(|_| {
            if zeros && rng.chance(0.3) {
                0.0
            } else if close {
                base * (1.0 + rng.range(-1e-3, 1e-3))
            } else {
                rng.sign() * rng.log_uniform(-3.0, 3.0)
            }
        })
    }

    /// Along random chains of every operation, each lane's value is its own
    /// point's (`Filtered`, the plane's first field) bit for bit, with the
    /// same `λ`, and the shared `M` is at least its own; a sign the lanes
    /// decide, each point decides alike, and an output (`x` or `x √y`) the
    /// lanes accept, each point accepts.
    #[test]
    fn each_lane_is_its_own_value_within_the_shared_bound() {
        let mut rng = Rng::new(41);
        let (mut signs, mut outputs, mut roots) = (0, 0, 0);
        for _ in 0..3000 {
            let mut shared: Vec<SharedLanes<4>> = Vec::new();
            let mut alone: Vec<[One; 4]> = Vec::new();
            for _ in 0..3 {
                let x = inputs(&mut rng);
                shared.push(SharedLanes::of_lanes(|i| x[i]));
                alone.push(x.map(One::exact));
            }
            let (num, den) = (
                inputs(&mut rng),
                inputs(&mut rng).map(|d| if d == 0.0 { 1.0 } else { d }),
            );
            shared.push(SharedLanes::quotient_of_lanes(|i| {
                (num[i], den[i], num[i] / den[i])
            }));
            alone.push(std::array::from_fn(|i| One::quotient_of(num[i], num[i] / den[i])));
            let c = rng.log_uniform(-1.0, 1.0);
            shared.push(SharedLanes::of(c));
            alone.push([One::exact(c); 4]);
            for _ in 0..12 {
                let [a, b, c] = [0; 3].map(|_| (rng.next_u64() % shared.len() as u64) as usize);
                let op = rng.next_u64() % 5;
                let s = match op {
                    0 => shared[a].add(&shared[b]),
                    1 => shared[a].sub(&shared[b]),
                    2 => shared[a].mul(&shared[b]),
                    3 => shared[a].mul_add(&shared[b], &shared[c]),
                    _ => shared[a].div(&shared[b]),
                };
                let one: [One; 4] = std::array::from_fn(|i| {
                    let (x, y, z) = (&alone[a][i], &alone[b][i], &alone[c][i]);
                    match op {
                        0 => x.add(y),
                        1 => x.sub(y),
                        2 => x.mul(y),
                        3 => x.mul_add(y, z),
                        _ => x.div(y),
                    }
                });
                for (i, point) in one.iter().enumerate() {
                    let (h, m, lambda, _) = point.parts();
                    assert_eq!(s.h[i].to_bits(), h.to_bits(), "{s:?} {point:?}");
                    assert_eq!(s.lambda, lambda);
                    // (A NaN `M` decides nothing.)
                    assert_ne!(
                        m.partial_cmp(&s.m),
                        Some(Ordering::Greater),
                        "lane {i}: {s:?} {point:?}"
                    );
                }
                if let Ok(sign) = s.sign() {
                    signs += 1;
                    for point in &one {
                        assert_eq!(Field::sign(point), Ok(sign), "{s:?} {point:?}");
                    }
                }
                let mut values = [0.0; 4];
                let scale = rng.log_uniform(-3.0, 3.0);
                let scales = crate::accuracy::ErrorScales {
                    velocity: scale,
                    ..Default::default()
                };
                crate::arith::measure_lanes_against(&[scales; 4]);
                if s.lanes_output(ScaleKind::Velocity, &mut values).is_ok() {
                    outputs += 1;
                    for (point, v) in one.iter().zip(values) {
                        assert_eq!(point.output_against(scale).map(f64::to_bits), Ok(v.to_bits()));
                    }
                }
                if shared[b].sign() == Ok(Ordering::Greater)
                    && s.lanes_output_times_sqrt(&shared[b], ScaleKind::Velocity, &mut values)
                        .is_ok()
                {
                    roots += 1;
                    for ((point, y), v) in one.iter().zip(&alone[b]).zip(values) {
                        let single = point.output_times_sqrt_against(y, scale);
                        assert_eq!(single.map(f64::to_bits), Ok(v.to_bits()));
                    }
                }
                shared.push(s);
                alone.push(one);
            }
        }
        // Most chains decide most signs and outputs in lanes.
        assert!(
            signs > 10_000 && outputs > 10_000 && roots > 1_000,
            "{signs} signs, {outputs} outputs, {roots} roots"
        );
    }
}
