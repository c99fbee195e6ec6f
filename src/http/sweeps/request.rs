//! The sweep request: its wire types and their checks (base, axes, outputs,
//! precision, point count), each failure naming its member.

use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::cases::CaseDto;
use super::negotiate::Format;
use crate::http::dto::PrecisionDto;
use crate::http::problem::ApiError;
use crate::impact::{Case, Precision};
use crate::quantity::{Input, Output};
use crate::sweep::{Axis, AxisValues, CaseSweep, CaseSweepError, GridError, Sweep};

/// How axes combine into points.
#[derive(Debug, Clone, Copy, Default, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CombineDto {
    /// Every combination; the first axis varies slowest.
    #[default]
    Product,
    /// The i-th values of all axes together; axes have equal lengths.
    Zip,
}

/// Evenly spaced values (linearly, or in logarithm for `logspace`), both ends included.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
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

/// A slice of a sweep's points: the points with indices `start ≤ i < end` in
/// the sweep's own order (the first axis varies slowest). Ranges that tile
/// `[0, N)` give rows that concatenate to exactly the whole sweep's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SliceDto {
    /// Index of the first point (from 0).
    pub start: u64,
    /// Index one past the last point (≤ the sweep's number of points).
    pub end: u64,
}

/// One axis: the input it sets and exactly one of `values`, `linspace`, `logspace`.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
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
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
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
    /// object takes all its members); absent means every output. Each column
    /// once: an entry naming only columns already chosen is refused.
    pub outputs: Option<Vec<String>>,
    /// Arithmetic precision: `fast` or `exact`. Absent: the base's `precision`,
    /// else `fast`; when both are given they must agree.
    pub precision: Option<PrecisionDto>,
    /// Only these points of the sweep (all when absent). The point limit applies
    /// to the range, so a grid larger than the limit is computed in slices;
    /// `POST /v1/sweeps/plan` gives the ranges.
    pub range: Option<SliceDto>,
    /// Answer a summary instead of rows (`application/json`): per output the
    /// count, minimum and maximum with their points, exact sum and mean,
    /// optional histograms; names counted; refused points counted by problem.
    /// Computed in one pass with bounded memory, so the streamed point limit
    /// applies.
    pub reduce: Option<super::reduce::ReduceDto>,
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
    /// Number of points in this answer (its range's).
    pub points: u64,
    /// Number of points of the whole sweep.
    pub total_points: u64,
    /// The points this answer holds.
    pub range: SliceDto,
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

/// The sweep's precision: its own, else the base's (which defaults to `fast`).
/// The base's is `fast` both when absent and when given as `fast`, so only an
/// explicit disagreement with an `exact` base is refused.
pub(super) fn precision(sweep: Option<PrecisionDto>, base: PrecisionDto) -> Result<Precision, ApiError> {
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

pub(super) fn structure(pointer: impl Into<String>, title: &str, detail: impl Into<String>) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "invalid-sweep", title, detail).at(pointer)
}

pub(super) fn axis_values(axes: &[AxisDto]) -> Result<Vec<AxisValues>, ApiError> {
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

/// The input each axis sets: its path must be the path of an input the base
/// impact reads (the same pointers the errors of the case's own endpoint use).
pub(super) fn axis_inputs<C: Case>(axes: &[AxisDto], base: &C) -> Result<Vec<Input>, ApiError> {
    let reads = base.reads();
    let known = || reads.iter().map(|i| i.path()).collect::<Vec<_>>().join(", ");
    let mut inputs = Vec::with_capacity(axes.len());
    for (i, axis) in axes.iter().enumerate() {
        let pointer = format!("/axes/{i}/path");
        if axes[..i].iter().any(|a| a.path == axis.path) {
            return Err(structure(
                pointer,
                "Invalid sweep axis",
                format!("{} is swept by an earlier axis", axis.path),
            ));
        }
        match C::INPUTS.iter().find(|input| input.path() == axis.path) {
            Some(&input) if reads.contains(&input) => inputs.push(input),
            Some(_) => {
                return Err(structure(
                    pointer,
                    "Invalid sweep axis",
                    format!(
                        "{} is not an input here: the base describes {}, which does not read it; one of: {}",
                        axis.path,
                        base.describe(),
                        known()
                    ),
                ));
            }
            None => {
                return Err(structure(
                    pointer,
                    "Invalid sweep axis",
                    format!(
                        "{:?} names no numeric input of this case; one of: {}",
                        axis.path,
                        known()
                    ),
                ));
            }
        }
    }
    Ok(inputs)
}

/// Chosen columns: every output of the case equal to a pointer or under it.
pub(super) fn output_columns<C: Case>(base: &C, outputs: Option<&[String]>) -> Result<Vec<Output>, ApiError> {
    let answered: Vec<Output> = C::OUTPUTS.iter().copied().filter(|&o| base.answers(o)).collect();
    let Some(outputs) = outputs else {
        return Ok(answered);
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
        let matched: Vec<Output> = answered
            .iter()
            .filter(|o| {
                let name = o.path();
                pointer.is_empty()
                    || name == pointer
                    || name
                        .strip_prefix(pointer.as_str())
                        .is_some_and(|rest| rest.starts_with('/'))
            })
            .copied()
            .collect();
        if matched.is_empty() {
            let known: Vec<&str> = answered.iter().map(|o| o.path()).collect();
            return Err(structure(
                format!("/outputs/{i}"),
                "Invalid sweep output",
                format!(
                    "{pointer:?} names no output of this case; one of: {}",
                    known.join(", ")
                ),
            ));
        }
        // Each column once: an entry that adds none is refused (a repeated
        // output would repeat a whole column of every point).
        let before = columns.len();
        columns.extend(
            matched
                .into_iter()
                .filter(|o| !columns.contains(o))
                .collect::<Vec<_>>(),
        );
        if columns.len() == before {
            return Err(structure(
                format!("/outputs/{i}"),
                "Invalid sweep output",
                format!(
                    "{pointer:?} names only outputs an earlier entry already asks for; give each output once"
                ),
            ));
        }
    }
    Ok(columns)
}

/// The sweep of `base` over the request's axes, checked whole.
pub(super) fn sweep<C: Case>(
    request: &SweepRequest,
    base: C,
    precision: Precision,
    limit: u64,
    format: Format,
) -> Result<Sweep<CaseSweep<C>>, ApiError> {
    let values = axis_values(&request.axes)?;
    let inputs = axis_inputs(&request.axes, &base)?;
    let mut columns = output_columns(&base, request.outputs.as_deref())?;
    // A plot shades or marks the regimes: computed alongside the plotted output.
    if format == Format::Svg && !columns.contains(&Output::Regime) && base.answers(Output::Regime) {
        columns.push(Output::Regime);
    }
    let combine = match request.combine {
        CombineDto::Product => crate::sweep::Combine::Product,
        CombineDto::Zip => crate::sweep::Combine::Zip,
    };
    let case = CaseSweep::new(&base, &inputs, columns, precision).map_err(|refused| match refused {
        CaseSweepError::NotRead(input) => structure(
            "/axes",
            "Invalid sweep axis",
            format!("{} is not an input here", input.path()),
        ),
        CaseSweepError::NotAnswered(output) => structure(
            "/outputs",
            "Invalid sweep output",
            format!("{} is not an output of this case", output.path()),
        ),
    })?;
    let axes = inputs
        .into_iter()
        .zip(values)
        .map(|(param, values)| Axis { param, values })
        .collect();
    let range = request.range.map(|r| r.start..r.end);
    Sweep::slice(case, base, axes, combine, range, limit).map_err(|error| grid_error(&error, format))
}

/// A grid error as a problem naming its axis.
fn grid_error(error: &GridError, format: Format) -> ApiError {
    let pointer = match error {
        GridError::NoAxes | GridError::TooManyPoints { .. } => "/axes".to_owned(),
        GridError::Empty { axis } | GridError::ZipLengths { axis, .. } => format!("/axes/{axis}"),
        GridError::NotFinite { axis, index } => format!("/axes/{axis}/values/{index}"),
        GridError::LogspaceBounds { axis } => format!("/axes/{axis}/logspace"),
        GridError::RangeOutside { .. } | GridError::RangeTooLarge { .. } => "/range".to_owned(),
    };
    let too_large = matches!(
        error,
        GridError::TooManyPoints { .. } | GridError::RangeTooLarge { .. }
    );
    let mut detail = error.to_string();
    if too_large && format.is_buffered() {
        detail.push_str(
            " for application/json and image/svg+xml; text/csv, application/x-ndjson and \
             application/vnd.apache.arrow.stream stream larger ones",
        );
    }
    if matches!(error, GridError::TooManyPoints { .. }) {
        detail.push_str(
            "; compute it in slices with \"range\" (POST /v1/sweeps/plan gives ranges that tile it)",
        );
    }
    let title = if too_large {
        "Sweep too large"
    } else if matches!(error, GridError::RangeOutside { .. }) {
        "Invalid sweep range"
    } else {
        "Invalid sweep axis"
    };
    structure(pointer, title, detail)
}

impl SweepRequest {
    /// SHA-256 (hex) of the request without its `range`, as compact JSON with
    /// object members in sorted order: every slice of one sweep has the same
    /// hash, so a client can check that parts it joins belong together.
    pub fn sweep_hash(&self) -> String {
        use sha2::{Digest, Sha256};
        let whole = SweepRequest {
            range: None,
            ..self.clone()
        };
        // `serde_json::Value` keeps object members sorted (no `preserve_order`).
        let canonical = serde_json::to_value(&whole).and_then(|v| serde_json::to_vec(&v));
        let digest = Sha256::digest(canonical.unwrap_or_default());
        digest.iter().map(|b| format!("{b:02x}")).collect()
    }
}
