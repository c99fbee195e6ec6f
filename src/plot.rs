//! SVG figures: lines, markers and shaded bands on linear or logarithmic axes,
//! written as SVG text directly. [`Figure`] draws the service's sweep plots
//! (`image/svg+xml` from `/v1/sweeps`), the validation report's model curves
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

use std::fmt::Write as _;

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

// --- text -------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shift {
    Base,
    Sub,
    Super,
}

#[derive(Debug, Clone, PartialEq)]
struct Run {
    text: String,
    shift: Shift,
}

/// Splits markup into runs: `_x`, `_{…}` subscripts and `^x`, `^{…}` superscripts.
fn parse(markup: &str) -> Vec<Run> {
    let chars: Vec<char> = markup.chars().collect();
    let mut runs = Vec::new();
    let mut base = String::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if (c == '_' || c == '^') && i + 1 < chars.len() {
            let shift = if c == '_' { Shift::Sub } else { Shift::Super };
            let (text, next) = if chars[i + 1] == '{' {
                match chars[i + 2..].iter().position(|&c| c == '}') {
                    Some(n) => (chars[i + 2..i + 2 + n].iter().collect::<String>(), i + 3 + n),
                    None => (String::new(), i),
                }
            } else {
                let n = chars[i + 1..].iter().take_while(|c| c.is_alphanumeric()).count();
                (chars[i + 1..i + 1 + n].iter().collect(), i + 1 + n)
            };
            if !text.is_empty() {
                if !base.is_empty() {
                    runs.push(Run {
                        text: std::mem::take(&mut base),
                        shift: Shift::Base,
                    });
                }
                runs.push(Run { text, shift });
                i = next;
                continue;
            }
        }
        base.push(c);
        i += 1;
    }
    if !base.is_empty() || runs.is_empty() {
        runs.push(Run {
            text: base,
            shift: Shift::Base,
        });
    }
    runs
}

/// The markup as plain text (for `<desc>`): subscripts as `_x`, powers as `^x`.
fn plain(markup: &str) -> String {
    parse(markup)
        .into_iter()
        .map(|r| match r.shift {
            Shift::Base => r.text,
            Shift::Sub => format!("_{}", r.text),
            Shift::Super => format!("^{}", r.text),
        })
        .collect()
}

const SMALL: f64 = 0.72;

/// Advance of a character in em (DejaVu Sans; 0.7 for characters not listed).
#[allow(clippy::approx_constant)] // font metrics, not 1/π
fn advance(c: char) -> f64 {
    const ASCII: [f64; 95] = [
        0.318, 0.401, 0.460, 0.838, 0.636, 0.950, 0.780, 0.275, 0.390, 0.390, 0.500, 0.838, 0.318, 0.361,
        0.318, 0.337, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.636, 0.337, 0.337,
        0.838, 0.838, 0.838, 0.531, 1.000, 0.684, 0.686, 0.698, 0.770, 0.632, 0.575, 0.775, 0.752, 0.295,
        0.295, 0.656, 0.557, 0.863, 0.748, 0.787, 0.603, 0.787, 0.695, 0.635, 0.611, 0.732, 0.684, 0.989,
        0.685, 0.611, 0.685, 0.390, 0.337, 0.390, 0.838, 0.500, 0.500, 0.613, 0.635, 0.550, 0.635, 0.615,
        0.352, 0.635, 0.634, 0.278, 0.278, 0.579, 0.278, 0.974, 0.634, 0.612, 0.635, 0.635, 0.411, 0.521,
        0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525, 0.636, 0.337, 0.636, 0.838,
    ];
    match c {
        ' '..='~' => ASCII[c as usize - 32],
        '−' | '×' | '±' | '≤' | '≥' | '→' => 0.838,
        '·' => 0.318,
        '²' | '³' | '¹' | '⁰'..='⁹' | '₀'..='₉' => 0.401,
        '°' | '–' => 0.5,
        '—' | '…' => 1.0,
        'ω' => 0.837,
        'ι' => 0.338,
        'Ω' => 0.764,
        'α'..='ψ' => 0.62,
        'Α'..='Ω' => 0.72,
        _ => 0.7,
    }
}

fn runs_width(runs: &[Run], size: f64) -> f64 {
    runs.iter()
        .map(|r| {
            let s = if r.shift == Shift::Base {
                size
            } else {
                size * SMALL
            };
            r.text.chars().map(advance).sum::<f64>() * s
        })
        .sum()
}

/// Estimated width of `markup` at font size `size`.
pub fn text_width(markup: &str, size: f64) -> f64 {
    runs_width(&parse(markup), size)
}

/// Height above the baseline of a line of `markup` at `size` (a superscript raises it).
fn ascent(markup: &str, size: f64) -> f64 {
    if parse(markup).iter().any(|r| r.shift == Shift::Super) {
        size * (0.42 + SMALL * 0.93)
    } else {
        size * 0.93
    }
}

/// Depth below the baseline of a line of `markup` at `size` (a subscript lowers it).
fn descent(markup: &str, size: f64) -> f64 {
    if parse(markup).iter().any(|r| r.shift == Shift::Sub) {
        size * (0.28 + SMALL * 0.24)
    } else {
        size * 0.24
    }
}

/// Baselines of `lines` stacked from `start` (the top of the first) with
/// `gap` between one line's lowest point and the next one's highest, and where
/// the last one ends.
fn stack(lines: &[String], size: f64, start: f64, gap: f64) -> (Vec<f64>, f64) {
    let mut baselines = Vec::with_capacity(lines.len());
    let mut cursor = start;
    for (i, line) in lines.iter().enumerate() {
        if i > 0 {
            cursor += gap;
        }
        let baseline = cursor + ascent(line, size);
        baselines.push(baseline);
        cursor = baseline + descent(line, size);
    }
    (baselines, cursor)
}

fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// A coordinate or length with at most two decimals.
fn num(v: f64) -> String {
    let s = format!("{:.2}", v);
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" { "0".to_owned() } else { s }
}

/// Greedy word wrap of `markup` to lines at most `max` wide (a longer word stays whole).
fn wrap(markup: &str, size: f64, max: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in markup.split(' ').filter(|w| !w.is_empty()) {
        match lines.last_mut() {
            Some(line) if text_width(&format!("{line} {word}"), size) <= max => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_owned()),
        }
    }
    if lines.is_empty() {
        lines.push(String::new());
    }
    lines
}

/// Text anchoring.
#[derive(Debug, Clone, Copy)]
enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn as_str(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

struct Text<'a> {
    markup: &'a str,
    x: f64,
    /// The baseline.
    y: f64,
    size: f64,
    anchor: Anchor,
    fill: Color,
    bold: bool,
    rotate: bool,
    part: Option<&'a str>,
}

impl<'a> Text<'a> {
    fn new(markup: &'a str, x: f64, y: f64, size: f64, anchor: Anchor) -> Self {
        Text {
            markup,
            x,
            y,
            size,
            anchor,
            fill: TEXT,
            bold: false,
            rotate: false,
            part: None,
        }
    }

    fn write(&self, out: &mut String) {
        let _ = write!(
            out,
            r#"<text x="{}" y="{}" font-size="{}" fill="{}" text-anchor="{}""#,
            num(self.x),
            num(self.y),
            num(self.size),
            self.fill.hex(),
            self.anchor.as_str()
        );
        if self.bold {
            out.push_str(r#" font-weight="bold""#);
        }
        if self.rotate {
            let _ = write!(out, r#" transform="rotate(-90 {} {})""#, num(self.x), num(self.y));
        }
        if let Some(part) = self.part {
            let _ = write!(out, r#" data-part="{part}""#);
        }
        out.push('>');
        let mut offset = 0.0;
        for run in parse(self.markup) {
            let (target, small) = match run.shift {
                Shift::Base => (0.0, false),
                Shift::Sub => (0.28 * self.size, true),
                Shift::Super => (-0.42 * self.size, true),
            };
            let dy = target - offset;
            offset = target;
            if !small && dy == 0.0 {
                out.push_str(&escape(&run.text));
                continue;
            }
            out.push_str("<tspan");
            if dy != 0.0 {
                let _ = write!(out, r#" dy="{}""#, num(dy));
            }
            if small {
                let _ = write!(out, r#" font-size="{}""#, num(self.size * SMALL));
            }
            let _ = write!(out, ">{}</tspan>", escape(&run.text));
        }
        out.push_str("</text>\n");
    }
}

// --- axes and ticks ----------------------------------------------------------

/// The range of the finite values (positive ones on a log scale), padded.
fn extent(values: impl Iterator<Item = f64>, scale: Scale) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (scale == Scale::Linear || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    match scale {
        Scale::Linear if !lo.is_finite() => (0.0, 1.0),
        Scale::Linear => {
            let pad = if hi > lo {
                (hi - lo) * 0.05
            } else {
                if lo == 0.0 { 0.05 } else { lo.abs() * 0.05 }
            };
            (lo - pad, hi + pad)
        }
        Scale::Log if !lo.is_finite() => (1.0, 10.0),
        Scale::Log => {
            let (a, b) = (lo.log10(), hi.log10());
            let pad = if b > a { (b - a) * 0.04 } else { 0.5 };
            (10f64.powf(a - pad), 10f64.powf(b + pad))
        }
    }
}

/// One axis: its values' range mapped onto a pixel range.
#[derive(Debug, Clone, Copy)]
struct Axis {
    scale: Scale,
    lo: f64,
    hi: f64,
    /// Pixel of `lo`.
    from: f64,
    /// Pixel of `hi`.
    to: f64,
}

impl Axis {
    fn t(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
        }
    }

    fn at(&self, v: f64) -> f64 {
        self.from + self.t(v) * (self.to - self.from)
    }

    fn shows(&self, v: f64) -> bool {
        v.is_finite() && (self.scale == Scale::Linear || v > 0.0)
    }
}

/// An axis's ticks: labelled ones with grid lines, unlabelled minor ones.
#[derive(Debug, Clone, Default, PartialEq)]
struct Ticks {
    major: Vec<(f64, String)>,
    minor: Vec<f64>,
    /// A factor every label shares (`×10^{n}`), said once after the axis name.
    factor: Option<String>,
}

/// The decimals that write `step` exactly.
fn decimals(step: f64) -> usize {
    (0..=15)
        .find(|&d| {
            let scaled = step * 10f64.powi(d as i32);
            (scaled - scaled.round()).abs() <= 1e-6 * scaled.abs().max(1.0)
        })
        .unwrap_or(15)
}

/// A number as a tick label: `decimals` decimals, a true minus, no negative zero.
fn fixed(value: f64, decimals: usize) -> String {
    let s = format!("{value:.decimals$}");
    let zero = s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.');
    if zero {
        s.trim_start_matches('-').to_owned()
    } else {
        s.replace('-', "−")
    }
}

fn power_of_ten(k: i32) -> String {
    format!("10^{{{}}}", k.to_string().replace('-', "−"))
}

/// Candidate linear tick sets for `[lo, hi]`, densest first.
fn linear_candidates(lo: f64, hi: f64) -> Vec<Ticks> {
    let span = hi - lo;
    if span.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !span.is_finite() {
        return vec![Ticks::default()];
    }
    let magnitude = lo.abs().max(hi.abs());
    let exponent = magnitude.log10().floor() as i32;
    let factored = !(1e-3..1e5).contains(&magnitude);
    let scale = if factored { 10f64.powi(exponent) } else { 1.0 };
    let k0 = (span / 30.0).log10().floor() as i32;
    let mut candidates = Vec::new();
    for k in k0..=k0 + 3 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let step = m * 10f64.powi(k);
            let first = (lo / step).ceil() as i64;
            let last = (hi / step).floor() as i64;
            if last - first > 40 || last < first + 1 {
                continue;
            }
            let d = decimals(step / scale);
            let major = (first..=last)
                .map(|i| {
                    let v = i as f64 * step;
                    (v, fixed(v / scale, d))
                })
                .collect();
            candidates.push(Ticks {
                major,
                minor: Vec::new(),
                factor: factored.then(|| format!("×{}", power_of_ten(exponent))),
            });
        }
    }
    if candidates.is_empty() {
        let d = decimals(span / scale).min(6);
        candidates.push(Ticks {
            major: vec![(lo, fixed(lo / scale, d)), (hi, fixed(hi / scale, d))],
            minor: Vec::new(),
            factor: factored.then(|| format!("×{}", power_of_ten(exponent))),
        });
    }
    candidates
}

/// Candidate logarithmic tick sets for `[lo, hi]`, densest first: `1 2 5`
/// steps written as decimals when the axis spans a few decades, powers of ten
/// (every decade, then every second, third, …) otherwise.
fn log_candidates(lo: f64, hi: f64) -> Vec<Ticks> {
    let (a, b) = (lo.log10(), hi.log10());
    let (k0, k1) = (a.floor() as i32, b.ceil() as i32);
    let inside = |v: f64| v >= lo * (1.0 - 1e-12) && v <= hi * (1.0 + 1e-12);
    let decimal = |m: f64, k: i32| fixed(m * 10f64.powi(k), (-k).max(0) as usize);
    let mut candidates = Vec::new();
    if b - a <= 3.0 {
        for mantissas in [&[1.0, 2.0, 5.0][..], &[1.0][..]] {
            let mut ticks = Ticks::default();
            for k in k0..=k1 {
                for m in 1..10 {
                    let v = f64::from(m) * 10f64.powi(k);
                    if !inside(v) {
                        continue;
                    }
                    if mantissas.contains(&f64::from(m)) {
                        ticks.major.push((v, decimal(f64::from(m), k)));
                    } else {
                        ticks.minor.push(v);
                    }
                }
            }
            if ticks.major.len() >= 2 {
                candidates.push(ticks);
            }
        }
    }
    for every in 1..=((k1 - k0).max(1)) {
        let mut ticks = Ticks::default();
        for k in k0..=k1 {
            let v = 10f64.powi(k);
            if inside(v) && k.rem_euclid(every) == 0 {
                ticks.major.push((v, power_of_ten(k)));
            } else if inside(v) {
                ticks.minor.push(v);
            }
            if every == 1 {
                ticks
                    .minor
                    .extend((2..10).map(|m| f64::from(m) * v).filter(|&v| inside(v)));
            }
        }
        if ticks.major.len() >= 2 || every == (k1 - k0).max(1) {
            candidates.push(ticks);
        }
    }
    candidates
}

/// The densest candidate whose labels keep `gap` pixels apart along the axis
/// (`extent` gives a label's size along it) and whose ticks are `spacing`
/// pixels apart at least, else the sparsest.
fn choose(
    axis: &Axis,
    candidates: Vec<Ticks>,
    extent: impl Fn(&str) -> f64,
    gap: f64,
    spacing: f64,
) -> Ticks {
    let fits = |t: &Ticks| {
        let mut at: Vec<f64> = t.major.iter().map(|(v, _)| axis.at(*v)).collect();
        at.sort_by(f64::total_cmp);
        if at.windows(2).any(|w| w[1] - w[0] < spacing) {
            return false;
        }
        let mut spans: Vec<(f64, f64)> = t
            .major
            .iter()
            .map(|(v, label)| {
                let p = axis.at(*v);
                let half = extent(label) / 2.0;
                (p - half, p + half)
            })
            .collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        spans.windows(2).all(|w| w[1].0 - w[0].1 >= gap)
    };
    let last = candidates.len().saturating_sub(1);
    candidates
        .into_iter()
        .enumerate()
        .find(|(i, t)| *i == last || fits(t))
        .map(|(_, t)| t)
        .unwrap_or_default()
}

fn candidates(scale: Scale, lo: f64, hi: f64) -> Vec<Ticks> {
    match scale {
        Scale::Linear => linear_candidates(lo, hi),
        Scale::Log => log_candidates(lo, hi),
    }
}

// --- marks -----------------------------------------------------------------

fn write_marker(out: &mut String, m: &Marker, x: f64, y: f64) {
    let s = m.size;
    let stroked_only = matches!(m.shape, Shape::Cross | Shape::Plus);
    let fill = if m.filled && !stroked_only {
        m.color.hex()
    } else {
        "none".to_owned()
    };
    let paint = format!(
        r#"fill="{fill}" stroke="{}" stroke-width="{}" stroke-linejoin="round""#,
        m.color.hex(),
        num(m.stroke_width)
    );
    let p = |dx: f64, dy: f64| format!("{} {}", num(x + dx), num(y + dy));
    let _ = match m.shape {
        Shape::Circle => writeln!(
            out,
            r#"<circle cx="{}" cy="{}" r="{}" {paint}/>"#,
            num(x),
            num(y),
            num(s)
        ),
        Shape::Square => {
            let h = s * 0.9;
            writeln!(
                out,
                r#"<rect x="{}" y="{}" width="{}" height="{}" {paint}/>"#,
                num(x - h),
                num(y - h),
                num(2.0 * h),
                num(2.0 * h)
            )
        }
        Shape::Diamond => {
            let h = s * 1.25;
            writeln!(
                out,
                r#"<path d="M{} L{} L{} L{} Z" {paint}/>"#,
                p(0.0, -h),
                p(h, 0.0),
                p(0.0, h),
                p(-h, 0.0)
            )
        }
        Shape::Triangle => writeln!(
            out,
            r#"<path d="M{} L{} L{} Z" {paint}/>"#,
            p(0.0, -1.2 * s),
            p(1.1 * s, 0.8 * s),
            p(-1.1 * s, 0.8 * s)
        ),
        Shape::TriangleDown => writeln!(
            out,
            r#"<path d="M{} L{} L{} Z" {paint}/>"#,
            p(0.0, 1.2 * s),
            p(1.1 * s, -0.8 * s),
            p(-1.1 * s, -0.8 * s)
        ),
        Shape::Cross => writeln!(
            out,
            r#"<path d="M{} L{} M{} L{}" {paint} stroke-linecap="round"/>"#,
            p(-s, -s),
            p(s, s),
            p(s, -s),
            p(-s, s)
        ),
        Shape::Plus => {
            let h = s * 1.2;
            writeln!(
                out,
                r#"<path d="M{} L{} M{} L{}" {paint} stroke-linecap="round"/>"#,
                p(-h, 0.0),
                p(h, 0.0),
                p(0.0, -h),
                p(0.0, h)
            )
        }
    };
}

fn line_paint(line: &Line) -> String {
    let mut s = format!(
        r#"fill="none" stroke="{}" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round""#,
        line.color.hex(),
        num(line.width)
    );
    if let Some(pattern) = line.dash.pattern() {
        let _ = write!(s, r#" stroke-dasharray="{pattern}""#);
    }
    s
}

// --- layout and drawing ------------------------------------------------------

/// A legend entry laid out: its mark, its label's lines and their baselines.
struct LegendRow {
    entry: LegendEntry,
    lines: Vec<String>,
    baselines: Vec<f64>,
}

impl LegendEntry {
    fn label(&self) -> &str {
        match self {
            LegendEntry::Heading(l)
            | LegendEntry::Line(_, l)
            | LegendEntry::Marker(_, l)
            | LegendEntry::Band(_, l)
            | LegendEntry::Swatch(_, l) => l,
        }
    }
}

const LEGEND_MARK: f64 = 30.0;
/// From the plot area's bottom to the lowest point of the x tick labels
/// (room for a superscript above and a descent below).
const X_TICKS_DEPTH: f64 = TICK_LENGTH + 3.0 + TICK_SIZE * (0.42 + SMALL * 0.93 + 0.24);

impl Figure {
    fn line_of(&self, i: usize) -> Line {
        self.curves[i]
            .line
            .unwrap_or_else(|| Line::solid(PALETTE[i % PALETTE.len()]))
    }

    fn marker_of(&self, i: usize) -> Marker {
        self.markers[i].marker.unwrap_or_else(|| {
            Marker::hollow(
                Shape::ALL[i % Shape::ALL.len()],
                PALETTE[(self.curves.len() + i) % PALETTE.len()],
            )
        })
    }

    /// The legend's entries: the given ones, or one per labelled curve, marker
    /// set and band label.
    pub fn legend_entries(&self) -> Vec<LegendEntry> {
        if let Some(legend) = &self.legend {
            return legend.clone();
        }
        let mut entries = Vec::new();
        for (i, c) in self.curves.iter().enumerate() {
            if !c.label.is_empty() {
                entries.push(LegendEntry::Line(self.line_of(i), c.label.clone()));
            }
        }
        for (i, m) in self.markers.iter().enumerate() {
            if !m.label.is_empty() {
                entries.push(LegendEntry::Marker(self.marker_of(i), m.label.clone()));
            }
        }
        let mut seen: Vec<&str> = Vec::new();
        for b in &self.bands {
            if !b.label.is_empty() && !seen.contains(&b.label.as_str()) {
                seen.push(&b.label);
                entries.push(LegendEntry::Band(b.fill, b.label.clone()));
            }
        }
        entries
    }

    fn describe(&self) -> String {
        if !self.description.is_empty() {
            return self.description.clone();
        }
        let mut d = String::new();
        if !self.title.is_empty() {
            let _ = write!(d, "{}. ", plain(&self.title));
        }
        if !self.subtitle.is_empty() {
            let _ = write!(d, "{}. ", plain(&self.subtitle));
        }
        let _ = write!(
            d,
            "Vertical axis: {}{}; horizontal axis: {}{}.",
            plain(&self.y_name),
            if self.y_scale == Scale::Log {
                " (logarithmic)"
            } else {
                ""
            },
            plain(&self.x_name),
            if self.x_scale == Scale::Log {
                " (logarithmic)"
            } else {
                ""
            },
        );
        let labels: Vec<String> = self
            .legend_entries()
            .iter()
            .filter(|e| !matches!(e, LegendEntry::Heading(_)))
            .map(|e| plain(e.label()))
            .collect();
        if !labels.is_empty() {
            let _ = write!(d, " Legend: {}.", labels.join("; "));
        }
        d
    }

    /// The figure as an SVG document.
    pub fn render(&self) -> String {
        let (width, height) = self.size.unwrap_or((900.0, 600.0));
        // Everything drawn, for the axes' ranges.
        let lines = self.curves.iter().flat_map(|c| c.segments.iter().flatten());
        let points = self.markers.iter().flat_map(|m| m.points.iter());
        let all = || lines.clone().chain(points.clone());
        let bands = self.bands.iter().flat_map(|b| [b.from, b.to]);
        let (x_lo, x_hi) = extent(all().map(|p| p.0).chain(bands), self.x_scale);
        let (y_lo, y_hi) = extent(all().map(|p| p.1), self.y_scale);

        // The legend: its rows and width.
        // Baselines from the legend box's top.
        let mut cursor = 9.0;
        let rows: Vec<LegendRow> = self
            .legend_entries()
            .into_iter()
            .enumerate()
            .map(|(i, entry)| {
                let lines = wrap(entry.label(), LEGEND_SIZE, LEGEND_TEXT_MAX);
                if i > 0 {
                    cursor += if matches!(entry, LegendEntry::Heading(_)) {
                        10.0
                    } else {
                        5.0
                    };
                }
                let (baselines, end) = stack(&lines, LEGEND_SIZE, cursor, 2.0);
                cursor = end;
                LegendRow {
                    entry,
                    lines,
                    baselines,
                }
            })
            .collect();
        let legend_text = rows
            .iter()
            .flat_map(|r| {
                let indent = if matches!(r.entry, LegendEntry::Heading(_)) {
                    0.0
                } else {
                    LEGEND_MARK
                };
                r.lines.iter().map(move |l| indent + text_width(l, LEGEND_SIZE))
            })
            .fold(0.0, f64::max);
        let legend_width = if rows.is_empty() { 0.0 } else { legend_text + 24.0 };
        let legend_height = if rows.is_empty() { 0.0 } else { cursor + 9.0 };

        // Vertical layout: title on top; tick labels and the axis name below.
        let title_lines = if self.title.is_empty() {
            Vec::new()
        } else {
            wrap(&self.title, TITLE_SIZE, width - 2.0 * PAD)
        };
        let subtitle_lines = if self.subtitle.is_empty() {
            Vec::new()
        } else {
            wrap(&self.subtitle, SUBTITLE_SIZE, width - 2.0 * PAD)
        };
        let (title_baselines, end) = stack(&title_lines, TITLE_SIZE, PAD, 3.0);
        let (subtitle_baselines, end) = stack(&subtitle_lines, SUBTITLE_SIZE, end + 4.0, 2.0);
        let top = if title_lines.is_empty() && subtitle_lines.is_empty() {
            PAD + TICK_SIZE * 0.6
        } else {
            end + 12.0
        };
        let right_reserved = if rows.is_empty() {
            PAD
        } else {
            PAD + legend_width + 20.0
        };
        let guess_width = width - right_reserved - PAD - 110.0;
        let x_title = wrap(&self.x_name, AXIS_SIZE, guess_width);
        let x_title_height = stack(&x_title, AXIS_SIZE, 0.0, 3.0).1;
        let bottom_margin = X_TICKS_DEPTH + 8.0 + x_title_height + PAD;
        let height = height.max(top + legend_height + bottom_margin);
        let bottom = height - bottom_margin;
        let mut y_axis = Axis {
            scale: self.y_scale,
            lo: y_lo,
            hi: y_hi,
            from: bottom,
            to: top,
        };
        let y_ticks = choose(
            &y_axis,
            candidates(self.y_scale, y_lo, y_hi),
            |_| TICK_SIZE * 1.1,
            TICK_SIZE * 0.9,
            36.0,
        );
        let y_title_text = match &y_ticks.factor {
            Some(f) => format!("{} {f}", self.y_name),
            None => self.y_name.clone(),
        };
        let y_title = wrap(&y_title_text, AXIS_SIZE, bottom - top);
        let y_labels_width = y_ticks
            .major
            .iter()
            .map(|(_, l)| text_width(l, TICK_SIZE))
            .fold(0.0, f64::max);
        let (y_title_baselines, y_title_end) = stack(&y_title, AXIS_SIZE, PAD, 3.0);
        let left = y_title_end + 8.0 + y_labels_width + TICK_LENGTH + 5.0;
        let mut right = width - right_reserved;
        let mut x_axis = Axis {
            scale: self.x_scale,
            lo: x_lo,
            hi: x_hi,
            from: left,
            to: right,
        };
        let mut x_ticks = choose(
            &x_axis,
            candidates(self.x_scale, x_lo, x_hi),
            |l| text_width(l, TICK_SIZE),
            12.0,
            50.0,
        );
        // The last x tick label must not run into the legend or off the edge.
        let overhang = x_ticks
            .major
            .iter()
            .map(|(v, l)| x_axis.at(*v) + text_width(l, TICK_SIZE) / 2.0)
            .fold(f64::NEG_INFINITY, f64::max);
        let limit = if rows.is_empty() {
            width - PAD
        } else {
            right + 14.0
        };
        if overhang > limit {
            right -= overhang - limit;
            x_axis.to = right;
            x_ticks = choose(
                &x_axis,
                candidates(self.x_scale, x_lo, x_hi),
                |l| text_width(l, TICK_SIZE),
                12.0,
                50.0,
            );
        }
        y_axis.from = bottom;

        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" role="img" font-family="{FONT}">"#,
            w = num(width),
            h = num(height)
        );
        let title_text = [&self.title, &self.subtitle]
            .iter()
            .filter(|t| !t.is_empty())
            .map(|t| plain(t))
            .collect::<Vec<_>>()
            .join(": ");
        let title_text = if title_text.is_empty() {
            format!("{} against {}", plain(&self.y_name), plain(&self.x_name))
        } else {
            title_text
        };
        let _ = writeln!(out, "<title>{}</title>", escape(&title_text));
        let _ = writeln!(out, "<desc>{}</desc>", escape(&self.describe()));
        let _ = writeln!(
            out,
            r#"<rect x="0" y="0" width="{}" height="{}" fill="{}"/>"#,
            num(width),
            num(height),
            WHITE.hex()
        );

        // Bands.
        if !self.bands.is_empty() {
            out.push_str("<g data-part=\"bands\">\n");
            for b in &self.bands {
                if !(x_axis.shows(b.from) && x_axis.shows(b.to)) {
                    continue;
                }
                let (a, c) = (x_axis.at(b.from), x_axis.at(b.to));
                let _ = writeln!(
                    out,
                    r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}" data-label="{}"/>"#,
                    num(a.min(c)),
                    num(top),
                    num((c - a).abs()),
                    num(bottom - top),
                    b.fill.hex(),
                    escape(&plain(&b.label))
                );
            }
            out.push_str("</g>\n");
        }

        // Grid.
        out.push_str("<g data-part=\"grid\">\n");
        for (axis, ticks, vertical) in [(&x_axis, &x_ticks, true), (&y_axis, &y_ticks, false)] {
            for (v, opacity) in ticks
                .minor
                .iter()
                .map(|v| (*v, MINOR_GRID_OPACITY))
                .chain(ticks.major.iter().map(|(v, _)| (*v, GRID_OPACITY)))
            {
                let p = num(axis.at(v));
                let _ = if vertical {
                    writeln!(
                        out,
                        r##"<line x1="{p}" y1="{}" x2="{p}" y2="{}" stroke="#000000" stroke-opacity="{opacity}" stroke-width="1"/>"##,
                        num(top),
                        num(bottom),
                    )
                } else {
                    writeln!(
                        out,
                        r##"<line x1="{}" y1="{p}" x2="{}" y2="{p}" stroke="#000000" stroke-opacity="{opacity}" stroke-width="1"/>"##,
                        num(left),
                        num(right),
                    )
                };
            }
        }
        out.push_str("</g>\n");

        // Curves.
        out.push_str("<g data-part=\"curves\">\n");
        for (i, curve) in self.curves.iter().enumerate() {
            let line = self.line_of(i);
            let mut d = String::new();
            let mut dots = Vec::new();
            for segment in &curve.segments {
                let shown: Vec<(f64, f64)> = segment
                    .iter()
                    .filter(|(x, y)| x_axis.shows(*x) && y_axis.shows(*y))
                    .map(|&(x, y)| (x_axis.at(x), y_axis.at(y)))
                    .collect();
                if shown.len() == 1 {
                    dots.push(shown[0]);
                }
                for (j, (x, y)) in shown.iter().enumerate() {
                    let _ = write!(d, "{}{} {} ", if j == 0 { 'M' } else { 'L' }, num(*x), num(*y));
                }
            }
            if !d.is_empty() {
                let _ = writeln!(
                    out,
                    r#"<path d="{}" {} data-series="{i}"/>"#,
                    d.trim_end(),
                    line_paint(&line)
                );
            }
            for (x, y) in dots {
                let _ = writeln!(
                    out,
                    r#"<circle cx="{}" cy="{}" r="{}" fill="{}" data-series="{i}"/>"#,
                    num(x),
                    num(y),
                    num(line.width),
                    line.color.hex()
                );
            }
        }
        out.push_str("</g>\n");

        // Markers.
        out.push_str("<g data-part=\"markers\">\n");
        for (i, set) in self.markers.iter().enumerate() {
            let marker = self.marker_of(i);
            let _ = writeln!(out, r#"<g data-series="{i}">"#);
            for &(x, y) in &set.points {
                if x_axis.shows(x) && y_axis.shows(y) {
                    write_marker(&mut out, &marker, x_axis.at(x), y_axis.at(y));
                }
            }
            out.push_str("</g>\n");
        }
        out.push_str("</g>\n");

        // Frame and tick marks.
        out.push_str("<g data-part=\"frame\">\n");
        let _ = writeln!(
            out,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="{}" stroke-width="1"/>"#,
            num(left),
            num(top),
            num(right - left),
            num(bottom - top),
            FRAME.hex()
        );
        let mut marks = String::new();
        for (v, _) in &x_ticks.major {
            let x = num(x_axis.at(*v));
            let _ = write!(marks, "M{x} {} L{x} {} ", num(bottom), num(bottom + TICK_LENGTH));
        }
        for (v, _) in &y_ticks.major {
            let y = num(y_axis.at(*v));
            let _ = write!(marks, "M{} {y} L{} {y} ", num(left - TICK_LENGTH), num(left));
        }
        if !marks.is_empty() {
            let _ = writeln!(
                out,
                r#"<path d="{}" fill="none" stroke="{}" stroke-width="1"/>"#,
                marks.trim_end(),
                FRAME.hex()
            );
        }
        out.push_str("</g>\n");

        // Tick labels.
        out.push_str("<g data-part=\"x-ticks\">\n");
        let x_ticks_ascent = x_ticks
            .major
            .iter()
            .map(|(_, l)| ascent(l, TICK_SIZE))
            .fold(0.0, f64::max);
        for (v, label) in &x_ticks.major {
            let mut t = Text::new(
                label,
                x_axis.at(*v),
                bottom + TICK_LENGTH + 3.0 + x_ticks_ascent,
                TICK_SIZE,
                Anchor::Middle,
            );
            t.fill = MUTED;
            t.write(&mut out);
        }
        out.push_str("</g>\n<g data-part=\"y-ticks\">\n");
        for (v, label) in &y_ticks.major {
            let mut t = Text::new(
                label,
                left - TICK_LENGTH - 5.0,
                y_axis.at(*v) + TICK_SIZE * 0.36,
                TICK_SIZE,
                Anchor::End,
            );
            t.fill = MUTED;
            t.write(&mut out);
        }
        out.push_str("</g>\n");

        // Axis names.
        let x_title_text = match &x_ticks.factor {
            Some(f) => format!("{} {f}", self.x_name),
            None => self.x_name.clone(),
        };
        let x_title = if x_title_text == self.x_name {
            x_title
        } else {
            wrap(&x_title_text, AXIS_SIZE, right - left)
        };
        let (baselines, _) = stack(&x_title, AXIS_SIZE, bottom + X_TICKS_DEPTH + 8.0, 3.0);
        for (line, y) in x_title.iter().zip(baselines) {
            let mut t = Text::new(line, (left + right) / 2.0, y, AXIS_SIZE, Anchor::Middle);
            t.part = Some("x-title");
            t.write(&mut out);
        }
        // Rotated: each line's baseline is its right edge, stacked from the left.
        for (line, x) in y_title.iter().zip(y_title_baselines) {
            let mut t = Text::new(line, x, (top + bottom) / 2.0, AXIS_SIZE, Anchor::Middle);
            t.rotate = true;
            t.part = Some("y-title");
            t.write(&mut out);
        }

        // Title.
        for (line, y) in title_lines.iter().zip(title_baselines) {
            let mut t = Text::new(line, width / 2.0, y, TITLE_SIZE, Anchor::Middle);
            t.part = Some("title");
            t.write(&mut out);
        }
        for (line, y) in subtitle_lines.iter().zip(subtitle_baselines) {
            let mut t = Text::new(line, width / 2.0, y, SUBTITLE_SIZE, Anchor::Middle);
            t.fill = MUTED;
            t.part = Some("title");
            t.write(&mut out);
        }

        // Legend, right of the plot area.
        if !rows.is_empty() {
            let lx = right + 20.0;
            let _ = writeln!(out, r#"<g data-part="legend">"#);
            let _ = writeln!(
                out,
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}" stroke="{}" stroke-width="1" data-part="legend-box"/>"#,
                num(lx),
                num(top),
                num(legend_width),
                num(legend_height),
                WHITE.hex(),
                Color(170, 170, 170).hex()
            );
            for row in &rows {
                let heading = matches!(row.entry, LegendEntry::Heading(_));
                // The mark at the middle of the first line's lower-case letters.
                let mid = top + row.baselines[0] - LEGEND_SIZE * 0.36;
                let mark_x = lx + 10.0;
                match &row.entry {
                    LegendEntry::Heading(_) => {}
                    LegendEntry::Line(line, _) => {
                        let _ = writeln!(
                            out,
                            r#"<path d="M{} {} L{} {}" {}/>"#,
                            num(mark_x),
                            num(mid),
                            num(mark_x + 22.0),
                            num(mid),
                            line_paint(line)
                        );
                    }
                    LegendEntry::Marker(marker, _) => write_marker(&mut out, marker, mark_x + 11.0, mid),
                    LegendEntry::Band(fill, _) | LegendEntry::Swatch(fill, _) => {
                        let outline = if matches!(row.entry, LegendEntry::Band(..)) {
                            format!(r#" stroke="{}" stroke-width="0.75""#, Color(140, 140, 140).hex())
                        } else {
                            String::new()
                        };
                        let _ = writeln!(
                            out,
                            r#"<rect x="{}" y="{}" width="22" height="12" fill="{}"{outline}/>"#,
                            num(mark_x),
                            num(mid - 6.0),
                            fill.hex()
                        );
                    }
                }
                let text_x = if heading {
                    lx + 10.0
                } else {
                    lx + 10.0 + LEGEND_MARK
                };
                for (line, y) in row.lines.iter().zip(&row.baselines) {
                    let mut t = Text::new(line, text_x, top + y, LEGEND_SIZE, Anchor::Start);
                    t.bold = heading;
                    t.write(&mut out);
                }
            }
            out.push_str("</g>\n");
        }
        out.push_str("</svg>\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(d: &str) -> Vec<&str> {
        d.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
            .filter(|s| !s.is_empty())
            .collect()
    }

    fn attribute<'a>(svg: &'a str, element: &str, name: &str) -> Vec<&'a str> {
        svg.match_indices(&format!("<{element} "))
            .filter_map(|(i, _)| {
                let tag = &svg[i..i + svg[i..].find('>')?];
                let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
                Some(&tag[start..start + tag[start..].find('"')?])
            })
            .collect()
    }

    fn texts(svg: &str, part: &str) -> Vec<String> {
        let open = format!("<g data-part=\"{part}\">");
        let Some(start) = svg.find(&open) else {
            return Vec::new();
        };
        let body = &svg[start + open.len()..];
        let body = &body[..body.find("</g>").unwrap_or(body.len())];
        body.split("<text ")
            .skip(1)
            .map(|t| {
                let inner = &t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()];
                // The text without tags, superscripts marked by ^.
                let mut s = String::new();
                let mut in_tag = false;
                for (i, c) in inner.char_indices() {
                    match c {
                        '<' => {
                            in_tag = true;
                            if inner[i..].starts_with("<tspan") {
                                s.push('^');
                            }
                        }
                        '>' => in_tag = false,
                        _ if !in_tag => s.push(c),
                        _ => {}
                    }
                }
                s
            })
            .collect()
    }

    fn line(points: &[(f64, f64)]) -> Curve {
        Curve {
            label: "line".into(),
            segments: vec![points.to_vec()],
            line: None,
        }
    }

    #[test]
    fn markup_makes_subscripts_and_superscripts() {
        let runs = parse("V_ct (m/s) and 10^{−3}, T_L*");
        let shifts: Vec<(&str, Shift)> = runs.iter().map(|r| (r.text.as_str(), r.shift)).collect();
        assert_eq!(
            shifts,
            [
                ("V", Shift::Base),
                ("ct", Shift::Sub),
                (" (m/s) and 10", Shift::Base),
                ("−3", Shift::Super),
                (", T", Shift::Base),
                ("L", Shift::Sub),
                ("*", Shift::Base),
            ]
        );
        assert_eq!(plain("V_ct / (μ V_n)"), "V_ct / (μ V_n)");
        assert_eq!(parse("a_ b")[0].text, "a_ b", "a lone _ is text");
    }

    #[test]
    fn linear_ticks_share_one_format_and_have_no_negative_zero() {
        for (lo, hi) in [
            (-0.34, 0.12),
            (-1.0, 5.0),
            (0.0, 0.003),
            (-2e6, 3e7),
            (0.55, 0.5500001),
            (617.0, 618.0),
        ] {
            for ticks in linear_candidates(lo, hi) {
                let decimals: Vec<usize> = ticks
                    .major
                    .iter()
                    .map(|(_, l)| l.split('.').nth(1).map_or(0, str::len))
                    .collect();
                assert!(decimals.windows(2).all(|w| w[0] == w[1]), "{lo}..{hi}: {ticks:?}");
                for (v, l) in &ticks.major {
                    let value: f64 = l.replace('−', "-").parse().expect("a number");
                    assert!(!(l.starts_with('-') || value == 0.0 && l.starts_with('−')), "{l}");
                    assert!(!l.contains('e'), "{l}");
                    if *v < 0.0 && v.abs() > 1e-9 * (hi - lo) {
                        assert!(l.starts_with('−'), "{v} {l}");
                    }
                }
            }
        }
        let big = &linear_candidates(-2e6, 3e7)[0];
        assert_eq!(big.factor.as_deref(), Some("×10^{7}"));
        assert_eq!(fixed(-2.7e-17, 1), "0.0");
        assert_eq!(fixed(-0.25, 2), "−0.25");
    }

    #[test]
    fn log_ticks_are_powers_of_ten_over_decades_and_1_2_5_over_a_few() {
        for ticks in log_candidates(0.3, 3e19) {
            assert!(
                ticks.major.iter().all(|(_, l)| l.starts_with("10^{")),
                "{ticks:?}"
            );
        }
        let few = &log_candidates(0.15, 30.0)[0];
        let labels: Vec<&str> = few.major.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["0.2", "0.5", "1", "2", "5", "10", "20"]);
    }

    #[test]
    fn a_wide_log_axis_labels_every_decade_it_has_room_for_with_superscripts() {
        let figure = Figure {
            title: "errors".into(),
            x_name: "time (ns)".into(),
            y_name: "error".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            markers: vec![Markers {
                label: "points".into(),
                points: vec![(30.0, 0.5), (27000.0, 8.7e18), (400.0, 1e4)],
                marker: None,
            }],
            ..Figure::default()
        };
        let svg = figure.render();
        let y = texts(&svg, "y-ticks");
        assert!(y.len() >= 5, "{y:?}");
        assert!(y.iter().all(|l| l.starts_with("10^")), "{y:?}");
        assert!(y.iter().any(|l| l == "10^18"), "{y:?}");
        let x = texts(&svg, "x-ticks");
        assert!(x.iter().all(|l| l.starts_with("10^")), "{x:?}");
    }

    #[test]
    fn coordinates_keep_two_decimals_and_are_not_snapped_to_pixels() {
        let points: Vec<(f64, f64)> = (0..50)
            .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
            .collect();
        let svg = Figure {
            x_name: "x".into(),
            y_name: "y".into(),
            curves: vec![line(&points)],
            ..Figure::default()
        }
        .render();
        let d = attribute(&svg, "path", "d");
        let curve = d.iter().find(|d| d.matches('L').count() > 40).expect("the curve");
        let coords = numbers(curve);
        assert!(coords.len() >= 100);
        let fractional = coords.iter().filter(|n| n.contains('.')).count();
        assert!(fractional > coords.len() / 2, "{curve}");
        assert!(
            coords
                .iter()
                .all(|n| n.split('.').nth(1).is_none_or(|f| f.len() <= 2)),
            "{curve}"
        );
    }

    #[test]
    fn no_style_element_or_attribute_and_a_title_and_description() {
        let svg = Figure {
            title: "A title with V_ct".into(),
            x_name: "x".into(),
            y_name: "y".into(),
            curves: vec![line(&[(0.0, 0.0), (1.0, 1.0)])],
            markers: vec![Markers {
                label: "m".into(),
                points: vec![(0.5, 0.5)],
                marker: None,
            }],
            bands: vec![Band {
                label: "sliding".into(),
                from: 0.0,
                to: 0.5,
                fill: Color(253, 228, 204),
            }],
            ..Figure::default()
        }
        .render();
        assert!(!svg.contains("<style") && !svg.contains("style="), "{svg}");
        assert!(svg.contains("<title>A title with V_ct</title>"), "{svg}");
        assert!(
            svg.contains("<desc>") && svg.contains("Legend: line; m; sliding."),
            "{svg}"
        );
        assert!(svg.contains(r#"role="img""#));
    }

    #[test]
    fn legend_marks_are_the_marks_drawn() {
        let marker = Marker::hollow(Shape::Triangle, PALETTE[3]);
        let svg = Figure {
            x_name: "x".into(),
            y_name: "y".into(),
            markers: vec![Markers {
                label: "data".into(),
                points: vec![(0.0, 0.0), (1.0, 2.0)],
                marker: Some(marker),
            }],
            ..Figure::default()
        }
        .render();
        let legend = &svg[svg.find("data-part=\"legend\"").unwrap()..];
        let drawn =
            &svg[svg.find("data-part=\"markers\"").unwrap()..svg.find("data-part=\"frame\"").unwrap()];
        let paint = format!(r#"fill="none" stroke="{}" stroke-width="1.6""#, PALETTE[3].hex());
        assert_eq!(drawn.matches(&paint).count(), 2);
        assert_eq!(legend.matches(&paint).count(), 1);
        assert!(legend.contains("<path d=\"M") && !legend.contains("<circle"));
    }

    #[test]
    fn the_legend_is_beside_the_plot_area() {
        let svg = Figure {
            x_name: "x".into(),
            y_name: "y".into(),
            curves: vec![line(&[(0.0, 0.0), (1.0, 1.0)])],
            ..Figure::default()
        }
        .render();
        let frame = &svg[svg.find("data-part=\"frame\"").unwrap()..];
        let (x, w) = (
            attribute(frame, "rect", "x")[0],
            attribute(frame, "rect", "width")[0],
        );
        let plot_right = x.parse::<f64>().unwrap() + w.parse::<f64>().unwrap();
        let legend = &svg[svg.find("data-part=\"legend\"").unwrap()..];
        let legend_left: f64 = attribute(legend, "rect", "x")[0].parse().unwrap();
        assert!(legend_left > plot_right, "{legend_left} {plot_right}");
    }

    #[test]
    fn text_colours_have_contrast_on_white() {
        assert!(TEXT.contrast(WHITE) >= 4.5);
        assert!(MUTED.contrast(WHITE) >= 4.5);
        for c in PALETTE {
            assert!(c.contrast(WHITE) >= 3.0, "{c:?}: {}", c.contrast(WHITE));
        }
    }

    #[test]
    fn margins_hold_the_widest_tick_label() {
        let svg = Figure {
            x_name: "x".into(),
            y_name: "a long vertical axis name (unit)".into(),
            curves: vec![line(&[(0.0, -123456.0), (1.0, 0.001)])],
            ..Figure::default()
        }
        .render();
        let frame = &svg[svg.find("data-part=\"frame\"").unwrap()..];
        let left: f64 = attribute(frame, "rect", "x")[0].parse().unwrap();
        let widest = texts(&svg, "y-ticks")
            .iter()
            .map(|l| text_width(l, TICK_SIZE))
            .fold(0.0, f64::max);
        assert!(
            left - TICK_LENGTH - 5.0 - widest >= PAD + AXIS_SIZE,
            "{left} {widest}"
        );
    }
}
