//! `POST /v1/fits/spatial`: a spatial law's coefficients fitted to measured
//! impacts in space (see [`crate::fit::spatial`]).

use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{EstimateDto, MeasuredDto};
use crate::fit::{self, FitError, Measured, SpatialChange, SpatialLaw, SpatialObservation};
use crate::http::dto::{RegimeDto, TorsionalRegimeDto};
use crate::http::impacts::spatial::{SpatialBodyDto, SpatialContactDto};
use crate::http::problem::ApiError;
use crate::impact::Law;

/// The law whose coefficients are fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum SpatialLawDto {
    /// e and Coulomb friction f.
    Friction,
    /// e and a prescribed impulse ratio μ ≥ 0 against the slip.
    ImpulseRatio,
    /// e, f and the tangential restitution e_t (section 3).
    TangentialRestitution,
    /// The two-phase law: R, μ_A and μ_R (Appendix).
    KineticRestitution,
    /// The two-phase law with Coulomb friction f_A in the approach: R, f_A, μ_R.
    KineticFriction,
}

impl From<SpatialLawDto> for SpatialLaw {
    fn from(l: SpatialLawDto) -> Self {
        match l {
            SpatialLawDto::Friction => SpatialLaw::Friction,
            SpatialLawDto::ImpulseRatio => SpatialLaw::ImpulseRatio,
            SpatialLawDto::TangentialRestitution => SpatialLaw::TangentialRestitution,
            SpatialLawDto::KineticRestitution => SpatialLaw::KineticRestitution,
            SpatialLawDto::KineticFriction => SpatialLaw::KineticFriction,
        }
    }
}

/// A measured vector in world axes.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredVector3Dto {
    /// x component.
    pub x: MeasuredDto,
    /// y component.
    pub y: MeasuredDto,
    /// z component.
    pub z: MeasuredDto,
}

impl From<MeasuredVector3Dto> for [Measured; 3] {
    fn from(v: MeasuredVector3Dto) -> Self {
        [v.x.into(), v.y.into(), v.z.into()]
    }
}

/// One body's measured change of motion in space.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpatialMeasuredChangeDto {
    /// ΔV = V − v of the mass centre.
    pub velocity_change: MeasuredVector3Dto,
    /// Δω = Ω − ω, if measured.
    pub angular_velocity_change: Option<MeasuredVector3Dto>,
}

/// One measured impact: the scene before it and each body's measured change.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpatialImpactDataDto {
    /// Body A, and body B unless A hit a barrier, before the impact.
    pub bodies: Vec<SpatialBodyDto>,
    /// The contact point and the normal from B into A.
    pub contact: SpatialContactDto,
    /// Each body's measured change, in the order of `bodies`.
    pub measured: Vec<SpatialMeasuredChangeDto>,
}

/// Fit the twist law too, with this pitch radius.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TwistFitDto {
    /// ρ_p: pitch radius of the torsional friction (> 0), not fitted.
    #[schema(exclusive_minimum = 0.0, example = 0.01)]
    pub pitch_radius: f64,
}

/// Measured impacts in space and the law to fit to them. (The example: a
/// hollow ball with topspin and one without, made with e = 0.75, f = 0.15:
/// the first slides, the second sticks.)
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "law": "friction",
    "impacts": [
        {"bodies": [{"mass": 0.057, "inertia": {"sphere": {"radius": 0.033, "hollow": true}},
                     "position": {"x": 0.0, "y": 0.0, "z": 0.033},
                     "velocity": {"x": 20.0, "y": 0.0, "z": -10.0},
                     "angular_velocity": {"x": 0.0, "y": 300.0, "z": 0.0}}],
         "contact": {"point": {"x": 0.0, "y": 0.0, "z": 0.0}, "normal": {"x": 0.0, "y": 0.0, "z": 1.0}},
         "measured": [{"velocity_change": {"x": {"value": -2.625, "uncertainty": 0.1},
                                           "y": {"value": 0.0, "uncertainty": 0.1},
                                           "z": {"value": 17.5, "uncertainty": 0.1}}}]},
        {"bodies": [{"mass": 0.057, "inertia": {"sphere": {"radius": 0.033, "hollow": true}},
                     "position": {"x": 0.0, "y": 0.0, "z": 0.033},
                     "velocity": {"x": 5.0, "y": 0.0, "z": -10.0},
                     "angular_velocity": {"x": 0.0, "y": 0.0, "z": 0.0}}],
         "contact": {"point": {"x": 0.0, "y": 0.0, "z": 0.0}, "normal": {"x": 0.0, "y": 0.0, "z": 1.0}},
         "measured": [{"velocity_change": {"x": {"value": -2.0, "uncertainty": 0.1},
                                           "y": {"value": 0.0, "uncertainty": 0.1},
                                           "z": {"value": 17.5, "uncertainty": 0.1}}}]}
    ]
}))]
pub struct SpatialFitRequest {
    /// The law whose coefficients are fitted.
    pub law: SpatialLawDto,
    /// Also fit the twist law's e_z and μ_z, with this pitch radius.
    pub torsion: Option<TwistFitDto>,
    /// The measured impacts, each its own scene.
    #[schema(min_items = 1)]
    pub impacts: Vec<SpatialImpactDataDto>,
}

/// One fitted coefficient.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CoefficientDto {
    /// Its member in a spatial impact request (a JSON pointer, e.g. `/friction`).
    pub member: &'static str,
    /// The paper's symbol.
    pub symbol: &'static str,
    /// The value and its standard error.
    #[serde(flatten)]
    pub estimate: EstimateDto,
}

/// One impact under the fitted law.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SpatialImpactFitDto {
    /// The branch of the tangential law that answers it.
    pub regime: RegimeDto,
    /// The branch of the twist law (with `torsion` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub torsional_regime: Option<TorsionalRegimeDto>,
    /// Measured minus fitted, per body: ΔV x, y, z, then Δω x, y, z where measured.
    pub residuals: Vec<f64>,
}

/// The fitted law.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SpatialFitResponse {
    /// The law fitted.
    pub law: SpatialLawDto,
    /// The fitted law as the members of a spatial impact request (restitution,
    /// friction, … or kinetic_restitution; torsion), ready to be sent.
    #[schema(value_type = Object)]
    pub members: serde_json::Value,
    /// Each coefficient with its standard error, from the covariance (JᵀJ)⁻¹.
    pub coefficients: Vec<CoefficientDto>,
    /// Each impact's regime and residuals, in input order.
    pub impacts: Vec<SpatialImpactFitDto>,
    /// Σ (residual / uncertainty)².
    pub chi_squared: f64,
    /// Measured values minus fitted coefficients.
    pub degrees_of_freedom: usize,
}

fn problem(pointer: impl Into<String>, detail: impl Into<String>) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "unfittable",
        "Impacts cannot be fitted",
        detail,
    )
    .at(pointer)
}

/// The members of a spatial impact request that say `law`.
fn members(law: &Law, torsion: Option<crate::impact::Twist>) -> serde_json::Value {
    use serde_json::json;
    let mut m = match *law {
        Law::Frictionless { restitution } => json!({"restitution": restitution}),
        Law::ImpulseRatio {
            restitution,
            impulse_ratio,
        } => json!({"restitution": restitution, "impulse_ratio": impulse_ratio}),
        Law::Friction {
            restitution,
            friction,
        } => json!({"restitution": restitution, "friction": friction}),
        Law::TangentialRestitution {
            restitution,
            friction,
            tangential_restitution,
        } => json!({"restitution": restitution, "friction": friction,
                    "tangential_restitution": tangential_restitution}),
        Law::KineticRestitution {
            value,
            approach_impulse_ratio,
            rebound_impulse_ratio,
        } => json!({"kinetic_restitution": {"value": value, "approach_impulse_ratio": approach_impulse_ratio,
                                             "rebound_impulse_ratio": rebound_impulse_ratio}}),
        Law::KineticFriction {
            value,
            approach_friction,
            rebound_impulse_ratio,
        } => json!({"kinetic_restitution": {"value": value, "approach_friction": approach_friction,
                                             "rebound_impulse_ratio": rebound_impulse_ratio}}),
    };
    if let Some(t) = torsion {
        m["torsion"] = json!({"restitution": t.restitution, "friction": t.friction,
                              "pitch_radius": t.pitch_radius});
    }
    m
}

json_operation! {
    /// Fit the coefficients of a spatial law (e with f, μ or f and e_t; the
    /// two-phase law; optionally the twist law) to measured impacts in space.
    fits_spatial: "/v1/fits/spatial" in "fits", SpatialFitRequest => SpatialFitResponse ("The fitted law") by respond_spatial_fit
}

/// The fit of a spatial fit request.
pub fn respond_spatial_fit(req: SpatialFitRequest) -> Result<SpatialFitResponse, ApiError> {
    if req.impacts.is_empty() {
        return Err(problem("/impacts", "give at least one measured impact"));
    }
    if let Some(t) = req.torsion
        && !(t.pitch_radius.is_finite() && t.pitch_radius > 0.0)
    {
        return Err(problem(
            "/torsion/pitch_radius",
            "the pitch radius must be positive and finite",
        ));
    }
    let mut observations = Vec::with_capacity(req.impacts.len());
    for (i, impact) in req.impacts.iter().enumerate() {
        let at = format!("/impacts/{i}");
        let bodies = impact
            .bodies
            .iter()
            .enumerate()
            .map(|(k, b)| b.body(k).map_err(|e| e.under(&at)))
            .collect::<Result<Vec<_>, _>>()?;
        if bodies.is_empty() || bodies.len() > 2 {
            return Err(problem(
                format!("{at}/bodies"),
                format!("give 1 or 2 bodies, not {}", bodies.len()),
            ));
        }
        if impact.measured.len() != bodies.len() {
            return Err(problem(
                format!("{at}/measured"),
                format!(
                    "give one measured change per body: {} bodies, {} changes",
                    bodies.len(),
                    impact.measured.len()
                ),
            ));
        }
        observations.push(SpatialObservation {
            a: bodies[0],
            b: bodies.get(1).copied(),
            contact: impact.contact.into(),
            measured: impact
                .measured
                .iter()
                .map(|m| SpatialChange {
                    velocity_change: m.velocity_change.into(),
                    angular_velocity_change: m.angular_velocity_change.map(Into::into),
                })
                .collect(),
        });
    }
    let law = SpatialLaw::from(req.law);
    let fit = fit::spatial(&observations, law, req.torsion.map(|t| t.pitch_radius)).map_err(|e| {
        let pointer = match &e {
            FitError::NotAnImpact { index, why } if why.contains("uncertainty") => {
                format!("/impacts/{index}/measured")
            }
            FitError::NotAnImpact { index, .. } => format!("/impacts/{index}"),
            FitError::Undetermined { parameter, .. } if parameter.starts_with("/torsion") => {
                "/torsion".into()
            }
            FitError::Undetermined { .. } => "/law".into(),
            _ => "/impacts".into(),
        };
        problem(pointer, e.to_string())
    })?;
    Ok(SpatialFitResponse {
        law: req.law,
        members: members(&fit.law, fit.torsion),
        coefficients: fit
            .estimates
            .iter()
            .map(|&(input, estimate)| CoefficientDto {
                member: input.path(),
                symbol: input.symbol(),
                estimate: estimate.into(),
            })
            .collect(),
        impacts: fit
            .impacts
            .into_iter()
            .map(|i| SpatialImpactFitDto {
                regime: i.regime.into(),
                torsional_regime: i.torsional_regime.map(Into::into),
                residuals: i.residuals,
            })
            .collect(),
        chi_squared: fit.chi_squared,
        degrees_of_freedom: fit.degrees_of_freedom,
    })
}
