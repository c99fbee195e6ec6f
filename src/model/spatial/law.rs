//! The branches of the tangential and twist laws in space, and the impulse
//! and couple of one combination of them. How a law reads as branches is
//! [`crate::law::Reading`].

use super::*;

/// A branch of the tangential law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Tangential {
    /// The target `U_t = −e_t u_t` (stick for `e_t = 0`).
    Kept,
    /// `|P_t| = c P_n` opposing the slip (frictionless: `c = 0`).
    Sliding,
}

/// A branch of the twist law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Spin {
    /// No twist law: no couple.
    Off,
    /// `S = −e_z s` (Eq 28).
    Restitution,
    /// `M = −e_z J s − sgn(s) μ_z ρ_p P_n` (Eq 29–30).
    Sliding,
}

/// An impulse and couple `(P, κ)`.
#[derive(Clone)]
pub(super) struct Solution<N> {
    pub(super) p: V3<N>,
    pub(super) kappa: N,
    /// `P·n`.
    pub(super) pn: N,
    /// `P_t = P − (P·n)/ν n`.
    pub(super) pt: V3<N>,
}
