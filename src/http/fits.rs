//! `POST /v1/fits/tangential`: coefficients of the bilinear tangential model
//! identified from measured impacts (see [`crate::fit`]).

use axum::Json;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::dto::{ContactDto, RegimeDto, RigidBodyDto, VelocityDto};
use super::extract::ApiJson;
use super::impacts::ImpactProblems;
use super::problem::ApiError;
use crate::fit::{self, Estimate, FitError, Observation};
use crate::scene::Body;

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
#[utoipa::path(
    post,
    path = "/v1/fits/tangential",
    tag = "fits",
    request_body(content = TangentialFitRequest, content_type = "application/json"),
    responses((status = 200, description = "The fitted coefficients", body = TangentialFitResponse), ImpactProblems)
)]
pub async fn fits_tangential(
    ApiJson(req): ApiJson<TangentialFitRequest>,
) -> Result<Json<TangentialFitResponse>, ApiError> {
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
    let fit = fit::tangential(&observations).map_err(|error| {
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
    })?;
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
    }))
}
