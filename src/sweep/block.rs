//! A block of a sweep's evaluated points, handed to a visitor column by
//! column ([`super::Sweep::for_each_block_in`]) or row by row.

use super::{BLOCK, Cell, Row};
use crate::error::ImpactError;

/// One output column of a [`Block`].
#[derive(Debug, Clone, Copy)]
pub enum Column<'a> {
    /// A number output read straight into numbers (`NaN` where not computed).
    Numbers(&'a [f64]),
    /// Cells: names, or numbers of a sweep that reads only cells.
    Cells(&'a [Cell]),
}

/// A block of evaluated points (at most 128), column by column.
#[derive(Debug)]
pub struct Block<'a> {
    pub(super) start: u64,
    pub(super) len: usize,
    pub(super) axes: usize,
    pub(super) axis_values: &'a [f64],
    pub(super) axis_indices: &'a [u64],
    /// Column `c`'s cells start at `c · BLOCK` (unless it was read as numbers).
    pub(super) cells: &'a [Cell],
    /// Column `c`'s numbers start at `c · BLOCK`, where it was read as numbers.
    pub(super) numbers: &'a [f64],
    /// Whether each column was read as numbers (empty where none was).
    pub(super) read_as_numbers: &'a [bool],
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

    /// Output column `column`, point by point (a refused point's value is
    /// not its answer: see [`answered`](Self::answered)): numbers where the
    /// sweep read a number output as numbers (for an encoder of typed
    /// columns, [`super::Sweep::for_each_block_in`]), else cells.
    #[inline]
    pub fn column(&self, column: usize) -> Column<'a> {
        let at = column * BLOCK..column * BLOCK + self.len;
        if self.read_as_numbers.get(column) == Some(&true) {
            Column::Numbers(&self.numbers[at])
        } else {
            Column::Cells(&self.cells[at])
        }
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

    /// Hands each point to `visit` as a [`Row`], its cells gathered into `row`
    /// (a block whose every column was read into cells).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn rows(&self, row: &mut [Cell], visit: &mut impl FnMut(Row<'_>)) {
        debug_assert!(!self.read_as_numbers.contains(&true));
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
