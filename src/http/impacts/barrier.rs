//! `POST /v1/impacts/{normal,oblique,tangential}`: one body against a
//! barrier in the paper's frame, one impact each. Each request type parses
//! into the solver's impact with `TryFrom` (a structural error names its
//! member); handlers only solve and map back.

use serde::Deserialize;
use utoipa::ToSchema;

use super::law::{law_problem, law_request};
use super::respond;
use crate::error::{ImpactError, Input};
use crate::http::dto::{ContactDto, NormalBodyDto, PlanarResponse, PrecisionDto, RigidBodyDto, VelocityDto};
use crate::http::problem::ApiError;
use crate::impact::{BarrierBody, BarrierImpact, Law};
use crate::scene::PlanarVelocity;

/// A normal (frictionless) impact: a point mass when `body.inertia` is absent.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93
}))]
pub struct NormalRequest {
    /// The body; without `inertia` a point mass.
    pub body: NormalBodyDto,
    /// Contact geometry (rigid body only; default d_c = d_d = 0).
    pub contact: Option<ContactDto>,
    /// Initial velocities (a point mass takes no angular velocity).
    pub velocity: VelocityDto,
    /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub restitution: f64,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

law_request! { in the plane;
/// An oblique impact: `restitution` with exactly one tangential law
/// (`friction`; `impulse_ratio`; `tangential_restitution` with `friction`),
/// or `kinetic_restitution` alone.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93,
    "friction": 0.123
}))]
pub struct ObliqueRequest {
    /// The rigid body.
    pub body: RigidBodyDto,
    /// Contact geometry.
    pub contact: ContactDto,
    /// Initial velocities.
    pub velocity: VelocityDto,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}
}

/// An impact with tangential restitution (the bilinear model of section 3).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "body": {"mass": 1.0, "inertia": 0.00125},
    "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
    "velocity": {"normal": -1.0, "tangential": 0.4, "angular": 0.0},
    "restitution": 0.93,
    "friction": 0.123,
    "tangential_restitution": 0.34
}))]
pub struct TangentialRequest {
    /// The rigid body.
    pub body: RigidBodyDto,
    /// Contact geometry.
    pub contact: ContactDto,
    /// Initial velocities.
    pub velocity: VelocityDto,
    /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub restitution: f64,
    /// f: Coulomb friction coefficient (≥ 0), the cap of the tangential impulse.
    #[schema(minimum = 0.0, example = 0.123)]
    pub friction: f64,
    /// e_t: tangential coefficient of restitution (Eq 20), in [−1, 1]; −1 means no tangential impulse.
    #[schema(minimum = -1.0, maximum = 1.0, example = 0.34)]
    pub tangential_restitution: f64,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}

impl TryFrom<&NormalRequest> for BarrierImpact {
    type Error = ApiError;

    /// A point mass when the body has no inertia (then no contact may be given).
    fn try_from(req: &NormalRequest) -> Result<Self, ApiError> {
        let body = match (req.body.inertia, req.contact) {
            (Some(inertia), contact) => BarrierBody::Rigid {
                mass: req.body.mass,
                inertia,
                contact: contact.map(Into::into).unwrap_or_default(),
            },
            (None, Some(_)) => {
                return Err(ImpactError::NeedsInertia {
                    input: Input::TangentialOffset,
                }
                .into());
            }
            (None, None) => BarrierBody::PointMass { mass: req.body.mass },
        };
        Ok(BarrierImpact {
            body,
            velocity: req.velocity.into(),
            law: Law::Frictionless {
                restitution: req.restitution,
            },
        })
    }
}

impl TryFrom<&ObliqueRequest> for BarrierImpact {
    type Error = ApiError;

    /// Exactly one law, read by the one wire parser: `restitution` with a
    /// tangential law, or `kinetic_restitution` alone.
    fn try_from(req: &ObliqueRequest) -> Result<Self, ApiError> {
        let law = req.law()?;
        if let Law::Frictionless { .. } = law {
            return Err(law_problem(
                "/friction",
                "an oblique impact needs a tangential law: give friction or impulse_ratio with restitution, or kinetic_restitution alone",
            ));
        }
        Ok(rigid(req.body, req.contact, req.velocity, law))
    }
}

impl From<&TangentialRequest> for BarrierImpact {
    fn from(req: &TangentialRequest) -> Self {
        rigid(
            req.body,
            req.contact,
            req.velocity,
            Law::TangentialRestitution {
                restitution: req.restitution,
                friction: req.friction,
                tangential_restitution: req.tangential_restitution,
            },
        )
    }
}

fn rigid(body: RigidBodyDto, contact: ContactDto, velocity: VelocityDto, law: Law) -> BarrierImpact {
    BarrierImpact::rigid(
        body.mass,
        body.inertia,
        contact.into(),
        PlanarVelocity::from(velocity),
        law,
    )
}

/// The response to a normal request.
pub fn respond_normal(req: NormalRequest) -> Result<PlanarResponse, ApiError> {
    respond(
        BarrierImpact::try_from(&req),
        req.precision,
        PlanarResponse::from_outcome,
    )
}

/// The response to an oblique request.
pub fn respond_oblique(req: ObliqueRequest) -> Result<PlanarResponse, ApiError> {
    respond(
        BarrierImpact::try_from(&req),
        req.precision,
        PlanarResponse::from_outcome,
    )
}

/// The response to a tangential-restitution request.
pub fn respond_tangential(req: TangentialRequest) -> Result<PlanarResponse, ApiError> {
    respond(
        Ok(BarrierImpact::from(&req)),
        req.precision,
        PlanarResponse::from_outcome,
    )
}

json_operation! {
    /// Normal impact of a point mass or a frictionless rigid body (section 2.1).
    impacts_normal: "/v1/impacts/normal" in "impacts", NormalRequest => PlanarResponse ("The impact's outcome") by respond_normal
}

json_operation! {
    /// Oblique impact with a prescribed impulse ratio, Coulomb friction, or two-phase kinetic restitution (Eqs 1–19, Appendix).
    impacts_oblique: "/v1/impacts/oblique" in "impacts", ObliqueRequest => PlanarResponse ("The impact's outcome") by respond_oblique
}

json_operation! {
    /// Impact with tangential restitution: the bilinear model of Eqs 20–27.
    impacts_tangential: "/v1/impacts/tangential" in "impacts", TangentialRequest => PlanarResponse ("The impact's outcome") by respond_tangential
}

#[cfg(test)]
mod tests {
    use serde_json::{Value as Json, json};

    use super::super::wire_check::{paths_resolve, with_law};
    use super::*;

    fn body() -> Json {
        json!({"mass": 1.25, "inertia": 0.0021})
    }

    fn contact() -> Json {
        json!({"tangential_offset": 0.011, "normal_offset": 0.053})
    }

    fn velocity() -> Json {
        json!({"normal": -1.1, "tangential": 0.37, "angular": 2.9})
    }

    #[test]
    fn every_input_and_output_path_resolves_in_the_planar_wire_types() {
        let requests = [
            json!({"body": body(), "contact": contact(), "velocity": velocity(), "restitution": 0.93}),
            json!({"body": {"mass": 1.25}, "velocity": {"normal": -1.1, "tangential": 0.37}, "restitution": 0.93}),
        ];
        let mut impacts: Vec<(Json, BarrierImpact)> = requests
            .into_iter()
            .map(|r| {
                let req: NormalRequest = serde_json::from_value(r.clone()).unwrap();
                (r, BarrierImpact::try_from(&req).unwrap())
            })
            .collect();
        for law in [
            json!({"restitution": 0.93, "friction": 0.123}),
            json!({"restitution": 0.93, "impulse_ratio": -0.05}),
            json!({"kinetic_restitution": {"value": 0.9, "approach_impulse_ratio": -0.05, "rebound_impulse_ratio": -0.04}}),
        ] {
            let r = with_law(
                json!({"body": body(), "contact": contact(), "velocity": velocity()}),
                &law,
            );
            let req: ObliqueRequest = serde_json::from_value(r.clone()).unwrap();
            impacts.push((r, BarrierImpact::try_from(&req).unwrap()));
        }
        let r = json!({"body": body(), "contact": contact(), "velocity": velocity(),
                       "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34});
        let req: TangentialRequest = serde_json::from_value(r.clone()).unwrap();
        impacts.push((r, BarrierImpact::from(&req)));
        for (request, impact) in &impacts {
            paths_resolve(request, impact, PlanarResponse::from_outcome);
        }
    }
}
