//! Reduced sweeps: `"reduce"` on a sweep answers one JSON summary instead of
//! rows, computed in parallel chunks in one pass with bounded memory
//! ([`crate::sweep::reduce`]), stopped when the client goes away.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::request::{SliceDto, SweepRequest, structure};
use super::stream::Streams;
use crate::http::dto::PrecisionDto;
use crate::http::problem::ApiError;
use crate::impact::Precision;
use crate::quantity::Output;
use crate::sweep::reduce::{Bins, ColumnStats, Extreme, Reduction};
use crate::sweep::{Sweep, SweepCase};

/// Most bins one histogram may have.
pub const MAX_BINS: u32 = 10_000;
/// Points per chunk of a reduction.
const CHUNK_POINTS: u64 = 16_384;

/// What to reduce a sweep to, besides the counts, extremes, sums and means
/// every number output gets.
#[derive(Debug, Clone, Default, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ReduceDto {
    /// Histograms of number outputs, each naming its output by pointer.
    #[serde(default)]
    pub histograms: Vec<HistogramDto>,
}

/// Equal-width bins over `[start, stop]` for one output: a value `x` falls in
/// bin `⌊(x − start)/(stop − start)·bins⌋` (computed in doubles; `stop` in the
/// last bin); values outside are counted as below or above.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct HistogramDto {
    /// Pointer of a number output among the sweep's columns.
    #[schema(example = "/energy/loss")]
    pub output: String,
    /// Lower edge of the first bin.
    pub start: f64,
    /// Upper edge of the last bin (> start).
    pub stop: f64,
    /// Number of bins (1 to 10,000).
    #[schema(minimum = 1, maximum = 10_000)]
    pub bins: u32,
}

/// A sweep reduced: counts, refusals, and per output its summary.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct SweepReduction {
    /// Points reduced (the range's).
    pub points: u64,
    /// Number of points of the whole sweep.
    pub total_points: u64,
    /// The points reduced.
    pub range: SliceDto,
    /// Points with an answer.
    pub answered: u64,
    /// Points without one, by problem type (slug).
    pub refused: BTreeMap<String, RefusedDto>,
    /// Per output pointer, its summary.
    pub outputs: BTreeMap<String, OutputSummary>,
    /// The precision that produced the answers.
    pub precision: PrecisionDto,
    /// SHA-256 of the sweep request without its range (equal for every slice of one sweep).
    pub sweep_sha256: String,
}

/// Refused points of one problem type.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct RefusedDto {
    /// The problem's title, as in a row's `error` column.
    pub title: String,
    /// Number of points.
    pub count: u64,
}

/// The summary of one output: numbers, or names (regimes).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum OutputSummary {
    /// A number output.
    Numbers(NumberSummary),
    /// A name output: how many points have each name.
    Names(NameSummary),
}

/// The summary of a number output over the finite values it took.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct NumberSummary {
    /// Finite values.
    pub count: u64,
    /// The least value and the first point where it occurs (null when count is 0).
    pub min: Option<ExtremeDto>,
    /// The greatest value and the first point where it occurs.
    pub max: Option<ExtremeDto>,
    /// The exact sum, correctly rounded (null when a partial sum overflows a double).
    pub sum: Option<f64>,
    /// Non-overlapping doubles whose exact sum is the sum: concatenate the
    /// parts of several reductions and sum them exactly (`math.fsum`) to merge.
    pub sum_parts: Vec<f64>,
    /// `sum / count` (null when count is 0 or the sum overflows).
    pub mean: Option<f64>,
    /// The histogram, when asked for.
    pub histogram: Option<HistogramCounts>,
}

/// Where an extreme occurs.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct ExtremeDto {
    /// The value.
    pub value: f64,
    /// The point's index in the sweep.
    pub index: u64,
    /// The swept inputs at that point, by axis path.
    #[schema(value_type = Object)]
    pub inputs: BTreeMap<String, f64>,
}

/// Counts per bin.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct HistogramCounts {
    /// Lower edge of the first bin.
    pub start: f64,
    /// Upper edge of the last bin.
    pub stop: f64,
    /// Count of values in each bin.
    pub counts: Vec<u64>,
    /// Values below `start`.
    pub below: u64,
    /// Values above `stop`.
    pub above: u64,
}

/// The count of each name.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct NameSummary {
    /// Points with a name.
    pub count: u64,
    /// Each name and its count.
    pub values: BTreeMap<String, u64>,
}

/// The bins asked for each column, checked against the sweep's columns.
pub(super) fn bins(reduce: &ReduceDto, columns: &[Output]) -> Result<Vec<Option<Bins>>, ApiError> {
    let mut bins = vec![None; columns.len()];
    for (i, h) in reduce.histograms.iter().enumerate() {
        let at = |member: &str| format!("/reduce/histograms/{i}{member}");
        let Some(column) = columns.iter().position(|o| o.path() == h.output) else {
            let known: Vec<&str> = columns
                .iter()
                .filter(|o| !o.is_name())
                .map(|o| o.path())
                .collect();
            return Err(structure(
                at("/output"),
                "Invalid sweep reduction",
                format!(
                    "{:?} is not a number column of this sweep; one of: {}",
                    h.output,
                    known.join(", ")
                ),
            ));
        };
        if columns[column].is_name() {
            return Err(structure(
                at("/output"),
                "Invalid sweep reduction",
                format!(
                    "{} is a name, not a number: its counts per name come without a histogram",
                    h.output
                ),
            ));
        }
        if bins[column].is_some() {
            return Err(structure(
                at("/output"),
                "Invalid sweep reduction",
                format!("{} has a histogram already", h.output),
            ));
        }
        if !(h.start.is_finite() && h.stop.is_finite() && h.stop > h.start && (h.stop - h.start).is_finite())
        {
            return Err(structure(
                at(""),
                "Invalid sweep reduction",
                "start and stop must be finite numbers with start < stop",
            ));
        }
        if !(1..=MAX_BINS).contains(&h.bins) {
            return Err(structure(
                at("/bins"),
                "Invalid sweep reduction",
                format!("bins must be between 1 and {MAX_BINS}"),
            ));
        }
        bins[column] = Some(Bins {
            start: h.start,
            stop: h.stop,
            count: h.bins,
        });
    }
    Ok(bins)
}

/// Sets a flag when dropped: the handler's future dropped (the client went
/// away, or the request timed out) stops the reduction's workers.
pub(super) struct CancelOnDrop(pub(super) Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Release);
    }
}

/// Reduces the sweep on the blocking pool; `None` when cancelled.
pub(super) async fn reduce<C>(
    sweep: Arc<Sweep<C>>,
    bins: Vec<Option<Bins>>,
    names: Vec<bool>,
    streams: &Streams,
) -> Option<Reduction>
where
    C: SweepCase + Send + 'static,
{
    let cancel = Arc::new(AtomicBool::new(false));
    let _guard = CancelOnDrop(cancel.clone());
    let active = streams.start();
    tokio::task::spawn_blocking(move || {
        let _active = active;
        reduce_blocking(&sweep, &bins, &names, || cancel.load(Ordering::Acquire))
    })
    .await
    .ok()
    .flatten()
}

/// Reduces the sweep in parallel chunks, merged in point order; `None` when
/// `stop()` turns true.
pub fn reduce_blocking<C: SweepCase>(
    sweep: &Sweep<C>,
    bins: &[Option<Bins>],
    names: &[bool],
    stop: impl Fn() -> bool + Sync,
) -> Option<Reduction> {
    let mut whole = Reduction::new(names, bins);
    let finished = sweep.run_parallel(
        CHUNK_POINTS,
        |range| {
            (!stop()).then(|| {
                let mut part = Reduction::new(names, bins);
                sweep.for_each_in(range, |row| part.add(&row));
                part
            })
        },
        |part| match part {
            Some(part) => {
                whole.merge(part);
                true
            }
            None => false,
        },
    );
    finished.then_some(whole)
}

/// The reduction as its wire type.
pub(super) fn to_dto<C: SweepCase>(
    reduction: Reduction,
    sweep: &Sweep<C>,
    axis_names: &[&'static str],
    columns: &[Output],
    precision: Precision,
    request: &SweepRequest,
) -> SweepReduction {
    let extreme = |e: Extreme| ExtremeDto {
        value: e.value,
        index: e.index,
        inputs: axis_names.iter().map(|n| (*n).to_owned()).zip(e.inputs).collect(),
    };
    let outputs = columns
        .iter()
        .zip(reduction.columns)
        .map(|(o, stats)| {
            let summary = match stats {
                ColumnStats::Numbers(s) => OutputSummary::Numbers(NumberSummary {
                    count: s.count,
                    sum: s.sum.value(),
                    sum_parts: s.sum.partials().to_vec(),
                    mean: s.mean(),
                    min: s.min.map(extreme),
                    max: s.max.map(extreme),
                    histogram: s.histogram.map(|h| HistogramCounts {
                        start: h.bins.start,
                        stop: h.bins.stop,
                        counts: h.counts,
                        below: h.below,
                        above: h.above,
                    }),
                }),
                ColumnStats::Names(names) => OutputSummary::Names(NameSummary {
                    count: names.iter().map(|(_, n)| n).sum(),
                    values: names.into_iter().map(|(n, c)| (n.to_owned(), c)).collect(),
                }),
            };
            (o.path().to_owned(), summary)
        })
        .collect();
    let range = sweep.range();
    SweepReduction {
        points: reduction.points,
        total_points: sweep.total_points(),
        range: SliceDto {
            start: range.start,
            end: range.end,
        },
        answered: reduction.answered,
        refused: reduction
            .refused
            .into_iter()
            .map(|(slug, title, count)| {
                (
                    slug.to_owned(),
                    RefusedDto {
                        title: title.to_owned(),
                        count,
                    },
                )
            })
            .collect(),
        outputs,
        precision: precision.into(),
        sweep_sha256: request.sweep_hash(),
    }
}
