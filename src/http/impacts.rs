//! `POST /v1/impacts/{normal,oblique,tangential,torsional}`: one impact each.
//! Each request type parses into the solver's impact with `TryFrom` (a
//! structural error names its member); handlers only solve and map back.

use axum::Json;
use axum::http::StatusCode;
use serde::Deserialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::dto::{
    ContactDto, NormalBodyDto, PlanarResponse, PrecisionDto, RigidBodyDto, TorsionalResponse, VelocityDto,
};
use super::extract::ApiJson;
use super::problem::{ApiError, Problems};
use crate::error::{ImpactError, Input};
use crate::impact::{Law, PlanarBody, PlanarImpact, Precision, TorsionalImpact, solve};
use crate::outcome::Outputs;
use crate::scene::PlanarVelocity;

/// The impact endpoints, with their OpenAPI operations.
pub fn router<S: Clone + Send + Sync + 'static>() -> OpenApiRouter<S> {
    OpenApiRouter::new()
        .routes(routes!(impacts_normal))
        .routes(routes!(impacts_oblique))
        .routes(routes!(impacts_tangential))
        .routes(routes!(impacts_torsional))
        .routes(routes!(super::planar::impacts_planar))
        .routes(routes!(super::spatial::impacts_spatial))
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

impl TryFrom<&NormalRequest> for PlanarImpact {
    type Error = ApiError;

    /// A point mass when the body has no inertia (then no contact may be given).
    fn try_from(req: &NormalRequest) -> Result<Self, ApiError> {
        let body = match (req.body.inertia, req.contact) {
            (Some(inertia), contact) => PlanarBody::Rigid {
                mass: req.body.mass,
                inertia,
                contact: contact.map(Into::into).unwrap_or_default(),
            },
            (None, Some(_)) => {
                return Err(ImpactError::NeedsInertia {
                    input: Input::TangentialOffset,
                }
                .into());
            }
            (None, None) => PlanarBody::PointMass { mass: req.body.mass },
        };
        Ok(PlanarImpact {
            body,
            velocity: req.velocity.into(),
            law: Law::Frictionless {
                restitution: req.restitution,
            },
        })
    }
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

impl TryFrom<&ObliqueRequest> for PlanarImpact {
    type Error = ApiError;

    /// Exactly one law: `restitution` with `friction` or `impulse_ratio`, or
    /// `kinetic_restitution` alone.
    fn try_from(req: &ObliqueRequest) -> Result<Self, ApiError> {
        let law = match (req.kinetic_restitution, req.restitution) {
            (Some(_), _)
                if req.restitution.is_some() || req.friction.is_some() || req.impulse_ratio.is_some() =>
            {
                return Err(unprocessable(
                    "/kinetic_restitution",
                    "kinetic_restitution replaces restitution, friction and impulse_ratio: give it alone",
                ));
            }
            (Some(k), _) => Law::KineticRestitution {
                value: k.value,
                approach_impulse_ratio: k.approach_impulse_ratio,
                rebound_impulse_ratio: k.rebound_impulse_ratio,
            },
            (None, None) => {
                return Err(unprocessable(
                    "/restitution",
                    "give restitution with friction or impulse_ratio, or kinetic_restitution alone",
                ));
            }
            (None, Some(restitution)) => match (req.friction, req.impulse_ratio) {
                (Some(friction), None) => Law::Friction {
                    restitution,
                    friction,
                },
                (None, Some(impulse_ratio)) => Law::ImpulseRatio {
                    restitution,
                    impulse_ratio,
                },
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
            },
        };
        Ok(rigid(req.body, req.contact, req.velocity, law))
    }
}

impl From<&TangentialRequest> for PlanarImpact {
    fn from(req: &TangentialRequest) -> Self {
        rigid(
            req.body,
            req.contact,
            req.velocity,
            Law::TangentialRestitution {
                restitution: req.restitution,
                friction: req.friction,
                tangential_restitution: req.tangential_restitution,
            },
        )
    }
}

fn rigid(body: RigidBodyDto, contact: ContactDto, velocity: VelocityDto, law: Law) -> PlanarImpact {
    PlanarImpact::rigid(
        body.mass,
        body.inertia,
        contact.into(),
        PlanarVelocity::from(velocity),
        law,
    )
}

impl From<&TorsionalRequest> for TorsionalImpact {
    fn from(req: &TorsionalRequest) -> Self {
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
}

fn respond_planar(impact: PlanarImpact, precision: PrecisionDto) -> Result<PlanarResponse, ApiError> {
    let precision = Precision::from(precision);
    let outcome = solve(&impact, Outputs::ALL, precision)?;
    Ok(PlanarResponse::from_outcome(&outcome, precision))
}

/// The response to a normal request.
pub fn respond_normal(req: NormalRequest) -> Result<PlanarResponse, ApiError> {
    respond_planar(PlanarImpact::try_from(&req)?, req.precision)
}

/// The response to an oblique request.
pub fn respond_oblique(req: ObliqueRequest) -> Result<PlanarResponse, ApiError> {
    respond_planar(PlanarImpact::try_from(&req)?, req.precision)
}

/// The response to a tangential-restitution request.
pub fn respond_tangential(req: TangentialRequest) -> Result<PlanarResponse, ApiError> {
    respond_planar(PlanarImpact::from(&req), req.precision)
}

/// The response to a torsional request.
pub fn respond_torsional(req: TorsionalRequest) -> Result<TorsionalResponse, ApiError> {
    let precision = Precision::from(req.precision);
    let outcome = solve(&TorsionalImpact::from(&req), Outputs::ALL, precision)?;
    Ok(TorsionalResponse::from_outcome(&outcome, precision))
}

/// Normal impact of a point mass or a frictionless rigid body (section 2.1).
#[utoipa::path(
    post,
    path = "/v1/impacts/normal",
    tag = "impacts",
    request_body(content = NormalRequest, content_type = "application/json"),
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), Problems)
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
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), Problems)
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
    responses((status = 200, description = "The impact's outcome", body = PlanarResponse), Problems)
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
    responses((status = 200, description = "The impact's outcome", body = TorsionalResponse), Problems)
)]
pub async fn impacts_torsional(
    ApiJson(req): ApiJson<TorsionalRequest>,
) -> Result<Json<TorsionalResponse>, ApiError> {
    Ok(Json(respond_torsional(req)?))
}

#[cfg(test)]
mod tests {
    use serde_json::{Value as Json, json};

    use super::*;
    use crate::impact::Case;
    use crate::quantity::Value;

    /// Every input a request's impact reads sits at its path in the request,
    /// with the value the impact reads.
    fn inputs_resolve<C: Case>(request: &Json, impact: &C) {
        let reads = impact.reads();
        assert!(!reads.is_empty());
        for input in reads {
            let at = request
                .pointer(input.path())
                .unwrap_or_else(|| panic!("{} in {request}", input.path()));
            assert_eq!(at.as_f64(), impact.input(input), "{}", input.path());
        }
    }

    /// Every output of the case sits at its path in the serialised response,
    /// with the value the case reads off the outcome.
    fn outputs_resolve<C: Case>(response: &Json, outcome: &C::Outcome) {
        for &output in C::OUTPUTS {
            let at = response
                .pointer(output.path())
                .unwrap_or_else(|| panic!("{} in {response}", output.path()));
            match C::output(outcome, output) {
                Value::Number(x) => assert_eq!(at.as_f64(), Some(x), "{}", output.path()),
                Value::Text(name) => assert_eq!(at.as_str(), Some(name), "{}", output.path()),
            }
        }
    }

    fn body() -> Json {
        json!({"mass": 1.25, "inertia": 0.0021})
    }

    fn contact() -> Json {
        json!({"tangential_offset": 0.011, "normal_offset": 0.053})
    }

    fn velocity() -> Json {
        json!({"normal": -1.1, "tangential": 0.37, "angular": 2.9})
    }

    #[test]
    fn every_input_and_output_path_resolves_in_the_planar_wire_types() {
        let requests = [
            json!({"body": body(), "contact": contact(), "velocity": velocity(), "restitution": 0.93}),
            json!({"body": {"mass": 1.25}, "velocity": {"normal": -1.1, "tangential": 0.37}, "restitution": 0.93}),
        ];
        let mut impacts: Vec<(Json, PlanarImpact)> = requests
            .into_iter()
            .map(|r| {
                let req: NormalRequest = serde_json::from_value(r.clone()).unwrap();
                (r, PlanarImpact::try_from(&req).unwrap())
            })
            .collect();
        for law in [
            json!({"restitution": 0.93, "friction": 0.123}),
            json!({"restitution": 0.93, "impulse_ratio": -0.05}),
            json!({"kinetic_restitution": {"value": 0.9, "approach_impulse_ratio": -0.05, "rebound_impulse_ratio": -0.04}}),
        ] {
            let mut r = json!({"body": body(), "contact": contact(), "velocity": velocity()});
            r.as_object_mut()
                .unwrap()
                .extend(law.as_object().unwrap().clone());
            let req: ObliqueRequest = serde_json::from_value(r.clone()).unwrap();
            impacts.push((r, PlanarImpact::try_from(&req).unwrap()));
        }
        let r = json!({"body": body(), "contact": contact(), "velocity": velocity(),
                       "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34});
        let req: TangentialRequest = serde_json::from_value(r.clone()).unwrap();
        impacts.push((r, PlanarImpact::from(&req)));
        for (request, impact) in &impacts {
            inputs_resolve(request, impact);
            for precision in [Precision::Fast, Precision::Exact] {
                let outcome = solve(impact, Outputs::ALL, precision).unwrap();
                let response =
                    serde_json::to_value(PlanarResponse::from_outcome(&outcome, precision)).unwrap();
                outputs_resolve::<PlanarImpact>(&response, &outcome);
            }
        }
    }

    #[test]
    fn every_input_and_output_path_resolves_in_the_torsional_wire_types() {
        let request = json!({"body": {"mass": 0.6, "normal_inertia": 0.003456},
                             "velocity": {"normal": -3.0, "spin": 20.0}, "restitution": 0.7,
                             "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}});
        let req: TorsionalRequest = serde_json::from_value(request.clone()).unwrap();
        let impact = TorsionalImpact::from(&req);
        inputs_resolve(&request, &impact);
        assert_eq!(impact.reads(), TorsionalImpact::INPUTS);
        let outcome = solve(&impact, Outputs::ALL, Precision::Fast).unwrap();
        let response =
            serde_json::to_value(TorsionalResponse::from_outcome(&outcome, Precision::Fast)).unwrap();
        outputs_resolve::<TorsionalImpact>(&response, &outcome);
    }
}
