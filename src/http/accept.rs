//! `Accept` negotiation shared by every resource: [`choose`] picks among the
//! media ranges an operation offers, and [`AcceptsJson`] refuses, with a
//! 406 problem, a request to an operation that answers JSON alone whose
//! `Accept` admits no JSON.

use axum::extract::FromRequestParts;
use axum::http::request::Parts;
use axum::http::{HeaderMap, StatusCode, header};
use utoipa::IntoResponses;

use crate::http::problem::{ApiError, Problem};

/// The format of the `offered` media range that `Accept` ranks highest (the
/// first listed among equal qualities); `default` without an `Accept` range;
/// `None` when no offered range is acceptable.
pub fn choose<T: Copy>(headers: &HeaderMap, offered: &[(&str, T)], default: T) -> Option<T> {
    let mut ranges: Vec<(f32, T)> = Vec::new();
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
            let Some(&(_, format)) = offered.iter().find(|(r, _)| *r == range) else {
                continue;
            };
            if quality > 0.0 {
                ranges.push((quality, format));
            }
        }
    }
    if !any {
        return Some(default);
    }
    // Stable: among equal qualities the first listed wins.
    ranges.sort_by(|a, b| b.0.total_cmp(&a.0));
    ranges.first().map(|&(_, f)| f)
}

/// The extractor of an operation that answers JSON alone: present when
/// `Accept` admits `application/json` (no header, `*/*` and `application/*`
/// do), else a 406 problem. It reads only headers, so it answers before the
/// body is read.
#[derive(Debug, Clone, Copy)]
pub struct AcceptsJson;

impl<S: Send + Sync> FromRequestParts<S> for AcceptsJson {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _state: &S) -> Result<Self, ApiError> {
        const OFFERED: &[(&str, ())] = &[("application/json", ()), ("application/*", ()), ("*/*", ())];
        choose(&parts.headers, OFFERED, ())
            .map(|()| AcceptsJson)
            .ok_or_else(|| {
                ApiError::new(
                    StatusCode::NOT_ACCEPTABLE,
                    "not-acceptable",
                    "Not acceptable",
                    "this operation answers application/json only: send `Accept: application/json` or none",
                )
            })
    }
}

/// The response of an operation that answers JSON alone to an `Accept`
/// that admits no JSON (for the document).
#[derive(IntoResponses)]
#[allow(dead_code)]
pub enum NotAcceptable {
    /// `Accept` admits no `application/json`.
    #[response(
        status = 406,
        description = "`Accept` admits no application/json, the only format this operation answers",
        content_type = "application/problem+json"
    )]
    Json(Problem),
}

/// An operation that answers JSON alone: `POST $path` under `$tag` with a
/// JSON `$request`, answered by `$respond` as a JSON `$response` described as
/// `$answer`, with its OpenAPI operation (the doc comment is its summary and
/// description; its refusals are [`Problems`](crate::http::problem::Problems)
/// and [`NotAcceptable`]).
macro_rules! json_operation {
    ($(#[$doc:meta])* $name:ident: $path:tt in $tag:tt, $request:ident => $response:ident ($answer:tt) by $respond:ident) => {
        $(#[$doc])*
        #[utoipa::path(
            post,
            path = $path,
            tag = $tag,
            request_body(content = $request, content_type = "application/json"),
            responses(
                (status = 200, description = $answer, body = $response),
                crate::http::problem::Problems,
                crate::http::accept::NotAcceptable
            )
        )]
        pub async fn $name(
            _: crate::http::accept::AcceptsJson,
            crate::http::extract::ApiJson(req): crate::http::extract::ApiJson<$request>,
        ) -> Result<axum::Json<$response>, crate::http::problem::ApiError> {
            Ok(axum::Json($respond(req)?))
        }
    };
}
