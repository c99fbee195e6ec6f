//! The Rapier engine side by side with restitution's contact laws on the
//! ContactNets cube tosses' bounces (`docs/tosses.md`, "A physics engine side
//! by side").
//!
//! The bounces, the two folds by toss (seed 34), the inertia `I₀` fitted on
//! each training fold and the point model's fits are those of
//! `examples/cube_tosses.rs` (`restitution_testkit::tosses`). Each bounce is
//! simulated in a Rapier world: the board a fixed cuboid whose top is the
//! board level, the cube a dynamic cuboid of half-extent `h` with the mass
//! `m` and the inertia `I₀ 1` set explicitly, started touching the board at
//! the measured pre-impact state at the impact instant; it is stepped until
//! it separates or until the instant the measured post-impact velocities
//! refer to, and its velocities are referred back to the impact instant
//! (gravity over the stepped time removed). Restitution and friction are
//! fitted "the same way" as the point model (`tosses::minimise`, the same
//! objective, box and budget as the Coulomb law) on each training fold's
//! single-corner impacts and predict the held-out fold. Then: the engine's
//! contacts (corners loaded, steps, span), the engine against the laws at
//! equal coefficients, the direction of the tangential impulse, and the
//! sensitivity to the step, the horizon and the friction model.
//!
//! `cargo run --release --manifest-path benches/rapier-tosses/Cargo.toml`
//!
//! With `RAPIER_TOSSES_DEBUG` set it prints instead the engine's and the
//! laws' outcomes for a few single-corner impacts at chosen coefficients
//! (frictionless, sticking, fitted).

use rapier3d::glamx::{Mat3, Quat, Vec3};
use rapier3d::prelude::*;
use restitution_testkit::tosses::{self, Bounce, Class, Model, Score, State};
use std::time::Instant;

/// The folds' seed, as in `examples/cube_tosses.rs`.
const SEED: u64 = 34;
/// Rapier's time step (s).
const DT: f32 = 0.0005;
/// Steps in a row with no contact impulse (and every corner near the board
/// moving away from it) after which the cube has separated: 5 ms at `DT`.
const QUIET_TIME: f64 = 0.005;

/// How long a bounce is simulated at most.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Horizon {
    /// Until the instant the measured post-impact velocities refer to (the
    /// post sample's backward difference, `t_post − dt/2`): what the engine
    /// does later is not in the measurement.
    PostSample,
    /// A fixed time (s).
    Fixed(f64),
}

/// The engine's settings.
#[derive(Debug, Clone, Copy)]
struct Settings {
    dt: f32,
    horizon: Horizon,
    friction: FrictionModel,
}

impl Settings {
    const MAIN: Settings = Settings {
        dt: DT,
        horizon: Horizon::PostSample,
        friction: FrictionModel::Simplified,
    };
}
/// Half-thickness of the ground cuboid (m); its top is the board.
const GROUND_HALF_THICKNESS: f32 = 0.5;

/// One simulated bounce.
#[derive(Debug, Clone, Copy)]
struct Run {
    /// The post-impact state referred to the impact instant.
    state: State,
    /// Time simulated (s).
    time: f64,
    /// Steps in which the board bore any normal impulse.
    contact_steps: usize,
    /// First to last step with an impulse, inclusive (s).
    contact_span: f64,
    /// Distinct corners of the cube that bore an impulse.
    corners: usize,
    /// Whether the separation criterion was met within the horizon.
    separated: bool,
    /// When a second corner first bore an impulse (s after the impact).
    second_corner: Option<f64>,
    /// The total impulse of the board on the cube over the run, gravity's
    /// removed (`m Δv_impulsive`, N s).
    impulse: [f64; 3],
}

fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
}

fn a3(v: Vec3) -> [f64; 3] {
    [v.x as f64, v.y as f64, v.z as f64]
}

/// The cube's corner `i` in its body frame (m).
fn corner(i: usize) -> Vec3 {
    v3(tosses::CORNERS[i].map(|c| c * tosses::HALF_WIDTH))
}

/// The corner nearest a body-frame point (m).
fn corner_of(p: Vec3) -> usize {
    (0..8)
        .min_by(|&a, &b| {
            (corner(a) - p)
                .length_squared()
                .total_cmp(&(corner(b) - p).length_squared())
        })
        .expect("eight corners")
}

/// Simulates bounce `b` in Rapier with inertia `I₀ 1` (kg m²), restitution
/// `e` and friction `f`.
fn simulate(b: &Bounce, inertia: f64, e: f64, f: f64, settings: Settings) -> Run {
    let mut world = PhysicsWorld {
        gravity: Vector::new(0.0, 0.0, -tosses::GRAVITY as f32),
        integration_parameters: IntegrationParameters {
            dt: settings.dt,
            friction_model: settings.friction,
            ..IntegrationParameters::default()
        },
        ..PhysicsWorld::default()
    };
    let dt = settings.dt as f64;
    let horizon = match settings.horizon {
        Horizon::PostSample => b.post_sample as f64 * tosses::DT - tosses::DT / 2.0 - b.t_impact,
        Horizon::Fixed(t) => t,
    };
    let max_steps = ((horizon / dt).round() as usize).max(1);
    let quiet_steps = ((QUIET_TIME / dt).round() as usize).max(1);
    // Both colliders carry e and f with the Max rule: max(e, e) = e and
    // max(f, f) = f exactly (Average, the default, would give the same).
    let coefficients = |c: ColliderBuilder| {
        c.friction(f as f32)
            .restitution(e as f32)
            .friction_combine_rule(CoefficientCombineRule::Max)
            .restitution_combine_rule(CoefficientCombineRule::Max)
    };
    // The board: the top of a fixed cuboid at z = 0 (heights are measured
    // from the board level the extraction found).
    let (_, board) = world.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.0, -GROUND_HALF_THICKNESS)),
        coefficients(ColliderBuilder::cuboid(10.0, 10.0, GROUND_HALF_THICKNESS)),
    );
    // The cube at the impact: its orientation, G placed so that its lowest
    // corner is on the board.
    let columns = [0, 1, 2].map(|j| {
        Vec3::new(
            b.rotation[0][j] as f32,
            b.rotation[1][j] as f32,
            b.rotation[2][j] as f32,
        )
    });
    let rotation = Quat::from_mat3(&Mat3::from_cols(columns[0], columns[1], columns[2])).normalize();
    let lowest = (0..8)
        .map(|i| (rotation * corner(i)).z)
        .fold(f32::INFINITY, f32::min);
    let h = tosses::HALF_WIDTH as f32;
    let (cube, cube_collider) = world.insert(
        RigidBodyBuilder::dynamic()
            .pose(Pose::from_parts(Vector::new(0.0, 0.0, -lowest), rotation))
            .linvel(v3(b.pre.velocity))
            .angvel(v3(b.pre.omega))
            .can_sleep(false),
        coefficients(ColliderBuilder::cuboid(h, h, h)).mass_properties(MassProperties::new(
            Vec3::ZERO,
            tosses::MASS as f32,
            Vec3::splat(inertia as f32),
        )),
    );
    let mut touched = [false; 8];
    let (mut steps, mut quiet, mut contact_steps) = (0, 0, 0);
    let (mut first, mut last) = (None, 0);
    let mut separated = false;
    let mut second_corner = None;
    while steps < max_steps {
        world.step();
        steps += 1;
        let mut loaded = false;
        if let Some(pair) = world.narrow_phase.contact_pair(cube_collider, board) {
            let cube_first = pair.collider1 == cube_collider;
            for m in pair.manifolds() {
                for p in &m.points {
                    if p.data.impulse > 0.0 {
                        loaded = true;
                        touched[corner_of(if cube_first { p.local_p1 } else { p.local_p2 })] = true;
                    }
                }
            }
        }
        if second_corner.is_none() && touched.iter().filter(|&&t| t).count() > 1 {
            second_corner = Some(steps as f64 * dt);
        }
        if loaded {
            contact_steps += 1;
            first.get_or_insert(steps);
            last = steps;
            quiet = 0;
        } else {
            quiet += 1;
        }
        let body = &world.bodies[cube];
        let (x, r, v, w) = (body.translation(), *body.rotation(), body.linvel(), body.angvel());
        let receding = (0..8).all(|i| {
            let arm = r * corner(i);
            x.z + arm.z > 0.02 || (v + w.cross(arm)).z > 0.0
        });
        if quiet >= quiet_steps && receding {
            separated = true;
            break;
        }
    }
    let body = &world.bodies[cube];
    let t = steps as f64 * dt;
    let mut velocity = a3(body.linvel());
    velocity[2] += tosses::GRAVITY * t;
    let state = State {
        velocity,
        omega: a3(body.angvel()),
    };
    Run {
        state,
        time: t,
        contact_steps,
        contact_span: first.map_or(0.0, |f| (last - f + 1) as f64 * dt),
        corners: touched.iter().filter(|&&t| t).count(),
        separated,
        second_corner,
        impulse: [0, 1, 2].map(|i| tosses::MASS * (state.velocity[i] - b.pre.velocity[i])),
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn sq(a: [f64; 3]) -> f64 {
    tosses::dot(a, a)
}

/// The errors of predictions over bounces, as `tosses::score` sums them
/// (copied: `score` takes a point model, not a prediction).
fn score_of(bounces: &[&Bounce], predicted: &[State]) -> Score {
    let mut s = Score::default();
    for (b, p) in bounces.iter().zip(predicted) {
        let (vc_pre, vc_post) = (
            tosses::contact_point_velocity(&b.pre, b.r),
            tosses::contact_point_velocity(&b.post, b.r),
        );
        s.n += 1;
        s.g += sq(sub(p.velocity, b.post.velocity));
        s.c += sq(sub(tosses::contact_point_velocity(p, b.r), vc_post));
        s.w += sq(sub(p.omega, b.post.omega));
        s.dg += sq(sub(b.pre.velocity, b.post.velocity));
        s.dc += sq(sub(vc_pre, vc_post));
        s.dw += sq(sub(b.pre.omega, b.post.omega));
    }
    s
}

/// A score's cells, as `examples/cube_tosses.rs` prints them.
fn error_cells(s: &Score) -> String {
    let rel = s.relative();
    format!(
        "{:.3} ({:.3}) | {:.3} ({:.3}) | {:.2} ({:.3}) | {:.3} ({:.3}) | {} of {}",
        s.rms_g(),
        rel[0],
        s.rms_c(),
        rel[1],
        s.rms_w(),
        rel[2],
        s.rms_gc(),
        rel[3],
        s.refused,
        s.n
    )
}

fn coefficients(names: &[&str], p: &[f64]) -> String {
    if names.is_empty() {
        return "–".into();
    }
    names
        .iter()
        .zip(p)
        .map(|(n, v)| format!("{n} {v:.3}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A table row: a name, each fold's coefficients and the pooled held-out
/// scores by class.
struct Row {
    name: String,
    fits: [String; 2],
    corner: Score,
    edge: Score,
    face: Score,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() { f64::NAN } else { v[v.len() / 2] }
}

fn percentile(mut v: Vec<f64>, q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[((v.len() - 1) as f64 * q).round() as usize]
    }
}

/// The pooled held-out scores by class and every simulated bounce (its
/// index in the bounces, its run), by class.
type HeldOutRuns = ([Score; 3], [Vec<(usize, Run)>; 3]);

const CLASSES: [Class; 3] = [Class::Corner, Class::Edge, Class::Face];

fn main() {
    let start = Instant::now();
    let all = tosses::read().expect("the toss data (tests/data)");
    let d = tosses::Detection::measured(&all);
    let distinct = tosses::distinct_bounces(&all, &d);
    let folds = tosses::fold_of_tosses(&distinct, SEED);
    let part = |k: usize, train: bool, class: Class| -> Vec<usize> {
        (0..distinct.len())
            .filter(|&i| (folds[&distinct[i].toss] == k) != train && distinct[i].class == class)
            .collect()
    };
    if std::env::var_os("RAPIER_TOSSES_DEBUG").is_some() {
        debug(&distinct);
        return;
    }
    let version = rapier3d::VERSION;
    println!("# Rapier {version} on the ContactNets cube tosses\n");
    println!(
        "{} distinct bounces (board level {:.2} mm); Rapier dt {} ms, friction model {:?}, separation after {} ms \
         without a contact impulse with every corner within 20 mm of the board receding, at most until the \
         measured post-impact instant.\n",
        distinct.len(),
        d.board * 1e3,
        DT * 1e3,
        Settings::MAIN.friction,
        QUIET_TIME * 1e3
    );
    // The point model: the example's held-out fits (I₀ per training fold,
    // the laws' coefficients), for the reference rows and the Coulomb e f.
    let laws = [
        Model::NoImpact,
        Model::Coulomb,
        Model::Twist,
        Model::CoulombApproach,
    ];
    let point = tosses::held_out(&distinct, &laws, SEED);
    let inertia = point[0].inertia;
    println!(
        "I0 per fold (fitted on its training tosses): {:.4}, {:.4} m h²",
        tosses::in_mh2(inertia[0]),
        tosses::in_mh2(inertia[1])
    );
    let law = |m: Model| point.iter().find(|h| h.model == m).expect("a fitted law");
    let coulomb = law(Model::Coulomb).coefficients.clone();
    let mut rows: Vec<Row> = point
        .iter()
        .map(|h| Row {
            name: h.model.name().into(),
            fits: [0, 1].map(|k| {
                if h.model == Model::NoImpact {
                    "–".into()
                } else {
                    coefficients(h.model.parameters(), &h.coefficients[k])
                }
            }),
            corner: h.corner,
            edge: h.edge,
            face: h.face,
        })
        .collect();

    // Rapier fitted the same way as the Coulomb law: the grid of 6 × 6, then
    // Nelder–Mead, 120 evaluations beyond the grid, e ∈ [0, 1], f ∈ [0, 3].
    let fit = |settings: Settings, label: &str| -> [Vec<f64>; 2] {
        [0, 1].map(|k| {
            let train: Vec<&Bounce> = part(k, true, Class::Corner).into_iter().map(|i| &distinct[i]).collect();
            let t0 = Instant::now();
            let mut evaluations = 0;
            let mut objective = |p: &[f64]| {
                evaluations += 1;
                let predicted: Vec<State> = train
                    .iter()
                    .map(|b| simulate(b, inertia[k], p[0], p[1], settings).state)
                    .collect();
                let s = score_of(&train, &predicted);
                s.g + s.c
            };
            let (p, v) = tosses::minimise(&mut objective, &Model::Coulomb.bounds(), 6, None, 120);
            println!(
                "{label}: fit for fold {} on {} single-corner impacts: e {:.4}, f {:.4}, objective {:.4} m²/s², \
                 {evaluations} evaluations, {:.1} s",
                k + 1,
                train.len(),
                p[0],
                p[1],
                v,
                t0.elapsed().as_secs_f64()
            );
            p
        })
    };
    let held = |p: &[Vec<f64>; 2], settings: Settings| -> HeldOutRuns {
        let mut scores = [Score::default(); 3];
        let mut runs: [Vec<(usize, Run)>; 3] = Default::default();
        for (c, class) in CLASSES.into_iter().enumerate() {
            for k in 0..2 {
                let test = part(k, false, class);
                let sims: Vec<Run> = test
                    .iter()
                    .map(|&i| simulate(&distinct[i], inertia[k], p[k][0], p[k][1], settings))
                    .collect();
                let bounces: Vec<&Bounce> = test.iter().map(|&i| &distinct[i]).collect();
                let states: Vec<State> = sims.iter().map(|r| r.state).collect();
                scores[c] = scores[c].plus(&score_of(&bounces, &states));
                runs[c].extend(test.into_iter().zip(sims));
            }
        }
        (scores, runs)
    };

    let fitted = fit(Settings::MAIN, "Rapier");
    println!();
    let (fitted_scores, fitted_runs) = held(&fitted, Settings::MAIN);
    let (coulomb_scores, coulomb_runs) = held(&coulomb, Settings::MAIN);
    for (name, p, s) in [
        (format!("Rapier {version}, e f fitted"), &fitted, fitted_scores),
        (
            format!("Rapier {version}, the point model's Coulomb e f"),
            &coulomb,
            coulomb_scores,
        ),
    ] {
        rows.push(Row {
            name,
            fits: [0, 1].map(|k| coefficients(&["e", "f"], &p[k])),
            corner: s[0],
            edge: s[1],
            face: s[2],
        });
    }

    for (title, class) in [
        ("Single-corner impacts", Class::Corner),
        ("Edge impacts (contact at the edge's midpoint)", Class::Edge),
        (
            "Face impacts (contact at the touching corners' mean)",
            Class::Face,
        ),
    ] {
        println!("### {title}, held out\n");
        println!(
            "| model | fit for fold 1 (on fold 2) | fit for fold 2 (on fold 1) | G m/s (rel) | contact m/s (rel) | ω rad/s (rel) | G+contact m/s (rel) | refused |\n\
             |---|---|---|---|---|---|---|---|"
        );
        for r in &rows {
            let s = match class {
                Class::Corner => r.corner,
                Class::Edge => r.edge,
                Class::Face => r.face,
            };
            println!(
                "| {} | {} | {} | {} |",
                r.name,
                r.fits[0],
                r.fits[1],
                error_cells(&s)
            );
        }
        println!();
    }

    // Why: the engine's contact during each simulated bounce.
    println!("### The engine's contacts (held out)\n");
    println!(
        "| coefficients | class | n | corners bearing an impulse 1 / 2 / 3+ | second corner's first impulse ms after the impact, median (n) | steps with an impulse median / 90 % / max | contact span ms median / 90 % / max | time simulated ms median / max | not separated by the horizon |\n\
         |---|---|---|---|---|---|---|---|---|"
    );
    for (label, runs) in [("fitted", &fitted_runs), ("point model's Coulomb", &coulomb_runs)] {
        for (c, class) in CLASSES.into_iter().enumerate() {
            let list = &runs[c];
            let count = |lo: usize, hi: usize| {
                list.iter()
                    .filter(|(_, r)| r.corners >= lo && r.corners <= hi)
                    .count()
            };
            let steps: Vec<f64> = list.iter().map(|(_, r)| r.contact_steps as f64).collect();
            let span: Vec<f64> = list.iter().map(|(_, r)| r.contact_span * 1e3).collect();
            let time: Vec<f64> = list.iter().map(|(_, r)| r.time * 1e3).collect();
            let second: Vec<f64> = list
                .iter()
                .filter_map(|(_, r)| r.second_corner.map(|t| t * 1e3))
                .collect();
            println!(
                "| {label} | {} | {} | {} / {} / {} | {:.1} ({}) | {:.0} / {:.0} / {:.0} | {:.1} / {:.1} / {:.1} | {:.1} / {:.1} | {} |",
                class.name(),
                list.len(),
                count(1, 1),
                count(2, 2),
                count(3, 8),
                median(second.clone()),
                second.len(),
                median(steps.clone()),
                percentile(steps.clone(), 0.9),
                percentile(steps, 1.0),
                median(span.clone()),
                percentile(span.clone(), 0.9),
                percentile(span, 1.0),
                median(time.clone()),
                percentile(time, 1.0),
                list.iter().filter(|(_, r)| !r.separated).count()
            );
        }
    }
    println!();

    // Single-corner impacts held out, at the point model's Coulomb e f: the
    // engine against the algebraic laws component by component.
    let mut diff = [[0.0; 5]; 2];
    let mut one = 0usize;
    for (i, r) in &coulomb_runs[0] {
        let b = &distinct[*i];
        let k = folds[&b.toss];
        let e = coulomb[k][0];
        let f = coulomb[k][1];
        one += 1;
        for (j, (model, p)) in [
            (Model::Coulomb, vec![e, f]),
            (Model::CoulombApproach, vec![e, f, 0.0]),
        ]
        .into_iter()
        .enumerate()
        {
            let s = tosses::predict(b, inertia[k], model, &p).expect("the law");
            let (cr, cl) = (
                tosses::contact_point_velocity(&r.state, b.r),
                tosses::contact_point_velocity(&s, b.r),
            );
            diff[j][0] += (cr[2] - cl[2]).powi(2);
            diff[j][1] += (cr[0] - cl[0]).powi(2) + (cr[1] - cl[1]).powi(2);
            diff[j][2] += sq(sub(r.state.velocity, s.velocity));
            diff[j][3] += sq(sub(r.state.omega, s.omega));
        }
    }
    let rms = |x: f64| (x / one.max(1) as f64).sqrt();
    println!(
        "Single-corner impacts held out ({one}), at the point model's Coulomb e f: RMS difference of the engine's outcome from the Coulomb law's: contact point normal {:.3} m/s, \
         tangential {:.3} m/s, G {:.3} m/s, ω {:.2} rad/s; from the two-phase Coulomb-approach law at R = e, \
         f_A = f, mu_R = 0: normal {:.3}, tangential {:.3}, G {:.3}, ω {:.2}.\n",
        rms(diff[0][0]),
        rms(diff[0][1]),
        rms(diff[0][2]),
        rms(diff[0][3]),
        rms(diff[1][0]),
        rms(diff[1][1]),
        rms(diff[1][2]),
        rms(diff[1][3])
    );

    // The direction of the tangential impulse: the Coulomb law's opposes the
    // initial slip; the engine's is the impulse that would stop the slip,
    // shortened to the friction cap. Angles (degrees) between each and the
    // measured tangential impulse, and the ratio |P_t|/P_n.
    let angle = |a: [f64; 3], b: [f64; 3]| {
        let (a, b) = ([a[0], a[1], 0.0], [b[0], b[1], 0.0]);
        (tosses::dot(a, b) / (tosses::norm(a) * tosses::norm(b)))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let ratio = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1]).sqrt() / p[2];
    let mut angles: [Vec<f64>; 5] = Default::default();
    let mut ratios: [Vec<f64>; 4] = Default::default();
    for (i, r) in &fitted_runs[0] {
        let b = &distinct[*i];
        let k = folds[&b.toss];
        let slip = tosses::contact_point_velocity(&b.pre, b.r).map(|v| -v);
        let measured = b.impulse();
        let at_coulomb = coulomb_runs[0]
            .iter()
            .find(|(j, _)| j == i)
            .expect("a run")
            .1
            .impulse;
        let law_state = tosses::predict(b, inertia[k], Model::Coulomb, &coulomb[k]).expect("the law");
        let law_impulse = [0, 1, 2].map(|m| tosses::MASS * (law_state.velocity[m] - b.pre.velocity[m]));
        for (j, p) in [measured, law_impulse, r.impulse, at_coulomb]
            .into_iter()
            .enumerate()
        {
            angles[j].push(angle(p, if j == 0 { slip } else { measured }));
            ratios[j].push(ratio(p));
        }
        angles[4].push(angle(r.impulse, slip));
    }
    println!(
        "Tangential impulse, single-corner impacts held out ({}): median angle (degrees) of the measured one from \
         the initial slip's opposite {:.1}; from the measured one: the Coulomb law's (fitted) {:.1}, the engine's \
         (fitted) {:.1}, the engine's at the point model's Coulomb e f {:.1}. Median |P_t|/P_n: measured {:.3}, \
         Coulomb law {:.3}, engine fitted {:.3}, engine at the Coulomb e f {:.3}. The engine's (fitted) from the \
         initial slip's opposite: {:.1}.\n",
        fitted_runs[0].len(),
        median(angles[0].clone()),
        median(angles[1].clone()),
        median(angles[2].clone()),
        median(angles[3].clone()),
        median(ratios[0].clone()),
        median(ratios[1].clone()),
        median(ratios[2].clone()),
        median(ratios[3].clone()),
        median(angles[4].clone())
    );

    // Edges: the engine's angular velocity error about the edge, across it
    // and about the normal (as the example does for the Coulomb law).
    let mut error = [0.0; 3];
    let mut change = [0.0; 3];
    for (i, r) in &fitted_runs[1] {
        let b = &distinct[*i];
        let u = tosses::edge_axis(b).expect("an edge");
        let e = tosses::edge_components(sub(r.state.omega, b.post.omega), u);
        let c = tosses::edge_components(b.domega(), u);
        for j in 0..3 {
            error[j] += e[j] * e[j];
            change[j] += c[j] * c[j];
        }
    }
    let n = fitted_runs[1].len().max(1) as f64;
    println!(
        "Edge impacts' angular velocity (Rapier fitted, held out, {}): RMS error (measured change) about the edge \
         {:.2} ({:.2}) rad/s, across it {:.2} ({:.2}), about the normal {:.2} ({:.2}).\n",
        fitted_runs[1].len(),
        (error[0] / n).sqrt(),
        (change[0] / n).sqrt(),
        (error[1] / n).sqrt(),
        (change[1] / n).sqrt(),
        (error[2] / n).sqrt(),
        (change[2] / n).sqrt()
    );

    // Sensitivity: each variant refitted the same way.
    println!("### Sensitivity (each row refitted; held out)\n");
    println!(
        "| variant | fit for fold 1 | fit for fold 2 | corner G+contact m/s (rel) | corner ω rad/s | edge G+contact m/s (rel) | edge ω rad/s | face G+contact m/s (rel) | face ω rad/s |\n\
         |---|---|---|---|---|---|---|---|---|"
    );
    let variants = [
        (
            "as above: dt 0.5 ms, up to the post sample, twist friction",
            Settings::MAIN,
        ),
        (
            "dt 0.25 ms",
            Settings {
                dt: 0.00025,
                ..Settings::MAIN
            },
        ),
        (
            "dt 1 ms",
            Settings {
                dt: 0.001,
                ..Settings::MAIN
            },
        ),
        (
            "dt 1/60 s (a game's step)",
            Settings {
                dt: 1.0 / 60.0,
                ..Settings::MAIN
            },
        ),
        (
            "stepped up to 100 ms",
            Settings {
                horizon: Horizon::Fixed(0.1),
                ..Settings::MAIN
            },
        ),
        (
            "per-point Coulomb friction",
            Settings {
                friction: FrictionModel::Coulomb,
                ..Settings::MAIN
            },
        ),
    ];
    for (name, settings) in variants {
        let p = if name.starts_with("as above") {
            fitted.clone()
        } else {
            fit(settings, name)
        };
        let (s, _) = held(&p, settings);
        println!(
            "| {name} | {} | {} | {:.3} ({:.3}) | {:.2} | {:.3} ({:.3}) | {:.2} | {:.3} ({:.3}) | {:.2} |",
            coefficients(&["e", "f"], &p[0]),
            coefficients(&["e", "f"], &p[1]),
            s[0].rms_gc(),
            s[0].relative()[3],
            s[0].rms_w(),
            s[1].rms_gc(),
            s[1].relative()[3],
            s[1].rms_w(),
            s[2].rms_gc(),
            s[2].relative()[3],
            s[2].rms_w()
        );
    }
    println!("\nRun time {:.1} s.", start.elapsed().as_secs_f64());
}

/// Development check: the engine against the algebraic laws on a few
/// single-corner impacts at chosen coefficients.
fn debug(distinct: &[Bounce]) {
    let inertia = tosses::fit_inertia(distinct, 0, SEED).inertia;
    for b in distinct.iter().filter(|b| b.class == Class::Corner).take(4) {
        println!(
            "bounce toss {} r {:?} pre v {:?} w {:?}",
            b.toss, b.r, b.pre.velocity, b.pre.omega
        );
        for (e, f) in [(0.0, 0.0), (0.3, 0.0), (0.0, 3.0), (0.3, 3.0), (0.3, 0.17)] {
            let r = simulate(b, inertia, e, f, Settings::MAIN);
            let law = tosses::predict(b, inertia, Model::Coulomb, &[e, f]).expect("law");
            let two = tosses::predict(b, inertia, Model::CoulombApproach, &[e, f, 0.0]).expect("law");
            let c = |s: &State| tosses::contact_point_velocity(s, b.r);
            println!(
                "  e {e} f {f}: rapier v {:.3?} w {:.3?} vc {:.3?} steps {} t {:.4}\n             law v {:.3?} w {:.3?} vc {:.3?}\n      approach v {:.3?} w {:.3?} vc {:.3?}",
                r.state.velocity,
                r.state.omega,
                c(&r.state),
                r.contact_steps,
                r.time,
                law.velocity,
                law.omega,
                c(&law),
                two.velocity,
                two.omega,
                c(&two)
            );
        }
    }
}
