//! The points of a sweep: axes of values and how they combine.

use thiserror::Error;

/// The values one axis takes.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// Explicit values, in order.
    List(Vec<f64>),
    /// `count` evenly spaced values from `start` to `stop`, both included.
    Linspace {
        /// First value.
        start: f64,
        /// Last value.
        stop: f64,
        /// Number of values (≥ 1).
        count: u64,
    },
    /// `count` values from `start` to `stop` (both > 0, both included), evenly spaced in logarithm.
    Logspace {
        /// First value (> 0).
        start: f64,
        /// Last value (> 0).
        stop: f64,
        /// Number of values (≥ 1).
        count: u64,
    },
}

impl AxisValues {
    /// Number of values.
    pub fn len(&self) -> u64 {
        match self {
            AxisValues::List(v) => v.len() as u64,
            AxisValues::Linspace { count, .. } | AxisValues::Logspace { count, .. } => *count,
        }
    }

    /// Whether the axis has no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The `i`-th value (`i < len`). Ends are exact; interior values are
    /// `start + i·step` (one rounding, by FMA) with `step = (stop − start)/(count − 1)`,
    /// as numpy's linspace, so `linspace(−1, 5, 7)` is exactly `−1, 0, …, 5`; when
    /// `stop − start` overflows, `start (1 − s) + stop s` with `s = i/(count − 1)`.
    pub fn value(&self, i: u64) -> f64 {
        self.sampler().value(i)
    }

    /// The values ready to be read one by one, each spacing's step formed once.
    pub(crate) fn sampler(&self) -> Sampler<'_> {
        match self {
            AxisValues::List(v) => Sampler::List(v),
            AxisValues::Linspace { start, stop, count } => {
                Sampler::Linear(Interpolation::new(*start, *stop, *count))
            }
            AxisValues::Logspace { start, stop, count } => Sampler::Logarithmic {
                start: *start,
                stop: *stop,
                count: *count,
                logarithm: Interpolation::new(start.ln(), stop.ln(), *count),
            },
        }
    }

    fn validate(&self, axis: usize) -> Result<(), GridError> {
        if self.is_empty() {
            return Err(GridError::Empty { axis });
        }
        match self {
            AxisValues::List(v) => match v.iter().position(|x| !x.is_finite()) {
                Some(index) => Err(GridError::NotFinite { axis, index }),
                None => Ok(()),
            },
            AxisValues::Linspace { start, stop, .. } => {
                if start.is_finite() && stop.is_finite() {
                    Ok(())
                } else {
                    Err(GridError::NotFinite { axis, index: 0 })
                }
            }
            AxisValues::Logspace { start, stop, .. } => {
                if start.is_finite() && stop.is_finite() && *start > 0.0 && *stop > 0.0 {
                    Ok(())
                } else {
                    Err(GridError::LogspaceBounds { axis })
                }
            }
        }
    }
}

/// One axis's values as [`AxisValues::value`] gives them, read by index.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Sampler<'a> {
    List(&'a [f64]),
    Linear(Interpolation),
    /// Interpolated in logarithm, its ends exact.
    Logarithmic {
        start: f64,
        stop: f64,
        count: u64,
        logarithm: Interpolation,
    },
}

impl Sampler<'_> {
    /// The `i`-th value (`i < len`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn value(&self, i: u64) -> f64 {
        match self {
            Sampler::List(v) => v[i as usize],
            Sampler::Linear(linear) => linear.value(i),
            Sampler::Logarithmic {
                start,
                stop,
                count,
                logarithm,
            } => {
                if i == 0 {
                    *start
                } else if i + 1 == *count {
                    *stop
                } else {
                    logarithm.value(i).exp()
                }
            }
        }
    }
}

/// `count` values evenly spaced from `start` to `stop`, its step formed once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Interpolation {
    start: f64,
    stop: f64,
    count: u64,
    intervals: f64,
    /// `(stop − start)/(count − 1)`, not finite where `stop − start` overflows.
    step: f64,
}

impl Interpolation {
    fn new(start: f64, stop: f64, count: u64) -> Self {
        let intervals = count.saturating_sub(1) as f64;
        Interpolation {
            start,
            stop,
            count,
            intervals,
            step: (stop - start) / intervals,
        }
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn value(&self, i: u64) -> f64 {
        let Interpolation {
            start,
            stop,
            count,
            intervals,
            step,
        } = *self;
        if i == 0 {
            return start;
        }
        if i + 1 == count {
            return stop;
        }
        if step.is_finite() {
            return (i as f64).mul_add(step, start);
        }
        let s = i as f64 / intervals;
        start.mul_add(1.0 - s, stop * s)
    }
}

/// How the axes combine into points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Combine {
    /// Every combination; the first axis varies slowest.
    #[default]
    Product,
    /// The `i`-th values of every axis together; all axes have the same length.
    Zip,
}

/// Why a set of axes does not make a sweep.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GridError {
    /// No axes.
    #[error("a sweep needs at least one axis")]
    NoAxes,
    /// An axis with no values.
    #[error("axis {axis} has no values")]
    Empty {
        /// Index of the axis.
        axis: usize,
    },
    /// An axis value is NaN or infinite.
    #[error("axis {axis} has a value that is not a finite number (value {index})")]
    NotFinite {
        /// Index of the axis.
        axis: usize,
        /// Index of the value.
        index: usize,
    },
    /// A logspace bound is not a finite positive number.
    #[error(
        "axis {axis}: logspace bounds must be finite and greater than 0 (they are values, not exponents)"
    )]
    LogspaceBounds {
        /// Index of the axis.
        axis: usize,
    },
    /// Zipped axes of different lengths.
    #[error("combine zip needs axes of equal length: axis {axis} has {len} values, axis 0 has {expected}")]
    ZipLengths {
        /// Index of the axis.
        axis: usize,
        /// Its length.
        len: u64,
        /// The length of axis 0.
        expected: u64,
    },
    /// More points than the limit.
    #[error("the sweep has {} points; the limit is {limit}", count.map_or_else(|| "more than 2^128".to_owned(), |c| c.to_string()))]
    TooManyPoints {
        /// The number of points, `None` when it exceeds `u128`.
        count: Option<u128>,
        /// The limit.
        limit: u64,
    },
    /// A range that is not a slice of the sweep's points.
    #[error(
        "the range [{start}, {end}) is not within the sweep's {points} points (0 ≤ start ≤ end ≤ {points})"
    )]
    RangeOutside {
        /// First point asked for.
        start: u64,
        /// One past the last point asked for.
        end: u64,
        /// The sweep's number of points.
        points: u64,
    },
    /// A range of more points than the limit.
    #[error("the range [{start}, {end}) has {} points; the limit is {limit}", end - start)]
    RangeTooLarge {
        /// First point asked for.
        start: u64,
        /// One past the last point asked for.
        end: u64,
        /// The limit.
        limit: u64,
    },
}

/// The `index`-th of `shards` consecutive ranges that tile `[0, points)`:
/// `[⌊points·index/shards⌋, ⌊points·(index + 1)/shards⌋)`, so lengths differ
/// by at most one. With more shards than points, some ranges are empty.
pub fn shard(points: u64, shards: u64, index: u64) -> std::ops::Range<u64> {
    debug_assert!(shards > 0 && index < shards);
    let at = |i: u64| (u128::from(points) * u128::from(i) / u128::from(shards)) as u64;
    at(index)..at(index + 1)
}

/// Counts the points of `axes` combined by `combine`, refusing more than `limit`
/// with arithmetic that cannot overflow. Checks every axis first.
pub fn count_points(axes: &[&AxisValues], combine: Combine, limit: u64) -> Result<u64, GridError> {
    if axes.is_empty() {
        return Err(GridError::NoAxes);
    }
    for (axis, values) in axes.iter().enumerate() {
        values.validate(axis)?;
    }
    let count: Option<u128> = match combine {
        Combine::Product => axes
            .iter()
            .try_fold(1u128, |acc, a| acc.checked_mul(u128::from(a.len()))),
        Combine::Zip => {
            let expected = axes[0].len();
            if let Some(axis) = axes.iter().position(|a| a.len() != expected) {
                return Err(GridError::ZipLengths {
                    axis,
                    len: axes[axis].len(),
                    expected,
                });
            }
            Some(u128::from(expected))
        }
    };
    match count {
        Some(c) if c <= u128::from(limit) => Ok(c as u64),
        _ => Err(GridError::TooManyPoints { count, limit }),
    }
}

/// Walks the points of a grid in order, keeping each axis's current index
/// (an odometer: no division per point).
#[derive(Debug, Clone)]
pub(crate) struct Odometer {
    lens: Vec<u64>,
    digits: Vec<u64>,
    combine: Combine,
}

impl Odometer {
    /// Positioned at point `start`.
    pub(crate) fn at(lens: Vec<u64>, combine: Combine, start: u64) -> Self {
        let mut digits = vec![0; lens.len()];
        match combine {
            Combine::Zip => digits.iter_mut().for_each(|d| *d = start),
            Combine::Product => {
                let mut rest = start;
                for (d, len) in digits.iter_mut().zip(&lens).rev() {
                    *d = rest % len;
                    rest /= len;
                }
            }
        }
        Odometer {
            lens,
            digits,
            combine,
        }
    }

    /// The current index on each axis.
    pub(crate) fn digits(&self) -> &[u64] {
        &self.digits
    }

    /// Moves to the next point; returns the lowest axis whose index changed.
    pub(crate) fn advance(&mut self) -> usize {
        match self.combine {
            Combine::Zip => {
                self.digits.iter_mut().for_each(|d| *d += 1);
                0
            }
            Combine::Product => {
                for axis in (0..self.digits.len()).rev() {
                    self.digits[axis] += 1;
                    if self.digits[axis] < self.lens[axis] || axis == 0 {
                        return axis;
                    }
                    self.digits[axis] = 0;
                }
                0
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linspace_ends_are_exact_and_interior_is_even() {
        let a = AxisValues::Linspace {
            start: 0.1,
            stop: 0.7,
            count: 7,
        };
        assert_eq!(a.value(0), 0.1);
        assert_eq!(a.value(6), 0.7);
        assert!((a.value(3) - 0.4).abs() < 1e-16);
        let integers = AxisValues::Linspace {
            start: -1.0,
            stop: 5.0,
            count: 7,
        };
        let values: Vec<f64> = (0..7).map(|i| integers.value(i)).collect();
        assert_eq!(values, [-1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
        let huge = AxisValues::Linspace {
            start: -f64::MAX,
            stop: f64::MAX,
            count: 3,
        };
        assert_eq!(huge.value(1), 0.0);
    }

    #[test]
    fn logspace_spans_decades() {
        let a = AxisValues::Logspace {
            start: 1e-3,
            stop: 1e3,
            count: 7,
        };
        assert_eq!(a.value(0), 1e-3);
        assert_eq!(a.value(6), 1e3);
        assert!((a.value(3) - 1.0).abs() < 1e-15);
        let bad = AxisValues::Logspace {
            start: 0.0,
            stop: 1.0,
            count: 2,
        };
        assert_eq!(
            count_points(&[&bad], Combine::Product, 10),
            Err(GridError::LogspaceBounds { axis: 0 })
        );
    }

    #[test]
    fn counts_refuse_overflow_at_once() {
        let big = AxisValues::Linspace {
            start: 0.0,
            stop: 1.0,
            count: u64::MAX,
        };
        let err = count_points(&[&big, &big, &big], Combine::Product, 10_000_000).unwrap_err();
        assert_eq!(
            err,
            GridError::TooManyPoints {
                count: None,
                limit: 10_000_000
            }
        );
        let million = AxisValues::Linspace {
            start: 0.0,
            stop: 1.0,
            count: 1_000_000,
        };
        let err = count_points(&[&million, &million], Combine::Product, 10_000_000).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the sweep has 1000000000000 points; the limit is 10000000"
        );
        assert_eq!(
            count_points(&[&million, &million], Combine::Zip, 10_000_000),
            Ok(1_000_000)
        );
    }

    #[test]
    fn shards_tile_the_points_evenly() {
        for points in [0u64, 1, 7, 100, 1_000_003, u64::MAX] {
            for shards in [1u64, 2, 3, 8, 1000] {
                let mut next = 0;
                let mut lens = Vec::new();
                for i in 0..shards {
                    let r = shard(points, shards, i);
                    assert_eq!(r.start, next);
                    next = r.end;
                    lens.push(r.end - r.start);
                }
                assert_eq!(next, points);
                let (lo, hi) = (lens.iter().min().unwrap(), lens.iter().max().unwrap());
                assert!(hi - lo <= 1, "{points} in {shards}: {lo}..{hi}");
            }
        }
    }

    #[test]
    fn odometer_matches_division() {
        let lens = vec![3, 1, 4, 2];
        let total: u64 = lens.iter().product();
        for start in 0..total {
            let mut o = Odometer::at(lens.clone(), Combine::Product, start);
            for point in start..total {
                let mut rest = point;
                let mut expect = vec![0; lens.len()];
                for (d, len) in expect.iter_mut().zip(&lens).rev() {
                    *d = rest % len;
                    rest /= len;
                }
                assert_eq!(o.digits(), &expect[..]);
                o.advance();
            }
        }
    }
}
