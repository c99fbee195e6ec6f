//! SVG figures: lines, markers and shaded bands on linear or logarithmic axes,
//! written as SVG text directly. [`Figure`] draws the service's plots
//! (`image/svg+xml` from `/v1/sweeps` and the tangential and torsional fits,
//! which the explorer inlines), the validation report's model curves
//! over measured points (`docs/validation/`) and the accuracy report's plot
//! (`docs/accuracy.svg`).
//!
//! Every figure is meant to print:
//!
//! - coordinates written with two decimals, never snapped to whole pixels, so
//!   lines are not staircases;
//! - one tick format per axis: the same number of decimals on a linear axis
//!   (a shared `×10ⁿ` for very large or small values), powers of ten with
//!   superscripts on a logarithmic axis spanning decades, `1 2 5` steps on one
//!   spanning a few;
//! - margins sized from the labels they hold (text widths estimated from
//!   DejaVu Sans' advances, the widest of the fonts named), so nothing is cut;
//! - the legend beside the plot area, never over the data, each entry drawn
//!   with the same mark as the plot;
//! - a `<title>` and a `<desc>`, and text at a contrast of at least 4.5:1 on
//!   the white background;
//! - presentation attributes only (`fill=`, `stroke=`, `font-size=`): no
//!   `<style>` element and no `style=""`, because the explorer inlines sweep
//!   plots under a Content-Security-Policy without inline styles.
//!
//! Text takes a small markup: `_x` or `_{…}` makes a subscript, `^x` or `^{…}`
//! a superscript, where `x` is a run of letters and digits (`V_ct` is V with
//! subscript ct, `10^{−3}` a power of ten). Parts of the drawing carry a
//! `data-part` attribute (`legend`, `x-ticks`, `curves`, …) for tests.

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// WCAG relative luminance.
    pub fn luminance(self) -> f64 {
        let channel = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.039_28 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * channel(self.0) + 0.7152 * channel(self.1) + 0.0722 * channel(self.2)
    }

    /// WCAG contrast ratio against `other`.
    pub fn contrast(self, other: Color) -> f64 {
        let (a, b) = (self.luminance(), other.luminance());
        (a.max(b) + 0.05) / (a.min(b) + 0.05)
    }
}

/// The background.
pub const WHITE: Color = Color(255, 255, 255);
/// Titles, axis names, legend text (17:1 on white).
pub const TEXT: Color = Color(26, 26, 26);
/// Tick labels (10:1 on white).
pub const MUTED: Color = Color(64, 64, 64);
/// Series colours for lines and markers without a style of their own: a
/// colour-blind-safe set (Okabe–Ito and Tol, darkened), each at least 3:1
/// against white.
pub const PALETTE: [Color; 10] = [
    Color(0, 114, 178),
    Color(213, 94, 0),
    Color(17, 119, 51),
    Color(170, 51, 119),
    Color(140, 81, 10),
    Color(51, 34, 136),
    Color(178, 24, 43),
    Color(77, 77, 77),
    Color(0, 124, 124),
    Color(107, 107, 0),
];

const FONT: &str = "DejaVu Sans, Verdana, Arial, sans-serif";
const TITLE_SIZE: f64 = 18.0;
const SUBTITLE_SIZE: f64 = 13.0;
const AXIS_SIZE: f64 = 14.0;
const TICK_SIZE: f64 = 13.0;
const LEGEND_SIZE: f64 = 13.0;
const PAD: f64 = 14.0;
const TICK_LENGTH: f64 = 5.0;
/// Widest legend label line before it wraps.
const LEGEND_TEXT_MAX: f64 = 230.0;
/// Grid lines: black at these opacities, so they read as darker lines over a
/// shaded band as over white (`#e0e0e0` and `#f2f2f2` on white).
const GRID_OPACITY: &str = "0.12";
const MINOR_GRID_OPACITY: &str = "0.05";
const FRAME: Color = Color(68, 68, 68);

/// How an axis maps values.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Scale {
    /// Evenly.
    #[default]
    Linear,
    /// By the logarithm (non-positive values are not drawn).
    Log,
}

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Dash {
    /// Unbroken.
    #[default]
    Solid,
    /// Long dashes.
    Dashed,
    /// Dots.
    Dotted,
    /// Dashes and dots.
    DashDot,
}

impl Dash {
    fn pattern(self) -> Option<&'static str> {
        match self {
            Dash::Solid => None,
            Dash::Dashed => Some("7 4"),
            Dash::Dotted => Some("1.5 3"),
            Dash::DashDot => Some("8 3 2 3"),
        }
    }
}

/// How a line is stroked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Colour.
    pub color: Color,
    /// Width in pixels.
    pub width: f64,
    /// Dash pattern.
    pub dash: Dash,
}

impl Line {
    /// A solid line of width 2.
    pub fn solid(color: Color) -> Line {
        Line {
            color,
            width: 2.0,
            dash: Dash::Solid,
        }
    }
}

/// A marker's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape {
    /// ○
    Circle,
    /// □
    Square,
    /// ◇
    Diamond,
    /// △
    Triangle,
    /// ▽
    TriangleDown,
    /// ×
    Cross,
    /// +
    Plus,
}

impl Shape {
    /// The shapes in the order sets without a style take them.
    pub const ALL: [Shape; 7] = [
        Shape::Circle,
        Shape::Triangle,
        Shape::Cross,
        Shape::Square,
        Shape::Diamond,
        Shape::TriangleDown,
        Shape::Plus,
    ];
}

/// How a point is marked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    /// Shape.
    pub shape: Shape,
    /// Colour of the outline (and of the inside when filled).
    pub color: Color,
    /// Filled, or hollow (an outline only; crosses and pluses are always strokes).
    pub filled: bool,
    /// Half the marker's size, in pixels.
    pub size: f64,
    /// Outline width in pixels.
    pub stroke_width: f64,
}

impl Marker {
    /// A hollow marker of size 4.5 with a 1.6 px outline.
    pub fn hollow(shape: Shape, color: Color) -> Marker {
        Marker {
            shape,
            color,
            filled: false,
            size: 4.5,
            stroke_width: 1.6,
        }
    }

    /// A filled marker of size 4.5.
    pub fn filled(shape: Shape, color: Color) -> Marker {
        Marker {
            filled: true,
            ..Marker::hollow(shape, color)
        }
    }
}

/// One labelled line, drawn as segments (a gap between segments).
#[derive(Debug, Clone, Default)]
pub struct Curve {
    /// Legend text (none when empty).
    pub label: String,
    /// The segments, each a polyline.
    pub segments: Vec<Vec<(f64, f64)>>,
    /// Its stroke; `None`: the next palette colour, solid, width 2.
    pub line: Option<Line>,
}

/// One labelled set of points, drawn as markers.
#[derive(Debug, Clone, Default)]
pub struct Markers {
    /// Legend text (none when empty).
    pub label: String,
    /// The points.
    pub points: Vec<(f64, f64)>,
    /// Its marker; `None`: the next shape and palette colour, hollow.
    pub marker: Option<Marker>,
}

/// A shaded band over the full height of the plot area, between two abscissae
/// (a regime, say).
#[derive(Debug, Clone)]
pub struct Band {
    /// Legend text; bands with the same label share one legend entry.
    pub label: String,
    /// Left and right abscissae.
    pub from: f64,
    /// Right abscissa.
    pub to: f64,
    /// Fill (a light tint: lines are drawn over it).
    pub fill: Color,
}

/// One line of the legend.
#[derive(Debug, Clone)]
pub enum LegendEntry {
    /// A group heading, in bold, without a mark.
    Heading(String),
    /// A line sample.
    Line(Line, String),
    /// A marker.
    Marker(Marker, String),
    /// A shaded band sample (outlined, for light tints).
    Band(Color, String),
    /// A solid colour patch (a colour key).
    Swatch(Color, String),
}

/// A plot: bands, lines and markers on axes fitted to everything drawn, a
/// legend to the right of the plot area.
#[derive(Debug, Clone, Default)]
pub struct Figure {
    /// Caption above the plot (markup allowed).
    pub title: String,
    /// A smaller second caption line (none when empty).
    pub subtitle: String,
    /// The `<desc>` text; generated from the rest when empty.
    pub description: String,
    /// Horizontal axis name, with its unit.
    pub x_name: String,
    /// Vertical axis name, with its unit.
    pub y_name: String,
    /// Horizontal scale.
    pub x_scale: Scale,
    /// Vertical scale.
    pub y_scale: Scale,
    /// Shaded bands, drawn first.
    pub bands: Vec<Band>,
    /// Lines, coloured in order.
    pub curves: Vec<Curve>,
    /// Point sets, coloured after the lines.
    pub markers: Vec<Markers>,
    /// The legend; `None`: one entry per labelled curve, marker set and band label.
    pub legend: Option<Vec<LegendEntry>>,
    /// Width and height in pixels; `None`: 900 × 600 (taller if the legend needs it).
    pub size: Option<(f64, f64)>,
}

mod layout;
mod marks;
#[cfg(test)]
mod tests;
mod text;
mod ticks;

pub use self::text::text_width;

use self::marks::*;
use self::text::*;
use self::ticks::*;
