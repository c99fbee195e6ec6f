//! RFC 9457 problem details: the one error type of the HTTP layer and its
//! mapping to status codes.

use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use utoipa::ToSchema;

use crate::error::{ImpactError, Input, Output};

/// The media type of every error body.
pub const PROBLEM_JSON: &str = "application/problem+json";

/// An admissible interval of impulse ratios; a missing bound is unbounded.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct IntervalDto {
    /// Lowest admissible impulse ratio, absent when unbounded below.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// Highest admissible impulse ratio, absent when unbounded above.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
}

/// An RFC 9457 problem details object.
#[derive(Debug, Clone, Serialize, ToSchema)]
// The server's refusal of the oblique request example with a receding contact (v_n = 1).
#[schema(title = "Problem", example = json!({
    "type": "urn:restitution:problem:not-approaching",
    "title": "Contact is not approaching",
    "status": 422,
    "detail": "the contact is not approaching the barrier: the normal contact velocity is 1, and an impact needs it below 0",
    "pointer": "/velocity/normal"
}))]
pub struct Problem {
    /// A URI reference naming the kind of problem.
    #[serde(rename = "type")]
    pub kind: String,
    /// A short summary of the kind of problem.
    pub title: String,
    /// The HTTP status code.
    pub status: u16,
    /// What went wrong with this request, in words.
    pub detail: String,
    /// JSON pointer (RFC 6901) to the offending member of the request, or of the
    /// response for an output that cannot be represented.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pointer: Option<String>,
    /// For an impulse ratio that would create energy: the admissible ratios.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub admissible_impulse_ratio: Option<IntervalDto>,
}

/// An error of the HTTP layer, rendered as problem+json.
#[derive(Debug, Clone)]
pub struct ApiError {
    status: StatusCode,
    problem: Box<Problem>,
    retry_after: Option<u32>,
}

impl ApiError {
    /// A problem with the given status, slug, title and detail.
    pub fn new(status: StatusCode, slug: &str, title: &str, detail: impl Into<String>) -> Self {
        ApiError {
            status,
            problem: Box::new(Problem {
                kind: format!("urn:restitution:problem:{slug}"),
                title: title.to_owned(),
                status: status.as_u16(),
                detail: detail.into(),
                pointer: None,
                admissible_impulse_ratio: None,
            }),
            retry_after: None,
        }
    }

    /// Names the offending member by JSON pointer.
    pub fn at(mut self, pointer: impl Into<String>) -> Self {
        self.problem.pointer = Some(pointer.into());
        self
    }

    /// Adds a `Retry-After` header (seconds).
    pub fn retry_after(mut self, seconds: u32) -> Self {
        self.retry_after = Some(seconds);
        self
    }

    /// The status code.
    pub fn status(&self) -> StatusCode {
        self.status
    }

    /// The problem body.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// A solver error: 422, naming the input (or output) by JSON pointer.
    pub fn from_solver(error: &ImpactError) -> Self {
        let mut api = ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            error.slug(),
            error.title(),
            error.to_string(),
        );
        if let Some(input) = error.input() {
            api = api.at(input_pointer(input));
        } else if let Some(output) = error.output() {
            api = api.at(output_pointer(output));
        }
        if let ImpactError::CreatesEnergy { admissible, .. } = error {
            api.problem.admissible_impulse_ratio = Some(IntervalDto {
                lower: admissible.lower,
                upper: admissible.upper,
            });
        }
        api
    }
}

impl From<ImpactError> for ApiError {
    fn from(error: ImpactError) -> Self {
        ApiError::from_solver(&error)
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = serde_json::to_vec(&*self.problem).unwrap_or_default();
        let mut response = (self.status, body).into_response();
        let headers = response.headers_mut();
        headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(PROBLEM_JSON));
        if let Some(seconds) = self.retry_after {
            headers.insert(header::RETRY_AFTER, HeaderValue::from(seconds));
        }
        response
    }
}

/// JSON pointer of an input in the request bodies (the same in every case).
pub fn input_pointer(input: Input) -> &'static str {
    match input {
        Input::Mass => "/body/mass",
        Input::Inertia => "/body/inertia",
        Input::NormalInertia => "/body/normal_inertia",
        Input::TangentialOffset => "/contact/tangential_offset",
        Input::NormalOffset => "/contact/normal_offset",
        Input::NormalVelocity => "/velocity/normal",
        Input::TangentialVelocity => "/velocity/tangential",
        Input::AngularVelocity => "/velocity/angular",
        Input::Spin => "/velocity/spin",
        Input::Restitution => "/restitution",
        Input::Friction => "/friction",
        Input::ImpulseRatio => "/impulse_ratio",
        Input::TangentialRestitution => "/tangential_restitution",
        Input::KineticRestitution => "/kinetic_restitution/value",
        Input::ApproachImpulseRatio => "/kinetic_restitution/approach_impulse_ratio",
        Input::ReboundImpulseRatio => "/kinetic_restitution/rebound_impulse_ratio",
        Input::TorsionalRestitution => "/torsion/restitution",
        Input::TorsionalFriction => "/torsion/friction",
        Input::PitchRadius => "/torsion/pitch_radius",
    }
}

/// JSON pointer of an output in the response bodies.
pub fn output_pointer(output: Output) -> &'static str {
    match output {
        Output::FinalNormalVelocity => "/final_velocity/normal",
        Output::FinalTangentialVelocity => "/final_velocity/tangential",
        Output::FinalAngularVelocity => "/final_velocity/angular",
        Output::InitialNormalContactVelocity => "/contact_velocity/initial/normal",
        Output::InitialTangentialContactVelocity => "/contact_velocity/initial/tangential",
        Output::FinalNormalContactVelocity => "/contact_velocity/final/normal",
        Output::FinalTangentialContactVelocity => "/contact_velocity/final/tangential",
        Output::NormalImpulse => "/impulse/normal",
        Output::TangentialImpulse => "/impulse/tangential",
        Output::ImpulseRatio => "/impulse_ratio",
        Output::CriticalImpulseRatio => "/critical_impulse_ratio",
        Output::Restitution => "/restitution",
        Output::InitialEnergy => "/energy/initial",
        Output::FinalEnergy => "/energy/final",
        Output::EnergyLoss => "/energy/loss",
        Output::MaxEnergyLoss => "/energy/max_loss",
        Output::NormalizedEnergyLoss => "/energy/normalized_loss",
        Output::FinalSpin => "/final_velocity/spin",
        Output::TorsionalImpulse => "/impulse/torsional",
        Output::SwitchSpin => "/switch_spin",
    }
}
