//! SVG plots (plotters' SVG backend). A sweep draws its first output against
//! its first axis, one series per combination of the other axes' values
//! (product sweeps), points without an answer leaving a gap. [`Figure`] is the
//! general plot both sweeps and the validation report (model curves over
//! measured points, `docs/validation.md`) draw with.

use axum::http::StatusCode;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::problem::ApiError;
use crate::sweep::{Cell, Combine, Sweep, SweepCase};

/// Most series a plot draws.
const MAX_SERIES: u64 = 64;
/// Series colours (Tableau 10), distinguishable on white.
const TABLEAU: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];
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

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        (hi - lo) * 0.05
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - pad, hi + pad)
}

/// One labelled line, drawn as segments (a gap between segments).
#[derive(Debug, Clone, Default)]
pub struct Curve {
    /// Legend text (none when empty).
    pub label: String,
    /// The segments, each a polyline.
    pub segments: Vec<Vec<(f64, f64)>>,
}

/// One labelled set of points, drawn as markers.
#[derive(Debug, Clone, Default)]
pub struct Markers {
    /// Legend text.
    pub label: String,
    /// The points.
    pub points: Vec<(f64, f64)>,
}

/// A plot: lines (model curves, sweep series) and markers (measured points),
/// on linear axes fitted to everything drawn.
#[derive(Debug, Clone, Default)]
pub struct Figure {
    /// Caption.
    pub title: String,
    /// Horizontal axis name.
    pub x_name: String,
    /// Vertical axis name.
    pub y_name: String,
    /// Lines, coloured in order.
    pub curves: Vec<Curve>,
    /// Point sets, coloured after the lines, each with its own marker shape.
    pub markers: Vec<Markers>,
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

/// plotters' tick label, except that a tick one rounding away from zero
/// (as tick positions stepped from a negative start often are) reads `0.0`,
/// not `-0.0`.
fn tick_label(value: &f64) -> String {
    let label = RangedCoordf64::format(value);
    if label.parse::<f64>() == Ok(0.0) {
        RangedCoordf64::format(&0.0)
    } else {
        label
    }
}

impl Figure {
    /// The figure as an SVG document. plotters' errors cannot occur when
    /// writing into a String, and any that did would leave a partial drawing
    /// rather than fail.
    pub fn render(&self) -> String {
        let lines = self.curves.iter().flat_map(|c| c.segments.iter().flatten());
        let points = self.markers.iter().flat_map(|m| m.points.iter());
        let all = || lines.clone().chain(points.clone());
        let (x0, x1) = range(all().map(|p| p.0));
        let (y0, y1) = range(all().map(|p| p.1));
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, (900, 600)).into_drawing_area();
            let _ = root.fill(&WHITE);
            let chart = ChartBuilder::on(&root)
                .caption(&self.title, ("sans-serif", 20))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(72)
                .build_cartesian_2d(x0..x1, y0..y1);
            if let Ok(mut chart) = chart {
                let _ = chart
                    .configure_mesh()
                    .x_desc(&self.x_name)
                    .y_desc(&self.y_name)
                    .x_label_formatter(&tick_label)
                    .y_label_formatter(&tick_label)
                    .draw();
                let color = |i: usize| {
                    let (r, g, b) = TABLEAU[i % TABLEAU.len()];
                    RGBColor(r, g, b)
                };
                for (i, curve) in self.curves.iter().enumerate() {
                    let color = color(i);
                    for (j, segment) in curve.segments.iter().enumerate() {
                        let line = chart
                            .draw_series(LineSeries::new(segment.iter().copied(), color.stroke_width(2)));
                        if let (Ok(line), 0, false) = (line, j, curve.label.is_empty()) {
                            line.label(curve.label.clone()).legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                            });
                        }
                    }
                }
                for (i, set) in self.markers.iter().enumerate() {
                    let color = color(self.curves.len() + i);
                    let drawn = match i % 3 {
                        0 => chart.draw_series(set.points.iter().map(|&p| Circle::new(p, 4, color.filled()))),
                        1 => chart.draw_series(
                            set.points
                                .iter()
                                .map(|&p| TriangleMarker::new(p, 5, color.filled())),
                        ),
                        _ => chart.draw_series(
                            set.points
                                .iter()
                                .map(|&p| Cross::new(p, 4, color.stroke_width(2))),
                        ),
                    };
                    if let Ok(drawn) = drawn {
                        drawn
                            .label(set.label.clone())
                            .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
                    }
                }
                let labelled = self.curves.iter().any(|c| !c.label.is_empty()) || !self.markers.is_empty();
                if labelled {
                    let _ = chart
                        .configure_series_labels()
                        .background_style(WHITE.mix(0.8))
                        .border_style(BLACK)
                        .draw();
                }
            }
            let _ = root.present();
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tick_next_to_zero_reads_zero_and_others_keep_their_sign() {
        assert_eq!(RangedCoordf64::format(&-2.7e-17), "-0.0", "plotters' own label");
        assert_eq!(tick_label(&-2.7e-17), "0.0");
        assert_eq!(tick_label(&-0.0), "0.0");
        assert_eq!(tick_label(&-0.25), "-0.25");
        assert_eq!(tick_label(&1.5), "1.5");
    }

    #[test]
    fn no_rendered_figure_has_a_negative_zero_tick() {
        let figure = Figure {
            title: "t".into(),
            x_name: "x".into(),
            y_name: "y".into(),
            curves: vec![Curve {
                label: String::new(),
                segments: vec![vec![(-0.3, -0.34), (0.7, 0.12)]],
            }],
            markers: Vec::new(),
        };
        let svg = figure.render();
        assert!(
            svg.contains(">0.0<") || svg.contains("\n0.0\n"),
            "a zero tick is drawn"
        );
        assert!(!svg.contains("-0.0\n") && !svg.contains(">-0.0<"), "{svg}");
    }
}
