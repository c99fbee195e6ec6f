//! `Accept` negotiation: which format a sweep (or a fit) is answered in.

use axum::http::{HeaderMap, StatusCode, header};

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

/// The format of the `offered` media range that `Accept` ranks highest (the
/// first listed among equal qualities); `default` without an `Accept` range;
/// `None` when no offered range is acceptable.
pub(crate) fn choose<T: Copy>(headers: &HeaderMap, offered: &[(&str, T)], default: T) -> Option<T> {
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
