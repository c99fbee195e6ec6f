//! `POST /v1/sweeps`: one case over a grid of inputs, as a JSON table,
//! streamed NDJSON or CSV, or an SVG plot, chosen by `Accept`.
//!
//! The request is checked whole before anything is computed: the base
//! request of its case, every axis path and output pointer, the point count
//! against its limit. Points are then computed in parallel chunks by
//! [`crate::sweep`] on a blocking thread and handed to the response body in
//! order through a bounded channel, so a streamed sweep holds a few chunks in
//! memory whatever its size, and stops when the client goes away or stops
//! reading.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use axum::Extension;
use axum::body::{Body, Bytes};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use tokio::sync::mpsc;
use utoipa::{IntoResponses, ToSchema};

use super::ServiceConfig;
use super::dto::PrecisionDto;
use super::extract::{ApiJson, parse_value};
use super::impacts::{
    NormalRequest, ObliqueRequest, TangentialRequest, TorsionalRequest, normal_input, oblique_input,
    tangential_input, torsional_input,
};
use super::problem::{ApiError, Problem, input_pointer};
use super::svg;
use crate::error::Input;
use crate::exact::Precision;
use crate::sweep::planar::{PLANAR_INPUTS, PlanarColumn, PlanarSweep};
use crate::sweep::torsional::{TORSIONAL_INPUTS, TorsionalColumn, TorsionalSweep};
use crate::sweep::{Axis, AxisValues, Cell, Combine, GridError, Row, Sweep, SweepCase};

/// Streamed sweeps whose producer is still working.
static ACTIVE_STREAMS: AtomicUsize = AtomicUsize::new(0);

/// The number of streamed sweeps still computing (for tests and diagnostics).
pub fn active_streams() -> usize {
    ACTIVE_STREAMS.load(Ordering::Acquire)
}

/// Counts a producer as active while it lives.
struct ActiveStream;

impl ActiveStream {
    fn start() -> Self {
        ACTIVE_STREAMS.fetch_add(1, Ordering::AcqRel);
        ActiveStream
    }
}

impl Drop for ActiveStream {
    fn drop(&mut self) {
        ACTIVE_STREAMS.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Bytes per chunk of formatted rows: the unit of parallel work and of
/// streaming. A stream holds at most `QUEUED_CHUNKS` chunks in its queue and
/// two per worker thread in flight, so its memory is a few MiB whatever its size.
const CHUNK_BYTES: u64 = 256 * 1024;
/// Bytes a formatted cell takes at most (a shortest-round-trip double and a separator).
const CELL_BYTES: u64 = 24;

impl RowWriter {
    /// Points per chunk: about `CHUNK_BYTES` of output, between 64 and 4,096 rows.
    fn chunk_points(&self) -> u64 {
        (CHUNK_BYTES / (CELL_BYTES * (self.names.len() as u64 + 1))).clamp(64, 4096)
    }
}
/// Chunks queued between the workers and the socket.
const QUEUED_CHUNKS: usize = 4;

/// The physical case a sweep evaluates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CaseDto {
    /// `POST /v1/impacts/normal`.
    Normal,
    /// `POST /v1/impacts/oblique`.
    Oblique,
    /// `POST /v1/impacts/tangential`.
    Tangential,
    /// `POST /v1/impacts/torsional`.
    Torsional,
}

/// How axes combine into points.
#[derive(Debug, Clone, Copy, Default, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CombineDto {
    /// Every combination; the first axis varies slowest.
    #[default]
    Product,
    /// The i-th values of all axes together; axes have equal lengths.
    Zip,
}

/// Evenly spaced values (linearly, or in logarithm for `logspace`), both ends included.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RangeDto {
    /// First value (logspace: > 0; a value, not an exponent).
    pub start: f64,
    /// Last value (logspace: > 0).
    pub stop: f64,
    /// Number of values (≥ 1).
    #[schema(minimum = 1)]
    pub count: u64,
}

/// One axis: the input it sets and exactly one of `values`, `linspace`, `logspace`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct AxisDto {
    /// JSON pointer of a numeric input in `base`, e.g. `/velocity/tangential`.
    #[schema(example = "/velocity/tangential")]
    pub path: String,
    /// Explicit values.
    #[schema(min_items = 1)]
    pub values: Option<Vec<f64>>,
    /// Linearly spaced values.
    pub linspace: Option<RangeDto>,
    /// Logarithmically spaced values.
    pub logspace: Option<RangeDto>,
}

/// A sweep: one case's request with some inputs swept over axes.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "case": "tangential",
    "base": {
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 0.0},
        "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34
    },
    "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 11}}],
    "outputs": ["/contact_velocity/final/tangential", "/regime"]
}))]
pub struct SweepRequest {
    /// The case, which fixes the schema of `base` and the outputs.
    pub case: CaseDto,
    /// A complete request of that case, exactly as its own endpoint takes it.
    #[schema(value_type = Object)]
    pub base: serde_json::Value,
    /// The swept inputs.
    #[schema(min_items = 1)]
    pub axes: Vec<AxisDto>,
    /// `product` (default) or `zip`.
    #[serde(default)]
    pub combine: CombineDto,
    /// JSON pointers into the case's response choosing the columns (a pointer to an
    /// object takes all its members); absent means every output.
    pub outputs: Option<Vec<String>>,
    /// Arithmetic precision: `fast` or `exact`. Absent: the base's `precision`,
    /// else `fast`; when both are given they must agree.
    pub precision: Option<PrecisionDto>,
}

/// A sweep as one JSON table. Columns are the axis paths, the output pointers and
/// `error`; a row holds a number (or a regime name) per column, nulls and the
/// problem's title in `error` where the point has no answer.
#[derive(Debug, Serialize, ToSchema)]
pub struct SweepTable {
    /// Column names.
    pub columns: Vec<String>,
    /// One row per point, in axis order.
    #[schema(schema_with = rows_schema)]
    pub rows: Vec<Vec<serde_json::Value>>,
    /// Number of points.
    pub points: u64,
    /// Number of points without an answer.
    pub errors: u64,
    /// The precision that produced the answers.
    pub precision: PrecisionDto,
}

/// Rows: arrays of cells, each a number, a name (regime, error title) or null.
fn rows_schema() -> utoipa::openapi::schema::Array {
    use utoipa::openapi::schema::{ArrayBuilder, ObjectBuilder, SchemaType, Type};
    let cell = ObjectBuilder::new()
        .schema_type(SchemaType::from_iter([Type::Number, Type::String, Type::Null]))
        .description(Some("A number, a name (regime or error title), or null"));
    ArrayBuilder::new().items(ArrayBuilder::new().items(cell)).build()
}

/// The error responses of the sweep endpoint (all problem+json).
#[derive(IntoResponses)]
#[allow(dead_code)]
pub enum SweepProblems {
    /// The body is not valid JSON.
    #[response(
        status = 400,
        description = "Malformed JSON",
        content_type = "application/problem+json"
    )]
    Malformed(Problem),
    /// The service has an API key and the request lacks it or has another.
    #[response(
        status = 401,
        description = "Missing or wrong bearer token (only when the service runs with an API key)",
        content_type = "application/problem+json"
    )]
    Unauthorized(Problem),
    /// No supported media type is acceptable.
    #[response(
        status = 406,
        description = "None of application/json, application/x-ndjson, text/csv, image/svg+xml is acceptable",
        content_type = "application/problem+json"
    )]
    NotAcceptable(Problem),
    /// The body is larger than the configured limit.
    #[response(
        status = 413,
        description = "Request body too large",
        content_type = "application/problem+json"
    )]
    TooLarge(Problem),
    /// The body is not sent as JSON.
    #[response(
        status = 415,
        description = "Content-Type is not application/json",
        content_type = "application/problem+json"
    )]
    UnsupportedMediaType(Problem),
    /// The sweep's structure is wrong: its base, an axis, an output, or too many points.
    #[response(
        status = 422,
        description = "The base request, an axis, an output pointer or the point count is not acceptable; \
                       `pointer` names the member",
        content_type = "application/problem+json"
    )]
    Unprocessable(Problem),
    /// The server is at its concurrency limit.
    #[response(
        status = 503,
        description = "Overloaded: retry after `Retry-After` seconds",
        content_type = "application/problem+json"
    )]
    Overloaded(Problem),
}

/// Sweep one case over a grid of inputs.
///
/// Formats by `Accept`: `application/json` (default; a buffered table),
/// `application/x-ndjson` and `text/csv` (streamed in point order with bounded
/// memory), `image/svg+xml` (the first output against the first axis, one series
/// per value of the other axes). A point without an answer carries the problem's
/// title in its `error` column; only errors of the sweep's own structure fail it.
#[utoipa::path(
    post,
    path = "/v1/sweeps",
    tag = "sweeps",
    request_body(content = SweepRequest, content_type = "application/json"),
    responses(
        (status = 200, description = "The sweep's points", headers(("x-sweep-points" = u64, description = "Number of points")),
         content(
            (SweepTable = "application/json"),
            (String = "application/x-ndjson"),
            (String = "text/csv"),
            (String = "image/svg+xml"),
        )),
        SweepProblems
    )
)]
pub async fn sweeps(
    Extension(config): Extension<Arc<ServiceConfig>>,
    headers: HeaderMap,
    ApiJson(request): ApiJson<SweepRequest>,
) -> Result<Response, ApiError> {
    let format = negotiate(&headers)?;
    let limit = if format.is_buffered() {
        config.max_buffered_sweep_points
    } else {
        config.max_sweep_points
    };
    let axes = axis_values(&request.axes)?;
    let combine = match request.combine {
        CombineDto::Product => Combine::Product,
        CombineDto::Zip => Combine::Zip,
    };
    let stall = Duration::from_millis(config.sweep_stall_timeout_ms);
    match request.case {
        CaseDto::Torsional => {
            let base: TorsionalRequest = parse_value(request.base, "/base")?;
            let precision = precision(request.precision, base.precision)?;
            let params = axis_params(&request.axes, &TORSIONAL_INPUTS, |_| Ok(()))?;
            let columns = output_columns(request.outputs.as_deref(), TORSIONAL_OUTPUTS)?;
            let point = torsional_input(&base);
            let case = TorsionalSweep::new(&point, &params, columns.iter().map(|(_, c)| *c).collect())
                .with_precision(precision);
            let sweep = build(case, point, params, axes, combine, limit, format)?;
            respond(sweep, names(&columns), format, precision, stall).await
        }
        planar => {
            let (law, point, base_precision) = match planar {
                CaseDto::Normal => {
                    let base = parse_value::<NormalRequest>(request.base, "/base")?;
                    let (law, point) = normal_input(&base)?;
                    (law, point, base.precision)
                }
                CaseDto::Oblique => {
                    let base = parse_value::<ObliqueRequest>(request.base, "/base")?;
                    let (law, point) = oblique_input(&base)?;
                    (law, point, base.precision)
                }
                _ => {
                    let base = parse_value::<TangentialRequest>(request.base, "/base")?;
                    let (law, point) = tangential_input(&base);
                    (law, point, base.precision)
                }
            };
            let precision = precision(request.precision, base_precision)?;
            let params = axis_params(&request.axes, &PLANAR_INPUTS, |p| {
                if law.reads(p) {
                    Ok(())
                } else {
                    Err(format!(
                        "the base describes {}, which does not read it",
                        law.describe()
                    ))
                }
            })?;
            let columns = output_columns(request.outputs.as_deref(), PLANAR_OUTPUTS)?;
            let case = PlanarSweep::new(law, &point, &params, columns.iter().map(|(_, c)| *c).collect())
                .with_precision(precision);
            let sweep = build(case, point, params, axes, combine, limit, format)?;
            respond(sweep, names(&columns), format, precision, stall).await
        }
    }
}

/// The sweep's precision: its own, else the base's (which defaults to `fast`).
/// The base's is `fast` both when absent and when given as `fast`, so only an
/// explicit disagreement with an `exact` base is refused.
fn precision(sweep: Option<PrecisionDto>, base: PrecisionDto) -> Result<Precision, ApiError> {
    match sweep {
        Some(p) if base == PrecisionDto::Exact && p != base => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "precision",
            "Conflicting precision",
            "the sweep's precision differs from the base's: give it once",
        )
        .at("/precision")),
        Some(p) => Ok(p.into()),
        None => Ok(base.into()),
    }
}

/// Outputs of the planar cases, by pointer into their responses.
const PLANAR_OUTPUTS: &[(&str, PlanarColumn)] = &[
    ("/final_velocity/normal", PlanarColumn::FinalNormalVelocity),
    (
        "/final_velocity/tangential",
        PlanarColumn::FinalTangentialVelocity,
    ),
    ("/final_velocity/angular", PlanarColumn::FinalAngularVelocity),
    (
        "/contact_velocity/initial/normal",
        PlanarColumn::InitialContactNormal,
    ),
    (
        "/contact_velocity/initial/tangential",
        PlanarColumn::InitialContactTangential,
    ),
    ("/contact_velocity/final/normal", PlanarColumn::FinalContactNormal),
    (
        "/contact_velocity/final/tangential",
        PlanarColumn::FinalContactTangential,
    ),
    ("/impulse/normal", PlanarColumn::NormalImpulse),
    ("/impulse/tangential", PlanarColumn::TangentialImpulse),
    ("/impulse_ratio", PlanarColumn::ImpulseRatio),
    ("/critical_impulse_ratio", PlanarColumn::CriticalImpulseRatio),
    ("/restitution", PlanarColumn::Restitution),
    ("/kinetic_restitution", PlanarColumn::KineticRestitution),
    ("/regime", PlanarColumn::Regime),
    ("/energy/initial", PlanarColumn::InitialEnergy),
    ("/energy/final", PlanarColumn::FinalEnergy),
    ("/energy/loss", PlanarColumn::EnergyLoss),
    ("/energy/max_loss", PlanarColumn::MaxEnergyLoss),
    ("/energy/normalized_loss", PlanarColumn::NormalizedEnergyLoss),
];

/// Outputs of the torsional case.
const TORSIONAL_OUTPUTS: &[(&str, TorsionalColumn)] = &[
    ("/final_velocity/normal", TorsionalColumn::FinalNormalVelocity),
    ("/final_velocity/spin", TorsionalColumn::FinalSpin),
    ("/impulse/normal", TorsionalColumn::NormalImpulse),
    ("/impulse/torsional", TorsionalColumn::TorsionalImpulse),
    ("/regime", TorsionalColumn::Regime),
    ("/switch_spin", TorsionalColumn::SwitchSpin),
    ("/energy/initial", TorsionalColumn::InitialEnergy),
    ("/energy/final", TorsionalColumn::FinalEnergy),
    ("/energy/loss", TorsionalColumn::EnergyLoss),
];

fn structure(pointer: impl Into<String>, title: &str, detail: impl Into<String>) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "invalid-sweep", title, detail).at(pointer)
}

fn axis_values(axes: &[AxisDto]) -> Result<Vec<AxisValues>, ApiError> {
    if axes.is_empty() {
        return Err(structure(
            "/axes",
            "Invalid sweep axis",
            "a sweep needs at least one axis",
        ));
    }
    axes.iter()
        .enumerate()
        .map(|(i, axis)| match (&axis.values, axis.linspace, axis.logspace) {
            (Some(values), None, None) => Ok(AxisValues::List(values.clone())),
            (None, Some(r), None) => Ok(AxisValues::Linspace {
                start: r.start,
                stop: r.stop,
                count: r.count,
            }),
            (None, None, Some(r)) => Ok(AxisValues::Logspace {
                start: r.start,
                stop: r.stop,
                count: r.count,
            }),
            _ => Err(structure(
                format!("/axes/{i}"),
                "Invalid sweep axis",
                "give exactly one of values, linspace or logspace",
            )),
        })
        .collect()
}

/// The input each axis sets: its path must be the pointer of one of `inputs`
/// (the same pointers the errors of the case's own endpoint use).
fn axis_params(
    axes: &[AxisDto],
    inputs: &[Input],
    read: impl Fn(Input) -> Result<(), String>,
) -> Result<Vec<Input>, ApiError> {
    let mut params = Vec::with_capacity(axes.len());
    for (i, axis) in axes.iter().enumerate() {
        let pointer = format!("/axes/{i}/path");
        if axes[..i].iter().any(|a| a.path == axis.path) {
            return Err(structure(
                pointer,
                "Invalid sweep axis",
                format!("{} is swept by an earlier axis", axis.path),
            ));
        }
        let Some(&param) = inputs.iter().find(|&&input| input_pointer(input) == axis.path) else {
            let known: Vec<&str> = inputs.iter().map(|&input| input_pointer(input)).collect();
            return Err(structure(
                pointer,
                "Invalid sweep axis",
                format!(
                    "{:?} names no numeric input of this case; one of: {}",
                    axis.path,
                    known.join(", ")
                ),
            ));
        };
        read(param).map_err(|why| {
            structure(
                pointer.clone(),
                "Invalid sweep axis",
                format!("{} is not an input here: {why}", axis.path),
            )
        })?;
        params.push(param);
    }
    Ok(params)
}

/// Chosen columns: every table entry equal to a pointer or under it.
fn output_columns<C: Copy>(
    outputs: Option<&[String]>,
    table: &[(&'static str, C)],
) -> Result<Vec<(&'static str, C)>, ApiError> {
    let Some(outputs) = outputs else {
        return Ok(table.to_vec());
    };
    if outputs.is_empty() {
        return Err(structure(
            "/outputs",
            "Invalid sweep output",
            "give at least one output, or leave outputs out for all",
        ));
    }
    let mut columns = Vec::new();
    for (i, pointer) in outputs.iter().enumerate() {
        let matched: Vec<_> = table
            .iter()
            .filter(|(name, _)| {
                pointer.is_empty()
                    || *name == pointer
                    || name
                        .strip_prefix(pointer.as_str())
                        .is_some_and(|rest| rest.starts_with('/'))
            })
            .copied()
            .collect();
        if matched.is_empty() {
            let known: Vec<&str> = table.iter().map(|(name, _)| *name).collect();
            return Err(structure(
                format!("/outputs/{i}"),
                "Invalid sweep output",
                format!(
                    "{pointer:?} names no output of this case; one of: {}",
                    known.join(", ")
                ),
            ));
        }
        columns.extend(matched);
    }
    Ok(columns)
}

fn names<C>(columns: &[(&'static str, C)]) -> Vec<&'static str> {
    columns.iter().map(|(name, _)| *name).collect()
}

fn build<C: SweepCase>(
    case: C,
    base: C::Point,
    params: Vec<C::Param>,
    values: Vec<AxisValues>,
    combine: Combine,
    limit: u64,
    format: Format,
) -> Result<Sweep<C>, ApiError> {
    let axes = params
        .into_iter()
        .zip(values)
        .map(|(param, values)| Axis { param, values })
        .collect();
    Sweep::new(case, base, axes, combine, limit).map_err(|error| {
        let pointer = match &error {
            GridError::NoAxes | GridError::TooManyPoints { .. } => "/axes".to_owned(),
            GridError::Empty { axis } | GridError::ZipLengths { axis, .. } => format!("/axes/{axis}"),
            GridError::NotFinite { axis, index } => format!("/axes/{axis}/values/{index}"),
            GridError::LogspaceBounds { axis } => format!("/axes/{axis}/logspace"),
        };
        let mut detail = error.to_string();
        if matches!(error, GridError::TooManyPoints { .. }) && format.is_buffered() {
            detail.push_str(
                " for application/json and image/svg+xml; text/csv and application/x-ndjson stream larger sweeps",
            );
        }
        let title = if matches!(error, GridError::TooManyPoints { .. }) {
            "Sweep too large"
        } else {
            "Invalid sweep axis"
        };
        structure(pointer, title, detail)
    })
}

/// A response format of the sweep endpoint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `application/json`: one buffered table.
    Json,
    /// `application/x-ndjson`: one object per point, streamed.
    Ndjson,
    /// `text/csv`: a header row and one row per point, streamed.
    Csv,
    /// `image/svg+xml`: a buffered plot.
    Svg,
}

impl Format {
    fn is_buffered(self) -> bool {
        matches!(self, Format::Json | Format::Svg)
    }

    fn content_type(self) -> &'static str {
        match self {
            Format::Json => "application/json",
            Format::Ndjson => "application/x-ndjson",
            Format::Csv => "text/csv; charset=utf-8; header=present",
            Format::Svg => "image/svg+xml",
        }
    }
}

/// Picks the format from `Accept`: the acceptable range with the highest
/// quality wins; `*/*`, `application/*` or no header mean JSON.
pub fn negotiate(headers: &HeaderMap) -> Result<Format, ApiError> {
    let mut ranges: Vec<(f32, Format)> = Vec::new();
    let mut any = false;
    for value in headers.get_all(header::ACCEPT) {
        let Ok(text) = value.to_str() else { continue };
        for entry in text.split(',') {
            let mut parts = entry.split(';');
            let range = parts.next().unwrap_or("").trim().to_ascii_lowercase();
            if range.is_empty() {
                continue;
            }
            any = true;
            let quality = parts
                .filter_map(|p| p.trim().strip_prefix("q="))
                .find_map(|q| q.trim().parse::<f32>().ok())
                .unwrap_or(1.0);
            let format = match range.as_str() {
                "application/json" | "application/*" | "*/*" => Format::Json,
                "application/x-ndjson" | "application/jsonl" => Format::Ndjson,
                "text/csv" | "text/*" => Format::Csv,
                "image/svg+xml" | "image/*" => Format::Svg,
                _ => continue,
            };
            if quality > 0.0 {
                ranges.push((quality, format));
            }
        }
    }
    if !any {
        return Ok(Format::Json);
    }
    // Stable: among equal qualities the first listed wins.
    ranges.sort_by(|a, b| b.0.total_cmp(&a.0));
    ranges.first().map(|&(_, f)| f).ok_or_else(|| {
        ApiError::new(
            StatusCode::NOT_ACCEPTABLE,
            "not-acceptable",
            "Not acceptable",
            "a sweep is available as application/json, application/x-ndjson, text/csv or image/svg+xml",
        )
    })
}

/// Writes one point in a format.
#[derive(Clone)]
struct RowWriter {
    format: Format,
    precision: Precision,
    /// Axis paths, then output pointers.
    names: Vec<&'static str>,
}

impl RowWriter {
    fn header(&self) -> Vec<u8> {
        let mut out = Vec::new();
        match self.format {
            Format::Csv => {
                for name in &self.names {
                    out.extend_from_slice(name.as_bytes());
                    out.push(b',');
                }
                out.extend_from_slice(b"error\r\n");
            }
            Format::Json => {
                out.extend_from_slice(b"{\"columns\":[");
                for name in &self.names {
                    push_string(&mut out, name);
                    out.push(b',');
                }
                out.extend_from_slice(b"\"error\"],\"rows\":[");
            }
            Format::Ndjson | Format::Svg => {}
        }
        out
    }

    fn row(&self, out: &mut Vec<u8>, row: &Row<'_>) {
        let mut number = ryu::Buffer::new();
        let mut cells = row
            .axis_values
            .iter()
            .map(|&v| Some(Cell::Number(v)))
            .chain(Cells::new(row, self.names.len() - row.axis_values.len()));
        let error = row.outcome.err().map(|e| e.title());
        match self.format {
            Format::Csv => {
                for cell in cells.by_ref() {
                    match cell {
                        Some(Cell::Number(x)) => push_number(out, &mut number, x),
                        Some(Cell::Text(s)) => out.extend_from_slice(s.as_bytes()),
                        None => {}
                    }
                    out.push(b',');
                }
                if let Some(title) = error {
                    out.extend_from_slice(title.as_bytes());
                }
                out.extend_from_slice(b"\r\n");
            }
            Format::Json => {
                if row.index > 0 {
                    out.push(b',');
                }
                out.push(b'[');
                for cell in cells.by_ref() {
                    push_cell(out, &mut number, cell);
                    out.push(b',');
                }
                push_error(out, error);
                out.push(b']');
            }
            Format::Ndjson => {
                out.push(b'{');
                for (name, cell) in self.names.iter().zip(cells.by_ref()) {
                    push_string(out, name);
                    out.push(b':');
                    push_cell(out, &mut number, cell);
                    out.push(b',');
                }
                out.extend_from_slice(b"\"error\":");
                push_error(out, error);
                out.extend_from_slice(b"}\n");
            }
            Format::Svg => {}
        }
    }
}

/// The output cells of a row, `None` for each when the point has no answer.
struct Cells<'a> {
    cells: Result<std::slice::Iter<'a, Cell>, std::ops::Range<usize>>,
}

impl<'a> Cells<'a> {
    fn new(row: &Row<'a>, outputs: usize) -> Self {
        Cells {
            cells: row.outcome.map(|c| c.iter()).map_err(|_| 0..outputs),
        }
    }
}

impl Iterator for Cells<'_> {
    type Item = Option<Cell>;
    fn next(&mut self) -> Option<Option<Cell>> {
        match &mut self.cells {
            Ok(iter) => iter.next().map(|c| Some(*c)),
            Err(range) => range.next().map(|_| None),
        }
    }
}

fn push_number(out: &mut Vec<u8>, buffer: &mut ryu::Buffer, x: f64) {
    if x.is_finite() {
        out.extend_from_slice(buffer.format_finite(x).as_bytes());
    }
}

fn push_cell(out: &mut Vec<u8>, buffer: &mut ryu::Buffer, cell: Option<Cell>) {
    match cell {
        Some(Cell::Number(x)) if x.is_finite() => push_number(out, buffer, x),
        Some(Cell::Text(s)) => push_string(out, s),
        _ => out.extend_from_slice(b"null"),
    }
}

fn push_error(out: &mut Vec<u8>, error: Option<&str>) {
    match error {
        Some(title) => push_string(out, title),
        None => out.extend_from_slice(b"null"),
    }
}

fn push_string(out: &mut Vec<u8>, s: &str) {
    // Names and titles are fixed ASCII-safe strings; serde_json escapes anyway.
    let _ = serde_json::to_writer(&mut *out, s);
}

/// Produces the response: buffered (JSON, SVG) or streamed (CSV, NDJSON).
async fn respond<C>(
    sweep: Sweep<C>,
    outputs: Vec<&'static str>,
    format: Format,
    precision: Precision,
    stall: Duration,
) -> Result<Response, ApiError>
where
    C: SweepCase<Param = Input> + Send + 'static,
{
    let axis_names: Vec<&'static str> = sweep.axes().iter().map(|a| input_pointer(a.param)).collect();
    let mut names = axis_names.clone();
    names.extend(&outputs);
    let points = sweep.points();
    let writer = RowWriter {
        format,
        precision,
        names,
    };
    let body = match format {
        Format::Svg => {
            let plot = svg::Plot::check(&axis_names, &outputs, &sweep)?;
            let sweep = Arc::new(sweep);
            let text = tokio::task::spawn_blocking(move || plot.render(&sweep))
                .await
                .map_err(|_| internal())?;
            Body::from(text)
        }
        Format::Json => {
            let sweep = Arc::new(sweep);
            let text = tokio::task::spawn_blocking(move || table(&sweep, &writer))
                .await
                .map_err(|_| internal())?;
            Body::from(text)
        }
        Format::Csv | Format::Ndjson => stream(Arc::new(sweep), writer, stall),
    };
    let mut response = (StatusCode::OK, body).into_response();
    let headers = response.headers_mut();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(format.content_type()),
    );
    headers.insert("x-sweep-points", HeaderValue::from(points));
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

/// The JSON table, computed in parallel chunks.
fn table<C: SweepCase>(sweep: &Sweep<C>, writer: &RowWriter) -> Vec<u8> {
    let mut out = writer.header();
    let mut errors = 0u64;
    sweep.run_parallel(
        writer.chunk_points(),
        |range| chunk(sweep, writer, range),
        |(bytes, failed)| {
            out.extend_from_slice(&bytes);
            errors += failed;
            true
        },
    );
    out.extend_from_slice(
        format!(
            "],\"points\":{},\"errors\":{errors},\"precision\":\"{}\"}}",
            sweep.points(),
            writer.precision.as_str()
        )
        .as_bytes(),
    );
    out
}

/// One chunk of rows and its number of failed points.
fn chunk<C: SweepCase>(sweep: &Sweep<C>, writer: &RowWriter, range: std::ops::Range<u64>) -> (Vec<u8>, u64) {
    let mut out =
        Vec::with_capacity(((range.end - range.start) * CELL_BYTES) as usize * (writer.names.len() + 1));
    let mut failed = 0;
    sweep.for_each_in(range, |row| {
        failed += u64::from(row.outcome.is_err());
        writer.row(&mut out, &row);
    });
    (out, failed)
}

/// Streams the rows through a bounded channel. The producer stops when the
/// client disconnects (the channel closes) or stops reading for `stall`; an
/// incomplete stream ends with an error so the client sees a broken body, not
/// a short one.
fn stream<C>(sweep: Arc<Sweep<C>>, writer: RowWriter, stall: Duration) -> Body
where
    C: SweepCase + Send + 'static,
{
    let (tx, rx) = mpsc::channel::<Bytes>(QUEUED_CHUNKS);
    let complete = Arc::new(AtomicBool::new(false));
    let done = complete.clone();
    let runtime = tokio::runtime::Handle::current();
    let active = ActiveStream::start();
    tokio::task::spawn_blocking(move || {
        let _active = active;
        let send = |bytes: Vec<u8>| {
            runtime
                .block_on(tx.send_timeout(Bytes::from(bytes), stall))
                .is_ok()
        };
        if !send(writer.header()) {
            return;
        }
        let finished = sweep.run_parallel(
            writer.chunk_points(),
            |range| {
                if tx.is_closed() {
                    return Vec::new();
                }
                chunk(&sweep, &writer, range).0
            },
            &send,
        );
        if finished {
            done.store(true, Ordering::Release);
        } else {
            tracing::info!("sweep stream stopped: the client went away or stopped reading");
        }
    });
    let stream = futures_util::stream::unfold((rx, complete), |(mut rx, complete)| async move {
        match rx.recv().await {
            Some(bytes) => Some((Ok::<_, std::io::Error>(bytes), (rx, complete))),
            None if complete.load(Ordering::Acquire) => None,
            None => {
                complete.store(true, Ordering::Release);
                Some((
                    Err(std::io::Error::other("sweep stopped before its end")),
                    (rx, complete),
                ))
            }
        }
    });
    Body::from_stream(stream)
}
