//! `POST /v1/impacts/planar`: body A against body B or a barrier, in world
//! axes (the general planar contact).

use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::law::law_request;
use super::respond;
use crate::http::dto::{ContactVelocitiesOut, PlanarEnergyOut, PrecisionDto, RegimeDto};
use crate::http::problem::ApiError;
use crate::impact::{BodiesImpact, Lamina, PlanarContact, Precision};
use crate::outcome::{BodiesOutcome, BodyOutcome};

/// A vector in world axes.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct VectorDto {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
}

impl From<VectorDto> for [f64; 2] {
    fn from(v: VectorDto) -> Self {
        [v.x, v.y]
    }
}

impl From<[f64; 2]> for VectorDto {
    fn from(v: [f64; 2]) -> Self {
        VectorDto { x: v[0], y: v[1] }
    }
}

/// A rigid lamina in world axes.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LaminaDto {
    /// m: mass (> 0).
    #[schema(exclusive_minimum = 0.0, example = 1500.0)]
    pub mass: f64,
    /// I: moment of inertia about the mass centre (> 0).
    #[schema(exclusive_minimum = 0.0, example = 2500.0)]
    pub inertia: f64,
    /// Position of the mass centre G.
    pub position: VectorDto,
    /// Velocity of G.
    pub velocity: VectorDto,
    /// ω: angular velocity, counter-clockwise positive.
    pub angular_velocity: f64,
}

impl From<LaminaDto> for Lamina {
    fn from(l: LaminaDto) -> Self {
        Lamina {
            mass: l.mass,
            inertia: l.inertia,
            position: l.position.into(),
            velocity: l.velocity.into(),
            angular_velocity: l.angular_velocity,
        }
    }
}

/// The contact point and the normal from body B (or the barrier) into body A.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PlanarContactDto {
    /// C: the contact point.
    pub point: VectorDto,
    /// n: the normal from B into A, any non-zero length (the model uses n/|n|).
    pub normal: VectorDto,
}

impl From<PlanarContactDto> for PlanarContact {
    fn from(c: PlanarContactDto) -> Self {
        PlanarContact {
            point: c.point.into(),
            normal: c.normal.into(),
        }
    }
}

law_request! { in the plane;
/// One point contact between two laminae, or one and a fixed barrier, in
/// world axes: `restitution` (or `kinetic_restitution`) and at most one
/// tangential law (`friction`; `impulse_ratio`; `tangential_restitution`
/// with `friction`); none is frictionless.
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
    "restitution": 0.2,
    "friction": 0.6
}))]
pub struct PlanarContactRequest {
    /// Body A, and body B unless A hits a fixed barrier (1 or 2 bodies).
    pub bodies: Vec<LaminaDto>,
    /// The contact.
    pub contact: PlanarContactDto,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}
}

/// The refusal of a body count other than 1 or 2.
pub(super) fn body_count(count: usize) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "body-count",
        "One or two bodies",
        format!("a contact has body A and either body B or a barrier: give 1 or 2 bodies, not {count}"),
    )
    .at("/bodies")
}

impl TryFrom<&PlanarContactRequest> for BodiesImpact {
    type Error = ApiError;

    fn try_from(req: &PlanarContactRequest) -> Result<Self, ApiError> {
        let (a, b) = match req.bodies[..] {
            [a] => (a, None),
            [a, b] => (a, Some(b)),
            _ => return Err(body_count(req.bodies.len())),
        };
        Ok(BodiesImpact {
            a: a.into(),
            b: b.map(Into::into),
            contact: req.contact.into(),
            law: req.law()?,
        })
    }
}

/// What one body answers.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct PlanarBodyOut {
    /// V: final velocity of the mass centre.
    pub velocity: VectorDto,
    /// Ω: final angular velocity.
    pub angular_velocity: f64,
    /// ΔV = V − v.
    pub velocity_change: VectorDto,
    /// |ΔV|: the delta-V of accident reconstruction.
    pub delta_v: f64,
    /// ΔΩ = Ω − ω.
    pub angular_velocity_change: f64,
}

impl From<&BodyOutcome> for PlanarBodyOut {
    fn from(b: &BodyOutcome) -> Self {
        PlanarBodyOut {
            velocity: b.velocity.into(),
            angular_velocity: b.angular_velocity,
            velocity_change: b.velocity_change.into(),
            delta_v: b.delta_v,
            angular_velocity_change: b.angular_velocity_change,
        }
    }
}

/// The impulse on body A (−P acts on B).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct WorldImpulseOut {
    /// P_n = P·n̂ > 0.
    pub normal: f64,
    /// P_t = P·t̂, t̂ = ẑ × n̂.
    pub tangential: f64,
    /// World x of P.
    pub x: f64,
    /// World y of P: the principal direction of force is (x, y).
    pub y: f64,
}

/// The outcome of a planar contact.
#[derive(Debug, Clone, Serialize, ToSchema)]
// The server's answer to the request example (two cars, sticking).
#[schema(example = json!({
    "bodies": [
        {"velocity": {"x": 7.523287026136095, "y": 3.9399105250765243},
         "angular_velocity": 2.5090652225100065,
         "velocity_change": {"x": -7.476712973863905, "y": 3.9399105250765243},
         "delta_v": 8.45127989355184, "angular_velocity_change": 2.5090652225100065},
        {"velocity": {"x": 9.345891217329882, "y": 7.075111843654344},
         "angular_velocity": -2.9809277136802463,
         "velocity_change": {"x": 9.345891217329882, "y": -4.924888156345656},
         "delta_v": 10.5640998669398, "angular_velocity_change": -2.9809277136802463}
    ],
    "contact_velocity": {"initial": {"normal": -15.0, "tangential": 12.0}, "final": {"normal": 3.0, "tangential": 0.0}},
    "impulse": {"normal": 11215.069460795858, "tangential": -5909.865787614786, "x": -11215.069460795858, "y": 5909.865787614786},
    "impulse_ratio": -0.5269575733145216,
    "critical_impulse_ratio": -0.5269575733145216,
    "restitution": 0.2,
    "kinetic_restitution": 0.2,
    "regime": "sticking",
    "energy": {"initial": 255150.0, "final": 152400.38850953613, "loss": 102749.61149046387,
               "max_loss": 105160.06592889097, "normalized_loss": 0.9770782338605888},
    "precision": "fast"
}))]
pub struct PlanarContactResponse {
    /// Body A, then body B if given.
    pub bodies: Vec<PlanarBodyOut>,
    /// Relative contact velocity u = u_A − u_B along n̂ and t̂, before and after.
    pub contact_velocity: ContactVelocitiesOut,
    /// The impulse on A.
    pub impulse: WorldImpulseOut,
    /// μ = P_t / P_n.
    pub impulse_ratio: f64,
    /// μ_c: the ratio of the sticking impulse (signed, along t̂); null when that impulse has P_n = 0.
    pub critical_impulse_ratio: Option<f64>,
    /// e (for the two-phase model, the equivalent e = R D_R / D_A).
    pub restitution: f64,
    /// R (e under the kinematic law).
    pub kinetic_restitution: f64,
    /// The branch of the law that answered.
    pub regime: RegimeDto,
    /// Kinetic energies of the pair: T_L in work form, T_M = ½ uᵀW⁻¹u, T_L* = T_L/T_M.
    pub energy: PlanarEnergyOut,
    /// The precision that produced the answer.
    pub precision: PrecisionDto,
}

impl PlanarContactResponse {
    /// Maps an outcome computed with every output in `precision`.
    pub fn from_outcome(o: &BodiesOutcome, precision: Precision) -> Self {
        PlanarContactResponse {
            bodies: o.bodies[..o.body_count].iter().map(Into::into).collect(),
            contact_velocity: ContactVelocitiesOut {
                initial: o.contact_velocity.initial.into(),
                final_: o.contact_velocity.r#final.into(),
            },
            impulse: WorldImpulseOut {
                normal: o.impulse.normal,
                tangential: o.impulse.tangential,
                x: o.impulse.x,
                y: o.impulse.y,
            },
            impulse_ratio: o.impulse_ratio,
            critical_impulse_ratio: o.critical_impulse_ratio,
            restitution: o.restitution,
            kinetic_restitution: o.kinetic_restitution,
            regime: o.regime.into(),
            energy: o.energy.unwrap_or_default().into(),
            precision: precision.into(),
        }
    }
}

/// The response to a planar contact request.
pub fn respond_planar_contact(req: PlanarContactRequest) -> Result<PlanarContactResponse, ApiError> {
    respond(
        BodiesImpact::try_from(&req),
        req.precision,
        PlanarContactResponse::from_outcome,
    )
}

json_operation! {
    /// Two laminae, or one against a barrier, in world axes: every law of the one-body endpoints.
    impacts_planar: "/v1/impacts/planar" in "impacts", PlanarContactRequest => PlanarContactResponse ("The contact's outcome") by respond_planar_contact
}

#[cfg(test)]
mod tests {
    use serde_json::{Value as Json, json};

    use super::super::wire_check::{paths_resolve, with_law};
    use super::*;

    fn request(bodies: usize, law: Json) -> Json {
        let lamina = |x: f64, vx: f64| {
            json!({"mass": 1.5, "inertia": 0.25, "position": {"x": x, "y": 0.125},
                   "velocity": {"x": vx, "y": 0.75}, "angular_velocity": 1.25})
        };
        let all = [lamina(0.0, 3.0), lamina(2.0, -1.0)];
        let scene = json!({
            "bodies": all[..bodies].to_vec(),
            "contact": {"point": {"x": 1.0, "y": 0.5}, "normal": {"x": -2.0, "y": 0.5}},
        });
        with_law(scene, &law)
    }

    #[test]
    fn every_input_and_output_path_resolves_in_the_planar_contact_wire_types() {
        for bodies in [1, 2] {
            for law in [
                json!({"restitution": 0.5}),
                json!({"restitution": 0.5, "friction": 0.3}),
                json!({"restitution": 0.5, "impulse_ratio": 0.05}),
                json!({"restitution": 0.5, "friction": 0.3, "tangential_restitution": 0.2}),
                json!({"kinetic_restitution": {"value": 0.5, "approach_impulse_ratio": 0.05, "rebound_impulse_ratio": 0.04}}),
            ] {
                let r = request(bodies, law);
                let req: PlanarContactRequest = serde_json::from_value(r.clone()).unwrap();
                let impact = BodiesImpact::try_from(&req).unwrap();
                paths_resolve(&r, &impact, PlanarContactResponse::from_outcome);
            }
        }
    }

    #[test]
    fn conflicting_law_members_are_refused_at_the_member_the_conventions_name() {
        for (law, pointer) in [
            (
                json!({"restitution": 0.5, "friction": 0.3, "impulse_ratio": 0.1}),
                "/impulse_ratio",
            ),
            (
                json!({"restitution": 0.5, "tangential_restitution": 0.2}),
                "/friction",
            ),
            (
                json!({"restitution": 0.5, "impulse_ratio": 0.1, "tangential_restitution": 0.2}),
                "/tangential_restitution",
            ),
            (
                json!({"restitution": 0.5, "kinetic_restitution": {"value": 0.5, "approach_impulse_ratio": 0.0, "rebound_impulse_ratio": 0.0}}),
                "/restitution",
            ),
            (json!({"friction": 0.3}), "/restitution"),
        ] {
            let req: PlanarContactRequest = serde_json::from_value(request(2, law.clone())).unwrap();
            let error = BodiesImpact::try_from(&req).unwrap_err();
            assert_eq!(error.pointer(), Some(pointer), "{law}");
        }
        let req: PlanarContactRequest =
            serde_json::from_value(request(0, json!({"restitution": 0.5}))).unwrap();
        assert_eq!(
            BodiesImpact::try_from(&req).unwrap_err().pointer(),
            Some("/bodies")
        );
    }
}
