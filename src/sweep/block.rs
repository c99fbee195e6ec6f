//! A block of a sweep's evaluated points, handed to a visitor column by
//! column ([`super::Sweep::for_each_block_in`]) or row by row.

use super::{BLOCK, Cell, Row};
use crate::error::ImpactError;

/// A block of evaluated points (at most 128), column by column.
#[derive(Debug)]
pub struct Block<'a> {
    pub(super) start: u64,
    pub(super) len: usize,
    pub(super) axes: usize,
    pub(super) axis_values: &'a [f64],
    pub(super) axis_indices: &'a [u64],
    /// Column `c`'s cells start at `c · BLOCK`.
    pub(super) cells: &'a [Cell],
    pub(super) answered: &'a [bool],
    pub(super) refusals: &'a [(usize, ImpactError)],
}

impl<'a> Block<'a> {
    /// The index of the block's first point in the sweep.
    pub fn start(&self) -> u64 {
        self.start
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the block has no points (never, for a block handed to a visitor).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Axis `axis`'s values, point by point.
    #[inline]
    pub fn axis(&self, axis: usize) -> impl Iterator<Item = f64> + '_ {
        self.axis_values.iter().skip(axis).step_by(self.axes).copied()
    }

    /// Output column `column`'s cells, point by point (a refused point's
    /// cell is not its answer: see [`answered`](Self::answered)).
    #[inline]
    pub fn column(&self, column: usize) -> &'a [Cell] {
        &self.cells[column * BLOCK..column * BLOCK + self.len]
    }

    /// Whether each point has an answer.
    #[inline]
    pub fn answered(&self) -> &'a [bool] {
        self.answered
    }

    /// The points without an answer, in order: position in the block, and why.
    #[inline]
    pub fn refusals(&self) -> &'a [(usize, ImpactError)] {
        self.refusals
    }

    /// Hands each point to `visit` as a [`Row`], its cells gathered into `row`.
    #[inline(always)]
    pub(super) fn rows(&self, row: &mut [Cell], visit: &mut impl FnMut(Row<'_>)) {
        let axes = self.axes;
        let mut refused = self.refusals.iter().peekable();
        for k in 0..self.len {
            let outcome = match refused.next_if(|(i, _)| *i == k) {
                Some((_, e)) => Err(e),
                None => {
                    for (column, cell) in row.iter_mut().enumerate() {
                        *cell = self.cells[column * BLOCK + k];
                    }
                    Ok(&row[..])
                }
            };
            visit(Row {
                index: self.start + k as u64,
                axis_values: &self.axis_values[k * axes..(k + 1) * axes],
                axis_indices: &self.axis_indices[k * axes..(k + 1) * axes],
                outcome,
            });
        }
    }
}
