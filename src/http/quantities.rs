//! `GET /v1/quantities`: the quantity table, per case — every input each case
//! reads and every output it answers, with its JSON pointer, the paper's
//! symbol, its name and SI unit. It is made from the solver's own
//! declarations ([`crate::quantity`], each case's `reads!` and its outcome's
//! `answers!`), so it lists nothing of its own; the explorer renders its
//! labels and units from it (`/assets/quantities.json`, the same document).

use axum::Json;
use serde::Serialize;
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use crate::http::accept::{AcceptsJson, NotAcceptable};
use crate::http::sweeps::CaseDto;
use crate::quantity::{DIMENSIONLESS, Input, Output};

/// The routes of the quantity table.
pub fn router<S: Clone + Send + Sync + 'static>() -> OpenApiRouter<S> {
    OpenApiRouter::new().routes(routes!(quantities))
}

/// Every case's inputs and outputs.
#[derive(Debug, Serialize, ToSchema)]
pub struct QuantityTable {
    /// The cases, in the order of the sweep request's `case`.
    pub cases: Vec<CaseQuantities>,
}

/// One case's quantities.
#[derive(Debug, Serialize, ToSchema)]
pub struct CaseQuantities {
    /// The case's name (a sweep's `case`).
    #[schema(example = "oblique")]
    pub case: &'static str,
    /// Its endpoint.
    #[schema(example = "/v1/impacts/oblique")]
    pub endpoint: &'static str,
    /// Every input an impact of the case may read, in request order (a
    /// given impact reads those of its body and law).
    pub inputs: Vec<Quantity>,
    /// Every output, in response order.
    pub outputs: Vec<Quantity>,
}

/// One named quantity.
#[derive(Debug, Serialize, ToSchema)]
pub struct Quantity {
    /// Its JSON pointer in the request or response (a sweep's axis path or column).
    #[schema(example = "/contact_velocity/final/tangential")]
    pub path: &'static str,
    /// The paper's symbol, `_` before a subscript.
    #[schema(example = "V_ct")]
    pub symbol: &'static str,
    /// Its name in words.
    #[schema(example = "final tangential contact velocity")]
    pub name: &'static str,
    /// Its SI unit: `1` for a dimensionless number, empty for a name (a regime).
    #[schema(example = "m/s")]
    pub unit: &'static str,
}

impl Quantity {
    fn input(i: &Input) -> Self {
        Quantity {
            path: i.path(),
            symbol: i.symbol(),
            name: i.name(),
            unit: i.unit(),
        }
    }

    fn output(o: &Output) -> Self {
        Quantity {
            path: o.path(),
            symbol: o.symbol(),
            name: o.name(),
            unit: o.unit(),
        }
    }
}

/// The table, from the cases' declarations, in the order of the sweep
/// request's `case` (`CaseDto`).
pub fn table() -> QuantityTable {
    debug_assert_eq!(DIMENSIONLESS, "1");
    QuantityTable {
        cases: CaseDto::ALL
            .iter()
            .map(|&case| CaseQuantities {
                case: case.as_str(),
                endpoint: case.endpoint(),
                inputs: case.inputs().iter().map(Quantity::input).collect(),
                outputs: case.outputs().iter().map(Quantity::output).collect(),
            })
            .collect(),
    }
}

/// The quantity table: every input and output of every case, with its
/// pointer, symbol, name and SI unit.
#[utoipa::path(
    get,
    path = "/v1/quantities",
    tag = "service",
    responses((status = 200, description = "Every case's inputs and outputs", body = QuantityTable), NotAcceptable)
)]
pub async fn quantities(_: AcceptsJson) -> Json<QuantityTable> {
    Json(table())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every case of the sweep request is in the table, once, with its lists.
    #[test]
    fn the_table_lists_every_sweep_case_once() {
        let table = table();
        let names: Vec<&str> = table.cases.iter().map(|c| c.case).collect();
        assert_eq!(
            names,
            [
                "normal",
                "oblique",
                "tangential",
                "torsional",
                "planar",
                "spatial"
            ]
        );
        for c in &table.cases {
            assert!(c.endpoint.ends_with(c.case));
            assert!(!c.inputs.is_empty() && !c.outputs.is_empty());
        }
        let spatial = &table.cases[5];
        assert_eq!(
            spatial.outputs.len(),
            <crate::SpatialImpact as crate::Case>::OUTPUTS.len()
        );
        assert_eq!(spatial.outputs[0].path, "/bodies/0/velocity/x");
        assert_eq!(spatial.outputs[0].unit, "m/s");
    }
}
