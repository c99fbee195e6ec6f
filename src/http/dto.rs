//! Wire types of the impact endpoints (JSON, snake_case) and their mapping
//! to and from the solver's types. Every input is named as in the paper in
//! its description; numbers are in any consistent unit system.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::impact::Precision;
use crate::outcome::{BarrierOutcome, Regime};
use crate::outcome::{TorsionalOutcome, TorsionalRegime};
use crate::scene::{Contact, ContactVelocity, PlanarVelocity};

/// Arithmetic precision of an answer.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum PrecisionDto {
    /// The f64 closed forms, every decision exact, and every number within
    /// 2⁻³² (about 2.3e-10) of max(|exact value|, S), S the scale of the
    /// output's unit in the impact (a velocity, spin, impulse or energy from
    /// the inputs; 1 for a ratio: docs/accuracy.md); where the f64 error
    /// bound cannot show that, the exact stages answer (the metric
    /// `restitution_fast_escalated_total` counts them).
    #[default]
    Fast,
    /// Every number is the correctly rounded f64 of the model's exact value for
    /// the given inputs, and every regime decision is exact (double-double with a
    /// certified error bound, exact rationals where that cannot decide).
    Exact,
}

impl From<PrecisionDto> for Precision {
    fn from(p: PrecisionDto) -> Self {
        match p {
            PrecisionDto::Fast => Precision::Fast,
            PrecisionDto::Exact => Precision::Exact,
        }
    }
}

impl From<Precision> for PrecisionDto {
    fn from(p: Precision) -> Self {
        match p {
            Precision::Fast => PrecisionDto::Fast,
            Precision::Exact => PrecisionDto::Exact,
        }
    }
}

/// A rigid body: mass and centroidal moment of inertia.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct RigidBodyDto {
    /// Mass m (> 0).
    #[schema(exclusive_minimum = 0.0, example = 1.0)]
    pub mass: f64,
    /// Centroidal moment of inertia I = m k² (> 0).
    #[schema(exclusive_minimum = 0.0, example = 0.00125)]
    pub inertia: f64,
}

/// A body for the normal case: a point mass when `inertia` is absent.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct NormalBodyDto {
    /// Mass m (> 0).
    #[schema(exclusive_minimum = 0.0, example = 1.0)]
    pub mass: f64,
    /// Centroidal moment of inertia I = m k² (> 0); absent for a point mass.
    #[schema(exclusive_minimum = 0.0)]
    pub inertia: Option<f64>,
}

/// Position of the centre of mass G relative to the contact point C.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactDto {
    /// d_c: G's offset from C along the tangent t.
    #[schema(example = 0.0)]
    pub tangential_offset: f64,
    /// d_d: G's offset from C along the barrier's outward normal n (a disc of radius ρ resting on the barrier: ρ).
    #[schema(example = 0.05)]
    pub normal_offset: f64,
}

impl From<ContactDto> for Contact {
    fn from(c: ContactDto) -> Self {
        Contact {
            tangential_offset: c.tangential_offset,
            normal_offset: c.normal_offset,
        }
    }
}

/// Initial velocity of the centre of mass and angular velocity.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct VelocityDto {
    /// v_n: normal velocity of G; the contact must approach: v_n + d_c ω < 0.
    #[schema(example = -1.0)]
    pub normal: f64,
    /// v_t: tangential velocity of G (default 0).
    #[serde(default)]
    #[schema(example = 0.4)]
    pub tangential: f64,
    /// ω: angular velocity, positive turning n toward t (default 0).
    #[serde(default)]
    #[schema(example = 0.0)]
    pub angular: f64,
}

impl From<VelocityDto> for PlanarVelocity {
    fn from(v: VelocityDto) -> Self {
        PlanarVelocity {
            normal: v.normal,
            tangential: v.tangential,
            angular: v.angular,
        }
    }
}

/// Normal and tangential velocity components.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct PlanarVelocityOut {
    /// V_n: final normal velocity of G.
    pub normal: f64,
    /// V_t: final tangential velocity of G.
    pub tangential: f64,
    /// Ω: final angular velocity.
    pub angular: f64,
}

/// A contact-point velocity.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ContactVelocityOut {
    /// Normal component (v_cn or V_cn).
    pub normal: f64,
    /// Tangential component (v_ct or V_ct).
    pub tangential: f64,
}

impl From<ContactVelocity> for ContactVelocityOut {
    fn from(c: ContactVelocity) -> Self {
        ContactVelocityOut {
            normal: c.normal,
            tangential: c.tangential,
        }
    }
}

/// Initial and final contact-point velocities.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ContactVelocitiesOut {
    /// (v_cn, v_ct) = (v_n + d_c ω, v_t − d_d ω).
    pub initial: ContactVelocityOut,
    /// (V_cn, V_ct).
    #[serde(rename = "final")]
    pub final_: ContactVelocityOut,
}

/// Impulses applied by the barrier at the contact point.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ImpulseOut {
    /// P_n ≥ 0: normal impulse.
    pub normal: f64,
    /// P_t: tangential impulse.
    pub tangential: f64,
}

/// Kinetic energies of a planar impact.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct PlanarEnergyOut {
    /// Initial kinetic energy.
    pub initial: f64,
    /// Final kinetic energy.
    #[serde(rename = "final")]
    pub final_: f64,
    /// T_L ≥ 0: energy lost (work of the impulses, Eq 8).
    pub loss: f64,
    /// T_M: the largest loss the contact can produce (e = 0, V_ct = 0).
    pub max_loss: f64,
    /// T_L* = T_L / T_M, in [0, 1].
    pub normalized_loss: f64,
}

impl From<crate::outcome::PlanarEnergy> for PlanarEnergyOut {
    fn from(e: crate::outcome::PlanarEnergy) -> Self {
        PlanarEnergyOut {
            initial: e.initial,
            final_: e.r#final,
            loss: e.loss,
            max_loss: e.max_loss,
            normalized_loss: e.normalized_loss,
        }
    }
}

/// The tangential law that produced a planar answer.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum RegimeDto {
    /// No tangential impulse.
    Frictionless,
    /// A prescribed impulse ratio (or the two-phase ratios).
    Prescribed,
    /// Sliding through separation, |μ| = f.
    Sliding,
    /// Slip stops before separation: μ = μ_c, V_ct = 0.
    Sticking,
    /// Tangential restitution: V_ct = −e_t v_ct.
    Restitution,
}

impl From<Regime> for RegimeDto {
    fn from(r: Regime) -> Self {
        match r {
            Regime::Frictionless => RegimeDto::Frictionless,
            Regime::Prescribed => RegimeDto::Prescribed,
            Regime::Sliding => RegimeDto::Sliding,
            Regime::Sticking => RegimeDto::Sticking,
            Regime::Restitution => RegimeDto::Restitution,
        }
    }
}

/// The outcome of a planar impact.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
// The server's answer to the oblique request example (the Maw disc, sticking).
#[schema(example = json!({
    "final_velocity": {"normal": 0.93, "tangential": 0.2666666666666667, "angular": 5.333333333333334},
    "contact_velocity": {
        "initial": {"normal": -1.0, "tangential": 0.4},
        "final": {"normal": 0.93, "tangential": 0.0}
    },
    "impulse": {"normal": 1.9300000000000002, "tangential": -0.1333333333333333},
    "impulse_ratio": -0.06908462867012088,
    "critical_impulse_ratio": -0.06908462867012088,
    "restitution": 0.93,
    "kinetic_restitution": 0.93,
    "regime": "sticking",
    "energy": {
        "initial": 0.5800000000000001,
        "final": 0.48578333333333346,
        "loss": 0.09421666666666662,
        "max_loss": 0.5266666666666666,
        "normalized_loss": 0.17889240506329107
    },
    "precision": "fast"
}))]
pub struct PlanarResponse {
    /// Final velocities (V_n, V_t, Ω).
    pub final_velocity: PlanarVelocityOut,
    /// Contact-point velocities before and after.
    pub contact_velocity: ContactVelocitiesOut,
    /// Impulses (P_n, P_t).
    pub impulse: ImpulseOut,
    /// μ = P_t / P_n: the applied impulse ratio (Eq 4).
    pub impulse_ratio: f64,
    /// μ_c: the critical impulse ratio, which ends with V_ct = 0.
    pub critical_impulse_ratio: f64,
    /// e: kinematic coefficient of restitution (Eq 1); for the two-phase model, the equivalent e of Eq 11.
    pub restitution: f64,
    /// R: kinetic coefficient of restitution (Eq 9).
    pub kinetic_restitution: f64,
    /// The law that produced the answer.
    pub regime: RegimeDto,
    /// Kinetic energies.
    pub energy: PlanarEnergyOut,
    /// The precision that produced the answer.
    pub precision: PrecisionDto,
}

impl PlanarResponse {
    /// Maps a solver outcome computed with every output in `precision`.
    pub fn from_outcome(o: &BarrierOutcome, precision: Precision) -> Self {
        PlanarResponse {
            final_velocity: PlanarVelocityOut {
                normal: o.final_velocity.normal,
                tangential: o.final_velocity.tangential,
                angular: o.final_velocity.angular,
            },
            contact_velocity: ContactVelocitiesOut {
                initial: o.contact_velocity.initial.into(),
                final_: o.contact_velocity.r#final.into(),
            },
            impulse: ImpulseOut {
                normal: o.impulse.normal,
                tangential: o.impulse.tangential,
            },
            impulse_ratio: o.impulse_ratio,
            critical_impulse_ratio: o.critical_impulse_ratio.unwrap_or(0.0),
            restitution: o.restitution,
            kinetic_restitution: o.kinetic_restitution,
            regime: o.regime.into(),
            energy: o.energy.unwrap_or_default().into(),
            precision: precision.into(),
        }
    }
}

/// Normal velocity and spin after a torsional impact.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct TorsionalVelocityOut {
    /// V_n = −e v_n.
    pub normal: f64,
    /// Ω_n: final spin about the normal.
    pub spin: f64,
}

/// Impulses of a torsional impact.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct TorsionalImpulseOut {
    /// P_n = m (1 + e) |v_n|.
    pub normal: f64,
    /// M_n = I_n (Ω_n − ω_n): torsional impulse (Eq 29).
    pub torsional: f64,
}

/// Rotational energies about the normal.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct RotationalEnergyOut {
    /// ½ I_n ω_n².
    pub initial: f64,
    /// ½ I_n Ω_n².
    #[serde(rename = "final")]
    pub final_: f64,
    /// Rotational energy lost, ≥ 0.
    pub loss: f64,
}

/// The branch of the torsional model.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum TorsionalRegimeDto {
    /// |ω_n| above the switch: rotational sliding through separation (Eq 30).
    Sliding,
    /// |ω_n| at or below the switch: Ω_n = −e_z ω_n (Eq 28).
    Restitution,
}

/// The outcome of a torsional impact.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
// The server's answer to the torsional request example (sliding).
#[schema(example = json!({
    "final_velocity": {"normal": 2.0999999999999996, "spin": 13.34375},
    "impulse": {"normal": 3.0599999999999996, "torsional": -0.023004},
    "regime": "sliding",
    "switch_spin": 2.65625,
    "energy": {"initial": 0.6911999999999999, "final": 0.3076801875, "loss": 0.3835198125},
    "precision": "fast"
}))]
pub struct TorsionalResponse {
    /// Final normal velocity and spin.
    pub final_velocity: TorsionalVelocityOut,
    /// Normal and torsional impulses.
    pub impulse: TorsionalImpulseOut,
    /// The branch used.
    pub regime: TorsionalRegimeDto,
    /// ω_s ≥ 0: spin magnitude at which the branches meet (Eq 31).
    pub switch_spin: f64,
    /// Rotational energies about the normal.
    pub energy: RotationalEnergyOut,
    /// The precision that produced the answer.
    pub precision: PrecisionDto,
}

impl TorsionalResponse {
    /// Maps a solver outcome computed with energies in `precision`.
    pub fn from_outcome(o: &TorsionalOutcome, precision: Precision) -> Self {
        let energy = o.energy.unwrap_or(crate::outcome::RotationalEnergy {
            initial: 0.0,
            r#final: 0.0,
            loss: 0.0,
        });
        TorsionalResponse {
            final_velocity: TorsionalVelocityOut {
                normal: o.final_normal_velocity,
                spin: o.final_spin,
            },
            impulse: TorsionalImpulseOut {
                normal: o.normal_impulse,
                torsional: o.torsional_impulse,
            },
            regime: match o.regime {
                TorsionalRegime::Sliding => TorsionalRegimeDto::Sliding,
                TorsionalRegime::Restitution => TorsionalRegimeDto::Restitution,
            },
            switch_spin: o.switch_spin,
            energy: RotationalEnergyOut {
                initial: energy.initial,
                final_: energy.r#final,
                loss: energy.loss,
            },
            precision: precision.into(),
        }
    }
}

impl From<crate::outcome::TorsionalRegime> for TorsionalRegimeDto {
    fn from(r: crate::outcome::TorsionalRegime) -> Self {
        match r {
            crate::outcome::TorsionalRegime::Restitution => TorsionalRegimeDto::Restitution,
            crate::outcome::TorsionalRegime::Sliding => TorsionalRegimeDto::Sliding,
        }
    }
}
