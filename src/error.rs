//! Typed errors of the solver: every variant names the input or output it is about.

use std::fmt;

pub use crate::quantity::{Input, Output};

/// The interval of impulse ratios `μ` that give a physical answer (`D > 0` and
/// no energy created) for a given scene and `e`. `None` means unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdmissibleInterval {
    /// Lowest admissible `μ`, or `None` for no lower bound.
    pub lower: Option<f64>,
    /// Highest admissible `μ`, or `None` for no upper bound.
    pub upper: Option<f64>,
}

impl AdmissibleInterval {
    /// Whether `mu` lies in the interval (bounds included).
    pub fn contains(&self, mu: f64) -> bool {
        self.lower.is_none_or(|lo| mu >= lo) && self.upper.is_none_or(|hi| mu <= hi)
    }
}

impl fmt::Display for AdmissibleInterval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.lower {
            Some(lo) => write!(f, "[{lo}, ")?,
            None => f.write_str("(-∞, ")?,
        }
        match self.upper {
            Some(hi) => write!(f, "{hi}]"),
            None => f.write_str("∞)"),
        }
    }
}

/// Why the solver gives no answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImpactError {
    /// An input is NaN or infinite.
    #[error("{input} must be a finite number")]
    NotFinite {
        /// The offending input.
        input: Input,
    },
    /// An input that must be strictly positive is not.
    #[error("{input} must be greater than 0, got {value}")]
    NotPositive {
        /// The offending input.
        input: Input,
        /// Its value.
        value: f64,
    },
    /// An input lies outside its closed range.
    #[error("{input} must lie in [{min}, {max}], got {value}")]
    OutOfRange {
        /// The offending input.
        input: Input,
        /// Its value.
        value: f64,
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
    /// An input that only makes sense for a rigid body was given for a point mass.
    #[error("{input} needs a moment of inertia: a point mass has no contact offset and no rotation")]
    NeedsInertia {
        /// The offending input.
        input: Input,
    },
    /// The contact point is not approaching the barrier (or body B), so there is no impact.
    #[error(
        "the contact is not approaching: the normal contact velocity (relative to the barrier or to body B, \
         along the normal out of it) is {normal_contact_velocity}, and an impact needs it below 0"
    )]
    NotApproaching {
        /// The input that sets the approach velocity.
        input: Input,
        /// `v_cn = v_n + d_c ω` (planar) or `v_n` (torsional).
        normal_contact_velocity: f64,
    },
    /// `D ≤ 0`: the rigid-body impulse model has no physical answer.
    #[error(
        "no impulse solution: D = 1 + d_c (d_c − μ d_d) / k² = {d} is not positive at impulse ratio μ = {impulse_ratio}; \
         the normal impulse would be infinite or negative, so the rigid-body impulse model has no physical answer"
    )]
    NoImpulseSolution {
        /// The input whose value leads to `D ≤ 0`.
        input: Input,
        /// The impulse ratio the answer would need.
        impulse_ratio: f64,
        /// `D` at that ratio.
        d: f64,
    },
    /// The answer would create kinetic energy, which is not physical.
    #[error(
        "the impulse ratio μ = {impulse_ratio} would create kinetic energy (T_L = {energy_loss} < 0); \
         the admissible impulse ratios for this scene and e are μ ∈ {admissible}"
    )]
    CreatesEnergy {
        /// The input that leads to the energy-creating ratio.
        input: Input,
        /// The impulse ratio of the rejected answer.
        impulse_ratio: f64,
        /// The (negative) energy loss of the rejected answer.
        energy_loss: f64,
        /// Impulse ratios that would be admissible.
        admissible: AdmissibleInterval,
    },
    /// A direction that is the zero vector (a contact normal).
    #[error("{input} must not be the zero vector")]
    ZeroVector {
        /// The offending input.
        input: Input,
    },
    /// An inertia tensor that is not symmetric positive definite.
    #[error(
        "{input} must be a symmetric positive definite tensor: its leading principal minor of order {order} \
         (I_xx, I_xx I_yy − I_xy², det I) is {minor}, not positive"
    )]
    NotPositiveDefinite {
        /// The tensor.
        input: Input,
        /// The order (1–3) of the first leading minor that is not positive.
        order: u8,
        /// Its value (rounded).
        minor: f64,
    },
    /// An inertia tensor whose principal moments break the triangle
    /// inequality: no rigid body has it.
    #[error(
        "{input} is not the inertia of a rigid body: its principal moments {moments:?} break the triangle \
         inequality (the largest, {largest}, exceeds the sum of the other two, {others}, by more than the \
         relative tolerance 1e-9); every body's principal moments are each at most the sum of the other two"
    )]
    NotRigidInertia {
        /// The tensor.
        input: Input,
        /// Its principal moments, ascending (rounded).
        moments: [f64; 3],
        /// The largest moment.
        largest: f64,
        /// The sum of the other two.
        others: f64,
    },
    /// `D ≤ 0` in space: the branches the law chose have no positive normal impulse.
    #[error(
        "no impulse solution: under the law and branches that apply ({input}), the normal impulse would be \
         zero, negative or infinite (D ≤ 0), so the rigid-body impulse model has no physical answer"
    )]
    NoImpulse {
        /// The law member whose branch has no solution.
        input: Input,
    },
    /// An answer in space that would create kinetic energy.
    #[error(
        "the answer under {input} would create kinetic energy (T_L = {energy_loss} < 0), which is not physical"
    )]
    EnergyCreated {
        /// The law member whose answer creates energy.
        input: Input,
        /// The (negative) energy loss of the rejected answer.
        energy_loss: f64,
    },
    /// A prescribed impulse ratio with no direction to act in.
    #[error(
        "{input} > 0 has no direction: there is no initial slip and the sticking impulse has no tangential part, \
         so the direction of the tangential impulse is undefined"
    )]
    NoSlipDirection {
        /// The prescribed ratio.
        input: Input,
    },
    /// A law, or a combination of laws, that this case does not offer.
    #[error("{input} is not available here: {reason}")]
    Unavailable {
        /// The law member.
        input: Input,
        /// Why.
        reason: &'static str,
    },
    /// The tangential and twist laws do not single out one combination of branches.
    #[error(
        "the regime is not unique: {combinations} combinations of the tangential and twist branches satisfy \
         their conditions, and exactly one must (each kept branch within its cap, each sliding branch only \
         where its kept branch fails)"
    )]
    NotUnique {
        /// The twist law.
        input: Input,
        /// How many combinations were valid (0, or 2 and more).
        combinations: usize,
    },
    /// An output's exact value does not fit in a finite f64.
    #[error("the output {output} is not representable as a finite double for these inputs")]
    OutputNotFinite {
        /// The offending output.
        output: Output,
    },
}

impl ImpactError {
    /// The input the error is about, if any.
    pub fn input(&self) -> Option<Input> {
        match self {
            ImpactError::NotFinite { input }
            | ImpactError::NotPositive { input, .. }
            | ImpactError::OutOfRange { input, .. }
            | ImpactError::NeedsInertia { input }
            | ImpactError::ZeroVector { input }
            | ImpactError::NotApproaching { input, .. }
            | ImpactError::NoImpulseSolution { input, .. }
            | ImpactError::CreatesEnergy { input, .. }
            | ImpactError::NotPositiveDefinite { input, .. }
            | ImpactError::NotRigidInertia { input, .. }
            | ImpactError::NoImpulse { input }
            | ImpactError::EnergyCreated { input, .. }
            | ImpactError::NoSlipDirection { input }
            | ImpactError::Unavailable { input, .. }
            | ImpactError::NotUnique { input, .. } => Some(*input),
            ImpactError::OutputNotFinite { .. } => None,
        }
    }

    /// The output the error is about, if any.
    pub fn output(&self) -> Option<Output> {
        match self {
            ImpactError::OutputNotFinite { output } => Some(*output),
            _ => None,
        }
    }

    /// A short, stable title for the kind of error.
    pub fn title(&self) -> &'static str {
        match self {
            ImpactError::NotFinite { .. } => "Input is not finite",
            ImpactError::NotPositive { .. } => "Input must be positive",
            ImpactError::OutOfRange { .. } => "Input out of range",
            ImpactError::NeedsInertia { .. } => "Input needs a moment of inertia",
            ImpactError::ZeroVector { .. } => "Direction is zero",
            ImpactError::NotApproaching { .. } => "Contact is not approaching",
            ImpactError::NoImpulseSolution { .. } => "No impulse solution",
            ImpactError::CreatesEnergy { .. } | ImpactError::EnergyCreated { .. } => {
                "Answer would create energy"
            }
            ImpactError::NotPositiveDefinite { .. } => "Inertia tensor is not positive definite",
            ImpactError::NotRigidInertia { .. } => "Inertia tensor is not a rigid body's",
            ImpactError::NoImpulse { .. } => "No impulse solution",
            ImpactError::NoSlipDirection { .. } => "Sliding direction is undefined",
            ImpactError::NotUnique { .. } => "Regime is not unique",
            ImpactError::Unavailable { .. } => "Law is not available here",
            ImpactError::OutputNotFinite { .. } => "Output is not finite",
        }
    }

    /// A stable machine-readable slug for the kind of error.
    pub fn slug(&self) -> &'static str {
        match self {
            ImpactError::NotFinite { .. } => "not-finite",
            ImpactError::NotPositive { .. } => "not-positive",
            ImpactError::OutOfRange { .. } => "out-of-range",
            ImpactError::NeedsInertia { .. } => "needs-inertia",
            ImpactError::ZeroVector { .. } => "zero-vector",
            ImpactError::NotApproaching { .. } => "not-approaching",
            ImpactError::NoImpulseSolution { .. } => "no-impulse-solution",
            ImpactError::CreatesEnergy { .. } | ImpactError::EnergyCreated { .. } => "creates-energy",
            ImpactError::NotPositiveDefinite { .. } => "not-positive-definite",
            ImpactError::NotRigidInertia { .. } => "not-rigid-inertia",
            ImpactError::NoImpulse { .. } => "no-impulse-solution",
            ImpactError::NoSlipDirection { .. } => "no-slip-direction",
            ImpactError::NotUnique { .. } => "not-unique",
            ImpactError::Unavailable { .. } => "law-unavailable",
            ImpactError::OutputNotFinite { .. } => "output-not-finite",
        }
    }
}

/// Result type of the solver.
pub type Result<T> = std::result::Result<T, ImpactError>;

/// Checks that `value` is finite.
pub(crate) fn finite(input: Input, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ImpactError::NotFinite { input })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(input: Input, value: f64) -> Result<f64> {
    finite(input, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ImpactError::NotPositive { input, value })
    }
}

/// Checks that `value` is finite and in `[min, max]`.
pub(crate) fn in_range(input: Input, value: f64, min: f64, max: f64) -> Result<f64> {
    finite(input, value)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(ImpactError::OutOfRange {
            input,
            value,
            min,
            max,
        })
    }
}

/// Checks that a computed output is finite.
pub(crate) fn finite_output(output: Output, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ImpactError::OutputNotFinite { output })
    }
}
