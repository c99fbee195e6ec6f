//! `POST /v1/impacts/…`: one impact per request, a module per case —
//! `barrier` (normal, oblique and tangential: one body against a barrier in
//! the paper's frame), `torsional`, `bodies` (two bodies or one against a
//! barrier in the plane, world axes: `/v1/impacts/planar`) and `spatial` —
//! and `law`, the wire form of a contact law that all of them read.

pub mod barrier;
pub mod bodies;
pub mod inertia;
pub mod law;
pub mod spatial;
pub mod torsional;

use crate::http::dto::PrecisionDto;
use crate::http::problem::ApiError;
use crate::impact::{Case, Precision, solve};
use crate::outcome::Outputs;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

pub use self::barrier::{
    NormalRequest, ObliqueRequest, TangentialRequest, respond_normal, respond_oblique, respond_tangential,
};
pub use self::bodies::PlanarContactRequest;
pub use self::law::KineticRestitutionDto;
pub use self::spatial::SpatialContactRequest;
pub use self::torsional::{TorsionalBodyDto, TorsionalRequest, respond_torsional};

/// The answer to an impact request: `impact` (the request's scene, or the
/// refusal of it) solved with every output in `precision`, written as the
/// response by `response`.
pub(crate) fn respond<C: Case, R>(
    impact: Result<C, ApiError>,
    precision: PrecisionDto,
    response: impl FnOnce(&C::Outcome, Precision) -> R,
) -> Result<R, ApiError> {
    let precision = Precision::from(precision);
    let outcome = solve(&impact?, Outputs::ALL, precision)?;
    Ok(response(&outcome, precision))
}

/// The table of cases, one row per impact endpoint: the variant of the
/// sweeps' `case`, its name on the wire (`/v1/impacts/<name>`), its request
/// type, the solver's impact that answers it, and the conversion of a
/// request to that impact. The table is handed, after the bracketed tokens
/// given with it, to `consumer`, a macro that generates from it (the
/// sweeps' `CaseDto`, `AnySweep`, `on_sweep!` and building, in
/// `src/http/sweeps/cases.rs`); a new case is one row here, beside its route
/// below.
macro_rules! impact_cases {
    ($($consumer:ident)::+ [$($extra:tt)*]) => {
        $($consumer)::+! {
            [$($extra)*]
            Normal => ("normal", $crate::http::impacts::NormalRequest, $crate::impact::BarrierImpact, |base| $crate::impact::BarrierImpact::try_from(base)),
            Oblique => ("oblique", $crate::http::impacts::ObliqueRequest, $crate::impact::BarrierImpact, |base| $crate::impact::BarrierImpact::try_from(base)),
            Tangential => ("tangential", $crate::http::impacts::TangentialRequest, $crate::impact::BarrierImpact, |base| Ok($crate::impact::BarrierImpact::from(base))),
            Torsional => ("torsional", $crate::http::impacts::TorsionalRequest, $crate::impact::TorsionalImpact, |base| Ok($crate::impact::TorsionalImpact::from(base))),
            Planar => ("planar", $crate::http::impacts::PlanarContactRequest, $crate::impact::BodiesImpact, |base| $crate::impact::BodiesImpact::try_from(base)),
            Spatial => ("spatial", $crate::http::impacts::SpatialContactRequest, $crate::impact::SpatialImpact, |base| $crate::impact::SpatialImpact::try_from(base)),
        }
    };
}
pub(crate) use impact_cases;

/// The impact endpoints, with their OpenAPI operations.
pub fn router<S: Clone + Send + Sync + 'static>() -> OpenApiRouter<S> {
    OpenApiRouter::new()
        .routes(routes!(barrier::impacts_normal))
        .routes(routes!(barrier::impacts_oblique))
        .routes(routes!(barrier::impacts_tangential))
        .routes(routes!(torsional::impacts_torsional))
        .routes(routes!(bodies::impacts_planar))
        .routes(routes!(spatial::impacts_spatial))
}

/// What the wire-type tests of every case check: the request's and the
/// response's members sit at the paths the solver's declarations give.
#[cfg(test)]
pub(crate) mod wire_check {
    use serde::Serialize;
    use serde_json::Value as Json;

    use crate::impact::{Case, Precision, solve};
    use crate::outcome::Outputs;
    use crate::quantity::Value;

    /// `request` with the members of `law` added: a case's scene under one law.
    pub fn with_law(mut request: Json, law: &Json) -> Json {
        request
            .as_object_mut()
            .unwrap()
            .extend(law.as_object().unwrap().clone());
        request
    }

    /// [`inputs_resolve`], then [`outputs_resolve`] for the impact solved in
    /// each precision, `response` mapping its outcome to the wire type.
    pub fn paths_resolve<C: Case, R: Serialize>(
        request: &Json,
        impact: &C,
        response: impl Fn(&C::Outcome, Precision) -> R,
    ) {
        inputs_resolve(request, impact);
        for precision in [Precision::Fast, Precision::Exact] {
            let outcome = solve(impact, Outputs::ALL, precision).unwrap();
            let answer = serde_json::to_value(response(&outcome, precision)).unwrap();
            outputs_resolve(&answer, impact, &outcome);
        }
    }

    /// Every input a request's impact reads sits at its path in the request,
    /// with the value the impact reads.
    pub fn inputs_resolve<C: Case>(request: &Json, impact: &C) {
        let reads = impact.reads();
        assert!(!reads.is_empty());
        for input in reads {
            let at = request
                .pointer(input.path())
                .unwrap_or_else(|| panic!("{} in {request}", input.path()));
            assert_eq!(at.as_f64(), impact.input(input), "{}", input.path());
        }
    }

    /// Every output the impact answers sits at its path in the serialised
    /// response, with the value the case reads off the outcome; one it does
    /// not answer (body B against a barrier, the twist regime without a
    /// twist law) is absent and `NaN`.
    pub fn outputs_resolve<C: Case>(response: &Json, impact: &C, outcome: &C::Outcome) {
        for &output in C::OUTPUTS {
            let value = C::output(outcome, output).expect("an output of the case");
            match (response.pointer(output.path()), value) {
                (Some(at), Value::Number(x)) => assert_eq!(at.as_f64(), Some(x), "{}", output.path()),
                (Some(at), Value::Text(name)) => assert_eq!(at.as_str(), Some(name), "{}", output.path()),
                (None, Value::Number(x)) => {
                    assert!(x.is_nan() && !impact.answers(output), "{}", output.path())
                }
                (None, Value::Text(_)) => panic!("{} in {response}", output.path()),
            }
        }
    }
}
