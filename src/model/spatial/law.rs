//! The law of a contact in space as the scene reads it: the branches of the
//! tangential and twist laws, their coefficients, and the pointers of their
//! refusals.

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

/// The law's reading: branches, coefficients and the pointers of refusals.
pub(super) struct Reading {
    pub(super) e: f64,
    /// `e_t` of the kept branch (0: stick), when the law has one.
    pub(super) kept: Option<f64>,
    /// `c` of the sliding branch (`f`, `μ` or 0).
    pub(super) c: f64,
    /// The cap `f` of a two-branch law.
    pub(super) cap: f64,
    pub(super) regimes: (Regime, Regime),
    pub(super) pointers: (Input, Input),
    /// A prescribed ratio: a zero direction is refused, not dropped.
    pub(super) prescribed: bool,
    /// The two-phase kinetic law, which the scene answers apart.
    pub(super) phases: Option<Phases>,
}

/// How the approach phase of the two-phase law picks its tangential impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Approach {
    /// `|P_t^A| = μ_A P_n^A` opposing the slip.
    Ratio(f64),
    /// Coulomb friction `f_A` within the phase: stick (`U = 0` at its end)
    /// when that impulse has `|P_t| ≤ f_A P_n`, else slide against the slip.
    Friction(f64),
}

/// The Appendix's two phases in space (conventions, rule 7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Phases {
    /// `R = P_n^R / P_n^A` (Eq 9).
    pub(super) r: f64,
    pub(super) approach: Approach,
    /// `μ_R ≥ 0`: `|P_t^R| = μ_R P_n^R`, along the approach's direction.
    pub(super) rebound: f64,
}

impl Reading {
    pub(super) fn of(law: &Law, twist: bool) -> Reading {
        let single = |e, c, regime, pointer| Reading {
            e,
            kept: None,
            c,
            cap: 0.0,
            regimes: (regime, regime),
            pointers: (pointer, pointer),
            prescribed: regime == Regime::Prescribed,
            phases: None,
        };
        match *law {
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => single(
                restitution,
                impulse_ratio,
                Regime::Prescribed,
                Input::ImpulseRatio,
            ),
            Law::Friction {
                restitution,
                friction,
            } => Reading {
                e: restitution,
                kept: Some(0.0),
                c: friction,
                cap: friction,
                regimes: (Regime::Sticking, Regime::Sliding),
                pointers: (Input::Friction, Input::Friction),
                prescribed: false,
                phases: None,
            },
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => Reading {
                e: restitution,
                kept: Some(tangential_restitution),
                c: friction,
                cap: friction,
                regimes: (Regime::Restitution, Regime::Sliding),
                pointers: (Input::TangentialRestitution, Input::Friction),
                prescribed: false,
                phases: None,
            },
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => Reading {
                phases: Some(Phases {
                    r: value,
                    approach: Approach::Ratio(approach_impulse_ratio),
                    rebound: rebound_impulse_ratio,
                }),
                ..single(
                    value,
                    approach_impulse_ratio,
                    Regime::Prescribed,
                    Input::KineticRestitution,
                )
            },
            Law::KineticFriction {
                value,
                approach_friction,
                rebound_impulse_ratio,
            } => Reading {
                phases: Some(Phases {
                    r: value,
                    approach: Approach::Friction(approach_friction),
                    rebound: rebound_impulse_ratio,
                }),
                cap: approach_friction,
                ..single(value, approach_friction, Regime::Sliding, Input::ApproachFriction)
            },
            Law::Frictionless { restitution } => {
                let pointer = if twist { Input::Torsion } else { Input::Restitution };
                single(restitution, 0.0, Regime::Frictionless, pointer)
            }
        }
    }
}
