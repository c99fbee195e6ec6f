//! `/metrics` and `/readyz` over loopback: the text parses as the Prometheus
//! exposition format and its counters move with traffic; readiness turns 503
//! while the service drains for shutdown and while it sheds load.

use std::collections::BTreeMap;
use std::time::Duration;

use crate::common::server::spawn_app;
use reqwest::StatusCode;
use restitution::http::{AppState, ServiceConfig, serve_app_until};
use serde_json::json;

/// Parses the text exposition format strictly enough to catch a malformed
/// document: every sample line is `name{label="value",...} number`, every
/// sample's family has a `# TYPE`, and the document ends with `# EOF`.
fn parse(text: &str) -> BTreeMap<String, f64> {
    let mut samples = BTreeMap::new();
    let mut families = Vec::new();
    let mut ended = false;
    for line in text.lines() {
        assert!(!ended, "text after # EOF");
        if line == "# EOF" {
            ended = true;
            continue;
        }
        if let Some(rest) = line.strip_prefix("# TYPE ") {
            let (name, kind) = rest.split_once(' ').expect("# TYPE name kind");
            assert!(["counter", "gauge", "histogram"].contains(&kind), "{line}");
            families.push(name.to_owned());
            continue;
        }
        if line.starts_with("# HELP ") || line.starts_with("# UNIT ") {
            continue;
        }
        let (series, value) = line
            .rsplit_once(' ')
            .unwrap_or_else(|| panic!("a sample: {line}"));
        let value: f64 = value.parse().unwrap_or_else(|_| panic!("a number: {line}"));
        let name = series.split('{').next().unwrap();
        assert!(
            name.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':'),
            "{line}"
        );
        if let Some(labels) = series.strip_prefix(name) {
            if !labels.is_empty() {
                let inner = labels
                    .strip_prefix('{')
                    .and_then(|l| l.strip_suffix('}'))
                    .expect("{labels}");
                for pair in inner.split("\",").filter(|p| !p.is_empty()) {
                    let (key, value) = pair.split_once("=\"").unwrap_or_else(|| panic!("label: {line}"));
                    assert!(
                        key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'),
                        "{line}"
                    );
                    assert!(!value.contains('\n'), "{line}");
                }
            }
        }
        assert!(
            families.iter().any(|f| name.starts_with(f.as_str())),
            "{name} has no # TYPE"
        );
        samples.insert(series.to_owned(), value);
    }
    assert!(ended, "the document ends with # EOF");
    samples
}

async fn metrics(app: &crate::common::server::TestApp) -> BTreeMap<String, f64> {
    let response = app
        .client
        .get(format!("{}/metrics", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::OK);
    assert!(
        response.headers()["content-type"]
            .to_str()
            .unwrap()
            .starts_with("text/plain; version=0.0.4")
    );
    parse(&response.text().await.unwrap())
}

fn oblique(precision: &str) -> serde_json::Value {
    json!({
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.01, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.3, "angular": 2.0},
        "restitution": 0.93, "friction": 0.123, "precision": precision
    })
}

#[tokio::test]
async fn metrics_parse_and_move_with_traffic() {
    let app = spawn_app(ServiceConfig::default()).await;
    let before = metrics(&app).await;
    let ok = r#"restitution_http_requests_total{route="/v1/impacts/oblique",method="POST",status="200"}"#;
    let refused =
        r#"restitution_http_requests_total{route="/v1/impacts/oblique",method="POST",status="422"}"#;
    let exact = r#"restitution_exact_settled_total{stage="compensated"}"#;
    let points = r#"restitution_sweep_points_total{case="oblique",precision="fast"}"#;
    let latency = r#"restitution_http_request_duration_seconds_count{route="/v1/impacts/oblique"}"#;
    let get = |m: &BTreeMap<String, f64>, k: &str| m.get(k).copied().unwrap_or(0.0);
    for _ in 0..3 {
        let (status, _, _) = app.post("/v1/impacts/oblique", &oblique("fast")).await;
        assert_eq!(status, StatusCode::OK);
    }
    let (status, _, _) = app.post("/v1/impacts/oblique", &oblique("exact")).await;
    assert_eq!(status, StatusCode::OK);
    let mut bad = oblique("fast");
    bad["restitution"] = json!(2.0);
    let (status, _, _) = app.post("/v1/impacts/oblique", &bad).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let sweep = json!({"case": "oblique", "base": oblique("fast"),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 1.0, "count": 5000}}]});
    let (status, _, _) = app.post_accept("/v1/sweeps", "text/csv", &sweep).await;
    assert_eq!(status, StatusCode::OK);
    let after = metrics(&app).await;
    assert_eq!(get(&after, ok) - get(&before, ok), 4.0);
    assert_eq!(get(&after, refused) - get(&before, refused), 1.0);
    assert_eq!(get(&after, latency) - get(&before, latency), 5.0);
    assert_eq!(get(&after, points) - get(&before, points), 5000.0);
    // The stage counters are process-wide; other tests may add to them.
    assert!(get(&after, exact) > get(&before, exact), "{after:?}");
    // The scrape is served outside the middleware, so nothing is in flight now.
    assert_eq!(get(&after, "restitution_http_requests_in_flight"), 0.0);
}

#[tokio::test]
async fn readiness_turns_503_while_draining_and_the_service_still_answers() {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let base = format!("http://{}", listener.local_addr().unwrap());
    let config = ServiceConfig {
        shutdown_drain_ms: 1_500,
        ..ServiceConfig::default()
    };
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let server = tokio::spawn(async move {
        serve_app_until(listener, &config, AppState::default(), async {
            let _ = stopped.await;
        })
        .await
    });
    let client = reqwest::Client::new();
    let ready = client.get(format!("{base}/readyz")).send().await.unwrap();
    assert_eq!(ready.status(), StatusCode::OK);
    assert_eq!(
        ready.json::<serde_json::Value>().await.unwrap()["status"],
        "ready"
    );
    stop.send(()).unwrap();
    tokio::time::sleep(Duration::from_millis(100)).await;
    let draining = client.get(format!("{base}/readyz")).send().await.unwrap();
    assert_eq!(draining.status(), StatusCode::SERVICE_UNAVAILABLE);
    assert_eq!(
        draining.json::<serde_json::Value>().await.unwrap()["status"],
        "draining"
    );
    let health = client.get(format!("{base}/healthz")).send().await.unwrap();
    assert_eq!(health.status(), StatusCode::OK, "still serving while draining");
    tokio::time::timeout(Duration::from_secs(10), server)
        .await
        .expect("the server stops after the drain")
        .unwrap()
        .unwrap();
}

#[tokio::test]
async fn readiness_turns_503_while_shedding_load() {
    // A window long enough that freeing the slot (a reduction's workers stop
    // at their next chunk) ends inside it on a loaded machine: the first CI
    // run that took longer than the default second to free it failed here.
    let window = Duration::from_millis(5_000);
    let app = spawn_app(ServiceConfig {
        concurrency_limit: 1,
        shedding_window_ms: window.as_millis() as u64,
        ..ServiceConfig::default()
    })
    .await;
    // Hold the only slot with a reduction of ten million points.
    let slow = json!({"case": "oblique", "base": oblique("fast"),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 1.0, "count": 10_000_000}}],
        "reduce": {}});
    let held = {
        let (client, url) = (app.client.clone(), format!("{}/v1/sweeps", app.base));
        tokio::spawn(async move { client.post(url).json(&slow).send().await })
    };
    while app.streams.active() == 0 {
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    // Liveness and metrics are answered by a saturated service.
    assert_eq!(app.get("/healthz").await.0, StatusCode::OK);
    assert!(metrics(&app).await["restitution_http_requests_in_flight"] >= 1.0);
    // Shed, then free the slot at once: readiness is checked within the window.
    let before_shed = std::time::Instant::now();
    let (status, _, _) = app.post("/v1/impacts/oblique", &oblique("fast")).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "shed at the limit");
    held.abort();
    app.until_sweeps_stop().await;
    let (status, readiness) = app.get("/readyz").await;
    assert!(
        before_shed.elapsed() < window,
        "the slot was freed inside the window"
    );
    assert_eq!(
        (status, &readiness["status"]),
        (StatusCode::SERVICE_UNAVAILABLE, &json!("shedding"))
    );
    let m = metrics(&app).await;
    assert!(m["restitution_http_requests_shed_total"] >= 1.0);
    // Ready again once the window has passed since the shed, not before (the
    // service counts whole milliseconds: 2 ms of slack).
    let ready_at = loop {
        let (status, readiness) = app.get("/readyz").await;
        if status == StatusCode::OK {
            assert_eq!(readiness["status"], json!("ready"));
            break before_shed.elapsed();
        }
        assert_eq!(readiness["status"], json!("shedding"));
        assert!(
            before_shed.elapsed() < window + Duration::from_secs(10),
            "never ready again"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    };
    assert!(
        ready_at + Duration::from_millis(2) >= window,
        "ready {ready_at:?} after the shed, inside the {window:?} window"
    );
}
