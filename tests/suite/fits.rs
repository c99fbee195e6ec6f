//! `POST /v1/fits/tangential` over loopback: coefficients recovered from
//! observations the solver generates, in any order; refusals name the member;
//! the tangential and torsional fits' plots (`image/svg+xml`).

use crate::common::plain::tangential;
use crate::common::server::spawn_app;
use reqwest::StatusCode;
use restitution::http::ServiceConfig;
use restitution::{BarrierScene, Body, Contact, Outputs, PlanarVelocity};
use serde_json::{Value, json};

/// Maw's disc over a range of v_t, with a small deterministic perturbation.
fn observations() -> Vec<Value> {
    maw((0..30).map(|i| 0.05 + 0.1 * f64::from(i)))
}

/// Maw's disc at each v_t, perturbed by the point's index.
fn maw(vts: impl Iterator<Item = f64>) -> Vec<Value> {
    let (e, f, et) = (0.93, 0.123, 0.34);
    vts.enumerate()
        .map(|(i, vt)| {
            let i = i as u32;
            let scene = BarrierScene::new(
                Body::new(1.0, 0.00125).unwrap(),
                Contact::central(0.05),
                PlanarVelocity {
                    normal: -1.0,
                    tangential: vt,
                    angular: 0.0,
                },
            )
            .unwrap();
            let o = tangential::solve(&scene, e, f, et, Outputs::MINIMAL).unwrap();
            let wiggle = 1e-3 * ((f64::from(i) * 2.399).sin());
            json!({
                "body": {"mass": 1.0, "inertia": 0.00125},
                "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                "initial": {"normal": -1.0, "tangential": vt},
                "final": {"normal": o.final_velocity.normal + wiggle,
                          "tangential": o.final_velocity.tangential - wiggle,
                          "angular": o.final_velocity.angular}
            })
        })
        .collect()
}

#[tokio::test]
async fn coefficients_are_recovered_within_their_standard_errors_in_any_order() {
    let app = spawn_app(ServiceConfig::default()).await;
    let mut data = observations();
    let (status, _, fit) = app
        .post("/v1/fits/tangential", &json!({"observations": data}))
        .await;
    assert_eq!(status, StatusCode::OK, "{fit}");
    for (name, truth) in [
        ("restitution", 0.93),
        ("friction", 0.123),
        ("tangential_restitution", 0.34),
    ] {
        let value = fit[name]["value"].as_f64().unwrap();
        let se = fit[name]["standard_error"].as_f64().unwrap();
        assert!(
            (value - truth).abs() <= 3.0 * se + 1e-12,
            "{name}: {value} ± {se}"
        );
    }
    let regimes = fit["regimes"].as_array().unwrap();
    assert_eq!(regimes.len(), 30);
    assert_eq!(regimes[0], "restitution");
    assert_eq!(regimes[29], "sliding");
    assert!(fit["r_squared"].as_f64().unwrap() > 0.999);
    data.reverse();
    let (_, _, reversed) = app
        .post("/v1/fits/tangential", &json!({"observations": data}))
        .await;
    let close = |a: &Value, b: &Value| (a.as_f64().unwrap() - b.as_f64().unwrap()).abs() < 1e-12;
    assert!(close(&reversed["friction"]["value"], &fit["friction"]["value"]));
    assert!(close(
        &reversed["tangential_restitution"]["value"],
        &fit["tangential_restitution"]["value"]
    ));
}

#[tokio::test]
async fn too_few_or_invalid_observations_are_422_naming_the_member() {
    let app = spawn_app(ServiceConfig::default()).await;
    let data = observations();
    let (status, _, problem) = app
        .post("/v1/fits/tangential", &json!({"observations": data[..2]}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/observations");
    let mut bad = data[..5].to_vec();
    bad[3]["initial"]["normal"] = json!(1.0);
    let (status, _, problem) = app
        .post("/v1/fits/tangential", &json!({"observations": bad}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/observations/3");
    let mut bad = data[..5].to_vec();
    bad[1]["body"]["mass"] = json!(-1.0);
    let (status, _, problem) = app
        .post("/v1/fits/tangential", &json!({"observations": bad}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/observations/1/body");
}

#[tokio::test]
async fn torsional_coefficients_are_recovered_over_http() {
    let app = spawn_app(ServiceConfig::default()).await;
    let observations = torsional_observations();
    let (status, _, fit) = app
        .post("/v1/fits/torsional", &json!({"observations": observations}))
        .await;
    assert_eq!(status, StatusCode::OK, "{fit}");
    for (name, truth) in [("torsional_restitution", 0.2), ("torsional_friction", 0.3)] {
        let value = fit[name]["value"].as_f64().unwrap();
        let se = fit[name]["standard_error"].as_f64().unwrap();
        assert!((value - truth).abs() <= 3.0 * se, "{name}: {value} ± {se}");
    }
    assert_eq!(fit["regimes"][0], "sliding");
    assert_eq!(fit["regimes"][9], "restitution");
    let (status, _, problem) = app
        .post("/v1/fits/torsional", &json!({"observations": observations[..2]}))
        .await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/observations");
}

/// `POST /v1/fits/planar`: the coefficients of a crash the service solved come
/// back from its velocity changes; a normal is fitted when asked; a plastic
/// sticking crash cannot fix a normal, and the problem says so.
#[tokio::test]
async fn a_planar_reconstruction_recovers_e_mu_and_the_normal() {
    let app = spawn_app(ServiceConfig::default()).await;
    let example = crate::common::examples::cars();
    let cars = example["bodies"].clone();
    let contact = example["contact"].clone();
    let measured = |outcome: &Value| -> Value {
        let m = |v: &Value| json!({"value": v.as_f64().unwrap(), "uncertainty": 0.1});
        Value::Array(
            outcome["bodies"]
                .as_array()
                .unwrap()
                .iter()
                .map(|b| {
                    json!({"velocity_change": {"x": m(&b["velocity_change"]["x"]), "y": m(&b["velocity_change"]["y"])},
                           "angular_velocity_change": m(&b["angular_velocity_change"])})
                })
                .collect(),
        )
    };
    for (law, fit_normal) in [
        (json!({"restitution": 0.3, "impulse_ratio": -0.2}), false),
        (json!({"restitution": 0.3, "friction": 0.9}), true),
    ] {
        let mut request = json!({"bodies": cars, "contact": contact});
        request
            .as_object_mut()
            .unwrap()
            .extend(law.as_object().unwrap().clone());
        let (status, _, outcome) = app.post("/v1/impacts/planar", &request).await;
        assert_eq!(status, StatusCode::OK, "{outcome}");
        let fit_request = json!({"bodies": cars, "contact": contact, "measured": measured(&outcome), "fit_normal": fit_normal});
        let (status, _, fit) = app.post("/v1/fits/planar", &fit_request).await;
        assert_eq!(status, StatusCode::OK, "{fit}");
        let close = |a: &Value, b: f64| (a.as_f64().unwrap() - b).abs() < 1e-9;
        assert!(close(&fit["restitution"]["value"], 0.3), "{fit}");
        assert!(
            close(
                &fit["impulse_ratio"]["value"],
                outcome["impulse_ratio"].as_f64().unwrap()
            ),
            "{fit}"
        );
        assert!(fit["chi_squared"].as_f64().unwrap() < 1e-12, "{fit}");
        if fit_normal {
            assert!(close(&fit["normal"]["direction"]["x"], -1.0), "{fit}");
        } else {
            assert!(fit["normal"].is_null());
        }
    }
    let mut plastic = json!({"bodies": cars, "contact": contact, "restitution": 0.0, "friction": 0.9});
    let (_, _, outcome) = app.post("/v1/impacts/planar", &plastic).await;
    plastic = json!({"bodies": cars, "contact": contact, "measured": measured(&outcome), "fit_normal": true});
    let (status, _, problem) = app.post("/v1/fits/planar", &plastic).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/fit_normal", "{problem}");
    assert!(
        problem["detail"].as_str().unwrap().contains("normal"),
        "{problem}"
    );
    let mut one = json!({"bodies": cars, "contact": contact, "measured": measured(&outcome)});
    one["measured"].as_array_mut().unwrap().pop();
    let (status, _, problem) = app.post("/v1/fits/planar", &one).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY);
    assert_eq!(problem["pointer"], "/measured", "{problem}");
}

/// The torsional observations of Figure 4's ball, in both branches.
fn torsional_observations() -> Vec<Value> {
    (0..20)
        .map(|i| {
            let spin = -50.0 + 5.5 * f64::from(i);
            let impact = restitution::TorsionalImpact {
                mass: 0.1,
                normal_inertia: 3.6e-5,
                normal_velocity: -3.0,
                spin,
                restitution: 0.8,
                torsional_restitution: 0.2,
                torsional_friction: 0.3,
                pitch_radius: 0.005,
            };
            let o = crate::common::plain::torsional::solve(&impact, false).unwrap();
            json!({
                "body": {"mass": 0.1, "normal_inertia": 3.6e-5}, "pitch_radius": 0.005,
                "initial": {"normal": -3.0, "spin": spin},
                "final": {"normal": o.final_normal_velocity, "spin": o.final_spin + 0.1 * (f64::from(i)).cos()}
            })
        })
        .collect()
}

/// A fit's plot, parsed: it must be well-formed XML.
async fn fit_svg(endpoint: &str, observations: &[Value]) -> String {
    let app = spawn_app(ServiceConfig::default()).await;
    let (status, headers, bytes) = app
        .post_accept(endpoint, "image/svg+xml", &json!({"observations": observations}))
        .await;
    let svg = String::from_utf8(bytes).unwrap();
    assert_eq!(status, StatusCode::OK, "{svg}");
    assert_eq!(headers["content-type"], "image/svg+xml");
    let doc = roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{e}: {svg}"));
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    svg
}

/// The elements named `tag` under the `data-part` group `part`.
fn drawn(svg: &str, part: &str, tag: &str) -> usize {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.attribute("data-part") == Some(part))
        .flat_map(|g| g.descendants().filter(|n| n.tag_name().name() == tag))
        .count()
}

/// `Accept: image/svg+xml`: the service's own plot, one marker per
/// observation, the fitted model's curve, both in the legend.
#[tokio::test]
async fn fit_svg_marks_every_observation_and_draws_the_fitted_curve() {
    for (endpoint, observations, axes) in [
        (
            "/v1/fits/tangential",
            observations(),
            "Vertical axis: V_ct/|v_cn| after the impact; horizontal axis: v_ct/|v_cn| before the impact.",
        ),
        (
            "/v1/fits/torsional",
            torsional_observations(),
            "Vertical axis: Ω_n/|v_n| after the impact (rad/m); horizontal axis: ω_n/|v_n| before the impact (rad/m).",
        ),
    ] {
        let svg = fit_svg(endpoint, &observations).await;
        assert_eq!(drawn(&svg, "markers", "circle"), observations.len(), "{endpoint}");
        assert_eq!(drawn(&svg, "curves", "path"), 1, "{endpoint}: {svg}");
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let curve = doc
            .descendants()
            .find(|n| n.attribute("data-part") == Some("curves"))
            .and_then(|g| g.descendants().find(|n| n.tag_name().name() == "path"))
            .and_then(|p| p.attribute("d"))
            .unwrap();
        assert!(curve.matches('L').count() >= 100, "{endpoint}: {curve}");
        assert!(
            svg.contains(">measured<") && svg.contains(">fitted model<"),
            "{svg}"
        );
        assert!(svg.contains(axes), "{svg}");
        assert!(!svg.contains("style"), "presentation attributes only");
    }
}

/// A fit without every coefficient (every point slides, so e_t is not
/// identified) plots the points only, and says so.
#[tokio::test]
async fn fit_svg_without_every_coefficient_draws_the_points_only() {
    let sliding = maw([2.0, 2.5, 3.0].into_iter());
    let app = spawn_app(ServiceConfig::default()).await;
    let (status, _, fit) = app
        .post("/v1/fits/tangential", &json!({"observations": sliding}))
        .await;
    assert_eq!(status, StatusCode::OK, "{fit}");
    assert!(fit["tangential_restitution"].is_null(), "{fit}");
    let svg = fit_svg("/v1/fits/tangential", &sliding).await;
    assert_eq!(drawn(&svg, "markers", "circle"), 3);
    assert_eq!(drawn(&svg, "curves", "path"), 0, "{svg}");
    assert!(
        svg.contains(">measured<") && !svg.contains(">fitted model<"),
        "{svg}"
    );
    let title = &svg[svg.find("<title>").unwrap()..svg.find("</title>").unwrap()];
    assert!(title.contains("Not every coefficient was identified"), "{title}");
}

/// JSON unless SVG ranks higher; a type neither can be is 406.
#[tokio::test]
async fn fit_accept_picks_json_or_svg_and_refuses_other_types_with_406() {
    let app = spawn_app(ServiceConfig::default()).await;
    let body = json!({"observations": observations()});
    for (accept, expected) in [
        ("*/*", "application/json"),
        ("application/json, image/svg+xml", "application/json"),
        ("application/json;q=0.5, image/svg+xml", "image/svg+xml"),
        ("image/*", "image/svg+xml"),
    ] {
        for endpoint in ["/v1/fits/tangential", "/v1/fits/torsional"] {
            let body = if endpoint.ends_with("torsional") {
                json!({"observations": torsional_observations()})
            } else {
                body.clone()
            };
            let (status, headers, _) = app.post_accept(endpoint, accept, &body).await;
            assert_eq!(status, StatusCode::OK, "{endpoint} {accept}");
            assert!(
                headers["content-type"].to_str().unwrap().starts_with(expected),
                "{endpoint} {accept}: {:?}",
                headers["content-type"]
            );
        }
    }
    for accept in [
        "text/csv",
        "application/x-ndjson",
        "image/png",
        "image/svg+xml;q=0",
    ] {
        let (status, headers, bytes) = app.post_accept("/v1/fits/tangential", accept, &body).await;
        assert_eq!(status, StatusCode::NOT_ACCEPTABLE, "{accept}");
        assert_eq!(headers["content-type"], "application/problem+json");
        let problem: Value = serde_json::from_slice(&bytes).unwrap();
        assert!(
            problem["detail"].as_str().unwrap().contains("image/svg+xml"),
            "{problem}"
        );
    }
}
