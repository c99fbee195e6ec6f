//! The cases a sweep takes, from the table of cases
//! ([`impact_cases!`](crate::http::impacts::impact_cases), beside the impact
//! endpoints): each case's name on the wire, its request type (the sweep's
//! `base`), the solver's impact it converts to and the kind of sweep that
//! runs it. `CaseDto`, its name and endpoint, its inputs and outputs (for
//! `GET /v1/quantities`) and the building of a sweep of each case are all
//! generated from the table.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::negotiate::Format;
use super::request::{self, SweepRequest};
use crate::http::dto::PrecisionDto;
use crate::http::extract::parse_value;
use crate::http::impacts::impact_cases;
use crate::http::problem::ApiError;
use crate::impact::{Case, Precision};
use crate::quantity::{Input, Output};
use crate::sweep::{CaseSweep, Sweep};

/// Runs `$body` with `$s` bound to the sweep inside an [`AnySweep`],
/// whichever case it is.
macro_rules! on_sweep {
    ($any:expr, $s:ident => $body:expr) => {
        $crate::http::impacts::impact_cases!(crate::http::sweeps::cases::on_sweep_arms [$any, $s => $body])
    };
}
pub(crate) use on_sweep;

/// The match of [`on_sweep!`], one arm per row of the table of cases.
macro_rules! on_sweep_arms {
    ([$any:expr, $s:ident => $body:expr] $($case:ident => ($name:literal, $request:ty, $impact:ty, |$base:ident| $convert:expr),)*) => {
        match $any {
            $(AnySweep::$case($s) => $body,)*
        }
    };
}
pub(crate) use on_sweep_arms;

/// Generates `AnySweep`, `CaseDto` and the building of each case's sweep
/// from one row per case: `Variant => ("name", Request, Impact, |base| the impact)`.
macro_rules! sweep_cases {
    ([] $($case:ident => ($name:literal, $request:ty, $impact:ty, |$base:ident| $convert:expr),)*) => {
        /// A checked sweep of any case (one per request, so its variants'
        /// sizes do not matter).
        #[derive(Debug)]
        #[allow(clippy::large_enum_variant)]
        pub enum AnySweep {
            $(
                #[doc = concat!("A sweep of `", $name, "` impacts.")]
                $case(Sweep<CaseSweep<$impact>>),
            )*
        }

        /// The physical case a sweep evaluates.
        // The wire names are the variants' in snake case (a test checks that
        // they are the table's names): utoipa does not read a `rename` given
        // through a macro.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
        #[serde(rename_all = "snake_case")]
        pub enum CaseDto {
            $(
                #[doc = concat!("`POST /v1/impacts/", $name, "`.")]
                $case,
            )*
        }

        impl CaseDto {
            /// Every case, in the table's order.
            pub const ALL: &'static [CaseDto] = &[$(CaseDto::$case,)*];

            /// The case's name on the wire.
            pub fn as_str(self) -> &'static str {
                match self {
                    $(CaseDto::$case => $name,)*
                }
            }

            /// The endpoint that answers one impact of the case.
            pub fn endpoint(self) -> &'static str {
                match self {
                    $(CaseDto::$case => concat!("/v1/impacts/", $name),)*
                }
            }

            /// Every input an impact of the case may read, in request order.
            pub fn inputs(self) -> &'static [Input] {
                match self {
                    $(CaseDto::$case => <$impact as Case>::INPUTS,)*
                }
            }

            /// Every output of the case, in response order.
            pub fn outputs(self) -> &'static [Output] {
                match self {
                    $(CaseDto::$case => <$impact as Case>::OUTPUTS,)*
                }
            }
        }

        /// Checks a sweep request whole (base, axes, outputs, precision,
        /// range, the point limit for the format) and builds its sweep.
        pub fn build(request: &SweepRequest, limit: u64, format: Format) -> Result<(AnySweep, Precision), ApiError> {
            Ok(match request.case {
                $(CaseDto::$case => {
                    let base: $request = parse_value(request.base.clone(), "/base")?;
                    let $base = &base;
                    let impact: $impact = ($convert).map_err(|e: ApiError| e.under("/base"))?;
                    let (sweep, precision) = checked(request, impact, base.precision, limit, format)?;
                    (AnySweep::$case(sweep), precision)
                })*
            })
        }
    };
}

impact_cases!(sweep_cases []);

/// The sweep of `base` the request describes, in its precision (the sweep's
/// own, else the base's).
fn checked<C: Case>(
    request: &SweepRequest,
    base: C,
    base_precision: PrecisionDto,
    limit: u64,
    format: Format,
) -> Result<(Sweep<CaseSweep<C>>, Precision), ApiError> {
    let precision = request::precision(request.precision, base_precision)?;
    Ok((
        request::sweep(request, base, precision, limit, format)?,
        precision,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each case's wire name (serde's and the schema's) is the table's, and
    /// its endpoint is in the OpenAPI document.
    #[test]
    fn wire_names_and_endpoints_are_the_table_s() {
        let document = crate::http::openapi();
        for &case in CaseDto::ALL {
            assert_eq!(serde_json::to_value(case).unwrap(), case.as_str());
            let parsed: CaseDto = serde_json::from_value(case.as_str().into()).unwrap();
            assert_eq!(parsed, case);
            assert!(
                document.paths.paths.contains_key(case.endpoint()),
                "{}",
                case.endpoint()
            );
            assert!(!case.inputs().is_empty() && !case.outputs().is_empty());
        }
        assert_eq!(CaseDto::ALL.len(), 6);
    }
}
