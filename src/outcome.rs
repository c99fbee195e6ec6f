//! What an impact answers: the outcome type of each case, the one
//! declaration of which outputs each answers and how each is read off it
//! ([`Answers`]), and which optional outputs a caller asks for.

use crate::quantity::{Output, Value};
use crate::scene::{ContactVelocity, PlanarVelocity};

/// The earlier name of [`BarrierOutcome`], kept for callers.
#[allow(deprecated)]
pub use crate::deprecated_names::PlanarOutcome;

/// An outcome type's outputs, declared once by `answers!`: the outputs it
/// answers in response order, and how each is read off an outcome. Every
/// list of a case's outputs (its response, its sweep columns, the model's
/// names for the outputs it writes) is taken from here.
pub trait Answers: Sized {
    /// Every output, in response order.
    const OUTPUTS: &'static [Output];
    /// How to read `output` off an outcome; `None` for an output this
    /// outcome does not answer (another case's). A number is `NaN` when the
    /// impact did not compute it (an optional output not asked for, body B
    /// of a barrier impact).
    fn reader(output: Output) -> Option<fn(&Self) -> Value>;
    /// How to read `output`'s column off many outcomes, `cells[i]` from
    /// `outcomes[i]` (the two equally long): one call per column of a block
    /// of a sweep, the read inlined into its loop, rather than one call per
    /// point and column. `None` for an output of another case.
    fn column(output: Output) -> Option<ColumnReader<Self>>;
    /// How to read a number output's column off many outcomes straight into
    /// numbers, `values[i]` from `outcomes[i]` (`NaN` where
    /// [`Answers::column`] gives a name): for an encoder that writes typed
    /// columns (Arrow), without a cell between. `None` for an output of
    /// another case.
    fn numbers(output: Output) -> Option<NumberReader<Self>>;
    /// One output's value, `None` for an output of another case.
    #[inline]
    fn value(&self, output: Output) -> Option<Value> {
        Self::reader(output).map(|read| read(self))
    }
}

/// Reads one output's column off many outcomes into as many cells ([`Answers::column`]).
pub type ColumnReader<O> = fn(&[O], &mut [Value]);

/// Reads one number output's column off many outcomes into as many numbers ([`Answers::numbers`]).
pub type NumberReader<O> = fn(&[O], &mut [f64]);

/// Implements [`Answers`] for an outcome type from one list of
/// `Output => |outcome| value` entries, in response order.
macro_rules! answers {
    ($outcome:ty { $($output:ident => |$o:ident| $read:expr,)* }) => {
        impl Answers for $outcome {
            const OUTPUTS: &'static [Output] = &[$(Output::$output,)*];

            #[inline]
            fn reader(output: Output) -> Option<fn(&Self) -> Value> {
                match output {
                    $(Output::$output => Some(|$o: &Self| Value::from($read)),)*
                    _ => None,
                }
            }

            #[inline]
            fn column(output: Output) -> Option<ColumnReader<Self>> {
                match output {
                    $(Output::$output => Some(|outcomes: &[Self], cells: &mut [Value]| {
                        for ($o, cell) in outcomes.iter().zip(cells) {
                            *cell = Value::from($read);
                        }
                    }),)*
                    _ => None,
                }
            }

            #[inline]
            fn numbers(output: Output) -> Option<NumberReader<Self>> {
                match output {
                    $(Output::$output => Some(|outcomes: &[Self], values: &mut [f64]| {
                        for ($o, value) in outcomes.iter().zip(values) {
                            *value = Value::from($read).number();
                        }
                    }),)*
                    _ => None,
                }
            }
        }
    };
}

/// An optional number read off an outcome: `NaN` when it was not computed.
#[inline]
fn or_nan<T>(part: Option<T>, read: impl FnOnce(T) -> f64) -> f64 {
    part.map_or(f64::NAN, read)
}

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
pub struct BarrierOutcome {
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

answers!(BarrierOutcome {
    FinalNormalVelocity => |o| o.final_velocity.normal,
    FinalTangentialVelocity => |o| o.final_velocity.tangential,
    FinalAngularVelocity => |o| o.final_velocity.angular,
    InitialNormalContactVelocity => |o| o.contact_velocity.initial.normal,
    InitialTangentialContactVelocity => |o| o.contact_velocity.initial.tangential,
    FinalNormalContactVelocity => |o| o.contact_velocity.r#final.normal,
    FinalTangentialContactVelocity => |o| o.contact_velocity.r#final.tangential,
    NormalImpulse => |o| o.impulse.normal,
    TangentialImpulse => |o| o.impulse.tangential,
    ImpulseRatio => |o| o.impulse_ratio,
    CriticalImpulseRatio => |o| o.critical_impulse_ratio.unwrap_or(f64::NAN),
    Restitution => |o| o.restitution,
    KineticRestitution => |o| o.kinetic_restitution,
    Regime => |o| o.regime.as_str(),
    InitialEnergy => |o| or_nan(o.energy, |e| e.initial),
    FinalEnergy => |o| or_nan(o.energy, |e| e.r#final),
    EnergyLoss => |o| or_nan(o.energy, |e| e.loss),
    MaxEnergyLoss => |o| or_nan(o.energy, |e| e.max_loss),
    NormalizedEnergyLoss => |o| or_nan(o.energy, |e| e.normalized_loss),
});

answers!(TorsionalOutcome {
    FinalNormalVelocity => |o| o.final_normal_velocity,
    FinalSpin => |o| o.final_spin,
    NormalImpulse => |o| o.normal_impulse,
    TorsionalImpulse => |o| o.torsional_impulse,
    Regime => |o| o.regime.as_str(),
    SwitchSpin => |o| o.switch_spin,
    InitialEnergy => |o| or_nan(o.energy, |e| e.initial),
    FinalEnergy => |o| or_nan(o.energy, |e| e.r#final),
    EnergyLoss => |o| or_nan(o.energy, |e| e.loss),
});

impl BodiesOutcome {
    /// A number of body `k`'s outcome, `NaN` where there is no body `k`.
    #[inline]
    fn body(&self, k: usize, read: impl FnOnce(&BodyOutcome) -> f64) -> f64 {
        or_nan(self.bodies.get(k).filter(|_| k < self.body_count), read)
    }
}

answers!(BodiesOutcome {
    FinalVelocityAX => |o| o.body(0, |b| b.velocity[0]),
    FinalVelocityAY => |o| o.body(0, |b| b.velocity[1]),
    FinalAngularVelocityA => |o| o.body(0, |b| b.angular_velocity),
    VelocityChangeAX => |o| o.body(0, |b| b.velocity_change[0]),
    VelocityChangeAY => |o| o.body(0, |b| b.velocity_change[1]),
    DeltaVA => |o| o.body(0, |b| b.delta_v),
    AngularVelocityChangeA => |o| o.body(0, |b| b.angular_velocity_change),
    FinalVelocityBX => |o| o.body(1, |b| b.velocity[0]),
    FinalVelocityBY => |o| o.body(1, |b| b.velocity[1]),
    FinalAngularVelocityB => |o| o.body(1, |b| b.angular_velocity),
    VelocityChangeBX => |o| o.body(1, |b| b.velocity_change[0]),
    VelocityChangeBY => |o| o.body(1, |b| b.velocity_change[1]),
    DeltaVB => |o| o.body(1, |b| b.delta_v),
    AngularVelocityChangeB => |o| o.body(1, |b| b.angular_velocity_change),
    InitialNormalContactVelocity => |o| o.contact_velocity.initial.normal,
    InitialTangentialContactVelocity => |o| o.contact_velocity.initial.tangential,
    FinalNormalContactVelocity => |o| o.contact_velocity.r#final.normal,
    FinalTangentialContactVelocity => |o| o.contact_velocity.r#final.tangential,
    NormalImpulse => |o| o.impulse.normal,
    TangentialImpulse => |o| o.impulse.tangential,
    ImpulseX => |o| o.impulse.x,
    ImpulseY => |o| o.impulse.y,
    ImpulseRatio => |o| o.impulse_ratio,
    CriticalImpulseRatio => |o| o.critical_impulse_ratio.unwrap_or(f64::NAN),
    Restitution => |o| o.restitution,
    KineticRestitution => |o| o.kinetic_restitution,
    Regime => |o| o.regime.as_str(),
    InitialEnergy => |o| or_nan(o.energy, |e| e.initial),
    FinalEnergy => |o| or_nan(o.energy, |e| e.r#final),
    EnergyLoss => |o| or_nan(o.energy, |e| e.loss),
    MaxEnergyLoss => |o| or_nan(o.energy, |e| e.max_loss),
    NormalizedEnergyLoss => |o| or_nan(o.energy, |e| e.normalized_loss),
});

/// Each body's outputs of the two-body planar case (velocity, angular
/// velocity, velocity change, delta-V, angular velocity change), as the
/// model names them: the first fourteen of [`BodiesOutcome`]'s declaration.
pub(crate) const BODY_OUTPUTS: [[Output; 7]; 2] = [
    crate::quantity::part(BodiesOutcome::OUTPUTS, 0),
    crate::quantity::part(BodiesOutcome::OUTPUTS, 7),
];

impl SpatialOutcome {
    /// A number of body `k`'s outcome, `NaN` where there is no body `k`.
    #[inline]
    fn body(&self, k: usize, read: impl FnOnce(&SpatialBodyOutcome) -> f64) -> f64 {
        or_nan(self.bodies.get(k).filter(|_| k < self.body_count), read)
    }
}

answers!(SpatialOutcome {
    FinalVelocityAX => |o| o.body(0, |b| b.velocity[0]),
    FinalVelocityAY => |o| o.body(0, |b| b.velocity[1]),
    FinalVelocityAZ => |o| o.body(0, |b| b.velocity[2]),
    FinalAngularVelocityAX => |o| o.body(0, |b| b.angular_velocity[0]),
    FinalAngularVelocityAY => |o| o.body(0, |b| b.angular_velocity[1]),
    FinalAngularVelocityAZ => |o| o.body(0, |b| b.angular_velocity[2]),
    VelocityChangeAX => |o| o.body(0, |b| b.velocity_change[0]),
    VelocityChangeAY => |o| o.body(0, |b| b.velocity_change[1]),
    VelocityChangeAZ => |o| o.body(0, |b| b.velocity_change[2]),
    DeltaVA => |o| o.body(0, |b| b.delta_v),
    AngularVelocityChangeAX => |o| o.body(0, |b| b.angular_velocity_change[0]),
    AngularVelocityChangeAY => |o| o.body(0, |b| b.angular_velocity_change[1]),
    AngularVelocityChangeAZ => |o| o.body(0, |b| b.angular_velocity_change[2]),
    FinalVelocityBX => |o| o.body(1, |b| b.velocity[0]),
    FinalVelocityBY => |o| o.body(1, |b| b.velocity[1]),
    FinalVelocityBZ => |o| o.body(1, |b| b.velocity[2]),
    FinalAngularVelocityBX => |o| o.body(1, |b| b.angular_velocity[0]),
    FinalAngularVelocityBY => |o| o.body(1, |b| b.angular_velocity[1]),
    FinalAngularVelocityBZ => |o| o.body(1, |b| b.angular_velocity[2]),
    VelocityChangeBX => |o| o.body(1, |b| b.velocity_change[0]),
    VelocityChangeBY => |o| o.body(1, |b| b.velocity_change[1]),
    VelocityChangeBZ => |o| o.body(1, |b| b.velocity_change[2]),
    DeltaVB => |o| o.body(1, |b| b.delta_v),
    AngularVelocityChangeBX => |o| o.body(1, |b| b.angular_velocity_change[0]),
    AngularVelocityChangeBY => |o| o.body(1, |b| b.angular_velocity_change[1]),
    AngularVelocityChangeBZ => |o| o.body(1, |b| b.angular_velocity_change[2]),
    InitialNormalContactVelocity => |o| o.contact_velocity.initial.normal,
    InitialTangentialContactVelocityX => |o| o.contact_velocity.initial.tangential[0],
    InitialTangentialContactVelocityY => |o| o.contact_velocity.initial.tangential[1],
    InitialTangentialContactVelocityZ => |o| o.contact_velocity.initial.tangential[2],
    InitialContactSpin => |o| o.contact_velocity.initial.spin,
    FinalNormalContactVelocity => |o| o.contact_velocity.r#final.normal,
    FinalTangentialContactVelocityX => |o| o.contact_velocity.r#final.tangential[0],
    FinalTangentialContactVelocityY => |o| o.contact_velocity.r#final.tangential[1],
    FinalTangentialContactVelocityZ => |o| o.contact_velocity.r#final.tangential[2],
    FinalContactSpin => |o| o.contact_velocity.r#final.spin,
    NormalImpulse => |o| o.impulse.normal,
    TangentialImpulseX => |o| o.impulse.tangential[0],
    TangentialImpulseY => |o| o.impulse.tangential[1],
    TangentialImpulseZ => |o| o.impulse.tangential[2],
    TorsionalImpulse => |o| o.impulse.torsional,
    ImpulseX => |o| o.impulse.x,
    ImpulseY => |o| o.impulse.y,
    ImpulseZ => |o| o.impulse.z,
    ImpulseRatio => |o| o.impulse_ratio,
    CriticalImpulseRatio => |o| o.critical_impulse_ratio.unwrap_or(f64::NAN),
    Restitution => |o| o.restitution,
    Regime => |o| o.regime.as_str(),
    TorsionalRegime => |o| o.torsional_regime.map_or(Value::Number(f64::NAN), |r| Value::Text(r.as_str())),
    InitialEnergy => |o| or_nan(o.energy, |e| e.initial),
    FinalEnergy => |o| or_nan(o.energy, |e| e.r#final),
    EnergyLoss => |o| or_nan(o.energy, |e| e.loss),
    MaxEnergyLoss => |o| or_nan(o.energy, |e| e.max_loss),
    NormalizedEnergyLoss => |o| or_nan(o.energy, |e| e.normalized_loss),
});

/// Each body's outputs in space (velocity, angular velocity, velocity
/// change, delta-V, angular velocity change), as the model names them: the
/// first twenty-six of [`SpatialOutcome`]'s declaration.
pub(crate) const SPATIAL_BODY_OUTPUTS: [[Output; 13]; 2] = [
    crate::quantity::part(SpatialOutcome::OUTPUTS, 0),
    crate::quantity::part(SpatialOutcome::OUTPUTS, 13),
];

#[cfg(test)]
mod tests;
