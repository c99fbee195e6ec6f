//! `ApiJson<T>`: the JSON body extractor whose every rejection is problem+json:
//! 415 for a missing or wrong content type, 413 for a body over the limit,
//! 400 for malformed JSON, 422 (with the member's JSON pointer) for a wrong
//! type, a missing or an unknown field, or a number too large for a double.

use axum::body::Bytes;
use axum::extract::{FromRequest, Request};
use axum::http::{StatusCode, header};
use serde::de::DeserializeOwned;
use serde_path_to_error::Segment;

use super::problem::ApiError;

/// A JSON request body deserialized into `T`.
pub struct ApiJson<T>(pub T);

impl<S, T> FromRequest<S> for ApiJson<T>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, Self::Rejection> {
        if !is_json(&req) {
            return Err(ApiError::new(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "unsupported-media-type",
                "Unsupported media type",
                "the request body must be JSON, sent with `Content-Type: application/json`",
            ));
        }
        let bytes = Bytes::from_request(req, state).await.map_err(|rejection| {
            let status = rejection.status();
            if status == StatusCode::PAYLOAD_TOO_LARGE {
                ApiError::new(
                    status,
                    "body-too-large",
                    "Request body too large",
                    rejection.body_text(),
                )
            } else {
                ApiError::new(
                    status,
                    "unreadable-body",
                    "Request body could not be read",
                    rejection.body_text(),
                )
            }
        })?;
        parse(&bytes).map(ApiJson)
    }
}

fn is_json(req: &Request) -> bool {
    let Some(value) = req
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
    else {
        return false;
    };
    let Ok(mime) = value.parse::<mime::Mime>() else {
        return false;
    };
    mime.type_() == mime::APPLICATION
        && (mime.subtype() == mime::JSON || mime.suffix().is_some_and(|s| s == mime::JSON))
}

/// Deserializes `bytes`, mapping failures to 400 (syntax) or 422 (data).
pub fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    let value = serde_path_to_error::deserialize(&mut deserializer);
    if value.is_ok() {
        if let Err(trailing) = deserializer.end() {
            return Err(malformed(&trailing));
        }
    }
    value.map_err(|error| {
        let inner = error.inner();
        match inner.classify() {
            serde_json::error::Category::Data => {
                // A data error found before the end may hide malformed JSON further on.
                if let Err(syntax) = serde_json::from_slice::<serde::de::IgnoredAny>(bytes) {
                    return malformed(&syntax);
                }
                schema_mismatch("", error.path(), inner)
            }
            // serde_json counts a number beyond f64's range (`1e999`) as a syntax
            // error, but it is well-formed JSON with a value the schema cannot take.
            serde_json::error::Category::Syntax if is_out_of_range(inner) => {
                // Skipping values does not convert numbers: this checks the rest of the syntax.
                if let Err(syntax) = serde_json::from_slice::<serde::de::IgnoredAny>(bytes) {
                    return malformed(&syntax);
                }
                schema_mismatch("", error.path(), inner)
            }
            // serde_json reports a value of the wrong kind where an enum is
            // read (`"precision": 12.5`) as "expected value", a syntax error:
            // well-formed JSON is read again from its tree, which says what
            // the member takes, at its pointer.
            serde_json::error::Category::Syntax => match serde_json::from_slice::<serde_json::Value>(bytes) {
                Ok(tree) => match parse_value::<T>(tree, "") {
                    Ok(_) => malformed(inner),
                    Err(problem) => problem,
                },
                Err(_) => malformed(inner),
            },
            _ => malformed(inner),
        }
    })
}

/// serde_json's error for a number whose magnitude does not fit its type.
fn is_out_of_range(error: &serde_json::Error) -> bool {
    error.to_string().starts_with(OUT_OF_RANGE)
}

/// serde_json's message for a number too large for an f64.
const OUT_OF_RANGE: &str = "number out of range";

/// Deserializes a JSON value that sits at `prefix` in the request body (a
/// member holding a request of its own); a mismatch is a 422 naming the member
/// by its pointer from the body's root.
pub fn parse_value<T: DeserializeOwned>(value: serde_json::Value, prefix: &str) -> Result<T, ApiError> {
    serde_path_to_error::deserialize(value)
        .map_err(|error| schema_mismatch(prefix, error.path(), error.inner()))
}

fn schema_mismatch(prefix: &str, path: &serde_path_to_error::Path, inner: &serde_json::Error) -> ApiError {
    let mut pointer = prefix.to_owned();
    pointer.push_str(&pointer_of(path));
    let message = inner.to_string();
    // serde names a missing field in the message, not in the path.
    if let Some(field) = quoted_field(&message, "missing field `") {
        pointer.push('/');
        pointer.push_str(&field.replace('~', "~0").replace('/', "~1"));
    }
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "invalid-body",
        "Request body does not match the schema",
        plain_words(&strip_position(&message)),
    )
    .at(pointer)
}

/// Rewords serde's Rust type names for the client: a wrong type on an `f64`
/// member says "expected a number", not "expected f64"; an integer member
/// says "expected a whole number" (non-negative for unsigned types); a number
/// beyond a double's range says so.
fn plain_words(message: &str) -> String {
    if message.starts_with(OUT_OF_RANGE) {
        return format!("{OUT_OF_RANGE}: the number does not fit a double (magnitude above 1.8e308)");
    }
    const EXPECTED: &str = ", expected ";
    let Some(at) = message.rfind(EXPECTED) else {
        return message.to_owned();
    };
    let wording = match &message[at + EXPECTED.len()..] {
        "f64" | "f32" => "a number",
        "u8" | "u16" | "u32" | "u64" | "u128" | "usize" => "a non-negative whole number",
        "i8" | "i16" | "i32" | "i64" | "i128" | "isize" => "a whole number",
        _ => return message.to_owned(),
    };
    format!("{}{EXPECTED}{wording}", &message[..at])
}

fn malformed(error: &serde_json::Error) -> ApiError {
    ApiError::new(
        StatusCode::BAD_REQUEST,
        "malformed-json",
        "Malformed JSON",
        format!("the request body is not valid JSON: {error}"),
    )
}

fn pointer_of(path: &serde_path_to_error::Path) -> String {
    let mut pointer = String::new();
    for segment in path.iter() {
        match segment {
            Segment::Seq { index } => pointer.push_str(&format!("/{index}")),
            Segment::Map { key } => {
                pointer.push('/');
                pointer.push_str(&key.replace('~', "~0").replace('/', "~1"));
            }
            Segment::Enum { variant } => {
                pointer.push('/');
                pointer.push_str(variant);
            }
            Segment::Unknown => {}
        }
    }
    pointer
}

fn quoted_field(message: &str, prefix: &str) -> Option<String> {
    let rest = message.strip_prefix(prefix)?;
    rest.split('`').next().map(str::to_owned)
}

/// Drops serde_json's " at line L column C" suffix from a data error.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(i) => message[..i].to_owned(),
        None => message.to_owned(),
    }
}
