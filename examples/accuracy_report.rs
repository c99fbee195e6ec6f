//! Run time against error for each case and method; writes `docs/accuracy.md`
//! (table) and `docs/accuracy.svg` (log–log plot of time per solve against
//! maximum error). Every point is measured; nothing is tuned away.
//!
//! ```text
//! cargo run --release --example accuracy_report
//! cargo run --release --example accuracy_report -- --plot-only
//! ```
//!
//! `--plot-only` measures nothing: it redraws `docs/accuracy.svg` from the
//! table already in `docs/accuracy.md`.
//!
//! Methods: `fast` (the service's fast mode: the model in f64 with error
//! bounds, escalating to the exact stages an impact with a decision too close
//! to its tie, an output whose bound exceeds the promised error, or an input
//! outside the fast range; the table counts each), `nalgebra` (the 3×3 momentum system by LU,
//! with the regime the exact answer found), `exact` (double-double with a
//! certified bound, rational fallback) and `rational` (exact rationals only).
//!
//! Error of an output: its distance, in steps of the f64 grid, from the
//! correctly rounded exact value (the `rational` answer). The distance to the
//! exact real value is at most that plus ½. Also given: the same distance in
//! ulps of the output's scale (the largest magnitude among the velocities it
//! combines), the measure the fast mode's bound is stated in.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use linear::{TangentialClosure, solve_momentum};
use restitution::impact::{Arithmetic, Stage, fast_decisions_escalated, fast_outputs_escalated, solve_in};
use restitution::plot::{Color, Figure, LegendEntry, Marker, Markers, Scale, Shape};
use restitution::{
    BarrierImpact, BarrierScene, Body, Contact, Law, Outputs, PlanarVelocity, Precision, Regime,
    TorsionalImpact, solve,
};

use restitution_testkit::{Rng, linear};

/// The planar laws the report measures (the numbers seed each law's inputs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    ImpulseRatio = 2,
    Friction = 3,
    TangentialRestitution = 4,
}

/// Every input of a planar impact; a law reads the ones it needs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct PlanarPoint {
    mass: f64,
    inertia: f64,
    contact: Contact,
    velocity: PlanarVelocity,
    restitution: f64,
    friction: f64,
    impulse_ratio: f64,
    tangential_restitution: f64,
}

impl PlanarPoint {
    fn impact(&self, kind: Kind) -> BarrierImpact {
        let restitution = self.restitution;
        let law = match kind {
            Kind::ImpulseRatio => Law::ImpulseRatio {
                restitution,
                impulse_ratio: self.impulse_ratio,
            },
            Kind::Friction => Law::Friction {
                restitution,
                friction: self.friction,
            },
            Kind::TangentialRestitution => Law::TangentialRestitution {
                restitution,
                friction: self.friction,
                tangential_restitution: self.tangential_restitution,
            },
        };
        BarrierImpact::rigid(self.mass, self.inertia, self.contact, self.velocity, law)
    }
}

/// Grid steps between `x` and the correctly rounded `reference`.
fn steps(x: f64, reference: f64) -> f64 {
    if x == reference {
        return 0.0;
    }
    if !x.is_finite() || !reference.is_finite() {
        return f64::INFINITY;
    }
    let key = |v: f64| {
        let b = v.to_bits() as i64;
        if b < 0 { i64::MIN - b } else { b }
    };
    (key(x) - key(reference)).unsigned_abs() as f64
}

fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x.is_finite() { x.next_up() - x } else { f64::MAX }
}

#[derive(Clone, Copy, PartialEq)]
enum Set {
    Typical,
    Stress,
}

impl Set {
    fn name(self) -> &'static str {
        match self {
            Set::Typical => "typical",
            Set::Stress => "stress",
        }
    }

    fn from_name(name: &str) -> Option<Set> {
        [Set::Typical, Set::Stress].into_iter().find(|s| s.name() == name)
    }
}

/// A planar input: the law and all inputs.
fn planar_point(rng: &mut Rng, set: Set, law: Kind) -> PlanarPoint {
    let (mass, length, speed) = match set {
        Set::Typical => (
            rng.log_uniform(-1.0, 1.0),
            rng.log_uniform(-1.0, 0.0),
            rng.log_uniform(-1.0, 1.0),
        ),
        Set::Stress => match (rng.unit() * 3.0) as u32 {
            0 => (
                rng.log_uniform(-300.0, 300.0),
                rng.log_uniform(-150.0, 150.0),
                rng.log_uniform(-150.0, 150.0),
            ),
            1 => (rng.log_uniform(-1.0, 1.0), 1.0, rng.log_uniform(-15.0, -3.0)),
            _ => (
                rng.log_uniform(-100.0, 100.0),
                rng.log_uniform(-50.0, 50.0),
                rng.log_uniform(-50.0, 50.0),
            ),
        },
    };
    let k = length * rng.log_uniform(-1.0, 0.5);
    let dc = if rng.unit() < 0.3 {
        0.0
    } else {
        length * rng.range(-2.0, 2.0)
    };
    let dd = length * rng.range(-2.0, 2.0);
    let w = speed / length * rng.range(-3.0, 3.0);
    let grazing = set == Set::Stress && rng.unit() < 0.3;
    let vcn = -speed
        * if grazing {
            rng.log_uniform(-15.0, -6.0)
        } else {
            rng.range(0.05, 2.0)
        };
    let e = if set == Set::Stress && rng.unit() < 0.5 {
        [0.0, 1.0, 1.0 - 1e-12][(rng.unit() * 3.0) as usize]
    } else {
        rng.unit()
    };
    let mut p = PlanarPoint {
        mass,
        inertia: mass * k * k,
        contact: Contact {
            tangential_offset: dc,
            normal_offset: dd,
        },
        velocity: PlanarVelocity {
            normal: vcn - dc * w,
            tangential: speed * rng.range(-3.0, 3.0),
            angular: w,
        },
        restitution: e,
        friction: rng.range(0.0, 1.0),
        impulse_ratio: rng.range(-0.3, 0.3),
        tangential_restitution: rng.range(-1.0, 1.0),
    };
    if set == Set::Stress && rng.unit() < 0.3 {
        // f or μ at, or one ulp from, the capped ratio (μ_c for Coulomb).
        let probe = PlanarPoint {
            friction: f64::MAX,
            ..p
        };
        if let Ok(o) = solve(&probe.impact(law), Outputs::MINIMAL, Precision::Exact) {
            let at = o.impulse_ratio;
            let near = [at, at.next_up(), at.next_down()][(rng.unit() * 3.0) as usize];
            p.friction = near.abs();
            p.impulse_ratio = near;
        }
    }
    p
}

fn torsional_impact(rng: &mut Rng, set: Set) -> TorsionalImpact {
    let span = if set == Set::Typical { 1.0 } else { 250.0 };
    let m = rng.log_uniform(-span, span);
    let i_n = rng.log_uniform(-span, span);
    let vn = -rng.log_uniform(-span, span);
    let rho = rng.log_uniform(-span.min(100.0), span.min(100.0));
    let (e, ez, mu_z) = (rng.unit(), rng.unit(), rng.unit());
    let switch = mu_z * rho * (1.0 + e) * -vn * m / i_n;
    let spin = if set == Set::Stress && rng.unit() < 0.5 && switch.is_finite() {
        [switch, switch.next_up(), -switch.next_down()][(rng.unit() * 3.0) as usize]
    } else {
        rng.sign() * rng.log_uniform(-span, span)
    };
    TorsionalImpact {
        mass: m,
        normal_inertia: i_n,
        normal_velocity: vn,
        spin,
        restitution: e,
        torsional_restitution: ez,
        torsional_friction: mu_z,
        pitch_radius: rho,
    }
}

/// One method's measurements on one case and set.
struct Row {
    case: &'static str,
    set: Set,
    method: &'static str,
    median_ns: f64,
    mean_ns: f64,
    median_steps: f64,
    max_steps: f64,
    max_scaled: f64,
    solved: usize,
    failed: usize,
    /// `fast` only: impacts sent to the exact stages, by reason (a close
    /// decision, an output past its bound, the fast range or a refusal).
    escalated: Option<[usize; 3]>,
}

/// How many of `inputs` the fast mode sends to the exact stages, by reason:
/// a decision within its bound of a tie, an output whose bound exceeds the
/// promised error, and the rest (inputs outside the fast range, refusals).
fn escalations<I>(inputs: &[I], run: impl Fn(&I) -> Stage) -> [usize; 3] {
    let mut counts = [0; 3];
    for input in inputs {
        let (decisions, outputs) = (fast_decisions_escalated(), fast_outputs_escalated());
        let stage = run(input);
        if fast_decisions_escalated() > decisions {
            counts[0] += 1;
        } else if fast_outputs_escalated() > outputs {
            counts[1] += 1;
        } else if stage != Stage::Fast {
            counts[2] += 1;
        }
    }
    counts
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Times `solve` per input (`reps` calls each) and measures its outputs against `reference`.
fn measure<I, O>(
    case: &'static str,
    set: Set,
    method: &'static str,
    inputs: &[I],
    reps: u32,
    solve: impl Fn(&I) -> Option<O>,
    compare: impl Fn(&I, &O) -> Option<(f64, f64)>,
) -> Row {
    let (mut times, mut errors) = (Vec::new(), Vec::new());
    let (mut max_scaled, mut failed, mut solved) = (0f64, 0, 0);
    for input in inputs {
        let start = Instant::now();
        for _ in 0..reps {
            black_box(solve(black_box(input)));
        }
        times.push(start.elapsed().as_nanos() as f64 / f64::from(reps));
        match solve(input) {
            Some(answer) => match compare(input, &answer) {
                Some((steps, scaled)) => {
                    solved += 1;
                    errors.push(steps);
                    max_scaled = max_scaled.max(scaled);
                }
                None => failed += 1,
            },
            None => failed += 1,
        }
    }
    let mean_ns = times.iter().sum::<f64>() / times.len() as f64;
    Row {
        case,
        set,
        method,
        median_ns: median(&mut times),
        mean_ns,
        max_steps: errors.iter().copied().fold(0.0, f64::max),
        median_steps: median(&mut errors),
        max_scaled,
        solved,
        failed,
        escalated: None,
    }
}

/// `(V_n, V_t, Ω)` errors against the reference: max grid steps and max ulps of the scale.
fn velocity_error(p: &PlanarPoint, got: &PlanarVelocity, reference: &PlanarVelocity) -> Option<(f64, f64)> {
    let length = p
        .contact
        .tangential_offset
        .abs()
        .max(p.contact.normal_offset.abs())
        .max((p.inertia / p.mass).sqrt());
    let v = p.velocity;
    let scale = [v.normal, v.tangential, reference.normal, reference.tangential]
        .iter()
        .map(|x| x.abs())
        .fold(v.angular.abs() * length, f64::max)
        .max(reference.angular.abs() * length);
    let pairs = [
        (got.normal, reference.normal, scale),
        (got.tangential, reference.tangential, scale),
        (got.angular, reference.angular, scale / length),
    ];
    let mut worst = (0f64, 0f64);
    for (x, r, s) in pairs {
        if !x.is_finite() {
            return None;
        }
        worst.0 = worst.0.max(steps(x, r));
        worst.1 = worst.1.max((x - r).abs() / ulp(s));
    }
    Some(worst)
}

fn planar_rows(case: &'static str, law: Kind, set: Set, n: usize, rows: &mut Vec<Row>) {
    let mut rng = Rng::new(0x5EED ^ (n as u64) ^ (law as u64) << 8 ^ (set as u64) << 16);
    let inputs: Vec<(PlanarPoint, PlanarVelocity, Option<TangentialClosure>)> = (0..n)
        .filter_map(|_| {
            let p = planar_point(&mut rng, set, law);
            let reference = solve_in(&p.impact(law), Outputs::ALL, Arithmetic::Rational)
                .0
                .ok()?;
            let closure = match reference.regime {
                Regime::Sticking | Regime::Restitution => Some(TangentialClosure::ContactVelocity(
                    reference.contact_velocity.r#final.tangential,
                )),
                _ => Some(TangentialClosure::ImpulseRatio(reference.impulse_ratio)),
            };
            Some((p, reference.final_velocity, closure))
        })
        .collect();
    let scale = if set == Set::Typical { 1 } else { 4 };
    let compare = |(p, reference, _): &(PlanarPoint, PlanarVelocity, _), got: &PlanarVelocity| {
        velocity_error(p, got, reference)
    };
    let reps_fast = 400 / scale;
    let mut fast = measure(
        case,
        set,
        "fast",
        &inputs,
        reps_fast as u32,
        |(p, _, _)| {
            solve(&p.impact(law), Outputs::ALL, Precision::Fast)
                .ok()
                .map(|o| o.final_velocity)
        },
        compare,
    );
    fast.escalated = Some(escalations(&inputs, |(p, _, _)| {
        solve_in(&p.impact(law), Outputs::ALL, Arithmetic::Fast).1
    }));
    rows.push(fast);
    rows.push(measure(
        case,
        set,
        "nalgebra",
        &inputs,
        reps_fast as u32,
        |(p, _, closure)| {
            let scene = BarrierScene::new(Body::new(p.mass, p.inertia).ok()?, p.contact, p.velocity).ok()?;
            solve_momentum(&scene, p.restitution, (*closure)?)
        },
        compare,
    ));
    rows.push(measure(
        case,
        set,
        "exact",
        &inputs,
        (100 / scale) as u32,
        |(p, _, _)| {
            solve(&p.impact(law), Outputs::ALL, Precision::Exact)
                .ok()
                .map(|o| o.final_velocity)
        },
        compare,
    ));
    rows.push(measure(
        case,
        set,
        "rational",
        &inputs,
        3,
        |(p, _, _)| {
            solve_in(&p.impact(law), Outputs::ALL, Arithmetic::Rational)
                .0
                .ok()
                .map(|o| o.final_velocity)
        },
        compare,
    ));
}

fn torsional_rows(set: Set, n: usize, rows: &mut Vec<Row>) {
    let mut rng = Rng::new(0x70E5 ^ (set as u64) << 16);
    let inputs: Vec<(TorsionalImpact, f64)> = (0..n)
        .filter_map(|_| {
            let impact = torsional_impact(&mut rng, set);
            let reference = solve_in(&impact, Outputs::ALL, Arithmetic::Rational).0.ok()?;
            Some((impact, reference.final_spin))
        })
        .collect();
    let compare = |(impact, reference): &(TorsionalImpact, f64), got: &f64| {
        let scale = impact.spin.abs().max(reference.abs());
        Some((steps(*got, *reference), (got - reference).abs() / ulp(scale)))
    };
    let scale = if set == Set::Typical { 1 } else { 4 };
    let mut fast = measure(
        "torsional",
        set,
        "fast",
        &inputs,
        400 / scale,
        |(impact, _)| {
            solve(impact, Outputs::ALL, Precision::Fast)
                .ok()
                .map(|o| o.final_spin)
        },
        compare,
    );
    fast.escalated = Some(escalations(&inputs, |(impact, _)| {
        solve_in(impact, Outputs::ALL, Arithmetic::Fast).1
    }));
    rows.push(fast);
    rows.push(measure(
        "torsional",
        set,
        "exact",
        &inputs,
        100 / scale,
        |(impact, _)| {
            solve(impact, Outputs::ALL, Precision::Exact)
                .ok()
                .map(|o| o.final_spin)
        },
        compare,
    ));
    rows.push(measure(
        "torsional",
        set,
        "rational",
        &inputs,
        3,
        |(impact, _)| {
            solve_in(impact, Outputs::ALL, Arithmetic::Rational)
                .0
                .ok()
                .map(|o| o.final_spin)
        },
        compare,
    ));
}

/// One point of the plot: a (case, set, method) row of the table.
struct PlotPoint {
    case: String,
    set: Set,
    method: String,
    median_ns: f64,
    max_steps: f64,
}

/// The methods' colours, the cases' shapes: the same in the plot and its legend.
const METHODS: [(&str, Color); 4] = [
    ("fast", Color(0, 114, 178)),
    ("nalgebra", Color(213, 94, 0)),
    ("exact", Color(17, 119, 51)),
    ("rational", Color(170, 51, 119)),
];
const CASES: [(&str, Shape); 4] = [
    ("prescribed μ", Shape::Circle),
    ("Coulomb f", Shape::Square),
    ("tangential e_t", Shape::Triangle),
    ("torsional", Shape::Diamond),
];

/// A row's marker: the method's colour, the case's shape, filled for the
/// typical set and hollow for the stress set.
fn marker(method: &str, case: &str, set: Set) -> Marker {
    let color = METHODS
        .iter()
        .find(|m| m.0 == method)
        .map_or(Color(64, 64, 64), |m| m.1);
    let shape = CASES.iter().find(|c| c.0 == case).map_or(Shape::Plus, |c| c.1);
    let mut m = match set {
        Set::Typical => Marker::filled(shape, color),
        Set::Stress => Marker::hollow(shape, color),
    };
    m.size = 5.0;
    m.stroke_width = 1.8;
    m
}

/// Log–log plot of median time per solve against maximum error + ½, one marker per row;
/// colour the method, shape the case, filled the typical set, hollow the stress set.
fn plot(points: &[PlotPoint], path: &str) {
    let grey = Color(64, 64, 64);
    let mut legend = vec![LegendEntry::Heading("Method".to_owned())];
    legend.extend(
        METHODS
            .iter()
            .map(|(m, c)| LegendEntry::Swatch(*c, (*m).to_owned())),
    );
    legend.push(LegendEntry::Heading("Case".to_owned()));
    legend.extend(
        CASES
            .iter()
            .map(|(c, s)| LegendEntry::Marker(Marker::hollow(*s, grey), (*c).to_owned())),
    );
    legend.push(LegendEntry::Heading("Set".to_owned()));
    legend.push(LegendEntry::Marker(
        Marker::filled(Shape::Circle, grey),
        "typical: filled".to_owned(),
    ));
    legend.push(LegendEntry::Marker(
        Marker::hollow(Shape::Circle, grey),
        "stress: hollow".to_owned(),
    ));
    // Stress sets first, so the filled typical markers sit on top.
    let mut sets: Vec<Markers> = Vec::new();
    for set in [Set::Stress, Set::Typical] {
        for p in points
            .iter()
            .filter(|p| p.set == set && (p.max_steps + 0.5).is_finite())
        {
            sets.push(Markers {
                label: format!("{}, {}, {}", p.method, p.case, set.name()),
                points: vec![(p.median_ns, p.max_steps + 0.5)],
                marker: Some(marker(&p.method, &p.case, set)),
            });
        }
    }
    let rows: Vec<String> = points
        .iter()
        .map(|p| {
            format!(
                "{} {} {}: {:.0} ns, {} steps",
                p.method,
                p.case,
                p.set.name(),
                p.median_ns,
                p.max_steps
            )
        })
        .collect();
    let figure = Figure {
        title: "Time per solve against maximum error".to_owned(),
        subtitle: "one marker per case, input set and method (the table in docs/accuracy.md)".to_owned(),
        description: format!(
            "Log–log plot of the median time per solve (ns) against the maximum error in grid steps from \
             the correctly rounded exact value plus one half. Colour: method; shape: case; filled: typical \
             set, hollow: stress set. Points: {}.",
            rows.join("; ")
        ),
        x_name: "median time per solve (ns)".to_owned(),
        y_name: "max error + ½ (f64 grid steps from the exact value)".to_owned(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        markers: sets,
        legend: Some(legend),
        ..Figure::default()
    };
    std::fs::write(path, figure.render()).expect("write svg");
}

/// The plot's points from the table in `docs/accuracy.md` (between the report markers).
fn table_points(doc: &str) -> Vec<PlotPoint> {
    let (begin, end) = (
        doc.find("<!-- report:begin -->")
            .expect("report:begin in docs/accuracy.md"),
        doc.find("<!-- report:end -->")
            .expect("report:end in docs/accuracy.md"),
    );
    doc[begin..end]
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.trim().trim_matches('|').split('|').map(str::trim).collect();
            let set = Set::from_name(cells.get(1)?)?;
            Some(PlotPoint {
                case: cells[0].to_owned(),
                set,
                method: cells[2].to_owned(),
                median_ns: cells[3].parse().ok()?,
                max_steps: cells[6].parse().ok()?,
            })
        })
        .collect()
}

fn main() {
    if std::env::args().any(|a| a == "--plot-only") {
        let doc = std::fs::read_to_string("docs/accuracy.md").expect("read docs/accuracy.md");
        let points = table_points(&doc);
        assert!(!points.is_empty(), "no table rows in docs/accuracy.md");
        plot(&points, "docs/accuracy.svg");
        println!("docs/accuracy.svg: {} points from docs/accuracy.md", points.len());
        return;
    }
    let mut rows = Vec::new();
    for set in [Set::Typical, Set::Stress] {
        let n = if set == Set::Typical { 2000 } else { 600 };
        planar_rows("prescribed μ", Kind::ImpulseRatio, set, n, &mut rows);
        planar_rows("Coulomb f", Kind::Friction, set, n, &mut rows);
        planar_rows("tangential e_t", Kind::TangentialRestitution, set, n, &mut rows);
        torsional_rows(set, n, &mut rows);
    }
    let mut table = String::new();
    table.push_str(
        "| case | set | method | median ns/solve | mean ns/solve | median error (steps) | max error (steps) | max error (ulps of scale) | answered | not answered | escalated: decision, output, range |\n",
    );
    table.push_str("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for r in &rows {
        let escalated = r
            .escalated
            .map_or_else(|| "–".to_owned(), |[d, o, x]| format!("{d}, {o}, {x}"));
        writeln!(
            table,
            "| {} | {} | {} | {:.0} | {:.0} | {} | {} | {:.2} | {} | {} | {} |",
            r.case,
            r.set.name(),
            r.method,
            r.median_ns,
            r.mean_ns,
            r.median_steps,
            r.max_steps,
            r.max_scaled,
            r.solved,
            r.failed,
            escalated
        )
        .expect("string");
    }
    print!("{table}");
    let points: Vec<PlotPoint> = rows
        .iter()
        .map(|r| PlotPoint {
            case: r.case.to_owned(),
            set: r.set,
            method: r.method.to_owned(),
            median_ns: r.median_ns,
            max_steps: r.max_steps,
        })
        .collect();
    plot(&points, "docs/accuracy.svg");
    let doc = std::fs::read_to_string("docs/accuracy.md").unwrap_or_default();
    let (begin, end) = ("<!-- report:begin -->", "<!-- report:end -->");
    let updated = match (doc.find(begin), doc.find(end)) {
        (Some(a), Some(b)) => format!("{}{begin}\n{table}{}", &doc[..a], &doc[b..]),
        _ => format!("{doc}\n{begin}\n{table}{end}\n"),
    };
    std::fs::write("docs/accuracy.md", updated).expect("write docs/accuracy.md");
}
