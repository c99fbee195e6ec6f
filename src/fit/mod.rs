//! Coefficient identification from measured impacts, one module per model:
//! [`tangential`](mod@tangential) (`e`, `f`, `e_t` of the bilinear tangential model, section 3),
//! [`torsional`](mod@torsional) (`e`, `e_z`, `μ_z` of the torsional model, section 4)
//! [`bodies`](mod@bodies) (`e`, `μ` and the normal of a two-body contact from the
//! measured velocity changes, as reconstruction needs) and [`spatial`](mod@spatial)
//! (any spatial law's coefficients from many measured impacts in space).
//! Fitted values are judged by the solver's own model: residuals and regimes
//! are what [`crate::impact`] answers for the fitted coefficients.

pub mod bodies;
pub mod spatial;
pub mod tangential;
pub mod torsional;

use thiserror::Error;

pub use bodies::{Measured, MeasuredChange, PlanarFit, planar};
pub use spatial::{ImpactFit, SpatialChange, SpatialFit, SpatialLaw, SpatialObservation, spatial};
pub use tangential::{Observation, TangentialFit, impulse_ratio_from_intercept, tangential};
pub use torsional::{TorsionalFit, TorsionalObservation, torsional};

/// An estimated coefficient and its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The least-squares value.
    pub value: f64,
    /// Its standard error (0 when the points fit exactly; `NaN` from a single point).
    pub standard_error: f64,
}

/// Why a set of observations cannot be fitted.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FitError {
    /// Fewer observations than coefficients.
    #[error("at least {needed} observations are needed, got {got}")]
    TooFewPoints {
        /// The minimum.
        needed: usize,
        /// How many were given.
        got: usize,
    },
    /// An observation is not an impact of the model (invalid body, not
    /// approaching, no positive normal impulse, non-finite numbers).
    #[error("observation {index} is not an impact: {why}")]
    NotAnImpact {
        /// Its index.
        index: usize,
        /// Why.
        why: String,
    },
    /// The data cannot determine the coefficients (all initial contact
    /// velocities tangentially zero, for instance).
    #[error("the observations cannot determine the coefficients: {0}")]
    Degenerate(&'static str),
    /// The data cannot determine one parameter.
    #[error("the data cannot determine {parameter}: {why}")]
    Undetermined {
        /// The parameter.
        parameter: &'static str,
        /// Why.
        why: String,
    },
}

/// Least squares of `y = −k x` through the origin: `(k, standard error)`.
pub(crate) fn through_origin(pairs: impl Iterator<Item = (f64, f64)> + Clone) -> Option<Estimate> {
    let (sxy, sxx, n) = pairs.clone().fold((0.0, 0.0, 0usize), |(a, b, n), (x, y)| {
        (a + x * y, b + x * x, n + 1)
    });
    if n == 0 || sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let k = -sxy / sxx;
    let ss: f64 = pairs.map(|(x, y)| (y + k * x).powi(2)).sum();
    let se = if n > 1 {
        (ss / (n - 1) as f64 / sxx).sqrt()
    } else {
        f64::NAN
    };
    Some(Estimate {
        value: k,
        standard_error: se,
    })
}

pub(crate) fn mean(values: &[f64]) -> Option<Estimate> {
    if values.is_empty() {
        return None;
    }
    let n = values.len() as f64;
    let m = values.iter().sum::<f64>() / n;
    let se = if values.len() > 1 {
        (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt()
    } else {
        f64::NAN
    };
    Some(Estimate {
        value: m,
        standard_error: se,
    })
}

/// `1 − SS_res/SS_tot` of the `observed` values given their `residuals`
/// (`NaN` when the observations do not vary).
fn r_squared(observed: impl Iterator<Item = f64> + Clone, residuals: &[f64]) -> f64 {
    let n = residuals.len() as f64;
    let mean = observed.clone().sum::<f64>() / n;
    let ss_tot: f64 = observed.map(|y| (y - mean).powi(2)).sum();
    let ss_res: f64 = residuals.iter().map(|r| r * r).sum();
    if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else {
        f64::NAN
    }
}
