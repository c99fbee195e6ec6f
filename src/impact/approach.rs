//! The approach decision of the two-body contact cases (in the plane and in
//! space): whether `u·n < 0`, decided exactly but in f64 where f64 is sure.

use std::cmp::Ordering;

use crate::arith::{Field, Fraction};

/// Whether a contact approaches (`u·n < 0`), decided exactly: by the f64
/// value `fast` where it lies farther from zero than its error bound
/// `bound()`, else by the `exact` value. Returns the decision and whether
/// the f64 value made it (the `certain` of [`super::evaluate_contact`]).
pub(crate) fn approaches(
    fast: f64,
    bound: impl FnOnce() -> f64,
    exact: impl FnOnce() -> Fraction,
) -> (bool, bool) {
    let certain = fast.is_finite() && fast.abs() > bound();
    let approaching = if certain {
        fast < 0.0
    } else {
        exact().sign() == Ok(Ordering::Less)
    };
    (approaching, certain)
}

/// The error bound of an f64 approach velocity: `ulps` roundings of `terms`,
/// the sum of the magnitudes of the terms it combines; `∞` where they leave
/// the normal range.
pub(crate) fn approach_bound(terms: f64, ulps: f64) -> f64 {
    if terms.is_finite() && terms > 2f64.powi(-900) {
        ulps * f64::EPSILON * terms
    } else {
        f64::INFINITY
    }
}
