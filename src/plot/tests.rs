//! The figure's layout and text, checked on the SVG it writes.

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
    let drawn = &svg[svg.find("data-part=\"markers\"").unwrap()..svg.find("data-part=\"frame\"").unwrap()];
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
