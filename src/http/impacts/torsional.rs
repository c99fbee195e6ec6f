//! `POST /v1/impacts/torsional`: a body spinning about the contact normal
//! (section 4, Eqs 28–31).

use serde::Deserialize;
use utoipa::ToSchema;

use super::respond;
use crate::http::dto::{PrecisionDto, TorsionalResponse};
use crate::http::problem::ApiError;
use crate::impact::TorsionalImpact;

/// Mass and moment of inertia about the contact normal.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionalBodyDto {
    /// Mass m (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.6)]
    pub mass: f64,
    /// I_n: moment of inertia about the normal axis (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.003456)]
    pub normal_inertia: f64,
}

/// Initial normal velocity and spin.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionalVelocityDto {
    /// v_n: normal velocity (< 0: approaching).
    #[schema(exclusive_maximum = 0.0, example = -3.0)]
    pub normal: f64,
    /// ω_n: spin about the normal.
    #[schema(example = 20.0)]
    pub spin: f64,
}

/// Torsional coefficients.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TorsionDto {
    /// e_z: torsional coefficient of restitution (Eq 28), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.2)]
    pub restitution: f64,
    /// μ_z: torsional friction coefficient (≥ 0, a magnitude; the moment opposes the spin).
    #[schema(minimum = 0.0, example = 0.3)]
    pub friction: f64,
    /// ρ_p: pitch radius of the torsional friction impulse (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.01)]
    pub pitch_radius: f64,
}

/// A torsional impact (section 4).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 0.6, "normal_inertia": 0.003456},
    "velocity": {"normal": -3.0, "spin": 20.0},
    "restitution": 0.7,
    "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}
}))]
pub struct TorsionalRequest {
    /// The body.
    pub body: TorsionalBodyDto,
    /// Initial normal velocity and spin.
    pub velocity: TorsionalVelocityDto,
    /// e: kinematic coefficient of restitution of the normal impact, in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.7)]
    pub restitution: f64,
    /// Torsional coefficients.
    pub torsion: TorsionDto,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

impl From<&TorsionalRequest> for TorsionalImpact {
    fn from(req: &TorsionalRequest) -> Self {
        TorsionalImpact {
            mass: req.body.mass,
            normal_inertia: req.body.normal_inertia,
            normal_velocity: req.velocity.normal,
            spin: req.velocity.spin,
            restitution: req.restitution,
            torsional_restitution: req.torsion.restitution,
            torsional_friction: req.torsion.friction,
            pitch_radius: req.torsion.pitch_radius,
        }
    }
}

/// The response to a torsional request.
pub fn respond_torsional(req: TorsionalRequest) -> Result<TorsionalResponse, ApiError> {
    respond(
        Ok(TorsionalImpact::from(&req)),
        req.precision,
        TorsionalResponse::from_outcome,
    )
}

json_operation! {
    /// Impact with torsional restitution: the bilinear model of Eqs 28–31.
    impacts_torsional: "/v1/impacts/torsional" in "impacts", TorsionalRequest => TorsionalResponse ("The impact's outcome") by respond_torsional
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::super::wire_check::{inputs_resolve, outputs_resolve};
    use super::*;
    use crate::impact::{Case, Precision, solve};
    use crate::outcome::Outputs;

    #[test]
    fn every_input_and_output_path_resolves_in_the_torsional_wire_types() {
        let request = json!({"body": {"mass": 0.6, "normal_inertia": 0.003456},
                             "velocity": {"normal": -3.0, "spin": 20.0}, "restitution": 0.7,
                             "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}});
        let req: TorsionalRequest = serde_json::from_value(request.clone()).unwrap();
        let impact = TorsionalImpact::from(&req);
        inputs_resolve(&request, &impact);
        assert_eq!(impact.reads(), TorsionalImpact::INPUTS);
        let outcome = solve(&impact, Outputs::ALL, Precision::Fast).unwrap();
        let response =
            serde_json::to_value(TorsionalResponse::from_outcome(&outcome, Precision::Fast)).unwrap();
        outputs_resolve(&response, &impact, &outcome);
    }
}
