//! The solver's entry points: one impact ([`solve`]), many at once
//! ([`solve_many`]), and the points of a sweep ([`Solver`]).

use super::{Arithmetic, Case, LANES, Precision, Stage, all_in_fast_range};
use crate::error::{ImpactError, Input, Result};
use crate::outcome::Outputs;

/// Solves one impact in `precision`, computing the optional `outputs`.
pub fn solve<C: Case>(impact: &C, outputs: Outputs, precision: Precision) -> Result<C::Outcome> {
    solve_in(impact, outputs, precision.into()).0
}

/// Solves every impact of `impacts` in `precision`, each answer (or refusal)
/// the one [`solve`] gives, in order. The whole slice runs in one entry into
/// the copy of the solver the CPU selects (x86-64-v3 where it has AVX2 and
/// FMA), where a caller's loop over [`solve`] enters it once per impact: use
/// it for many impacts at once (a Monte Carlo draw, a batch read from a
/// file). The impacts may differ in anything; a grid that varies a few
/// inputs of one scene is a sweep ([`Solver`], `restitution sweep`), which
/// also validates what the points share once.
pub fn solve_many<C: Case>(impacts: &[C], outputs: Outputs, precision: Precision) -> Vec<Result<C::Outcome>> {
    let arithmetic = Arithmetic::from(precision);
    crate::kernels::run(
        #[cfg_attr(not(debug_assertions), inline(always))]
        || {
            impacts
                .iter()
                .map(|impact| solve_here(impact, outputs, arithmetic).0)
                .collect()
        },
    )
}

/// Solves one impact in `arithmetic`, reporting which stage answered (a
/// measurement hook, like [`Arithmetic`]).
#[doc(hidden)]
pub fn solve_in<C: Case>(
    impact: &C,
    outputs: Outputs,
    arithmetic: Arithmetic,
) -> (Result<C::Outcome>, Stage) {
    crate::kernels::run(
        #[cfg_attr(not(debug_assertions), inline(always))]
        || solve_here(impact, outputs, arithmetic),
    )
}

/// One impact solved in the copy of the solver that calls it.
#[cfg_attr(not(debug_assertions), inline(always))]
fn solve_here<C: Case>(impact: &C, outputs: Outputs, arithmetic: Arithmetic) -> (Result<C::Outcome>, Stage) {
    let fixed = impact.fix(&[]);
    let in_range = arithmetic.checks_range() && impact.all_in_fast_range();
    let mut outcome = C::Outcome::default();
    let (result, stage) = impact.evaluate(&fixed, outputs, arithmetic, in_range, &mut outcome);
    (result.map(|()| outcome), stage)
}

/// One case prepared for many impacts that differ only in the `swept`
/// inputs (a sweep): what the others fix is validated, and their fast range
/// checked, once.
#[derive(Debug, Clone)]
pub struct Solver<C: Case> {
    pub(in crate::impact) fixed: C::Fixed,
    outputs: Outputs,
    arithmetic: Arithmetic,
    /// Whether every input not swept is in the fast range.
    fixed_in_range: bool,
    swept: Vec<Input>,
}

impl<C: Case> Solver<C> {
    /// Prepares `base`, whose `swept` inputs will change, for `outputs` in `precision`.
    pub fn new(base: &C, swept: &[Input], outputs: Outputs, precision: Precision) -> Self {
        Solver::in_arithmetic(base, swept, outputs, precision.into())
    }

    /// The same in one `arithmetic` (for comparisons and benchmarks: what
    /// the filter of `fast` costs a sweep is `Fast` against `Unfiltered`).
    #[doc(hidden)]
    pub fn in_arithmetic(base: &C, swept: &[Input], outputs: Outputs, arithmetic: Arithmetic) -> Self {
        let fixed_inputs: Vec<Input> = base.reads().into_iter().filter(|i| !swept.contains(i)).collect();
        Solver {
            fixed: base.fix(swept),
            outputs,
            arithmetic,
            fixed_in_range: all_in_fast_range(base, &fixed_inputs),
            swept: swept.to_vec(),
        }
    }

    /// The optional outputs computed.
    pub fn outputs(&self) -> Outputs {
        self.outputs
    }

    /// Solves `impact` (the base with other values of the swept inputs).
    #[inline]
    pub fn solve(&self, impact: &C) -> Result<C::Outcome> {
        let mut outcome = C::Outcome::default();
        self.solve_into(impact, &mut outcome).map(|()| outcome)
    }

    /// Whether [`Solver::solve_block_into`] evaluates points together: in
    /// `fast`, with every input not swept in the fast range, where the case
    /// can ([`Case::in_lanes`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn in_lanes(&self) -> bool {
        self.arithmetic == Arithmetic::Fast && self.fixed_in_range && C::in_lanes(&self.fixed)
    }

    /// Solves `impacts` into `outs` (of the same length), handing each
    /// refusal to `refused` with the point's position: each point's answer
    /// or refusal is what [`Solver::solve_into`] gives it, but in `fast` the
    /// points go through the model four at a time where the case can
    /// ([`Case::evaluate_lanes`]), and one by one where it cannot (a
    /// refusal, a decision the lanes do not all take alike).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn solve_block_into(
        &self,
        impacts: &[C],
        outs: &mut [C::Outcome],
        mut refused: impl FnMut(usize, ImpactError),
    ) {
        assert_eq!(impacts.len(), outs.len(), "one outcome per impact");
        // Points before `alone_until` are solved one by one.
        let mut alone_until = if self.in_lanes() { 0 } else { impacts.len() };
        let mut k = 0;
        while k < impacts.len() {
            if k >= alone_until {
                if let (Some(points), Some(answers)) = (
                    impacts[k..].first_chunk::<LANES>(),
                    outs[k..].first_chunk_mut::<LANES>(),
                ) {
                    // (A loop, not a closure: one compiled apart from the
                    // copy that runs costs a call per point.)
                    let mut in_range = true;
                    for point in points {
                        in_range &= all_in_fast_range(point, &self.swept);
                    }
                    if in_range && C::evaluate_lanes(points, &self.fixed, self.outputs, answers) {
                        k += LANES;
                        continue;
                    }
                }
                alone_until = k + LANES;
            }
            if let Err(e) = self.solve_into(&impacts[k], &mut outs[k]) {
                refused(k, e);
            }
            k += 1;
        }
    }

    /// Solves `impact` into `out` (left as it was on a refusal).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub fn solve_into(&self, impact: &C, out: &mut C::Outcome) -> Result<()> {
        let in_range =
            self.arithmetic.checks_range() && self.fixed_in_range && all_in_fast_range(impact, &self.swept);
        impact
            .evaluate(&self.fixed, self.outputs, self.arithmetic, in_range, out)
            .0
    }
}
