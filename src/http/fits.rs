//! `POST /v1/fits/tangential` and `POST /v1/fits/torsional`: coefficients of
//! the bilinear models identified from measured impacts (see [`crate::fit`]).

use axum::Json;
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::dto::{ContactDto, RegimeDto, RigidBodyDto, TorsionalRegimeDto, VelocityDto};
use super::extract::ApiJson;
use super::impacts::TorsionalBodyDto;
use super::impacts::bodies::{LaminaDto, PlanarContactDto, VectorDto};
use super::problem::{ApiError, Problems};
use crate::fit::{self, Estimate, FitError, Measured, MeasuredChange, Observation, TorsionalObservation};
use crate::impact::{Lamina, PlanarContact};
use crate::scene::Body;

/// The fit endpoints, with their OpenAPI operations.
pub fn router<S: Clone + Send + Sync + 'static>() -> OpenApiRouter<S> {
    OpenApiRouter::new()
        .routes(routes!(fits_tangential))
        .routes(routes!(fits_torsional))
        .routes(routes!(fits_planar))
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
#[utoipa::path(
    post,
    path = "/v1/fits/tangential",
    tag = "fits",
    request_body(content = TangentialFitRequest, content_type = "application/json"),
    responses((status = 200, description = "The fitted coefficients", body = TangentialFitResponse), Problems)
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
    let fit = fit::tangential(&observations).map_err(unfittable)?;
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
#[utoipa::path(
    post,
    path = "/v1/fits/torsional",
    tag = "fits",
    request_body(content = TorsionalFitRequest, content_type = "application/json"),
    responses((status = 200, description = "The fitted coefficients", body = TorsionalFitResponse), Problems)
)]
pub async fn fits_torsional(
    ApiJson(req): ApiJson<TorsionalFitRequest>,
) -> Result<Json<TorsionalFitResponse>, ApiError> {
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
    }))
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

/// A measured vector.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredVectorDto {
    /// x component.
    pub x: MeasuredDto,
    /// y component.
    pub y: MeasuredDto,
}

/// One body's measured change of motion.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredChangeDto {
    /// ΔV = V − v of the mass centre.
    pub velocity_change: MeasuredVectorDto,
    /// ΔΩ = Ω − ω.
    pub angular_velocity_change: MeasuredDto,
}

/// A reconstruction: the scene before the impact and each body's measured
/// velocity changes; `e` and `μ` (and the normal's direction, with
/// `fit_normal`) are identified.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "bodies": [
        {"mass": 1500.0, "inertia": 2500.0, "position": {"x": 0.0, "y": 0.0},
         "velocity": {"x": 15.0, "y": 0.0}, "angular_velocity": 0.0},
        {"mass": 1200.0, "inertia": 1800.0, "position": {"x": 3.0, "y": -1.5},
         "velocity": {"x": 0.0, "y": 12.0}, "angular_velocity": 0.0}
    ],
    "contact": {"point": {"x": 2.2, "y": -0.6}, "normal": {"x": -1.0, "y": 0.0}},
    "measured": [
        {"velocity_change": {"x": {"value": -7.5, "uncertainty": 0.3}, "y": {"value": 3.9, "uncertainty": 0.3}},
         "angular_velocity_change": {"value": 2.5, "uncertainty": 0.2}},
        {"velocity_change": {"x": {"value": 9.3, "uncertainty": 0.3}, "y": {"value": -4.9, "uncertainty": 0.3}},
         "angular_velocity_change": {"value": -3.0, "uncertainty": 0.2}}
    ]
}))]
pub struct PlanarFitRequest {
    /// Body A, and body B unless A hit a barrier: the scene before the impact.
    pub bodies: Vec<LaminaDto>,
    /// The contact point and normal (from B into A).
    pub contact: PlanarContactDto,
    /// Each body's measured change, in the order of `bodies`.
    pub measured: Vec<MeasuredChangeDto>,
    /// Also fit the normal's direction, taking the contact to end sticking (U_t = 0).
    #[serde(default)]
    pub fit_normal: bool,
}

/// A fitted normal.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct FittedNormalDto {
    /// The unit normal from B into A.
    pub direction: VectorDto,
    /// Its angle from the x axis, radians, with its standard error.
    pub angle: EstimateDto,
}

/// The identified contact.
#[derive(Debug, Clone, Serialize, ToSchema)]
// The server's answer to the request example.
#[schema(example = json!({
    "restitution": {"value": 0.19991028395983862, "standard_error": 0.03103088460902592},
    "impulse_ratio": {"value": -0.5249778594437716, "standard_error": 0.015511744144803644},
    "normal": null,
    "impulse": {"x": -11201.409080383859, "y": 5880.491761773945},
    "impulse_standard_error": {"x": 241.35286564153012, "y": 179.08186246614608},
    "residuals": [-0.03239394641076121, -0.020327841182629758, 0.013505428931054553,
                  -0.034507566986549776, 0.00040980147828761915, -0.012847353929823058],
    "chi_squared": 0.038169933482384455,
    "degrees_of_freedom": 4
}))]
pub struct PlanarFitResponse {
    /// e = −U_n / u_n.
    pub restitution: EstimateDto,
    /// μ = P_t / P_n along t̂ = ẑ × n̂.
    pub impulse_ratio: EstimateDto,
    /// The fitted normal, when asked for.
    pub normal: Option<FittedNormalDto>,
    /// The impulse on A in world axes.
    pub impulse: VectorDto,
    /// Its standard errors.
    pub impulse_standard_error: VectorDto,
    /// Measured minus fitted, per body: ΔV_x, ΔV_y, ΔΩ.
    pub residuals: Vec<f64>,
    /// Σ (residual / uncertainty)².
    pub chi_squared: f64,
    /// Measured values minus fitted parameters.
    pub degrees_of_freedom: usize,
}

/// Identify e and μ (and, if asked, the normal) of a two-body contact from measured velocity changes.
#[utoipa::path(
    post,
    path = "/v1/fits/planar",
    tag = "fits",
    request_body(content = PlanarFitRequest, content_type = "application/json"),
    responses((status = 200, description = "The identified contact", body = PlanarFitResponse), Problems)
)]
pub async fn fits_planar(
    ApiJson(req): ApiJson<PlanarFitRequest>,
) -> Result<Json<PlanarFitResponse>, ApiError> {
    let problem = |pointer: &str, detail: String| {
        ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "unfittable",
            "Contact cannot be fitted",
            detail,
        )
        .at(pointer)
    };
    if req.bodies.is_empty() || req.bodies.len() > 2 {
        return Err(problem(
            "/bodies",
            format!("give 1 or 2 bodies, not {}", req.bodies.len()),
        ));
    }
    if req.measured.len() != req.bodies.len() {
        return Err(problem(
            "/measured",
            format!(
                "give one measured change per body: {} bodies, {} changes",
                req.bodies.len(),
                req.measured.len()
            ),
        ));
    }
    let bodies: Vec<Lamina> = req.bodies.iter().map(|&b| b.into()).collect();
    let contact = PlanarContact {
        point: req.contact.point.into(),
        normal: req.contact.normal.into(),
    };
    let measured: Vec<MeasuredChange> = req
        .measured
        .iter()
        .map(|m| MeasuredChange {
            velocity_change: [m.velocity_change.x.into(), m.velocity_change.y.into()],
            angular_velocity_change: m.angular_velocity_change.into(),
        })
        .collect();
    let fit = fit::planar(&bodies, contact, &measured, req.fit_normal).map_err(|e| match &e {
        FitError::NotAnImpact { why, .. } if why.contains("uncertainty") => {
            problem("/measured", e.to_string())
        }
        FitError::NotAnImpact { .. } => problem("/bodies", e.to_string()),
        // The detail names the parameter; the pointer the member that asked for it.
        FitError::Undetermined {
            parameter: "normal", ..
        } => problem("/fit_normal", e.to_string()),
        _ => problem("/measured", e.to_string()),
    })?;
    Ok(Json(PlanarFitResponse {
        restitution: fit.restitution.into(),
        impulse_ratio: fit.impulse_ratio.into(),
        normal: fit.normal.map(|(direction, angle)| FittedNormalDto {
            direction: direction.into(),
            angle: angle.into(),
        }),
        impulse: fit.impulse.into(),
        impulse_standard_error: fit.impulse_standard_error.into(),
        residuals: fit.residuals,
        chi_squared: fit.chi_squared,
        degrees_of_freedom: fit.degrees_of_freedom,
    }))
}
