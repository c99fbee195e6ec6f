//! HTTP load harness: the release binary and a baseline server, each in its
//! own process on 127.0.0.1, driven by a keep-alive client in this process.
//!
//! The baseline serves the same paths through the same middleware stack and
//! connection loop (`restitution::http::with_middleware`, `serve_router_until`)
//! and the same configuration, but its handlers only deserialize the request
//! into the endpoint's DTO and serialize a response of the same size (computed
//! once at start-up): the cost of everything but the physics.
//!
//! ```text
//! cargo bench --bench load                    # concurrency 1, 16, 64; 5 s (≤ 500,000 requests) per cell
//! cargo bench --bench load -- --smoke         # CI: 0.5 s per cell, concurrency 1 and 16
//! cargo bench --bench load -- --soak SECONDS  # mixed traffic, resident memory over time
//! cargo bench --bench load -- --precision     # the service with "precision": "fast" against "exact"
//! cargo bench --bench load -- --metrics       # the service with request metrics on against off
//! ```
//! Every run is bounded in requests and seconds and targets loopback only.

use std::net::{SocketAddr, TcpListener};
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use axum::Json;
use axum::routing::post;
use bytes::Bytes;
use http_body_util::{BodyExt, Full};
use hyper::Request;
use hyper_util::rt::TokioIo;
use restitution::http::extract::{ApiJson, parse};
use restitution::http::impacts::{NormalRequest, ObliqueRequest, TangentialRequest, TorsionalRequest};
use restitution::http::{ServiceConfig, serve_router_until, with_middleware};

const NORMAL: &str = r#"{"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#;
const OBLIQUE: &str = r#"{"body": {"mass": 1.0, "inertia": 0.00125},
  "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
  "velocity": {"normal": -1.0, "tangential": 2.0, "angular": 0.0},
  "restitution": 0.93, "friction": 0.123}"#;
const TANGENTIAL: &str = r#"{"body": {"mass": 1.0, "inertia": 0.00125},
  "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
  "velocity": {"normal": -1.0, "tangential": 0.1, "angular": 0.0},
  "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34}"#;
const TORSIONAL: &str = r#"{"body": {"mass": 0.6, "normal_inertia": 0.003456},
  "velocity": {"normal": -3.0, "spin": 20.0}, "restitution": 0.7,
  "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}}"#;
const SMALL_SWEEP: &str = r#"{"case": "tangential", "base": {"body": {"mass": 1.0, "inertia": 0.00125},
  "contact": {"tangential_offset": 0.0, "normal_offset": 0.05}, "velocity": {"normal": -1.0},
  "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34},
  "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 200}}]}"#;
const CSV_SWEEP: &str = r#"{"case": "oblique", "base": {"body": {"mass": 1.0, "inertia": 0.00125},
  "contact": {"tangential_offset": 0.01, "normal_offset": 0.05}, "velocity": {"normal": -1.0, "angular": 2.0},
  "restitution": 0.93, "friction": 0.123},
  "axes": [{"path": "/velocity/tangential", "linspace": {"start": -5.0, "stop": 5.0, "count": 20000}}]}"#;

const ENDPOINTS: [(&str, &str); 4] = [
    ("/v1/impacts/normal", NORMAL),
    ("/v1/impacts/oblique", OBLIQUE),
    ("/v1/impacts/tangential", TANGENTIAL),
    ("/v1/impacts/torsional", TORSIONAL),
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(i) = args.iter().position(|a| a == "--serve-baseline") {
        let port: u16 = args[i + 1].parse().expect("a port");
        serve_baseline(port, true);
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--serve-bare") {
        let port: u16 = args[i + 1].parse().expect("a port");
        serve_baseline(port, false);
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--soak") {
        let seconds: u64 = args.get(i + 1).and_then(|s| s.parse().ok()).unwrap_or(600);
        soak(Duration::from_secs(seconds));
        return;
    }
    let smoke = args.iter().any(|a| a == "--smoke");
    if args.iter().any(|a| a == "--metrics") {
        compare_metrics(smoke);
        return;
    }
    if args.iter().any(|a| a == "--precision") {
        compare_precision(smoke);
        return;
    }
    compare(smoke);
}

/// The request with `"precision"` set (the field is top-level on every impact and sweep request).
fn with_precision(body: &str, precision: &str) -> Bytes {
    let rest = body.strip_prefix('{').expect("a JSON object");
    Bytes::from(format!(r#"{{"precision": "{precision}", {rest}"#))
}

/// The service answering each endpoint, and two sweeps, in `fast` and in
/// `exact` precision: what choosing `exact` costs a caller over HTTP.
fn compare_precision(smoke: bool) {
    let (levels, duration, max): (&[usize], _, _) = if smoke {
        (&[1, 16], Duration::from_millis(500), 50_000)
    } else {
        (&[1, 16], Duration::from_secs(5), 500_000)
    };
    let runtime = client_runtime();
    let service = product();
    println!(
        "| request | concurrency | fast req/s | exact req/s | exact/fast time | fast p50 ms | exact p50 ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let sweeps = [
        (
            "/v1/sweeps",
            "application/json",
            SMALL_SWEEP,
            "200-point JSON sweep",
        ),
        ("/v1/sweeps", "text/csv", CSV_SWEEP, "20,000-point CSV sweep"),
    ];
    let requests = ENDPOINTS
        .iter()
        .map(|&(path, body)| (path, "application/json", body, path))
        .chain(sweeps);
    let mut failures = 0;
    for (path, accept, body, name) in requests {
        for &c in levels {
            let mut cells = Vec::new();
            for precision in ["fast", "exact"] {
                let bodies = vec![(path, accept, with_precision(body, precision))];
                drive(
                    &runtime,
                    service.addr,
                    bodies.clone(),
                    c,
                    Duration::from_millis(100),
                    10_000,
                );
                let cell = drive(&runtime, service.addr, bodies, c, duration, max);
                failures += cell.failures;
                cells.push(cell);
            }
            let (fast, exact) = (cells[0].rps(), cells[1].rps());
            let (f50, e50) = (cells[0].percentile(0.5), cells[1].percentile(0.5));
            println!(
                "| {name} | {c} | {fast:.0} | {exact:.0} | {:.2} | {f50:.3} | {e50:.3} |",
                fast / exact
            );
        }
    }
    assert_eq!(failures, 0, "every request answered 200");
}

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// A child server process, killed on drop.
struct Server {
    child: Child,
    addr: SocketAddr,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn spawn(program: &std::path::Path, args: &[String], port: u16) -> Server {
    let child = Command::new(program)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start a server");
    let addr = SocketAddr::from(([127, 0, 0, 1], port));
    let deadline = Instant::now() + Duration::from_secs(10);
    while std::net::TcpStream::connect(addr).is_err() {
        assert!(Instant::now() < deadline, "server did not start");
        std::thread::sleep(Duration::from_millis(5));
    }
    Server { child, addr }
}

fn product() -> Server {
    product_with(&[])
}

fn product_with(extra: &[&str]) -> Server {
    let port = free_port();
    let mut args = vec!["--bind".to_owned(), format!("127.0.0.1:{port}")];
    args.extend(extra.iter().map(|a| (*a).to_owned()));
    spawn(
        std::path::Path::new(env!("CARGO_BIN_EXE_restitution")),
        &args,
        port,
    )
}

fn baseline() -> Server {
    let port = free_port();
    let me = std::env::current_exe().expect("this harness");
    spawn(&me, &["--serve-baseline".to_owned(), port.to_string()], port)
}

/// The bare baseline: the same handlers on plain `axum::serve`, no middleware, no log.
fn bare() -> Server {
    let port = free_port();
    let me = std::env::current_exe().expect("this harness");
    spawn(&me, &["--serve-bare".to_owned(), port.to_string()], port)
}

/// The baseline: the same DTOs in, same-sized responses out, no physics;
/// through the service's middleware and connection loop, or bare (plain
/// `axum::serve`, no middleware, no log).
fn serve_baseline(port: u16, middleware: bool) {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async move {
        if middleware {
            tracing_subscriber::fmt()
                .with_env_filter(tracing_subscriber::EnvFilter::new("info"))
                .init();
        }
        use restitution::http::impacts as i;
        let normal = i::respond_normal(parse(NORMAL.as_bytes()).unwrap()).unwrap();
        let oblique = i::respond_oblique(parse(OBLIQUE.as_bytes()).unwrap()).unwrap();
        let tangential = i::respond_tangential(parse(TANGENTIAL.as_bytes()).unwrap()).unwrap();
        let torsional = i::respond_torsional(parse(TORSIONAL.as_bytes()).unwrap()).unwrap();
        let router = axum::Router::new()
            .route(
                "/v1/impacts/normal",
                post(move |ApiJson(_): ApiJson<NormalRequest>| async move { Json(normal) }),
            )
            .route(
                "/v1/impacts/oblique",
                post(move |ApiJson(_): ApiJson<ObliqueRequest>| async move { Json(oblique) }),
            )
            .route(
                "/v1/impacts/tangential",
                post(move |ApiJson(_): ApiJson<TangentialRequest>| async move { Json(tangential) }),
            )
            .route(
                "/v1/impacts/torsional",
                post(move |ApiJson(_): ApiJson<TorsionalRequest>| async move { Json(torsional) }),
            );
        let config = ServiceConfig::default();
        let listener = tokio::net::TcpListener::bind(("127.0.0.1", port)).await.unwrap();
        if !middleware {
            axum::serve(listener, router).await.unwrap();
            return;
        }
        serve_router_until(
            listener,
            with_middleware(router, &config),
            &config,
            restitution::http::shutdown_signal(),
        )
        .await
        .unwrap();
    });
}

/// Latencies and counts of one run.
struct Cell {
    requests: u64,
    failures: u64,
    seconds: f64,
    latencies_us: Vec<u32>,
}

impl Cell {
    fn rps(&self) -> f64 {
        self.requests as f64 / self.seconds
    }
    fn percentile(&mut self, p: f64) -> f64 {
        if self.latencies_us.is_empty() {
            return f64::NAN;
        }
        self.latencies_us.sort_unstable();
        let i = ((self.latencies_us.len() - 1) as f64 * p).round() as usize;
        f64::from(self.latencies_us[i]) / 1000.0
    }
}

/// One connection's loop: requests from `bodies` in turn until the deadline or the shared budget.
async fn user(
    addr: SocketAddr,
    bodies: Arc<Vec<(&'static str, &'static str, Bytes)>>,
    offset: usize,
    deadline: Instant,
    budget: Arc<AtomicU64>,
) -> (u64, u64, Vec<u32>) {
    let stream = tokio::net::TcpStream::connect(addr).await.expect("connect");
    stream.set_nodelay(true).unwrap();
    let (mut sender, connection) = hyper::client::conn::http1::handshake(TokioIo::new(stream))
        .await
        .expect("handshake");
    tokio::spawn(connection);
    let (mut ok, mut failed, mut latencies) = (0, 0, Vec::new());
    let mut k = offset;
    while Instant::now() < deadline && budget.fetch_sub(1, Ordering::Relaxed) > 0 {
        let (path, accept, body) = &bodies[k % bodies.len()];
        k += 1;
        let request = Request::post(*path)
            .header("host", "127.0.0.1")
            .header("content-type", "application/json")
            .header("accept", *accept)
            .body(Full::new(body.clone()))
            .unwrap();
        let start = Instant::now();
        let Ok(response) = sender.send_request(request).await else {
            failed += 1;
            break;
        };
        let status = response.status();
        let complete = response.into_body().collect().await.is_ok();
        latencies.push(start.elapsed().as_micros().min(u128::from(u32::MAX)) as u32);
        if status.is_success() && complete {
            ok += 1;
        } else {
            failed += 1;
        }
    }
    (ok, failed, latencies)
}

fn drive(
    runtime: &tokio::runtime::Runtime,
    addr: SocketAddr,
    bodies: Bodies,
    concurrency: usize,
    duration: Duration,
    max_requests: u64,
) -> Cell {
    let bodies = Arc::new(bodies);
    runtime.block_on(async {
        let budget = Arc::new(AtomicU64::new(max_requests));
        let start = Instant::now();
        let deadline = start + duration;
        let users: Vec<_> = (0..concurrency)
            .map(|u| tokio::spawn(user(addr, bodies.clone(), u, deadline, budget.clone())))
            .collect();
        let mut cell = Cell {
            requests: 0,
            failures: 0,
            seconds: 0.0,
            latencies_us: Vec::new(),
        };
        for u in users {
            let (ok, failed, latencies) = u.await.expect("user");
            cell.requests += ok;
            cell.failures += failed;
            cell.latencies_us.extend(latencies);
        }
        cell.seconds = start.elapsed().as_secs_f64();
        cell
    })
}

fn client_runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap()
}

/// Baseline and product side by side for every endpoint and concurrency.
fn compare(smoke: bool) {
    let (levels, duration, max): (&[usize], _, _) = if smoke {
        (&[1, 16], Duration::from_millis(500), 50_000)
    } else {
        (&[1, 16, 64], Duration::from_secs(5), 500_000)
    };
    let runtime = client_runtime();
    let base = baseline();
    let bare = bare();
    let service = product();
    println!(
        "| endpoint | concurrency | bare req/s | baseline req/s | service req/s | service/baseline | service/bare | service p50 ms | service p99 ms | baseline p99 ms |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut failures = 0;
    for (path, body) in ENDPOINTS {
        for &c in levels {
            let bodies = vec![(path, "application/json", Bytes::from_static(body.as_bytes()))];
            // Warm each, then measure each in turn.
            warm(&runtime, &[&bare, &base, &service], &bodies, c);
            let r = drive(&runtime, bare.addr, bodies.clone(), c, duration, max);
            let mut b = drive(&runtime, base.addr, bodies.clone(), c, duration, max);
            let mut s = drive(&runtime, service.addr, bodies, c, duration, max);
            failures += r.failures + b.failures + s.failures;
            let (p50, p99, b99) = (s.percentile(0.5), s.percentile(0.99), b.percentile(0.99));
            println!(
                "| {path} | {c} | {:.0} | {:.0} | {:.0} | {:.2} | {:.2} | {p50:.3} | {p99:.3} | {b99:.3} |",
                r.rps(),
                b.rps(),
                s.rps(),
                s.rps() / b.rps(),
                s.rps() / r.rps(),
            );
        }
    }
    assert_eq!(failures, 0, "every request answered 200");
}

/// Requests to send, in turn: path, `Accept`, body.
type Bodies = Vec<(&'static str, &'static str, Bytes)>;

/// 100 ms (at most 10,000 requests) of `bodies` on each server.
fn warm(runtime: &tokio::runtime::Runtime, servers: &[&Server], bodies: &Bodies, c: usize) {
    for server in servers {
        drive(
            runtime,
            server.addr,
            bodies.clone(),
            c,
            Duration::from_millis(100),
            10_000,
        );
    }
}

/// The service with per-request metrics recorded against the same service
/// with the recording off, alternating per cell: what `/metrics` costs.
fn compare_metrics(smoke: bool) {
    let (levels, duration, max, rounds): (&[usize], _, _, _) = if smoke {
        (&[16], Duration::from_millis(500), 50_000, 1)
    } else {
        (&[1, 16], Duration::from_secs(3), 500_000, 3)
    };
    let runtime = client_runtime();
    let off = product_with(&["--metrics", "false"]);
    let on = product();
    println!("| endpoint | concurrency | metrics off req/s | metrics on req/s | on/off |");
    println!("|---|---:|---:|---:|---:|");
    let mut failures = 0;
    for (path, body) in ENDPOINTS {
        for &c in levels {
            let bodies = vec![(path, "application/json", Bytes::from_static(body.as_bytes()))];
            warm(&runtime, &[&off, &on], &bodies, c);
            let (mut total_off, mut total_on) = (0.0, 0.0);
            for _ in 0..rounds {
                let a = drive(&runtime, off.addr, bodies.clone(), c, duration, max);
                let b = drive(&runtime, on.addr, bodies.clone(), c, duration, max);
                failures += a.failures + b.failures;
                total_off += a.rps();
                total_on += b.rps();
            }
            println!(
                "| {path} | {c} | {:.0} | {:.0} | {:.3} |",
                total_off / rounds as f64,
                total_on / rounds as f64,
                total_on / total_off
            );
        }
    }
    assert_eq!(failures, 0, "every request answered 200");
}

fn rss_mib(pid: u32) -> f64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        })
        .unwrap_or(0.0)
        / 1024.0
}

/// Mixed traffic (every impact endpoint, JSON and CSV sweeps) at concurrency 16
/// for `total`, in slices of 30 s, printing requests, failures and resident memory.
fn soak(total: Duration) {
    let runtime = client_runtime();
    let service = product();
    let pid = service.child.id();
    let mut bodies: Vec<(&'static str, &'static str, Bytes)> = ENDPOINTS
        .iter()
        .map(|(p, b)| (*p, "application/json", Bytes::from_static(b.as_bytes())))
        .collect();
    bodies.push((
        "/v1/sweeps",
        "application/json",
        Bytes::from_static(SMALL_SWEEP.as_bytes()),
    ));
    bodies.push(("/v1/sweeps", "text/csv", Bytes::from_static(CSV_SWEEP.as_bytes())));
    let slice = Duration::from_secs(30).min(total);
    let start = Instant::now();
    let (mut requests, mut failures) = (0, 0);
    println!("| elapsed s | requests in slice | failures in slice | req/s | p99 ms | server RSS MiB |");
    println!("|---:|---:|---:|---:|---:|---:|");
    println!("| 0 | 0 | 0 | 0 | 0 | {:.1} |", rss_mib(pid));
    while start.elapsed() < total {
        let mut cell = drive(&runtime, service.addr, bodies.clone(), 16, slice, 50_000_000);
        requests += cell.requests;
        failures += cell.failures;
        let p99 = cell.percentile(0.99);
        println!(
            "| {:.0} | {} | {} | {:.0} | {:.2} | {:.1} |",
            start.elapsed().as_secs_f64(),
            cell.requests,
            cell.failures,
            cell.rps(),
            p99,
            rss_mib(pid)
        );
    }
    println!();
    println!("total: {requests} requests served, {failures} failures");
    assert_eq!(failures, 0, "no failures under mixed traffic");
}
