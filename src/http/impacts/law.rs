//! The wire form of a contact law, one for every endpoint and sweep: the
//! members `restitution`, `kinetic_restitution` (with `approach_impulse_ratio`
//! or `approach_friction`), `friction`,
//! `impulse_ratio` and `tangential_restitution`, declared once
//! (`law_request!`, which every request taking any law is written in) and
//! read into a [`Law`] by one parser with one set of messages (`law_of`).
//! A law with new members adds them here.

use axum::http::StatusCode;
use serde::Deserialize;
use utoipa::ToSchema;

use crate::http::problem::ApiError;
use crate::impact::Law;

/// The Appendix's two-phase model: kinetic restitution R with phase impulse
/// ratios (in space magnitudes, ≥ 0, along one direction opposing the slip),
/// or Coulomb friction in the approach phase instead of its ratio.
#[derive(Debug, Clone, Copy, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct KineticRestitutionDto {
    /// R = P_n^R / P_n^A: kinetic coefficient of restitution (Eq 9), in [0, 1].
    #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
    pub value: f64,
    /// μ_A = P_t^A / P_n^A: impulse ratio of the approach phase (Eq 12);
    /// give it or `approach_friction`.
    #[schema(example = -0.123)]
    pub approach_impulse_ratio: Option<f64>,
    /// f_A ≥ 0: Coulomb friction within the approach phase, which sticks
    /// when the impulse ending it with no relative contact velocity has
    /// |P_t| ≤ f_A P_n, and otherwise slides against the slip; μ_R is then a
    /// magnitude along the approach's tangential impulse.
    #[schema(minimum = 0.0, example = 0.3)]
    pub approach_friction: Option<f64>,
    /// μ_R = P_t^R / P_n^R: impulse ratio of the rebound phase (Eq 13); ≥ 0
    /// with `approach_friction`.
    #[schema(example = -0.123)]
    pub rebound_impulse_ratio: f64,
}

/// Declares a request that takes any contact law: the struct as written,
/// with every law member appended after its own fields, and its `law()`,
/// the law they name (read by [`law_of`]). `in the plane` or `in space` says
/// how the impulse ratios read (a signed `μ` along `t`, or magnitudes
/// opposing the slip).
macro_rules! law_request {
    (in the plane; $($item:tt)*) => {
        law_request!(@emit [
            /// μ = P_t / P_n: a prescribed signed impulse ratio along the tangent t
            /// (the paper's t; t = ẑ × n in world axes) (Eq 2); refused when it
            /// would create energy.
        ] [
            /// The two-phase kinetic law (Appendix), in place of `restitution` and
            /// a tangential law; `restitution` answers the equivalent e.
        ] $($item)*);
    };
    (in space; $($item:tt)*) => {
        law_request!(@emit [
            /// μ ≥ 0: a prescribed impulse ratio |P_t| / P_n, the tangential
            /// impulse opposing the slip; refused when it would create energy.
            #[schema(minimum = 0.0)]
        ] [
            /// The two-phase kinetic law (Appendix), in place of `restitution` and
            /// a tangential law: in space both impulse ratios are magnitudes (≥ 0)
            /// along one direction opposing the initial slip; `restitution`
            /// answers the equivalent e.
        ] $($item)*);
    };
    (@emit [$($ratio:tt)*] [$($kinetic:tt)*]
        $(#[$meta:meta])*
        pub struct $name:ident { $($fields:tt)* }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $($fields)*
            /// e: kinematic coefficient of restitution (Eq 1), in [0, 1].
            #[schema(minimum = 0.0, maximum = 1.0, example = 0.93)]
            pub restitution: Option<f64>,
            $($kinetic)*
            pub kinetic_restitution: Option<$crate::http::impacts::law::KineticRestitutionDto>,
            /// f: Coulomb friction coefficient (≥ 0), the cap of the tangential
            /// impulse (|P_t| ≤ f P_n).
            #[schema(minimum = 0.0, example = 0.123)]
            pub friction: Option<f64>,
            $($ratio)*
            pub impulse_ratio: Option<f64>,
            /// e_t: tangential coefficient of restitution (Eq 20) in [−1, 1],
            /// with `friction` as its cap; −1 means no tangential impulse.
            #[schema(minimum = -1.0, maximum = 1.0)]
            pub tangential_restitution: Option<f64>,
        }

        impl $name {
            /// The law the request's members name.
            fn law(&self) -> Result<$crate::impact::Law, $crate::http::problem::ApiError> {
                $crate::http::impacts::law::law_of(
                    self.restitution,
                    self.kinetic_restitution,
                    self.friction,
                    self.impulse_ratio,
                    self.tangential_restitution,
                )
            }
        }
    };
}
pub(super) use law_request;

/// A law whose members do not fit together, at the member the conventions name.
pub(super) fn law_problem(pointer: &str, detail: &str) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "tangential-law",
        "The law's members do not fit together",
        detail,
    )
    .at(pointer)
}

/// The law the members of a contact request name (conventions: the second of
/// two tangential members is refused; `tangential_restitution` needs
/// `friction`; `kinetic_restitution` replaces `restitution`).
pub(super) fn law_of(
    restitution: Option<f64>,
    kinetic_restitution: Option<KineticRestitutionDto>,
    friction: Option<f64>,
    impulse_ratio: Option<f64>,
    tangential_restitution: Option<f64>,
) -> Result<Law, ApiError> {
    let tangential = match (friction, impulse_ratio, tangential_restitution) {
        (Some(_), Some(_), _) => {
            return Err(law_problem(
                "/impulse_ratio",
                "give friction or impulse_ratio, not both",
            ));
        }
        (None, Some(_), Some(_)) => {
            return Err(law_problem(
                "/tangential_restitution",
                "tangential_restitution goes with friction, not with impulse_ratio",
            ));
        }
        (None, None, Some(_)) => {
            return Err(law_problem(
                "/friction",
                "tangential_restitution needs friction, its cap",
            ));
        }
        other => other,
    };
    if let Some(k) = kinetic_restitution {
        if restitution.is_some() {
            return Err(law_problem(
                "/restitution",
                "kinetic_restitution replaces restitution: give one",
            ));
        }
        if tangential != (None, None, None) {
            let pointer = if tangential.0.is_some() {
                "/friction"
            } else {
                "/impulse_ratio"
            };
            return Err(law_problem(
                pointer,
                "kinetic_restitution carries its own impulse ratios: give no other tangential law",
            ));
        }
        return match (k.approach_impulse_ratio, k.approach_friction) {
            (Some(approach_impulse_ratio), None) => Ok(Law::KineticRestitution {
                value: k.value,
                approach_impulse_ratio,
                rebound_impulse_ratio: k.rebound_impulse_ratio,
            }),
            (None, Some(approach_friction)) => Ok(Law::KineticFriction {
                value: k.value,
                approach_friction,
                rebound_impulse_ratio: k.rebound_impulse_ratio,
            }),
            (Some(_), Some(_)) => Err(law_problem(
                "/kinetic_restitution/approach_friction",
                "give approach_impulse_ratio or approach_friction, not both",
            )),
            (None, None) => Err(law_problem(
                "/kinetic_restitution/approach_impulse_ratio",
                "the approach phase needs approach_impulse_ratio or approach_friction",
            )),
        };
    }
    let Some(restitution) = restitution else {
        return Err(law_problem(
            "/restitution",
            "give restitution, or kinetic_restitution",
        ));
    };
    Ok(match tangential {
        (Some(friction), None, Some(tangential_restitution)) => Law::TangentialRestitution {
            restitution,
            friction,
            tangential_restitution,
        },
        (Some(friction), None, None) => Law::Friction {
            restitution,
            friction,
        },
        (None, Some(impulse_ratio), None) => Law::ImpulseRatio {
            restitution,
            impulse_ratio,
        },
        _ => Law::Frictionless { restitution },
    })
}
