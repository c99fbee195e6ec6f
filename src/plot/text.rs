//! Text in a figure: the markup of subscripts and superscripts, widths
//! estimated from DejaVu Sans' advances, wrapping, escaping, and `<text>`
//! elements.

use std::fmt::Write as _;

use super::*;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Shift {
    Base,
    Sub,
    Super,
}

#[derive(Debug, Clone, PartialEq)]
pub(super) struct Run {
    pub(super) text: String,
    pub(super) shift: Shift,
}

/// Splits markup into runs: `_x`, `_{…}` subscripts and `^x`, `^{…}` superscripts.
pub(super) fn parse(markup: &str) -> Vec<Run> {
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
pub(super) fn plain(markup: &str) -> String {
    parse(markup)
        .into_iter()
        .map(|r| match r.shift {
            Shift::Base => r.text,
            Shift::Sub => format!("_{}", r.text),
            Shift::Super => format!("^{}", r.text),
        })
        .collect()
}

pub(super) const SMALL: f64 = 0.72;

/// Advance of a character in em (DejaVu Sans; 0.7 for characters not listed).
#[allow(clippy::approx_constant)] // font metrics, not 1/π
pub(super) fn advance(c: char) -> f64 {
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

pub(super) fn runs_width(runs: &[Run], size: f64) -> f64 {
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
pub(super) fn ascent(markup: &str, size: f64) -> f64 {
    if parse(markup).iter().any(|r| r.shift == Shift::Super) {
        size * (0.42 + SMALL * 0.93)
    } else {
        size * 0.93
    }
}

/// Depth below the baseline of a line of `markup` at `size` (a subscript lowers it).
pub(super) fn descent(markup: &str, size: f64) -> f64 {
    if parse(markup).iter().any(|r| r.shift == Shift::Sub) {
        size * (0.28 + SMALL * 0.24)
    } else {
        size * 0.24
    }
}

/// Baselines of `lines` stacked from `start` (the top of the first) with
/// `gap` between one line's lowest point and the next one's highest, and where
/// the last one ends.
pub(super) fn stack(lines: &[String], size: f64, start: f64, gap: f64) -> (Vec<f64>, f64) {
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

pub(super) fn escape(text: &str) -> String {
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
pub(super) fn num(v: f64) -> String {
    let s = format!("{:.2}", v);
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" { "0".to_owned() } else { s }
}

/// Greedy word wrap of `markup` to lines at most `max` wide (a longer word stays whole).
pub(super) fn wrap(markup: &str, size: f64, max: f64) -> Vec<String> {
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
pub(super) enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    pub(super) fn as_str(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

pub(super) struct Text<'a> {
    pub(super) markup: &'a str,
    pub(super) x: f64,
    /// The baseline.
    pub(super) y: f64,
    pub(super) size: f64,
    pub(super) anchor: Anchor,
    pub(super) fill: Color,
    pub(super) bold: bool,
    pub(super) rotate: bool,
    pub(super) part: Option<&'a str>,
}

impl<'a> Text<'a> {
    pub(super) fn new(markup: &'a str, x: f64, y: f64, size: f64, anchor: Anchor) -> Self {
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

    pub(super) fn write(&self, out: &mut String) {
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
