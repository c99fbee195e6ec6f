//! What an impact is given: the data of each case's impact — its bodies,
//! contact and law — as plain values. The model (`src/model/`) evaluates
//! them and the front door (`src/impact/`) validates them and says what
//! each case reads; both depend on these types, neither on the other.

/// The earlier names of [`BarrierImpact`] and [`BarrierBody`], kept for callers.
#[allow(deprecated)]
pub use crate::deprecated_names::{PlanarBody, PlanarImpact};
pub use crate::law::Law;
use crate::scene::{Contact, PlanarVelocity};

// One body against a barrier, in the paper's frame (the normal, oblique and tangential endpoints).

/// The body of a planar impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BarrierBody {
    /// A point mass: no inertia, no contact offset, no rotation; its law is
    /// frictionless restitution.
    PointMass {
        /// Mass `m > 0`.
        mass: f64,
    },
    /// A rigid lamina.
    Rigid {
        /// Mass `m > 0`.
        mass: f64,
        /// Centroidal moment of inertia `I = m k² > 0`.
        inertia: f64,
        /// Where the centre of mass sits relative to the contact point.
        contact: Contact,
    },
}

/// A planar impact: a body, its initial velocities and the law of the contact.
///
/// A point mass takes only `velocity.normal`, `velocity.tangential` and a
/// [`Law::Frictionless`] law; any other combination is refused when solved
/// (a spin or a tangential law needs a moment of inertia).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarrierImpact {
    /// The body.
    pub body: BarrierBody,
    /// Initial velocities of the centre of mass and angular velocity.
    pub velocity: PlanarVelocity,
    /// The tangential law and its coefficients.
    pub law: Law,
}

// A body spinning about the contact normal (section 4).

/// A torsional impact: a body spinning about the contact normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsionalImpact {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Moment of inertia about the normal axis `I_n > 0`.
    pub normal_inertia: f64,
    /// Initial normal velocity `v_n < 0`.
    pub normal_velocity: f64,
    /// Initial spin about the normal `ω_n`.
    pub spin: f64,
    /// Kinematic coefficient of restitution `e ∈ [0, 1]`.
    pub restitution: f64,
    /// Torsional coefficient of restitution `e_z ∈ [0, 1]`.
    pub torsional_restitution: f64,
    /// Torsional friction coefficient `μ_z ≥ 0` (a magnitude).
    pub torsional_friction: f64,
    /// Pitch radius `ρ_p > 0` of the torsional friction impulse.
    pub pitch_radius: f64,
}

// Two laminae, or one against a barrier, in world axes (the planar endpoint).

/// A lamina in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lamina {
    /// Mass `m > 0`.
    pub mass: f64,
    /// Moment of inertia about the mass centre, `I > 0`.
    pub inertia: f64,
    /// Position of the mass centre `G`.
    pub position: [f64; 2],
    /// Velocity of the mass centre.
    pub velocity: [f64; 2],
    /// Angular velocity, counter-clockwise positive.
    pub angular_velocity: f64,
}

/// The contact point and the normal from B into A (any non-zero length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarContact {
    /// The contact point `C`.
    pub point: [f64; 2],
    /// The normal `n`, from B into A (out of the barrier).
    pub normal: [f64; 2],
}

/// One point contact between body A and body B, or A and a fixed barrier
/// (`b: None`), under one law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodiesImpact {
    /// Body A.
    pub a: Lamina,
    /// Body B; `None` for a barrier.
    pub b: Option<Lamina>,
    /// The contact.
    pub contact: PlanarContact,
    /// The tangential law with its coefficients.
    pub law: Law,
}

// Bodies in space, in world axes (the spatial endpoint).

/// A rigid body in space, in world axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass `m > 0`.
    pub mass: f64,
    /// The inertia tensor about the mass centre, `[I_xx, I_yy, I_zz, I_xy,
    /// I_xz, I_yz]`, the matrix's own entries (`I_xy = −∫ x y dm`);
    /// symmetric positive definite.
    pub inertia: [f64; 6],
    /// Position of the mass centre `G`.
    pub position: [f64; 3],
    /// Velocity of `G`.
    pub velocity: [f64; 3],
    /// Angular velocity.
    pub angular_velocity: [f64; 3],
}

/// The contact point and the normal from B into A (any non-zero length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialContact {
    /// The contact point `C`.
    pub point: [f64; 3],
    /// The normal `n` from B into A.
    pub normal: [f64; 3],
}

/// The twist law about the normal (section 4 generalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Twist {
    /// `e_z ∈ [0, 1]`.
    pub restitution: f64,
    /// `μ_z ≥ 0`.
    pub friction: f64,
    /// `ρ_p > 0`.
    pub pitch_radius: f64,
}

/// One point contact in space between body A and body B, or A and a fixed
/// barrier (`b: None`), under one tangential law and optionally a twist law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialImpact {
    /// Body A.
    pub a: RigidBody,
    /// Body B; `None` for a barrier.
    pub b: Option<RigidBody>,
    /// The contact.
    pub contact: SpatialContact,
    /// The tangential law (not the planar kinetic one). A prescribed
    /// `impulse_ratio` is a magnitude `μ ≥ 0` opposing the slip.
    pub law: Law,
    /// The twist law, if any.
    pub torsion: Option<Twist>,
}
