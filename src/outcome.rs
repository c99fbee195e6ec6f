//! What an impact answers: the outcome types of the planar and torsional
//! cases, and which optional outputs a caller asks for.

use crate::scene::{ContactVelocity, PlanarVelocity};

/// Which tangential law produced a planar answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Regime {
    /// No tangential impulse (`μ = 0`).
    #[default]
    Frictionless,
    /// A prescribed impulse ratio `μ`, or the two-phase ratios `μ_A`, `μ_R`.
    Prescribed,
    /// Coulomb sliding through separation, `|μ| = f`.
    Sliding,
    /// Coulomb friction stops the slip: `μ = μ_c`, `V_ct = 0` ("rolling").
    Sticking,
    /// Tangential restitution: `V_ct = −e_t v_ct` (Eq 20), `|μ| ≤ f`.
    Restitution,
}

impl Regime {
    /// The regime's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            Regime::Frictionless => "frictionless",
            Regime::Prescribed => "prescribed",
            Regime::Sliding => "sliding",
            Regime::Sticking => "sticking",
            Regime::Restitution => "restitution",
        }
    }
}

/// Impulses the barrier applies to the body at the contact point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Impulse {
    /// Normal impulse `P_n ≥ 0`.
    pub normal: f64,
    /// Tangential impulse `P_t`.
    pub tangential: f64,
}

/// Initial and final contact-point velocities.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactVelocities {
    /// `(v_cn, v_ct)`.
    pub initial: ContactVelocity,
    /// `(V_cn, V_ct)`.
    pub r#final: ContactVelocity,
}

/// Which optional outputs a caller wants. The solver skips the rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Outputs {
    /// Compute the critical impulse ratio `μ_c` even where the law does not need it.
    pub critical_impulse_ratio: bool,
    /// Compute the energies (initial, final, `T_M`, `T_L*`). The sign of `T_L`
    /// is always checked, because no answer may create energy.
    pub energy: bool,
}

impl Outputs {
    /// Every output.
    pub const ALL: Outputs = Outputs {
        critical_impulse_ratio: true,
        energy: true,
    };
    /// Only what every answer carries (velocities, impulses, `μ`, `e`, `R`, regime).
    pub const MINIMAL: Outputs = Outputs {
        critical_impulse_ratio: false,
        energy: false,
    };
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs::ALL
    }
}

/// The outcome of a planar impact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarOutcome {
    /// Final velocities `V_n`, `V_t`, `Ω`.
    pub final_velocity: PlanarVelocity,
    /// Initial and final contact-point velocities.
    pub contact_velocity: ContactVelocities,
    /// Impulses `P_n`, `P_t`.
    pub impulse: Impulse,
    /// Applied impulse ratio `μ = P_t / P_n` (Eq 4).
    pub impulse_ratio: f64,
    /// Critical impulse ratio `μ_c` (the ratio that ends with `V_ct = 0`),
    /// when asked for or needed by the law.
    pub critical_impulse_ratio: Option<f64>,
    /// Kinematic coefficient of restitution `e` (Eq 1).
    pub restitution: f64,
    /// Kinetic coefficient of restitution `R` (Eq 9).
    pub kinetic_restitution: f64,
    /// The law that produced the answer.
    pub regime: Regime,
    /// Energies, when asked for.
    pub energy: Option<PlanarEnergy>,
}

/// Kinetic energies of a planar answer.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarEnergy {
    /// Initial kinetic energy `½ m (v_n² + v_t²) + ½ I ω²`.
    pub initial: f64,
    /// Final kinetic energy `½ m (V_n² + V_t²) + ½ I Ω²`.
    pub r#final: f64,
    /// Energy loss `T_L` (Eq 8 in work form), `≥ 0` for every accepted answer.
    pub loss: f64,
    /// Maximum loss `T_M`: the loss when the contact point stops (`e = 0`, `V_ct = 0`).
    pub max_loss: f64,
    /// `T_L* = T_L / T_M` (Appendix), in `[0, 1]` for every accepted answer.
    pub normalized_loss: f64,
}

/// Which branch of the torsional model applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum TorsionalRegime {
    #[default]
    /// `|ω_n| ≤ ω_s`: `Ω_n = −e_z ω_n` (Eq 28).
    Restitution,
    /// `|ω_n| > ω_s`: rotational sliding through separation (Eq 30).
    Sliding,
}

impl TorsionalRegime {
    /// The regime's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            TorsionalRegime::Restitution => "restitution",
            TorsionalRegime::Sliding => "sliding",
        }
    }
}

/// Rotational kinetic energy about the normal axis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RotationalEnergy {
    /// `½ I_n ω_n²`.
    pub initial: f64,
    /// `½ I_n Ω_n²`.
    pub r#final: f64,
    /// `½ I_n (ω_n − Ω_n)(ω_n + Ω_n) ≥ 0`.
    pub loss: f64,
}

/// The outcome of a torsional impact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TorsionalOutcome {
    /// Final normal velocity `V_n = −e v_n`.
    pub final_normal_velocity: f64,
    /// Final spin `Ω_n`.
    pub final_spin: f64,
    /// Normal impulse `P_n = m (1 + e) |v_n|`.
    pub normal_impulse: f64,
    /// Torsional impulse `M_n = I_n (Ω_n − ω_n)` (Eq 29).
    pub torsional_impulse: f64,
    /// The branch used.
    pub regime: TorsionalRegime,
    /// The switch spin magnitude `ω_s` of Eq 31 (`≥ 0`).
    pub switch_spin: f64,
    /// Rotational energies, when asked for.
    pub energy: Option<RotationalEnergy>,
}

impl Outputs {
    /// The optional outputs that computing `outputs` needs.
    pub fn needed_by(outputs: &[crate::quantity::Output]) -> Self {
        Outputs {
            critical_impulse_ratio: outputs.contains(&crate::quantity::Output::CriticalImpulseRatio),
            energy: outputs.iter().any(|o| o.needs_energy()),
        }
    }
}

/// What one body of a contact in world axes answers.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyOutcome {
    /// Final velocity of the mass centre `(V_x, V_y)`.
    pub velocity: [f64; 2],
    /// Final angular velocity `Ω` (counter-clockwise positive).
    pub angular_velocity: f64,
    /// `ΔV = V − v`.
    pub velocity_change: [f64; 2],
    /// `|ΔV|`, the delta-V of accident reconstruction.
    pub delta_v: f64,
    /// `ΔΩ = Ω − ω`.
    pub angular_velocity_change: f64,
}

/// The impulse on body A (`−P` acts on B).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WorldImpulse {
    /// `P_n = P·n̂ ≥ 0`.
    pub normal: f64,
    /// `P_t = P·t̂`, `t̂ = ẑ × n̂`.
    pub tangential: f64,
    /// World x of `P`.
    pub x: f64,
    /// World y of `P`.
    pub y: f64,
}

/// The outcome of a planar contact between body A and body B or a barrier.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodiesOutcome {
    /// Body A, and body B when there is one.
    pub bodies: [BodyOutcome; 2],
    /// 1 (a barrier) or 2.
    pub body_count: usize,
    /// Relative contact velocity `u = u_A − u_B` along `n̂` and `t̂`, initial and final.
    pub contact_velocity: ContactVelocities,
    /// The impulse on A.
    pub impulse: WorldImpulse,
    /// `μ = P_t / P_n`.
    pub impulse_ratio: f64,
    /// `μ_c`, the ratio of the sticking impulse, when asked for or needed by the law.
    pub critical_impulse_ratio: Option<f64>,
    /// `e` (the equivalent `e` under the kinetic law).
    pub restitution: f64,
    /// `R` (`e` under the kinematic law).
    pub kinetic_restitution: f64,
    /// The branch of the law that answered.
    pub regime: Regime,
    /// Energies of the pair, when asked for.
    pub energy: Option<PlanarEnergy>,
}

/// What one body of a contact in space answers.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialBodyOutcome {
    /// Final velocity of the mass centre.
    pub velocity: [f64; 3],
    /// Final angular velocity.
    pub angular_velocity: [f64; 3],
    /// `ΔV = V − v`.
    pub velocity_change: [f64; 3],
    /// `|ΔV|`.
    pub delta_v: f64,
    /// `ΔΩ = Ω − ω`.
    pub angular_velocity_change: [f64; 3],
}

/// The relative contact velocity in space at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialContactVelocity {
    /// `u·n̂`.
    pub normal: f64,
    /// The slip `u − (u·n̂) n̂`, a world vector.
    pub tangential: [f64; 3],
    /// The relative spin about the normal `(ω_A − ω_B)·n̂`.
    pub spin: f64,
}

/// Initial and final relative contact velocities in space.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialContactVelocities {
    /// Before the impact.
    pub initial: SpatialContactVelocity,
    /// After it.
    pub r#final: SpatialContactVelocity,
}

/// The impulse and couple on body A in space (`−P`, `−M` on B).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialImpulse {
    /// `P_n = P·n̂ > 0`.
    pub normal: f64,
    /// `P_t = P − P_n n̂`, a world vector.
    pub tangential: [f64; 3],
    /// The couple `M` about `n̂` (0 without a twist law).
    pub torsional: f64,
    /// World x of `P`.
    pub x: f64,
    /// World y of `P`.
    pub y: f64,
    /// World z of `P`.
    pub z: f64,
}

/// The outcome of a contact in space between body A and body B or a barrier.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpatialOutcome {
    /// Body A, and body B when there is one.
    pub bodies: [SpatialBodyOutcome; 2],
    /// 1 (a barrier) or 2.
    pub body_count: usize,
    /// Relative contact velocities.
    pub contact_velocity: SpatialContactVelocities,
    /// The impulse and couple on A.
    pub impulse: SpatialImpulse,
    /// `|P_t| / P_n`.
    pub impulse_ratio: f64,
    /// `|P_t| / |P_n|` of the sticking impulse (a magnitude, the quantity the
    /// friction cap compares with `f`), when asked for or sticking (`None`
    /// also where that impulse has `P_n = 0` or its system is singular).
    pub critical_impulse_ratio: Option<f64>,
    /// `e`.
    pub restitution: f64,
    /// The tangential law's branch.
    pub regime: Regime,
    /// The twist law's branch, with a twist law.
    pub torsional_regime: Option<TorsionalRegime>,
    /// Energies of the pair (with the couple's work), when asked for.
    pub energy: Option<PlanarEnergy>,
}
