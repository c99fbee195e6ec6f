//! The binary's two compiled copies of the hot code (`--kernels auto`, the
//! x86-64-v3 copy on a CPU with AVX2 and FMA, and `--kernels portable`) give
//! the same bytes for the same sweeps: every case, every output, `fast` and
//! `exact`, over ranges that cross the regime switches and leave the fast
//! range (so the exact stages run too). The binary says which copy it runs
//! (`restitution kernels`). A debug build compiles the portable copy alone
//! (`restitution::kernels::V3_COMPILED`), so with the binary cargo built for
//! the tests this only checks that every sweep runs; `.ci/run` runs it again
//! with the release binary (`RESTITUTION_BINARY`), which must have both
//! copies on a CPU with x86-64-v3, and there the two are compared.

use std::process::Command;

use serde_json::{Value, json};

/// The binary under test: `RESTITUTION_BINARY` if set, else the one cargo built.
fn binary() -> std::path::PathBuf {
    std::env::var_os("RESTITUTION_BINARY")
        .map(Into::into)
        .unwrap_or_else(|| env!("CARGO_BIN_EXE_restitution").into())
}

/// The copy the binary under test runs with `--kernels kernels`.
fn runs(kernels: &str) -> String {
    let out = Command::new(binary())
        .args(["kernels", "--kernels", kernels])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().trim().to_owned()
}

/// Whether the binary under test has both copies (it runs the x86-64-v3 one
/// when left to choose). A binary named by `RESTITUTION_BINARY` (the release
/// binary in `.ci/run`) must, on a CPU with x86-64-v3: one without the copy
/// there (a debug build) would compare its one copy with itself.
fn has_both_copies() -> bool {
    assert_eq!(runs("portable"), "portable");
    let both = runs("auto") == "x86-64-v3";
    if std::env::var_os("RESTITUTION_BINARY").is_some() && restitution::kernels::cpu_has_v3() {
        assert!(
            both,
            "RESTITUTION_BINARY names a binary without the x86-64-v3 copy"
        );
    }
    both
}

/// The CSV of the sweep in `path` with `kernels`.
fn sweep_with(kernels: &str, path: &std::path::Path) -> Vec<u8> {
    let out = Command::new(binary())
        .args(["sweep", "--kernels", kernels, "--format", "csv", "--request"])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{kernels}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

fn requests() -> Vec<Value> {
    let oblique = json!({
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.01, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 2.0},
        "restitution": 0.93, "friction": 0.123
    });
    let mut tangential = oblique.clone();
    tangential["tangential_restitution"] = json!(0.34);
    let mut kinetic = oblique.clone();
    for law in ["restitution", "friction"] {
        kinetic.as_object_mut().unwrap().remove(law);
    }
    kinetic["kinetic_restitution"] =
        json!({"value": 0.9, "approach_impulse_ratio": -0.2, "rebound_impulse_ratio": 0.1});
    let torsional = json!({
        "body": {"mass": 0.1, "normal_inertia": 0.000036},
        "velocity": {"normal": -3.0, "spin": 0.0},
        "restitution": 0.8,
        "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.005}
    });
    let planar: Value =
        serde_json::from_str(include_str!("../examples/planar_car_to_car_sweep.json")).unwrap();
    let spatial: Value =
        serde_json::from_str(include_str!("../examples/spatial_tennis_topspin.json")).unwrap();
    let lin = |path: &str, start: f64, stop: f64, count: u64| json!({"path": path, "linspace": {"start": start, "stop": stop, "count": count}});
    // Magnitudes from 1e-250 to 1e250: outside 2^±200 the exact stages answer.
    let log = |path: &str| json!({"path": path, "logspace": {"start": 1e-250, "stop": 1e250, "count": 101}});
    let mut all = Vec::new();
    for precision in ["fast", "exact"] {
        all.extend([
            json!({"case": "oblique", "base": oblique, "precision": precision,
                   "axes": [lin("/velocity/tangential", -5.0, 5.0, 401), lin("/friction", 0.0, 1.0, 5)]}),
            json!({"case": "oblique", "base": oblique, "precision": precision,
                   "axes": [log("/velocity/tangential")]}),
            json!({"case": "oblique", "base": kinetic, "precision": precision,
                   "axes": [lin("/velocity/tangential", -5.0, 5.0, 201)]}),
            json!({"case": "tangential", "base": tangential, "precision": precision,
                   "axes": [lin("/velocity/tangential", -5.0, 5.0, 401), log("/body/mass")]}),
            json!({"case": "torsional", "base": torsional, "precision": precision,
                   "axes": [lin("/velocity/spin", -100.0, 100.0, 801)]}),
            // In `fast`, in lanes; beyond 2^±200 one by one.
            json!({"case": "torsional", "base": torsional, "precision": precision,
                   "axes": [lin("/velocity/spin", -100.0, 100.0, 81), log("/body/mass")]}),
            json!({"case": "planar", "base": planar["base"], "precision": precision,
                   "axes": [lin("/bodies/1/velocity/y", -30.0, 30.0, 61), lin("/friction", 0.0, 1.0, 11)]}),
            // No law on an axis: in `fast`, in lanes.
            json!({"case": "planar", "base": planar["base"], "precision": precision,
                   "axes": [lin("/bodies/1/velocity/y", -30.0, 30.0, 61), lin("/bodies/0/angular_velocity", -3.0, 3.0, 7)]}),
            json!({"case": "spatial", "base": spatial, "precision": precision,
                   "axes": [lin("/bodies/0/angular_velocity/x", -600.0, 600.0, 41),
                            lin("/bodies/0/velocity/y", -10.0, 10.0, 11)]}),
        ]);
    }
    all
}

#[test]
fn both_kernels_give_the_same_bytes() {
    let dir = std::env::temp_dir().join(format!("restitution-kernels-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let compared = has_both_copies();
    for (i, request) in requests().into_iter().enumerate() {
        let path = dir.join(format!("{i}.json"));
        std::fs::write(&path, request.to_string()).unwrap();
        let auto = sweep_with("auto", &path);
        let rows = auto.iter().filter(|&&b| b == b'\n').count();
        assert!(rows > 100, "{request}: only {rows} lines");
        if compared {
            let portable = sweep_with("portable", &path);
            assert!(auto == portable, "{request}: the kernels disagree");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    if !compared {
        eprintln!(
            "the binary runs its portable copy alone (a debug build, or a CPU without x86-64-v3): \
             the copies are compared with a release binary on an x86-64-v3 CPU"
        );
    }
}

#[test]
fn an_unknown_kernel_is_refused() {
    let out = Command::new(binary())
        .args(["openapi", "--kernels", "avx512"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("avx512"));
}
