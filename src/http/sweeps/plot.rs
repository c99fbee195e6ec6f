//! The sweep as an SVG plot: its first output against its first axis, one
//! series per combination of the other axes' values (product sweeps), points
//! without an answer leaving a gap.

use axum::http::StatusCode;

use crate::http::problem::ApiError;
use crate::plot::{Curve, Figure};
use crate::sweep::{Cell, Combine, Sweep, SweepCase};

/// Most series a plot draws.
const MAX_SERIES: u64 = 64;
/// Points per parallel chunk.
const CHUNK_POINTS: u64 = 4096;

/// A checked plot request.
#[derive(Debug, Clone)]
pub struct Plot {
    x_name: &'static str,
    y_name: &'static str,
    other_axes: Vec<&'static str>,
    series: u64,
}

impl Plot {
    /// Checks that the sweep can be plotted: a numeric first output and at most
    /// `MAX_SERIES` (64) series.
    pub fn check<C: SweepCase>(
        axis_names: &[&'static str],
        outputs: &[&'static str],
        sweep: &Sweep<C>,
    ) -> Result<Plot, ApiError> {
        let y_name = outputs.first().copied().unwrap_or("");
        if y_name == "/regime" {
            return Err(ApiError::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "invalid-sweep",
                "Invalid sweep output",
                "an SVG plot draws the first output, which must be numeric; /regime is a name",
            )
            .at("/outputs/0"));
        }
        let series = if sweep.combine() == Combine::Product {
            sweep
                .axes()
                .iter()
                .skip(1)
                .try_fold(1u64, |n, a| n.checked_mul(a.values.len()))
                .unwrap_or(u64::MAX)
        } else {
            1
        };
        if series > MAX_SERIES {
            return Err(ApiError::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "invalid-sweep",
                "Sweep too large",
                format!(
                    "an SVG plot draws one series per combination of the axes after the first: {series} here, at most {MAX_SERIES}"
                ),
            )
            .at("/axes"));
        }
        Ok(Plot {
            x_name: axis_names[0],
            y_name,
            other_axes: if sweep.combine() == Combine::Product {
                axis_names[1..].to_vec()
            } else {
                Vec::new()
            },
            series,
        })
    }

    /// Computes the sweep and draws it.
    pub fn render<C: SweepCase>(&self, sweep: &Sweep<C>) -> String {
        let mut series: Vec<Vec<Vec<(f64, f64)>>> = vec![vec![Vec::new()]; self.series as usize];
        let product = sweep.combine() == Combine::Product;
        sweep.run_parallel(
            CHUNK_POINTS,
            |range| {
                let mut points = Vec::new();
                sweep.for_each_in(range, |row| {
                    let key = if product {
                        row.axis_indices
                            .iter()
                            .zip(sweep.axes())
                            .skip(1)
                            .fold(0, |k, (&d, a)| k * a.values.len() + d)
                    } else {
                        0
                    };
                    let y = match row.outcome {
                        Ok(cells) => match cells.first() {
                            Some(Cell::Number(y)) if y.is_finite() => Some(*y),
                            _ => None,
                        },
                        Err(_) => None,
                    };
                    points.push((key as usize, row.axis_values[0], y));
                });
                points
            },
            |points| {
                for (key, x, y) in points {
                    let segments = &mut series[key];
                    match y {
                        Some(y) => segments.last_mut().expect("a segment").push((x, y)),
                        None if segments.last().is_some_and(|s| !s.is_empty()) => segments.push(Vec::new()),
                        None => {}
                    }
                }
                true
            },
        );
        let labels: Vec<String> = (0..self.series).map(|key| self.label(sweep, key)).collect();
        draw(self.x_name, self.y_name, &series, &labels)
    }

    fn label<C: SweepCase>(&self, sweep: &Sweep<C>, mut key: u64) -> String {
        let mut parts = Vec::new();
        for (name, axis) in self.other_axes.iter().zip(sweep.axes().iter().skip(1)).rev() {
            let len = axis.values.len();
            parts.push(format!("{name} = {}", axis.values.value(key % len)));
            key /= len;
        }
        parts.reverse();
        parts.join(", ")
    }
}

fn draw(x_name: &str, y_name: &str, series: &[Vec<Vec<(f64, f64)>>], labels: &[String]) -> String {
    Figure {
        title: format!("{y_name} against {x_name}"),
        x_name: x_name.to_owned(),
        y_name: y_name.to_owned(),
        curves: series
            .iter()
            .zip(labels)
            .map(|(segments, label)| Curve {
                label: label.clone(),
                segments: segments.clone(),
            })
            .collect(),
        markers: Vec::new(),
    }
    .render()
}
