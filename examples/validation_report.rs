//! Rewrites the generated part of `docs/validation.md` (between
//! `<!-- validation:begin -->` and `<!-- validation:end -->`) and the plots in
//! `docs/validation/`: for every dataset, the fitted `e_t`, the deviation
//! tables per quantity and regime for Coulomb friction alone and for the
//! bilinear model, and one SVG per quantity with the model curves (the
//! project's sweep engine) over the data points (the project's plot code).
//!
//! ```text
//! cargo run --release --example validation_report
//! ```

use restitution_testkit::validation;

use std::collections::BTreeMap;
use std::fmt::Write as _;

use restitution::plot::{Color, Curve, Dash, Figure, LegendEntry, Line, Marker, Markers, Scale, Shape};
use validation::{Dataset, Deviation, Quantity};

const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation.md");
const PLOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation");
const BEGIN: &str = "<!-- validation:begin -->";
const END: &str = "<!-- validation:end -->";
/// Points per model curve.
const CURVE_POINTS: usize = 241;

/// A model variant: its label, its legend text and `e_t`.
struct Variant {
    label: String,
    legend: String,
    et: f64,
    /// Only data at abscissa ≥ this were used to fit it.
    min_x: f64,
}

fn variants(d: &Dataset) -> Vec<Variant> {
    let mut v = vec![Variant {
        label: "(a) Coulomb friction only, e_t = 0".to_owned(),
        legend: "(a) Coulomb friction only, e_t = 0".to_owned(),
        et: 0.0,
        min_x: f64::NEG_INFINITY,
    }];
    let et = d.fit_et(f64::NEG_INFINITY);
    v.push(Variant {
        label: format!(
            "(b) bilinear model, e_t = {et:.3} fitted to all {}",
            d.fitted.name()
        ),
        legend: format!(
            "(b) bilinear, e_t = {} fitted to {}",
            signed(et),
            quantity_symbol(d.fitted)
        ),
        et,
        min_x: f64::NEG_INFINITY,
    });
    if d.key == "kharaz2001" {
        let et = d.fit_et(5.0);
        v.push(Variant {
            label: format!(
                "(c) bilinear model, e_t = {et:.3} fitted at incidence ≥ 5° (deviations over those incidences)"
            ),
            legend: format!("(c) bilinear, e_t = {} fitted at incidence ≥ 5°", signed(et)),
            et,
            min_x: 5.0,
        });
        if let Ok(fit) = restitution::fit::tangential(&validation::kharaz_observations(d, 0.0))
            && let (Some(f), Some(et)) = (fit.friction, fit.tangential_restitution)
        {
            v.push(Variant {
                label: format!(
                    "(d) bilinear model, e_t = {:.3} ± {:.3} from the coefficient fit (`POST /v1/fits/tangential`: \
                     V_ct regressed on v_ct, Eq 20), which also gives f = {:.4} ± {:.4}",
                    et.value, et.standard_error, f.value, f.standard_error
                ),
                legend: format!(
                    "(d) bilinear, e_t = {} from the coefficient fit (Eq 20)",
                    signed(et.value)
                ),
                et: et.value,
                min_x: f64::NEG_INFINITY,
            });
        }
    }
    v
}

fn table(out: &mut String, rows: &BTreeMap<(Quantity, &'static str), Deviation>) {
    out.push_str("| quantity | model regime | points | RMS | max |\n|---|---|---:|---:|---:|\n");
    for ((q, regime), dev) in rows {
        let _ = writeln!(
            out,
            "| {} | {regime} | {} | {:.4} | {:.4} |",
            q.name(),
            dev.count,
            dev.rms(),
            dev.max
        );
    }
}

/// The model curve of one variant over `[lo, hi]` (spaced evenly in the
/// logarithm if `log`), split where it has no answer.
fn curve(d: &Dataset, quantity: Quantity, variant: &Variant, lo: f64, hi: f64, log: bool) -> Curve {
    let at = |t: f64| {
        if log {
            lo * (hi / lo).powf(t)
        } else {
            lo + (hi - lo) * t
        }
    };
    let xs: Vec<f64> = (0..CURVE_POINTS)
        .map(|i| at(i as f64 / (CURVE_POINTS - 1) as f64))
        .collect();
    let mut segments = vec![Vec::new()];
    for (x, y) in xs.iter().zip(d.predict(quantity, variant.et, &xs)) {
        match y {
            Some(y) => segments.last_mut().expect("a segment").push((*x, y.value)),
            None if segments.last().is_some_and(|s| !s.is_empty()) => segments.push(Vec::new()),
            None => {}
        }
    }
    Curve {
        label: variant.legend.clone(),
        segments,
        line: None,
    }
}

/// Three decimals, with a true minus sign.
fn signed(v: f64) -> String {
    format!("{v:.3}").replace('-', "−")
}

/// The line of each model variant, by its place in [`variants`]: (a) Coulomb
/// friction alone dashed, the fitted bilinear models solid, in the same
/// colours in every figure.
fn variant_line(i: usize) -> Line {
    const COLORS: [Color; 4] = [
        Color(77, 77, 77),
        Color(0, 114, 178),
        Color(17, 119, 51),
        Color(51, 34, 136),
    ];
    Line {
        color: COLORS[i % COLORS.len()],
        width: 2.0,
        dash: if i == 0 { Dash::Dashed } else { Dash::Solid },
    }
}

/// Each data source's name in the legend and its marker, the same in every
/// figure (the source column of the data files; `docs/validation.md` says
/// where each comes from).
fn source(name: &str) -> (String, Marker) {
    let (label, shape, color) = match name {
        "kratos_chung_ooi" => ("Kharaz, Kratos digitization", Shape::Circle, Color(213, 94, 0)),
        "lethe" => ("Kharaz, Lethe digitization", Shape::Triangle, Color(170, 51, 119)),
        "mfix_dem05" => (
            "Kharaz, MFIX DEM05 digitization",
            Shape::Cross,
            Color(107, 107, 0),
        ),
        "Al_oxide" => ("Al oxide, DEM", Shape::Square, Color(140, 81, 10)),
        "Al_alloy" => ("Al alloy, DEM", Shape::Diamond, Color(0, 124, 124)),
        "nylon" => ("nylon, DEM", Shape::TriangleDown, Color(178, 24, 43)),
        "steel_DEM" => ("steel, DEM", Shape::Circle, Color(106, 61, 154)),
        other => {
            return (
                other.replace('_', " "),
                Marker::hollow(Shape::Plus, Color(64, 64, 64)),
            );
        }
    };
    (label.to_owned(), Marker::hollow(shape, color))
}

/// A quantity in words, for titles.
fn quantity_title(q: Quantity) -> &'static str {
    match q {
        Quantity::ReboundAngleCentroid => "Rebound angle of the centre of mass",
        Quantity::ReboundAngleContactPoint => "Rebound angle of the contact point",
        Quantity::CentroidRatio => "Tangential velocity ratio of the centre of mass",
        Quantity::SpinMagnitude => "Spin after the impact",
        Quantity::RecoilOverFriction => "Normalised tangential recoil of the contact point",
        Quantity::SpinOverFriction => "Normalised spin after the impact",
        Quantity::Beta => "Tangential restitution of the contact point",
        Quantity::RecoilOverRebound => "Tangential recoil of the contact point",
    }
}

/// A quantity's symbol (the axis label without its words).
fn quantity_symbol(q: Quantity) -> &'static str {
    match q {
        Quantity::ReboundAngleCentroid => "atan(V_t/V_n)",
        Quantity::ReboundAngleContactPoint => "atan(V_ct/V_n)",
        Quantity::CentroidRatio => "V_t/v_t",
        Quantity::SpinMagnitude => "|Ω|",
        Quantity::RecoilOverFriction => "V_ct/(μ V_n)",
        Quantity::SpinOverFriction => "R |Ω|/(μ |v_n|)",
        Quantity::Beta => "β",
        Quantity::RecoilOverRebound => "V_ct/V_n",
    }
}

fn plot(d: &Dataset, quantity: Quantity, variants: &[Variant]) -> String {
    let xs = d.of(quantity).flat_map(|s| s.points.iter().map(|p| p.x));
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    let (drive, x_label) = d.drive(quantity);
    // f/μ_c spans two decades: drawn on a logarithmic axis.
    let log = matches!(drive, validation::Drive::CriticalOverSlip { .. });
    let curves: Vec<Curve> = variants
        .iter()
        .enumerate()
        .map(|(i, v)| Curve {
            line: Some(variant_line(i)),
            ..curve(d, quantity, v, lo, hi, log)
        })
        .collect();
    let markers: Vec<Markers> = d
        .of(quantity)
        .map(|s| {
            let (label, marker) = source(&s.source);
            Markers {
                label,
                points: s.points.iter().map(|p| (p.x, p.value)).collect(),
                marker: Some(marker),
            }
        })
        .collect();
    let mut legend = vec![LegendEntry::Heading("Model".to_owned())];
    legend.extend(
        curves
            .iter()
            .map(|c| LegendEntry::Line(c.line.expect("a line"), c.label.clone())),
    );
    legend.push(LegendEntry::Heading("Data".to_owned()));
    legend.extend(
        markers
            .iter()
            .map(|m| LegendEntry::Marker(m.marker.expect("a marker"), m.label.clone())),
    );
    Figure {
        title: format!("{}, {}", quantity_title(quantity), quantity_symbol(quantity)),
        subtitle: d.title.to_owned(),
        x_name: x_label.to_owned(),
        y_name: quantity.label().to_owned(),
        x_scale: if log { Scale::Log } else { Scale::Linear },
        curves,
        markers,
        legend: Some(legend),
        ..Figure::default()
    }
    .render()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let datasets = validation::datasets()?;
    std::fs::create_dir_all(PLOTS)?;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Generated by `cargo run --release --example validation_report`; do not edit by hand.\n"
    );
    let _ = writeln!(
        out,
        "Digitization scatter: the two digitizations of Chung & Ooi's Test 6 β curve differ by {:.2} % of its span (RMS).\n",
        100.0 * validation::digitization_scatter()?
    );
    for d in &datasets {
        let variants = variants(d);
        let _ = writeln!(out, "### {}\n", d.title);
        let _ = writeln!(
            out,
            "Data: `tests/data/{}`. Sphere of radius {} m, e = {}, f = μ = {}.\n",
            d.file, d.radius, d.restitution, d.friction
        );
        for v in &variants {
            let _ = writeln!(out, "{}\n", v.label);
            table(&mut out, &d.deviations(v.et, v.min_x));
            out.push('\n');
        }
        for quantity in d.quantities() {
            let name = format!("{}_{}.svg", d.key, quantity.name());
            std::fs::write(format!("{PLOTS}/{name}"), plot(d, quantity, &variants))?;
            let _ = writeln!(
                out,
                "![{}, {}](validation/{name})\n",
                quantity_title(quantity),
                d.title
            );
        }
    }
    let doc = std::fs::read_to_string(DOC)?;
    let (Some(begin), Some(end)) = (doc.find(BEGIN), doc.find(END)) else {
        return Err(format!("{DOC} has no {BEGIN} … {END} block").into());
    };
    let updated = format!("{}{BEGIN}\n{out}{}", &doc[..begin], &doc[end..]);
    std::fs::write(DOC, updated)?;
    println!("{out}");
    Ok(())
}
