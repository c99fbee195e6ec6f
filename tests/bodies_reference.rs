//! The planar two-body contact against an independent exact reference
//! (`tests/common/bodies_reference.rs`, rationals, derived from the momentum
//! equations alone).
//!
//! - `exact` precision: every rational output equals the reference's
//!   correctly rounded value bit for bit (`+0.0` for an exact zero), every
//!   `x √y` output (components along `n̂`, `t̂` and `|ΔV|`) is correctly rounded
//!   by an exact comparison of squares, regimes and refusals agree.
//! - `fast` precision: every output within `FAST_BOUND_ULPS` ulps of its scale
//!   (the magnitude of the terms it combines times the conditioning of the
//!   solve); `cargo test --release --test bodies_reference -- --nocapture`
//!   prints the largest error of each output.

mod common;

use common::Rng;
use common::bodies_reference::{
    self as exact, Answer, Scene, is_correctly_rounded, is_correctly_rounded_sqrt, sqrt_approx,
};
use common::reference::{self as one, Q, q, to_f64, ulps};
use num_traits::{One, Signed, Zero};
use restitution::{
    BodiesImpact, BodiesOutcome, ImpactError, Lamina, Law, Outputs, PlanarContact, Precision, solve,
};

/// The largest error of a `fast` answer, in ulps of each output's scale. The
/// largest measured over every set below is about 3.9 ulps (impulse
/// components on the heavy-partner set); twice that, rounded up.
const FAST_BOUND_ULPS: f64 = 8.0;

/// Fewer cases in the debug profile (CI's `cargo test`).
const SIZE: usize = if cfg!(debug_assertions) { 1 } else { 4 };

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Set {
    /// Two laminae, sizes, speeds and masses over six decades each.
    Pairs,
    /// One lamina against the barrier.
    Barrier,
    /// B 10⁶…10¹² times heavier than A.
    Heavy,
    /// Central contacts (`r ∥ n` exactly) on A, and on B or a barrier.
    Central,
    /// Small dyadic inputs: exact zeros and rounding ties.
    Dyadic,
    /// Dyadic scenes whose initial slip is exactly zero.
    ZeroSlip,
    /// `f` at the rounded `|μ_target|` and one ulp either side.
    AtCap,
}

const SETS: [(Set, usize); 7] = [
    (Set::Pairs, 600),
    (Set::Barrier, 400),
    (Set::Heavy, 150),
    (Set::Central, 150),
    (Set::Dyadic, 250),
    (Set::ZeroSlip, 150),
    (Set::AtCap, 400),
];

struct Case {
    set: Set,
    impact: BodiesImpact,
    /// A decision sits within rounding of its boundary: `fast` may take the other side.
    boundary: bool,
    /// `f` equals `|μ_target|` exactly.
    on_cap: bool,
}

fn random_e(rng: &mut Rng) -> f64 {
    if rng.chance(0.3) {
        rng.pick(&[0.0, 1.0])
    } else {
        rng.unit()
    }
}

fn random_law(rng: &mut Rng) -> Law {
    let e = random_e(rng);
    match rng.next_u64() % 5 {
        0 => Law::Frictionless { restitution: e },
        1 => Law::ImpulseRatio {
            restitution: e,
            impulse_ratio: if rng.chance(0.1) {
                0.0
            } else {
                rng.range(-1.5, 1.5)
            },
        },
        2 => Law::Friction {
            restitution: e,
            friction: if rng.chance(0.5) {
                rng.pick(&[0.0, 0.1, 0.3, 1.0, 10.0])
            } else {
                rng.log_uniform(-2.0, 1.0)
            },
        },
        3 => Law::TangentialRestitution {
            restitution: e,
            friction: if rng.chance(0.5) {
                rng.pick(&[0.0, 0.1, 0.3, 1.0, 10.0])
            } else {
                rng.log_uniform(-2.0, 1.0)
            },
            tangential_restitution: if rng.chance(0.3) {
                rng.pick(&[-1.0, 0.0, 1.0])
            } else {
                rng.range(-1.0, 1.0)
            },
        },
        _ => Law::KineticRestitution {
            value: random_e(rng),
            approach_impulse_ratio: rng.range(-1.0, 1.0),
            rebound_impulse_ratio: rng.range(-1.0, 1.0),
        },
    }
}

/// `k / den` with `k` uniform in `lo..=hi`.
fn dy(rng: &mut Rng, lo: i64, hi: i64, den: f64) -> f64 {
    (lo + (rng.next_u64() % (hi - lo + 1) as u64) as i64) as f64 / den
}

fn dyadic_law(rng: &mut Rng) -> Law {
    let e = dy(rng, 0, 4, 4.0);
    match rng.next_u64() % 5 {
        0 => Law::Frictionless { restitution: e },
        1 => Law::ImpulseRatio {
            restitution: e,
            impulse_ratio: dy(rng, -8, 8, 8.0),
        },
        2 => Law::Friction {
            restitution: e,
            friction: dy(rng, 0, 8, 8.0),
        },
        3 => Law::TangentialRestitution {
            restitution: e,
            friction: dy(rng, 0, 8, 8.0),
            tangential_restitution: dy(rng, -4, 4, 4.0),
        },
        _ => Law::KineticRestitution {
            value: dy(rng, 0, 4, 4.0),
            approach_impulse_ratio: dy(rng, -4, 4, 8.0),
            rebound_impulse_ratio: dy(rng, -4, 4, 8.0),
        },
    }
}

/// A lamina touching `c`, of size `length`, speed `speed`.
fn lamina(rng: &mut Rng, c: [f64; 2], mass: f64, length: f64, speed: f64) -> Lamina {
    let k = length * rng.log_uniform(-1.0, 0.5);
    let r = [length * rng.range(-2.0, 2.0), length * rng.range(-2.0, 2.0)];
    Lamina {
        mass,
        inertia: mass * k * k,
        position: [c[0] - r[0], c[1] - r[1]],
        velocity: [speed * rng.range(-2.0, 2.0), speed * rng.range(-2.0, 2.0)],
        angular_velocity: if rng.chance(0.2) {
            0.0
        } else {
            speed / length * rng.range(-3.0, 3.0)
        },
    }
}

fn random_normal(rng: &mut Rng) -> [f64; 2] {
    let len = rng.log_uniform(-3.0, 3.0);
    if rng.chance(0.1) {
        let axis = rng.pick(&[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]);
        [axis[0] * len, axis[1] * len]
    } else {
        let angle = rng.range(0.0, std::f64::consts::TAU);
        [len * angle.cos(), len * angle.sin()]
    }
}

/// Reverses every velocity (exact) unless the contact approaches; a few stay
/// separating, to check the refusal.
fn approaching(rng: &mut Rng, mut impact: BodiesImpact) -> BodiesImpact {
    if !Scene::new(&impact).u[0].is_negative() && rng.chance(0.97) {
        for l in std::iter::once(&mut impact.a).chain(impact.b.as_mut()) {
            l.velocity = [-l.velocity[0], -l.velocity[1]];
            l.angular_velocity = -l.angular_velocity;
        }
    }
    impact
}

fn float_scene(rng: &mut Rng, set: Set) -> BodiesImpact {
    let mass = rng.log_uniform(-3.0, 3.0);
    let length = rng.log_uniform(-3.0, 3.0);
    let speed = rng.log_uniform(-3.0, 3.0);
    let offset = if rng.chance(0.1) { 1e3 } else { 3.0 };
    let c = [
        length * rng.range(-offset, offset),
        length * rng.range(-offset, offset),
    ];
    let a = lamina(rng, c, mass * rng.log_uniform(-1.0, 1.0), length, speed);
    let b = match set {
        Set::Barrier => None,
        Set::Heavy => {
            let l = length * rng.log_uniform(-1.0, 1.0);
            Some(lamina(rng, c, a.mass * rng.log_uniform(6.0, 12.0), l, speed))
        }
        _ => {
            let l = length * rng.log_uniform(-1.0, 1.0);
            let s = speed * rng.log_uniform(-1.0, 1.0);
            Some(lamina(rng, c, mass * rng.log_uniform(-1.5, 1.5), l, s))
        }
    };
    BodiesImpact {
        a,
        b,
        contact: PlanarContact {
            point: c,
            normal: random_normal(rng),
        },
        law: random_law(rng),
    }
}

/// A and maybe B central: C at the origin, `G = −λ n` with `λ` a power of two,
/// so that `r = λ n` exactly.
fn central_scene(rng: &mut Rng) -> BodiesImpact {
    let n = random_normal(rng);
    let norm = n[0].hypot(n[1]);
    let length = rng.log_uniform(-3.0, 3.0);
    let speed = rng.log_uniform(-3.0, 3.0);
    let mass = rng.log_uniform(-3.0, 3.0);
    let central = |rng: &mut Rng, mass: f64| {
        let mut l = lamina(rng, [0.0, 0.0], mass, length, speed);
        let lambda = rng.sign() * 2f64.powi(((length / norm).log2() + rng.range(-1.0, 1.0)).round() as i32);
        l.position = [-lambda * n[0], -lambda * n[1]];
        l
    };
    let a = central(rng, mass);
    let b = match rng.next_u64() % 3 {
        0 => None,
        1 => Some(central(rng, mass * rng.log_uniform(-1.0, 1.0))),
        _ => Some(lamina(rng, [0.0, 0.0], mass * rng.log_uniform(-1.0, 1.0), length, speed)),
    };
    BodiesImpact {
        a,
        b,
        contact: PlanarContact {
            point: [0.0, 0.0],
            normal: n,
        },
        law: random_law(rng),
    }
}

fn dyadic_lamina(rng: &mut Rng, c: [f64; 2]) -> Lamina {
    let r = [dy(rng, -8, 8, 4.0), dy(rng, -8, 8, 4.0)];
    Lamina {
        mass: dy(rng, 1, 8, rng.pick(&[1.0, 2.0, 4.0])),
        inertia: dy(rng, 1, 16, 4.0),
        position: [c[0] - r[0], c[1] - r[1]],
        velocity: [dy(rng, -8, 8, 2.0), dy(rng, -8, 8, 2.0)],
        angular_velocity: dy(rng, -4, 4, 2.0),
    }
}

fn dyadic_scene(rng: &mut Rng) -> BodiesImpact {
    let c = [dy(rng, -8, 8, 4.0), dy(rng, -8, 8, 4.0)];
    let n = loop {
        let n = [dy(rng, -4, 4, 1.0), dy(rng, -4, 4, 1.0)];
        if n != [0.0, 0.0] {
            break n;
        }
    };
    let scale = rng.pick(&[1.0, 0.25, 8.0]);
    let a = dyadic_lamina(rng, c);
    let b = if rng.chance(0.7) {
        Some(dyadic_lamina(rng, c))
    } else {
        None
    };
    BodiesImpact {
        a,
        b,
        contact: PlanarContact {
            point: c,
            normal: [n[0] * scale, n[1] * scale],
        },
        law: dyadic_law(rng),
    }
}

fn exactly(x: &Q) -> f64 {
    let f = to_f64(x);
    assert_eq!(&q(f), x, "not representable");
    f
}

/// A dyadic scene with `u = λ n`, `λ < 0`: approaching with no slip.
fn zero_slip_scene(rng: &mut Rng) -> BodiesImpact {
    let mut impact = dyadic_scene(rng);
    let s = Scene::new(&impact);
    let n = [q(impact.contact.normal[0]), q(impact.contact.normal[1])];
    let lambda = q(-dy(rng, 1, 8, 4.0));
    // u_A must be λ n + u_B; v_A = u_A − ω_A ẑ × r_A.
    let ub = match s.bodies.get(1) {
        Some(b) => b.point_velocity(&b.v, &b.w),
        None => [Q::zero(), Q::zero()],
    };
    let a = &s.bodies[0];
    let va = [
        &lambda * &n[0] + &ub[0] + &a.w * &a.r[1],
        &lambda * &n[1] + &ub[1] - &a.w * &a.r[0],
    ];
    impact.a.velocity = [exactly(&va[0]), exactly(&va[1])];
    let s = Scene::new(&impact);
    assert!(s.u[1].is_zero() && s.u[0].is_negative());
    impact
}

/// Friction or tangential restitution with `f` at the rounded `|μ_target|`
/// or one ulp either side; `None` where the target has `P_n = 0`.
fn at_cap(rng: &mut Rng) -> Option<(BodiesImpact, bool)> {
    let dyadic = rng.chance(0.6);
    let mut impact = if dyadic {
        dyadic_scene(rng)
    } else {
        let set = rng.pick(&[Set::Pairs, Set::Barrier, Set::Heavy]);
        float_scene(rng, set)
    };
    impact = approaching(rng, impact);
    let e = if dyadic {
        dy(rng, 0, 4, 4.0)
    } else {
        random_e(rng)
    };
    let et = if rng.chance(0.5) {
        None
    } else if dyadic {
        Some(dy(rng, -4, 4, 4.0))
    } else {
        Some(rng.range(-1.0, 1.0))
    };
    let s = Scene::new(&impact);
    let target = s.target_ratio(&q(e), &q(et.unwrap_or(0.0)))?.abs();
    let f0 = to_f64(&target);
    let variant = rng.next_u64() % 3;
    let f = match variant {
        0 => f0,
        1 => f64::from_bits(f0.to_bits() + 1),
        _ if f0 > 0.0 => f64::from_bits(f0.to_bits() - 1),
        _ => f0,
    };
    impact.law = match et {
        None => Law::Friction {
            restitution: e,
            friction: f,
        },
        Some(et) => Law::TangentialRestitution {
            restitution: e,
            friction: f,
            tangential_restitution: et,
        },
    };
    Some((impact, q(f) == target))
}

fn cases(seed: u64) -> Vec<Case> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    for (set, count) in SETS {
        let mut made = 0;
        while made < count * SIZE {
            let (impact, boundary, on_cap) = match set {
                Set::Pairs | Set::Barrier | Set::Heavy => {
                    let i = float_scene(&mut rng, set);
                    (approaching(&mut rng, i), false, false)
                }
                Set::Central => {
                    let i = central_scene(&mut rng);
                    (approaching(&mut rng, i), false, false)
                }
                Set::Dyadic => {
                    let i = dyadic_scene(&mut rng);
                    (approaching(&mut rng, i), false, false)
                }
                Set::ZeroSlip => {
                    let mut i = zero_slip_scene(&mut rng);
                    let e = dy(&mut rng, 0, 4, 4.0);
                    let f = dy(&mut rng, 0, 8, 8.0);
                    i.law = if rng.chance(0.5) {
                        Law::Friction {
                            restitution: e,
                            friction: f,
                        }
                    } else {
                        Law::TangentialRestitution {
                            restitution: e,
                            friction: f,
                            tangential_restitution: dy(&mut rng, -4, 4, 4.0),
                        }
                    };
                    (i, false, false)
                }
                Set::AtCap => match at_cap(&mut rng) {
                    Some((i, on_cap)) => (i, true, on_cap),
                    None => continue,
                },
            };
            out.push(Case {
                set,
                impact,
                boundary,
                on_cap,
            });
            made += 1;
        }
    }
    out
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits()
}

/// Every disagreement of an `exact` answer with the reference.
fn exact_mismatches(o: &BodiesOutcome, a: &Answer) -> Vec<String> {
    let mut bad = Vec::new();
    let mut rational = |name: String, got: f64, x: &Q| {
        let want = to_f64(x);
        if !same(got, want) {
            bad.push(format!("{name}: got {got:e}, want {want:e} (exact {x})"));
        }
    };
    for (k, b) in a.bodies.iter().enumerate() {
        let g = &o.bodies[k];
        rational(format!("bodies[{k}].velocity.x"), g.velocity[0], &b.v[0]);
        rational(format!("bodies[{k}].velocity.y"), g.velocity[1], &b.v[1]);
        rational(format!("bodies[{k}].angular_velocity"), g.angular_velocity, &b.w);
        rational(format!("bodies[{k}].velocity_change.x"), g.velocity_change[0], &b.dv[0]);
        rational(format!("bodies[{k}].velocity_change.y"), g.velocity_change[1], &b.dv[1]);
        rational(format!("bodies[{k}].angular_velocity_change"), g.angular_velocity_change, &b.dw);
    }
    rational("impulse.x".into(), o.impulse.x, &a.p[0]);
    rational("impulse.y".into(), o.impulse.y, &a.p[1]);
    rational("impulse_ratio".into(), o.impulse_ratio, &a.mu);
    rational("restitution".into(), o.restitution, &a.e);
    rational("kinetic_restitution".into(), o.kinetic_restitution, &a.r);
    match (&o.energy, &a.t_max) {
        (Some(en), t_max) => {
            rational("energy.initial".into(), en.initial, &a.t_initial);
            rational("energy.final".into(), en.r#final, &a.t_final);
            rational("energy.loss".into(), en.loss, &a.t_loss);
            rational("energy.max_loss".into(), en.max_loss, t_max);
            rational("energy.normalized_loss".into(), en.normalized_loss, &(&a.t_loss / t_max));
        }
        (None, _) => bad.push("energy missing".into()),
    }
    match (o.critical_impulse_ratio, &a.mu_c) {
        (Some(got), Some(x)) => rational("critical_impulse_ratio".into(), got, x),
        (None, None) => {}
        (got, want) => bad.push(format!("critical_impulse_ratio: got {got:?}, want {want:?}")),
    }
    let mut root = |name: String, got: f64, x: &Q, y: &Q| {
        if !is_correctly_rounded_sqrt(got, x, y) {
            let approx = to_f64(&(x * sqrt_approx(y)));
            bad.push(format!("{name}: got {got:e}, not the rounding of ≈ {approx:e}"));
        }
    };
    for (k, b) in a.bodies.iter().enumerate() {
        root(format!("bodies[{k}].delta_v"), o.bodies[k].delta_v, &Q::one(), &b.dv2);
    }
    let cv = &o.contact_velocity;
    root("contact_velocity.initial.normal".into(), cv.initial.normal, &(&a.u[0] / &a.n2), &a.n2);
    root("contact_velocity.initial.tangential".into(), cv.initial.tangential, &(&a.u[1] / &a.n2), &a.n2);
    root("contact_velocity.final.normal".into(), cv.r#final.normal, &(&a.uf[0] / &a.n2), &a.n2);
    root("contact_velocity.final.tangential".into(), cv.r#final.tangential, &(&a.uf[1] / &a.n2), &a.n2);
    root("impulse.normal".into(), o.impulse.normal, &a.q[0], &a.n2);
    root("impulse.tangential".into(), o.impulse.tangential, &a.q[1], &a.n2);
    if o.regime.as_str() != a.regime {
        bad.push(format!("regime: got {}, want {}", o.regime.as_str(), a.regime));
    }
    if o.body_count != a.bodies.len() {
        bad.push(format!("body_count: got {}, want {}", o.body_count, a.bodies.len()));
    }
    bad
}

#[test]
fn exact_precision_is_the_correctly_rounded_reference_for_every_output() {
    let (mut answered, mut refused, mut on_cap) = (0usize, 0usize, 0usize);
    let mut per_set = Vec::new();
    let mut refusals = std::collections::BTreeMap::new();
    let mut regimes = std::collections::BTreeMap::new();
    for case in cases(0x0b0d_1e5e_ac7) {
        let want = exact::solve(&case.impact);
        let got = solve(&case.impact, Outputs::ALL, Precision::Exact);
        match (&want, &got) {
            (Ok(a), Ok(o)) => {
                let bad = exact_mismatches(o, a);
                assert!(
                    bad.is_empty(),
                    "{:?} {:?}: exact answer differs from the reference:\n  {}",
                    case.set,
                    case.impact,
                    bad.join("\n  ")
                );
                answered += 1;
                *regimes.entry(a.regime).or_insert(0usize) += 1;
                on_cap += usize::from(case.on_cap);
            }
            (Err(r), Err(e)) => {
                assert_eq!(r.slug(), e.slug(), "{:?} {:?}: {e}", case.set, case.impact);
                refused += 1;
                *refusals.entry(r.slug()).or_insert(0usize) += 1;
            }
            (want, got) => panic!(
                "{:?} {:?}: reference {:?}, solver {:?}",
                case.set,
                case.impact,
                want.as_ref().map(|a| a.regime),
                got.as_ref().map(|o| o.regime)
            ),
        }
        per_set.push(case.set);
    }
    eprintln!(
        "exact: {answered} answered, {refused} refused {refusals:?}; regimes {regimes:?}; \
         {on_cap} answered with f = |μ_target| exactly"
    );
    assert!(answered > 2000 * SIZE / 4 && refused > 0, "answered {answered}, refused {refused}");
    assert!(on_cap > 0, "no case sat exactly on the friction cap");
    for r in ["not-approaching", "no-impulse-solution", "creates-energy"] {
        assert!(refusals.contains_key(r), "no {r} refusal exercised");
    }
    for r in ["frictionless", "prescribed", "sliding", "sticking", "restitution"] {
        assert!(regimes.contains_key(r), "no {r} answer exercised");
    }
}

/// The largest error per output, with the case that made it.
#[derive(Default)]
struct Errors {
    rows: Vec<(&'static str, f64, String)>,
}

impl Errors {
    fn record(&mut self, name: &'static str, err: f64, case: &dyn Fn() -> String) {
        assert!(err.is_finite(), "{name}: error {err} for {}", case());
        match self.rows.iter_mut().find(|r| r.0 == name) {
            Some(row) if err > row.1 => {
                row.1 = err;
                row.2 = case();
            }
            Some(_) => {}
            None => self.rows.push((name, err, case())),
        }
    }
}

fn max_abs<'a>(values: impl IntoIterator<Item = &'a Q>) -> Q {
    values.into_iter().map(|v| v.abs()).max().unwrap_or_else(Q::zero)
}

/// Compares a `fast` answer with the reference, output by output, in ulps of its scale.
fn measure(errors: &mut Errors, impact: &BodiesImpact, o: &BodiesOutcome, a: &Answer) {
    let s = Scene::new(impact);
    let case = || format!("{impact:?}");
    let one = Q::one();
    // σ_v: every velocity term of the contact, initial and final.
    let mut sv = Q::zero();
    for (b, f) in s.bodies.iter().zip(&a.bodies) {
        let lever = b.r[0].abs() + b.r[1].abs();
        let terms = [
            b.v[0].abs(),
            b.v[1].abs(),
            f.v[0].abs(),
            f.v[1].abs(),
            (b.w.abs() + f.w.abs()) * &lever,
        ];
        sv = sv.max(max_abs(&terms));
    }
    let kappa = &a.kappa;
    let m_red = one.clone() / s.bodies.iter().map(|b| one.clone() / &b.m).sum::<Q>();
    // σ_P: an impulse from velocity changes ≤ σ_v through ‖W⁻¹‖ ≤ m_red, with the solve's conditioning.
    let sp = &m_red * &sv * kappa;
    let norm = sqrt_approx(&a.n2);
    let mut body_scales = Vec::new();
    for (k, (b, f)) in s.bodies.iter().zip(&a.bodies).enumerate() {
        let g = &o.bodies[k];
        let lever = b.r[0].abs() + b.r[1].abs();
        let sdv = &sp / &b.m;
        let sdw = &sp * &lever / &b.i;
        let svb = max_abs(&[b.v[0].clone(), b.v[1].clone(), f.v[0].clone(), f.v[1].clone(), sdv.clone()]);
        let swb = max_abs(&[b.w.clone(), f.w.clone(), sdw.clone()]);
        errors.record("velocity", ulps(g.velocity[0], &f.v[0], &svb), &case);
        errors.record("velocity", ulps(g.velocity[1], &f.v[1], &svb), &case);
        errors.record("angular_velocity", ulps(g.angular_velocity, &f.w, &swb), &case);
        errors.record("velocity_change", ulps(g.velocity_change[0], &f.dv[0], &sdv), &case);
        errors.record("velocity_change", ulps(g.velocity_change[1], &f.dv[1], &sdv), &case);
        errors.record("delta_v", ulps(g.delta_v, &sqrt_approx(&f.dv2), &sdv), &case);
        errors.record("angular_velocity_change", ulps(g.angular_velocity_change, &f.dw, &sdw), &case);
        body_scales.push((svb, swb));
    }
    let cv = &o.contact_velocity;
    let along = |x: &Q| x / &norm;
    let svk = &sv * kappa;
    errors.record("contact_velocity.initial", ulps(cv.initial.normal, &along(&a.u[0]), &sv), &case);
    errors.record("contact_velocity.initial", ulps(cv.initial.tangential, &along(&a.u[1]), &sv), &case);
    errors.record("contact_velocity.final", ulps(cv.r#final.normal, &along(&a.uf[0]), &svk), &case);
    errors.record("contact_velocity.final", ulps(cv.r#final.tangential, &along(&a.uf[1]), &svk), &case);
    let pn = &a.q[0] * &norm;
    errors.record("impulse.normal", ulps(o.impulse.normal, &pn, &sp), &case);
    errors.record("impulse.tangential", ulps(o.impulse.tangential, &(&a.q[1] * &norm), &sp), &case);
    errors.record("impulse.x", ulps(o.impulse.x, &a.p[0], &sp), &case);
    errors.record("impulse.y", ulps(o.impulse.y, &a.p[1], &sp), &case);
    // μ = P_t/P_n: both parts within σ_P.
    let smu = &sp * (&one + a.mu.abs()) / &pn;
    errors.record("impulse_ratio", ulps(o.impulse_ratio, &a.mu, &smu), &case);
    if let (Some(got), Some(mu_c)) = (o.critical_impulse_ratio, &a.mu_c) {
        let pn_c = (&a.qn_c * &norm).abs();
        let scale = &m_red * &sv * &a.kappa_c * (&one + mu_c.abs()) / pn_c;
        errors.record("critical_impulse_ratio", ulps(got, mu_c, &scale), &case);
    } else {
        assert_eq!(o.critical_impulse_ratio.is_some(), a.mu_c.is_some(), "μ_c presence: {}", case());
    }
    // e: the input, or R D(μ_R)/D(μ_A) with both D's conditioning.
    let se = match impact.law {
        Law::KineticRestitution {
            approach_impulse_ratio,
            rebound_impulse_ratio,
            ..
        } => {
            let (mu_a, mu_r) = (q(approach_impulse_ratio), q(rebound_impulse_ratio));
            let size_r = &s.w[0][0] + mu_r.abs() * &s.w12_size;
            &a.r * size_r / s.d(&mu_a) + &a.e * s.kappa_ratio(&mu_a)
        }
        _ => a.e.clone(),
    };
    errors.record("restitution", ulps(o.restitution, &a.e, &se), &case);
    errors.record("kinetic_restitution", ulps(o.kinetic_restitution, &a.r, &a.r), &case);
    let en = o.energy.expect("energy requested");
    errors.record("energy.initial", ulps(en.initial, &a.t_initial, &a.t_initial), &case);
    let sf: Q = s
        .bodies
        .iter()
        .zip(&body_scales)
        .map(|(b, (v, w))| &b.m * v * v + &b.i * w * w)
        .sum();
    errors.record("energy.final", ulps(en.r#final, &a.t_final, &sf), &case);
    // T_L = −½ P·(u + U): an impulse within σ_P times velocities within κ σ_v.
    let sl = &sp * &svk;
    errors.record("energy.loss", ulps(en.loss, &a.t_loss, &sl), &case);
    // T_M = ½ ũᵀ W̃⁻¹ ũ: W̃'s conditioning, and ũ within σ_v.
    let sm = &a.t_max * &a.kappa_c + &m_red * &sv * &sv;
    errors.record("energy.max_loss", ulps(en.max_loss, &a.t_max, &sm), &case);
    let tls = &a.t_loss / &a.t_max;
    let sls = (&sl + &tls * &sm) / &a.t_max;
    errors.record("energy.normalized_loss", ulps(en.normalized_loss, &tls, &sls), &case);
}

#[test]
fn fast_precision_is_within_its_bound_of_the_reference() {
    let mut errors = Errors::default();
    let (mut measured, mut refused, mut flipped) = (0usize, 0usize, 0usize);
    for case in cases(0xfa57_b0d1) {
        let want = exact::solve(&case.impact);
        let got = solve(&case.impact, Outputs::ALL, Precision::Fast);
        match (&want, &got) {
            (Ok(a), Ok(o)) if o.regime.as_str() == a.regime => {
                measure(&mut errors, &case.impact, o, a);
                measured += 1;
            }
            (Err(r), Err(e)) if r.slug() == e.slug() => refused += 1,
            (want, got) => {
                // Only a decision within rounding of its boundary may go the other way.
                assert!(
                    case.boundary,
                    "{:?} {:?}: reference {:?}, fast {:?}",
                    case.set,
                    case.impact,
                    want.as_ref().map(|a| a.regime),
                    got.as_ref().map(|o| o.regime).map_err(ImpactError::slug)
                );
                flipped += 1;
            }
        }
    }
    let mut table = format!("fast: {measured} measured, {refused} refused alike, {flipped} flipped at a boundary; max ulps of scale:");
    for (name, err, _) in &errors.rows {
        table.push_str(&format!("\n  {name:<26} {err:>8.3}"));
    }
    eprintln!("{table}");
    for (name, err, case) in &errors.rows {
        assert!(*err <= FAST_BOUND_ULPS, "{name}: {err} ulps (bound {FAST_BOUND_ULPS}) for {case}");
    }
    assert!(measured > 2000 * SIZE / 4, "measured {measured}");
}

/// The reference against the one-body reference of `tests/common/reference.rs`
/// (a separate derivation, Gaussian elimination in the `(n, t)` frame): a body
/// against the barrier in the four axis-aligned frames, exactly.
#[test]
fn the_reference_reproduces_the_one_body_reference() {
    let mut rng = Rng::new(0x0e_b0d7);
    let frames = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    let (mut answered, mut refused) = (0, 0);
    for i in 0..300 * SIZE {
        let inp = common::accuracy::random_inputs(&mut rng);
        let law = random_law(&mut rng);
        let [c, s] = frames[i % 4];
        let t = [-s, c];
        let (dc, dd) = (inp.dc, inp.dd);
        // r_A = C − G = −(d_c t̂ + d_d n̂) with C at the origin; v = v_n n̂ + v_t t̂ (exact: axis frames).
        let impact = BodiesImpact {
            a: Lamina {
                mass: inp.m,
                inertia: inp.inertia,
                position: [dc * t[0] + dd * c, dc * t[1] + dd * s],
                velocity: [inp.vn * c + inp.vt * t[0], inp.vn * s + inp.vt * t[1]],
                angular_velocity: inp.w,
            },
            b: None,
            contact: PlanarContact {
                point: [0.0, 0.0],
                normal: [c, s],
            },
            law,
        };
        let scene = inp.exact();
        let expected = match law {
            Law::Frictionless { restitution } => one::frictionless(&scene, restitution),
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => one::prescribed(&scene, restitution, impulse_ratio),
            Law::Friction {
                restitution,
                friction,
            } => one::bilinear(&scene, restitution, friction, 0.0, "sticking"),
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => one::bilinear(&scene, restitution, friction, tangential_restitution, "restitution"),
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => one::kinetic(&scene, value, approach_impulse_ratio, rebound_impulse_ratio),
        };
        let got = exact::solve(&impact);
        match (expected, got) {
            (Ok(e), Ok(g)) => {
                answered += 1;
                let b = &g.bodies[0];
                let (qc, qs) = (q(c), q(s));
                let vn = &b.v[0] * &qc + &b.v[1] * &qs;
                let vt = -(&b.v[0] * &qs) + &b.v[1] * &qc;
                assert_eq!((vn, vt, &b.w), (e.vn, e.vt, &e.w), "{impact:?}");
                assert_eq!((&g.uf[0], &g.uf[1]), (&e.vcn, &e.vct), "{impact:?}");
                assert_eq!((&g.q[0], &g.q[1]), (&e.pn, &e.pt), "{impact:?}");
                assert_eq!((&g.mu, &g.mu_c, &g.e, &g.r), (&e.mu, &e.mu_c, &e.e, &e.r), "{impact:?}");
                assert_eq!(g.regime, e.regime, "{impact:?}");
                assert_eq!(
                    (&g.t_initial, &g.t_final, &g.t_loss, &g.t_max),
                    (&e.t_initial, &e.t_final, &e.t_loss, &e.t_max),
                    "{impact:?}"
                );
            }
            (Err(e), Err(g)) => {
                refused += 1;
                assert_eq!(format!("{e:?}"), format!("{g:?}"), "{impact:?}");
            }
            (e, g) => panic!("{impact:?}: one body {:?}, two-body {:?}", e.map(|o| o.regime), g.map(|o| o.regime)),
        }
    }
    assert!(answered > 100 * SIZE && refused > 0, "answered {answered}, refused {refused}");
}

/// The rounding checks themselves: against `to_f64` (num-rational's correctly
/// rounded conversion) on random rationals, on exact ties, and on roots.
#[test]
fn the_rounding_checks_accept_exactly_the_correctly_rounded_double() {
    let mut rng = Rng::new(0x0123);
    let up = |a: f64| if a == 0.0 { f64::from_bits(1) } else if a > 0.0 { f64::from_bits(a.to_bits() + 1) } else { f64::from_bits(a.to_bits() - 1) };
    let down = |a: f64| -up(-a);
    for _ in 0..2000 {
        let x = q(rng.sign() * rng.log_uniform(-30.0, 30.0)) / q(rng.log_uniform(-30.0, 30.0));
        let a = to_f64(&x);
        assert!(is_correctly_rounded(a, &x), "{x}");
        assert!(!is_correctly_rounded(up(a), &x) && !is_correctly_rounded(down(a), &x), "{x}");
        // x √y with y a non-square, and with y a square.
        let y = q(rng.log_uniform(-20.0, 20.0));
        let approx = to_f64(&(&x * sqrt_approx(&y)));
        let hits = [down(down(approx)), down(approx), approx, up(approx), up(up(approx))]
            .into_iter()
            .filter(|&c| is_correctly_rounded_sqrt(c, &x, &y))
            .count();
        assert_eq!(hits, 1, "{x} √{y}");
        let root = q(rng.log_uniform(-10.0, 10.0));
        let y = &root * &root;
        assert!(is_correctly_rounded_sqrt(to_f64(&(&x * &root)), &x, &y), "{x} · {root}");
    }
    // Ties go to even: 1 + 2⁻⁵³ rounds to 1, 1 + 3·2⁻⁵³ to 1 + 2⁻⁵¹.
    let eps = q(f64::EPSILON) / q(2.0);
    let tie = Q::one() + &eps;
    assert!(is_correctly_rounded(1.0, &tie) && !is_correctly_rounded(up(1.0), &tie));
    assert!(is_correctly_rounded_sqrt(1.0, &Q::one(), &(&tie * &tie)));
    assert!(is_correctly_rounded_sqrt(-1.0, &-Q::one(), &(&tie * &tie)));
    let tie = Q::one() + q(3.0) * &eps;
    assert!(is_correctly_rounded(up(up(1.0)), &tie) && !is_correctly_rounded(up(1.0), &tie));
    // Zeros: an exact zero is +0.0 only; a tiny negative value rounds to −0.0.
    assert!(is_correctly_rounded(0.0, &Q::zero()) && !is_correctly_rounded(-0.0, &Q::zero()));
    let tiny = -q(f64::from_bits(1)) / q(4.0);
    assert!(is_correctly_rounded(-0.0, &tiny) && !is_correctly_rounded(0.0, &tiny));
}
