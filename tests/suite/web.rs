//! The explorer page (`/` and `/assets/…`) over loopback: content types, the
//! Content-Security-Policy, ETags, every asset the page reaches served from
//! the binary and nothing fetched from elsewhere, the page open without the
//! API key and absent from the OpenAPI document, and every preset a request
//! the service answers.

use std::collections::BTreeSet;

use crate::common::server::spawn_app;
use reqwest::StatusCode;
use restitution::http::web::CONTENT_SECURITY_POLICY;
use restitution::http::{ServiceConfig, openapi};
use serde_json::Value;

/// The one absolute URL the assets may hold: the SVG namespace, an XML
/// identifier that is never fetched.
const SVG_NAMESPACE: &str = "http://www.w3.org/2000/svg";

async fn get(app: &crate::common::server::TestApp, path: &str) -> reqwest::Response {
    app.client
        .get(format!("{}{path}", app.base))
        .send()
        .await
        .expect("send")
}

fn header<'a>(response: &'a reqwest::Response, name: &str) -> &'a str {
    response
        .headers()
        .get(name)
        .unwrap_or_else(|| panic!("{} lacks {name}", response.url()))
        .to_str()
        .unwrap()
}

/// The values of `attribute="…"` in `html`.
fn attribute_values(html: &str, attribute: &str) -> Vec<String> {
    let needle = format!(" {attribute}=\"");
    html.match_indices(&needle)
        .map(|(at, _)| {
            let rest = &html[at + needle.len()..];
            rest[..rest.find('"').unwrap()].to_owned()
        })
        .collect()
}

/// The modules a script imports (`from './x.js'`), as asset paths.
fn imports(script: &str) -> Vec<String> {
    script
        .match_indices("from './")
        .map(|(at, _)| {
            let rest = &script[at + "from './".len()..];
            format!("/assets/{}", &rest[..rest.find('\'').unwrap()])
        })
        .collect()
}

/// Every `http://` or `https://` in `text`, with what follows up to a quote,
/// space or bracket.
fn absolute_urls(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for scheme in ["http://", "https://"] {
        for (at, _) in text.match_indices(scheme) {
            let rest = &text[at..];
            let end = rest
                .find(|c: char| {
                    c == '"' || c == '\'' || c == '`' || c == ')' || c == '<' || c.is_whitespace()
                })
                .unwrap_or(rest.len());
            found.push(rest[..end].to_owned());
        }
    }
    found
}

fn expected_type(path: &str) -> &'static str {
    match path.rsplit('.').next() {
        Some("js") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("svg") => "image/svg+xml",
        Some("json") => "application/json",
        _ => "text/html; charset=utf-8",
    }
}

fn assert_page_headers(response: &reqwest::Response) {
    assert_eq!(
        header(response, "content-security-policy"),
        CONTENT_SECURITY_POLICY
    );
    assert_eq!(header(response, "cache-control"), "no-cache");
    assert_eq!(header(response, "x-content-type-options"), "nosniff");
    let etag = header(response, "etag");
    assert!(
        etag.starts_with('"') && etag.ends_with('"') && etag.len() > 10,
        "{etag}"
    );
}

#[test]
fn the_policy_admits_the_page_s_own_origin_only() {
    let directives: Vec<&str> = CONTENT_SECURITY_POLICY.split(';').map(str::trim).collect();
    for expected in [
        "default-src 'none'",
        "script-src 'self'",
        "style-src 'self'",
        "img-src 'self'",
        "connect-src 'self'",
        "object-src 'none'",
        "base-uri 'none'",
        "frame-ancestors 'none'",
    ] {
        assert!(directives.contains(&expected), "{expected} missing");
    }
    assert!(!CONTENT_SECURITY_POLICY.contains("unsafe"));
    assert!(!CONTENT_SECURITY_POLICY.contains("http"));
    assert!(!CONTENT_SECURITY_POLICY.contains('*'));
}

#[tokio::test]
async fn the_page_and_every_asset_it_reaches_are_served_from_the_binary() {
    let app = spawn_app(ServiceConfig::default()).await;
    let page = get(&app, "/").await;
    assert_eq!(page.status(), StatusCode::OK);
    assert_eq!(header(&page, "content-type"), "text/html; charset=utf-8");
    assert_page_headers(&page);
    let html = page.text().await.unwrap();
    assert!(html.starts_with("<!doctype html>"));

    // No inline script, style or handler: the policy would block them.
    assert!(!html.contains(" style=\""), "inline style attribute");
    assert!(!html.contains("<style"), "inline style element");
    assert!(
        !html.contains(" onclick=") && !html.contains(" onload="),
        "inline handler"
    );
    for (at, _) in html.match_indices("<script") {
        let tag = &html[at..at + html[at..].find('>').unwrap()];
        assert!(tag.contains(" src=\"/assets/"), "inline script: {tag}");
    }

    // What the page loads: local paths only; links may name the API docs.
    let mut queue: Vec<String> = Vec::new();
    for value in attribute_values(&html, "src") {
        assert!(value.starts_with("/assets/"), "src {value}");
        queue.push(value);
    }
    for value in attribute_values(&html, "href") {
        assert!(
            value.starts_with('#') || (value.starts_with('/') && !value.starts_with("//")),
            "href {value} is not on this origin"
        );
        if value.starts_with("/assets/") {
            queue.push(value);
        }
    }
    // The JSON the page fetches: the presets, the quantity table and the operations.
    for asset in ["presets", "quantities", "operations"] {
        queue.push(format!("/assets/{asset}.json"));
    }

    let mut seen = BTreeSet::new();
    while let Some(path) = queue.pop() {
        if !seen.insert(path.clone()) {
            continue;
        }
        let response = get(&app, &path).await;
        assert_eq!(response.status(), StatusCode::OK, "{path}");
        assert_eq!(header(&response, "content-type"), expected_type(&path), "{path}");
        assert_page_headers(&response);
        let text = response.text().await.unwrap();
        for url in absolute_urls(&text) {
            assert_eq!(url, SVG_NAMESPACE, "{path} names {url}");
        }
        if path.ends_with(".js") {
            for (at, _) in text.match_indices("fetch(") {
                let argument = &text[at + "fetch(".len()..];
                assert!(
                    argument.starts_with("path") || argument.starts_with("'/"),
                    "{path}: fetch of {}",
                    &argument[..argument.len().min(30)]
                );
            }
            assert!(!text.contains("import("), "{path}: dynamic import");
            assert!(!text.contains("eval("), "{path}: eval");
            queue.extend(imports(&text));
        }
        if path.ends_with(".css") {
            assert!(!text.contains("url("), "{path}: a url() in the styles");
            assert!(!text.contains("@import"), "{path}: an @import");
        }
    }

    // Every file of src/http/web is reached (none embedded for nothing, none
    // forgotten).
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/http/web");
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name != "index.html" {
            assert!(
                seen.contains(&format!("/assets/{name}")),
                "{name} is not reached from the page"
            );
        }
    }
}

#[tokio::test]
async fn assets_are_revalidated_by_etag() {
    let app = spawn_app(ServiceConfig::default()).await;
    for path in ["/", "/assets/app.js", "/assets/style.css"] {
        let first = get(&app, path).await;
        let etag = header(&first, "etag").to_owned();
        let again = app
            .client
            .get(format!("{}{path}", app.base))
            .header("if-none-match", &etag)
            .send()
            .await
            .unwrap();
        assert_eq!(again.status(), StatusCode::NOT_MODIFIED, "{path}");
        assert_eq!(header(&again, "etag"), etag);
        assert!(again.bytes().await.unwrap().is_empty());
        let other = app
            .client
            .get(format!("{}{path}", app.base))
            .header("if-none-match", "\"something-else\"")
            .send()
            .await
            .unwrap();
        assert_eq!(other.status(), StatusCode::OK, "{path}");
    }
    let head = app
        .client
        .head(format!("{}/assets/app.js", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(head.status(), StatusCode::OK);
    let missing = get(&app, "/assets/nope.js").await;
    assert_eq!(missing.status(), StatusCode::NOT_FOUND);
    assert_eq!(header(&missing, "content-type"), "application/problem+json");
    let post = app.client.post(format!("{}/", app.base)).send().await.unwrap();
    assert_eq!(post.status(), StatusCode::METHOD_NOT_ALLOWED);
}

#[tokio::test]
async fn the_page_is_open_without_the_api_key_and_the_api_is_not() {
    let config = ServiceConfig {
        api_key: Some("s3cret-token".into()),
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    for path in ["/", "/assets/app.js", "/assets/presets.json"] {
        assert_eq!(get(&app, path).await.status(), StatusCode::OK, "{path}");
    }
    let api = app
        .client
        .post(format!("{}/v1/impacts/normal", app.base))
        .json(&serde_json::json!({"body": {"mass": 1.0}, "velocity": {"normal": -1.0}, "restitution": 0.5}))
        .send()
        .await
        .unwrap();
    assert_eq!(api.status(), StatusCode::UNAUTHORIZED);
    // A path beside the assets is not opened by them.
    assert_eq!(get(&app, "/assetsx").await.status(), StatusCode::UNAUTHORIZED);
}

#[test]
fn the_page_is_not_in_the_openapi_document() {
    let doc = openapi();
    for path in doc.paths.paths.keys() {
        assert!(
            path.starts_with("/v1/") || ["/healthz", "/readyz", "/metrics"].contains(&path.as_str()),
            "{path}"
        );
    }
}

#[tokio::test]
async fn every_preset_is_a_request_the_service_answers() {
    let app = spawn_app(ServiceConfig::default()).await;
    let presets: Value = get(&app, "/assets/presets.json").await.json().await.unwrap();
    let presets = presets.as_array().unwrap();
    let ids: Vec<&str> = presets.iter().map(|p| p["id"].as_str().unwrap()).collect();
    for id in [
        "maw-oblique",
        "maw-tangential",
        "spinning-ball",
        "cars",
        "tennis-topspin",
    ] {
        assert!(ids.contains(&id), "{id}");
    }
    for preset in presets {
        let case = preset["case"].as_str().unwrap();
        let (status, _, body) = app.post(&format!("/v1/impacts/{case}"), &preset["request"]).await;
        assert_eq!(status, StatusCode::OK, "{}: {body}", preset["id"]);
        if let Some(sweep) = preset.get("sweep") {
            let request = serde_json::json!({
                "case": case, "base": preset["request"], "axes": sweep["axes"], "outputs": sweep["outputs"]
            });
            let (status, _, body) = app.post("/v1/sweeps", &request).await;
            assert_eq!(status, StatusCode::OK, "{} sweep: {body}", preset["id"]);
        }
    }
    // The Maw disc of the oblique case is the README's: sliding at v_t = 2.
    let maw = &presets[0];
    assert_eq!(maw["id"], "maw-oblique");
    let (_, _, outcome) = app.post("/v1/impacts/oblique", &maw["request"]).await;
    assert_eq!(outcome["regime"], "sliding");
}

/// The explorer's labels and units come from the service's quantity table:
/// the asset is the table `GET /v1/quantities` serves, and no script of the
/// page holds an output's name or a list of operations of its own.
#[tokio::test]
async fn the_page_reads_the_quantity_table_and_the_operations_from_the_service() {
    let app = spawn_app(ServiceConfig::default()).await;
    let asset: Value = get(&app, "/assets/quantities.json").await.json().await.unwrap();
    let served: Value = get(&app, "/v1/quantities").await.json().await.unwrap();
    assert_eq!(asset, served);
    let cases = asset["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 6);
    // The forms label inputs; an output that is also an input (`e`, `μ`, `R`) is theirs.
    let inputs: BTreeSet<&str> = cases
        .iter()
        .flat_map(|c| c["inputs"].as_array().unwrap())
        .map(|i| i["name"].as_str().unwrap())
        .collect();
    let outputs: BTreeSet<&str> = cases
        .iter()
        .flat_map(|c| c["outputs"].as_array().unwrap())
        .map(|o| o["name"].as_str().unwrap())
        // A name of several words is a label; "regime" is also a word of the page's prose.
        .filter(|name| name.split(' ').count() > 2 && !inputs.contains(name))
        .collect();
    assert!(outputs.contains("final tangential contact velocity"));
    let operations: Value = get(&app, "/assets/operations.json").await.json().await.unwrap();
    assert_eq!(
        operations["/v1/impacts/spatial"],
        serde_json::json!({"module": "impacts", "function": "impacts_spatial", "model": "SpatialContactRequest"})
    );
    let html = get(&app, "/").await.text().await.unwrap();
    let mut scripts: Vec<String> = attribute_values(&html, "src")
        .into_iter()
        .filter(|s| s.ends_with(".js"))
        .collect();
    let mut seen = BTreeSet::new();
    while let Some(path) = scripts.pop() {
        if !seen.insert(path.clone()) {
            continue;
        }
        let text = get(&app, &path).await.text().await.unwrap();
        scripts.extend(imports(&text));
        for name in &outputs {
            assert!(!text.contains(name), "{path} names the output {name:?}");
        }
        assert!(!text.contains("'impacts_spatial'"), "{path} lists operations");
    }
    assert!(seen.len() > 5, "{seen:?}");
}
