//! `POST /v1/fits/planar`: one planar contact reconstructed from the measured
//! velocity changes of its bodies (see [`crate::fit::planar`]).

use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{EstimateDto, MeasuredDto};
use crate::fit::{self, FitError, MeasuredChange};
use crate::http::impacts::bodies::{LaminaDto, PlanarContactDto, VectorDto};
use crate::http::problem::ApiError;
use crate::impact::{Lamina, PlanarContact};

/// A measured vector.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredVectorDto {
    /// x component.
    pub x: MeasuredDto,
    /// y component.
    pub y: MeasuredDto,
}

/// One body's measured change of motion.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredChangeDto {
    /// ΔV = V − v of the mass centre.
    pub velocity_change: MeasuredVectorDto,
    /// ΔΩ = Ω − ω.
    pub angular_velocity_change: MeasuredDto,
}

/// A reconstruction: the scene before the impact and each body's measured
/// velocity changes; `e` and `μ` (and the normal's direction, with
/// `fit_normal`) are identified.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "bodies": [
        {"mass": 1500.0, "inertia": 2500.0, "position": {"x": 0.0, "y": 0.0},
         "velocity": {"x": 15.0, "y": 0.0}, "angular_velocity": 0.0},
        {"mass": 1200.0, "inertia": 1800.0, "position": {"x": 3.0, "y": -1.5},
         "velocity": {"x": 0.0, "y": 12.0}, "angular_velocity": 0.0}
    ],
    "contact": {"point": {"x": 2.2, "y": -0.6}, "normal": {"x": -1.0, "y": 0.0}},
    "measured": [
        {"velocity_change": {"x": {"value": -7.5, "uncertainty": 0.3}, "y": {"value": 3.9, "uncertainty": 0.3}},
         "angular_velocity_change": {"value": 2.5, "uncertainty": 0.2}},
        {"velocity_change": {"x": {"value": 9.3, "uncertainty": 0.3}, "y": {"value": -4.9, "uncertainty": 0.3}},
         "angular_velocity_change": {"value": -3.0, "uncertainty": 0.2}}
    ]
}))]
pub struct PlanarFitRequest {
    /// Body A, and body B unless A hit a barrier: the scene before the impact.
    pub bodies: Vec<LaminaDto>,
    /// The contact point and normal (from B into A).
    pub contact: PlanarContactDto,
    /// Each body's measured change, in the order of `bodies`.
    pub measured: Vec<MeasuredChangeDto>,
    /// Also fit the normal's direction, taking the contact to end sticking (U_t = 0).
    #[serde(default)]
    pub fit_normal: bool,
}

/// A fitted normal.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct FittedNormalDto {
    /// The unit normal from B into A.
    pub direction: VectorDto,
    /// Its angle from the x axis, radians, with its standard error.
    pub angle: EstimateDto,
}

/// The identified contact.
#[derive(Debug, Clone, Serialize, ToSchema)]
// The server's answer to the request example.
#[schema(example = json!({
    "restitution": {"value": 0.19991028395983862, "standard_error": 0.03103088460902592},
    "impulse_ratio": {"value": -0.5249778594437716, "standard_error": 0.015511744144803644},
    "normal": null,
    "impulse": {"x": -11201.409080383859, "y": 5880.491761773945},
    "impulse_standard_error": {"x": 241.35286564153012, "y": 179.08186246614608},
    "residuals": [-0.03239394641076121, -0.020327841182629758, 0.013505428931054553,
                  -0.034507566986549776, 0.00040980147828761915, -0.012847353929823058],
    "chi_squared": 0.038169933482384455,
    "degrees_of_freedom": 4
}))]
pub struct PlanarFitResponse {
    /// e = −U_n / u_n.
    pub restitution: EstimateDto,
    /// μ = P_t / P_n along t̂ = ẑ × n̂.
    pub impulse_ratio: EstimateDto,
    /// The fitted normal, when asked for.
    pub normal: Option<FittedNormalDto>,
    /// The impulse on A in world axes.
    pub impulse: VectorDto,
    /// Its standard errors.
    pub impulse_standard_error: VectorDto,
    /// Measured minus fitted, per body: ΔV_x, ΔV_y, ΔΩ.
    pub residuals: Vec<f64>,
    /// Σ (residual / uncertainty)².
    pub chi_squared: f64,
    /// Measured values minus fitted parameters.
    pub degrees_of_freedom: usize,
}

json_operation! {
    /// Identify e and μ (and, if asked, the normal) of a two-body contact from measured velocity changes.
    fits_planar: "/v1/fits/planar" in "fits", PlanarFitRequest => PlanarFitResponse ("The identified contact") by respond_planar_fit
}

/// The fit of a planar reconstruction request.
pub fn respond_planar_fit(req: PlanarFitRequest) -> Result<PlanarFitResponse, ApiError> {
    let problem = |pointer: &str, detail: String| {
        ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "unfittable",
            "Contact cannot be fitted",
            detail,
        )
        .at(pointer)
    };
    if req.bodies.is_empty() || req.bodies.len() > 2 {
        return Err(problem(
            "/bodies",
            format!("give 1 or 2 bodies, not {}", req.bodies.len()),
        ));
    }
    if req.measured.len() != req.bodies.len() {
        return Err(problem(
            "/measured",
            format!(
                "give one measured change per body: {} bodies, {} changes",
                req.bodies.len(),
                req.measured.len()
            ),
        ));
    }
    let bodies: Vec<Lamina> = req.bodies.iter().map(|&b| b.into()).collect();
    let contact = PlanarContact::from(req.contact);
    let measured: Vec<MeasuredChange> = req
        .measured
        .iter()
        .map(|m| MeasuredChange {
            velocity_change: [m.velocity_change.x.into(), m.velocity_change.y.into()],
            angular_velocity_change: m.angular_velocity_change.into(),
        })
        .collect();
    let fit = fit::planar(&bodies, contact, &measured, req.fit_normal).map_err(|e| match &e {
        FitError::NotAnImpact { why, .. } if why.contains("uncertainty") => {
            problem("/measured", e.to_string())
        }
        FitError::NotAnImpact { .. } => problem("/bodies", e.to_string()),
        // The detail names the parameter; the pointer the member that asked for it.
        FitError::Undetermined {
            parameter: "normal", ..
        } => problem("/fit_normal", e.to_string()),
        _ => problem("/measured", e.to_string()),
    })?;
    Ok(PlanarFitResponse {
        restitution: fit.restitution.into(),
        impulse_ratio: fit.impulse_ratio.into(),
        normal: fit.normal.map(|(direction, angle)| FittedNormalDto {
            direction: direction.into(),
            angle: angle.into(),
        }),
        impulse: fit.impulse.into(),
        impulse_standard_error: fit.impulse_standard_error.into(),
        residuals: fit.residuals,
        chi_squared: fit.chi_squared,
        degrees_of_freedom: fit.degrees_of_freedom,
    })
}
