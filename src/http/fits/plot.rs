//! The tangential and torsional fits as SVG plots ([`crate::plot`]): the
//! measured points and the fitted model's curve in the paper's normalised
//! axes, velocities over the approach speed. The model is homogeneous in the
//! velocities, so one curve, solved for the first observation's body at unit
//! approach speed, stands for every point. Without every coefficient the
//! plot holds the points only and its subtitle says why.

use axum::http::{HeaderMap, StatusCode};

use crate::fit::{Observation, TangentialFit, TorsionalFit, TorsionalObservation};
use crate::http::accept::choose;
use utoipa::IntoResponses;

use crate::http::problem::{ApiError, Problem};
use crate::impact::{BarrierImpact, Law, Precision, TorsionalImpact, solve};
use crate::outcome::Outputs;
use crate::plot::{Curve, Figure, LegendEntry, Line, Marker, Markers, PALETTE, Shape};
use crate::scene::PlanarVelocity;

/// Points of the fitted curve.
const CURVE_POINTS: usize = 201;

/// A response format of the tangential and torsional fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitFormat {
    /// `application/json`: the coefficients.
    Json,
    /// `image/svg+xml`: the points and the fitted curve.
    Svg,
}

/// Picks the format from `Accept`, as the sweeps do: JSON unless SVG ranks higher.
pub fn negotiate(headers: &HeaderMap) -> Result<FitFormat, ApiError> {
    const OFFERED: &[(&str, FitFormat)] = &[
        ("application/json", FitFormat::Json),
        ("application/*", FitFormat::Json),
        ("*/*", FitFormat::Json),
        ("image/svg+xml", FitFormat::Svg),
        ("image/*", FitFormat::Svg),
    ];
    choose(headers, OFFERED, FitFormat::Json).ok_or_else(|| {
        ApiError::new(
            StatusCode::NOT_ACCEPTABLE,
            "not-acceptable",
            "Not acceptable",
            "this fit is available as application/json or image/svg+xml",
        )
    })
}

/// The response of a fit to an `Accept` that admits neither of its formats
/// (for the document).
#[derive(IntoResponses)]
#[allow(dead_code)]
pub enum FitNotAcceptable {
    /// `Accept` admits neither JSON nor SVG.
    #[response(
        status = 406,
        description = "Neither application/json nor image/svg+xml is acceptable",
        content_type = "application/problem+json"
    )]
    Problem(Problem),
}

/// V_ct/|v_cn| after against v_ct/|v_cn| before.
pub fn tangential(observations: &[Observation], fit: &TangentialFit) -> String {
    let points: Vec<(f64, f64)> = observations
        .iter()
        .map(|o| {
            let c = o.contact;
            let vcn = c.tangential_offset.mul_add(o.initial.angular, o.initial.normal);
            let vct = (-c.normal_offset).mul_add(o.initial.angular, o.initial.tangential);
            let final_vct = (-c.normal_offset).mul_add(o.r#final.angular, o.r#final.tangential);
            (vct / vcn.abs(), final_vct / vcn.abs())
        })
        .collect();
    let curve = match (fit.friction, fit.tangential_restitution, observations.first()) {
        (Some(f), Some(et), Some(o0)) => {
            let law = Law::TangentialRestitution {
                restitution: fit.restitution.value.clamp(0.0, 1.0),
                friction: f.value.max(0.0),
                tangential_restitution: et.value.clamp(-1.0, 1.0),
            };
            Some(model_curve(&points, |vt| {
                let velocity = PlanarVelocity {
                    normal: -1.0,
                    tangential: vt,
                    angular: 0.0,
                };
                let impact =
                    BarrierImpact::rigid(o0.body.mass(), o0.body.inertia(), o0.contact, velocity, law);
                solve(&impact, Outputs::MINIMAL, Precision::Fast)
                    .ok()
                    .map(|o| o.contact_velocity.r#final.tangential)
            }))
        }
        _ => None,
    };
    figure(
        "Tangential",
        "Contact velocities over the approach speed",
        "v_ct/|v_cn| before the impact",
        "V_ct/|v_cn| after the impact",
        points,
        curve,
    )
}

/// Ω_n/|v_n| after against ω_n/|v_n| before.
pub fn torsional(observations: &[TorsionalObservation], fit: &TorsionalFit) -> String {
    let points: Vec<(f64, f64)> = observations
        .iter()
        .map(|o| {
            let speed = o.normal_velocity.abs();
            (o.spin / speed, o.final_spin / speed)
        })
        .collect();
    let curve = match (fit.torsional_friction, observations.first()) {
        (Some(mu), Some(o0)) => Some(model_curve(&points, |spin| {
            let impact = TorsionalImpact {
                mass: o0.mass,
                normal_inertia: o0.normal_inertia,
                normal_velocity: -1.0,
                spin,
                restitution: fit.restitution.value.clamp(0.0, 1.0),
                torsional_restitution: fit.torsional_restitution.value.clamp(0.0, 1.0),
                torsional_friction: mu.value.max(0.0),
                pitch_radius: o0.pitch_radius,
            };
            solve(&impact, Outputs::MINIMAL, Precision::Fast)
                .ok()
                .map(|o| o.final_spin)
        })),
        _ => None,
    };
    figure(
        "Torsional",
        "Spins over the approach speed",
        "ω_n/|v_n| before the impact (rad/m)",
        "Ω_n/|v_n| after the impact (rad/m)",
        points,
        curve,
    )
}

/// The model over the measured abscissae's range, split where it has no answer.
fn model_curve(points: &[(f64, f64)], model: impl Fn(f64) -> Option<f64>) -> Vec<Vec<(f64, f64)>> {
    let xs = points.iter().map(|p| p.0).filter(|x| x.is_finite());
    let lo = xs.clone().fold(f64::INFINITY, f64::min);
    let hi = xs.fold(f64::NEG_INFINITY, f64::max);
    let mut segments = vec![Vec::new()];
    if !(lo.is_finite() && hi.is_finite()) {
        return segments;
    }
    for i in 0..CURVE_POINTS {
        let x = lo + (hi - lo) * i as f64 / (CURVE_POINTS - 1) as f64;
        match model(x).filter(|y| y.is_finite()) {
            Some(y) => segments.last_mut().expect("a segment").push((x, y)),
            None if segments.last().is_some_and(|s| !s.is_empty()) => segments.push(Vec::new()),
            None => {}
        }
    }
    segments.retain(|s| !s.is_empty());
    segments
}

/// The figure of the `kind` fit, its axes `scaled` as said.
fn figure(
    kind: &str,
    scaled: &str,
    x_name: &str,
    y_name: &str,
    points: Vec<(f64, f64)>,
    curve: Option<Vec<Vec<(f64, f64)>>>,
) -> String {
    let marker = Marker::hollow(Shape::Circle, PALETTE[0]);
    let line = Line::solid(PALETTE[1]);
    let mut legend = vec![LegendEntry::Marker(marker, "measured".to_owned())];
    let mut curves = Vec::new();
    let mut title = format!("{kind} fit: measured points");
    let subtitle = match curve {
        None => format!("{scaled}. Not every coefficient was identified: the measured points only"),
        Some(segments) if segments.is_empty() => {
            format!("{scaled}. The fitted model has no answer over the measured range: the points only")
        }
        Some(segments) => {
            legend.push(LegendEntry::Line(line, "fitted model".to_owned()));
            curves.push(Curve {
                label: "fitted model".to_owned(),
                segments,
                line: Some(line),
            });
            title.push_str(" and the fitted model");
            format!("{scaled}; the curve for the first observation's body")
        }
    };
    Figure {
        title,
        subtitle,
        x_name: x_name.to_owned(),
        y_name: y_name.to_owned(),
        curves,
        markers: vec![Markers {
            label: "measured".to_owned(),
            points,
            marker: Some(marker),
        }],
        legend: Some(legend),
        ..Figure::default()
    }
    .render()
}
