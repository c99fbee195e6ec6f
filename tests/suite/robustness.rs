//! Attacks over loopback: hostile bodies, overload, slow clients, a reader that
//! stops reading a stream, and the exposure settings (API key, CORS, nosniff).
//! Every wait is bounded by a timeout so a hang fails the test instead of
//! stalling it.

use std::time::Duration;

use crate::common::server::{TestApp, spawn_app};
use reqwest::StatusCode;
use restitution::http::ServiceConfig;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::time::timeout;

const BOUND: Duration = Duration::from_secs(10);

fn normal_request() -> Value {
    json!({"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5})
}

#[tokio::test]
async fn hostile_planar_contacts_get_a_422_naming_their_member_and_never_a_5xx() {
    let app = spawn_app(ServiceConfig::default()).await;
    let with = |pointer: &str, value: Value| {
        let mut r = crate::common::examples::cars();
        *r.pointer_mut(pointer).unwrap() = value;
        r
    };
    let lamina = crate::common::examples::cars()["bodies"][0].clone();
    let cases: Vec<(&str, Value, &str)> = vec![
        (
            "a third body",
            with("/bodies", json!([lamina, lamina, lamina])),
            "/bodies",
        ),
        ("no body", with("/bodies", json!([])), "/bodies"),
        (
            "a zero normal",
            with("/contact/normal", json!({"x": 0.0, "y": -0.0})),
            "/contact/normal",
        ),
        (
            "a negative mass",
            with("/bodies/1/mass", json!(-1.0)),
            "/bodies/1/mass",
        ),
        (
            "a zero inertia",
            with("/bodies/0/inertia", json!(0.0)),
            "/bodies/0/inertia",
        ),
        (
            "separating",
            with("/bodies/0/velocity", json!({"x": -15.0, "y": 0.0})),
            "/bodies/0/velocity",
        ),
        (
            "restitution above 1",
            with("/restitution", json!(1.5)),
            "/restitution",
        ),
        ("a huge friction", with("/friction", json!(1e308)), ""),
        (
            "a number as a string",
            with("/bodies/0/position/x", json!("NaN")),
            "/bodies/0/position/x",
        ),
        (
            "an unknown member",
            with("/contact/normal", json!({"x": 1.0, "y": 0.0, "z": 0.0})),
            "/contact/normal",
        ),
    ];
    for (name, body, pointer) in cases {
        let (status, _, problem) = timeout(BOUND, app.post("/v1/impacts/planar", &body))
            .await
            .unwrap();
        if pointer.is_empty() {
            assert!(status.is_success(), "{name}: {status} {problem}");
        } else {
            assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{name}: {problem}");
            assert!(
                problem["pointer"]
                    .as_str()
                    .is_some_and(|p| p.starts_with(pointer)),
                "{name}: {problem}"
            );
        }
        still_serving(&app).await;
    }
    // Huge arrays of bodies and numbers beyond f64: refused, not a 5xx.
    let many = format!(
        r#"{{"bodies": [{}], "contact": {{"point": {{"x": 0, "y": 0}}, "normal": {{"x": 1, "y": 0}}}}, "restitution": 0.5}}"#,
        vec![serde_json::to_string(&lamina).unwrap(); 5000].join(",")
    );
    let beyond = serde_json::to_string(&crate::common::examples::cars())
        .unwrap()
        .replace("1500.0", "1e400");
    for body in [many, beyond] {
        let response = timeout(
            BOUND,
            app.client
                .post(format!("{}/v1/impacts/planar", app.base))
                .header("content-type", "application/json")
                .body(body)
                .send(),
        )
        .await
        .unwrap()
        .unwrap();
        assert_eq!(response.status(), StatusCode::UNPROCESSABLE_ENTITY);
        still_serving(&app).await;
    }
}

/// A planar sweep of 10^12 points is refused before anything is computed,
/// naming its axes; the server keeps serving.
#[tokio::test]
async fn a_trillion_point_planar_sweep_is_refused_and_the_server_keeps_serving() {
    let app = spawn_app(ServiceConfig::default()).await;
    let million = json!({"start": 1.0, "stop": 30.0, "count": 1_000_000});
    let body = json!({
        "case": "planar",
        "base": crate::common::examples::cars(),
        "axes": [
            {"path": "/bodies/1/velocity/y", "linspace": million},
            {"path": "/contact/normal/y", "linspace": million}
        ]
    });
    let (status, _, problem) = timeout(BOUND, app.post("/v1/sweeps", &body)).await.unwrap();
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/axes", "{problem}");
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("1000000000000 points"),
        "{problem}"
    );
    still_serving(&app).await;
}

/// Posts raw bytes; returns status, content type and the body as JSON.
async fn raw(app: &TestApp, content_type: Option<&str>, body: Vec<u8>) -> (StatusCode, String, Value) {
    timeout(BOUND, app.post_raw("/v1/impacts/normal", content_type, body))
        .await
        .expect("answered in time")
}

async fn still_serving(app: &TestApp) {
    let (status, _, body) = timeout(BOUND, app.post("/v1/impacts/normal", &normal_request()))
        .await
        .expect("answered in time");
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["final_velocity"]["normal"], 1.5);
}

#[tokio::test]
async fn hostile_bodies_get_the_right_4xx_and_the_server_keeps_serving() {
    let app = spawn_app(ServiceConfig::default()).await;
    let json = Some("application/json");
    // Valid JSON nested 100,000 deep: the schema refuses it at the first level.
    let mut nested = "[".repeat(100_000);
    nested.push_str(&"]".repeat(100_000));
    let cases: Vec<(&str, Option<&str>, Vec<u8>, StatusCode)> = vec![
        (
            "deeply nested",
            json,
            nested.into_bytes(),
            StatusCode::UNPROCESSABLE_ENTITY,
        ),
        (
            "huge number",
            json,
            br#"{"body": {"mass": 1e400}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#.to_vec(),
            StatusCode::UNPROCESSABLE_ENTITY,
        ),
        (
            "number as string",
            json,
            br#"{"body": {"mass": "2.0"}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#.to_vec(),
            StatusCode::UNPROCESSABLE_ENTITY,
        ),
        (
            "duplicate key",
            json,
            br#"{"body": {"mass": 2.0, "mass": 3.0}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#
                .to_vec(),
            StatusCode::UNPROCESSABLE_ENTITY,
        ),
        (
            "long string",
            json,
            format!(r#"{{"body": {{"mass": "{}"}}}}"#, "x".repeat(500_000)).into_bytes(),
            StatusCode::UNPROCESSABLE_ENTITY,
        ),
        (
            "over the body limit",
            json,
            format!(r#"{{"body": {{"mass": "{}"}}}}"#, "x".repeat(2 << 20)).into_bytes(),
            StatusCode::PAYLOAD_TOO_LARGE,
        ),
        (
            "not UTF-8",
            json,
            b"{\"body\": {\"mass\": \xff\xfe}}".to_vec(),
            StatusCode::BAD_REQUEST,
        ),
        ("empty", json, Vec::new(), StatusCode::BAD_REQUEST),
        (
            "cut short",
            json,
            br#"{"body": {"mass": 2.0}, "veloc"#.to_vec(),
            StatusCode::BAD_REQUEST,
        ),
        (
            "wrong content type",
            Some("text/plain"),
            serde_json::to_vec(&normal_request()).unwrap(),
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
        ),
        (
            "no content type",
            None,
            serde_json::to_vec(&normal_request()).unwrap(),
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
        ),
    ];
    for (name, content_type, body, expected) in cases {
        let (status, ct, problem) = raw(&app, content_type, body).await;
        assert_eq!(status, expected, "{name}: {problem}");
        assert_eq!(ct, "application/problem+json", "{name}");
        assert_eq!(problem["status"], expected.as_u16(), "{name}");
        still_serving(&app).await;
    }
    // Deep nesting where the schema takes any JSON (a sweep's base): the parser's
    // recursion limit refuses it as malformed.
    let mut sweep = br#"{"case": "normal", "axes": [], "base": "#.to_vec();
    sweep.extend(b"[".repeat(100_000));
    sweep.extend(b"]".repeat(100_000));
    sweep.push(b'}');
    let response = timeout(
        BOUND,
        app.client
            .post(format!("{}/v1/sweeps", app.base))
            .header("content-type", "application/json")
            .body(sweep)
            .send(),
    )
    .await
    .unwrap()
    .unwrap();
    assert_eq!(response.status(), StatusCode::BAD_REQUEST);
    still_serving(&app).await;
    // A body that stops half-way: the connection ends before Content-Length bytes.
    let mut stream = TcpStream::connect(app.addr).await.unwrap();
    stream
        .write_all(
            b"POST /v1/impacts/normal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
              content-length: 200\r\n\r\n{\"body\": {\"mass\"",
        )
        .await
        .unwrap();
    stream.shutdown().await.unwrap();
    let mut reply = Vec::new();
    let _ = timeout(BOUND, stream.read_to_end(&mut reply))
        .await
        .expect("closed in time");
    let reply = String::from_utf8_lossy(&reply);
    assert!(reply.is_empty() || reply.starts_with("HTTP/1.1 400"), "{reply}");
    still_serving(&app).await;
    // A sweep whose point count overflows 64 bits (but not 128).
    let huge = json!({"start": 0.0, "stop": 1.0, "count": 9_223_372_036_854_775_807_u64});
    let sweep = json!({"case": "normal", "base": normal_request(), "axes": [
        {"path": "/velocity/normal", "linspace": huge},
        {"path": "/restitution", "values": [0.1, 0.2, 0.3, 0.4]}
    ]});
    let (status, _, problem) = timeout(BOUND, app.post("/v1/sweeps", &sweep)).await.unwrap();
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("36893488147419103228 points"),
        "{problem}"
    );
}

/// Opens a request whose body never arrives: it holds a concurrency slot.
async fn hold_a_slot(app: &TestApp) -> TcpStream {
    let length = serde_json::to_vec(&normal_request()).unwrap().len();
    let mut stream = TcpStream::connect(app.addr).await.unwrap();
    let head = format!(
        "POST /v1/impacts/normal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
         content-length: {length}\r\n\r\n"
    );
    stream.write_all(head.as_bytes()).await.unwrap();
    stream
}

#[tokio::test]
async fn at_the_concurrency_limit_excess_requests_are_shed_at_once() {
    let config = ServiceConfig {
        concurrency_limit: 2,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut held = vec![hold_a_slot(&app).await, hold_a_slot(&app).await];
    tokio::time::sleep(Duration::from_millis(200)).await;
    for _ in 0..10 {
        let response = timeout(Duration::from_secs(2), async {
            app.client
                .post(format!("{}/v1/impacts/normal", app.base))
                .json(&normal_request())
                .send()
                .await
                .unwrap()
        })
        .await
        .expect("shed at once, not queued");
        assert_eq!(response.status(), StatusCode::SERVICE_UNAVAILABLE);
        assert_eq!(response.headers()["retry-after"], "1");
        assert_eq!(response.headers()["content-type"], "application/problem+json");
    }
    // The held requests complete correctly once their bodies arrive.
    let body = serde_json::to_vec(&normal_request()).unwrap();
    for stream in &mut held {
        stream.write_all(&body).await.unwrap();
        let mut reply = vec![0u8; 1024];
        let n = timeout(BOUND, stream.read(&mut reply)).await.unwrap().unwrap();
        let reply = String::from_utf8_lossy(&reply[..n]);
        assert!(reply.starts_with("HTTP/1.1 200"), "{reply}");
        assert!(reply.contains("\"normal\":1.5"), "{reply}");
    }
    still_serving(&app).await;
}

#[tokio::test]
async fn a_bounded_burst_is_either_answered_correctly_or_shed() {
    let config = ServiceConfig {
        concurrency_limit: 4,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut tasks = Vec::new();
    for i in 0..400 {
        let client = app.client.clone();
        let url = format!("{}/v1/impacts/normal", app.base);
        let speed = -1.0 - f64::from(i % 7);
        tasks.push(tokio::spawn(async move {
            let body = json!({"body": {"mass": 2.0}, "velocity": {"normal": speed}, "restitution": 0.5});
            let response = client.post(url).json(&body).send().await.unwrap();
            let status = response.status();
            let value: Value = response.json().await.unwrap();
            (status, speed, value)
        }));
    }
    let (mut ok, mut shed) = (0, 0);
    for task in tasks {
        let (status, speed, value) = timeout(BOUND, task).await.unwrap().unwrap();
        match status {
            StatusCode::OK => {
                ok += 1;
                assert_eq!(value["final_velocity"]["normal"], -0.5 * speed);
            }
            StatusCode::SERVICE_UNAVAILABLE => {
                shed += 1;
                assert_eq!(value["status"], 503);
            }
            other => panic!("unexpected {other}: {value}"),
        }
    }
    assert_eq!(ok + shed, 400);
    assert!(ok > 0, "some requests are answered");
}

#[tokio::test]
async fn slow_headers_are_cut_off_and_slow_bodies_get_408() {
    let config = ServiceConfig {
        header_read_timeout_ms: 300,
        request_timeout_ms: 300,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    // Headers one byte at a time, 50 ms apart: the connection is closed.
    let mut stream = TcpStream::connect(app.addr).await.unwrap();
    let head = b"POST /v1/impacts/normal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n";
    let mut cut = false;
    for byte in head {
        if stream.write_all(&[*byte]).await.is_err() {
            cut = true;
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
        let mut probe = [0u8; 256];
        if let Ok(Ok(n)) = timeout(Duration::from_millis(1), stream.read(&mut probe)).await {
            // Closed (0) or answered with an error status before the headers ended.
            let reply = String::from_utf8_lossy(&probe[..n]);
            assert!(n == 0 || reply.starts_with("HTTP/1.1 408"), "{reply}");
            cut = true;
            break;
        }
    }
    assert!(cut, "the server waited for slow headers");
    still_serving(&app).await;
    // A body one byte at a time: 408 problem once the request timeout passes.
    let mut stream = hold_a_slot(&app).await;
    let body = serde_json::to_vec(&normal_request()).unwrap();
    let mut reply = Vec::new();
    for byte in body {
        if stream.write_all(&[byte]).await.is_err() {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
        let mut probe = [0u8; 1024];
        if let Ok(Ok(n)) = timeout(Duration::from_millis(1), stream.read(&mut probe)).await {
            reply.extend_from_slice(&probe[..n]);
            break;
        }
    }
    let reply = String::from_utf8_lossy(&reply);
    assert!(reply.starts_with("HTTP/1.1 408"), "{reply}");
    assert!(reply.contains("application/problem+json"), "{reply}");
    still_serving(&app).await;
}

/// Reads one HTTP/1.1 answer with a `content-length` from `stream`; `None`
/// if the connection closed first.
async fn read_answer(stream: &mut TcpStream) -> Option<String> {
    let mut answer = Vec::new();
    loop {
        if let Some(end) = answer.windows(4).position(|w| w == b"\r\n\r\n") {
            let head = String::from_utf8_lossy(&answer[..end]).to_ascii_lowercase();
            let length: usize = head
                .lines()
                .find_map(|line| line.strip_prefix("content-length:"))
                .map(|v| v.trim().parse().unwrap())
                .unwrap_or(0);
            if answer.len() >= end + 4 + length {
                return Some(String::from_utf8_lossy(&answer).into_owned());
            }
        }
        let mut buffer = [0u8; 4096];
        match timeout(BOUND, stream.read(&mut buffer))
            .await
            .expect("read in time")
        {
            Ok(0) | Err(_) => return None,
            Ok(n) => answer.extend_from_slice(&buffer[..n]),
        }
    }
}

/// The header-read timeout runs from a connection's start or the end of its
/// last answer: a keep-alive connection busy for longer than the timeout in
/// all is served throughout; one idle for longer is closed.
#[tokio::test]
async fn the_header_timeout_spares_a_busy_keep_alive_connection_and_closes_an_idle_one() {
    let config = ServiceConfig {
        header_read_timeout_ms: 300,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let body = serde_json::to_vec(&normal_request()).unwrap();
    let request = format!(
        "POST /v1/impacts/normal HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
         content-length: {}\r\n\r\n{}",
        body.len(),
        String::from_utf8(body).unwrap()
    );
    let mut stream = TcpStream::connect(app.addr).await.unwrap();
    // Ten requests 100 ms apart: a second in all, on one connection.
    for _ in 0..10 {
        stream.write_all(request.as_bytes()).await.unwrap();
        let answer = read_answer(&mut stream)
            .await
            .expect("answered on the same connection");
        assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    // Idle past the timeout: closed.
    tokio::time::sleep(Duration::from_millis(600)).await;
    let mut probe = [0u8; 64];
    let read = timeout(BOUND, stream.read(&mut probe))
        .await
        .expect("closed in time");
    assert!(matches!(read, Ok(0) | Err(_)), "{read:?}");
    still_serving(&app).await;
}

/// Sends a CSV sweep of ten million points on a new connection, its answer
/// left unread.
async fn request_long_csv_sweep(app: &TestApp) -> TcpStream {
    let body = serde_json::to_vec(&json!({
        "case": "normal", "base": normal_request(),
        "axes": [{"path": "/velocity/normal", "linspace": {"start": -5.0, "stop": -1.0, "count": 10_000_000}}]
    }))
    .unwrap();
    let mut stream = TcpStream::connect(app.addr).await.unwrap();
    let head = format!(
        "POST /v1/sweeps HTTP/1.1\r\nhost: x\r\naccept: text/csv\r\ncontent-type: application/json\r\n\
         content-length: {}\r\n\r\n",
        body.len()
    );
    stream.write_all(head.as_bytes()).await.unwrap();
    stream.write_all(&body).await.unwrap();
    stream
}

/// A streamed answer longer than the header-read timeout is not cut: the
/// timeout runs only while a connection waits for a request head.
#[tokio::test]
async fn a_stream_longer_than_the_header_timeout_is_not_cut() {
    let config = ServiceConfig {
        header_read_timeout_ms: 200,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut stream = request_long_csv_sweep(&app).await;
    // Read slowly for three times the timeout: data keeps coming.
    let start = std::time::Instant::now();
    let mut buffer = vec![0u8; 4096];
    while start.elapsed() < Duration::from_millis(600) {
        let n = timeout(BOUND, stream.read(&mut buffer)).await.unwrap().unwrap();
        assert!(n > 0, "the stream was cut after {:?}", start.elapsed());
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    assert_eq!(app.streams.active(), 1, "still streaming");
    drop(stream);
    app.until_sweeps_stop().await;
}

#[tokio::test]
async fn a_reader_that_stops_reading_a_stream_is_dropped_and_its_work_stops() {
    let config = ServiceConfig {
        sweep_stall_timeout_ms: 300,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut stream = request_long_csv_sweep(&app).await;
    let mut first = vec![0u8; 4096];
    let n = timeout(BOUND, stream.read(&mut first)).await.unwrap().unwrap();
    assert!(String::from_utf8_lossy(&first[..n]).starts_with("HTTP/1.1 200"));
    assert_eq!(app.streams.active(), 1);
    // Stop reading, keep the connection open.
    let stopped = timeout(BOUND, async {
        while app.streams.active() > 0 {
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    })
    .await;
    assert!(stopped.is_ok(), "the producer stopped after the stall timeout");
    still_serving(&app).await;
    drop(stream);
}

/// A client that stops reading is cut off by the write timeout, whatever
/// the sweep's own stall timeout: the connection closes and the stream's
/// producer stops with it.
#[tokio::test]
async fn a_connection_whose_client_stops_reading_is_closed_by_the_write_timeout() {
    let config = ServiceConfig {
        write_timeout_ms: 300,
        // Far longer than the test: only the write timeout can end it.
        sweep_stall_timeout_ms: 600_000,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut stream = request_long_csv_sweep(&app).await;
    let mut first = vec![0u8; 4096];
    let n = timeout(BOUND, stream.read(&mut first)).await.unwrap().unwrap();
    assert!(String::from_utf8_lossy(&first[..n]).starts_with("HTTP/1.1 200"));
    // Stop reading, keep the connection open: the socket buffers fill, the
    // server's writes wait, and the timeout closes the connection.
    let stopped = timeout(BOUND, async {
        while app.streams.active() > 0 {
            tokio::time::sleep(Duration::from_millis(20)).await;
        }
    })
    .await;
    assert!(stopped.is_ok(), "the stream ended after the write timeout");
    // What the socket still holds drains, then the connection is closed.
    let mut buffer = vec![0u8; 1 << 16];
    let closed = timeout(BOUND, async {
        loop {
            match stream.read(&mut buffer).await {
                Ok(0) | Err(_) => break,
                Ok(_) => {}
            }
        }
    })
    .await;
    assert!(closed.is_ok(), "the server closed the connection");
    still_serving(&app).await;
}

#[tokio::test]
async fn the_api_key_guards_every_route_but_health() {
    let config = ServiceConfig {
        api_key: Some("s3cret-token".into()),
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let url = format!("{}/v1/impacts/normal", app.base);
    let missing = app
        .client
        .post(&url)
        .json(&normal_request())
        .send()
        .await
        .unwrap();
    assert_eq!(missing.status(), StatusCode::UNAUTHORIZED);
    assert_eq!(
        missing.headers()["www-authenticate"],
        "Bearer realm=\"restitution\""
    );
    assert_eq!(missing.headers()["content-type"], "application/problem+json");
    let wrong = app
        .client
        .post(&url)
        .bearer_auth("s3cret-tokem")
        .json(&normal_request())
        .send()
        .await
        .unwrap();
    assert_eq!(wrong.status(), StatusCode::UNAUTHORIZED);
    let problem: Value = wrong.json().await.unwrap();
    assert_eq!(problem["type"], "urn:restitution:problem:invalid-api-key");
    let right = app
        .client
        .post(&url)
        .bearer_auth("s3cret-token")
        .json(&normal_request())
        .send()
        .await
        .unwrap();
    assert_eq!(right.status(), StatusCode::OK);
    let health = app
        .client
        .get(format!("{}/healthz", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(health.status(), StatusCode::OK);
    // The documentation is open like the explorer page (a browser opening
    // either cannot send the key); the document declares the bearer scheme.
    for path in ["/openapi.json", "/docs/"] {
        let docs = app
            .client
            .get(format!("{}{path}", app.base))
            .send()
            .await
            .unwrap();
        assert_eq!(docs.status(), StatusCode::OK, "{path}");
    }
    let document: Value = app
        .client
        .get(format!("{}/openapi.json", app.base))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    assert!(
        document["components"]["securitySchemes"]["bearer"].is_object(),
        "{document}"
    );
    // A path beside the documentation is not opened by it.
    let beside = app
        .client
        .get(format!("{}/docsx", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(beside.status(), StatusCode::UNAUTHORIZED);
}

#[tokio::test]
async fn cors_is_off_by_default_and_follows_the_allow_list() {
    let off = spawn_app(ServiceConfig::default()).await;
    let response = off
        .client
        .post(format!("{}/v1/impacts/normal", off.base))
        .header("origin", "http://localhost:3000")
        .json(&normal_request())
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::OK);
    assert!(!response.headers().contains_key("access-control-allow-origin"));
    assert_eq!(response.headers()["x-content-type-options"], "nosniff");

    let config = ServiceConfig {
        cors_allow_origins: vec!["http://localhost:3000".to_owned()],
        api_key: Some("k".into()),
        ..ServiceConfig::default()
    };
    let on = spawn_app(config).await;
    let preflight = |origin: &'static str| {
        on.client
            .request(reqwest::Method::OPTIONS, format!("{}/v1/impacts/normal", on.base))
            .header("origin", origin)
            .header("access-control-request-method", "POST")
            .header("access-control-request-headers", "content-type, authorization")
            .send()
    };
    let allowed = preflight("http://localhost:3000").await.unwrap();
    assert_eq!(allowed.status(), StatusCode::OK);
    assert_eq!(
        allowed.headers()["access-control-allow-origin"],
        "http://localhost:3000"
    );
    let other = preflight("http://evil.example").await.unwrap();
    assert!(!other.headers().contains_key("access-control-allow-origin"));
}
