//! `POST /v1/sweeps`: one case over a grid of inputs, as a JSON table,
//! streamed NDJSON or CSV, or an SVG plot, chosen by `Accept`.
//!
//! The request is checked whole before anything is computed (`request.rs`):
//! the base request of its case, every axis path and output pointer, the point
//! count against its limit. Points are then computed in parallel chunks by
//! [`crate::sweep`]: buffered into a table (`encode.rs`) or a plot
//! (`plot.rs`), or streamed (`stream.rs`) in the format `Accept` chose
//! (`negotiate.rs`).

mod arrow;
mod cases;
mod encode;
mod negotiate;
mod plan;
mod plot;
mod reduce;
mod request;
mod stream;

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use axum::extract::{FromRef, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use self::arrow::{ArrowLayout, ArrowSink};
pub(crate) use self::cases::on_sweep;
pub use self::cases::{AnySweep, CaseDto, build};
use self::encode::{RowWriter, table};
pub use self::negotiate::{Format, negotiate};
pub use self::plan::{MAX_SHARDS, PlanRequest, SweepPlan, split};
use self::reduce::CancelOnDrop;
pub use self::reduce::{
    ExtremeDto, HistogramCounts, HistogramDto, MAX_BINS, NameSummary, NumberSummary, OutputSummary,
    ReduceDto, RefusedDto, SweepReduction, reduce_blocking,
};
pub use self::request::{AxisDto, CombineDto, RangeDto, SliceDto, SweepRequest, SweepTable};
pub use self::stream::Streams;
use self::stream::stream;
use super::ServiceConfig;
use super::extract::ApiJson;
use super::problem::{ApiError, Problem, Problems};
use super::telemetry::Telemetry;
use crate::impact::{Case, Precision};
use crate::sweep::{CaseSweep, Sweep};
use prometheus_client::metrics::counter::Counter;

/// The sweep endpoints (`/v1/sweeps`, `/v1/sweeps/plan`), with their OpenAPI operations.
pub fn router<S>() -> OpenApiRouter<S>
where
    S: Clone + Send + Sync + 'static,
    Arc<ServiceConfig>: FromRef<S>,
    Streams: FromRef<S>,
    Telemetry: FromRef<S>,
{
    OpenApiRouter::new()
        .routes(routes!(sweeps))
        .routes(routes!(plan::plan))
}

/// Sweep one case over a grid of inputs.
///
/// Formats by `Accept`: `application/json` (default; a buffered table),
/// `application/x-ndjson`, `text/csv` and `application/vnd.apache.arrow.stream`
/// (an Arrow IPC stream: one record batch per chunk, f64 columns, dictionary
/// regime and error names, nulls where a point has no answer; the schema's
/// metadata holds the request's hash and the model version) streamed in point
/// order with bounded memory, `image/svg+xml` (the first output against the first axis, one series
/// per value of the other axes). A point without an answer carries the problem's
/// title in its `error` column; only errors of the sweep's own structure fail it.
#[utoipa::path(
    post,
    path = "/v1/sweeps",
    tag = "sweeps",
    request_body(content = SweepRequest, content_type = "application/json"),
    responses(
        (status = 200, description = "The sweep's points", headers(
            ("x-sweep-points" = u64, description = "Number of points in this answer"),
            ("x-sweep-total-points" = u64, description = "Number of points of the whole sweep"),
            ("x-sweep-range" = String, description = "The answer's points as `start-end` (end excluded)"),
         ),
         content(
            (SweepJson = "application/json"),
            (String = "application/x-ndjson"),
            (String = "text/csv"),
            (String = "image/svg+xml"),
            (Vec<u8> = "application/vnd.apache.arrow.stream"),
        )),

        (status = 406, description = "None of application/json, application/x-ndjson, text/csv, application/vnd.apache.arrow.stream, image/svg+xml is acceptable",
         body = Problem, content_type = "application/problem+json"),
        Problems
    )
)]
pub async fn sweeps(
    State(config): State<Arc<ServiceConfig>>,
    State(streams): State<Streams>,
    State(telemetry): State<Telemetry>,
    headers: HeaderMap,
    ApiJson(request): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    if request.reduce.is_some() && format != Format::Json {
        return Err(ApiError::new(
            StatusCode::NOT_ACCEPTABLE,
            "not-acceptable",
            "Not acceptable",
            "a reduced sweep is answered as application/json",
        ));
    }
    let limit = if format.is_buffered() && request.reduce.is_none() {
        config.max_buffered_sweep_points
    } else {
        config.max_sweep_points
    };
    let stall = Duration::from_millis(config.sweep_stall_timeout_ms);
    let (sweep, precision) = build(&request, limit, format)?;
    let computed = Some(telemetry.sweep_counter(request.case.as_str(), precision.as_str()));
    let answer = Answer {
        format,
        precision,
        stall,
        request: &request,
        computed,
    };
    on_sweep!(sweep, s => respond(s, answer, &streams).await)
}

/// The JSON answers of a sweep: its table, or with `reduce` its summary.
#[derive(Debug, serde::Serialize, utoipa::ToSchema)]
#[serde(untagged)]
pub enum SweepJson {
    /// Every row.
    Table(SweepTable),
    /// The summary asked for by `reduce`.
    Reduction(SweepReduction),
}

/// How to answer a checked sweep.
struct Answer<'a> {
    format: Format,
    precision: Precision,
    stall: Duration,
    request: &'a SweepRequest,
    /// Counts the points computed, for the metrics.
    computed: Option<Counter>,
}

/// The Arrow schema's metadata: what the stream is a slice of.
fn arrow_metadata(
    request: &SweepRequest,
    precision: Precision,
    total: u64,
    range: &std::ops::Range<u64>,
) -> HashMap<String, String> {
    [
        ("restitution.sweep_sha256", request.sweep_hash()),
        ("restitution.model_version", env!("CARGO_PKG_VERSION").to_owned()),
        ("restitution.precision", precision.as_str().to_owned()),
        ("restitution.total_points", total.to_string()),
        ("restitution.range_start", range.start.to_string()),
        ("restitution.range_end", range.end.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v))
    .collect()
}

/// Produces the response: buffered (JSON, SVG) or streamed (CSV, NDJSON, Arrow).
async fn respond<C: Case>(
    sweep: Sweep<CaseSweep<C>>,
    answer: Answer<'_>,
    streams: &Streams,
) -> Result<Response, ApiError> {
    let Answer {
        format,
        precision,
        stall,
        request,
        computed,
    } = answer;
    let computed = computed.unwrap_or_default();
    // Counts a chunk's points as the workers finish computing it.
    let counted = {
        let computed = computed.clone();
        move |range: &std::ops::Range<u64>| {
            computed.inc_by(range.end - range.start);
        }
    };
    let axis_names: Vec<&'static str> = sweep.axes().iter().map(|a| a.param.path()).collect();
    let outputs: Vec<&'static str> = sweep.case().columns().iter().map(|o| o.path()).collect();
    let mut names = axis_names.clone();
    names.extend(&outputs);
    let points = sweep.points();
    let range = sweep.range();
    let total = sweep.total_points();
    let writer = RowWriter {
        format,
        precision,
        names,
        first: range.start,
    };
    if let Some(reduce) = &request.reduce {
        let columns = sweep.case().columns().to_vec();
        let bins = reduce::bins(reduce, &columns)?;
        let names: Vec<bool> = columns.iter().map(|o| o.is_name()).collect();
        let sweep = Arc::new(sweep);
        let reduction = reduce::reduce(sweep.clone(), bins, names, streams)
            .await
            .ok_or_else(internal)?;
        computed.inc_by(points);
        let dto = reduce::to_dto(reduction, &sweep, &axis_names, &columns, precision, request);
        let mut response = axum::Json(dto).into_response();
        response
            .headers_mut()
            .insert("x-sweep-points", HeaderValue::from(points));
        return Ok(response);
    }
    let body = match format {
        Format::Svg => {
            let axes: Vec<_> = sweep.axes().iter().map(|a| a.param).collect();
            let plot = plot::Plot::check(&axes, sweep.case().columns(), &sweep)?;
            let (permit, cancel) = (streams.buffered_permit()?, Arc::new(AtomicBool::new(false)));
            let _cancel_on_drop = CancelOnDrop(cancel.clone());
            let sweep = Arc::new(sweep);
            let (text, permit) = tokio::task::spawn_blocking(move || {
                (plot.render(&sweep, || cancel.load(Ordering::Acquire)), permit)
            })
            .await
            .map_err(|_| internal())?;
            computed.inc_by(points);
            stream::buffered(text.into_bytes(), stall, permit)
        }
        Format::Json => {
            // Held until the computation ends, and stopped at its next chunk
            // when the request is dropped (a timeout, a client gone).
            let (permit, cancel) = (streams.buffered_permit()?, Arc::new(AtomicBool::new(false)));
            let _cancel_on_drop = CancelOnDrop(cancel.clone());
            let sweep = Arc::new(sweep);
            let (text, permit) = tokio::task::spawn_blocking(move || {
                (table(&sweep, &writer, || cancel.load(Ordering::Acquire)), permit)
            })
            .await
            .map_err(|_| internal())?;
            computed.inc_by(points);
            stream::buffered(text, stall, permit)
        }
        Format::Csv | Format::Ndjson => {
            let chunk_points = writer.chunk_points();
            let rows = writer.clone();
            let produce = move |sweep: &Sweep<_>, range| {
                counted(&range);
                encode::chunk(sweep, &rows, range).0
            };
            let permit = streams.streamed_permit()?;
            stream(
                Arc::new(sweep),
                chunk_points,
                produce,
                writer,
                stall,
                streams,
                permit,
            )
        }
        Format::Arrow => {
            let metadata = arrow_metadata(request, precision, total, &range);
            let layout = Arc::new(ArrowLayout::new(&axis_names, sweep.case().columns(), metadata));
            let chunk_points = layout.chunk_points();
            let sink = ArrowSink::new(layout.clone());
            let produce = move |sweep: &Sweep<_>, range| {
                counted(&range);
                layout.chunk(sweep, range)
            };
            let permit = streams.streamed_permit()?;
            stream(
                Arc::new(sweep),
                chunk_points,
                produce,
                sink,
                stall,
                streams,
                permit,
            )
        }
    };
    let mut response = (StatusCode::OK, body).into_response();
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(format.content_type()),
    );
    headers.insert("x-sweep-points", HeaderValue::from(points));
    headers.insert("x-sweep-total-points", HeaderValue::from(total));
    if let Ok(value) = HeaderValue::from_str(&format!("{}-{}", range.start, range.end)) {
        headers.insert("x-sweep-range", value);
    }
    headers.insert("x-precision", HeaderValue::from_static(precision.as_str()));
    Ok(response)
}

fn internal() -> ApiError {
    ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        "internal",
        "Internal error",
        "the sweep failed",
    )
}
