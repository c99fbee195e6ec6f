//! The API key of a service run with `--api-key-file`: which paths are open
//! without it, and the middleware that refuses the others.

use std::sync::Arc;

use axum::extract::{Request, State};
use axum::http::{HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::problem::ApiError;
use super::{OPEN_ROUTES, web};

/// Whether `path` is the API's documentation: Swagger UI at `/docs` and the
/// OpenAPI document it loads.
fn is_documentation(path: &str) -> bool {
    path == "/openapi.json" || path == "/docs" || path.starts_with("/docs/")
}

/// Refuses every request but the probes, metrics, the explorer page and the
/// API's documentation without `Authorization: Bearer <key>` (401). The pages
/// are open because a browser opening them cannot send the key; they hold no
/// data and compute nothing, and every call they make to `/v1` sends the key
/// typed into them (the explorer's field, Swagger UI's "Authorize").
pub(super) async fn require_api_key(State(key): State<Arc<str>>, request: Request, next: Next) -> Response {
    let path = request.uri().path();
    if OPEN_ROUTES.contains(&path) || web::is_page(path) || is_documentation(path) {
        return next.run(request).await;
    }
    let token = request
        .headers()
        .get(axum::http::header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.split_once(' '))
        .filter(|(scheme, _)| scheme.eq_ignore_ascii_case("bearer"))
        .map(|(_, token)| token.trim());
    let refusal = match token {
        Some(token) if same_secret(token.as_bytes(), key.as_bytes()) => return next.run(request).await,
        Some(_) => ApiError::new(
            StatusCode::UNAUTHORIZED,
            "invalid-api-key",
            "Invalid API key",
            "the bearer token is not the service's API key",
        ),
        None => ApiError::new(
            StatusCode::UNAUTHORIZED,
            "missing-api-key",
            "API key required",
            "send the service's API key as `Authorization: Bearer <key>`",
        ),
    };
    let mut response = refusal.into_response();
    response.headers_mut().insert(
        axum::http::header::WWW_AUTHENTICATE,
        HeaderValue::from_static("Bearer realm=\"restitution\""),
    );
    response
}

/// Compares secrets in time independent of where they differ.
fn same_secret(given: &[u8], key: &[u8]) -> bool {
    given.len() == key.len() && given.iter().zip(key).fold(0u8, |acc, (a, b)| acc | (a ^ b)) == 0
}
