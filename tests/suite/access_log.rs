//! The real binary's access log, formatted by its log-writer thread: one line
//! per request in `tracing_subscriber::fmt`'s format, filtered by
//! `RESTITUTION_LOG`, every line written out before the process exits.

use crate::common::process::{connect, free_port};
use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const IMPACT: &str = r#"{"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5}"#;

/// Sends one request on its own connection; the answer's status line and request id.
fn send(port: u16, method: &str, path: &str, body: &str) -> (String, String) {
    let mut stream = connect(port);
    write!(
        stream,
        "{method} {path} HTTP/1.1\r\nhost: x\r\ncontent-type: application/json\r\n\
         content-length: {}\r\nconnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut reply = String::new();
    stream.read_to_string(&mut reply).unwrap();
    let status = reply.lines().next().unwrap_or_default().to_owned();
    let id = reply
        .lines()
        .find_map(|l| l.strip_prefix("x-request-id: "))
        .expect("a request id")
        .trim()
        .to_owned();
    (status, id)
}

/// Runs the binary with `log` as `RESTITUTION_LOG` (unset: `None`), sends
/// `count` impact requests and one for a missing route (each on its own
/// connection), stops it with SIGTERM and gives its standard output and the
/// request ids.
fn run(log: Option<&str>, count: usize) -> (String, Vec<String>) {
    let port = free_port();
    let mut command = Command::new(env!("CARGO_BIN_EXE_restitution"));
    command
        .args(["--bind", &format!("127.0.0.1:{port}")])
        .stdout(Stdio::piped())
        .stderr(Stdio::null());
    match log {
        Some(level) => command.env("RESTITUTION_LOG", level),
        None => command.env_remove("RESTITUTION_LOG"),
    };
    let mut child = command.spawn().expect("start the binary");
    let mut ids = Vec::new();
    for _ in 0..count {
        let (status, id) = send(port, "POST", "/v1/impacts/normal", IMPACT);
        assert!(status.starts_with("HTTP/1.1 200"), "{status}");
        ids.push(id);
    }
    let (status, id) = send(port, "GET", "/no/such/route", "");
    assert!(status.starts_with("HTTP/1.1 404"), "{status}");
    ids.push(id);
    let signalled = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .expect("send SIGTERM");
    assert!(signalled.success());
    let mut out = String::new();
    child.stdout.take().unwrap().read_to_string(&mut out).unwrap();
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "exit status {status}");
            break;
        }
        assert!(Instant::now() < deadline, "the process did not exit");
        std::thread::sleep(Duration::from_millis(20));
    }
    (out, ids)
}

/// `2026-11-25T20:54:26.123456Z`
fn is_timestamp(text: &str) -> bool {
    let b = text.as_bytes();
    b.len() == 27
        && b.iter().enumerate().all(|(i, &c)| match i {
            4 | 7 => c == b'-',
            10 => c == b'T',
            13 | 16 => c == b':',
            19 => c == b'.',
            26 => c == b'Z',
            _ => c.is_ascii_digit(),
        })
}

#[test]
fn every_request_has_one_line_in_the_subscribers_format_written_before_exit() {
    let (out, ids) = run(None, 200);
    let lines: Vec<&str> = out.lines().collect();
    for (k, id) in ids.iter().enumerate() {
        let needle = format!(" request_id={id} ");
        let mine: Vec<&&str> = lines.iter().filter(|l| l.contains(&needle)).collect();
        assert_eq!(mine.len(), 1, "one line for {id}: {mine:?}");
        let line = mine[0];
        let (time, rest) = line.split_once(' ').unwrap();
        assert!(is_timestamp(time), "{line}");
        let (path, status) = if k + 1 < ids.len() {
            ("/v1/impacts/normal", 200)
        } else {
            ("/no/such/route", 404)
        };
        let method = if status == 200 { "POST" } else { "GET" };
        let expected = format!(
            " INFO restitution::http: request request_id={id} method={method} path={path} status={status} latency_us="
        );
        assert!(rest.starts_with(&expected), "{line}\n{expected}");
        let latency = &rest[expected.len()..];
        assert!(latency.parse::<u64>().is_ok(), "{line}");
    }
    // The tracing lines share the thread and keep their order: the access
    // lines come after `listening` and before the last word.
    let first = lines.iter().position(|l| l.contains("request_id=")).unwrap();
    let listening = lines.iter().position(|l| l.contains(" listening ")).unwrap();
    assert!(listening < first, "{out}");
    assert!(
        lines.last().unwrap().contains("every connection closed; exiting"),
        "{out}"
    );
}

#[test]
fn at_warn_the_info_lines_are_not_written() {
    let (out, ids) = run(Some("warn"), 3);
    for id in &ids {
        assert!(!out.contains(&format!("request_id={id} ")), "{out}");
    }
    assert!(!out.contains(" INFO "), "{out}");
}

#[test]
fn a_directive_for_the_access_logs_target_is_honoured() {
    let (out, ids) = run(Some("info,restitution::http=warn"), 2);
    for id in &ids {
        assert!(!out.contains(&format!("request_id={id} ")), "{out}");
    }
    // Other targets stay at info.
    assert!(out.contains(" listening "), "{out}");
}
