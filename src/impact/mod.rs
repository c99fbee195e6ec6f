//! The front door of the solver: an impact of one case with its law and that
//! law's coefficients, and [`solve`], which validates it, checks the fast
//! range, evaluates the model (`src/model/`) in the chosen precision and
//! escalates to exact arithmetic where the fast one cannot answer.
//!
//! - `fast` precision evaluates the model in plain `f64`, every value carrying
//!   a static error bound that each decision is checked against
//!   (`Filtered`, `src/arith/filtered/`): a decision is the exact one, or too close to its tie to
//!   tell, and then the impact is answered by the exact evaluation. Inputs
//!   outside 2^±200 ([`in_fast_range`]) and answers whose evaluation leaves
//!   the f64 range (an output that overflows, a sign that is NaN) are answered
//!   by the exact evaluation too, which neither overflows nor underflows.
//! - `exact` precision: every numeric output is the correctly rounded f64 of
//!   the model's exact value for the given f64 inputs, and every regime
//!   decision and refusal is the exact one. Adaptive precision in the manner
//!   of Shewchuk's robust predicates: the model is evaluated in up to four
//!   arithmetics (`src/arith/`), each dearer and more decisive than the
//!   last (compensated f64 with a static bound; double-double with a tracked
//!   bound; the same keeping exact operations exact; exact fractions). When
//!   every sign the model decides and every output it rounds is certified, the
//!   answer of that arithmetic stands; otherwise the whole answer is evaluated
//!   again in the next. An output whose exact value is zero is `+0.0`.
//!
//! A case ([`Case`]) also says, once, which inputs an impact reads and how to
//! read each output from its outcome; sweeps and the HTTP layer derive their
//! axes, columns and pointers from that.

/// Declares, inside a case's `impl Case`, what the case reads: `INPUTS` (in
/// request order) and `input_mut` from one list of `Input => slot` entries,
/// each slot an `Option<&mut f64>` of the impact bound to `$impact` (`None`
/// where this impact does not read it: a point mass's inertia, body B of a
/// barrier impact); `$input` names the input for entries that share a slot
/// expression. The entry `law => slot` stands for every member of every
/// contact law (`src/law.rs`), in one place for every case that takes one.
macro_rules! reads {
    (|$impact:ident, $input:ident| { $($entries:tt)* }) => {
        reads!(@entries [$impact $input] [] $($entries)*);
    };
    (@entries $names:tt [$($done:tt)*] law => $slot:expr, $($rest:tt)*) => {
        $crate::law::law_members!(reads! { @law $names [$($done)*] ($slot) [$($rest)*] });
    };
    (@law $names:tt [$($done:tt)*] ($slot:expr) [$($rest:tt)*] $($member:ident)|+) => {
        reads!(@entries $names [$($done)* $($member)|+ => $slot,] $($rest)*);
    };
    (@entries $names:tt [$($done:tt)*] $($name:ident)|+ => $slot:expr, $($rest:tt)*) => {
        reads!(@entries $names [$($done)* $($name)|+ => $slot,] $($rest)*);
    };
    (@entries [$impact:ident $input:ident] [$($($name:ident)|+ => $slot:expr,)*]) => {
        const INPUTS: &'static [Input] = &[$($(Input::$name,)+)*];

        #[inline]
        fn input_mut(&mut self, $input: Input) -> Option<&mut f64> {
            let $impact = self;
            match $input {
                $($(Input::$name)|+ => $slot,)*
                _ => None,
            }
        }
    };
}

mod approach;
mod barrier;
mod bodies;
mod entry;
mod spatial;
#[cfg(test)]
pub(crate) mod testing;
mod torsional;

use std::convert::Infallible;
use std::fmt;

use crate::accuracy::ErrorScales;
use crate::arith::{
    Bounded, Compensated, Filtered, OutOfRange, Radical, Surd, Uncertain, Undecided, Unsettled,
};
use crate::error::{Input, Output, Result};
pub use crate::input::{
    BarrierBody, BarrierImpact, BodiesImpact, Lamina, Law, PlanarContact, RigidBody, SpatialContact,
    SpatialImpact, TorsionalImpact, Twist,
};
use crate::model::{Exact, Fail};
use crate::outcome::{Answers, Outputs};
use crate::quantity::Value;

pub use self::entry::{Solver, solve, solve_in, solve_many};
/// The earlier names of [`BarrierImpact`] and [`BarrierBody`], kept for callers.
#[allow(deprecated)]
pub use crate::deprecated_names::{PlanarBody, PlanarImpact};

/// Which arithmetic answers a request.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// The model in plain f64: fastest, error bounded relative to the terms
    /// each output combines (`docs/accuracy.md`).
    #[default]
    Fast,
    /// Correctly rounded outputs and exact decisions.
    Exact,
}

impl Precision {
    /// The mode's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            Precision::Fast => "fast",
            Precision::Exact => "exact",
        }
    }
}

/// How an impact is evaluated: a [`Precision`], or one arithmetic alone (for
/// comparisons, tests and benchmarks). A measurement hook, hidden from the
/// API's documentation: callers choose a [`Precision`].
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Arithmetic {
    /// `fast` precision: f64 with exact decisions inside the fast range, else exact.
    Fast,
    /// `exact` precision: the adaptive stages.
    Exact,
    /// The `fast` evaluation whatever the inputs' range (no range check):
    /// what tests of the f64 forms over wide magnitudes measure.
    Plain,
    /// The same with every decision taken on the f64 value as it is (no
    /// error bound, so a decision within rounding of its tie may go the
    /// wrong way): what the filter of `fast` is measured against.
    Unfiltered,
    /// Exact fractions alone (no earlier stage).
    Rational,
    /// `Fast` without its promise on the numbers (every output accepted
    /// whatever its error bound; decisions still exact): what the promise's
    /// surveys show would break without the output test.
    Unpromised,
}

impl Arithmetic {
    /// Whether the f64 evaluation answers only inside the fast range.
    fn checks_range(self) -> bool {
        matches!(self, Arithmetic::Fast | Arithmetic::Unpromised)
    }

    /// The stage that reports a refusal made before any arithmetic (input validation).
    pub(crate) fn validating_stage(self) -> Stage {
        match self {
            Arithmetic::Fast | Arithmetic::Plain | Arithmetic::Unfiltered | Arithmetic::Unpromised => {
                Stage::Fast
            }
            Arithmetic::Exact => Stage::Compensated,
            Arithmetic::Rational => Stage::Rational,
        }
    }
}

impl From<Precision> for Arithmetic {
    fn from(p: Precision) -> Self {
        match p {
            Precision::Fast => Arithmetic::Fast,
            Precision::Exact => Arithmetic::Exact,
        }
    }
}

/// Which arithmetic produced an answer (or refusal).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Plain f64 (`fast` precision).
    Fast,
    /// Compensated f64 evaluation with a static error bound (also: inputs
    /// refused before any arithmetic in `exact` precision).
    Compensated,
    /// Double-double with a certified error bound.
    DoubleDouble,
    /// Exact rationals, after the compensated and double-double stages could not decide.
    Rational,
}

/// A physical case: an impact type whose values carry their law. What it
/// reads is declared once, by `reads!` in its `impl Case` (its inputs in
/// request order, each with its slot); what it answers is declared once,
/// beside its outcome type ([`Answers`], `src/outcome.rs`).
pub trait Case: Copy + fmt::Debug + Send + Sync + 'static {
    /// The outcome of one impact (the default one is overwritten by every answer).
    type Outcome: Answers + Copy + fmt::Debug + Default + Send;
    /// What a sweep validates once when no axis changes it.
    type Fixed: Clone + fmt::Debug + Send + Sync;
    /// Every input any impact of this case may read, in request order.
    const INPUTS: &'static [Input];
    /// Every output of the case, in response order (its outcome's declaration).
    const OUTPUTS: &'static [Output] = <Self::Outcome as Answers>::OUTPUTS;
    /// The slot of an input this impact reads (its body and law), `None` for
    /// one it does not.
    fn input_mut(&mut self, input: Input) -> Option<&mut f64>;
    /// The value of an input this impact reads.
    #[inline]
    fn input(&self, input: Input) -> Option<f64> {
        let mut copy = *self;
        copy.input_mut(input).map(|x| *x)
    }
    /// The inputs this impact reads, in request order.
    fn reads(&self) -> Vec<Input> {
        Self::INPUTS
            .iter()
            .copied()
            .filter(|&i| self.input(i).is_some())
            .collect()
    }
    /// Whether every input the impact reads is in the fast range ([`in_fast_range`]);
    /// a case may check its fields directly instead of input by input.
    #[inline]
    fn all_in_fast_range(&self) -> bool {
        all_in_fast_range(self, Self::INPUTS)
    }
    /// Whether this impact answers `output` (a barrier has no body B).
    #[inline]
    fn answers(&self, output: Output) -> bool {
        let _ = output;
        true
    }
    /// What the impact is, in words (for messages).
    fn describe(&self) -> &'static str;
    /// The scales `fast`'s promised error is measured against
    /// ([`crate::accuracy`]), from the inputs alone.
    fn error_scales(&self) -> ErrorScales;
    /// One output's value in an outcome (a number is `NaN` when it was not
    /// computed), `None` for an output of another case.
    #[inline]
    fn output(outcome: &Self::Outcome, output: Output) -> Option<Value> {
        outcome.value(output)
    }
    /// Validates what no axis in `swept` changes, once for a sweep.
    fn fix(&self, swept: &[Input]) -> Self::Fixed;
    /// Whether [`Case::evaluate_lanes`] may answer points of a sweep whose
    /// [`Case::fix`] result is `fixed` (a case without an evaluation in
    /// lanes: never).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_lanes(fixed: &Self::Fixed) -> bool {
        let _ = fixed;
        false
    }
    /// Evaluates `impacts`, points of one sweep whose [`Case::fix`] result is
    /// `fixed`, together in `fast`'s first field (`arith::Lanes`, four points):
    /// `true` when every one was answered there (each outcome its single
    /// solve, bit for bit), `false` when they are to be solved one by one
    /// (outcomes partly written). Called in `fast` alone, with every input in
    /// the fast range; a case that has no evaluation in lanes answers
    /// `false`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_lanes(
        impacts: &[Self; LANES],
        fixed: &Self::Fixed,
        outputs: Outputs,
        out: &mut [Self::Outcome; LANES],
    ) -> bool {
        let _ = (impacts, fixed, outputs, out);
        false
    }
    /// Validates and evaluates the impact in `arithmetic` into `out`, `fixed`
    /// being this impact's own [`Case::fix`] result for the inputs not swept;
    /// `in_range` tells `Fast` whether every input read is in the fast range.
    /// The outcome is written in place, whole on success and not at all on a
    /// refusal: returned by value, it would be copied through every layer
    /// (and read back before the copies settle).
    fn evaluate(
        &self,
        fixed: &Self::Fixed,
        outputs: Outputs,
        arithmetic: Arithmetic,
        in_range: bool,
        out: &mut Self::Outcome,
    ) -> (Result<()>, Stage);
}

/// How many points a sweep evaluates together where its case can
/// ([`Case::evaluate_lanes`]): four doubles fill an AVX2 register.
pub(crate) const LANES: usize = crate::arith::MAX_LANES;

/// The largest and smallest magnitudes (2^±200) the fast evaluation takes:
/// products of up to five such inputs stay normal doubles, so no intermediate
/// overflows or loses bits to underflow.
const FAST_RANGE: (f64, f64) = (
    1.0 / (1u128 << 100) as f64 / (1u128 << 100) as f64,
    (1u128 << 100) as f64 * (1u128 << 100) as f64,
);

/// Whether the fast evaluation takes `x` (zero, or a magnitude in 2^±200).
pub fn in_fast_range(x: f64) -> bool {
    x == 0.0 || (FAST_RANGE.0..=FAST_RANGE.1).contains(&x.abs())
}

/// Whether every one of `inputs` the impact reads is in the fast range (one
/// copy of the impact for all of them, not one per input).
#[inline]
fn all_in_fast_range<C: Case>(impact: &C, inputs: &[Input]) -> bool {
    let mut copy = *impact;
    inputs
        .iter()
        .all(|&i| copy.input_mut(i).is_none_or(|x| in_fast_range(*x)))
}

/// Evaluates a validated impact: `model` is the model instantiated in each
/// field. `Fast` answers in f64 when `in_range` and the f64 evaluation stays
/// in range (its outputs within the promised error of `scales`, the
/// impact's [`Case::error_scales`]), else as `Exact`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn evaluate<T>(
    arithmetic: Arithmetic,
    in_range: bool,
    scales: impl FnOnce() -> ErrorScales,
    bounds: StaticBounds,
    model: impl Model<T>,
    out: &mut T,
) -> (Result<()>, Stage) {
    match arithmetic {
        Arithmetic::Fast if in_range => fast_or_exact(&model, scales(), bounds, out),
        Arithmetic::Plain => fast_or_exact(&model, scales(), bounds, out),
        Arithmetic::Unpromised if in_range => fast_or_exact(&model, ErrorScales::UNPROMISED, bounds, out),
        Arithmetic::Unfiltered => unfiltered_or_exact(&model, bounds, out),
        Arithmetic::Fast | Arithmetic::Unpromised | Arithmetic::Exact => adaptive(&model, bounds, out),
        Arithmetic::Rational => rational(&model, out),
    }
}

/// [`evaluate`] for a contact whose approach validation decided in f64,
/// `certain` telling whether that decision was certain: where it was not,
/// the f64 evaluation may not answer (`Fast` goes to the exact stages, the
/// measurement modes `Plain` and `Unfiltered` become `Exact`).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn evaluate_contact<T>(
    arithmetic: Arithmetic,
    in_range: bool,
    certain: bool,
    scales: impl FnOnce() -> ErrorScales,
    bounds: StaticBounds,
    model: impl Model<T>,
    out: &mut T,
) -> (Result<()>, Stage) {
    let arithmetic = match arithmetic {
        Arithmetic::Plain | Arithmetic::Unfiltered if !certain => Arithmetic::Exact,
        other => other,
    };
    evaluate(arithmetic, in_range && certain, scales, bounds, model, out)
}

/// How tight the static error bounds (`λ u M` of `fast`'s
/// `crate::arith::Filtered`, `λ² u² M` of the compensated stage) are for a
/// model: it orders the bounds each precision tries. Either way every
/// decision is exact and every output within the promise; the choice is
/// only what it costs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StaticBounds {
    /// A short computation (one or two laminae): `fast` runs the static
    /// bound alone, then both where it leaves a decision or an output
    /// undecided (the running bound's bookkeeping would cost 25–70 % more on
    /// every answer); in `exact`, a value the compensated stage finds within
    /// its bound of a tie is taken to be near one and goes to the
    /// double-double stage that keeps exact operations exact.
    Tight,
    /// A long chain of products and quotients (the contact in space, through
    /// two 3×3 inverses), where `M` multiplies the conditioning of every
    /// factor: `fast` runs the running bound alone, then both where it leaves
    /// something undecided (the static one alone leaves most outputs
    /// inaccurate, and its magnitudes cost 20–40 % more on every answer); in
    /// `exact`, a value the compensated stage could not decide goes to plain
    /// double-double first, whose bound is tracked, and to the one that keeps
    /// exact operations exact only if that fails too.
    Loose,
}

/// The model in exact fractions alone.
#[inline(never)]
fn rational<T>(model: &impl Model<T>, out: &mut T) -> (Result<()>, Stage) {
    (decided(stage::<Surd, T>(model, out)), Stage::Rational)
}

/// One stage of the exact evaluation, in the kernels the CPU supports, in a
/// function of its own.
#[cfg_attr(not(debug_assertions), inline(always))]
fn stage<N: Radical, T>(model: &impl Model<T>, out: &mut T) -> Exact<N, ()> {
    crate::kernels::run(
        #[cfg_attr(not(debug_assertions), inline(always))]
        || model.run::<N>(out),
    )
}

/// The f64 answer, or the exact one where a decision of the f64 evaluation
/// is within its error bound of a tie (or the evaluation leaves the f64
/// range: an output that overflows, a decision on an infinity or a NaN) or
/// refuses the impact. Every decision of a `fast` answer is the exact one.
#[cfg_attr(not(debug_assertions), inline(always))]
fn fast_or_exact<T>(
    model: &impl Model<T>,
    scales: ErrorScales,
    bounds: StaticBounds,
    out: &mut T,
) -> (Result<()>, Stage) {
    // The only place the f64 evaluation runs: its outputs are measured
    // against this impact's scales, whoever called.
    crate::arith::measure_against(&scales);
    // For `Loose`, the first is in `LooseFast`.
    let first = match bounds {
        StaticBounds::Tight => run_fast::<false, true, T>(model, out),
        StaticBounds::Loose => run_fast::<true, false, T>(model, out),
    };
    match first {
        Ok(()) => return (Ok(()), Stage::Fast),
        // Both bounds together may still decide it.
        Err(Fail::Undecided(Uncertain::Close | Uncertain::Inaccurate)) => {}
        Err(Fail::Refused(_) | Fail::Undecided(Uncertain::Range)) => return adaptive(model, bounds, out),
    }
    match run_fast::<true, true, T>(model, out) {
        Ok(()) => (Ok(()), Stage::Fast),
        Err(Fail::Undecided(Uncertain::Close)) => {
            FAST_ESCALATED[0].fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            adaptive(model, bounds, out)
        }
        Err(Fail::Undecided(Uncertain::Inaccurate)) => {
            FAST_ESCALATED[1].fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            adaptive(model, bounds, out)
        }
        // A refusal of the model is rare and final: the exact stages confirm
        // it and give its payload exactly.
        Err(Fail::Refused(_) | Fail::Undecided(Uncertain::Range)) => adaptive(model, bounds, out),
    }
}

/// The field `fast` evaluates a [`StaticBounds::Loose`] model in first (the
/// running bound alone), which answers nearly every point: what a sweep
/// forms once for such a model, it forms in this field.
pub(crate) type LooseFast = Filtered<true, false>;

/// The field `fast` evaluates a [`StaticBounds::Tight`] model in first (the
/// static bound alone).
pub(crate) type TightFast = Filtered<false, true>;

/// A sweep's geometry formed once in the two fields that answer nearly
/// every point: `fast`'s first (`F`, in [`LooseFast`] or [`TightFast`]) and
/// `exact`'s first (`C`, in the compensated stage). Every other field forms
/// its own per point.
#[derive(Clone)]
pub(crate) struct Prepared<F, C> {
    pub(crate) fast: F,
    pub(crate) compensated: C,
}

impl<F: std::any::Any, C: std::any::Any> Prepared<F, C> {
    /// The geometry of type `G` (a geometry in the field the model runs
    /// in), if it is one of the two.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn get<G: std::any::Any>(&self) -> Option<&G> {
        let fast: &dyn std::any::Any = &self.fast;
        let compensated: &dyn std::any::Any = &self.compensated;
        fast.downcast_ref().or_else(|| compensated.downcast_ref())
    }
}

/// The model in `Filtered`, through `kernels::run`: one compiled body per
/// model and bound, whoever calls (a sweep's every output format, a fit, a
/// single solve), rather than one inlined into each caller, which made the
/// release build's fat LTO run for tens of minutes. (A debug build forces
/// no inlining, so there it is a call like any other.)
#[cfg_attr(not(debug_assertions), inline(always))]
fn run_fast<const RUNNING: bool, const STATIC: bool, T>(
    model: &impl Model<T>,
    out: &mut T,
) -> Exact<Filtered<RUNNING, STATIC>, ()> {
    crate::kernels::run(
        #[cfg_attr(not(debug_assertions), inline(always))]
        || model.run::<Filtered<RUNNING, STATIC>>(out),
    )
}

/// The f64 answer with the decisions f64 takes (no error bound), or the exact
/// one where the evaluation leaves the f64 range or refuses.
#[cfg_attr(not(debug_assertions), inline(always))]
fn unfiltered_or_exact<T>(model: &impl Model<T>, bounds: StaticBounds, out: &mut T) -> (Result<()>, Stage) {
    match stage::<f64, T>(model, out) {
        Ok(()) => (Ok(()), Stage::Fast),
        Err(Fail::Refused(_) | Fail::Undecided(OutOfRange)) => adaptive(model, bounds, out),
    }
}

/// `fast` answers sent to the exact stages since the process started: `[0]`
/// for a decision within its error bound of a tie, `[1]` for an output whose
/// error bound exceeded the promised error.
static FAST_ESCALATED: [std::sync::atomic::AtomicU64; 2] =
    [const { std::sync::atomic::AtomicU64::new(0) }; 2];

/// How many `fast` answers were sent to the exact stages because a decision
/// (a regime, a branch, a refusal) was too close to its tie for the f64
/// error bound, since the process started.
pub fn fast_decisions_escalated() -> u64 {
    FAST_ESCALATED[0].load(std::sync::atomic::Ordering::Relaxed)
}

/// How many `fast` answers were sent to the exact stages because an output's
/// f64 error bound exceeded [`crate::PROMISED_RELATIVE_ERROR`] (a cancelling
/// output, a nearly singular contact), since the process started.
pub fn fast_outputs_escalated() -> u64 {
    FAST_ESCALATED[1].load(std::sync::atomic::Ordering::Relaxed)
}

/// The model of one validated impact, ready to run in any field.
pub(crate) trait Model<T> {
    /// Evaluates the model in `N`, writing the outcome to `out` (whole, or
    /// not at all when it fails).
    fn run<N: Radical>(&self, out: &mut T) -> Exact<N, ()>;
}

/// Runs the model compensated; if that cannot decide because of the range (or
/// a root's conditioning), in double-double; if that cannot decide either, or
/// the compensated value was too close to a zero or a rounding midpoint
/// (perhaps exactly on it), in double-double tracking exact operations
/// (decides ties and cancelled zeros formed without a quotient); and last in
/// exact fractions, which decide everything: its undecided case is
/// uninhabited. Where the model's static bounds are [`StaticBounds::Loose`],
/// a close compensated value is tried in plain double-double first.
#[inline(never)]
fn adaptive<T>(model: &impl Model<T>, bounds: StaticBounds, out: &mut T) -> (Result<()>, Stage) {
    let (result, stage) = adaptive_stages(model, bounds, out);
    let counter = match stage {
        Stage::DoubleDouble => 1,
        Stage::Rational => 2,
        Stage::Fast | Stage::Compensated => 0,
    };
    SETTLED[counter].fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    (result, stage)
}

/// Answers (and refusals) settled by the compensated, double-double and exact
/// stages of the adaptive evaluation since the process started.
static SETTLED: [std::sync::atomic::AtomicU64; 3] = [const { std::sync::atomic::AtomicU64::new(0) }; 3];

/// How many impacts each stage of the adaptive (`exact`) evaluation settled
/// since the process started, in order: compensated, double-double, exact
/// fractions (`fast` answers that needed no escalation are not counted).
pub fn settled_by_stage() -> [(Stage, u64); 3] {
    let n = |i: usize| SETTLED[i].load(std::sync::atomic::Ordering::Relaxed);
    [
        (Stage::Compensated, n(0)),
        (Stage::DoubleDouble, n(1)),
        (Stage::Rational, n(2)),
    ]
}

#[cfg_attr(not(debug_assertions), inline(always))]
fn adaptive_stages<T>(model: &impl Model<T>, bounds: StaticBounds, out: &mut T) -> (Result<()>, Stage) {
    let settled = |result: Exact<Bounded, ()>| match result {
        Ok(()) => Some(Ok(())),
        Err(Fail::Refused(e)) => Some(Err(e)),
        Err(Fail::Undecided(Undecided)) => None,
    };
    let why = match stage::<Compensated, T>(model, out) {
        Ok(()) => return (Ok(()), Stage::Compensated),
        Err(Fail::Refused(e)) => return (Err(e), Stage::Compensated),
        Err(Fail::Undecided(why)) => why,
    };
    let double_double = match why {
        Unsettled::Range => settled(stage::<Bounded, T>(model, out)),
        Unsettled::Close => match bounds {
            StaticBounds::Tight => None,
            StaticBounds::Loose => settled(stage::<Bounded, T>(model, out)),
        },
        // The static bound does not cover a root; double-double's tracked one does.
        Unsettled::Root => settled(stage::<Bounded, T>(model, out)),
    };
    let tracked = || match stage::<Bounded<true>, T>(model, out) {
        Ok(()) => Some(Ok(())),
        Err(Fail::Refused(e)) => Some(Err(e)),
        Err(Fail::Undecided(Undecided)) => None,
    };
    if let Some(answer) = double_double.or_else(tracked) {
        return (answer, Stage::DoubleDouble);
    }
    (decided(stage::<Surd, T>(model, out)), Stage::Rational)
}

/// The rational pass's result: an answer or the model's refusal.
fn decided(result: std::result::Result<(), Fail<Infallible>>) -> Result<()> {
    result.map_err(|fail| match fail {
        Fail::Refused(e) => e,
        Fail::Undecided(never) => match never {},
    })
}
