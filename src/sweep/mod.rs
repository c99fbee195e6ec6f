//! The sweep engine: one case evaluated over a grid of points, in order,
//! chunk by chunk, in parallel across cores.
//!
//! A [`SweepCase`] knows its inputs (a `Point`), which input an axis sets (a
//! `Param`), and how to evaluate a point into the chosen output columns.
//! [`CaseSweep`] is the one for every impact case: built once per sweep, after
//! the axes are known, it validates and prepares every input no axis touches
//! (through [`crate::impact::Solver`]) and skips every output no column asks for. The engine
//! walks the grid with an odometer, resets only the inputs whose axis moved,
//! and reuses its buffers: no allocation per point.

mod block;
mod case;
mod grid;
pub mod reduce;

use std::collections::VecDeque;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering as AtomicOrdering};
use std::sync::mpsc;

pub use block::{Block, Column};
pub use case::{CaseSweep, CaseSweepError};
use grid::Odometer;
pub use grid::{AxisValues, Combine, GridError, count_points, shard};

use crate::error::ImpactError;

/// One output value of a point: a number or a name (a regime).
pub type Cell = crate::quantity::Value;

/// A physical case a sweep can run.
pub trait SweepCase: Sync {
    /// Every input of one impact.
    type Point: Copy + Send + Sync;
    /// Which input an axis sets.
    type Param: Copy + Send + Sync;
    /// One point's answer, before its columns are read off.
    type Outcome: Copy + Default;
    /// Sets one input of a point.
    fn set(point: &mut Self::Point, param: Self::Param, value: f64);
    /// Number of output columns.
    fn columns(&self) -> usize;
    /// Evaluates one point into `out` (left as it was when the point has no answer).
    fn evaluate(&self, point: &Self::Point, out: &mut Self::Outcome) -> Result<(), ImpactError>;
    /// Whether [`evaluate_block`](Self::evaluate_block) evaluates points
    /// together; else each point is evaluated as soon as it is set (not
    /// copied aside first: for two laminae that copy cost 5 % of a point).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_blocks(&self) -> bool {
        false
    }
    /// Evaluates a block's `points` into `outs` (of the same length), pushing
    /// each point without an answer to `refusals` in order, with its position
    /// and why: each as [`evaluate`](Self::evaluate) answers it, though a
    /// case may evaluate several together.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_block(
        &self,
        points: &[Self::Point],
        outs: &mut [Self::Outcome],
        refusals: &mut Vec<(usize, ImpactError)>,
    ) {
        for (k, (point, out)) in points.iter().zip(outs).enumerate() {
            if let Err(e) = self.evaluate(point, out) {
                refusals.push((k, e));
            }
        }
    }
    /// Reads column `column` off a block's `outcomes` into `cells`, one cell
    /// per outcome (including outcomes of points without an answer, whose
    /// cells are not shown).
    fn read(&self, column: usize, outcomes: &[Self::Outcome], cells: &mut [Cell]);
    /// Reads number column `column` off a block's `outcomes` into `values`,
    /// as [`read`](Self::read) would into cells: `false` (nothing read) for
    /// a column of names, or a case that reads only cells.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn read_numbers(&self, column: usize, outcomes: &[Self::Outcome], values: &mut [f64]) -> bool {
        let _ = (column, outcomes, values);
        false
    }
}

/// Points evaluated before their columns are read: enough that a column is
/// read in one loop, few enough that the block's outcomes and cells stay in
/// the first levels of cache.
const BLOCK: usize = 128;

/// One axis: the input it sets and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis<P> {
    /// The input the axis sets.
    pub param: P,
    /// Its values.
    pub values: AxisValues,
}

/// One evaluated point, handed to a visitor.
#[derive(Debug)]
pub struct Row<'a> {
    /// The point's index in the sweep.
    pub index: u64,
    /// The value of each axis at this point.
    pub axis_values: &'a [f64],
    /// The index of each axis's value at this point.
    pub axis_indices: &'a [u64],
    /// The output cells, or why the point has no answer.
    pub outcome: Result<&'a [Cell], &'a ImpactError>,
}

/// A case over a grid of points, or over one range of them (a slice of the
/// grid's point order, addressed by the points' indices in the whole grid).
#[derive(Debug)]
pub struct Sweep<C: SweepCase> {
    case: C,
    base: C::Point,
    axes: Vec<Axis<C::Param>>,
    combine: Combine,
    total: u64,
    range: Range<u64>,
}

impl<C: SweepCase> Sweep<C> {
    /// A sweep of `case` from `base` over `axes`, refusing more than `limit` points
    /// before anything is computed.
    pub fn new(
        case: C,
        base: C::Point,
        axes: Vec<Axis<C::Param>>,
        combine: Combine,
        limit: u64,
    ) -> Result<Self, GridError> {
        Self::slice(case, base, axes, combine, None, limit)
    }

    /// The points of `range` (all when `None`) of the sweep of `case` from
    /// `base` over `axes`, refusing a range outside the grid, and more than
    /// `limit` points in the range, before anything is computed. The grid
    /// itself may be larger than the limit when a range is given.
    pub fn slice(
        case: C,
        base: C::Point,
        axes: Vec<Axis<C::Param>>,
        combine: Combine,
        range: Option<Range<u64>>,
        limit: u64,
    ) -> Result<Self, GridError> {
        let values: Vec<&AxisValues> = axes.iter().map(|a| &a.values).collect();
        let (total, range) = match range {
            None => {
                let total = count_points(&values, combine, limit)?;
                (total, 0..total)
            }
            Some(range) => {
                let total = count_points(&values, combine, u64::MAX)?;
                if range.start > range.end || range.end > total {
                    return Err(GridError::RangeOutside {
                        start: range.start,
                        end: range.end,
                        points: total,
                    });
                }
                if range.end - range.start > limit {
                    return Err(GridError::RangeTooLarge {
                        start: range.start,
                        end: range.end,
                        limit,
                    });
                }
                (total, range)
            }
        };
        Ok(Sweep {
            case,
            base,
            axes,
            combine,
            total,
            range,
        })
    }

    /// Number of points this sweep computes (those of its range).
    pub fn points(&self) -> u64 {
        self.range.end - self.range.start
    }

    /// Number of points of the whole grid.
    pub fn total_points(&self) -> u64 {
        self.total
    }

    /// The points this sweep computes, as indices into the whole grid.
    pub fn range(&self) -> Range<u64> {
        self.range.clone()
    }

    /// The axes.
    pub fn axes(&self) -> &[Axis<C::Param>] {
        &self.axes
    }

    /// How the axes combine.
    pub fn combine(&self) -> Combine {
        self.combine
    }

    /// The case.
    pub fn case(&self) -> &C {
        &self.case
    }

    /// Evaluates the points in `range` (indices into the whole grid, clipped to
    /// the sweep's own range), in order, handing each to `visit`.
    /// Runs in the kernels the CPU supports ([`crate::kernels`]).
    pub fn for_each_in(&self, range: Range<u64>, mut visit: impl FnMut(Row<'_>)) {
        let mut row = vec![Cell::Number(0.0); self.case.columns()];
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || {
                self.for_each_block_here(
                    range,
                    false,
                    #[cfg_attr(not(debug_assertions), inline(always))]
                    |block| block.rows(&mut row, &mut visit),
                )
            },
        )
    }

    /// Evaluates the points in `range` as [`for_each_in`](Self::for_each_in)
    /// does, handing them to `visit` a block at a time, column by column: for
    /// an encoder that writes columns (Arrow), one loop per column rather than
    /// a pass over every column per point.
    pub fn for_each_block_in(&self, range: Range<u64>, visit: impl FnMut(&Block<'_>)) {
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || self.for_each_block_here(range, true, visit),
        )
    }

    /// The block loop: with `typed`, number columns are read straight into
    /// numbers ([`SweepCase::read_numbers`]), else every column into cells.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn for_each_block_here(&self, range: Range<u64>, typed: bool, mut visit: impl FnMut(&Block<'_>)) {
        let start = range.start.max(self.range.start);
        let end = range.end.min(self.range.end);
        if start >= end {
            return;
        }
        let (axes, columns) = (self.axes.len(), self.case.columns());
        let lens = self.axes.iter().map(|a| a.values.len()).collect();
        let samplers: Vec<_> = self.axes.iter().map(|a| a.values.sampler()).collect();
        let mut odometer = Odometer::at(lens, self.combine, start);
        // One block's points: axis values and digits point by point, the
        // points themselves where they are evaluated together, outcomes,
        // the refusals (rare: only they are kept, not a result per point, whose
        // copies through the stack cost more than a small model), and the
        // cells column by column.
        let mut values = vec![0.0; BLOCK * axes];
        let mut digits = vec![0; BLOCK * axes];
        // On the heap: a block of outcomes in space is tens of kilobytes.
        #[allow(clippy::useless_vec)]
        let mut outcomes = vec![C::Outcome::default(); BLOCK];
        let in_blocks = self.case.in_blocks();
        let mut points = vec![self.base; if in_blocks { BLOCK } else { 0 }];
        let mut refusals: Vec<(usize, ImpactError)> = Vec::with_capacity(BLOCK);
        let mut answered = [true; BLOCK];
        let mut cells = vec![Cell::Number(0.0); BLOCK * columns];
        let mut numbers = vec![0.0; if typed { BLOCK * columns } else { 0 }];
        let mut read_as_numbers = vec![false; if typed { columns } else { 0 }];
        let mut current = vec![0.0; axes];
        let mut point = self.base;
        let mut changed = 0;
        let mut block_start = start;
        while block_start < end {
            let n = (end - block_start).min(BLOCK as u64) as usize;
            refusals.clear();
            for k in 0..n {
                let axes_here = self.axes.iter().zip(&samplers).zip(odometer.digits());
                for (axis, ((a, sampler), &digit)) in axes_here.enumerate().skip(changed) {
                    let v = sampler.value(digit);
                    current[axis] = v;
                    C::set(&mut point, a.param, v);
                }
                if axes == 1 {
                    // Most sweeps have one axis: copied as one value (a
                    // copy of a slice is a call to `memcpy`).
                    values[k] = current[0];
                    digits[k] = odometer.digits()[0];
                } else {
                    values[k * axes..(k + 1) * axes].copy_from_slice(&current);
                    digits[k * axes..(k + 1) * axes].copy_from_slice(odometer.digits());
                }
                if in_blocks {
                    // Each point set aside is the base with every swept
                    // input set: only those are written (not a copy of
                    // the whole point).
                    for (a, &v) in self.axes.iter().zip(&current) {
                        C::set(&mut points[k], a.param, v);
                    }
                } else if let Err(e) = self.case.evaluate(&point, &mut outcomes[k]) {
                    refusals.push((k, e));
                }
                changed = odometer.advance();
            }
            if in_blocks {
                self.case
                    .evaluate_block(&points[..n], &mut outcomes[..n], &mut refusals);
            }
            for column in 0..columns {
                let at = column * BLOCK..column * BLOCK + n;
                let as_numbers = typed
                    && self
                        .case
                        .read_numbers(column, &outcomes[..n], &mut numbers[at.clone()]);
                if let Some(read) = read_as_numbers.get_mut(column) {
                    *read = as_numbers;
                }
                if !as_numbers {
                    self.case.read(column, &outcomes[..n], &mut cells[at]);
                }
            }
            answered[..n].fill(true);
            for &(k, _) in &refusals {
                answered[k] = false;
            }
            visit(&Block {
                start: block_start,
                len: n,
                axes,
                axis_values: &values[..n * axes],
                axis_indices: &digits[..n * axes],
                cells: &cells,
                numbers: &numbers,
                read_as_numbers: &read_as_numbers,
                answered: &answered[..n],
                refusals: &refusals,
            });
            block_start += n as u64;
        }
    }

    /// Evaluates the sweep's range in chunks of `chunk` points: `produce` turns a range
    /// into a value (rows formatted as bytes, say) on the worker threads, and
    /// `consume` receives the values in point order on the calling thread.
    /// Stops early, returning `false`, when `consume` returns `false`. At most
    /// twice as many chunks as there are threads are held at once.
    ///
    /// A sliding window, not batches: as soon as the oldest chunk is consumed
    /// the next one is queued, so no worker waits for the slowest chunk of a
    /// batch (on this 2-core VM, batches with a barrier gave 1.2× one core).
    /// The calling thread waits for each chunk in turn; called from a thread
    /// of the rayon pool itself (where that wait could hold the pool's only
    /// thread), it evaluates the chunks in order on that thread instead.
    pub fn run_parallel<T: Send>(
        &self,
        chunk: u64,
        produce: impl Fn(Range<u64>) -> T + Sync,
        mut consume: impl FnMut(T) -> bool,
    ) -> bool {
        let chunk = chunk.max(1);
        if rayon::current_thread_index().is_some() {
            let mut start = self.range.start;
            while start < self.range.end {
                let range = start..start.saturating_add(chunk).min(self.range.end);
                start = range.end;
                if !consume(produce(range)) {
                    return false;
                }
            }
            return true;
        }
        let window = 2 * rayon::current_num_threads().max(1);
        let end = self.range.end;
        let stopped = AtomicBool::new(false);
        let (produce, stopped) = (&produce, &stopped);
        rayon::in_place_scope_fifo(|scope| {
            let mut next = self.range.start;
            let mut pending = VecDeque::with_capacity(window);
            loop {
                while pending.len() < window && next < end {
                    let range = next..next.saturating_add(chunk).min(end);
                    next = range.end;
                    let (sender, receiver) = mpsc::sync_channel(1);
                    scope.spawn_fifo(move |_| {
                        if !stopped.load(AtomicOrdering::Relaxed) {
                            // The receiver is gone only after a stop.
                            let _ = sender.send(produce(range));
                        }
                    });
                    pending.push_back(receiver);
                }
                let Some(receiver) = pending.pop_front() else {
                    return true;
                };
                // A closed channel means `produce` panicked: the scope
                // resumes that panic once the spawned chunks are done.
                let Ok(value) = receiver.recv() else {
                    stopped.store(true, AtomicOrdering::Relaxed);
                    return false;
                };
                if !consume(value) {
                    stopped.store(true, AtomicOrdering::Relaxed);
                    return false;
                }
            }
        })
    }
}

#[cfg(test)]
mod tests;
