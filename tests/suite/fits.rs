//! `POST /v1/fits/tangential` over loopback: coefficients recovered from
//! observations the solver generates, in any order; refusals name the member.

use crate::common::plain::tangential;
use crate::common::server::spawn_app;
use reqwest::StatusCode;
use restitution::http::ServiceConfig;
use restitution::{Body, Contact, Outputs, PlanarScene, PlanarVelocity};
use serde_json::{Value, json};

/// Maw's disc over a range of v_t, with a small deterministic perturbation.
fn observations() -> Vec<Value> {
    let (e, f, et) = (0.93, 0.123, 0.34);
    (0..30)
        .map(|i| {
            let vt = 0.05 + 0.1 * f64::from(i);
            let scene = PlanarScene::new(
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
    let observations: Vec<Value> = (0..20)
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
        .collect();
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
