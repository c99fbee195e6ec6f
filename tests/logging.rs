//! The access log: one line per request, 5xx answers above info level with
//! their request id.
//!
//! Alone in its own test binary on purpose: the log is captured by a
//! thread-local subscriber (`tracing::subscriber::set_default`), and tracing
//! caches each call site's interest process-wide, so a server of another test
//! running on another thread can register the access-log call site as
//! uninteresting and its lines here are lost.

use std::time::Duration;

use reqwest::StatusCode;
use restitution::http::ServiceConfig;
use tokio::io::AsyncWriteExt;
use tokio::net::TcpStream;
use tokio::time::timeout;

const BOUND: Duration = Duration::from_secs(10);

/// The log lines written while the guard lives, on this thread (a
/// `#[tokio::test]` runs the server on the test's own thread).
struct CapturedLog {
    lines: std::sync::Arc<std::sync::Mutex<Vec<u8>>>,
    _guard: tracing::subscriber::DefaultGuard,
}

impl CapturedLog {
    fn start() -> Self {
        let lines = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
        let sink = lines.clone();
        let subscriber = tracing_subscriber::fmt()
            .with_ansi(false)
            .with_max_level(tracing::Level::INFO)
            .with_writer(move || SharedWriter(sink.clone()))
            .finish();
        CapturedLog {
            lines,
            _guard: tracing::subscriber::set_default(subscriber),
        }
    }

    /// The lines naming `request_id`.
    fn about(&self, request_id: &str) -> Vec<String> {
        let needle = format!("request_id={request_id} ");
        String::from_utf8_lossy(&self.lines.lock().unwrap())
            .lines()
            .filter(|line| line.contains(&needle))
            .map(str::to_owned)
            .collect()
    }
}

struct SharedWriter(std::sync::Arc<std::sync::Mutex<Vec<u8>>>);

impl std::io::Write for SharedWriter {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(bytes);
        Ok(bytes.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A 5xx is logged above info level with its request id, in the one access
/// line of the request: a handler's panic (500, with the panic message) at
/// error, load shedding (503) at warn; a 200 stays at info.
#[tokio::test]
async fn server_errors_are_logged_with_the_request_id() {
    let log = CapturedLog::start();
    let config = ServiceConfig {
        concurrency_limit: 1,
        ..ServiceConfig::default()
    };
    let router = axum::Router::new()
        .route(
            "/boom",
            axum::routing::get(|| async {
                if std::hint::black_box(true) {
                    panic!("the handler broke");
                }
                "unreachable"
            }),
        )
        .route("/ok", axum::routing::get(|| async { "ok" }))
        .route("/echo", axum::routing::post(|body: String| async move { body }));
    let router = restitution::http::with_middleware(router, &config);
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let served = config.clone();
    tokio::spawn(async move {
        restitution::http::serve_router_until(listener, router, &served, std::future::pending()).await
    });
    let client = reqwest::Client::new();
    let send = |method: reqwest::Method, path: &'static str| {
        let request = client
            .request(method, format!("http://{addr}{path}"))
            .body("0123456789");
        async move {
            let response = timeout(BOUND, request.send())
                .await
                .expect("answered in time")
                .unwrap();
            let id = response.headers()["x-request-id"].to_str().unwrap().to_owned();
            (response.status(), id)
        }
    };
    let get = |path: &'static str| send(reqwest::Method::GET, path);

    let (status, id) = get("/boom").await;
    assert_eq!(status, StatusCode::INTERNAL_SERVER_ERROR);
    let lines = log.about(&id);
    assert_eq!(lines.len(), 1, "one line per request: {lines:?}");
    assert!(lines[0].contains("ERROR"), "{lines:?}");
    assert!(lines[0].contains("status=500"), "{lines:?}");
    assert!(lines[0].contains("the handler broke"), "{lines:?}");

    let (status, id) = get("/ok").await;
    assert_eq!(status, StatusCode::OK);
    let lines = log.about(&id);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains(" INFO "), "{lines:?}");

    // The one slot (of the route: the limit applies per route) is held by a
    // request whose body never arrives.
    let mut held = TcpStream::connect(addr).await.unwrap();
    held.write_all(b"POST /echo HTTP/1.1\r\nhost: x\r\ncontent-length: 10\r\n\r\n")
        .await
        .unwrap();
    tokio::time::sleep(Duration::from_millis(200)).await;
    let (status, id) = send(reqwest::Method::POST, "/echo").await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    let lines = log.about(&id);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains(" WARN "), "{lines:?}");
    assert!(lines[0].contains("status=503"), "{lines:?}");
    drop(held);
}
