//! Graceful shutdown of the real binary: requests and a streamed sweep in
//! flight when SIGTERM arrives all complete, new connections are refused, and
//! the process exits 0 within its grace period.

use crate::common::process::{connect, free_port};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The grace period: long enough for the debug binary to stream the sweep
/// below on a loaded machine (a CI run cut a 500,000-row sweep at 8 s, after
/// 456,242 lines; alone it takes about 5 s), short enough to fail a
/// shutdown that hangs.
const GRACE: Duration = Duration::from_secs(30);

const IMPACT: &str = r#"{"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#;

fn head(path: &str, accept: &str, length: usize) -> String {
    format!(
        "POST {path} HTTP/1.1\r\nhost: x\r\naccept: {accept}\r\ncontent-type: application/json\r\n\
         content-length: {length}\r\nconnection: close\r\n\r\n"
    )
}

fn read_all(mut stream: TcpStream) -> String {
    let mut reply = Vec::new();
    stream.read_to_end(&mut reply).expect("the response completes");
    String::from_utf8_lossy(&reply).into_owned()
}

#[test]
fn sigterm_lets_in_flight_work_finish_refuses_new_connections_and_exits_zero() {
    let port = free_port();
    let mut child = Command::new(env!("CARGO_BIN_EXE_restitution"))
        .args([
            "--bind",
            &format!("127.0.0.1:{port}"),
            "--shutdown-grace-ms",
            &GRACE.as_millis().to_string(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start the binary");

    // In flight 1: a request whose body is only half sent. It asks for
    // `100 Continue` and waits for it, so the server is known to be reading
    // its body (a connection whose head the server has not read yet when the
    // signal arrives counts as idle and is closed).
    let mut half = connect(port);
    let expecting = head("/v1/impacts/normal", "application/json", IMPACT.len()).replace(
        "connection: close\r\n",
        "connection: close\r\nexpect: 100-continue\r\n",
    );
    half.write_all(expecting.as_bytes()).unwrap();
    let mut interim = [0u8; 25];
    half.read_exact(&mut interim).unwrap();
    assert_eq!(&interim, b"HTTP/1.1 100 Continue\r\n\r\n");
    half.write_all(&IMPACT.as_bytes()[..20]).unwrap();

    // In flight 2: a streamed sweep of 200,000 rows (far more than the
    // sockets' buffers hold), of which we read only the start for now.
    let sweep = r#"{"case": "normal", "base": {"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5},
                   "axes": [{"path": "/velocity/normal", "linspace": {"start": -5.0, "stop": -1.0, "count": 200000}}]}"#;
    let mut stream = connect(port);
    stream
        .write_all(head("/v1/sweeps", "text/csv", sweep.len()).as_bytes())
        .unwrap();
    stream.write_all(sweep.as_bytes()).unwrap();
    let mut start = [0u8; 64];
    stream.read_exact(&mut start).unwrap();
    assert!(start.starts_with(b"HTTP/1.1 200"));

    let signalled = Instant::now();
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("send SIGTERM");
    assert!(status.success());

    // New connections are refused once the listener closes.
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        match TcpStream::connect(("127.0.0.1", port)) {
            Err(_) => break,
            Ok(_) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(20)),
            Ok(_) => panic!("new connections still accepted after SIGTERM"),
        }
    }

    // The in-flight request completes once its body arrives.
    half.write_all(&IMPACT.as_bytes()[20..]).unwrap();
    let reply = read_all(half);
    assert!(reply.starts_with("HTTP/1.1 200"), "{reply}");
    assert!(reply.contains(r#""normal":1.5"#), "{reply}");

    // The streamed sweep completes: every row arrives.
    let rest = read_all(stream);
    let rows = rest.matches("\r\n").count();
    // Headers and chunk framing add CRLFs; the rows alone are 200,001 lines (with the header row).
    assert!(rows > 200_001, "{rows} lines");
    assert!(
        rest.trim_end().ends_with("0\r\n\r\n".trim_end()),
        "the chunked body ends properly"
    );

    // The process exits 0 within its grace period.
    let deadline = signalled + GRACE;
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "exit status {status}");
            break;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("the process did not exit within the grace period");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}
