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

#[allow(dead_code)]
#[path = "../tests/common/validation.rs"]
mod validation;

use std::collections::BTreeMap;
use std::fmt::Write as _;

use restitution::plot::{Curve, Figure, Markers};
use validation::{Dataset, Deviation, Quantity};

const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation.md");
const PLOTS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/validation");
const BEGIN: &str = "<!-- validation:begin -->";
const END: &str = "<!-- validation:end -->";
/// Points per model curve.
const CURVE_POINTS: usize = 241;

/// A model variant: its label and `e_t`.
struct Variant {
    label: String,
    et: f64,
    /// Only data at abscissa ≥ this were used to fit it.
    min_x: f64,
}

fn variants(d: &Dataset) -> Vec<Variant> {
    let mut v = vec![Variant {
        label: "(a) Coulomb friction only, e_t = 0".to_owned(),
        et: 0.0,
        min_x: f64::NEG_INFINITY,
    }];
    let et = d.fit_et(f64::NEG_INFINITY);
    v.push(Variant {
        label: format!(
            "(b) bilinear model, e_t = {et:.3} fitted to all {}",
            d.fitted.name()
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
        label: format!("model, e_t = {:.3}", variant.et),
        segments,
    }
}

fn plot(d: &Dataset, quantity: Quantity, variants: &[Variant]) -> String {
    let xs = d.of(quantity).flat_map(|s| s.points.iter().map(|p| p.x));
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    let (drive, x_label) = d.drive(quantity);
    // f/μ_c spans two decades: drawn against its logarithm.
    let log = matches!(drive, validation::Drive::CriticalOverSlip { .. });
    let axis = |x: f64| if log { x.log10() } else { x };
    let mut curves: Vec<Curve> = variants
        .iter()
        .map(|v| curve(d, quantity, v, lo, hi, log))
        .collect();
    for c in &mut curves {
        for segment in &mut c.segments {
            for p in segment.iter_mut() {
                p.0 = axis(p.0);
            }
        }
    }
    Figure {
        title: format!("{}: {}", d.key, quantity.name()),
        x_name: if log {
            format!("log10 of {x_label}")
        } else {
            x_label.to_owned()
        },
        y_name: quantity.label().to_owned(),
        curves,
        markers: d
            .of(quantity)
            .map(|s| Markers {
                label: s.source.clone(),
                points: s.points.iter().map(|p| (axis(p.x), p.value)).collect(),
            })
            .collect(),
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
            let _ = writeln!(out, "![{} {}](validation/{name})\n", d.key, quantity.name());
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
