//! The explorer: a page at `/` and its assets at `/assets/…`, for people who
//! would rather set a scene than write JSON. Plain HTML, CSS and
//! vanilla JavaScript modules, embedded in the binary (no CDN, no font, no
//! build step); the page calls the API under `/v1` like any client. It is not
//! API: it is routed outside the OpenAPI document and outside the API key
//! (the page itself holds no data; its calls to `/v1` carry the key the user
//! types in).
//!
//! Every answer here carries an `ETag` (revalidated: `Cache-Control:
//! no-cache`), and a Content-Security-Policy that lets the page load and
//! fetch from its own origin only, with no inline script or style.

use std::sync::LazyLock;

use axum::Router;
use axum::extract::Path;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use serde_json::{Value, json};

use super::problem::ApiError;

/// The page's policy: everything from its own origin, nothing inline, no
/// plugins, no framing.
pub const CONTENT_SECURITY_POLICY: &str = "default-src 'none'; script-src 'self'; style-src 'self'; \
     img-src 'self'; connect-src 'self'; font-src 'none'; object-src 'none'; base-uri 'none'; \
     form-action 'self'; frame-ancestors 'none'";

/// Where the assets are served.
pub const ASSETS: &str = "/assets/";

/// The routes of the page: `/` and `/assets/{name}`.
pub fn router() -> Router {
    Router::new()
        .route("/", get(index))
        .route("/assets/{name}", get(asset))
}

/// Whether `path` is the page's (open without the API key).
pub fn is_page(path: &str) -> bool {
    path == "/" || path.starts_with(ASSETS)
}

/// One embedded file.
struct Asset {
    name: &'static str,
    content_type: &'static str,
    body: Vec<u8>,
    etag: HeaderValue,
}

impl Asset {
    fn new(name: &'static str, content_type: &'static str, body: Vec<u8>) -> Self {
        use sha2::{Digest, Sha256};
        let digest = Sha256::digest(&body);
        let hex: String = digest[..12].iter().map(|b| format!("{b:02x}")).collect();
        let etag = HeaderValue::from_str(&format!("\"{hex}\"")).expect("hex is a valid header");
        Asset {
            name,
            content_type,
            body,
            etag,
        }
    }
}

const HTML: &str = "text/html; charset=utf-8";
const JS: &str = "text/javascript; charset=utf-8";
const CSS: &str = "text/css; charset=utf-8";
const JSON: &str = "application/json";
const SVG: &str = "image/svg+xml";

/// The page and its assets, the first one being the page.
static FILES: LazyLock<Vec<Asset>> = LazyLock::new(|| {
    let file =
        |name, content_type, text: &'static str| Asset::new(name, content_type, text.as_bytes().to_vec());
    vec![
        file("index.html", HTML, include_str!("web/index.html")),
        file("style.css", CSS, include_str!("web/style.css")),
        file("app.js", JS, include_str!("web/app.js")),
        file("cases.js", JS, include_str!("web/cases.js")),
        file("form.js", JS, include_str!("web/form.js")),
        file("scene.js", JS, include_str!("web/scene.js")),
        file("outcome.js", JS, include_str!("web/outcome.js")),
        file("sweep.js", JS, include_str!("web/sweep.js")),
        file("fit.js", JS, include_str!("web/fit.js")),
        file("share.js", JS, include_str!("web/share.js")),
        file("api.js", JS, include_str!("web/api.js")),
        file("favicon.svg", SVG, include_str!("web/favicon.svg")),
        Asset::new("presets.json", JSON, presets().to_string().into_bytes()),
        Asset::new(
            "quantities.json",
            JSON,
            serde_json::to_vec(&super::quantities::table()).expect("the table serialises"),
        ),
        Asset::new("operations.json", JSON, operations().to_string().into_bytes()),
    ]
});

/// A preset's source: a request of its case, or a sweep whose base is one.
enum Source {
    Impact(&'static str),
    Sweep(&'static str),
}

/// The presets, from the repository's examples (whose numbers `tests/http.rs`
/// and `tests/sweeps.rs` check): id, label, case, the request (or a sweep
/// with its base), a sweep to offer beside it, and inputs set over the
/// example's (JSON pointer, value).
#[allow(clippy::type_complexity)]
const PRESETS: &[(&str, &str, &str, Source, Option<&str>, &[(&str, f64)])] = &[
    (
        "maw-oblique",
        "Maw's steel disc, Coulomb friction (Figure 2)",
        "oblique",
        Source::Sweep(include_str!("../../examples/figure2_coulomb_friction.json")),
        None,
        &[("/velocity/tangential", 2.0)],
    ),
    (
        "maw-tangential",
        "Maw's steel disc, tangential restitution (Figure 3)",
        "tangential",
        Source::Sweep(include_str!(
            "../../examples/figure3_tangential_restitution_maw.json"
        )),
        None,
        &[("/velocity/tangential", 0.4)],
    ),
    (
        "spinning-ball",
        "Spinning ball, torsional restitution (Figure 4, after Horak)",
        "torsional",
        Source::Sweep(include_str!("../../examples/figure4_torsional_rubber_ball.json")),
        None,
        &[("/velocity/spin", 40.0)],
    ),
    (
        "cars",
        "Two cars at an intersection",
        "planar",
        Source::Impact(include_str!("../../examples/planar_car_to_car.json")),
        Some(include_str!("../../examples/planar_car_to_car_sweep.json")),
        &[],
    ),
    (
        "billiards",
        "Billiard cut shot (two discs)",
        "planar",
        Source::Impact(include_str!("../../examples/planar_billiard_discs.json")),
        None,
        &[],
    ),
    (
        "tennis-topspin",
        "Tennis ball with topspin",
        "spatial",
        Source::Impact(include_str!("../../examples/spatial_tennis_topspin.json")),
        None,
        &[],
    ),
    (
        "tennis-sidespin",
        "Tennis ball with sidespin and twist",
        "spatial",
        Source::Impact(include_str!("../../examples/spatial_tennis_sidespin.json")),
        None,
        &[],
    ),
    (
        "dem-spheres",
        "Two DEM spheres",
        "spatial",
        Source::Impact(include_str!("../../examples/spatial_dem_spheres.json")),
        None,
        &[],
    ),
    (
        "robot-tool",
        "Robot tool on a plate",
        "spatial",
        Source::Impact(include_str!("../../examples/spatial_robot_tool.json")),
        None,
        &[],
    ),
    (
        "cube-corner",
        "Tossed cube, a corner on the board (fitted e and f)",
        "spatial",
        Source::Impact(include_str!("../../examples/spatial_cube_corner.json")),
        None,
        &[],
    ),
];

/// The presets as the page reads them: `[{id, label, case, request, sweep?}]`,
/// `sweep` holding the axes and outputs of a sweep over the request.
fn presets() -> Value {
    let parse = |text: &str| serde_json::from_str::<Value>(text).expect("the examples are JSON");
    let sweep_part = |sweep: &Value| json!({"axes": sweep["axes"], "outputs": sweep["outputs"]});
    let list = PRESETS
        .iter()
        .map(|(id, label, case, source, sweep, set)| {
            let (mut request, mut offered) = match source {
                Source::Impact(text) => (parse(text), None),
                Source::Sweep(text) => {
                    let sweep = parse(text);
                    (sweep["base"].clone(), Some(sweep_part(&sweep)))
                }
            };
            if let Some(text) = sweep {
                offered = Some(sweep_part(&parse(text)));
            }
            for (pointer, value) in *set {
                if let Some(slot) = request.pointer_mut(pointer) {
                    *slot = json!(value);
                }
            }
            let mut preset = json!({"id": id, "label": label, "case": case, "request": request});
            if let Some(offered) = offered {
                preset["sweep"] = offered;
            }
            preset
        })
        .collect();
    Value::Array(list)
}

/// The POST operations of the OpenAPI document, as the page's share
/// snippets name them in the client `openapi-python-client` generates:
/// `{path: {module, function, model}}` (the operation's tag, its id, its
/// request schema).
fn operations() -> Value {
    let doc = serde_json::to_value(super::openapi()).expect("the document serialises");
    let mut out = serde_json::Map::new();
    for (path, item) in doc["paths"].as_object().expect("paths") {
        let Some(post) = item.get("post") else { continue };
        let model = post
            .pointer("/requestBody/content/application~1json/schema/$ref")
            .and_then(Value::as_str)
            .and_then(|r| r.rsplit('/').next());
        if let (Some(module), Some(function), Some(model)) = (
            post.pointer("/tags/0").and_then(Value::as_str),
            post["operationId"].as_str(),
            model,
        ) {
            out.insert(
                path.clone(),
                json!({"module": module, "function": function, "model": model}),
            );
        }
    }
    Value::Object(out)
}

async fn index(headers: HeaderMap) -> Response {
    serve(&FILES[0], &headers)
}

async fn asset(Path(name): Path<String>, headers: HeaderMap) -> Response {
    match FILES.iter().skip(1).find(|a| a.name == name) {
        Some(found) => serve(found, &headers),
        None => ApiError::new(
            StatusCode::NOT_FOUND,
            "not-found",
            "Not found",
            format!("no asset {ASSETS}{name}"),
        )
        .into_response(),
    }
}

/// The asset, or 304 when the client's copy is current.
fn serve(asset: &Asset, request: &HeaderMap) -> Response {
    let current = request
        .get_all(header::IF_NONE_MATCH)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|tag| {
            let tag = tag.trim();
            tag == "*" || tag.trim_start_matches("W/").as_bytes() == asset.etag.as_bytes()
        });
    let mut response = if current {
        StatusCode::NOT_MODIFIED.into_response()
    } else {
        let mut response = asset.body.clone().into_response();
        response
            .headers_mut()
            .insert(header::CONTENT_TYPE, HeaderValue::from_static(asset.content_type));
        response
    };
    let headers = response.headers_mut();
    headers.insert(header::ETAG, asset.etag.clone());
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    headers.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static(CONTENT_SECURITY_POLICY),
    );
    headers.insert(header::REFERRER_POLICY, HeaderValue::from_static("no-referrer"));
    response
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_requests_of_their_case() {
        let presets = presets();
        let list = presets.as_array().unwrap();
        assert_eq!(list.len(), PRESETS.len());
        for preset in list {
            assert!(preset["request"].is_object(), "{preset}");
            assert!(preset["case"].is_string(), "{preset}");
        }
        assert_eq!(list[0]["request"]["velocity"]["tangential"], 2.0);
        assert_eq!(list[0]["sweep"]["axes"][0]["path"], "/velocity/tangential");
        assert_eq!(list[3]["sweep"]["axes"][0]["path"], "/bodies/1/velocity/y");
    }

    #[test]
    fn every_file_is_named_once() {
        let mut names: Vec<_> = FILES.iter().map(|a| a.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), FILES.len());
    }
}
