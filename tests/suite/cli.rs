//! The binary's offline commands: `restitution solve` answers as the
//! endpoints do, `restitution sweep` shards tile the whole sweep.

use std::io::Write;
use std::process::{Command, Stdio};

use crate::common::server::spawn_app;
use restitution::http::ServiceConfig;
use serde_json::{Value, json};

fn binary() -> Command {
    Command::new(env!("CARGO_BIN_EXE_restitution"))
}

fn oblique() -> Value {
    json!({
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.01, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 2.0},
        "restitution": 0.93, "friction": 0.123
    })
}

/// Each line of standard input gets the endpoint's own answer or problem, in order.
#[tokio::test]
async fn solve_answers_each_line_as_the_endpoint_does() {
    let app = spawn_app(ServiceConfig::default()).await;
    let refused = json!({"body": {"mass": -1.0, "inertia": 1.0}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                         "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 0.0}, "restitution": 0.5, "friction": 0.1});
    let pretty = serde_json::to_string_pretty(&oblique()).unwrap();
    let input = format!("{}\n\n{}\nnot json\n{pretty}\n", oblique(), refused);
    let mut child = binary()
        .args(["solve", "oblique"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(1), "a refused line makes the exit code 1");
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 4);
    let (_, _, answer) = app.post("/v1/impacts/oblique", &oblique()).await;
    let (_, _, problem) = app.post("/v1/impacts/oblique", &refused).await;
    assert_eq!(lines[0], answer);
    assert_eq!(lines[1], problem);
    assert_eq!(lines[2]["status"], 400);
    assert_eq!(lines[3], answer, "a document spread over lines is one request");
}

/// Shards written to files concatenate to the whole sweep; the Arrow file is a stream.
#[test]
fn sweep_shards_tile_the_whole_sweep() {
    let dir = std::env::temp_dir().join(format!("restitution-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let request = dir.join("sweep.json");
    let sweep = json!({
        "case": "oblique", "base": oblique(),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": -5.0, "stop": 5.0, "count": 1001}},
                 {"path": "/friction", "values": [0.0, 0.1, 0.5]}]
    });
    std::fs::write(&request, sweep.to_string()).unwrap();
    let run = |args: &[&str]| {
        let out = binary()
            .arg("sweep")
            .arg("--request")
            .arg(&request)
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        out.stdout
    };
    let whole = String::from_utf8(run(&[])).unwrap();
    assert_eq!(whole.lines().count(), 3004);
    let mut joined = String::new();
    for index in 0..4 {
        let part = String::from_utf8(run(&["--shards", "4", "--index", &index.to_string()])).unwrap();
        let rows = part.split_once('\n').unwrap().1;
        if index == 0 {
            joined.push_str(part.split_once('\n').unwrap().0);
            joined.push('\n');
        }
        joined.push_str(rows);
    }
    assert_eq!(joined, whole);
    let arrow = dir.join("part.arrow");
    run(&[
        "--shards",
        "4",
        "--index",
        "3",
        "--output",
        arrow.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&arrow).unwrap();
    let reader = arrow_ipc::reader::StreamReader::try_new(&bytes[..], None).unwrap();
    let rows: usize = reader.map(|b| b.unwrap().num_rows()).sum();
    assert_eq!(rows, 751);
    let out = binary()
        .args(["sweep", "--shards", "4", "--index", "4", "--request"])
        .arg(&request)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    std::fs::remove_dir_all(&dir).unwrap();
}
