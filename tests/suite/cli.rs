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

/// Every cell of an Arrow stream as text (numbers by their bits), row by row,
/// with the schema's metadata.
fn arrow_cells(bytes: &[u8]) -> (Vec<Vec<String>>, std::collections::HashMap<String, String>) {
    use arrow_array::cast::AsArray;
    use arrow_array::types::{Float64Type, Int16Type};
    let reader = arrow_ipc::reader::StreamReader::try_new(bytes, None).unwrap();
    let metadata = reader.schema().metadata().clone().into_iter().collect();
    let mut rows = Vec::new();
    for batch in reader {
        let batch = batch.unwrap();
        for row in 0..batch.num_rows() {
            let cells = batch
                .columns()
                .iter()
                .map(|column| {
                    if column.is_null(row) {
                        return "null".to_owned();
                    }
                    if let Some(x) = column.as_primitive_opt::<Float64Type>() {
                        return format!("{:x}", x.value(row).to_bits());
                    }
                    if let Some(d) = column.as_dictionary_opt::<Int16Type>() {
                        let key = d.keys().value(row) as usize;
                        return d.values().as_string::<i32>().value(key).to_owned();
                    }
                    if let Some(s) = column.as_string_opt::<i32>() {
                        return s.value(row).to_owned();
                    }
                    panic!("a column of type {}", column.data_type())
                })
                .collect();
            rows.push(cells);
        }
    }
    (rows, metadata)
}

/// `restitution collect` joins the Arrow parts of a sharded sweep into the
/// whole sweep's rows, and refuses parts out of order, a missing part and a
/// part of another sweep, naming it.
#[test]
fn collect_joins_checked_parts_and_refuses_mismatched_ones() {
    let dir = std::env::temp_dir().join(format!("restitution-collect-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write_request = |name: &str, restitution: f64| {
        let mut base = oblique();
        base["restitution"] = json!(restitution);
        let sweep = json!({
            "case": "oblique", "base": base,
            "axes": [{"path": "/velocity/tangential", "linspace": {"start": -5.0, "stop": 5.0, "count": 301}},
                     {"path": "/friction", "values": [0.0, 0.1, 0.5]}]
        });
        let path = dir.join(name);
        std::fs::write(&path, sweep.to_string()).unwrap();
        path
    };
    let (request, other) = (
        write_request("sweep.json", 0.93),
        write_request("other.json", 0.5),
    );
    let sweep = |request: &std::path::Path, output: &std::path::Path, shard: Option<u64>| {
        let mut command = binary();
        command
            .arg("sweep")
            .arg("--request")
            .arg(request)
            .arg("--output")
            .arg(output);
        if let Some(index) = shard {
            command.args(["--shards", "3", "--index", &index.to_string()]);
        }
        let out = command.output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    };
    let part = |i: u64| dir.join(format!("part-{i}.arrow"));
    for i in 0..3 {
        sweep(&request, &part(i), Some(i));
    }
    let whole = dir.join("whole.arrow");
    sweep(&request, &whole, None);
    let collect = |parts: &[std::path::PathBuf]| {
        let output = dir.join("collected.arrow");
        let out = binary()
            .arg("collect")
            .arg("--output")
            .arg(&output)
            .args(parts)
            .output()
            .unwrap();
        (out, output)
    };
    let (out, collected) = collect(&[part(0), part(1), part(2)]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (rows, metadata) = arrow_cells(&std::fs::read(&collected).unwrap());
    let (expected, whole_metadata) = arrow_cells(&std::fs::read(&whole).unwrap());
    assert_eq!(rows.len(), 903);
    assert_eq!(rows, expected);
    assert_eq!(metadata, whole_metadata);
    assert_eq!(metadata["restitution.range_start"], "0");
    assert_eq!(metadata["restitution.range_end"], "903");

    sweep(&other, &dir.join("other-1.arrow"), Some(1));
    for (parts, says) in [
        (
            vec![part(1), part(0), part(2)],
            "part-1.arrow: its range starts at point 301, where 0 was expected",
        ),
        (
            vec![part(0), part(2)],
            "part-2.arrow: its range starts at point 602, where 301 was expected",
        ),
        (
            vec![part(0), part(1)],
            "part-1.arrow: the parts end at point 602 of the sweep's 903",
        ),
        (
            vec![part(0), dir.join("other-1.arrow"), part(2)],
            "other-1.arrow: restitution.sweep_sha256 is",
        ),
        (
            vec![part(0), request.clone()],
            "sweep.json: not an Arrow IPC stream",
        ),
    ] {
        let (out, output) = collect(&parts);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(says), "{parts:?}: {stderr}");
        assert!(!output.exists(), "no output is left behind on a refusal");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A limit of sweeps at once below 1 is refused when the service starts,
/// naming the flag (0 would refuse every sweep of its kind).
#[test]
fn a_sweep_limit_of_zero_is_refused_at_start() {
    for flag in ["--max-buffered-sweeps", "--max-streamed-sweeps"] {
        let output = binary()
            .args(["serve", "--bind", "127.0.0.1:0", flag, "0"])
            .output()
            .expect("the binary runs");
        assert!(!output.status.success(), "{flag} 0 was accepted");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains(flag) && stderr.contains("from 1 to 100000"),
            "{stderr}"
        );
    }
}
