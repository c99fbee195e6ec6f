//! End-to-end sweep streaming over loopback: the release binary in its own
//! process, a client that reads every byte, rows per second and the server's
//! peak resident memory (sampled from /proc every 10 ms). Also start-up time to
//! the first answered request and idle memory.
//!
//! `cargo bench --bench sweep_stream` (optionally `-- POINTS` to change the
//! one-output sweep size; default 10,000,000). Prints a Markdown table.

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use serde_json::json;

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free loopback port")
}

fn rss_kib(pid: u32) -> u64 {
    std::fs::read_to_string(format!("/proc/{pid}/status"))
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmRSS:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse().ok()))
        })
        .unwrap_or(0)
}

struct Server {
    child: Child,
    base: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts the binary and measures the time until `/healthz` first answers.
fn start() -> (Server, Duration) {
    let port = free_port();
    let started = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_restitution"))
        .args(["--bind", &format!("127.0.0.1:{port}")])
        .env("RUST_LOG", "warn")
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the server");
    let base = format!("http://127.0.0.1:{port}");
    let deadline = started + Duration::from_secs(10);
    loop {
        if let Ok(mut stream) = std::net::TcpStream::connect(("127.0.0.1", port)) {
            use std::io::{Read, Write};
            let _ = stream.write_all(b"GET /healthz HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n");
            let mut reply = String::new();
            let _ = stream.read_to_string(&mut reply);
            if reply.starts_with("HTTP/1.1 200") {
                break;
            }
        }
        assert!(Instant::now() < deadline, "server did not start");
        std::thread::sleep(Duration::from_millis(1));
    }
    let elapsed = started.elapsed();
    let mut server = Server { child, base };
    if let Some(stderr) = server.child.stderr.take() {
        std::thread::spawn(move || BufReader::new(stderr).lines().for_each(drop));
    }
    (server, elapsed)
}

const ARROW: &str = "application/vnd.apache.arrow.stream";

struct Run {
    rows: u64,
    bytes: u64,
    seconds: f64,
    peak_rss_kib: u64,
}

async fn stream(server: &Server, accept: &str, points: u64, outputs: Option<&[&str]>) -> Run {
    let mut body = json!({
        "case": "oblique",
        "base": {
            "body": {"mass": 1.0, "inertia": 0.00125},
            "contact": {"tangential_offset": 0.01, "normal_offset": 0.05},
            "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 2.0},
            "restitution": 0.93, "friction": 0.123
        },
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": -5.0, "stop": 5.0, "count": points}}]
    });
    if let Some(outputs) = outputs {
        body["outputs"] = json!(outputs);
    }
    let pid = server.child.id();
    let peak = Arc::new(AtomicU64::new(rss_kib(pid)));
    let running = Arc::new(AtomicBool::new(true));
    let sampler = {
        let (peak, running) = (peak.clone(), running.clone());
        std::thread::spawn(move || {
            while running.load(Ordering::Relaxed) {
                peak.fetch_max(rss_kib(pid), Ordering::Relaxed);
                std::thread::sleep(Duration::from_millis(10));
            }
        })
    };
    let client = reqwest::Client::new();
    let started = Instant::now();
    let mut response = client
        .post(format!("{}/v1/sweeps", server.base))
        .header("accept", accept)
        .json(&body)
        .send()
        .await
        .expect("send");
    assert!(response.status().is_success(), "{}", response.status());
    let (mut bytes, mut lines, mut batches) = (0u64, 0u64, 0u64);
    let arrow = accept == ARROW;
    // Arrow: record batches decoded as they arrive (zero-copy), as a reader would.
    let mut decoder = arrow_ipc::reader::StreamDecoder::new();
    while let Some(chunk) = response.chunk().await.expect("a complete body") {
        bytes += chunk.len() as u64;
        if arrow {
            let mut buffer = arrow_buffer::Buffer::from(chunk.to_vec());
            while let Some(batch) = decoder.decode(&mut buffer).expect("an Arrow stream") {
                lines += batch.num_rows() as u64;
                batches += 1;
            }
        } else {
            lines += chunk.iter().filter(|&&b| b == b'\n').count() as u64;
        }
    }
    if arrow {
        decoder.finish().expect("a complete Arrow stream");
        assert!(batches > 0);
    }
    let seconds = started.elapsed().as_secs_f64();
    running.store(false, Ordering::Relaxed);
    sampler.join().expect("sampler");
    let rows = if accept == "text/csv" { lines - 1 } else { lines };
    assert_eq!(rows, points, "every row arrived");
    Run {
        rows,
        bytes,
        seconds,
        peak_rss_kib: peak.load(Ordering::Relaxed),
    }
}

fn main() {
    let points: u64 = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(10_000_000);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .expect("runtime");
    let (server, startup) = start();
    std::thread::sleep(Duration::from_millis(200));
    let idle = rss_kib(server.child.id());
    println!(
        "start-up to first answered request: {:.1} ms",
        startup.as_secs_f64() * 1e3
    );
    println!("idle resident memory: {:.1} MiB", idle as f64 / 1024.0);
    println!();
    println!("| format | outputs | points | seconds | rows/s | MB/s | server peak RSS (MiB) |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    let one: &[&str] = &["/contact_velocity/final/tangential"];
    for (accept, outputs, n) in [
        ("text/csv", Some(one), points),
        ("application/x-ndjson", Some(one), points),
        (ARROW, Some(one), points),
        ("text/csv", None, points / 5),
        ("application/x-ndjson", None, points / 5),
        (ARROW, None, points / 5),
    ] {
        let run = runtime.block_on(stream(&server, accept, n, outputs));
        println!(
            "| {accept} | {} | {} | {:.2} | {:.2e} | {:.0} | {:.1} |",
            if outputs.is_some() { "1" } else { "all 19" },
            run.rows,
            run.seconds,
            run.rows as f64 / run.seconds,
            run.bytes as f64 / run.seconds / 1e6,
            run.peak_rss_kib as f64 / 1024.0
        );
    }
}
