//! Several points of a sweep evaluated together: [`Lanes`], `fast`'s first
//! field for `L` points at once ([`Filtered`] with the running bound alone
//! in space, with the static bound alone for the torsional case), each
//! operation applied lane by lane (straight-line code over arrays, which the
//! compiler vectorises across the lanes), each lane keeping its own bounds.
//! (One and two laminae evaluate their lanes with one static bound for all,
//! `super::SharedLanes`.)
//!
//! The model runs in it unchanged. A decision is taken where every lane
//! decides it the same way; where one lane cannot decide it, or two lanes
//! decide it differently, the whole evaluation stops ([`Diverged`]) and
//! the caller solves the points one by one. So every lane takes the path its
//! point takes alone, forms the same values by the same operations (each
//! [`Filtered`] rule, applied to the lane's parts), and passes the same
//! output tests: a point answered in lanes is its single solve, bit for bit.

use std::cell::Cell;
use std::cmp::Ordering;

use super::filtered::Filtered;
use crate::accuracy::{ErrorScales, ScaleKind};

/// The most lanes a [`Lanes`] value holds (the scales' storage).
pub(crate) const MAX_LANES: usize = 4;

/// `L` points' values of one expression in `Filtered<RUNNING, STATIC>`
/// (by default `fast`'s first field for the plane, `crate::impact`'s
/// `TightFast`; in space its `LooseFast`), kept part by part: the values
/// `h`, the magnitudes `M`, the running bounds `E` (zeros without
/// `RUNNING`, which no rule reads), and `λ`, which depends on the path alone
/// (`filtered`'s module documentation), so one for all lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lanes<const L: usize, const RUNNING: bool = false, const STATIC: bool = true> {
    h: [f64; L],
    m: [f64; L],
    e: [f64; L],
    lambda: f64,
}

/// Why an evaluation in lanes stopped: a lane could not decide, or the lanes
/// decided differently, or an output was asked of all lanes at once. The
/// caller solves the points one by one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Diverged;

thread_local! {
    /// The lanes' scales ([`ErrorScales::by_kind`]) kind by kind, lane by
    /// lane, set by [`measure_lanes_against`] before an evaluation in lanes.
    static LANE_SCALES: [Cell<[f64; MAX_LANES]>; 6] =
        const { [const { Cell::new([0.0; MAX_LANES]) }; 6] };
}

/// Sets the scales each lane's outputs are measured against in the next
/// evaluation in lanes on this thread: lane `i`'s are `scales[i]` (at most
/// [`MAX_LANES`]), its point's own, as a single solve measures them.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn measure_lanes_against(scales: &[ErrorScales]) {
    let mut by_kind = [[0.0; MAX_LANES]; 6];
    for (lane, s) in scales.iter().enumerate() {
        for (kind, scale) in s.by_kind().into_iter().enumerate() {
            by_kind[kind][lane] = scale;
        }
    }
    LANE_SCALES.with(|kinds| {
        for (cell, scales) in kinds.iter().zip(by_kind) {
            cell.set(scales);
        }
    });
}

/// The scales of outputs of `kind` of the first `L` lanes, that
/// [`measure_lanes_against`] set.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn lane_scales<const L: usize>(kind: ScaleKind) -> [f64; L] {
    const { assert!(L <= MAX_LANES, "more lanes than scales") };
    let scales = LANE_SCALES.with(|kinds| kinds[kind as usize].get());
    std::array::from_fn(|i| scales[i])
}

impl<const L: usize, const RUNNING: bool, const STATIC: bool> Lanes<L, RUNNING, STATIC> {
    /// Lane `i` as a value of its own.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lane(&self, i: usize) -> Filtered<RUNNING, STATIC> {
        Filtered::of_parts(self.h[i], self.m[i], self.lambda, self.e[i])
    }
}

/// Applies a [`Filtered`] rule lane by lane, `$i` the lane, in an explicit
/// loop (a closure passed down might be compiled apart from the copy that
/// runs, `crate::kernels`). Every lane's `λ` is the same: the rule's, of
/// the operands' one `λ` each.
macro_rules! lanewise {
    (|$i:ident| $rule:expr) => {{
        let mut out = Lanes {
            h: [0.0; L],
            m: [0.0; L],
            e: [0.0; L],
            lambda: 0.0,
        };
        for $i in 0..L {
            let (h, m, lambda, e) = $rule.parts();
            out.h[$i] = h;
            out.m[$i] = m;
            out.e[$i] = e;
            out.lambda = lambda;
        }
        out
    }};
}

impl<const L: usize, const RUNNING: bool, const STATIC: bool> super::Field for Lanes<L, RUNNING, STATIC> {
    type Undecided = Diverged;

    const LANES: usize = L;

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of(x: f64) -> Self {
        lanewise!(|_i| Filtered::<RUNNING, STATIC>::exact(x))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of_lanes(x: impl Fn(usize) -> f64) -> Self {
        lanewise!(|i| Filtered::<RUNNING, STATIC>::exact(x(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of_lanes(q: impl Fn(usize) -> (f64, f64, f64)) -> Self {
        lanewise!(|i| {
            let (num, den, rounded) = q(i);
            <Filtered<RUNNING, STATIC> as super::Field>::quotient_of(num, den, rounded)
        })
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(&self, o: &Self) -> Self {
        lanewise!(|i| self.lane(i).add(&o.lane(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(&self, o: &Self) -> Self {
        lanewise!(|i| self.lane(i).sub(&o.lane(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(&self, o: &Self) -> Self {
        lanewise!(|i| self.lane(i).mul(&o.lane(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul_add(&self, b: &Self, c: &Self) -> Self {
        lanewise!(|i| self.lane(i).mul_add(&b.lane(i), &c.lane(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn div(&self, o: &Self) -> Self {
        lanewise!(|i| self.lane(i).div(&o.lane(i)))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn quotient_of(num: f64, den: f64, rounded: f64) -> Self {
        lanewise!(|_i| <Filtered<RUNNING, STATIC> as super::Field>::quotient_of(num, den, rounded))
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn neg(&self) -> Self {
        lanewise!(|i| self.lane(i).neg())
    }
    /// The sign every lane decides, or [`Diverged`]: the lanes' common path
    /// ([`Filtered::clear_sign`]) tested together, the rest lane by lane.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sign(&self) -> Result<Ordering, Diverged> {
        let (mut clear, mut positive, mut negative) = (true, true, true);
        for i in 0..L {
            let (c, p) = self.lane(i).clear_sign();
            clear &= c;
            positive &= p;
            negative &= !p;
        }
        if clear && positive {
            return Ok(Ordering::Greater);
        }
        if clear && negative {
            return Ok(Ordering::Less);
        }
        let first = self.lane(0).sign();
        let mut same = true;
        for i in 1..L {
            same &= self.lane(i).sign() == first;
        }
        match first {
            Ok(sign) if same => Ok(sign),
            _ => Err(Diverged),
        }
    }
    no_one_value!();
    /// Every lane's output, each tested against its lane's scale as its
    /// single solve tests it ([`Filtered::output_test`]), together.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output(&self, kind: ScaleKind, out: &mut [f64]) -> Result<(), Diverged> {
        let scales = lane_scales::<L>(kind);
        let mut accepted = true;
        for (i, (value, &scale)) in out[..L].iter_mut().zip(&scales).enumerate() {
            let (v, ok) = self.lane(i).output_test(scale);
            *value = v;
            accepted &= ok;
        }
        if accepted { Ok(()) } else { Err(Diverged) }
    }
    /// Every lane's output `x √y`, each as its single solve tests it
    /// ([`Filtered::output_times_sqrt_against`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn lanes_output_times_sqrt(&self, y: &Self, kind: ScaleKind, out: &mut [f64]) -> Result<(), Diverged> {
        let scales = lane_scales::<L>(kind);
        let mut accepted = true;
        for (i, (value, &scale)) in out[..L].iter_mut().zip(&scales).enumerate() {
            match self.lane(i).output_times_sqrt_against(&y.lane(i), scale) {
                Ok(v) => *value = v,
                Err(_) => accepted = false,
            }
        }
        if accepted { Ok(()) } else { Err(Diverged) }
    }
    fn approx(&self) -> f64 {
        self.h[0]
    }
}

/// Every lane's root, or [`Diverged`] where one lane's radicand is too
/// uncertain ([`Filtered::sqrt`]).
impl<const L: usize, const RUNNING: bool, const STATIC: bool> super::Radical for Lanes<L, RUNNING, STATIC> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sqrt(&self) -> Result<Self, Diverged> {
        let mut rooted = true;
        let root = lanewise!(|i| match self.lane(i).sqrt() {
            Ok(root) => root,
            Err(_) => {
                rooted = false;
                self.lane(i)
            }
        });
        if rooted { Ok(root) } else { Err(Diverged) }
    }
}
