//! `POST /v1/fits/tangential`, `/v1/fits/torsional`, `/v1/fits/planar`
//! (`bodies.rs`) and `/v1/fits/spatial` (`spatial.rs`): coefficients
//! identified from measured impacts (see [`crate::fit`]). The tangential and
//! torsional fits also answer `image/svg+xml`: their points and fitted curve
//! (`plot.rs`).

mod bodies;
mod plot;
mod spatial;

pub use bodies::*;
pub use spatial::*;

use axum::Json;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::dto::{ContactDto, RegimeDto, RigidBodyDto, TorsionalRegimeDto, VelocityDto};
use super::extract::ApiJson;
use super::impacts::TorsionalBodyDto;
use super::problem::{ApiError, Problems};
use crate::fit::{self, Estimate, FitError, Measured, Observation, TorsionalObservation};
use crate::scene::Body;

/// The fit endpoints, with their OpenAPI operations.
pub fn router<S: Clone + Send + Sync + 'static>() -> OpenApiRouter<S> {
    OpenApiRouter::new()
        .routes(routes!(fits_tangential))
        .routes(routes!(fits_torsional))
        .routes(routes!(fits_planar))
        .routes(routes!(fits_spatial))
}

/// One measured impact: geometry, and velocities before and after.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ObservationDto {
    /// The body.
    pub body: RigidBodyDto,
    /// Contact geometry.
    pub contact: ContactDto,
    /// Velocities before the impact (v_n, v_t, ω).
    pub initial: VelocityDto,
    /// Velocities after the impact (V_n, V_t, Ω).
    #[serde(rename = "final")]
    pub final_: VelocityDto,
}

/// Measured impacts to fit.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"observations": [
    {"body": {"mass": 1.0, "inertia": 0.00125}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
     "initial": {"normal": -1.0, "tangential": 0.1}, "final": {"normal": 0.93, "tangential": 0.0553, "angular": 1.7867}},
    {"body": {"mass": 1.0, "inertia": 0.00125}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
     "initial": {"normal": -1.0, "tangential": 1.0}, "final": {"normal": 0.93, "tangential": 0.76261, "angular": 9.4956}},
    {"body": {"mass": 1.0, "inertia": 0.00125}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
     "initial": {"normal": -1.0, "tangential": 2.0}, "final": {"normal": 0.93, "tangential": 1.76261, "angular": 9.4956}}
]}))]
pub struct TangentialFitRequest {
    /// At least three impacts, in any order, in either regime.
    #[schema(min_items = 3)]
    pub observations: Vec<ObservationDto>,
}

/// A coefficient and its standard error.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct EstimateDto {
    /// The least-squares value.
    pub value: f64,
    /// Its standard error; null when one point determines it.
    pub standard_error: Option<f64>,
}

impl From<Estimate> for EstimateDto {
    fn from(e: Estimate) -> Self {
        EstimateDto {
            value: e.value,
            standard_error: e.standard_error.is_finite().then_some(e.standard_error),
        }
    }
}

/// The fitted bilinear model.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TangentialFitResponse {
    /// e, from V_cn = −e v_cn (Eq 1).
    pub restitution: EstimateDto,
    /// f, from the sliding points (|μ| = f); null when no point slides.
    pub friction: Option<EstimateDto>,
    /// e_t, from the restitution points (V_ct = −e_t v_ct, Eq 20); null when none.
    pub tangential_restitution: Option<EstimateDto>,
    /// The regime of each observation under the fitted model, in input order.
    pub regimes: Vec<RegimeDto>,
    /// Observed minus fitted V_ct, in input order (null where the fitted model refuses the point).
    pub residuals: Vec<Option<f64>>,
    /// 1 − SS_res/SS_tot of V_ct; null when V_ct does not vary.
    pub r_squared: Option<f64>,
}

/// Identify e, f and e_t of the bilinear tangential model from measured impacts.
///
/// Formats by `Accept`: `application/json` (default; the coefficients) or
/// `image/svg+xml` (V_ct/|v_cn| after against v_ct/|v_cn| before: the
/// measured points and the fitted model's curve for the first observation's
/// body; the points only, and a subtitle saying so, when f or e_t is not
/// identified).
#[utoipa::path(
    post,
    path = "/v1/fits/tangential",
    tag = "fits",
    request_body(content = TangentialFitRequest, content_type = "application/json"),
    responses(
        (status = 200, description = "The fitted coefficients, or their plot", content(
            (TangentialFitResponse = "application/json"),
            (String = "image/svg+xml"),
        )),
        plot::FitNotAcceptable,
        Problems
    )
)]
pub async fn fits_tangential(
    headers: HeaderMap,
    ApiJson(req): ApiJson<TangentialFitRequest>,
) -> Result<Response, ApiError> {
    let format = plot::negotiate(&headers)?;
    let mut observations = Vec::with_capacity(req.observations.len());
    for (i, o) in req.observations.iter().enumerate() {
        let body = Body::new(o.body.mass, o.body.inertia).map_err(|e| {
            ApiError::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                e.slug(),
                e.title(),
                e.to_string(),
            )
            .at(format!("/observations/{i}/body"))
        })?;
        observations.push(Observation {
            body,
            contact: o.contact.into(),
            initial: o.initial.into(),
            r#final: o.final_.into(),
        });
    }
    let fit = fit::tangential(&observations).map_err(unfittable)?;
    if format == plot::FitFormat::Svg {
        return Ok(svg(plot::tangential(&observations, &fit)));
    }
    Ok(Json(TangentialFitResponse {
        restitution: fit.restitution.into(),
        friction: fit.friction.map(Into::into),
        tangential_restitution: fit.tangential_restitution.map(Into::into),
        regimes: fit.regimes.into_iter().map(Into::into).collect(),
        residuals: fit
            .residuals
            .into_iter()
            .map(|r| r.is_finite().then_some(r))
            .collect(),
        r_squared: fit.r_squared.is_finite().then_some(fit.r_squared),
    })
    .into_response())
}

/// An SVG answer.
fn svg(text: String) -> Response {
    (
        [(header::CONTENT_TYPE, HeaderValue::from_static("image/svg+xml"))],
        text,
    )
        .into_response()
}

/// Normal velocity and spin after a torsional impact.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpinStateDto {
    /// Normal velocity of the centre of mass.
    pub normal: f64,
    /// Spin about the normal.
    pub spin: f64,
}

/// One measured torsional impact.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionalObservationDto {
    /// Mass and moment of inertia about the normal.
    pub body: TorsionalBodyDto,
    /// ρ_p: pitch radius of the torsional friction impulse (> 0).
    #[schema(exclusive_minimum = 0.0)]
    pub pitch_radius: f64,
    /// Before the impact (v_n < 0, ω_n).
    pub initial: SpinStateDto,
    /// After the impact (V_n, Ω_n).
    #[serde(rename = "final")]
    pub final_: SpinStateDto,
}

/// Measured torsional impacts to fit.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"observations": [
    {"body": {"mass": 0.1, "normal_inertia": 0.000036}, "pitch_radius": 0.005,
     "initial": {"normal": -3.0, "spin": 10.0}, "final": {"normal": 2.4, "spin": -2.0}},
    {"body": {"mass": 0.1, "normal_inertia": 0.000036}, "pitch_radius": 0.005,
     "initial": {"normal": -3.0, "spin": 40.0}, "final": {"normal": 2.4, "spin": 9.5}},
    {"body": {"mass": 0.1, "normal_inertia": 0.000036}, "pitch_radius": 0.005,
     "initial": {"normal": -3.0, "spin": 80.0}, "final": {"normal": 2.4, "spin": 41.5}}
]}))]
pub struct TorsionalFitRequest {
    /// At least three impacts, in any order, in either branch.
    #[schema(min_items = 3)]
    pub observations: Vec<TorsionalObservationDto>,
}

/// The fitted torsional model.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TorsionalFitResponse {
    /// e, from V_n = −e v_n.
    pub restitution: EstimateDto,
    /// e_z (Eq 28).
    pub torsional_restitution: EstimateDto,
    /// μ_z (Eq 30); null when no point slides.
    pub torsional_friction: Option<EstimateDto>,
    /// The branch of each observation under the fitted model, in input order.
    pub regimes: Vec<TorsionalRegimeDto>,
    /// Observed minus fitted Ω_n, in input order.
    pub residuals: Vec<f64>,
    /// 1 − SS_res/SS_tot of Ω_n; null when Ω_n does not vary.
    pub r_squared: Option<f64>,
}

fn unfittable(error: FitError) -> ApiError {
    let pointer = match &error {
        FitError::NotAnImpact { index, .. } => format!("/observations/{index}"),
        _ => "/observations".to_owned(),
    };
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "unfittable",
        "Observations cannot be fitted",
        error.to_string(),
    )
    .at(pointer)
}

/// Identify e, e_z and μ_z of the torsional model from measured impacts.
///
/// Formats by `Accept`: `application/json` (default; the coefficients) or
/// `image/svg+xml` (Ω_n/|v_n| after against ω_n/|v_n| before: the measured
/// points and the fitted model's curve for the first observation's body; the
/// points only, and a subtitle saying so, when μ_z is not identified).
#[utoipa::path(
    post,
    path = "/v1/fits/torsional",
    tag = "fits",
    request_body(content = TorsionalFitRequest, content_type = "application/json"),
    responses(
        (status = 200, description = "The fitted coefficients, or their plot", content(
            (TorsionalFitResponse = "application/json"),
            (String = "image/svg+xml"),
        )),
        plot::FitNotAcceptable,
        Problems
    )
)]
pub async fn fits_torsional(
    headers: HeaderMap,
    ApiJson(req): ApiJson<TorsionalFitRequest>,
) -> Result<Response, ApiError> {
    let format = plot::negotiate(&headers)?;
    let observations: Vec<TorsionalObservation> = req
        .observations
        .iter()
        .map(|o| TorsionalObservation {
            mass: o.body.mass,
            normal_inertia: o.body.normal_inertia,
            pitch_radius: o.pitch_radius,
            normal_velocity: o.initial.normal,
            spin: o.initial.spin,
            final_normal_velocity: o.final_.normal,
            final_spin: o.final_.spin,
        })
        .collect();
    let fit = fit::torsional(&observations).map_err(unfittable)?;
    if format == plot::FitFormat::Svg {
        return Ok(svg(plot::torsional(&observations, &fit)));
    }
    Ok(Json(TorsionalFitResponse {
        restitution: fit.restitution.into(),
        torsional_restitution: fit.torsional_restitution.into(),
        torsional_friction: fit.torsional_friction.map(Into::into),
        regimes: fit
            .sliding
            .iter()
            .map(|&s| {
                if s {
                    TorsionalRegimeDto::Sliding
                } else {
                    TorsionalRegimeDto::Restitution
                }
            })
            .collect(),
        residuals: fit.residuals,
        r_squared: fit.r_squared.is_finite().then_some(fit.r_squared),
    })
    .into_response())
}

/// A measured value with its standard uncertainty.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredDto {
    /// The value.
    pub value: f64,
    /// Its standard uncertainty (> 0), the weight's 1/σ.
    #[schema(exclusive_minimum = 0.0)]
    pub uncertainty: f64,
}

impl From<MeasuredDto> for Measured {
    fn from(m: MeasuredDto) -> Self {
        Measured {
            value: m.value,
            uncertainty: m.uncertainty,
        }
    }
}
