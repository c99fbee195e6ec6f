//! The sweep as an SVG plot: its first output against its first axis, one
//! series per combination of the other axes' values (product sweeps), points
//! without an answer leaving a gap. Axes are labelled with the quantity's
//! name, the paper's symbol and the SI unit ([`crate::quantity`]). Where the
//! case answers a regime (the sweep computes it alongside the plotted output),
//! a one-series plot shades each regime's stretch of the axis and a plot of
//! several series marks each switch on its curve, the regimes named in the
//! legend.

use axum::http::StatusCode;

use crate::http::problem::ApiError;
use crate::plot::{
    Band, Color, Curve, Figure, LegendEntry, Line, Marker, Markers, PALETTE, Scale, Shape, TEXT,
};
use crate::quantity::{DIMENSIONLESS, Input, Output};
use crate::sweep::{AxisValues, Cell, Combine, Sweep, SweepCase};

/// Most series a plot draws.
const MAX_SERIES: u64 = 64;
/// Points per parallel chunk.
const CHUNK_POINTS: u64 = 4096;

/// A checked plot request.
#[derive(Debug, Clone)]
pub struct Plot {
    x: Input,
    /// Logarithmic when the first axis is a `logspace`.
    x_scale: Scale,
    y: Output,
    /// The regime's column, when the sweep computes one.
    regime: Option<usize>,
    other_axes: Vec<Input>,
    series: u64,
}

/// One plotted point of a series: the abscissa, the answer (if any) and its regime.
type Point = (f64, Option<f64>, Option<&'static str>);

impl Plot {
    /// Checks that the sweep can be plotted: a numeric first output and at most
    /// `MAX_SERIES` (64) series.
    pub fn check<C: SweepCase>(
        axes: &[Input],
        outputs: &[Output],
        sweep: &Sweep<C>,
    ) -> Result<Plot, ApiError> {
        let y = match outputs.first() {
            Some(&y) if !y.is_name() => y,
            other => {
                return Err(ApiError::new(
                    StatusCode::UNPROCESSABLE_ENTITY,
                    "invalid-sweep",
                    "Invalid sweep output",
                    format!(
                        "an SVG plot draws the first output, which must be numeric; {} is a name",
                        other.map_or("/regime", |o| o.path())
                    ),
                )
                .at("/outputs/0"));
            }
        };
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
        let x_scale = match sweep.axes().first().map(|a| &a.values) {
            Some(AxisValues::Logspace { .. }) => Scale::Log,
            _ => Scale::Linear,
        };
        Ok(Plot {
            x: axes[0],
            x_scale,
            y,
            regime: outputs.iter().position(|&o| o == Output::Regime),
            other_axes: if sweep.combine() == Combine::Product {
                axes[1..].to_vec()
            } else {
                Vec::new()
            },
            series,
        })
    }

    /// Computes the sweep and draws it (what is computed when `stop()`
    /// turns true: the caller has gone and discards it).
    pub fn render<C: SweepCase>(&self, sweep: &Sweep<C>, stop: impl Fn() -> bool + Sync) -> String {
        let mut series: Vec<Vec<Point>> = vec![Vec::new(); self.series as usize];
        let product = sweep.combine() == Combine::Product;
        let regime = self.regime;
        sweep.run_parallel(
            CHUNK_POINTS,
            |range| {
                if stop() {
                    return None;
                }
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
                    let (y, name) = match row.outcome {
                        Ok(cells) => (
                            match cells.first() {
                                Some(Cell::Number(y)) if y.is_finite() => Some(*y),
                                _ => None,
                            },
                            match regime.and_then(|i| cells.get(i)) {
                                Some(Cell::Text(name)) => Some(*name),
                                _ => None,
                            },
                        ),
                        Err(_) => (None, None),
                    };
                    points.push((key as usize, (row.axis_values[0], y, name)));
                });
                Some(points)
            },
            |points| match points {
                Some(points) => {
                    for (key, point) in points {
                        series[key].push(point);
                    }
                    true
                }
                None => false,
            },
        );
        let labels: Vec<String> = (0..self.series).map(|key| self.label(sweep, key)).collect();
        self.figure(&series, &labels).render()
    }

    /// The legend text of series `key`: the other axes' symbols and values.
    fn label<C: SweepCase>(&self, sweep: &Sweep<C>, mut key: u64) -> String {
        let mut parts = Vec::new();
        for (input, axis) in self.other_axes.iter().zip(sweep.axes().iter().skip(1)).rev() {
            let len = axis.values.len();
            let unit = match input.unit() {
                DIMENSIONLESS | "" => String::new(),
                unit => format!(" {unit}"),
            };
            parts.push(format!(
                "{} = {}{unit}",
                input.symbol(),
                short(axis.values.value(key % len))
            ));
            key /= len;
        }
        parts.reverse();
        parts.join(", ")
    }

    fn figure(&self, series: &[Vec<Point>], labels: &[String]) -> Figure {
        let curves: Vec<Curve> = series
            .iter()
            .zip(labels)
            .enumerate()
            .map(|(i, (points, label))| Curve {
                label: label.clone(),
                segments: segments(points),
                line: Some(Line::solid(PALETTE[i % PALETTE.len()])),
            })
            .collect();
        let mut legend: Vec<LegendEntry> = curves
            .iter()
            .filter(|c| !c.label.is_empty())
            .map(|c| LegendEntry::Line(c.line.unwrap_or(Line::solid(PALETTE[0])), c.label.clone()))
            .collect();
        let mut bands = Vec::new();
        let mut markers = Vec::new();
        if series.len() == 1 {
            bands = regime_bands(&series[0]);
            let mut seen = Vec::new();
            for band in &bands {
                if !seen.contains(&band.label) {
                    seen.push(band.label.clone());
                    legend.push(LegendEntry::Band(band.fill, format!("regime: {}", band.label)));
                }
            }
        } else {
            let mut kinds: Vec<(&str, &str)> = Vec::new();
            let mut points: Vec<Vec<(f64, f64)>> = Vec::new();
            for s in series {
                for (from, to, at) in switches(s) {
                    let k = match kinds.iter().position(|&k| k == (from, to)) {
                        Some(k) => k,
                        None => {
                            kinds.push((from, to));
                            points.push(Vec::new());
                            kinds.len() - 1
                        }
                    };
                    points[k].push(at);
                }
            }
            for (k, ((from, to), points)) in kinds.into_iter().zip(points).enumerate() {
                let marker = switch_marker(k);
                let label = format!("regime switch: {from} → {to}");
                legend.push(LegendEntry::Marker(marker, label.clone()));
                markers.push(Markers {
                    label,
                    points,
                    marker: Some(marker),
                });
            }
        }
        let x_name = self.x.label();
        let y_name = self.y.label();
        let title = format!("{} against {}", capitalized(self.y.name()), self.x.name());
        let mut description = format!(
            "{title}: {} ({}) against {} ({}).",
            self.y.name(),
            self.y.symbol(),
            self.x.name(),
            self.x.symbol()
        );
        if series.len() > 1 {
            description.push_str(&format!(" One line per {}.", labels.join("; ")));
        }
        if !bands.is_empty() {
            let names: Vec<String> = bands
                .iter()
                .map(|b| format!("{} from {} to {}", b.label, short(b.from), short(b.to)))
                .collect();
            description.push_str(&format!(" Regimes: {}.", names.join(", ")));
        }
        let switches: usize = markers.iter().map(|m| m.points.len()).sum();
        if switches > 0 {
            description.push_str(&format!(" {switches} regime switches marked on the lines."));
        }
        Figure {
            title,
            description,
            x_name,
            y_name,
            x_scale: self.x_scale,
            curves,
            markers,
            bands,
            legend: Some(legend),
            ..Figure::default()
        }
    }
}

/// A series' answered stretches, split where a point has no answer.
fn segments(points: &[Point]) -> Vec<Vec<(f64, f64)>> {
    let mut segments = vec![Vec::new()];
    for &(x, y, _) in points {
        match y {
            Some(y) => segments.last_mut().expect("a segment").push((x, y)),
            None if segments.last().is_some_and(|s| !s.is_empty()) => segments.push(Vec::new()),
            None => {}
        }
    }
    segments
}

/// The light tint each regime is shaded with.
fn regime_fill(name: &str) -> Color {
    match name {
        "sliding" => Color(253, 228, 204),
        "sticking" => Color(214, 230, 245),
        "restitution" => Color(220, 239, 216),
        "prescribed" => Color(232, 224, 240),
        "frictionless" => Color(236, 236, 236),
        _ => Color(242, 242, 220),
    }
}

/// The stretches of one series' axis in each regime: from the first point of a
/// run of points in one regime to the last, widened to halfway to the
/// neighbouring points (the switch lies between them).
fn regime_bands(points: &[Point]) -> Vec<Band> {
    let mut bands: Vec<Band> = Vec::new();
    let mut previous: Option<(f64, &str)> = None;
    for &(x, _, name) in points {
        if let Some(name) = name {
            match (previous, bands.last_mut()) {
                (Some((_, p)), Some(band)) if p == name => band.to = x,
                (Some((px, _)), Some(band)) => {
                    let mid = (px + x) / 2.0;
                    band.to = mid;
                    bands.push(Band {
                        label: name.to_owned(),
                        from: mid,
                        to: x,
                        fill: regime_fill(name),
                    });
                }
                _ => bands.push(Band {
                    label: name.to_owned(),
                    from: x,
                    to: x,
                    fill: regime_fill(name),
                }),
            }
        }
        previous = name.map(|n| (x, n));
    }
    bands
}

/// Where one series changes regime between two answered neighbours: the two
/// regimes and the midpoint of the two points.
fn switches(points: &[Point]) -> Vec<(&'static str, &'static str, (f64, f64))> {
    points
        .windows(2)
        .filter_map(|w| match (w[0], w[1]) {
            ((x0, Some(y0), Some(a)), (x1, Some(y1), Some(b))) if a != b => {
                Some((a, b, ((x0 + x1) / 2.0, (y0 + y1) / 2.0)))
            }
            _ => None,
        })
        .collect()
}

/// The marker of the `k`-th kind of regime switch: hollow, dark, a shape each.
fn switch_marker(k: usize) -> Marker {
    const SHAPES: [Shape; 5] = [
        Shape::Diamond,
        Shape::Square,
        Shape::TriangleDown,
        Shape::Circle,
        Shape::Triangle,
    ];
    Marker {
        size: 5.0,
        stroke_width: 1.8,
        ..Marker::hollow(SHAPES[k % SHAPES.len()], TEXT)
    }
}

fn capitalized(s: &str) -> String {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect(),
        None => String::new(),
    }
}

/// A value for a legend: at most six significant digits, a true minus.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let magnitude = v.abs().log10().floor() as i32;
    let s = if !(-4..6).contains(&magnitude) {
        format!("{v:.5e}")
            .split_once('e')
            .map(|(m, e)| {
                let m = m.trim_end_matches('0').trim_end_matches('.');
                format!("{m}×10^{{{e}}}")
            })
            .unwrap_or_default()
    } else {
        let decimals = (5 - magnitude).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            s
        }
    };
    s.replace('-', "−")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_values_read_as_written() {
        assert_eq!(short(0.1), "0.1");
        assert_eq!(short(0.30000000000000004), "0.3");
        assert_eq!(short(0.123), "0.123");
        assert_eq!(short(-1.0), "−1");
        assert_eq!(short(2.5e-7), "2.5×10^{−7}");
        assert_eq!(short(123456.0), "123456");
        assert_eq!(short(1.5e6), "1.5×10^{6}");
    }

    #[test]
    fn bands_meet_halfway_between_points_of_two_regimes() {
        let points: Vec<Point> = vec![
            (0.0, Some(0.0), Some("sticking")),
            (1.0, Some(0.0), Some("sticking")),
            (2.0, Some(1.0), Some("sliding")),
            (3.0, Some(2.0), Some("sliding")),
        ];
        let bands = regime_bands(&points);
        assert_eq!(bands.len(), 2);
        assert_eq!(
            (bands[0].label.as_str(), bands[0].from, bands[0].to),
            ("sticking", 0.0, 1.5)
        );
        assert_eq!(
            (bands[1].label.as_str(), bands[1].from, bands[1].to),
            ("sliding", 1.5, 3.0)
        );
        assert_eq!(switches(&points), [("sticking", "sliding", (1.5, 0.5))]);
    }
}
