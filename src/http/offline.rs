//! The service without a server: `restitution solve` and `restitution sweep`
//! send their requests through the same application in-process (same DTOs,
//! same checks, same problem+json errors), for scripts and batch jobs (a
//! Kubernetes Indexed Job computing one range of a sweep) that want no HTTP.

use std::io::{BufRead, Write};
use std::path::Path;

use axum::Router;
use axum::body::Body;
use axum::http::{Request, StatusCode, header};
use futures_util::StreamExt;
use serde_json::Value;
use tower::ServiceExt;

use super::ServiceConfig;

/// Settings of the in-process application: no point limit for streamed and
/// reduced sweeps and no request deadline (a batch job may run for hours);
/// the buffered formats keep their limit.
fn offline_config() -> ServiceConfig {
    ServiceConfig {
        max_sweep_points: u64::MAX,
        request_timeout_ms: 30 * 24 * 3600 * 1000,
        sweep_stall_timeout_ms: 30 * 24 * 3600 * 1000,
        body_limit: 64 << 20,
        ..ServiceConfig::default()
    }
}

/// Why an offline command failed.
#[derive(Debug, thiserror::Error)]
pub enum OfflineError {
    /// Reading or writing a file or a standard stream failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The service refused the request: its problem+json document.
    #[error("{0}")]
    Refused(String),
}

/// Posts `body` to `path` and returns the status, content type and body stream.
async fn post(app: &Router, path: &str, accept: &str, body: Vec<u8>) -> (StatusCode, String, Body) {
    let request = Request::post(path)
        .header(header::CONTENT_TYPE, "application/json")
        .header(header::ACCEPT, accept)
        .body(Body::from(body))
        .expect("a valid request");
    let response = app
        .clone()
        .oneshot(request)
        .await
        .expect("the router is infallible");
    let content_type = response
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .unwrap_or_default()
        .to_owned();
    (response.status(), content_type, response.into_body())
}

async fn collect(body: Body) -> Result<Vec<u8>, std::io::Error> {
    let mut out = Vec::new();
    let mut stream = body.into_data_stream();
    while let Some(chunk) = stream.next().await {
        out.extend_from_slice(&chunk.map_err(std::io::Error::other)?);
    }
    Ok(out)
}

/// The JSON documents of `input`: one per line, or one spread over several
/// lines (a line that ends inside a document takes the next ones); a line that
/// is not JSON is passed on as it is, for the service to refuse.
fn documents(input: impl BufRead) -> impl Iterator<Item = std::io::Result<String>> {
    let mut lines = input.lines();
    std::iter::from_fn(move || {
        let mut document = String::new();
        loop {
            match lines.next() {
                None if document.trim().is_empty() => return None,
                None => return Some(Ok(document)),
                Some(Err(e)) => return Some(Err(e)),
                Some(Ok(line)) => {
                    document.push_str(&line);
                    document.push('\n');
                    if document.trim().is_empty() {
                        document.clear();
                        continue;
                    }
                    match serde_json::from_str::<serde::de::IgnoredAny>(&document) {
                        Err(e) if e.is_eof() => continue,
                        _ => return Some(Ok(document)),
                    }
                }
            }
        }
    })
}

/// `restitution solve CASE`: answers each JSON request on `input` (one per
/// line, or documents spread over lines) with one line on `output`: the case
/// endpoint's answer, or its problem+json. Returns the number of refused requests.
pub async fn solve(case: &str, input: impl BufRead, mut output: impl Write) -> Result<u64, OfflineError> {
    let app = super::app(&offline_config());
    let path = format!("/v1/impacts/{case}");
    let mut refused = 0;
    for document in documents(input) {
        let (status, _, body) = post(&app, &path, "application/json", document?.into_bytes()).await;
        let mut bytes = collect(body).await?;
        if !status.is_success() {
            refused += 1;
        }
        // One line per answer.
        if let Ok(value) = serde_json::from_slice::<Value>(&bytes) {
            bytes = serde_json::to_vec(&value).unwrap_or(bytes);
        }
        output.write_all(&bytes)?;
        output.write_all(b"\n")?;
    }
    output.flush()?;
    Ok(refused)
}

/// Which slice of a sweep to compute.
#[derive(Debug, Clone, Copy)]
pub struct Shard {
    /// Number of shards.
    pub shards: u64,
    /// This one's index (0-based).
    pub index: u64,
}

/// A sweep output format, by name or by file extension.
pub fn accept_for(format: &str) -> Option<&'static str> {
    match format {
        "csv" => Some("text/csv"),
        "ndjson" | "jsonl" => Some("application/x-ndjson"),
        "arrow" | "arrows" => Some("application/vnd.apache.arrow.stream"),
        "json" => Some("application/json"),
        "svg" => Some("image/svg+xml"),
        _ => None,
    }
}

/// `restitution sweep`: computes the sweep request in `request` (its
/// `shard`, when given: the ranges `POST /v1/sweeps/plan` gives for that many
/// shards) in the format `accept` names, streaming it to `output`.
pub async fn sweep(
    request: &Path,
    shard: Option<Shard>,
    accept: &str,
    mut output: impl Write,
) -> Result<(), OfflineError> {
    let app = super::app(&offline_config());
    let mut sweep: Value = serde_json::from_slice(&std::fs::read(request)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("{}: {e}", request.display()),
        )
    })?;
    if let Some(Shard { shards, index }) = shard {
        if index >= shards {
            return Err(OfflineError::Refused(format!(
                "--index {index} is not below --shards {shards}"
            )));
        }
        let plan = serde_json::json!({"sweep": sweep, "shards": shards});
        let (status, _, body) = post(
            &app,
            "/v1/sweeps/plan",
            "application/json",
            plan.to_string().into_bytes(),
        )
        .await;
        let bytes = collect(body).await?;
        if !status.is_success() {
            return Err(OfflineError::Refused(
                String::from_utf8_lossy(&bytes).into_owned(),
            ));
        }
        let plan: Value = serde_json::from_slice(&bytes).map_err(std::io::Error::other)?;
        sweep["range"] = plan["ranges"][index as usize].clone();
    }
    // A reduction is answered as JSON whatever the format.
    let accept = if sweep.get("reduce").is_some_and(|r| !r.is_null()) {
        "application/json"
    } else {
        accept
    };
    let (status, _, body) = post(&app, "/v1/sweeps", accept, sweep.to_string().into_bytes()).await;
    if !status.is_success() {
        let bytes = collect(body).await?;
        return Err(OfflineError::Refused(
            String::from_utf8_lossy(&bytes).into_owned(),
        ));
    }
    let mut stream = body.into_data_stream();
    while let Some(chunk) = stream.next().await {
        output.write_all(&chunk.map_err(std::io::Error::other)?)?;
    }
    output.flush()?;
    Ok(())
}
