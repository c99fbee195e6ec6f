//! `POST /v1/sweeps` over loopback: every format, both combine modes, per-point
//! errors, limits, streaming past the buffered limit, and the paper's figures.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use crate::common::server::{TestApp, spawn_app};
use reqwest::StatusCode;
use restitution::http::ServiceConfig;
use restitution::{BarrierImpact, Contact, Law, Outputs, PlanarVelocity, Precision, solve};
use serde_json::{Value, json};

fn maw_base() -> Value {
    json!({
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 0.0},
        "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34
    })
}

fn maw_point(vt: f64, f: f64) -> BarrierImpact {
    BarrierImpact::rigid(
        1.0,
        0.00125,
        Contact::central(0.05),
        PlanarVelocity {
            normal: -1.0,
            tangential: vt,
            angular: 0.0,
        },
        Law::TangentialRestitution {
            restitution: 0.93,
            friction: f,
            tangential_restitution: 0.34,
        },
    )
}

fn two_axis_sweep() -> Value {
    json!({
        "case": "tangential",
        "base": maw_base(),
        "axes": [
            {"path": "/velocity/tangential", "linspace": {"start": -1.0, "stop": 5.0, "count": 61}},
            {"path": "/friction", "values": [0.1, 0.123, 0.2]}
        ],
        "outputs": ["/contact_velocity/final/tangential", "/regime", "/energy/loss"]
    })
}

async fn json_table(app: &TestApp, body: &Value) -> Value {
    let (status, headers, bytes) = app.post_accept("/v1/sweeps", "application/json", body).await;
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&bytes));
    assert_eq!(headers["content-type"], "application/json");
    serde_json::from_slice(&bytes).expect("a JSON table")
}

#[tokio::test]
async fn json_table_is_in_product_order_and_matches_the_library_bit_for_bit() {
    let app = spawn_app(ServiceConfig::default()).await;
    let table = json_table(&app, &two_axis_sweep()).await;
    assert_eq!(
        table["columns"],
        json!([
            "/velocity/tangential",
            "/friction",
            "/contact_velocity/final/tangential",
            "/regime",
            "/energy/loss",
            "error"
        ])
    );
    assert_eq!(table["points"], 183);
    assert_eq!(table["errors"], 0);
    assert_eq!(table["precision"], "fast");
    let rows = table["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 183);
    let frictions = [0.1, 0.123, 0.2];
    for (i, row) in rows.iter().enumerate() {
        let vt = row[0].as_f64().unwrap();
        let f = row[1].as_f64().unwrap();
        // The first axis varies slowest; linspace(−1, 5, 61) steps by exactly 0.1 (one rounding).
        assert_eq!(f, frictions[i % 3]);
        assert_eq!(vt, ((i / 3) as f64).mul_add(0.1, -1.0));
        let expected = solve(&maw_point(vt, f), Outputs::ALL, Precision::Fast).unwrap();
        assert_eq!(
            row[2].as_f64().unwrap().to_bits(),
            expected.contact_velocity.r#final.tangential.to_bits()
        );
        assert_eq!(row[3], expected.regime.as_str());
        assert_eq!(
            row[4].as_f64().unwrap().to_bits(),
            expected.energy.unwrap().loss.to_bits()
        );
        assert_eq!(row[5], Value::Null);
    }
}

#[tokio::test]
async fn csv_and_ndjson_carry_the_same_rows_as_the_table() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = two_axis_sweep();
    let table = json_table(&app, &body).await;
    let rows = table["rows"].as_array().unwrap();

    let (status, headers, csv) = app.post_accept("/v1/sweeps", "text/csv", &body).await;
    assert_eq!(status, StatusCode::OK);
    assert!(headers["content-type"].to_str().unwrap().starts_with("text/csv"));
    assert_eq!(headers["x-sweep-points"], "183");
    let text = String::from_utf8(csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "/velocity/tangential,/friction,/contact_velocity/final/tangential,/regime,/energy/loss,error"
    );
    assert_eq!(lines.len(), 184);
    for (line, row) in lines[1..].iter().zip(rows) {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), 6);
        for k in [0, 1, 2, 4] {
            assert_eq!(fields[k].parse::<f64>().unwrap(), row[k].as_f64().unwrap());
        }
        assert_eq!(fields[3], row[3].as_str().unwrap());
        assert_eq!(fields[5], "");
    }

    let (status, headers, ndjson) = app.post_accept("/v1/sweeps", "application/x-ndjson", &body).await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(headers["content-type"], "application/x-ndjson");
    let objects: Vec<Value> = String::from_utf8(ndjson)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(objects.len(), 183);
    let columns = table["columns"].as_array().unwrap();
    for (object, row) in objects.iter().zip(rows) {
        for (k, column) in columns.iter().enumerate() {
            assert_eq!(object[column.as_str().unwrap()], row[k]);
        }
    }
}

#[tokio::test]
async fn zip_pairs_axes_and_refuses_unequal_lengths() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut body = json!({
        "case": "tangential",
        "base": maw_base(),
        "axes": [
            {"path": "/velocity/tangential", "values": [0.1, 1.0, 2.0]},
            {"path": "/friction", "values": [0.1, 0.123, 0.2]}
        ],
        "combine": "zip",
        "outputs": ["/final_velocity"]
    });
    let table = json_table(&app, &body).await;
    assert_eq!(table["points"], 3);
    assert_eq!(
        table["columns"],
        json!([
            "/velocity/tangential",
            "/friction",
            "/final_velocity/normal",
            "/final_velocity/tangential",
            "/final_velocity/angular",
            "error"
        ])
    );
    let row = &table["rows"][2];
    assert_eq!((row[0].as_f64(), row[1].as_f64()), (Some(2.0), Some(0.2)));
    let expected = solve(&maw_point(2.0, 0.2), Outputs::ALL, Precision::Fast).unwrap();
    assert_eq!(row[3].as_f64().unwrap(), expected.final_velocity.tangential);

    body["axes"][1]["values"] = json!([0.1, 0.2]);
    let (status, _, problem) = app.post("/v1/sweeps", &body).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/axes/1");
    assert!(problem["detail"].as_str().unwrap().contains("equal length"));
}

#[tokio::test]
async fn invalid_points_carry_an_error_and_do_not_fail_the_sweep() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({
        "case": "oblique",
        "base": {
            "body": {"mass": 1.0, "inertia": 0.00125},
            "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
            "velocity": {"normal": -1.0, "tangential": 2.0},
            "restitution": 0.93, "friction": 0.123
        },
        "axes": [
            {"path": "/velocity/normal", "values": [-1.0, 0.0, 2.0]},
            {"path": "/restitution", "values": [0.5, 1.5]}
        ],
        "outputs": ["/regime", "/impulse/normal"]
    });
    let table = json_table(&app, &body).await;
    assert_eq!(table["points"], 6);
    assert_eq!(table["errors"], 5);
    let rows = table["rows"].as_array().unwrap();
    assert_eq!(rows[0][2], "sliding");
    assert!(rows[0][3].as_f64().unwrap() > 0.0);
    assert_eq!(rows[0][4], Value::Null);
    assert_eq!(rows[1][4], "Input out of range");
    for row in &rows[2..] {
        assert_eq!(row[2], Value::Null);
        assert_eq!(row[3], Value::Null);
        assert_eq!(row[4], "Contact is not approaching");
    }
    let (_, _, csv) = app.post_accept("/v1/sweeps", "text/csv", &body).await;
    let text = String::from_utf8(csv).unwrap();
    assert_eq!(
        text.lines().nth(4).unwrap(),
        "0.0,1.5,,,Contact is not approaching"
    );
}

#[tokio::test]
async fn structural_errors_are_422_problems_naming_the_member() {
    let app = spawn_app(ServiceConfig::default()).await;
    let cases = [
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/velocity/speed", "values": [1.0]}]}),
            "/axes/0/path",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "values": [1.0]}], "outputs": ["/energy/nope"]}),
            "/outputs/0",
        ),
        (
            // A repeated output would repeat its column at every point.
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "values": [1.0]}], "outputs": ["/energy", "/energy/loss"]}),
            "/outputs/1",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "values": [1.0]}], "outputs": ["", ""]}),
            "/outputs/1",
        ),
        (
            json!({"case": "tangential", "base": {"body": {"mass": 1.0}}, "axes": [{"path": "/friction", "values": [1.0]}]}),
            "/base/body/inertia",
        ),
        (
            json!({"case": "oblique", "base": {
                "body": {"mass": 1.0, "inertia": 0.00125},
                "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                "velocity": {"normal": -1.0}, "restitution": 0.5, "impulse_ratio": 0.1},
                "axes": [{"path": "/friction", "values": [1.0]}]}),
            "/axes/0/path",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "values": [1.0], "linspace": {"start": 0, "stop": 1, "count": 2}}]}),
            "/axes/0",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "logspace": {"start": 0.0, "stop": 1.0, "count": 3}}]}),
            "/axes/0/logspace",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": []}),
            "/axes",
        ),
        (
            json!({"case": "tangential", "base": maw_base(), "axes": [{"path": "/friction", "values": [1.0]}, {"path": "/friction", "values": [2.0]}]}),
            "/axes/1/path",
        ),
        (
            json!({"case": "normal", "base": {"body": {"mass": 1.0}, "velocity": {"normal": -1.0}, "restitution": 0.5},
                   "axes": [{"path": "/body/inertia", "values": [1.0]}]}),
            "/axes/0/path",
        ),
    ];
    for (body, pointer) in cases {
        let (status, headers, problem) = app.post("/v1/sweeps", &body).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{body}: {problem}");
        assert_eq!(headers["content-type"], "application/problem+json");
        assert_eq!(problem["pointer"], pointer, "{body}: {problem}");
    }
    let (status, headers, bytes) = app
        .post_accept("/v1/sweeps", "text/html", &two_axis_sweep())
        .await;
    assert_eq!(status, StatusCode::NOT_ACCEPTABLE);
    assert_eq!(headers["content-type"], "application/problem+json");
    assert!(String::from_utf8_lossy(&bytes).contains("text/csv"));
}

#[tokio::test]
async fn an_axis_error_lists_the_inputs_the_base_law_reads_and_no_others() {
    let app = spawn_app(ServiceConfig::default()).await;
    for (base_case, base, path, readable, unread) in [
        (
            "tangential",
            maw_base(),
            "/impulse_ratio",
            "/tangential_restitution",
            "/impulse_ratio",
        ),
        (
            "normal",
            json!({"body": {"mass": 1.0}, "velocity": {"normal": -1.0}, "restitution": 0.5}),
            "/velocity/angular",
            "/velocity/tangential",
            "/body/inertia",
        ),
        (
            "tangential",
            maw_base(),
            "/nowhere",
            "/friction",
            "/kinetic_restitution/value",
        ),
    ] {
        let body = json!({"case": base_case, "base": base, "axes": [{"path": path, "values": [0.1]}]});
        let (status, _, problem) = app.post("/v1/sweeps", &body).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
        assert_eq!(problem["pointer"], "/axes/0/path");
        let detail = problem["detail"].as_str().unwrap();
        let (_, offered) = detail.split_once("one of: ").expect("a list of the inputs");
        let offered: Vec<&str> = offered.split(", ").collect();
        assert!(offered.contains(&readable), "{detail}");
        assert!(!offered.contains(&unread), "{detail}");
    }
}

#[tokio::test]
async fn an_exact_zero_is_written_as_zero_not_minus_zero() {
    let app = spawn_app(ServiceConfig::default()).await;
    // μ_c = v_t / ((1 + e) v_n) with v_t = 0 and v_n < 0 is −0 in IEEE arithmetic.
    let request =
        json!({"body": {"mass": 1.0}, "velocity": {"normal": -1.0, "tangential": 0.0}, "restitution": 0.5});
    for precision in ["fast", "exact"] {
        let mut request = request.clone();
        request["precision"] = json!(precision);
        let response = app
            .client
            .post(format!("{}/v1/impacts/normal", app.base))
            .json(&request)
            .send()
            .await
            .unwrap();
        assert_eq!(response.status(), StatusCode::OK);
        let text = response.text().await.unwrap();
        assert!(text.contains("\"critical_impulse_ratio\":0.0"), "{text}");
        assert!(!text.contains("-0.0"), "{text}");
    }
    let sweep = json!({"case": "normal", "base": request,
                       "axes": [{"path": "/restitution", "values": [0.0, 0.5, 1.0]}]});
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &sweep).await;
    assert_eq!(status, StatusCode::OK);
    let csv = String::from_utf8(bytes).unwrap();
    assert!(csv.lines().count() == 4 && !csv.contains("-0"), "{csv}");
}

#[tokio::test]
async fn a_sweep_of_a_trillion_points_is_refused_at_once() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [
            {"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 1_000_000}},
            {"path": "/friction", "linspace": {"start": 0.0, "stop": 1.0, "count": 1_000_000}}
        ]
    });
    for accept in ["text/csv", "application/json"] {
        let start = Instant::now();
        let (status, _, bytes) = app.post_accept("/v1/sweeps", accept, &body).await;
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "refused without computing"
        );
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
        let problem: Value = serde_json::from_slice(&bytes).unwrap();
        let detail = problem["detail"].as_str().unwrap();
        assert!(detail.contains("1000000000000 points"), "{detail}");
        let limit = if accept == "text/csv" {
            "10000000"
        } else {
            "200000"
        };
        assert!(detail.contains(&format!("the limit is {limit}")), "{detail}");
        assert_eq!(problem["pointer"], "/axes");
    }
    // Beyond 2^64: three axes of 2^63 values each.
    let huge = json!({"start": 0.0, "stop": 1.0, "count": 9_223_372_036_854_775_807_u64});
    let body = json!({"case": "tangential", "base": maw_base(), "axes": [
        {"path": "/velocity/tangential", "linspace": huge},
        {"path": "/friction", "linspace": huge},
        {"path": "/restitution", "linspace": huge}
    ]});
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &body).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let problem: Value = serde_json::from_slice(&bytes).unwrap();
    assert!(problem["detail"].as_str().unwrap().contains("more than 2^128"));
}

#[tokio::test]
async fn csv_streams_sweeps_larger_than_the_buffered_limit_in_order() {
    let config = ServiceConfig {
        max_buffered_sweep_points: 1_000,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 50_001}}],
        "outputs": ["/contact_velocity/final/tangential"]
    });
    let (status, _, _) = app.post_accept("/v1/sweeps", "application/json", &body).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &body).await;
    assert_eq!(status, StatusCode::OK);
    let text = String::from_utf8(bytes).unwrap();
    let mut previous = f64::NEG_INFINITY;
    let mut count = 0;
    for line in text.lines().skip(1) {
        let vt: f64 = line.split(',').next().unwrap().parse().unwrap();
        assert!(vt > previous, "rows in axis order");
        previous = vt;
        count += 1;
    }
    assert_eq!(count, 50_001);
    assert_eq!(previous, 5.0);
}

#[tokio::test]
async fn a_client_that_disconnects_stops_the_stream_and_the_server_keeps_serving() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 10_000_000}}]
    });
    for (accept, first_bytes) in [
        ("text/csv", &b"/velocity/tangential,"[..]),
        // An Arrow stream starts with the continuation marker of its schema message.
        ("application/vnd.apache.arrow.stream", &b"\xff\xff\xff\xff"[..]),
    ] {
        let mut response = app
            .client
            .post(format!("{}/v1/sweeps", app.base))
            .header("accept", accept)
            .json(&body)
            .send()
            .await
            .unwrap();
        assert_eq!(response.status(), StatusCode::OK);
        let first = response.chunk().await.unwrap().unwrap();
        assert!(first.starts_with(first_bytes), "{accept}");
        assert!(app.streams.active() > 0);
        drop(response);
        app.until_sweeps_stop().await;
    }
    let table = json_table(&app, &two_axis_sweep()).await;
    assert_eq!(table["points"], 183);
}

#[tokio::test]
async fn svg_plots_the_first_output_with_one_series_per_second_axis_value() {
    let app = spawn_app(ServiceConfig::default()).await;
    let (status, headers, bytes) = app
        .post_accept("/v1/sweeps", "image/svg+xml", &two_axis_sweep())
        .await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(headers["content-type"], "image/svg+xml");
    let svg = String::from_utf8(bytes).unwrap();
    assert!(svg.starts_with("<svg"));
    // Axes named in words, with the paper's symbol (its subscript a tspan) and the SI unit.
    assert!(svg.contains(">tangential velocity v<tspan"), "{svg}");
    assert!(
        svg.contains(">final tangential contact velocity V<tspan"),
        "{svg}"
    );
    assert!(
        svg.contains(">ct</tspan><tspan dy=") && svg.contains("> (m/s)</tspan>"),
        "{svg}"
    );
    assert!(
        !svg.contains("/velocity/tangential") && !svg.contains("/contact_velocity"),
        "no JSON pointers"
    );
    assert!(svg.contains("<title>") && svg.contains("<desc>"));
    assert!(!svg.contains("style"), "presentation attributes only");
    for label in [">f = 0.1<", ">f = 0.123<", ">f = 0.2<"] {
        assert!(svg.contains(label), "legend {label}");
    }
    // Three series, each one path; their legend marks are three more.
    assert_eq!(part(&svg, "curves").matches("<path ").count(), 3);
    assert_eq!(part(&svg, "legend").matches(r#"stroke-width="2""#).count(), 3);
    // Coordinates keep their decimals.
    let curves = part(&svg, "curves");
    assert!(curves.matches('.').count() > 3 * 61, "{curves}");
    // Each friction switches from sliding to tangential restitution and back
    // within the sweep: marked on its line, the switch named in the legend.
    assert!(
        part(&svg, "markers").matches("<path ").count() + part(&svg, "markers").matches("<rect ").count()
            >= 6
    );
    assert!(svg.contains("regime switch: sliding → restitution"), "{svg}");
    assert!(svg.contains("regime switch: restitution → sliding"), "{svg}");
    // A regime cannot be plotted.
    let mut body = two_axis_sweep();
    body["outputs"] = json!(["/regime"]);
    let (status, _, _) = app.post_accept("/v1/sweeps", "image/svg+xml", &body).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
}

/// The body of the plot's `<g data-part="…">` group, nested groups included.
fn part<'a>(svg: &'a str, name: &str) -> &'a str {
    let open = format!(r#"<g data-part="{name}">"#);
    let start = svg.find(&open).unwrap_or_else(|| panic!("no {name} in {svg}")) + open.len();
    let rest = &svg[start..];
    let mut depth = 0;
    for (i, _) in rest.match_indices('<') {
        if rest[i..].starts_with("<g ") || rest[i..].starts_with("<g>") {
            depth += 1;
        } else if rest[i..].starts_with("</g>") {
            if depth == 0 {
                return &rest[..i];
            }
            depth -= 1;
        }
    }
    rest
}

#[tokio::test]
async fn a_one_series_svg_plot_shades_each_regime_even_when_the_regime_is_not_asked_for() {
    let app = spawn_app(ServiceConfig::default()).await;
    let path = format!(
        "{}/examples/figure2_coulomb_friction.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    body["outputs"] = json!(["/contact_velocity/final/tangential"]);
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "image/svg+xml", &body).await;
    assert_eq!(status, StatusCode::OK);
    let svg = String::from_utf8(bytes).unwrap();
    // Maw's disc sticks up to v_t = (1 + e) μ_c |v_n| ≈ 0.712 m/s, then slides.
    let bands = part(&svg, "bands");
    assert_eq!(bands.matches("<rect ").count(), 2, "{bands}");
    let sticking = bands.find(r#"data-label="sticking""#).expect("a sticking band");
    let sliding = bands.find(r#"data-label="sliding""#).expect("a sliding band");
    assert!(sticking < sliding, "sticking first, at low v_t");
    assert!(
        svg.contains(">regime: sticking<") && svg.contains(">regime: sliding<"),
        "{svg}"
    );
    assert!(
        svg.contains("Regimes: sticking from 0 to 0.715, sliding from 0.715 to 3."),
        "{svg}"
    );
    // The plot still answers only what was asked in the other formats.
    let table = json_table(&app, &body).await;
    assert_eq!(
        table["columns"],
        json!([
            "/velocity/tangential",
            "/contact_velocity/final/tangential",
            "error"
        ])
    );
}

#[tokio::test]
async fn an_svg_plot_of_a_logspace_axis_has_a_logarithmic_axis() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [{"path": "/friction", "logspace": {"start": 0.01, "stop": 1.0, "count": 41}}],
        "outputs": ["/energy/loss"]
    });
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "image/svg+xml", &body).await;
    assert_eq!(status, StatusCode::OK);
    let svg = String::from_utf8(bytes).unwrap();
    let ticks = part(&svg, "x-ticks");
    for label in [">0.01<", ">0.1<", ">1<"] {
        assert!(ticks.contains(label), "{label} in {ticks}");
    }
    assert!(svg.contains(">friction coefficient f (dimensionless)<"), "{svg}");
    assert!(
        svg.contains(">energy loss T<tspan") && svg.contains("> (J)</tspan>"),
        "{svg}"
    );
}

/// Rows of a one-axis sweep from an example file: (axis value, first output, regime).
async fn example(app: &TestApp, file: &str) -> Vec<(f64, f64, String)> {
    let path = format!("{}/examples/{file}", env!("CARGO_MANIFEST_DIR"));
    let body: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let table = json_table(app, &body).await;
    assert_eq!(table["errors"], 0);
    table["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            (
                r[0].as_f64().unwrap(),
                r[1].as_f64().unwrap(),
                r[2].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

/// Least-squares line through points: (slope, intercept).
fn line(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let (sx, sy) = points.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
    let (mx, my) = (sx / n, sy / n);
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), p| {
        (a + (p.0 - mx) * (p.1 - my), b + (p.0 - mx) * (p.0 - mx))
    });
    let slope = sxy / sxx;
    (slope, my - slope * mx)
}

fn branch(rows: &[(f64, f64, String)], regime: &str) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.2 == regime)
        .map(|r| (r.0, r.1))
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

#[tokio::test]
async fn figure_2_rolling_then_sliding_with_unit_slope() {
    let app = spawn_app(ServiceConfig::default()).await;
    let rows = example(&app, "figure2_coulomb_friction.json").await;
    let b = 0.123 * 1.93 * 3.0;
    let rolling = branch(&rows, "sticking");
    let sliding = branch(&rows, "sliding");
    assert!(rolling.iter().all(|&(x, y)| x <= b && y.abs() < 1e-15));
    let (slope, intercept) = line(&sliding);
    assert!(close(slope, 1.0) && close(intercept, -b), "{slope} {intercept}");
    assert!(sliding.iter().all(|&(x, _)| x > b));
}

#[tokio::test]
async fn figure_3_sliding_and_restitution_lines_meet_at_the_switch() {
    let app = spawn_app(ServiceConfig::default()).await;
    let rows = example(&app, "figure3_tangential_restitution_maw.json").await;
    let (e, f, et, lambda) = (0.93, 0.123, 0.34, 2.0);
    let (slope_s, intercept_s) = line(&branch(&rows, "sliding"));
    let (slope_r, intercept_r) = line(&branch(&rows, "restitution"));
    assert!(close(slope_s, 1.0), "sliding slope {slope_s}");
    // −f (1 + e)(1 + λ) = −0.71217; the paper reads −0.72 off its plot.
    assert!(close(intercept_s, -f * (1.0 + e) * (1.0 + lambda)));
    assert!((intercept_s + 0.72).abs() < 0.01);
    assert!(
        close(slope_r, -et) && intercept_r.abs() < 1e-12,
        "restitution {slope_r} {intercept_r}"
    );
    // The lines meet where the model switches: v_ct = f (1 + e)(1 + λ) / (1 + e_t).
    let switch = f * (1.0 + e) * (1.0 + lambda) / (1.0 + et);
    assert!(close(
        slope_s * switch + intercept_s,
        slope_r * switch + intercept_r
    ));
    let last_restitution = rows
        .iter()
        .filter(|r| r.2 == "restitution")
        .map(|r| r.0)
        .fold(0.0, f64::max);
    let first_sliding = rows
        .iter()
        .filter(|r| r.2 == "sliding")
        .map(|r| r.0)
        .fold(f64::MAX, f64::min);
    assert!(last_restitution <= switch && switch < first_sliding);
}

#[tokio::test]
async fn figure_4_torsional_branches_have_slopes_minus_ez_and_one_minus_ez() {
    let app = spawn_app(ServiceConfig::default()).await;
    let rows = example(&app, "figure4_torsional_rubber_ball.json").await;
    let ez = 0.2;
    let switch = 0.3 * 0.005 * 0.1 * 1.8 * 3.0 / 0.000036;
    let (slope_r, intercept_r) = line(&branch(&rows, "restitution"));
    let (slope_s, intercept_s) = line(&branch(&rows, "sliding"));
    assert!(close(slope_r, -ez) && intercept_r.abs() < 1e-12);
    assert!(close(slope_s, 1.0 - ez));
    assert!(close(
        slope_s * switch + intercept_s,
        slope_r * switch + intercept_r
    ));
    assert!((switch - 22.5).abs() < 1e-12);
}

/// A planar sweep: an axis on body B's velocity, the columns each car's
/// delta-V; every row is the library's answer for that point, bit for bit.
#[tokio::test]
async fn a_planar_sweep_takes_body_inputs_as_axes_and_body_outputs_as_columns() {
    use restitution::{BodiesImpact, Lamina, Law, Outputs, PlanarContact, Precision, solve};
    let app = spawn_app(ServiceConfig::default()).await;
    let cars = crate::common::examples::cars();
    let body = json!({
        "case": "planar",
        "base": cars,
        "axes": [{"path": "/bodies/1/velocity/y", "linspace": {"start": 0.0, "stop": 30.0, "count": 7}}],
        "outputs": ["/bodies/0/delta_v", "/bodies/1/delta_v", "/regime"]
    });
    let table = json_table(&app, &body).await;
    assert_eq!(
        table["columns"],
        json!([
            "/bodies/1/velocity/y",
            "/bodies/0/delta_v",
            "/bodies/1/delta_v",
            "/regime",
            "error"
        ])
    );
    let lamina = |mass: f64, inertia: f64, position: [f64; 2], velocity: [f64; 2]| Lamina {
        mass,
        inertia,
        position,
        velocity,
        angular_velocity: 0.0,
    };
    for row in table["rows"].as_array().unwrap() {
        let vy = row[0].as_f64().unwrap();
        let impact = BodiesImpact {
            a: lamina(1500.0, 2500.0, [0.0, 0.0], [15.0, 0.0]),
            b: Some(lamina(1200.0, 1800.0, [3.0, -1.5], [0.0, vy])),
            contact: PlanarContact {
                point: [2.2, -0.6],
                normal: [-1.0, 0.0],
            },
            law: Law::Friction {
                restitution: 0.2,
                friction: 0.6,
            },
        };
        let o = solve(&impact, Outputs::ALL, Precision::Fast).unwrap();
        assert_eq!(row[1].as_f64(), Some(o.bodies[0].delta_v), "{row}");
        assert_eq!(row[2].as_f64(), Some(o.bodies[1].delta_v), "{row}");
        assert_eq!(row[3].as_str(), Some(o.regime.as_str()), "{row}");
    }
    // A barrier base's columns (all outputs) leave body B out.
    let mut all = body.clone();
    all["base"]["bodies"] = json!([cars["bodies"][0]]);
    all["axes"] = json!([{"path": "/bodies/0/velocity/x", "values": [10.0, 20.0]}]);
    all.as_object_mut().unwrap().remove("outputs");
    let table = json_table(&app, &all).await;
    let columns: Vec<&str> = table["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert!(
        columns.contains(&"/bodies/0/delta_v") && !columns.iter().any(|c| c.starts_with("/bodies/1/")),
        "{columns:?}"
    );
    // An axis on body B of a barrier base names the inputs the base reads.
    let mut barrier = body.clone();
    barrier["base"]["bodies"] = json!([cars["bodies"][0]]);
    let (status, _, problem) = app.post("/v1/sweeps", &barrier).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/axes/0/path", "{problem}");
}

/// Ranges from the plan tile the sweep: their rows, concatenated, are the whole
/// sweep's rows byte for byte, in every streamed format and in the JSON table.
#[tokio::test]
async fn planned_ranges_tile_the_whole_sweep_in_every_format() {
    let app = spawn_app(ServiceConfig::default()).await;
    let sweep = two_axis_sweep();
    for (shards, each) in [(Some(4), None), (Some(200), None), (None, Some(50))] {
        let mut request = json!({"sweep": sweep});
        if let Some(k) = shards {
            request["shards"] = json!(k);
        }
        if let Some(m) = each {
            request["points_per_shard"] = json!(m);
        }
        let (status, _, plan) = app.post("/v1/sweeps/plan", &request).await;
        assert_eq!(status, StatusCode::OK, "{plan}");
        assert_eq!(plan["points"], 183);
        let ranges: Vec<(u64, u64)> = plan["ranges"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| (r["start"].as_u64().unwrap(), r["end"].as_u64().unwrap()))
            .collect();
        assert_eq!(ranges.len() as u64, shards.unwrap_or(183_u64.div_ceil(50)));
        assert_eq!(ranges.first().unwrap().0, 0);
        assert_eq!(ranges.last().unwrap().1, 183);
        assert!(ranges.windows(2).all(|w| w[0].1 == w[1].0), "{ranges:?}");
        for accept in ["text/csv", "application/x-ndjson"] {
            let (_, _, whole) = app.post_accept("/v1/sweeps", accept, &sweep).await;
            let mut joined = Vec::new();
            for &(start, end) in &ranges {
                let mut slice = sweep.clone();
                slice["range"] = json!({"start": start, "end": end});
                let (status, headers, bytes) = app.post_accept("/v1/sweeps", accept, &slice).await;
                assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&bytes));
                assert_eq!(headers["x-sweep-points"], (end - start).to_string().as_str());
                assert_eq!(headers["x-sweep-total-points"], "183");
                assert_eq!(headers["x-sweep-range"], format!("{start}-{end}").as_str());
                let body = if accept == "text/csv" {
                    // Each slice repeats the header line.
                    let at = bytes.iter().position(|&b| b == b'\n').unwrap() + 1;
                    if joined.is_empty() {
                        joined.extend_from_slice(&bytes[..at]);
                    }
                    bytes[at..].to_vec()
                } else {
                    bytes
                };
                joined.extend(body);
            }
            assert_eq!(
                String::from_utf8(joined).unwrap(),
                String::from_utf8(whole).unwrap()
            );
        }
    }
    let whole = json_table(&app, &sweep).await;
    let mut slice = sweep.clone();
    slice["range"] = json!({"start": 60, "end": 70});
    let part = json_table(&app, &slice).await;
    assert_eq!(part["rows"], json!(whole["rows"].as_array().unwrap()[60..70]));
    assert_eq!(
        (&part["points"], &part["total_points"], &part["range"]),
        (&json!(10), &json!(183), &json!({"start": 60, "end": 70}))
    );
}

/// The point limit applies to a range: a grid far above the limit is served
/// in slices, and the plan refuses shards that would exceed it.
#[tokio::test]
async fn a_grid_above_the_limit_is_served_in_ranges_and_bad_ranges_are_422() {
    let config = ServiceConfig {
        max_sweep_points: 1000,
        ..ServiceConfig::default()
    };
    let app = spawn_app(config).await;
    let mut big = two_axis_sweep();
    big["axes"][0]["linspace"]["count"] = json!(1_000_000_000_000_u64);
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &big).await;
    let problem: Value = serde_json::from_slice(&bytes).unwrap();
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert!(
        problem["detail"].as_str().unwrap().contains("\"range\""),
        "{problem}"
    );

    let (status, _, plan) = app
        .post("/v1/sweeps/plan", &json!({"sweep": big, "shards": 10}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(plan["pointer"], "/shards");
    assert!(
        plan["detail"]
            .as_str()
            .unwrap()
            .contains("at least 3000000000 shards"),
        "{plan}"
    );
    let (status, _, plan) = app
        .post(
            "/v1/sweeps/plan",
            &json!({"sweep": big, "points_per_shard": 1000}),
        )
        .await;
    assert_eq!(
        (status, &plan["pointer"]),
        (StatusCode::UNPROCESSABLE_ENTITY, &json!("/points_per_shard"))
    );
    let mut last = big.clone();
    last["range"] = json!({"start": 2_999_999_999_900_u64, "end": 3_000_000_000_000_u64});
    let (status, _, plan) = app
        .post("/v1/sweeps/plan", &json!({"sweep": last, "points_per_shard": 30}))
        .await;
    assert_eq!(status, StatusCode::OK, "{plan}");
    assert_eq!(plan["points"], 3_000_000_000_000_u64);
    assert_eq!(plan["ranges"].as_array().unwrap().len(), 4);
    assert_eq!(
        plan["ranges"][3],
        json!({"start": 2_999_999_999_990_u64, "end": 3_000_000_000_000_u64})
    );

    // The last 100 points of a 3·10^12-point grid, streamed.
    let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &last).await;
    assert_eq!(status, StatusCode::OK);
    let text = String::from_utf8(bytes).unwrap();
    assert_eq!(text.lines().count(), 101);
    assert!(text.lines().last().unwrap().starts_with("5.0,0.2,"), "{text}");

    for (range, detail) in [
        (json!({"start": 5, "end": 4}), "not within"),
        (json!({"start": 0, "end": 3_000_000_000_001_u64}), "not within"),
        (json!({"start": 0, "end": 1001}), "the limit is 1000"),
    ] {
        let mut bad = big.clone();
        bad["range"] = range;
        let (status, _, bytes) = app.post_accept("/v1/sweeps", "text/csv", &bad).await;
        let problem: Value = serde_json::from_slice(&bytes).unwrap();
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
        assert_eq!(problem["pointer"], "/range");
        assert!(problem["detail"].as_str().unwrap().contains(detail), "{problem}");
    }
    let (status, _, plan) = app
        .post("/v1/sweeps/plan", &json!({"sweep": two_axis_sweep()}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{plan}");
    let mut bad_base = two_axis_sweep();
    bad_base["base"]["restitution"] = json!("high");
    let (status, _, plan) = app
        .post("/v1/sweeps/plan", &json!({"sweep": bad_base, "shards": 2}))
        .await;
    assert_eq!(
        (status, &plan["pointer"]),
        (
            StatusCode::UNPROCESSABLE_ENTITY,
            &json!("/sweep/base/restitution")
        )
    );
}

/// Reads an Arrow IPC stream into its schema metadata and rows of cells
/// (`None` for null, numbers as f64, names as text).
fn read_arrow(bytes: &[u8]) -> (HashMap<String, String>, Vec<String>, Rows) {
    use arrow_array::cast::AsArray;
    use arrow_array::types::{Float64Type, Int16Type};
    use arrow_array::{Array, StringArray};
    let reader = arrow_ipc::reader::StreamReader::try_new(bytes, None).expect("an Arrow stream");
    let schema = reader.schema();
    let names = schema.fields().iter().map(|f| f.name().clone()).collect();
    let mut rows = Vec::new();
    for batch in reader {
        let batch = batch.expect("a record batch");
        let start = rows.len();
        rows.extend((0..batch.num_rows()).map(|_| Vec::new()));
        for column in batch.columns() {
            for (i, row) in rows[start..].iter_mut().enumerate() {
                row.push(if column.is_null(i) {
                    None
                } else if let Some(numbers) = column.as_primitive_opt::<Float64Type>() {
                    Some(Cell::Number(numbers.value(i)))
                } else {
                    let names = column.as_dictionary::<Int16Type>();
                    let values = names.values().as_any().downcast_ref::<StringArray>().unwrap();
                    Some(Cell::Name(
                        values.value(names.keys().value(i) as usize).to_owned(),
                    ))
                });
            }
        }
    }
    (schema.metadata().clone().into(), names, rows)
}

/// Rows of cells, `None` for an empty cell.
type Rows = Vec<Vec<Option<Cell>>>;

#[derive(Debug, Clone, PartialEq)]
enum Cell {
    Number(f64),
    Name(String),
}

/// CSV rows as cells: an empty cell is `None`, a number parses to the exact
/// double its shortest round-trip text names.
fn read_csv(bytes: &[u8]) -> (Vec<String>, Rows) {
    let text = String::from_utf8(bytes.to_vec()).unwrap();
    let mut lines = text.lines();
    let names = lines.next().unwrap().split(',').map(str::to_owned).collect();
    let rows = lines
        .map(|line| {
            line.split(',')
                .map(|c| match c {
                    "" => None,
                    c => Some(
                        c.parse::<f64>()
                            .map_or_else(|_| Cell::Name(c.to_owned()), Cell::Number),
                    ),
                })
                .collect()
        })
        .collect();
    (names, rows)
}

/// Arrow and CSV carry the same rows bit for bit: numbers, regimes, nulls and
/// error titles, over several record batches with names first met late in the
/// stream (dictionary deltas).
#[tokio::test]
async fn arrow_rows_equal_csv_rows_bit_for_bit() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut sweep = mixed_sweep(100);
    let (status, headers, arrow) = app
        .post_accept("/v1/sweeps", "application/vnd.apache.arrow.stream", &sweep)
        .await;
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&arrow));
    assert_eq!(headers["content-type"], "application/vnd.apache.arrow.stream");
    let (_, _, csv) = app.post_accept("/v1/sweeps", "text/csv", &sweep).await;
    let (metadata, arrow_names, arrow_rows) = read_arrow(&arrow);
    let (csv_names, csv_rows) = read_csv(&csv);
    assert_eq!(arrow_names, csv_names);
    assert_eq!(arrow_rows.len(), 70_000);
    let differing = arrow_rows.iter().zip(&csv_rows).position(|(a, c)| {
        a.len() != c.len()
            || a.iter().zip(c).any(|(a, c)| match (a, c) {
                (Some(Cell::Number(a)), Some(Cell::Number(c))) => a.to_bits() != c.to_bits(),
                _ => a != c,
            })
    });
    assert_eq!(
        differing,
        None,
        "{:?}",
        differing.map(|i| (&arrow_rows[i], &csv_rows[i]))
    );
    assert_eq!(
        arrow_rows,
        csv_rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()
    );
    let errors = arrow_rows.iter().filter(|r| r.last().unwrap().is_some()).count();
    assert!(errors > 0 && errors < 70_000, "{errors}");
    assert_eq!(metadata["restitution.model_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(metadata["restitution.total_points"], "70000");
    assert_eq!(metadata["restitution.sweep_sha256"].len(), 64);

    // A slice: the same hash, its own range, the same rows.
    sweep["range"] = json!({"start": 60_000, "end": 70_000});
    let (_, _, part) = app
        .post_accept("/v1/sweeps", "application/vnd.apache.arrow.stream", &sweep)
        .await;
    let (part_metadata, _, part_rows) = read_arrow(&part);
    assert_eq!(
        part_metadata["restitution.sweep_sha256"],
        metadata["restitution.sweep_sha256"]
    );
    assert_eq!(
        (
            &part_metadata["restitution.range_start"][..],
            &part_metadata["restitution.range_end"][..]
        ),
        ("60000", "70000")
    );
    assert_eq!(part_rows, arrow_rows[60_000..]);
}

/// A sweep whose points include refusals (a separating contact) and several
/// regimes: 700 × `count` points.
fn mixed_sweep(count: u64) -> Value {
    json!({
        "case": "tangential",
        "base": maw_base(),
        "axes": [
            {"path": "/velocity/normal", "linspace": {"start": -3.0, "stop": 0.5, "count": 700}},
            {"path": "/velocity/tangential", "linspace": {"start": -1.0, "stop": 5.0, "count": count}}
        ]
    })
}

/// The reduction equals the one computed here from the full rows: counts,
/// refusals, extremes at their first points, the exact sum (its parts sum
/// exactly to the rows' exact sum; the sum is that sum correctly rounded),
/// the mean, histograms and name counts; ranges' partial reductions merge to
/// the whole exactly.
#[tokio::test]
async fn a_reduction_equals_the_reduction_of_the_full_rows() {
    use crate::common::reference::{Q, q, to_f64};
    let app = spawn_app(ServiceConfig::default()).await;
    let sweep = mixed_sweep(20);
    let table = json_table(&app, &sweep).await;
    let columns: Vec<String> = serde_json::from_value(table["columns"].clone()).unwrap();
    let rows = table["rows"].as_array().unwrap();
    let mut reduced = sweep.clone();
    reduced["reduce"] = json!({"histograms": [
        {"output": "/energy/loss", "start": 0.0, "stop": 3.0, "bins": 7},
        {"output": "/final_velocity/tangential", "start": -1.0, "stop": 1.0, "bins": 3}
    ]});
    let (status, headers, r) = app.post("/v1/sweeps", &reduced).await;
    assert_eq!(status, StatusCode::OK, "{r}");
    assert_eq!(headers["content-type"], "application/json");
    assert_eq!(
        (&r["points"], &r["total_points"]),
        (&json!(14_000), &json!(14_000))
    );

    let errors: Vec<&Value> = rows
        .iter()
        .map(|row| row.as_array().unwrap().last().unwrap())
        .collect();
    let refused = errors.iter().filter(|e| !e.is_null()).count() as u64;
    assert!(refused > 0);
    assert_eq!(r["answered"], 14_000 - refused);
    assert_eq!(r["refused"]["not-approaching"]["count"], refused);
    assert_eq!(
        &r["refused"]["not-approaching"]["title"],
        *errors.iter().find(|e| !e.is_null()).unwrap()
    );

    let axes = &columns[..2];
    let mut checked = 0;
    for (c, name) in columns.iter().enumerate().skip(2) {
        if name == "error" {
            continue;
        }
        let summary = &r["outputs"][name];
        let cells: Vec<(usize, &Value)> = rows
            .iter()
            .enumerate()
            .map(|(i, row)| (i, &row[c]))
            .filter(|(_, v)| !v.is_null())
            .collect();
        if name == "/regime" {
            let mut counts = std::collections::BTreeMap::new();
            for (_, v) in &cells {
                *counts.entry(v.as_str().unwrap().to_owned()).or_insert(0u64) += 1;
            }
            assert!(counts.len() >= 2, "{counts:?}");
            assert_eq!(summary["values"], json!(counts));
            assert_eq!(summary["count"], cells.len());
            continue;
        }
        let values: Vec<(usize, f64)> = cells.iter().map(|(i, v)| (*i, v.as_f64().unwrap())).collect();
        assert_eq!(summary["count"], values.len(), "{name}");
        let first = |better: fn(f64, f64) -> bool| {
            values
                .iter()
                .fold(None, |best: Option<(usize, f64)>, &(i, x)| match best {
                    Some((_, b)) if !better(x, b) => best,
                    _ => Some((i, x)),
                })
                .unwrap()
        };
        for (key, (i, x)) in [("min", first(|x, b| x < b)), ("max", first(|x, b| x > b))] {
            assert_eq!(
                summary[key]["value"].as_f64().unwrap().to_bits(),
                x.to_bits(),
                "{name} {key}"
            );
            assert_eq!(summary[key]["index"], i, "{name} {key}");
            for (a, axis) in axes.iter().enumerate() {
                assert_eq!(summary[key]["inputs"][axis], rows[i][a], "{name} {key}");
            }
        }
        let exact: Q = values.iter().map(|&(_, x)| q(x)).sum();
        let parts: Q = summary["sum_parts"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| q(p.as_f64().unwrap()))
            .sum();
        assert_eq!(parts, exact, "{name}: the parts sum exactly to the rows' sum");
        let sum = to_f64(&exact);
        assert_eq!(
            summary["sum"].as_f64().unwrap().to_bits(),
            sum.to_bits(),
            "{name}"
        );
        assert_eq!(
            summary["mean"].as_f64().unwrap().to_bits(),
            (sum / values.len() as f64).to_bits()
        );
        if let Some(h) = summary["histogram"].as_object() {
            let (start, stop) = (h["start"].as_f64().unwrap(), h["stop"].as_f64().unwrap());
            let bins = h["counts"].as_array().unwrap().len();
            let mut counts = vec![0u64; bins];
            let (mut below, mut above) = (0u64, 0u64);
            for &(_, x) in &values {
                if x < start {
                    below += 1;
                } else if x > stop {
                    above += 1;
                } else {
                    let at = ((x - start) / (stop - start) * bins as f64).floor() as usize;
                    counts[at.min(bins - 1)] += 1;
                }
            }
            assert_eq!(
                (h["below"].as_u64().unwrap(), h["above"].as_u64().unwrap()),
                (below, above)
            );
            assert_eq!(h["counts"], json!(counts), "{name}");
            checked += 1;
        }
    }
    assert_eq!(checked, 2, "both histograms were checked");

    // Ranges: partial reductions merge exactly into the whole's.
    let mut parts = Vec::new();
    for (start, end) in [(0, 5_000), (5_000, 12_001), (12_001, 14_000)] {
        let mut slice = reduced.clone();
        slice["range"] = json!({"start": start, "end": end});
        let (status, _, part) = app.post("/v1/sweeps", &slice).await;
        assert_eq!(status, StatusCode::OK, "{part}");
        assert_eq!(part["sweep_sha256"], r["sweep_sha256"]);
        parts.push(part);
    }
    let loss = |p: &Value| p["outputs"]["/energy/loss"].clone();
    let count: u64 = parts.iter().map(|p| loss(p)["count"].as_u64().unwrap()).sum();
    assert_eq!(count, loss(&r)["count"].as_u64().unwrap());
    let merged: Q = parts
        .iter()
        .flat_map(|p| loss(p)["sum_parts"].as_array().unwrap().clone())
        .map(|x| q(x.as_f64().unwrap()))
        .sum();
    let whole: Q = loss(&r)["sum_parts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| q(x.as_f64().unwrap()))
        .sum();
    assert_eq!(merged, whole);
    let min = parts
        .iter()
        .map(|p| loss(p)["min"].clone())
        .filter(|m| !m.is_null())
        .min_by(|a, b| {
            a["value"]
                .as_f64()
                .unwrap()
                .total_cmp(&b["value"].as_f64().unwrap())
        })
        .unwrap();
    assert_eq!(min, loss(&r)["min"]);
}

/// Reduction requests are checked whole; a reduction is JSON only.
#[tokio::test]
async fn bad_reductions_are_refused_naming_the_member() {
    let app = spawn_app(ServiceConfig::default()).await;
    for (histogram, pointer) in [
        (
            json!({"output": "/nope", "start": 0, "stop": 1, "bins": 3}),
            "/reduce/histograms/0/output",
        ),
        (
            json!({"output": "/regime", "start": 0, "stop": 1, "bins": 3}),
            "/reduce/histograms/0/output",
        ),
        (
            json!({"output": "/energy/loss", "start": 1, "stop": 1, "bins": 3}),
            "/reduce/histograms/0",
        ),
        (
            json!({"output": "/energy/loss", "start": 0, "stop": 1, "bins": 0}),
            "/reduce/histograms/0/bins",
        ),
        (
            json!({"output": "/energy/loss", "start": 0, "stop": 1, "bins": 10_001}),
            "/reduce/histograms/0/bins",
        ),
    ] {
        let mut sweep = mixed_sweep(100);
        sweep["reduce"] = json!({"histograms": [histogram]});
        let (status, _, problem) = app.post("/v1/sweeps", &sweep).await;
        assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{problem}");
        assert_eq!(problem["pointer"], pointer, "{problem}");
    }
    let mut sweep = mixed_sweep(100);
    sweep["reduce"] = json!({});
    let (status, _, _) = app.post_accept("/v1/sweeps", "text/csv", &sweep).await;
    assert_eq!(status, StatusCode::NOT_ACCEPTABLE);
}

/// A client that goes away mid-reduction stops the work.
#[tokio::test]
async fn a_client_that_disconnects_stops_the_reduction() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 10_000_000}}],
        "reduce": {}
    });
    let client = reqwest::Client::builder()
        .timeout(Duration::from_millis(300))
        .build()
        .unwrap();
    let sent = tokio::spawn(client.post(format!("{}/v1/sweeps", app.base)).json(&body).send());
    let started = Instant::now();
    while app.streams.active() == 0 && started.elapsed() < Duration::from_secs(5) {
        tokio::task::yield_now().await;
    }
    assert!(app.streams.active() > 0, "the reduction started");
    assert!(sent.await.unwrap().is_err(), "the client gave up first");
    let deadline = Instant::now() + Duration::from_secs(10);
    while app.streams.active() > 0 {
        assert!(
            Instant::now() < deadline,
            "the reduction went on after the client left"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let table = json_table(&app, &two_axis_sweep()).await;
    assert_eq!(table["points"], 183);
}

/// A reduction that outlasts the request deadline is answered 408 and stops.
#[tokio::test]
async fn a_reduction_past_the_request_deadline_is_408_and_stops() {
    let app = spawn_app(ServiceConfig {
        request_timeout_ms: 200,
        ..ServiceConfig::default()
    })
    .await;
    let body = json!({
        "case": "tangential", "base": maw_base(),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": 0.0, "stop": 5.0, "count": 10_000_000}}],
        "reduce": {}
    });
    let (status, _, problem) = app.post("/v1/sweeps", &body).await;
    assert_eq!(status, StatusCode::REQUEST_TIMEOUT, "{problem}");
    let deadline = Instant::now() + Duration::from_secs(10);
    while app.streams.active() > 0 {
        assert!(
            Instant::now() < deadline,
            "the reduction went on after the deadline"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

/// Every case's sweep, in both precisions, gives the CSV bytes committed in
/// `tests/data/golden/` (requests `*.json`, answers `*.fast.csv` and
/// `*.exact.csv`): the answers a refactor must leave unchanged, inputs at
/// 10^±250 that go to the exact stages included. `RESTITUTION_BLESS=1`
/// writes the files anew (a deliberate change of answers, reviewed in the diff).
#[tokio::test]
async fn every_case_sweeps_to_the_committed_csv_bytes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/golden");
    let bless = std::env::var_os("RESTITUTION_BLESS").is_some();
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    names.sort();
    assert!(names.len() >= 10, "{names:?}");
    let scratch = std::env::temp_dir().join(format!("restitution-golden-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let mut compared = 0;
    for request in &names {
        let stem = request.file_stem().unwrap().to_str().unwrap();
        for precision in ["fast", "exact"] {
            let mut sweep: Value = serde_json::from_slice(&std::fs::read(request).unwrap()).unwrap();
            sweep["precision"] = json!(precision);
            let path = scratch.join(format!("{stem}.{precision}.json"));
            std::fs::write(&path, sweep.to_string()).unwrap();
            let mut csv = Vec::new();
            restitution::http::offline::sweep(&path, None, "text/csv", &mut csv)
                .await
                .unwrap_or_else(|e| panic!("{stem} {precision}: {e}"));
            let answer = dir.join(format!("{stem}.{precision}.csv"));
            if bless {
                std::fs::write(&answer, &csv).unwrap();
            }
            let committed = std::fs::read(&answer)
                .unwrap_or_else(|e| panic!("{}: {e} (RESTITUTION_BLESS=1 writes it)", answer.display()));
            assert!(
                csv == committed,
                "{stem} {precision}: the CSV differs from {}",
                answer.display()
            );
            assert!(csv.len() > 200, "{stem} {precision}: {} bytes", csv.len());
            compared += 1;
        }
    }
    std::fs::remove_dir_all(&scratch).ok();
    assert_eq!(compared, 2 * names.len());
}

/// Buffered and streamed sweeps each have a limit of sweeps computed at once
/// (the memory they hold): past it, 503 with Retry-After, and the other kind
/// is still served.
#[tokio::test]
async fn sweeps_past_their_kinds_limit_are_refused_with_retry_after() {
    let body = two_axis_sweep();
    for (buffered, streamed) in [(0, 64), (4, 0)] {
        let app = spawn_app(ServiceConfig {
            max_buffered_sweeps: buffered,
            max_streamed_sweeps: streamed,
            ..ServiceConfig::default()
        })
        .await;
        for accept in [
            "application/json",
            "image/svg+xml",
            "text/csv",
            "application/x-ndjson",
        ] {
            let (status, headers, bytes) = app.post_accept("/v1/sweeps", accept, &body).await;
            let refused = if accept.starts_with("application/json") || accept.starts_with("image/") {
                buffered == 0
            } else {
                streamed == 0
            };
            if refused {
                assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{accept}");
                assert_eq!(headers["retry-after"], "1", "{accept}");
                let problem: Value = serde_json::from_slice(&bytes).expect("a problem");
                assert_eq!(
                    problem["type"], "urn:restitution:problem:sweeps-busy",
                    "{problem}"
                );
                assert!(
                    problem["detail"].as_str().unwrap().contains("retry shortly"),
                    "{problem}"
                );
            } else {
                assert_eq!(
                    status,
                    StatusCode::OK,
                    "{accept}: {}",
                    String::from_utf8_lossy(&bytes)
                );
            }
        }
    }
}
