//! `Accept` negotiation: which format a sweep is answered in.

use axum::http::{HeaderMap, StatusCode};

use crate::http::accept::choose;
use crate::http::problem::ApiError;

/// A response format of the sweep endpoint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `application/json`: one buffered table.
    Json,
    /// `application/x-ndjson`: one object per point, streamed.
    Ndjson,
    /// `text/csv`: a header row and one row per point, streamed.
    Csv,
    /// `image/svg+xml`: a buffered plot.
    Svg,
    /// `application/vnd.apache.arrow.stream`: an Arrow IPC stream, one record batch per chunk.
    Arrow,
}

impl Format {
    pub(super) fn is_buffered(self) -> bool {
        matches!(self, Format::Json | Format::Svg)
    }

    pub(super) fn content_type(self) -> &'static str {
        match self {
            Format::Json => "application/json",
            Format::Ndjson => "application/x-ndjson",
            Format::Csv => "text/csv; charset=utf-8; header=present",
            Format::Svg => "image/svg+xml",
            Format::Arrow => "application/vnd.apache.arrow.stream",
        }
    }
}

/// Picks the format from `Accept`: the acceptable range with the highest
/// quality wins; `*/*`, `application/*` or no header mean JSON.
pub fn negotiate(headers: &HeaderMap) -> Result<Format, ApiError> {
    const OFFERED: &[(&str, Format)] = &[
        ("application/json", Format::Json),
        ("application/*", Format::Json),
        ("*/*", Format::Json),
        ("application/x-ndjson", Format::Ndjson),
        ("application/jsonl", Format::Ndjson),
        ("text/csv", Format::Csv),
        ("text/*", Format::Csv),
        ("image/svg+xml", Format::Svg),
        ("image/*", Format::Svg),
        ("application/vnd.apache.arrow.stream", Format::Arrow),
    ];
    choose(headers, OFFERED, Format::Json).ok_or_else(|| {
        ApiError::new(
            StatusCode::NOT_ACCEPTABLE,
            "not-acceptable",
            "Not acceptable",
            "a sweep is available as application/json, application/x-ndjson, text/csv, \
             application/vnd.apache.arrow.stream or image/svg+xml",
        )
    })
}
