//! The contact laws: each law's variant with its coefficients, their checks,
//! their slots (what a sweep's axis sets), and how the model reads a law as
//! branches of its tangential impulse (`Reading`, one reading for the plane
//! and space). Adding a law whose branches `Reading` can state is its variant
//! here (every match below fails to compile until it learns it) and its wire
//! form (`src/http/impacts/law.rs`); a new kind of branch is also model code
//! (`src/model/contact.rs` in the plane, `src/model/spatial/` in space).

use crate::error::{ImpactError, Input, Result, finite, in_range};
use crate::outcome::Regime;

/// Expands to `$callback! { $args… Restitution | Friction | … }`: the
/// [`Input`]s of every member of every law, in the order the cases list them
/// (the one list of them; a case's `reads!` entry `law => slot` expands to it).
macro_rules! law_members {
    ($callback:ident ! { $($args:tt)* }) => {
        $callback! { $($args)*
            Restitution | Friction | ImpulseRatio | TangentialRestitution | KineticRestitution
            | ApproachImpulseRatio | ApproachFriction | ReboundImpulseRatio
        }
    };
}
pub(crate) use law_members;

/// The tangential law of a rigid-body impact, with its coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// No tangential impulse (`μ = 0`), kinematic restitution `e ∈ [0, 1]` (section 2.1).
    Frictionless {
        /// `e`.
        restitution: f64,
    },
    /// A prescribed impulse ratio `μ = P_t / P_n` (Eqs 2, 4). Refused when it
    /// gives `D ≤ 0` or creates energy; the error states the admissible interval.
    ImpulseRatio {
        /// `e ∈ [0, 1]`.
        restitution: f64,
        /// `μ`.
        impulse_ratio: f64,
    },
    /// Coulomb friction `f ≥ 0`: `μ = μ_c` when `|μ_c| ≤ f` (sticking,
    /// `V_ct = 0`), otherwise `|μ| = f` opposing the initial slip (sliding).
    Friction {
        /// `e ∈ [0, 1]`.
        restitution: f64,
        /// `f ≥ 0`.
        friction: f64,
    },
    /// The bilinear tangential-restitution model (section 3, Eqs 20–27): the
    /// ratio that gives `V_ct = −e_t v_ct` when `|μ| ≤ f`, else sliding.
    TangentialRestitution {
        /// `e ∈ [0, 1]`.
        restitution: f64,
        /// `f ≥ 0`.
        friction: f64,
        /// `e_t ∈ [−1, 1]` (`−1`: no tangential impulse from restitution).
        tangential_restitution: f64,
    },
    /// The Appendix's two-phase kinetic restitution: `R = P_n^R / P_n^A`
    /// (Eq 9) with the approach and rebound impulse ratios (Eqs 12, 13).
    KineticRestitution {
        /// `R ∈ [0, 1]`.
        value: f64,
        /// `μ_A = P_t^A / P_n^A`.
        approach_impulse_ratio: f64,
        /// `μ_R = P_t^R / P_n^R`.
        rebound_impulse_ratio: f64,
    },
    /// The two-phase law with Coulomb friction in the approach phase (in the
    /// plane and in space): the approach sticks when the impulse that ends it with
    /// `U = 0` has `|P_t| ≤ f_A P_n`, else slides with `|P_t| = f_A P_n`; the
    /// rebound is `R` times its normal impulse with ratio `μ_R` along the
    /// approach's tangential direction. With `μ_R = 0` it is the contact of
    /// time-stepping engines (friction capped by the compression impulse,
    /// restitution a frictionless normal impulse).
    KineticFriction {
        /// `R ∈ [0, 1]`.
        value: f64,
        /// `f_A ≥ 0`.
        approach_friction: f64,
        /// `μ_R ≥ 0`.
        rebound_impulse_ratio: f64,
    },
}

impl Law {
    /// The law's coefficients checked in range, in request order.
    pub(crate) fn validate(&self) -> Result<Law> {
        let e = |e| in_range(Input::Restitution, e, 0.0, 1.0);
        let f = |f| in_range(Input::Friction, f, 0.0, f64::INFINITY);
        Ok(match *self {
            Law::Frictionless { restitution } => Law::Frictionless {
                restitution: e(restitution)?,
            },
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => Law::ImpulseRatio {
                restitution: e(restitution)?,
                impulse_ratio: finite(Input::ImpulseRatio, impulse_ratio)? + 0.0,
            },
            Law::Friction {
                restitution,
                friction,
            } => Law::Friction {
                restitution: e(restitution)?,
                friction: f(friction)?,
            },
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => Law::TangentialRestitution {
                restitution: e(restitution)?,
                friction: f(friction)?,
                tangential_restitution: in_range(
                    Input::TangentialRestitution,
                    tangential_restitution,
                    -1.0,
                    1.0,
                )?,
            },
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => Law::KineticRestitution {
                value: in_range(Input::KineticRestitution, value, 0.0, 1.0)?,
                approach_impulse_ratio: finite(Input::ApproachImpulseRatio, approach_impulse_ratio)?,
                rebound_impulse_ratio: finite(Input::ReboundImpulseRatio, rebound_impulse_ratio)?,
            },
            Law::KineticFriction {
                value,
                approach_friction,
                rebound_impulse_ratio,
            } => Law::KineticFriction {
                value: in_range(Input::KineticRestitution, value, 0.0, 1.0)?,
                approach_friction: in_range(Input::ApproachFriction, approach_friction, 0.0, f64::INFINITY)?,
                rebound_impulse_ratio: in_range(
                    Input::ReboundImpulseRatio,
                    rebound_impulse_ratio,
                    0.0,
                    f64::INFINITY,
                )?,
            },
        })
    }

    /// The slot of a coefficient this law reads.
    #[inline]
    pub(crate) fn input_mut(&mut self, input: Input) -> Option<&mut f64> {
        match (self, input) {
            (
                Law::Frictionless { restitution }
                | Law::ImpulseRatio { restitution, .. }
                | Law::Friction { restitution, .. }
                | Law::TangentialRestitution { restitution, .. },
                Input::Restitution,
            ) => Some(restitution),
            (Law::ImpulseRatio { impulse_ratio, .. }, Input::ImpulseRatio) => Some(impulse_ratio),
            (
                Law::Friction { friction, .. } | Law::TangentialRestitution { friction, .. },
                Input::Friction,
            ) => Some(friction),
            (
                Law::TangentialRestitution {
                    tangential_restitution,
                    ..
                },
                Input::TangentialRestitution,
            ) => Some(tangential_restitution),
            (
                Law::KineticRestitution { value, .. } | Law::KineticFriction { value, .. },
                Input::KineticRestitution,
            ) => Some(value),
            (
                Law::KineticRestitution {
                    approach_impulse_ratio,
                    ..
                },
                Input::ApproachImpulseRatio,
            ) => Some(approach_impulse_ratio),
            (
                Law::KineticFriction {
                    approach_friction, ..
                },
                Input::ApproachFriction,
            ) => Some(approach_friction),
            (
                Law::KineticRestitution {
                    rebound_impulse_ratio,
                    ..
                }
                | Law::KineticFriction {
                    rebound_impulse_ratio,
                    ..
                },
                Input::ReboundImpulseRatio,
            ) => Some(rebound_impulse_ratio),
            _ => None,
        }
    }

    /// Every coefficient of the law, zeros after the last.
    #[inline]
    pub(crate) fn coefficients(&self) -> [f64; 3] {
        match *self {
            Law::Frictionless { restitution } => [restitution, 0.0, 0.0],
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => [restitution, impulse_ratio, 0.0],
            Law::Friction {
                restitution,
                friction,
            } => [restitution, friction, 0.0],
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => [restitution, friction, tangential_restitution],
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => [value, approach_impulse_ratio, rebound_impulse_ratio],
            Law::KineticFriction {
                value,
                approach_friction,
                rebound_impulse_ratio,
            } => [value, approach_friction, rebound_impulse_ratio],
        }
    }

    /// The law's name, for messages.
    pub fn describe(&self) -> &'static str {
        match self {
            Law::Frictionless { .. } => "a frictionless rigid body",
            Law::ImpulseRatio { .. } => "a prescribed impulse ratio",
            Law::Friction { .. } => "Coulomb friction",
            Law::TangentialRestitution { .. } => "tangential restitution",
            Law::KineticRestitution { .. } => "two-phase kinetic restitution",
            Law::KineticFriction { .. } => "two-phase kinetic restitution with a Coulomb approach",
        }
    }
}

/// The checks of a law in space: a prescribed ratio and the two-phase
/// ratios are magnitudes there, opposing the slip (conventions, rule 7), and
/// the two-phase laws do not combine with the twist law.
impl Law {
    /// [`Law::validate`] for the contact in space, `twist` telling whether
    /// it has a twist law.
    pub(crate) fn validate_spatial(&self, twist: bool) -> Result<Law> {
        let law = self.validate()?;
        let no_twist = || {
            if twist {
                Err(ImpactError::Unavailable {
                    input: Input::Torsion,
                    reason: "the two-phase kinetic law does not combine with the twist law",
                })
            } else {
                Ok(())
            }
        };
        match law {
            Law::ImpulseRatio { impulse_ratio, .. } => {
                in_range(Input::ImpulseRatio, impulse_ratio, 0.0, f64::INFINITY)?;
            }
            Law::KineticFriction { .. } => no_twist()?,
            Law::KineticRestitution {
                approach_impulse_ratio,
                rebound_impulse_ratio,
                ..
            } => {
                in_range(
                    Input::ApproachImpulseRatio,
                    approach_impulse_ratio,
                    0.0,
                    f64::INFINITY,
                )?;
                in_range(
                    Input::ReboundImpulseRatio,
                    rebound_impulse_ratio,
                    0.0,
                    f64::INFINITY,
                )?;
                no_twist()?;
            }
            Law::Frictionless { .. } | Law::Friction { .. } | Law::TangentialRestitution { .. } => {}
        }
        Ok(law)
    }
}

// How the model reads a law.

/// A law as the model reads it, in the plane and in space alike: the
/// coefficients of its kept and sliding branches, the regimes they report and
/// the members their refusals point at (conventions, rule 9), or its two
/// phases (the models: `src/model/contact.rs`, `src/model/spatial/`).
pub(crate) struct Reading {
    pub(crate) e: f64,
    /// `e_t` of the kept branch (0: stick), when the law has one.
    pub(crate) kept: Option<f64>,
    /// `c` of the sliding branch (`f`, `μ` or 0).
    pub(crate) c: f64,
    /// The cap `f` of a two-branch law.
    pub(crate) cap: f64,
    pub(crate) regimes: (Regime, Regime),
    pub(crate) pointers: (Input, Input),
    /// A prescribed ratio: a zero direction is refused, not dropped.
    pub(crate) prescribed: bool,
    /// The two-phase kinetic law, which the scene answers apart.
    pub(crate) phases: Option<Phases>,
}

/// How the approach phase of the two-phase law picks its tangential impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Approach {
    /// `|P_t^A| = μ_A P_n^A` opposing the slip.
    Ratio(f64),
    /// Coulomb friction `f_A` within the phase: stick (`U = 0` at its end)
    /// when that impulse has `|P_t| ≤ f_A P_n`, else slide against the slip.
    Friction(f64),
}

/// The Appendix's two phases in space (conventions, rule 7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Phases {
    /// `R = P_n^R / P_n^A` (Eq 9).
    pub(crate) r: f64,
    pub(crate) approach: Approach,
    /// `μ_R ≥ 0`: `|P_t^R| = μ_R P_n^R`, along the approach's direction.
    pub(crate) rebound: f64,
}

impl Reading {
    pub(crate) fn of(law: &Law, twist: bool) -> Reading {
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
