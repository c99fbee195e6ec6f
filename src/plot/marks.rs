//! Marks: the markers' shapes and the lines' paint.

use std::fmt::Write as _;

use super::*;

pub(super) fn write_marker(out: &mut String, m: &Marker, x: f64, y: f64) {
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

pub(super) fn line_paint(line: &Line) -> String {
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
