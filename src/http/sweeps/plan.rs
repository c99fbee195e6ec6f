//! `POST /v1/sweeps/plan`: how many points a sweep has and the ranges that
//! split it into shards, so a client (a Dask graph, a Kubernetes Indexed Job)
//! fans a sweep out without counting points itself.

use std::sync::Arc;

use axum::Json;
use axum::extract::State;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::negotiate::Format;
use super::request::{SliceDto, SweepRequest, structure};
use super::{AnySweep, build, on_sweep};
use crate::http::ServiceConfig;
use crate::http::accept::{AcceptsJson, NotAcceptable};
use crate::http::extract::ApiJson;
use crate::http::problem::{ApiError, Problems};
use crate::sweep::shard;

/// Most ranges one plan lists.
pub const MAX_SHARDS: u64 = 100_000;

/// A sweep to split, and into how many shards or how many points per shard
/// (exactly one of the two).
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "sweep": {
        "case": "oblique",
        "base": {"body": {"mass": 1.0, "inertia": 0.00125}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                 "velocity": {"normal": -1.0, "tangential": 1.0, "angular": 0.0}, "restitution": 0.9, "friction": 0.2},
        "axes": [{"path": "/friction", "linspace": {"start": 0.0, "stop": 1.0, "count": 1000}},
                 {"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 1000}}],
        "outputs": ["/contact_velocity/final/tangential"]
    },
    "shards": 8
}))]
pub struct PlanRequest {
    /// The sweep, exactly as `POST /v1/sweeps` takes it; with a `range`, the
    /// plan splits that range.
    pub sweep: SweepRequest,
    /// Number of ranges (1 to 100,000); their lengths differ by at most one.
    #[schema(minimum = 1, maximum = 100_000)]
    pub shards: Option<u64>,
    /// Points per range (≥ 1, at most the streamed sweep limit); the last range
    /// may be shorter.
    #[schema(minimum = 1)]
    pub points_per_shard: Option<u64>,
}

/// The ranges that tile a sweep.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct SweepPlan {
    /// Number of points of the whole sweep.
    pub points: u64,
    /// Consecutive ranges tiling the sweep's points (its `range`, else all):
    /// put each in the sweep's `range` member.
    pub ranges: Vec<SliceDto>,
    /// Most points one streamed request (CSV, NDJSON, Arrow) may hold on this
    /// service; buffered formats (JSON, SVG) allow fewer.
    pub max_points_per_range: u64,
}

/// Plan the shards of a sweep.
///
/// Checks the sweep whole (as `POST /v1/sweeps` does, but for the point
/// limit, which applies to each range) and returns its number of points and
/// consecutive ranges tiling it: the rows of the ranges, in order, are exactly
/// the rows of the whole sweep.
#[utoipa::path(
    post,
    path = "/v1/sweeps/plan",
    tag = "sweeps",
    request_body(content = PlanRequest, content_type = "application/json"),
    responses(
        (status = 200, description = "The sweep's ranges", body = SweepPlan),
        Problems,
        NotAcceptable
    )
)]
pub async fn plan(
    _: AcceptsJson,
    State(config): State<Arc<ServiceConfig>>,
    ApiJson(request): ApiJson<PlanRequest>,
) -> Result<Json<SweepPlan>, ApiError> {
    let (sweep, _) = build(&request.sweep, u64::MAX, Format::Csv).map_err(|e| e.under("/sweep"))?;
    let (total, range) = on_sweep!(&sweep, s => (s.total_points(), s.range()));
    let limit = config.max_sweep_points;
    let ranges = split(range, request.shards, request.points_per_shard, limit)?;
    Ok(Json(SweepPlan {
        points: total,
        ranges,
        max_points_per_range: limit,
    }))
}

/// Splits `range` into shards of at most `limit` points, by a number of shards
/// or a number of points per shard.
pub fn split(
    range: std::ops::Range<u64>,
    shards: Option<u64>,
    points_per_shard: Option<u64>,
    limit: u64,
) -> Result<Vec<SliceDto>, ApiError> {
    let points = range.end - range.start;
    let shards = match (shards, points_per_shard) {
        (Some(shards), None) => {
            if !(1..=MAX_SHARDS).contains(&shards) {
                return Err(structure(
                    "/shards",
                    "Invalid sweep plan",
                    format!("shards must be between 1 and {MAX_SHARDS}"),
                ));
            }
            let longest = points.div_ceil(shards);
            if longest > limit {
                return Err(structure(
                    "/shards",
                    "Invalid sweep plan",
                    format!(
                        "{shards} shards of {points} points hold up to {longest} points each; the limit per range \
                         is {limit}: ask for at least {} shards",
                        points.div_ceil(limit)
                    ),
                ));
            }
            shards
        }
        (None, Some(each)) => {
            if !(1..=limit).contains(&each) {
                return Err(structure(
                    "/points_per_shard",
                    "Invalid sweep plan",
                    format!("points_per_shard must be between 1 and the limit per range, {limit}"),
                ));
            }
            let shards = points.div_ceil(each).max(1);
            if shards > MAX_SHARDS {
                return Err(structure(
                    "/points_per_shard",
                    "Invalid sweep plan",
                    format!(
                        "{points} points in shards of {each} make {shards} ranges; a plan lists at most {MAX_SHARDS}: \
                         ask for at least {} points per shard",
                        points.div_ceil(MAX_SHARDS)
                    ),
                ));
            }
            return Ok((0..shards)
                .map(|i| SliceDto {
                    start: range.start + i * each,
                    end: range.start + ((i + 1) * each).min(points),
                })
                .collect());
        }
        _ => {
            return Err(structure(
                "",
                "Invalid sweep plan",
                "give exactly one of shards or points_per_shard",
            ));
        }
    };
    Ok((0..shards)
        .map(|i| {
            let r = shard(points, shards, i);
            SliceDto {
                start: range.start + r.start,
                end: range.start + r.end,
            }
        })
        .collect())
}
