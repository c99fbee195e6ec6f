//! Reductions: a sweep summarised in one pass instead of returned row by row.
//!
//! Per output column: for numbers, the count of finite values, the minimum
//! and maximum with the point where each first occurs, the exact sum (and the
//! mean from it) and an optional histogram; for names (regimes), the count of
//! each name; per sweep, the points answered and the points refused by
//! problem. Every part merges exactly: counts add, extremes keep the earlier
//! point on ties, sums are kept as non-overlapping partials (Shewchuk's
//! expansion, as Python's `math.fsum`), so the reduction of a sweep is the
//! same whatever its chunks or ranges, and partial reductions of ranges
//! combine into exactly the reduction of the whole.

use super::{Cell, Row};

/// An exact sum of doubles: non-overlapping partials whose exact sum is the
/// sum of every value added (Shewchuk 1997; the algorithm of Python's `math.fsum`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ExactSum {
    partials: Vec<f64>,
    overflowed: bool,
}

impl ExactSum {
    /// Adds `x` exactly (finite `x`; a partial beyond the double range marks the sum overflowed).
    #[inline]
    pub fn add(&mut self, mut x: f64) {
        if self.overflowed {
            return;
        }
        let mut kept = 0;
        for j in 0..self.partials.len() {
            let y = self.partials[j];
            let hi = x + y;
            let b = hi - x;
            let lo = (x - (hi - b)) + (y - b);
            if lo != 0.0 {
                self.partials[kept] = lo;
                kept += 1;
            }
            x = hi;
        }
        self.partials.truncate(kept);
        if !x.is_finite() {
            self.overflowed = true;
            self.partials.clear();
            return;
        }
        self.partials.push(x);
    }

    /// Adds every partial of `other` (exact).
    pub fn merge(&mut self, other: &ExactSum) {
        if other.overflowed {
            self.overflowed = true;
            self.partials.clear();
        }
        for &p in &other.partials {
            self.add(p);
        }
    }

    /// The partials, least significant first: their exact sum is the sum.
    pub fn partials(&self) -> &[f64] {
        &self.partials
    }

    /// The sum correctly rounded to a double (ties to even); `None` when a
    /// partial sum left the double range.
    pub fn value(&self) -> Option<f64> {
        if self.overflowed {
            return None;
        }
        let p = &self.partials;
        let mut n = p.len();
        if n == 0 {
            return Some(0.0);
        }
        n -= 1;
        let mut hi = p[n];
        let mut lo = 0.0;
        while n > 0 {
            let x = hi;
            n -= 1;
            let y = p[n];
            hi = x + y;
            lo = y - (hi - x);
            if lo != 0.0 {
                break;
            }
        }
        // Round half to even: when the rest has the sign of the rounding error, the tie breaks away.
        if n > 0 && ((lo < 0.0 && p[n - 1] < 0.0) || (lo > 0.0 && p[n - 1] > 0.0)) {
            let y = lo * 2.0;
            let x = hi + y;
            if y == x - hi {
                hi = x;
            }
        }
        Some(hi)
    }
}

/// Equal-width bins over `[start, stop]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bins {
    /// Lower edge of the first bin.
    pub start: f64,
    /// Upper edge of the last bin (included in it).
    pub stop: f64,
    /// Number of bins.
    pub count: u32,
}

impl Bins {
    /// The bin of `x`: `Ok(i)` with `i = ⌊(x − start)/(stop − start)·count⌋`
    /// (in doubles, clamped to the last bin, which holds `stop`), `Err(false)`
    /// below `start`, `Err(true)` above `stop`.
    #[inline]
    pub fn of(&self, x: f64) -> Result<usize, bool> {
        if x < self.start {
            return Err(false);
        }
        if x > self.stop {
            return Err(true);
        }
        let at = ((x - self.start) / (self.stop - self.start) * f64::from(self.count)).floor();
        Ok((at as usize).min(self.count as usize - 1))
    }
}

/// A histogram: counts per bin, and of values outside the bins.
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// The bins.
    pub bins: Bins,
    /// Count of values in each bin.
    pub counts: Vec<u64>,
    /// Values below `start`.
    pub below: u64,
    /// Values above `stop`.
    pub above: u64,
}

/// Where an extreme value first occurs.
#[derive(Debug, Clone, PartialEq)]
pub struct Extreme {
    /// The value.
    pub value: f64,
    /// The point's index in the sweep.
    pub index: u64,
    /// The axis values at that point.
    pub inputs: Vec<f64>,
}

/// The reduction of a number column.
#[derive(Debug, Clone, PartialEq)]
pub struct NumberStats {
    /// Finite values seen.
    pub count: u64,
    /// The least value (the first point on ties).
    pub min: Option<Extreme>,
    /// The greatest value (the first point on ties).
    pub max: Option<Extreme>,
    /// The exact sum.
    pub sum: ExactSum,
    /// The histogram, when asked for.
    pub histogram: Option<Histogram>,
}

impl NumberStats {
    /// The mean: the correctly rounded sum divided by the count.
    pub fn mean(&self) -> Option<f64> {
        (self.count > 0)
            .then(|| self.sum.value())
            .flatten()
            .map(|s| s / self.count as f64)
    }

    fn add(&mut self, x: f64, row: &Row<'_>) {
        self.count += 1;
        if self.min.as_ref().is_none_or(|m| x < m.value) {
            self.min = Some(extreme(x, row));
        }
        if self.max.as_ref().is_none_or(|m| x > m.value) {
            self.max = Some(extreme(x, row));
        }
        self.sum.add(x);
        if let Some(h) = &mut self.histogram {
            match h.bins.of(x) {
                Ok(i) => h.counts[i] += 1,
                Err(false) => h.below += 1,
                Err(true) => h.above += 1,
            }
        }
    }

    /// Merges the stats of later points.
    fn merge(&mut self, later: NumberStats) {
        self.count += later.count;
        if let Some(m) = later.min
            && self.min.as_ref().is_none_or(|s| m.value < s.value)
        {
            self.min = Some(m);
        }
        if let Some(m) = later.max
            && self.max.as_ref().is_none_or(|s| m.value > s.value)
        {
            self.max = Some(m);
        }
        self.sum.merge(&later.sum);
        if let (Some(h), Some(l)) = (&mut self.histogram, later.histogram) {
            h.counts.iter_mut().zip(l.counts).for_each(|(a, b)| *a += b);
            h.below += l.below;
            h.above += l.above;
        }
    }
}

fn extreme(value: f64, row: &Row<'_>) -> Extreme {
    Extreme {
        value,
        index: row.index,
        inputs: row.axis_values.to_vec(),
    }
}

/// The reduction of one output column.
#[derive(Debug, Clone, PartialEq)]
pub enum ColumnStats {
    /// A number column.
    Numbers(NumberStats),
    /// A name column: each name and how many points have it, in order of first appearance.
    Names(Vec<(&'static str, u64)>),
}

/// The reduction of a sweep, or of some of its points.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduction {
    /// Points reduced.
    pub points: u64,
    /// Points with an answer.
    pub answered: u64,
    /// Points without one, by problem (slug, title, count), in order of first appearance.
    pub refused: Vec<(&'static str, &'static str, u64)>,
    /// One entry per output column.
    pub columns: Vec<ColumnStats>,
}

impl Reduction {
    /// An empty reduction of columns that are names where `names` is true,
    /// numbers elsewhere, with the histograms asked for.
    pub fn new(names: &[bool], histograms: &[Option<Bins>]) -> Self {
        let columns = names
            .iter()
            .zip(histograms)
            .map(|(&name, bins)| {
                if name {
                    ColumnStats::Names(Vec::new())
                } else {
                    ColumnStats::Numbers(NumberStats {
                        count: 0,
                        min: None,
                        max: None,
                        sum: ExactSum::default(),
                        histogram: bins.map(|bins| Histogram {
                            bins,
                            counts: vec![0; bins.count as usize],
                            below: 0,
                            above: 0,
                        }),
                    })
                }
            })
            .collect();
        Reduction {
            points: 0,
            answered: 0,
            refused: Vec::new(),
            columns,
        }
    }

    /// Adds one evaluated point.
    pub fn add(&mut self, row: &Row<'_>) {
        self.points += 1;
        let cells = match row.outcome {
            Ok(cells) => cells,
            Err(e) => {
                count(&mut self.refused, (e.slug(), e.title()), 1);
                return;
            }
        };
        self.answered += 1;
        for (stats, cell) in self.columns.iter_mut().zip(cells) {
            match (stats, cell) {
                (ColumnStats::Numbers(s), Cell::Number(x)) if x.is_finite() => s.add(*x, row),
                (ColumnStats::Names(names), Cell::Text(name)) => {
                    match names.iter_mut().find(|(n, _)| n == name) {
                        Some((_, c)) => *c += 1,
                        None => names.push((name, 1)),
                    }
                }
                _ => {}
            }
        }
    }

    /// Merges the reduction of points that come after this one's.
    pub fn merge(&mut self, later: Reduction) {
        self.points += later.points;
        self.answered += later.answered;
        for (slug, title, n) in later.refused {
            count(&mut self.refused, (slug, title), n);
        }
        for (stats, later) in self.columns.iter_mut().zip(later.columns) {
            match (stats, later) {
                (ColumnStats::Numbers(s), ColumnStats::Numbers(l)) => s.merge(l),
                (ColumnStats::Names(s), ColumnStats::Names(l)) => {
                    for (name, n) in l {
                        match s.iter_mut().find(|(m, _)| *m == name) {
                            Some((_, c)) => *c += n,
                            None => s.push((name, n)),
                        }
                    }
                }
                _ => debug_assert!(false, "reductions of different columns"),
            }
        }
    }
}

fn count(
    refused: &mut Vec<(&'static str, &'static str, u64)>,
    (slug, title): (&'static str, &'static str),
    n: u64,
) {
    match refused.iter_mut().find(|(s, t, _)| *s == slug && *t == title) {
        Some((_, _, c)) => *c += n,
        None => refused.push((slug, title, n)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact sum against integer arithmetic on scaled values, and the
    /// correctly rounded result where naive summation loses everything.
    #[test]
    fn exact_sums_are_exact_and_merge_exactly() {
        let mut s = ExactSum::default();
        for x in [1e100, 1.0, -1e100, 1e-100] {
            s.add(x);
        }
        assert_eq!(s.value(), Some(1.0));
        // Integers of up to 53 bits in units of 2^-30, of both signs: their exact
        // sum needs up to 67 bits, so naive summation rounds.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let units: Vec<i64> = (0..10_000)
            .map(|_| {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (state >> 11) as i64 - (1 << 52)
            })
            .collect();
        let values: Vec<f64> = units.iter().map(|&k| k as f64 * 2f64.powi(-30)).collect();
        let mut whole = ExactSum::default();
        values.iter().for_each(|&x| whole.add(x));
        let mut parts = ExactSum::default();
        for chunk in values.chunks(333) {
            let mut part = ExactSum::default();
            chunk.iter().for_each(|&x| part.add(x));
            parts.merge(&part);
        }
        assert_eq!(whole.value(), parts.value());
        // The integer sum, rounded once (i128 → f64 rounds to nearest, ties to even).
        let exact: i128 = units.iter().map(|&k| i128::from(k)).sum();
        assert_eq!(whole.value(), Some(exact as f64 * 2f64.powi(-30)));
        let naive: f64 = values.iter().sum();
        assert_ne!(
            naive,
            exact as f64 * 2f64.powi(-30),
            "the test needs a sum that naive addition rounds"
        );
        // Halfway cases round to even, as math.fsum.
        let mut tie = ExactSum::default();
        for x in [1.0, 2f64.powi(-53), 2f64.powi(-106)] {
            tie.add(x);
        }
        assert_eq!(tie.value(), Some(1.0 + f64::EPSILON));
        let mut over = ExactSum::default();
        over.add(f64::MAX);
        over.add(f64::MAX);
        assert_eq!(over.value(), None);
    }

    #[test]
    fn bins_cover_their_ends() {
        let b = Bins {
            start: 0.0,
            stop: 1.0,
            count: 4,
        };
        assert_eq!(b.of(0.0), Ok(0));
        assert_eq!(b.of(0.25), Ok(1));
        assert_eq!(b.of(0.999), Ok(3));
        assert_eq!(b.of(1.0), Ok(3));
        assert_eq!(b.of(-0.1), Err(false));
        assert_eq!(b.of(1.1), Err(true));
    }
}
