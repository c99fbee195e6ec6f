//! `POST /v1/impacts/{normal,oblique,tangential,torsional}`: one impact each.
//! Handlers only map the wire types to solver inputs and back.

use axum::Json;
use axum::http::StatusCode;
use serde::Deserialize;
use utoipa::{IntoResponses, ToSchema};

use super::dto::{
    ContactDto, NormalBodyDto, PlanarResponse, PrecisionDto, RigidBodyDto, TorsionalResponse, VelocityDto,
};
use super::extract::ApiJson;
use super::problem::{ApiError, Problem};
use crate::error::{ImpactError, Input};
use crate::exact::Precision;
use crate::oblique::KineticRestitution;
use crate::planar::Outputs;
use crate::sweep::planar::{PlanarLaw, PlanarPoint, solve_point};
use crate::sweep::torsional::solve_torsional;
use crate::torsional::TorsionalImpact;

/// The error responses every impact endpoint may give (all problem+json).
#[derive(IntoResponses)]
#[allow(dead_code)]
pub enum ImpactProblems {
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
    /// The body does not match the schema, or the inputs have no physical answer
    /// (a contact that is not approaching, D ≤ 0, energy creation); `pointer` names the member.
    #[response(
        status = 422,
        description = "Schema mismatch, or inputs without a physical impact answer; `pointer` names the offending member",
        content_type = "application/problem+json"
    )]
    Unprocessable(Problem),
    /// The server is at its concurrency limit; retry after the given seconds.
    #[response(
        status = 503,
        description = "Overloaded: retry after `Retry-After` seconds",
        content_type = "application/problem+json"
    )]
    Overloaded(Problem),
}

/// A normal (frictionless) impact: a point mass when `body.inertia` is absent.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93
}))]
pub struct NormalRequest {
    /// The body; without `inertia` a point mass.
    pub body: NormalBodyDto,
    /// Contact geometry (rigid body only; default d_c = d_d = 0).
    pub contact: Option<ContactDto>,
    /// Initial velocities (a point mass takes no angular velocity).
    pub velocity: VelocityDto,
    /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub restitution: f64,
    /// `fast` (default) or `exact` (correctly rounded outputs, exact regime decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

/// The Appendix's two-phase model: kinetic restitution R with phase impulse ratios.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct KineticRestitutionDto {
    /// R = P_n^R / P_n^A: kinetic coefficient of restitution (Eq 9), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub value: f64,
    /// μ_A = P_t^A / P_n^A: impulse ratio of the approach phase (Eq 12).
    #[schema(example = -0.123)]
    pub approach_impulse_ratio: f64,
    /// μ_R = P_t^R / P_n^R: impulse ratio of the rebound phase (Eq 13).
    #[schema(example = -0.123)]
    pub rebound_impulse_ratio: f64,
}

/// An oblique impact: `restitution` with exactly one of `friction` or
/// `impulse_ratio`, or `kinetic_restitution` alone.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93,
    "friction": 0.123
}))]
pub struct ObliqueRequest {
    /// The rigid body.
    pub body: RigidBodyDto,
    /// Contact geometry.
    pub contact: ContactDto,
    /// Initial velocities.
    pub velocity: VelocityDto,
    /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub restitution: Option<f64>,
    /// f: Coulomb friction coefficient (≥ 0); the ratio is capped by the critical ratio μ_c.
    #[schema(minimum = 0.0, example = 0.123)]
    pub friction: Option<f64>,
    /// μ = P_t / P_n: a prescribed impulse ratio (Eq 2); refused when it would create energy.
    pub impulse_ratio: Option<f64>,
    /// The two-phase kinetic model, in place of `restitution` and a tangential law.
    pub kinetic_restitution: Option<KineticRestitutionDto>,
    /// `fast` (default) or `exact` (correctly rounded outputs, exact regime decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

/// An impact with tangential restitution (the bilinear model of section 3).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93,
    "friction": 0.123,
    "tangential_restitution": 0.34
}))]
pub struct TangentialRequest {
    /// The rigid body.
    pub body: RigidBodyDto,
    /// Contact geometry.
    pub contact: ContactDto,
    /// Initial velocities.
    pub velocity: VelocityDto,
    /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub restitution: f64,
    /// f: Coulomb friction coefficient (≥ 0), the cap of the tangential impulse.
    #[schema(minimum = 0.0, example = 0.123)]
    pub friction: f64,
    /// e_t: tangential coefficient of restitution (Eq 20), in [−1, 1]; −1 means no tangential impulse.
    #[schema(minimum = -1.0, maximum = 1.0, example = 0.34)]
    pub tangential_restitution: f64,
    /// `fast` (default) or `exact` (correctly rounded outputs, exact regime decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

/// Mass and moment of inertia about the contact normal.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionalBodyDto {
    /// Mass m (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.6)]
    pub mass: f64,
    /// I_n: moment of inertia about the normal axis (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.003456)]
    pub normal_inertia: f64,
}

/// Initial normal velocity and spin.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionalVelocityDto {
    /// v_n: normal velocity (< 0: approaching).
    #[schema(exclusive_maximum = 0.0, example = -3.0)]
    pub normal: f64,
    /// ω_n: spin about the normal.
    #[schema(example = 20.0)]
    pub spin: f64,
}

/// Torsional coefficients.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionDto {
    /// e_z: torsional coefficient of restitution (Eq 28), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.2)]
    pub restitution: f64,
    /// μ_z: torsional friction coefficient (≥ 0, a magnitude; the moment opposes the spin).
    #[schema(minimum = 0.0, example = 0.3)]
    pub friction: f64,
    /// ρ_p: pitch radius of the torsional friction impulse (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.01)]
    pub pitch_radius: f64,
}

/// A torsional impact (section 4).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 0.6, "normal_inertia": 0.003456},
    "velocity": {"normal": -3.0, "spin": 20.0},
    "restitution": 0.7,
    "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}
}))]
pub struct TorsionalRequest {
    /// The body.
    pub body: TorsionalBodyDto,
    /// Initial normal velocity and spin.
    pub velocity: TorsionalVelocityDto,
    /// e: kinematic coefficient of restitution of the normal impact, in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.7)]
    pub restitution: f64,
    /// Torsional coefficients.
    pub torsion: TorsionDto,
    /// `fast` (default) or `exact` (correctly rounded outputs, exact regime decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

/// The law and inputs of a normal request.
pub fn normal_input(req: &NormalRequest) -> Result<(PlanarLaw, PlanarPoint), ApiError> {
    let law = match req.body.inertia {
        Some(_) => PlanarLaw::Frictionless,
        None if req.contact.is_some() => {
            return Err(ImpactError::NeedsInertia {
                input: Input::TangentialOffset,
            }
            .into());
        }
        None => PlanarLaw::PointMass,
    };
    let point = PlanarPoint {
        mass: req.body.mass,
        inertia: req.body.inertia.unwrap_or(0.0),
        contact: req.contact.map(Into::into).unwrap_or_default(),
        velocity: req.velocity.into(),
        restitution: req.restitution,
        ..PlanarPoint::default()
    };
    Ok((law, point))
}

fn unprocessable(pointer: &str, detail: &str) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "tangential-law",
        "Exactly one tangential law is needed",
        detail,
    )
    .at(pointer)
}

/// The law and inputs of an oblique request, checking that exactly one law is given.
pub fn oblique_input(req: &ObliqueRequest) -> Result<(PlanarLaw, PlanarPoint), ApiError> {
    let mut point = PlanarPoint {
        mass: req.body.mass,
        inertia: req.body.inertia,
        contact: req.contact.into(),
        velocity: req.velocity.into(),
        ..PlanarPoint::default()
    };
    if let Some(k) = req.kinetic_restitution {
        if req.restitution.is_some() || req.friction.is_some() || req.impulse_ratio.is_some() {
            return Err(unprocessable(
                "/kinetic_restitution",
                "kinetic_restitution replaces restitution, friction and impulse_ratio: give it alone",
            ));
        }
        point.kinetic = KineticRestitution {
            value: k.value,
            approach_impulse_ratio: k.approach_impulse_ratio,
            rebound_impulse_ratio: k.rebound_impulse_ratio,
        };
        return Ok((PlanarLaw::KineticRestitution, point));
    }
    let Some(e) = req.restitution else {
        return Err(unprocessable(
            "/restitution",
            "give restitution with friction or impulse_ratio, or kinetic_restitution alone",
        ));
    };
    point.restitution = e;
    let law = match (req.friction, req.impulse_ratio) {
        (Some(f), None) => {
            point.friction = f;
            PlanarLaw::Friction
        }
        (None, Some(mu)) => {
            point.impulse_ratio = mu;
            PlanarLaw::ImpulseRatio
        }
        (Some(_), Some(_)) => {
            return Err(unprocessable(
                "/impulse_ratio",
                "give friction or impulse_ratio, not both",
            ));
        }
        (None, None) => {
            return Err(unprocessable(
                "/friction",
                "give a tangential law: friction or impulse_ratio",
            ));
        }
    };
    Ok((law, point))
}

/// The law and inputs of a tangential-restitution request.
pub fn tangential_input(req: &TangentialRequest) -> (PlanarLaw, PlanarPoint) {
    let point = PlanarPoint {
        mass: req.body.mass,
        inertia: req.body.inertia,
        contact: req.contact.into(),
        velocity: req.velocity.into(),
        restitution: req.restitution,
        friction: req.friction,
        tangential_restitution: req.tangential_restitution,
        ..PlanarPoint::default()
    };
    (PlanarLaw::TangentialRestitution, point)
}

/// The inputs of a torsional request.
pub fn torsional_input(req: &TorsionalRequest) -> TorsionalImpact {
    TorsionalImpact {
        mass: req.body.mass,
        normal_inertia: req.body.normal_inertia,
        normal_velocity: req.velocity.normal,
        spin: req.velocity.spin,
        restitution: req.restitution,
        torsional_restitution: req.torsion.restitution,
        torsional_friction: req.torsion.friction,
        pitch_radius: req.torsion.pitch_radius,
    }
}

fn solve_planar(
    input: Result<(PlanarLaw, PlanarPoint), ApiError>,
    precision: PrecisionDto,
) -> Result<PlanarResponse, ApiError> {
    let (law, point) = input?;
    let precision = Precision::from(precision);
    let outcome = solve_point(law, &point, Outputs::ALL, precision)?;
    Ok(PlanarResponse::from_outcome(&outcome, precision))
}

/// The response to a normal request.
pub fn respond_normal(req: NormalRequest) -> Result<PlanarResponse, ApiError> {
    solve_planar(normal_input(&req), req.precision)
}

/// The response to an oblique request.
pub fn respond_oblique(req: ObliqueRequest) -> Result<PlanarResponse, ApiError> {
    solve_planar(oblique_input(&req), req.precision)
}

/// The response to a tangential-restitution request.
pub fn respond_tangential(req: TangentialRequest) -> Result<PlanarResponse, ApiError> {
    solve_planar(Ok(tangential_input(&req)), req.precision)
}

/// The response to a torsional request.
pub fn respond_torsional(req: TorsionalRequest) -> Result<TorsionalResponse, ApiError> {
    let precision = Precision::from(req.precision);
    let outcome = solve_torsional(&torsional_input(&req), true, precision)?;
    Ok(TorsionalResponse::from_outcome(&outcome, precision))
}

/// Normal impact of a point mass or a frictionless rigid body (section 2.1).
#[utoipa::path(
    post,
    path = "/v1/impacts/normal",
    tag = "impacts",
    request_body(content = NormalRequest, content_type = "application/json"),
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), ImpactProblems)
)]
pub async fn impacts_normal(ApiJson(req): ApiJson<NormalRequest>) -> Result<Json<PlanarResponse>, ApiError> {
    Ok(Json(respond_normal(req)?))
}

/// Oblique impact with a prescribed impulse ratio, Coulomb friction, or two-phase kinetic restitution (Eqs 1–19, Appendix).
#[utoipa::path(
    post,
    path = "/v1/impacts/oblique",
    tag = "impacts",
    request_body(content = ObliqueRequest, content_type = "application/json"),
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), ImpactProblems)
)]
pub async fn impacts_oblique(
    ApiJson(req): ApiJson<ObliqueRequest>,
) -> Result<Json<PlanarResponse>, ApiError> {
    Ok(Json(respond_oblique(req)?))
}

/// Impact with tangential restitution: the bilinear model of Eqs 20–27.
#[utoipa::path(
    post,
    path = "/v1/impacts/tangential",
    tag = "impacts",
    request_body(content = TangentialRequest, content_type = "application/json"),
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), ImpactProblems)
)]
pub async fn impacts_tangential(
    ApiJson(req): ApiJson<TangentialRequest>,
) -> Result<Json<PlanarResponse>, ApiError> {
    Ok(Json(respond_tangential(req)?))
}

/// Impact with torsional restitution: the bilinear model of Eqs 28–31.
#[utoipa::path(
    post,
    path = "/v1/impacts/torsional",
    tag = "impacts",
    request_body(content = TorsionalRequest, content_type = "application/json"),
    responses((status = 200, description = "The impact's outcome", body = TorsionalResponse), ImpactProblems)
)]
pub async fn impacts_torsional(
    ApiJson(req): ApiJson<TorsionalRequest>,
) -> Result<Json<TorsionalResponse>, ApiError> {
    Ok(Json(respond_torsional(req)?))
}
