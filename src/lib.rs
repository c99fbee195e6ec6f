//! # restitution
//!
//! Exact, fast rigid-body point-collision computation after R. M. Brach,
//! "Restitution in Point Collisions" (1991): a rigid lamina (or a point mass)
//! strikes a massive barrier at one point; coefficients of restitution and
//! friction give the final velocities, the impulses and the energy loss.
//!
//! The solver (every module but `http`) is pure: no I/O, no async, no
//! allocation per impact. One module per physical case:
//!
//! - [`normal`]: point mass or frictionless rigid body (section 2.1);
//! - [`oblique`]: prescribed impulse ratio, Coulomb friction, or the
//!   Appendix's kinetic restitution (Eqs 1–19, A-1…A-16);
//! - [`tangential`]: the bilinear tangential-restitution model (Eqs 20–27);
//! - [`torsional`]: the bilinear torsional model (Eqs 28–31);
//! - [`exact`]: the `exact` precision mode, correctly rounded outputs by
//!   double-double arithmetic with a certified bound and a rational fallback;
//! - [`sweep`]: any case over a grid of inputs, in parallel, computing only
//!   the chosen outputs;
//!
//! with the shared pieces in [`scene`] (frame, contact kinematics),
//! [`planar`] (impulse answers, critical ratio, admissible ratios),
//! [`energy`], [`linear`] (the nalgebra 3×3 cross-check) and [`error`].
//!
//! Conventions, derivations and every departure from the printed paper are in
//! `docs/physics.md`.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod energy;
pub mod error;
pub mod exact;
pub mod fit;
pub mod linear;
pub mod normal;
pub mod oblique;
pub mod planar;
pub mod scene;
pub mod sweep;
pub mod tangential;
pub mod torsional;

#[cfg(feature = "server")]
pub mod http;

pub use error::{AdmissibleInterval, ImpactError, Input, Output};
pub use exact::Precision;
pub use planar::{Outputs, PlanarOutcome, Regime};
pub use scene::{Body, Contact, ContactVelocity, PlanarScene, PlanarVelocity};
