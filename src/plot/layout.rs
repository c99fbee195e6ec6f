//! Layout and drawing: the legend laid out, the margins sized from the
//! labels, and the figure written as SVG.

use std::fmt::Write as _;

use super::*;

/// A legend entry laid out: its mark, its label's lines and their baselines.
pub(super) struct LegendRow {
    pub(super) entry: LegendEntry,
    pub(super) lines: Vec<String>,
    pub(super) baselines: Vec<f64>,
}

impl LegendEntry {
    pub(super) fn label(&self) -> &str {
        match self {
            LegendEntry::Heading(l)
            | LegendEntry::Line(_, l)
            | LegendEntry::Marker(_, l)
            | LegendEntry::Band(_, l)
            | LegendEntry::Swatch(_, l) => l,
        }
    }
}

pub(super) const LEGEND_MARK: f64 = 30.0;
/// From the plot area's bottom to the lowest point of the x tick labels
/// (room for a superscript above and a descent below).
pub(super) const X_TICKS_DEPTH: f64 = TICK_LENGTH + 3.0 + TICK_SIZE * (0.42 + SMALL * 0.93 + 0.24);

impl Figure {
    pub(super) fn line_of(&self, i: usize) -> Line {
        self.curves[i]
            .line
            .unwrap_or_else(|| Line::solid(PALETTE[i % PALETTE.len()]))
    }

    pub(super) fn marker_of(&self, i: usize) -> Marker {
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

    pub(super) fn describe(&self) -> String {
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
