//! SVG figures (plotters' SVG backend): lines and markers on linear axes.
//! [`Figure`] is what sweep plots (`image/svg+xml` from `/v1/sweeps`) and the
//! validation report (model curves over measured points, `docs/validation.md`)
//! draw with.

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

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
