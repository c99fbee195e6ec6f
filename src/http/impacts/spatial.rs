//! `POST /v1/impacts/spatial`: body A against body B or a barrier in space,
//! with inertia tensors and an optional twist law.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::bodies::body_count;
pub use super::inertia::{InertiaDto, PrincipalDto, QuaternionDto, SphereDto, TensorDto};
use super::law::law_request;
use super::respond;
use crate::http::dto::{PlanarEnergyOut, PrecisionDto, RegimeDto, TorsionalRegimeDto};
use crate::http::problem::ApiError;
use crate::impact::{Precision, RigidBody, SpatialContact, SpatialImpact, Twist};
use crate::outcome::{SpatialBodyOutcome, SpatialContactVelocity, SpatialOutcome};

/// A vector in world axes.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Vector3Dto {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

impl From<Vector3Dto> for [f64; 3] {
    fn from(v: Vector3Dto) -> Self {
        [v.x, v.y, v.z]
    }
}

impl From<[f64; 3]> for Vector3Dto {
    fn from(v: [f64; 3]) -> Self {
        Vector3Dto {
            x: v[0],
            y: v[1],
            z: v[2],
        }
    }
}

/// A rigid body in space.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpatialBodyDto {
    /// m: mass (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.057)]
    pub mass: f64,
    /// The inertia tensor about the mass centre.
    pub inertia: InertiaDto,
    /// Position of the mass centre G.
    pub position: Vector3Dto,
    /// Velocity of G.
    pub velocity: Vector3Dto,
    /// ω: angular velocity.
    pub angular_velocity: Vector3Dto,
}

impl SpatialBodyDto {
    pub(crate) fn body(&self, k: usize) -> Result<RigidBody, ApiError> {
        Ok(RigidBody {
            mass: self.mass,
            inertia: self.inertia.tensor(k, self.mass)?,
            position: self.position.into(),
            velocity: self.velocity.into(),
            angular_velocity: self.angular_velocity.into(),
        })
    }
}

/// The contact point and the normal from body B (or the barrier) into body A.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpatialContactDto {
    /// C: the contact point.
    pub point: Vector3Dto,
    /// n: the normal from B into A, any non-zero length (the model uses n/|n|).
    pub normal: Vector3Dto,
}

impl From<SpatialContactDto> for SpatialContact {
    fn from(c: SpatialContactDto) -> Self {
        SpatialContact {
            point: c.point.into(),
            normal: c.normal.into(),
        }
    }
}

/// The twist law about the normal (section 4 generalised).
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TwistDto {
    /// e_z: torsional coefficient of restitution, in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.3)]
    pub restitution: f64,
    /// μ_z: torsional friction coefficient (≥ 0).
    #[schema(minimum = 0.0, example = 0.2)]
    pub friction: f64,
    /// ρ_p: pitch radius of the torsional friction (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.01)]
    pub pitch_radius: f64,
}

law_request! { in space;
/// One point contact in space between two bodies, or one and a fixed barrier:
/// `restitution` and at most one tangential law (`friction`; `impulse_ratio`,
/// a magnitude opposing the slip; `tangential_restitution` with `friction`),
/// none being frictionless; or `kinetic_restitution`, the two-phase law, whose
/// impulse ratios are magnitudes along one direction opposing the slip;
/// `torsion` adds the twist law (not with `kinetic_restitution`).
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "bodies": [
        {"mass": 0.057, "inertia": {"sphere": {"radius": 0.033, "hollow": true}},
         "position": {"x": 0.0, "y": 0.0, "z": 0.033},
         "velocity": {"x": 20.0, "y": 0.0, "z": -10.0},
         "angular_velocity": {"x": 0.0, "y": 300.0, "z": 0.0}}
    ],
    "contact": {"point": {"x": 0.0, "y": 0.0, "z": 0.0}, "normal": {"x": 0.0, "y": 0.0, "z": 1.0}},
    "restitution": 0.75,
    "friction": 0.6
}))]
pub struct SpatialContactRequest {
    /// Body A, and body B unless A hits a fixed barrier (1 or 2 bodies).
    pub bodies: Vec<SpatialBodyDto>,
    /// The contact.
    pub contact: SpatialContactDto,
    /// The twist law about the normal, if any.
    pub torsion: Option<TwistDto>,
    /// `fast` (default: exact decisions, every number within 2⁻³² of its scale) or
    /// `exact` (correctly rounded numbers, exact decisions).
    #[serde(default)]
    pub precision: PrecisionDto,
}
}

impl TryFrom<&SpatialContactRequest> for SpatialImpact {
    type Error = ApiError;

    fn try_from(req: &SpatialContactRequest) -> Result<Self, ApiError> {
        let (a, b) = match &req.bodies[..] {
            [a] => (a.body(0)?, None),
            [a, b] => (a.body(0)?, Some(b.body(1)?)),
            _ => return Err(body_count(req.bodies.len())),
        };
        Ok(SpatialImpact {
            a,
            b,
            contact: req.contact.into(),
            law: req.law()?,
            torsion: req.torsion.map(|t| Twist {
                restitution: t.restitution,
                friction: t.friction,
                pitch_radius: t.pitch_radius,
            }),
        })
    }
}

/// What one body answers.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SpatialBodyOut {
    /// V: final velocity of the mass centre.
    pub velocity: Vector3Dto,
    /// Ω: final angular velocity.
    pub angular_velocity: Vector3Dto,
    /// ΔV = V − v.
    pub velocity_change: Vector3Dto,
    /// |ΔV|: the delta-V of accident reconstruction.
    pub delta_v: f64,
    /// ΔΩ = Ω − ω.
    pub angular_velocity_change: Vector3Dto,
}

impl From<&SpatialBodyOutcome> for SpatialBodyOut {
    fn from(b: &SpatialBodyOutcome) -> Self {
        SpatialBodyOut {
            velocity: b.velocity.into(),
            angular_velocity: b.angular_velocity.into(),
            velocity_change: b.velocity_change.into(),
            delta_v: b.delta_v,
            angular_velocity_change: b.angular_velocity_change.into(),
        }
    }
}

/// The relative contact velocity `u = u_A − u_B` at one instant.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SpatialContactVelocityOut {
    /// u·n̂ (negative before the impact).
    pub normal: f64,
    /// The slip u − (u·n̂) n̂, a world vector.
    pub tangential: Vector3Dto,
    /// The relative spin about the normal, (ω_A − ω_B)·n̂.
    pub spin: f64,
}

impl From<SpatialContactVelocity> for SpatialContactVelocityOut {
    fn from(c: SpatialContactVelocity) -> Self {
        SpatialContactVelocityOut {
            normal: c.normal,
            tangential: c.tangential.into(),
            spin: c.spin,
        }
    }
}

/// Initial and final relative contact velocities.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SpatialContactVelocitiesOut {
    /// Before the impact.
    pub initial: SpatialContactVelocityOut,
    /// After it.
    #[serde(rename = "final")]
    pub final_: SpatialContactVelocityOut,
}

/// The impulse and couple on body A (−P, −M act on B).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SpatialImpulseOut {
    /// P_n = P·n̂ > 0.
    pub normal: f64,
    /// P_t = P − P_n n̂, a world vector.
    pub tangential: Vector3Dto,
    /// M: the couple about n̂ (0 without a twist law).
    pub torsional: f64,
    /// World x of P.
    pub x: f64,
    /// World y of P.
    pub y: f64,
    /// World z of P: the principal direction of force is (x, y, z).
    pub z: f64,
}

/// The outcome of a contact in space.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SpatialContactResponse {
    /// Body A, then body B if given.
    pub bodies: Vec<SpatialBodyOut>,
    /// Relative contact velocities before and after.
    pub contact_velocity: SpatialContactVelocitiesOut,
    /// The impulse and couple on A.
    pub impulse: SpatialImpulseOut,
    /// μ = |P_t| / P_n.
    pub impulse_ratio: f64,
    /// μ_c = |P_t| / |P_n| of the sticking impulse (with the answer's twist
    /// branch); null when that impulse has P_n = 0 or its system is singular.
    pub critical_impulse_ratio: Option<f64>,
    /// e.
    pub restitution: f64,
    /// The branch of the tangential law that answered.
    pub regime: RegimeDto,
    /// The branch of the twist law (with `torsion` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub torsional_regime: Option<TorsionalRegimeDto>,
    /// Kinetic energies of the pair: T_L in work form (with the couple's work),
    /// T_M = ½ (u, s)ᵀ𝒲⁻¹(u, s), T_L* = T_L/T_M.
    pub energy: PlanarEnergyOut,
    /// The precision that produced the answer.
    pub precision: PrecisionDto,
}

impl SpatialContactResponse {
    /// Maps an outcome computed with every output in `precision`.
    pub fn from_outcome(o: &SpatialOutcome, precision: Precision) -> Self {
        SpatialContactResponse {
            bodies: o.bodies[..o.body_count].iter().map(Into::into).collect(),
            contact_velocity: SpatialContactVelocitiesOut {
                initial: o.contact_velocity.initial.into(),
                final_: o.contact_velocity.r#final.into(),
            },
            impulse: SpatialImpulseOut {
                normal: o.impulse.normal,
                tangential: o.impulse.tangential.into(),
                torsional: o.impulse.torsional,
                x: o.impulse.x,
                y: o.impulse.y,
                z: o.impulse.z,
            },
            impulse_ratio: o.impulse_ratio,
            critical_impulse_ratio: o.critical_impulse_ratio,
            restitution: o.restitution,
            regime: o.regime.into(),
            torsional_regime: o.torsional_regime.map(Into::into),
            energy: o.energy.unwrap_or_default().into(),
            precision: precision.into(),
        }
    }
}

/// The response to a spatial contact request.
pub fn respond_spatial_contact(req: SpatialContactRequest) -> Result<SpatialContactResponse, ApiError> {
    respond(
        SpatialImpact::try_from(&req),
        req.precision,
        SpatialContactResponse::from_outcome,
    )
}

json_operation! {
    /// Two rigid bodies, or one against a barrier, in space: inertia tensors, slip
    /// in any direction, the twist law about the normal.
    impacts_spatial: "/v1/impacts/spatial" in "impacts", SpatialContactRequest => SpatialContactResponse ("The contact's outcome") by respond_spatial_contact
}

#[cfg(test)]
mod tests {
    use serde_json::{Value as Json, json};

    use super::super::wire_check::{paths_resolve, with_law};
    use super::*;

    fn request(bodies: usize, law: Json) -> Json {
        let body = |x: f64, vx: f64| {
            json!({"mass": 1.5, "inertia": {"xx": 0.375, "yy": 0.5, "zz": 0.4375, "xy": 0.0625, "xz": -0.03125, "yz": 0.0625},
                   "position": {"x": x, "y": 0.125, "z": -0.25},
                   "velocity": {"x": vx, "y": 0.75, "z": 0.5}, "angular_velocity": {"x": 1.25, "y": -2.0, "z": 3.0}})
        };
        let all = [body(0.0, 8.0), body(2.0, -1.0)];
        let scene = json!({
            "bodies": all[..bodies].to_vec(),
            "contact": {"point": {"x": 1.0, "y": 0.5, "z": 0.25}, "normal": {"x": -2.0, "y": 0.5, "z": 0.25}},
        });
        with_law(scene, &law)
    }

    #[test]
    fn every_input_and_output_path_resolves_in_the_spatial_contact_wire_types() {
        let torsion = json!({"restitution": 0.3, "friction": 0.2, "pitch_radius": 0.05});
        for bodies in [1, 2] {
            for law in [
                json!({"restitution": 0.5}),
                json!({"restitution": 0.5, "friction": 0.3}),
                json!({"restitution": 0.5, "impulse_ratio": 0.05}),
                json!({"restitution": 0.5, "friction": 0.3, "tangential_restitution": 0.2}),
                json!({"restitution": 0.5, "friction": 0.3, "torsion": torsion}),
                json!({"kinetic_restitution": {"value": 0.5, "approach_impulse_ratio": 0.2, "rebound_impulse_ratio": 0.1}}),
            ] {
                let r = request(bodies, law);
                let req: SpatialContactRequest = serde_json::from_value(r.clone()).unwrap();
                let impact = SpatialImpact::try_from(&req).unwrap();
                paths_resolve(&r, &impact, SpatialContactResponse::from_outcome);
            }
        }
    }

    #[test]
    fn the_inertia_conveniences_give_the_tensors_they_name() {
        let mut r = request(1, json!({"restitution": 0.5}));
        r["bodies"][0]["inertia"] = json!({"sphere": {"radius": 0.5, "hollow": true}});
        let req: SpatialContactRequest = serde_json::from_value(r.clone()).unwrap();
        let t = SpatialImpact::try_from(&req).unwrap().a.inertia;
        // (2/3) m r² = (2/3) 1.5 · 0.25.
        assert_eq!(t, [0.25, 0.25, 0.25, 0.0, 0.0, 0.0]);
        r["bodies"][0]["inertia"] = json!({"principal": {"moments": {"x": 1.0, "y": 2.0, "z": 3.0},
                                                           "rotation": {"w": 1.0, "x": 0.0, "y": 0.0, "z": 1.0}}});
        let req: SpatialContactRequest = serde_json::from_value(r.clone()).unwrap();
        let t = SpatialImpact::try_from(&req).unwrap().a.inertia;
        // 90° about z swaps the x and y moments.
        for (got, want) in t.iter().zip([2.0, 1.0, 3.0, 0.0, 0.0, 0.0]) {
            assert!((got - want).abs() < 1e-15, "{t:?}");
        }
        r["bodies"][0]["inertia"] = json!({"sphere": {"radius": -1.0}});
        let req: SpatialContactRequest = serde_json::from_value(r).unwrap();
        assert_eq!(
            SpatialImpact::try_from(&req).unwrap_err().pointer(),
            Some("/bodies/0/inertia/sphere/radius")
        );
    }
}
