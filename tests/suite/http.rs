//! The real server on 127.0.0.1:0, called over HTTP with reqwest.

use reqwest::StatusCode;

use crate::common::plain::oblique::{self, TangentialLaw};
use crate::common::plain::tangential;
use crate::common::plain::torsional::{self, TorsionalImpact};
use crate::common::server::spawn_app;
use restitution::http::{ServiceConfig, openapi_json};
use restitution::{BarrierScene, Body, Contact, Outputs, PlanarVelocity};
use serde_json::{Value, json};

/// The Maw steel disc: 1 kg, radius 0.05 m, e = 0.93, f = 0.123.
fn maw_disc(vt: f64) -> Value {
    json!({
        "body": {"mass": 1.0, "inertia": 0.5 * 0.05 * 0.05},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": vt, "angular": 0.0},
        "restitution": 0.93,
        "friction": 0.123
    })
}

fn maw_scene(vt: f64) -> BarrierScene {
    BarrierScene::new(
        Body::new(1.0, 0.5 * 0.05 * 0.05).unwrap(),
        Contact::central(0.05),
        PlanarVelocity {
            normal: -1.0,
            tangential: vt,
            angular: 0.0,
        },
    )
    .unwrap()
}

fn assert_problem(
    status: StatusCode,
    content_type: &str,
    body: &Value,
    expected: StatusCode,
    pointer: Option<&str>,
) {
    assert_eq!(status, expected, "{body}");
    assert_eq!(content_type, "application/problem+json");
    assert_eq!(body["status"], expected.as_u16());
    assert!(body["type"].as_str().is_some_and(|t| !t.is_empty()));
    assert!(body["title"].as_str().is_some_and(|t| !t.is_empty()));
    assert!(body["detail"].as_str().is_some_and(|t| !t.is_empty()));
    if let Some(p) = pointer {
        assert_eq!(body["pointer"], p, "{body}");
    }
}

#[tokio::test]
async fn oblique_friction_matches_the_library_bit_for_bit() {
    let app = spawn_app(ServiceConfig::default()).await;
    for vt in [0.4, 2.0] {
        let (status, headers, body) = app.post("/v1/impacts/oblique", &maw_disc(vt)).await;
        assert_eq!(status, StatusCode::OK, "{body}");
        assert!(headers.contains_key("x-request-id"));
        assert_eq!(headers["x-content-type-options"], "nosniff");
        let expected =
            oblique::solve(&maw_scene(vt), 0.93, TangentialLaw::Friction(0.123), Outputs::ALL).unwrap();
        assert_eq!(body["final_velocity"]["normal"], expected.final_velocity.normal);
        assert_eq!(
            body["final_velocity"]["tangential"],
            expected.final_velocity.tangential
        );
        assert_eq!(body["final_velocity"]["angular"], expected.final_velocity.angular);
        assert_eq!(
            body["contact_velocity"]["final"]["tangential"],
            expected.contact_velocity.r#final.tangential
        );
        assert_eq!(body["impulse"]["normal"], expected.impulse.normal);
        assert_eq!(body["impulse_ratio"], expected.impulse_ratio);
        assert_eq!(
            body["critical_impulse_ratio"],
            expected.critical_impulse_ratio.unwrap()
        );
        assert_eq!(body["energy"]["loss"], expected.energy.unwrap().loss);
        assert_eq!(body["regime"], expected.regime.as_str());
    }
    let (_, _, sliding) = app.post("/v1/impacts/oblique", &maw_disc(2.0)).await;
    assert_eq!(sliding["regime"], "sliding");
    assert_eq!(sliding["impulse_ratio"], -0.123);
}

#[tokio::test]
async fn oblique_prescribed_ratio_and_kinetic_restitution_are_served() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut request = maw_disc(2.0);
    request.as_object_mut().unwrap().remove("friction");
    request["impulse_ratio"] = json!(-0.1);
    let (status, _, body) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["regime"], "prescribed");
    assert_eq!(body["impulse_ratio"], -0.1);

    let kinetic = json!({
        "body": {"mass": 2.0, "inertia": 0.3},
        "contact": {"tangential_offset": 0.2, "normal_offset": 0.5},
        "velocity": {"normal": -1.0, "tangential": 0.3, "angular": 0.2},
        "kinetic_restitution": {"value": 0.6, "approach_impulse_ratio": 0.1, "rebound_impulse_ratio": -0.2}
    });
    let (status, _, body) = app.post("/v1/impacts/oblique", &kinetic).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["kinetic_restitution"], 0.6);
    assert_ne!(body["restitution"], 0.6);
}

#[tokio::test]
async fn tangential_normal_and_torsional_endpoints_match_the_library() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut request = maw_disc(0.1);
    request["tangential_restitution"] = json!(0.34);
    let (status, _, body) = app.post("/v1/impacts/tangential", &request).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    let expected = tangential::solve(&maw_scene(0.1), 0.93, 0.123, 0.34, Outputs::ALL).unwrap();
    assert_eq!(body["regime"], "restitution");
    assert_eq!(
        body["contact_velocity"]["final"]["tangential"],
        expected.contact_velocity.r#final.tangential
    );
    assert_eq!(body["final_velocity"]["angular"], expected.final_velocity.angular);
    // The oblique endpoint takes every law (one wire form): the same answer.
    let (status, _, oblique) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(status, StatusCode::OK, "{oblique}");
    assert_eq!(oblique, body);

    let point =
        json!({"body": {"mass": 2.0}, "velocity": {"normal": -3.0, "tangential": 1.0}, "restitution": 0.5});
    let (status, _, body) = app.post("/v1/impacts/normal", &point).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    assert_eq!(body["final_velocity"]["normal"], 1.5);
    assert_eq!(body["impulse"]["normal"], 9.0);
    assert_eq!(body["regime"], "frictionless");
    assert_eq!(body["kinetic_restitution"], 0.5);
    assert_eq!(body["energy"]["loss"], 0.5 * 2.0 * 9.0 * 0.75);

    let torsion = json!({
        "body": {"mass": 0.6, "normal_inertia": 0.003456},
        "velocity": {"normal": -3.0, "spin": 20.0},
        "restitution": 0.7,
        "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}
    });
    let (status, _, body) = app.post("/v1/impacts/torsional", &torsion).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    let expected = torsional::solve(
        &TorsionalImpact {
            mass: 0.6,
            normal_inertia: 0.003456,
            normal_velocity: -3.0,
            spin: 20.0,
            restitution: 0.7,
            torsional_restitution: 0.2,
            torsional_friction: 0.3,
            pitch_radius: 0.01,
        },
        true,
    )
    .unwrap();
    assert_eq!(body["final_velocity"]["spin"], expected.final_spin);
    assert_eq!(body["impulse"]["torsional"], expected.torsional_impulse);
    assert_eq!(body["switch_spin"], expected.switch_spin);
    assert_eq!(body["regime"], expected.regime.as_str());
}

#[tokio::test]
async fn malformed_json_is_a_400_problem() {
    let app = spawn_app(ServiceConfig::default()).await;
    for body in [&b"{"[..], b"", b"{\"body\": }", b"{} trailing", b"\xff\xfe"] {
        let (status, ct, problem) = app
            .post_raw("/v1/impacts/oblique", Some("application/json"), body.to_vec())
            .await;
        assert_problem(status, &ct, &problem, StatusCode::BAD_REQUEST, None);
    }
}

#[tokio::test]
async fn schema_mismatches_are_422_problems_naming_the_member() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut missing = maw_disc(1.0);
    missing["body"].as_object_mut().unwrap().remove("mass");
    let mut wrong_type = maw_disc(1.0);
    wrong_type["velocity"]["normal"] = json!("-1.0");
    let mut unknown = maw_disc(1.0);
    unknown["contact"]["radius"] = json!(1.0);
    for (request, pointer) in [
        (missing, "/body/mass"),
        (wrong_type, "/velocity/normal"),
        (unknown, "/contact/radius"),
    ] {
        let (status, ct, problem) = app
            .post_raw(
                "/v1/impacts/oblique",
                Some("application/json"),
                request.to_string().into_bytes(),
            )
            .await;
        assert_problem(
            status,
            &ct,
            &problem,
            StatusCode::UNPROCESSABLE_ENTITY,
            Some(pointer),
        );
    }
}

#[tokio::test]
async fn physically_invalid_inputs_are_422_problems_naming_the_input() {
    let app = spawn_app(ServiceConfig::default()).await;
    let cases = [
        (json!({"restitution": 1.5}), "/restitution"),
        (json!({"friction": -0.1}), "/friction"),
        (json!({"body": {"mass": 0.0, "inertia": 1.0}}), "/body/mass"),
        (json!({"body": {"mass": 1.0, "inertia": -1.0}}), "/body/inertia"),
        (
            json!({"velocity": {"normal": 0.5, "tangential": 0.0}}),
            "/velocity/normal",
        ),
        (json!({"impulse_ratio": 0.1}), "/impulse_ratio"),
    ];
    for (patch, pointer) in cases {
        let mut request = maw_disc(1.0);
        for (k, v) in patch.as_object().unwrap() {
            request[k] = v.clone();
        }
        let response = app
            .client
            .post(format!("{}/v1/impacts/oblique", app.base))
            .json(&request)
            .send()
            .await
            .unwrap();
        let status = response.status();
        let ct = response.headers()["content-type"].to_str().unwrap().to_owned();
        let problem: Value = response.json().await.unwrap();
        assert_problem(
            status,
            &ct,
            &problem,
            StatusCode::UNPROCESSABLE_ENTITY,
            Some(pointer),
        );
    }
    // A non-approaching torsional impact.
    let torsion = json!({
        "body": {"mass": 0.6, "normal_inertia": 0.003456},
        "velocity": {"normal": 3.0, "spin": 20.0},
        "restitution": 0.7,
        "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}
    });
    let (status, _, problem) = app.post("/v1/impacts/torsional", &torsion).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/velocity/normal");
}

#[tokio::test]
async fn energy_creating_ratio_and_d_not_positive_are_refused_with_reasons() {
    let app = spawn_app(ServiceConfig::default()).await;
    // Maw disc sliding with v_t > 0: μ = +0.124 pushes along the slip and creates energy.
    let mut request = maw_disc(2.0);
    request.as_object_mut().unwrap().remove("friction");
    request["impulse_ratio"] = json!(2.0);
    let (status, _, problem) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/impulse_ratio");
    assert!(
        problem["admissible_impulse_ratio"]["lower"].is_number(),
        "{problem}"
    );
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("create kinetic energy")
    );
    // A slender body struck off-centre with a large ratio: D ≤ 0.
    let request = json!({
        "body": {"mass": 1.0, "inertia": 0.01},
        "contact": {"tangential_offset": 1.0, "normal_offset": 1.0},
        "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 0.0},
        "restitution": 0.5,
        "impulse_ratio": 5.0
    });
    let (status, _, problem) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["type"], "urn:restitution:problem:no-impulse-solution");
    assert!(problem["detail"].as_str().unwrap().contains("no physical answer"));
}

#[tokio::test]
async fn oblique_needs_exactly_one_tangential_law() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut both = maw_disc(1.0);
    both["impulse_ratio"] = json!(0.1);
    let mut none = maw_disc(1.0);
    none.as_object_mut().unwrap().remove("friction");
    let mut mixed = maw_disc(1.0);
    mixed["kinetic_restitution"] =
        json!({"value": 0.5, "approach_impulse_ratio": 0.0, "rebound_impulse_ratio": 0.0});
    // The one wire parser of a law (conventions, rule 9): the second of two
    // tangential members, a missing tangential law at `friction`, and
    // `kinetic_restitution` given with `restitution` at `restitution`.
    for (request, pointer) in [
        (both, "/impulse_ratio"),
        (none, "/friction"),
        (mixed, "/restitution"),
    ] {
        let (status, _, problem) = app.post("/v1/impacts/oblique", &request).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
        assert_eq!(problem["pointer"], pointer);
    }
}

#[tokio::test]
async fn a_point_mass_refuses_contact_offsets_and_spin() {
    let app = spawn_app(ServiceConfig::default()).await;
    let with_contact = json!({"body": {"mass": 1.0}, "contact": {"tangential_offset": 0.1, "normal_offset": 0.0},
                              "velocity": {"normal": -1.0}, "restitution": 0.5});
    let with_spin =
        json!({"body": {"mass": 1.0}, "velocity": {"normal": -1.0, "angular": 2.0}, "restitution": 0.5});
    for (request, pointer) in [
        (with_contact, "/contact/tangential_offset"),
        (with_spin, "/velocity/angular"),
    ] {
        let (status, _, problem) = app.post("/v1/impacts/normal", &request).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
        assert_eq!(problem["pointer"], pointer);
    }
}

#[tokio::test]
async fn media_type_size_route_and_method_errors_are_problems() {
    let config = ServiceConfig {
        body_limit: 256,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let body = maw_disc(1.0).to_string().into_bytes();
    let (status, ct, problem) = app
        .post_raw("/v1/impacts/oblique", Some("text/plain"), body.clone())
        .await;
    assert_problem(status, &ct, &problem, StatusCode::UNSUPPORTED_MEDIA_TYPE, None);
    let (status, ct, problem) = app.post_raw("/v1/impacts/oblique", None, body).await;
    assert_problem(status, &ct, &problem, StatusCode::UNSUPPORTED_MEDIA_TYPE, None);
    let big = format!("{{\"pad\": \"{}\"}}", "x".repeat(4096)).into_bytes();
    let (status, ct, problem) = app
        .post_raw("/v1/impacts/oblique", Some("application/json"), big)
        .await;
    assert_problem(status, &ct, &problem, StatusCode::PAYLOAD_TOO_LARGE, None);
    let response = app
        .client
        .get(format!("{}/v1/nothing", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::NOT_FOUND);
    assert_eq!(response.headers()["content-type"], "application/problem+json");
    let response = app
        .client
        .get(format!("{}/v1/impacts/normal", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::METHOD_NOT_ALLOWED);
    assert_eq!(response.headers()["content-type"], "application/problem+json");
}

#[tokio::test]
async fn health_docs_and_openapi_are_served() {
    let app = spawn_app(ServiceConfig::default()).await;
    let health: Value = app
        .client
        .get(format!("{}/healthz", app.base))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    assert_eq!(health["status"], "ok");
    let docs = app
        .client
        .get(format!("{}/docs/", app.base))
        .send()
        .await
        .unwrap();
    assert_eq!(docs.status(), StatusCode::OK);
    assert!(docs.text().await.unwrap().contains("swagger"));
    let served: Value = app
        .client
        .get(format!("{}/openapi.json", app.base))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let generated: Value = serde_json::from_str(&openapi_json()).unwrap();
    assert_eq!(served, generated);
}

/// Every `$ref` resolves, every response has a description, every operation
/// documents its problems, and the version is 3.1.
#[test]
fn openapi_document_is_valid_3_1() {
    let doc: Value = serde_json::from_str(&openapi_json()).unwrap();
    assert_eq!(doc["openapi"], "3.1.0");
    assert!(!doc["info"]["license"]["name"].as_str().unwrap().is_empty());
    fn walk(v: &Value, doc: &Value) {
        match v {
            Value::Object(map) => {
                if let Some(Value::String(r)) = map.get("$ref") {
                    let pointer = r.strip_prefix('#').expect("local ref");
                    assert!(doc.pointer(pointer).is_some(), "dangling {r}");
                }
                map.values().for_each(|x| walk(x, doc));
            }
            Value::Array(items) => items.iter().for_each(|x| walk(x, doc)),
            _ => {}
        }
    }
    walk(&doc, &doc);
    for path in [
        "/v1/impacts/normal",
        "/v1/impacts/oblique",
        "/v1/impacts/tangential",
        "/v1/impacts/torsional",
    ] {
        let op = &doc["paths"][path]["post"];
        assert!(
            op["requestBody"]["content"]["application/json"]["schema"].is_object(),
            "{path}"
        );
        for (code, response) in op["responses"].as_object().unwrap() {
            assert!(
                response["description"].as_str().is_some_and(|d| !d.is_empty()),
                "{path} {code}"
            );
        }
        for code in ["200", "400", "413", "415", "422"] {
            assert!(op["responses"][code].is_object(), "{path} lacks {code}");
        }
    }
}

/// The committed `openapi/openapi.json` is what the code generates.
/// Regenerate with `cargo run -- openapi > openapi/openapi.json`.
#[test]
fn committed_openapi_document_is_up_to_date() {
    let committed = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/openapi/openapi.json"))
        .expect("openapi/openapi.json is committed");
    assert!(
        committed == openapi_json(),
        "openapi/openapi.json is stale: run `cargo run -- openapi > openapi/openapi.json`"
    );
}

/// `precision` on every impact endpoint and on sweeps: echoed, and `exact`
/// answers are the library's exact answers bit for bit (on an input where the
/// fast answer differs in the last place).
#[tokio::test]
async fn precision_is_chosen_echoed_and_exact_over_http() {
    use restitution::{BarrierImpact, Law, Precision};
    let app = spawn_app(ServiceConfig::default()).await;
    let point = |vt: f64| {
        BarrierImpact::rigid(
            1.0,
            0.5 * 0.05 * 0.05,
            Contact::central(0.05),
            PlanarVelocity {
                normal: -1.0,
                tangential: vt,
                angular: 0.0,
            },
            Law::Friction {
                restitution: 0.93,
                friction: 0.123,
            },
        )
    };
    let solve = |vt: f64, p: Precision| restitution::solve(&point(vt), Outputs::ALL, p).unwrap();
    let vt = (1..200)
        .map(|i| 0.37 * f64::from(i))
        .find(|&vt| {
            let (f, x) = (solve(vt, Precision::Fast), solve(vt, Precision::Exact));
            f.energy != x.energy || f.impulse != x.impulse
        })
        .expect("an input where fast and exact differ");
    for (name, precision) in [("fast", Precision::Fast), ("exact", Precision::Exact)] {
        let mut request = maw_disc(vt);
        request["precision"] = json!(name);
        let (status, _, body) = app.post("/v1/impacts/oblique", &request).await;
        assert_eq!(status, StatusCode::OK, "{body}");
        assert_eq!(body["precision"], name);
        let expected = solve(vt, precision).final_velocity.angular;
        assert_eq!(
            body["final_velocity"]["angular"].as_f64().unwrap().to_bits(),
            expected.to_bits()
        );
    }
    // The default is fast, and every endpoint takes and echoes the field.
    let (_, _, body) = app.post("/v1/impacts/oblique", &maw_disc(vt)).await;
    assert_eq!(body["precision"], "fast");
    let normal = json!({"body": {"mass": 2.0}, "velocity": {"normal": -3.0, "tangential": 1.0, "angular": 0.0},
                        "restitution": 0.5, "precision": "exact"});
    let tangential = json!({"body": {"mass": 1.0, "inertia": 0.00125}, "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                            "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
                            "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34, "precision": "exact"});
    let torsional = json!({"body": {"mass": 0.6, "normal_inertia": 0.003456}, "velocity": {"normal": -3.0, "spin": 20.0},
                           "restitution": 0.7, "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01},
                           "precision": "exact"});
    for (path, body) in [
        ("/v1/impacts/normal", normal),
        ("/v1/impacts/tangential", tangential),
        ("/v1/impacts/torsional", torsional),
    ] {
        let (status, _, answer) = app.post(path, &body).await;
        assert_eq!(status, StatusCode::OK, "{path}: {answer}");
        assert_eq!(answer["precision"], "exact", "{path}");
    }
    let mut bad = maw_disc(vt);
    bad["precision"] = json!("double-double");
    let (status, headers, body) = app.post("/v1/impacts/oblique", &bad).await;
    assert_problem(
        status,
        headers["content-type"].to_str().unwrap(),
        &body,
        StatusCode::UNPROCESSABLE_ENTITY,
        Some("/precision"),
    );
    // Sweeps: the mode applies to every point, is echoed in the table and a header.
    let sweep = json!({"case": "oblique", "base": maw_disc(vt), "precision": "exact",
                       "axes": [{"path": "/velocity/tangential", "values": [vt]}],
                       "outputs": ["/final_velocity/angular"]});
    let response = app
        .client
        .post(format!("{}/v1/sweeps", app.base))
        .json(&sweep)
        .send()
        .await
        .unwrap();
    assert_eq!(response.headers()["x-precision"], "exact");
    let table: Value = response.json().await.unwrap();
    assert_eq!(table["precision"], "exact");
    let exact = solve(vt, Precision::Exact).final_velocity.angular;
    assert_eq!(table["rows"][0][1].as_f64().unwrap().to_bits(), exact.to_bits());
    let mut conflict = sweep.clone();
    conflict["precision"] = json!("fast");
    conflict["base"]["precision"] = json!("exact");
    let (status, headers, body) = app.post("/v1/sweeps", &conflict).await;
    assert_problem(
        status,
        headers["content-type"].to_str().unwrap(),
        &body,
        StatusCode::UNPROCESSABLE_ENTITY,
        Some("/precision"),
    );
}

/// A number beyond a double's range (`1e999`) is well-formed JSON with a value
/// the schema cannot take: a 422 naming the member, like any other bad number,
/// in a request and in a sweep's `base` or axis values; JSON broken after it
/// is still a 400.
#[tokio::test]
async fn numbers_beyond_a_double_are_422_problems_naming_the_member() {
    let app = spawn_app(ServiceConfig::default()).await;
    let oblique = maw_disc(0.4).to_string();
    let cases = [
        (
            "/v1/impacts/oblique",
            oblique.replacen("\"mass\":1.0", "\"mass\":1e999", 1),
            "/body/mass",
        ),
        (
            "/v1/impacts/oblique",
            oblique.replacen("\"normal\":-1.0", "\"normal\":-1e999", 1),
            "/velocity/normal",
        ),
        (
            "/v1/impacts/oblique",
            oblique.replacen("\"friction\":0.123", "\"friction\":123e400", 1),
            "/friction",
        ),
        (
            "/v1/sweeps",
            format!(
                r#"{{"case": "oblique", "base": {}, "axes": [{{"path": "/velocity/tangential", "values": [0.4]}}]}}"#,
                oblique.replacen("\"mass\":1.0", "\"mass\":1e999", 1)
            ),
            "/base/body/mass",
        ),
        (
            "/v1/sweeps",
            format!(
                r#"{{"case": "oblique", "base": {oblique}, "axes": [{{"path": "/velocity/tangential", "values": [0.4, 1e999]}}]}}"#
            ),
            "/axes/0/values/1",
        ),
    ];
    for (path, body, pointer) in cases {
        assert!(body.contains("e999") || body.contains("e400"), "{body}");
        let (status, ct, problem) = app
            .post_raw(path, Some("application/json"), body.into_bytes())
            .await;
        assert_problem(
            status,
            &ct,
            &problem,
            StatusCode::UNPROCESSABLE_ENTITY,
            Some(pointer),
        );
        let detail = problem["detail"].as_str().unwrap();
        assert!(detail.starts_with("number out of range"), "{problem}");
        assert!(!detail.contains("line"), "{problem}");
    }
    // Malformed JSON after the huge number is still malformed.
    let broken = br#"{"body": {"mass": 1e999, "inertia": 1.0}, "contact": }"#.to_vec();
    let (status, ct, problem) = app
        .post_raw("/v1/impacts/oblique", Some("application/json"), broken)
        .await;
    assert_problem(status, &ct, &problem, StatusCode::BAD_REQUEST, None);
}

/// A wrong type on a number says "expected a number", not Rust's "f64"; on a
/// count, "expected a non-negative whole number".
#[tokio::test]
async fn wrong_types_are_described_in_plain_words() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut request = maw_disc(0.4);
    request["body"]["mass"] = json!("x");
    let (status, _, problem) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/body/mass");
    assert_eq!(problem["detail"], "invalid type: string \"x\", expected a number");
    // An optional number, and a number in a sweep's base (parsed on its own).
    let mut request = maw_disc(0.4);
    request["friction"] = json!(true);
    let (_, _, problem) = app.post("/v1/impacts/oblique", &request).await;
    assert_eq!(problem["pointer"], "/friction");
    assert_eq!(
        problem["detail"],
        "invalid type: boolean `true`, expected a number"
    );
    let mut base = maw_disc(0.4);
    base["velocity"]["normal"] = json!(null);
    let sweep = json!({"case": "oblique", "base": base,
                       "axes": [{"path": "/velocity/tangential", "values": [0.4]}]});
    let (status, _, problem) = app.post("/v1/sweeps", &sweep).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/base/velocity/normal");
    assert_eq!(problem["detail"], "invalid type: null, expected a number");
    let sweep = json!({"case": "oblique", "base": maw_disc(0.4),
                       "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 1.0, "count": -3}}]});
    let (status, _, problem) = app.post("/v1/sweeps", &sweep).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/axes/0/linspace/count");
    assert_eq!(
        problem["detail"],
        "invalid value: integer `-3`, expected a non-negative whole number"
    );
}

/// The served document declares the bearer token only when the service has an
/// API key, and then on every operation but `/healthz`.
#[tokio::test]
async fn the_served_openapi_document_declares_security_only_with_an_api_key() {
    fn security_members(v: &Value, at: &str, found: &mut Vec<String>) {
        match v {
            Value::Object(map) => {
                for (k, x) in map {
                    let here = format!("{at}/{}", k.replace('~', "~0").replace('/', "~1"));
                    if k == "security" || k == "securitySchemes" {
                        found.push(here.clone());
                    }
                    security_members(x, &here, found);
                }
            }
            Value::Array(items) => {
                for (i, x) in items.iter().enumerate() {
                    security_members(x, &format!("{at}/{i}"), found);
                }
            }
            _ => {}
        }
    }
    let open = spawn_app(ServiceConfig::default()).await;
    let doc: Value = open
        .client
        .get(format!("{}/openapi.json", open.base))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let mut found = Vec::new();
    security_members(&doc, "", &mut found);
    assert!(found.is_empty(), "no key, yet security at {found:?}");

    let keyed = spawn_app(ServiceConfig {
        api_key: Some("s3cret-token".into()),
        ..ServiceConfig::default()
    })
    .await;
    let doc: Value = keyed
        .client
        .get(format!("{}/openapi.json", keyed.base))
        .bearer_auth("s3cret-token")
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let scheme = &doc["components"]["securitySchemes"]["bearer"];
    assert_eq!(scheme["type"], "http", "{scheme}");
    assert_eq!(scheme["scheme"], "bearer", "{scheme}");
    assert!(doc.get("security").is_none(), "no document-wide requirement");
    let mut operations = 0;
    for (path, item) in doc["paths"].as_object().unwrap() {
        for (method, operation) in item.as_object().unwrap() {
            operations += 1;
            if ["/healthz", "/readyz", "/metrics"].contains(&path.as_str()) {
                assert!(operation.get("security").is_none(), "{method} {path}");
            } else {
                assert_eq!(operation["security"], json!([{"bearer": []}]), "{method} {path}");
            }
        }
    }
    assert!(operations >= 8, "{operations}");
}

/// The documented examples are real: the planar answer's example is the
/// server's answer to the oblique request example, the torsional one to the
/// torsional request example, and the Problem example is a refusal the server
/// gives (the oblique example made to recede).
#[tokio::test]
async fn documented_examples_are_the_servers_real_answers() {
    let app = spawn_app(ServiceConfig::default()).await;
    let doc: Value = serde_json::from_str(&openapi_json()).unwrap();
    let schema = |name: &str| doc["components"]["schemas"][name].clone();
    let example = |name: &str| {
        let s = schema(name);
        s.get("example")
            .cloned()
            .or_else(|| s["examples"].get(0).cloned())
            .unwrap_or_else(|| panic!("{name} has no example"))
    };
    for (path, request, response) in [
        ("/v1/impacts/oblique", "ObliqueRequest", "PlanarResponse"),
        ("/v1/impacts/torsional", "TorsionalRequest", "TorsionalResponse"),
    ] {
        let (status, _, answer) = app.post(path, &example(request)).await;
        assert_eq!(status, StatusCode::OK, "{path}: {answer}");
        assert_eq!(answer, example(response), "{path}");
    }
    let problem = example("Problem");
    let mut refused = example("ObliqueRequest");
    refused["velocity"]["normal"] = json!(1.0);
    let (status, _, answer) = app.post("/v1/impacts/oblique", &refused).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(answer, problem);
}

/// `POST /v1/impacts/planar` over HTTP: two cars conserve momentum; one body
/// against a barrier in world axes answers what `/v1/impacts/oblique` answers,
/// bit for bit in `exact` precision.
#[tokio::test]
async fn the_planar_contact_endpoint_answers_two_bodies_and_reduces_to_the_oblique_one() {
    let app = spawn_app(ServiceConfig::default()).await;
    let cars = crate::common::examples::cars();
    let (status, _, body) = app.post("/v1/impacts/planar", &cars).await;
    assert_eq!(status, StatusCode::OK, "{body}");
    let bodies = body["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), 2);
    for axis in ["x", "y"] {
        let p = 1500.0 * bodies[0]["velocity_change"][axis].as_f64().unwrap()
            + 1200.0 * bodies[1]["velocity_change"][axis].as_f64().unwrap();
        assert!(p.abs() < 1e-9, "momentum change {p} along {axis}");
    }
    assert_eq!(body["contact_velocity"]["final"]["tangential"], 0.0);
    assert_eq!(body["regime"], "sticking");

    // The Maw disc of the oblique example, in world axes with n = ŷ (t̂ = −x̂):
    // G sits d_d above C, v = v_n ŷ + v_t t̂.
    let oblique = json!({
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
        "restitution": 0.93, "friction": 0.123, "precision": "exact"
    });
    let world = json!({
        "bodies": [{"mass": 1.0, "inertia": 0.00125, "position": {"x": 0.0, "y": 0.05},
                    "velocity": {"x": -0.4, "y": -1.0}, "angular_velocity": 0.0}],
        "contact": {"point": {"x": 0.0, "y": 0.0}, "normal": {"x": 0.0, "y": 2.0}},
        "restitution": 0.93, "friction": 0.123, "precision": "exact"
    });
    let (_, _, one) = app.post("/v1/impacts/oblique", &oblique).await;
    let (status, _, general) = app.post("/v1/impacts/planar", &world).await;
    assert_eq!(status, StatusCode::OK, "{general}");
    let b = &general["bodies"][0];
    assert_eq!(b["velocity"]["y"], one["final_velocity"]["normal"]);
    assert_eq!(
        b["velocity"]["x"].as_f64().unwrap(),
        -one["final_velocity"]["tangential"].as_f64().unwrap()
    );
    assert_eq!(b["angular_velocity"], one["final_velocity"]["angular"]);
    for key in [
        "contact_velocity",
        "impulse_ratio",
        "critical_impulse_ratio",
        "restitution",
        "regime",
        "energy",
    ] {
        assert_eq!(general[key], one[key], "{key}");
    }
    assert_eq!(general["impulse"]["normal"], one["impulse"]["normal"]);
    assert_eq!(general["impulse"]["tangential"], one["impulse"]["tangential"]);
}

/// The planar examples in `examples/` answer what `examples/README.md` says.
#[tokio::test]
async fn the_planar_examples_answer_what_the_examples_readme_says() {
    let app = spawn_app(ServiceConfig::default()).await;
    let read = crate::common::examples::example;
    let (status, _, cars) = app
        .post("/v1/impacts/planar", &read("planar_car_to_car.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{cars}");
    assert_eq!(cars["regime"], "sticking");
    let dv = |o: &Value, k: usize| o["bodies"][k]["delta_v"].as_f64().unwrap();
    assert!(
        (dv(&cars, 0) - 8.45).abs() < 0.005 && (dv(&cars, 1) - 10.56).abs() < 0.005,
        "{cars}"
    );
    assert!((cars["impulse_ratio"].as_f64().unwrap() + 0.527).abs() < 0.0005);
    let (px, py) = (
        cars["impulse"]["x"].as_f64().unwrap(),
        cars["impulse"]["y"].as_f64().unwrap(),
    );
    let norm = px.hypot(py);
    assert!((px / norm + 0.885).abs() < 0.0005 && (py / norm - 0.466).abs() < 0.0005);
    assert!((cars["energy"]["normalized_loss"].as_f64().unwrap() - 0.98).abs() < 0.005);

    let (status, _, discs) = app
        .post("/v1/impacts/planar", &read("planar_billiard_discs.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{discs}");
    assert_eq!(discs["regime"], "sliding");
    assert_eq!(discs["impulse"]["normal"], 0.2652);
    assert_eq!(discs["impulse_ratio"], -0.06);
    assert!((discs["critical_impulse_ratio"].as_f64().unwrap() + 0.128).abs() < 0.0005);
    assert_eq!(discs["bodies"][0]["delta_v"], discs["bodies"][1]["delta_v"]);
    assert!((discs["bodies"][0]["angular_velocity"].as_f64().unwrap() - 6.55).abs() < 0.005);

    let response = app
        .client
        .post(format!("{}/v1/sweeps", app.base))
        .header("accept", "text/csv")
        .json(&read("planar_car_to_car_sweep.json"))
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::OK);
    assert_eq!(response.text().await.unwrap().lines().count(), 16);
}

/// `POST /v1/impacts/spatial` over HTTP: the examples answer with momentum
/// conserved, hostile tensors and normals are refused at their pointers, and
/// a spatial sweep streams.
#[tokio::test]
async fn the_spatial_contact_endpoint_answers_the_examples_and_refuses_at_the_pointer() {
    let app = spawn_app(ServiceConfig::default()).await;
    let read = crate::common::examples::example;
    let (status, _, topspin) = app
        .post("/v1/impacts/spatial", &read("spatial_tennis_topspin.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{topspin}");
    // Topspin slows the contact point's forward slip: the ball keeps more of
    // its forward speed than a flat one.
    let mut flat = read("spatial_tennis_topspin.json");
    flat["bodies"][0]["angular_velocity"]["y"] = json!(0.0);
    let (_, _, flat) = app.post("/v1/impacts/spatial", &flat).await;
    let forward = |o: &Value| o["bodies"][0]["velocity"]["x"].as_f64().unwrap();
    assert!(forward(&topspin) > forward(&flat), "{topspin} {flat}");
    assert_eq!(topspin["bodies"][0]["velocity"]["z"], 7.5);
    assert!(topspin.get("torsional_regime").is_none());
    let (status, _, sidespin) = app
        .post("/v1/impacts/spatial", &read("spatial_tennis_sidespin.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{sidespin}");
    // Spin about x slips the contact point along y: the ball kicks sideways.
    assert!(sidespin["bodies"][0]["velocity"]["y"].as_f64().unwrap() != 0.0);
    assert!(sidespin["torsional_regime"].is_string(), "{sidespin}");
    assert_eq!(sidespin["precision"], "exact");
    let (status, _, dem) = app
        .post("/v1/impacts/spatial", &read("spatial_dem_spheres.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{dem}");
    for axis in ["x", "y", "z"] {
        let dp = dem["bodies"][0]["velocity_change"][axis].as_f64().unwrap()
            + dem["bodies"][1]["velocity_change"][axis].as_f64().unwrap();
        assert!(dp.abs() < 1e-12, "equal masses: ΔV_A = −ΔV_B along {axis}: {dem}");
    }
    let (status, _, tool) = app
        .post("/v1/impacts/spatial", &read("spatial_robot_tool.json"))
        .await;
    assert_eq!(status, StatusCode::OK, "{tool}");
    assert!(tool["energy"]["loss"].as_f64().unwrap() >= 0.0);

    let mut hostile = read("spatial_tennis_topspin.json");
    hostile["bodies"][0]["inertia"] =
        json!({"xx": 1.0, "yy": 1.0, "zz": 1.0, "xy": 2.0, "xz": 0.0, "yz": 0.0});
    let (status, _, problem) = app.post("/v1/impacts/spatial", &hostile).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/bodies/0/inertia", "{problem}");
    hostile["bodies"][0]["inertia"] =
        json!({"xx": "NaN", "yy": 1.0, "zz": 1.0, "xy": 0.0, "xz": 0.0, "yz": 0.0});
    let (status, _, problem) = app.post("/v1/impacts/spatial", &hostile).await;
    assert!(status.is_client_error(), "{problem}");
    // Principal moments that break the triangle inequality: no rigid body.
    hostile["bodies"][0]["inertia"] =
        json!({"xx": 1.0, "yy": 1.0, "zz": 5.0, "xy": 0.0, "xz": 0.0, "yz": 0.0});
    let (status, _, problem) = app.post("/v1/impacts/spatial", &hostile).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
    assert_eq!(problem["pointer"], "/bodies/0/inertia", "{problem}");
    assert_eq!(
        problem["type"], "urn:restitution:problem:not-rigid-inertia",
        "{problem}"
    );
    assert!(
        problem["detail"]
            .as_str()
            .unwrap()
            .contains("triangle inequality"),
        "{problem}"
    );
    // A malformed inertia names the member and the forms accepted, no Rust type.
    for (inertia, pointer) in [
        (
            json!({"xx": 1.0, "yy": 1.0, "zz": 1.0, "xz": 0.0, "yz": 0.0}),
            "/bodies/0/inertia/xy",
        ),
        (
            json!({"xx": 1.0, "yy": 1.0, "zz": 1.0, "xy": "0", "xz": 0.0, "yz": 0.0}),
            "/bodies/0/inertia/xy",
        ),
        (
            json!({"sphere": {"radius": "big"}}),
            "/bodies/0/inertia/sphere/radius",
        ),
        (
            json!({"sphere": {"diameter": 1.0}}),
            "/bodies/0/inertia/sphere/diameter",
        ),
        (json!({"cube": {"edge": 1.0}}), "/bodies/0/inertia"),
        (json!(0.4), "/bodies/0/inertia"),
    ] {
        hostile["bodies"][0]["inertia"] = inertia.clone();
        let (status, _, problem) = app.post("/v1/impacts/spatial", &hostile).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{inertia}: {problem}");
        assert_eq!(problem["pointer"], pointer, "{inertia}: {problem}");
        let detail = problem["detail"].as_str().unwrap();
        for internal in ["Dto", "untagged", "variant", "f64"] {
            assert!(!detail.contains(internal), "{inertia}: {detail}");
        }
        if pointer == "/bodies/0/inertia" {
            assert!(
                detail.contains("sphere") && detail.contains("principal"),
                "{detail}"
            );
        }
    }
    let mut zero = read("spatial_tennis_topspin.json");
    zero["contact"]["normal"] = json!({"x": 0.0, "y": 0.0, "z": 0.0});
    let (status, _, problem) = app.post("/v1/impacts/spatial", &zero).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/contact/normal", "{problem}");
    let huge = r#"{"bodies": [{"mass": 1, "inertia": {"xx": 1e400, "yy": 1, "zz": 1, "xy": 0, "xz": 0, "yz": 0},
        "position": {"x": 0, "y": 0, "z": 1}, "velocity": {"x": 0, "y": 0, "z": -1},
        "angular_velocity": {"x": 0, "y": 0, "z": 0}}],
        "contact": {"point": {"x": 0, "y": 0, "z": 0}, "normal": {"x": 0, "y": 0, "z": 1}}, "restitution": 0.5}"#;
    let response = app
        .client
        .post(format!("{}/v1/impacts/spatial", app.base))
        .header("content-type", "application/json")
        .body(huge)
        .send()
        .await
        .unwrap();
    assert!(response.status().is_client_error());

    let sweep = json!({
        "case": "spatial",
        "base": read("spatial_tennis_topspin.json"),
        "axes": [{"path": "/bodies/0/angular_velocity/y", "linspace": {"start": -300.0, "stop": 300.0, "count": 7}}],
        "outputs": ["/bodies/0/velocity", "/regime", "/impulse/tangential/x"]
    });
    let response = app
        .client
        .post(format!("{}/v1/sweeps", app.base))
        .header("accept", "text/csv")
        .json(&sweep)
        .send()
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::OK);
    let text = response.text().await.unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 8, "{text}");
    assert!(
        lines[0].contains("/bodies/0/velocity/z") && lines[0].contains("/regime"),
        "{text}"
    );
}

/// Every scalar member of a JSON value with its pointer, in document order.
fn leaves(value: &Value, pointer: String, out: &mut Vec<(String, Value)>) {
    match value {
        Value::Object(members) => {
            for (key, member) in members {
                leaves(member, format!("{pointer}/{key}"), out);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                leaves(item, format!("{pointer}/{i}"), out);
            }
        }
        scalar => out.push((pointer, scalar.clone())),
    }
}

/// Every member of every request schema, given a value of the wrong kind,
/// is refused with a problem at that member's pointer whose detail names no
/// Rust type, serde variant or internal function. The requests are the
/// OpenAPI document's own examples, so a new member or schema is covered
/// without editing this test.
#[tokio::test]
async fn a_malformed_member_of_any_request_is_named_in_plain_words() {
    let app = spawn_app(ServiceConfig::default()).await;
    let doc: Value = serde_json::from_str(&openapi_json()).unwrap();
    let schemas = &doc["components"]["schemas"];
    let (mut operations, mut members) = (0, 0);
    for (path, item) in doc["paths"].as_object().unwrap() {
        let Some(reference) = item
            .pointer("/post/requestBody/content/application~1json/schema/$ref")
            .and_then(Value::as_str)
        else {
            continue;
        };
        let example = &schemas[reference.rsplit('/').next().unwrap()]["example"];
        assert!(example.is_object(), "{path}: {reference} has no example");
        operations += 1;
        let mut scalars = Vec::new();
        leaves(example, String::new(), &mut scalars);
        for (pointer, value) in scalars {
            let wrong = match value {
                Value::String(_) => json!(12.5),
                Value::Bool(_) => json!("yes"),
                _ => json!("twelve"),
            };
            let mut request = example.clone();
            *request.pointer_mut(&pointer).unwrap() = wrong.clone();
            let (status, _, problem) = app.post(path, &request).await;
            let context = format!("{path} {pointer} = {wrong}: {problem}");
            assert!(
                status == StatusCode::UNPROCESSABLE_ENTITY || status == StatusCode::BAD_REQUEST,
                "{status} {context}"
            );
            assert_eq!(problem["pointer"], pointer.as_str(), "{context}");
            let detail = problem["detail"].as_str().unwrap();
            for internal in [
                "Dto",
                "untagged",
                "variant of",
                "f64",
                "u64",
                "usize",
                "::",
                "struct ",
                "enum ",
            ] {
                assert!(!detail.contains(internal), "{internal:?} in {context}");
            }
            members += 1;
        }
    }
    assert!(
        operations >= 11 && members > 100,
        "{operations} operations, {members} members"
    );
}

/// Every operation that answers JSON alone (the document lists its 406)
/// refuses an `Accept` without JSON with a 406 problem before it reads the
/// body, and takes one that admits JSON at any quality; every other
/// operation with a body either negotiates its own formats or has none.
#[tokio::test]
async fn json_only_operations_refuse_an_accept_without_json() {
    let app = spawn_app(ServiceConfig::default()).await;
    let doc: Value = serde_json::from_str(&openapi_json()).unwrap();
    let mut checked = Vec::new();
    for (path, item) in doc["paths"].as_object().unwrap() {
        for (method, operation) in item.as_object().unwrap() {
            let Some(refusal) = operation["responses"].get("406") else {
                continue;
            };
            let only_json = refusal["description"]
                .as_str()
                .is_some_and(|d| d.contains("only format this operation answers"));
            if !only_json {
                continue;
            }
            let url = format!("{}{path}", app.base);
            let send = |accept: &'static str| {
                let request = match method.as_str() {
                    "get" => app.client.get(&url),
                    "post" => app.client.post(&url).json(&json!({})),
                    other => panic!("{other} {path}"),
                };
                request.header("accept", accept).send()
            };
            for accept in ["text/csv", "image/svg+xml, text/*", "application/json;q=0"] {
                let response = send(accept).await.unwrap();
                let status = response.status();
                let content_type = response.headers()["content-type"].to_str().unwrap().to_owned();
                let body: Value = response.json().await.unwrap();
                assert_problem(status, &content_type, &body, StatusCode::NOT_ACCEPTABLE, None);
                assert!(
                    body["detail"].as_str().unwrap().contains("application/json"),
                    "{body}"
                );
            }
            for accept in ["text/csv, application/json;q=0.1", "*/*", "application/*"] {
                let status = send(accept).await.unwrap().status();
                // The empty body's 422 for a post: past the negotiation.
                let expected = if method == "get" {
                    StatusCode::OK
                } else {
                    StatusCode::UNPROCESSABLE_ENTITY
                };
                assert_eq!(status, expected, "{method} {path} {accept}");
            }
            checked.push(format!("{method} {path}"));
        }
    }
    checked.sort();
    let expected = [
        "get /v1/quantities",
        "post /v1/fits/planar",
        "post /v1/fits/spatial",
        "post /v1/impacts/normal",
        "post /v1/impacts/oblique",
        "post /v1/impacts/planar",
        "post /v1/impacts/spatial",
        "post /v1/impacts/tangential",
        "post /v1/impacts/torsional",
        "post /v1/sweeps/plan",
    ];
    assert_eq!(checked, expected);
}
