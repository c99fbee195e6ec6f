//! # restitution
//!
//! Exact, fast rigid-body point-collision computation after R. M. Brach,
//! "Restitution in Point Collisions" (1991): bodies meet at one point — a
//! lamina or a point mass against a massive barrier in the paper's frame, a
//! body spinning about the normal, two laminae in world axes, or rigid bodies
//! in space with inertia tensors and a twist law — and coefficients of
//! restitution and friction give the final velocities, the impulses and the
//! energy loss.
//!
//! The solver (every module but `http`) is pure: no I/O, no async, no
//! allocation per impact. A request flows through:
//!
//! - [`input`]: what an impact is given, per case ([`BarrierImpact`] with its
//!   [`Law`], [`TorsionalImpact`], [`BodiesImpact`], [`SpatialImpact`]);
//! - [`impact`]: the front door. What each case reads ([`Case`]) and
//!   [`solve`]: validation, the fast range check, the choice of arithmetic,
//!   escalation to exact;
//! - `model` (`src/model/`): the laws of the paper written once, over any arithmetic
//!   (Eqs 1–31, A-1…A-16);
//! - `arith` (`src/arith/`): the arithmetics (plain f64 for `fast`; compensated,
//!   double-double and exact fractions for `exact`);
//!
//! with the shared pieces in [`scene`] (frame, contact kinematics, `D(μ)`, the
//! admissible impulse ratios), [`outcome`] (what an impact answers, and each
//! outcome's declaration of its outputs),
//! [`quantity`] (every input and output with its symbol and path) and
//! [`error`]. Around them: [`sweep`] (any case over a grid of inputs, in
//! parallel, computing only the chosen outputs), [`fit`] (coefficients
//! identified from measured impacts) and [`plot`] (SVG figures, with the
//! `plot` feature).
//!
//! Conventions, derivations and every departure from the printed paper are in
//! `docs/physics.md`.
//!
//! ```
//! use restitution::{Contact, Law, Outputs, BarrierImpact, PlanarVelocity, Precision, solve};
//!
//! let disc = BarrierImpact::rigid(
//!     1.0,                    // m (kg)
//!     0.00125,                // I = m k² (kg·m²)
//!     Contact::central(0.05), // G 0.05 m above the contact point
//!     PlanarVelocity { normal: -1.0, tangential: 0.4, angular: 0.0 },
//!     Law::Friction { restitution: 0.93, friction: 0.123 },
//! );
//! let outcome = solve(&disc, Outputs::ALL, Precision::Exact)?;
//! println!("{:?} {}", outcome.regime, outcome.contact_velocity.r#final.tangential);
//! # Ok::<(), restitution::ImpactError>(())
//! ```
#![warn(missing_docs)]
// Unsafe code only where `kernels` calls the copy compiled for the CPU's features.
#![deny(unsafe_code)]

pub mod accuracy;
pub(crate) mod arith;
pub mod error;
pub mod fit;
pub mod impact;
pub mod input;
pub mod kernels;
pub mod law;
pub(crate) mod model;
pub mod outcome;
#[cfg(feature = "plot")]
pub mod plot;
pub mod quantity;
#[cfg(test)]
pub(crate) use restitution_testkit::rng;
pub mod scene;
pub mod sweep;

#[cfg(feature = "server")]
pub mod http;

pub use accuracy::{ErrorScales, PROMISED_RELATIVE_ERROR};
pub use error::{AdmissibleInterval, ImpactError, Input, Output, Result};
pub use impact::{
    BarrierBody, BarrierImpact, BodiesImpact, Case, Lamina, Law, PlanarContact, Precision, RigidBody,
    SpatialContact, SpatialImpact, TorsionalImpact, Twist, solve, solve_many,
};
pub use outcome::{
    Answers, BarrierOutcome, BodiesOutcome, BodyOutcome, Outputs, Regime, SpatialBodyOutcome, SpatialOutcome,
    TorsionalOutcome, TorsionalRegime, WorldImpulse,
};
pub use scene::{BarrierScene, Body, Contact, ContactVelocity, PlanarVelocity};

/// The earlier names of one body against a barrier (the paper's frame),
/// kept for callers: "planar" now names the contact in the plane in world
/// axes (`POST /v1/impacts/planar`, [`BodiesImpact`]).
#[allow(deprecated)]
pub use deprecated_names::*;

mod deprecated_names {
    #![allow(missing_docs)]
    #[deprecated(note = "renamed `BarrierImpact`: one body against a barrier")]
    pub type PlanarImpact = crate::BarrierImpact;
    #[deprecated(note = "renamed `BarrierBody`")]
    pub type PlanarBody = crate::BarrierBody;
    #[deprecated(note = "renamed `BarrierOutcome`")]
    pub type PlanarOutcome = crate::BarrierOutcome;
    #[deprecated(note = "renamed `BarrierScene`")]
    pub type PlanarScene = crate::BarrierScene;
}
