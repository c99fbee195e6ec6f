//! RFC 9457 problem details: the one error type of the HTTP layer and its
//! mapping to status codes.

use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use utoipa::{IntoResponses, ToSchema};

use crate::error::ImpactError;

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
    "detail": "the contact is not approaching: the normal contact velocity (relative to the barrier or to body B, along the normal out of it) is 1, and an impact needs it below 0",
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

    /// The same problem for a member nested under `prefix` (a JSON pointer):
    /// `/base` turns `/restitution` into `/base/restitution`.
    pub fn under(mut self, prefix: &str) -> Self {
        if let Some(pointer) = self.problem.pointer.take() {
            self.problem.pointer = Some(format!("{prefix}{pointer}"));
        }
        self
    }

    /// The pointer to the offending member, if any.
    pub fn pointer(&self) -> Option<&str> {
        self.problem.pointer.as_deref()
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
            api = api.at(input.path());
        } else if let Some(output) = error.output() {
            api = api.at(output.path());
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

/// The error responses every operation that takes a JSON body may give (all
/// problem+json); an operation lists its own others (406 for sweeps) beside it.
#[derive(IntoResponses)]
#[allow(dead_code)]
pub enum Problems {
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
        description = "Schema mismatch, or inputs that are not acceptable: an impact without a physical answer \
                       (not approaching, D ≤ 0, energy creation), a sweep's base, axis, output or point count; \
                       `pointer` names the offending member",
        content_type = "application/problem+json"
    )]
    Unprocessable(Problem),
    /// The server is at its concurrency limit; retry after the given seconds.
    #[response(
        status = 503,
        description = "Overloaded (the concurrency limit, or for sweeps the limit of buffered or streamed sweeps computed at once): retry after `Retry-After` seconds",
        content_type = "application/problem+json"
    )]
    Overloaded(Problem),
}
