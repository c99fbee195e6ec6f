//! The planar two-body contact against an independent exact reference
//! (`testkit/src/bodies_reference.rs`: rationals, derived from the momentum
//! equations alone, checked against the one-body reference below).
//!
//! The cases: pairs and single bodies against the barrier with masses, sizes,
//! speeds and normal lengths over six decades and normals of any direction;
//! partners 10⁶…10¹² times heavier; exactly central contacts; small dyadic
//! scenes (exact zeros, rounding ties); scenes with exactly zero initial slip;
//! friction at, and one ulp either side of, the kept branch's cap (exactly on
//! it where `|μ_target|` is a double, by construction). Every law, `e` and `R`
//! at 0 and 1.
//!
//! - `exact` precision: every rational output equals the reference's
//!   correctly rounded value bit for bit (`+0.0` for an exact zero), every
//!   `x √y` output (components along `n̂`, `t̂` and `|ΔV|`) is correctly rounded
//!   by an exact comparison of squares, regimes and refusals agree.
//! - `fast` precision: every output within `FAST_BOUND_ULPS` ulps of its scale,
//!   the magnitude of the terms it combines times the conditioning of the
//!   solve (`measure`); every regime and refusal is the reference's, on the
//!   caps and one ulp either side of them too (`fast` decisions are exact).
//!   `cargo test --release --test bodies_reference -- --nocapture` prints the
//!   largest error of each output; `-- --ignored` runs the larger survey.

use crate::common::Rng;
use crate::common::bodies_reference::{
    self as exact, Answer, Scene, is_correctly_rounded, is_correctly_rounded_sqrt, sqrt_approx,
};
use crate::common::reference::{self as one, Q, q, to_f64, ulp_of};
use num_traits::{One, Signed, Zero};
use restitution::{
    BodiesImpact, BodiesOutcome, ImpactError, Lamina, Law, Outputs, PlanarContact, Precision, solve,
};

/// The largest error of a `fast` answer, in ulps of each output's scale. The
/// largest measured is 5.8 ulps (`impulse.normal`; `velocity` 5.7) over the
/// 84,000 cases of `fast_precision_survey`; twice that, rounded up.
const FAST_BOUND_ULPS: f64 = 12.0;

/// Fewer cases in the debug profile (CI's `cargo test`): 2,100 there, 4,200 in release.
const SIZE: usize = if cfg!(debug_assertions) { 1 } else { 2 };

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
    /// A decision sits within rounding of its boundary (the cap or one ulp from it).
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
    let ma = mass * rng.log_uniform(-1.0, 1.0);
    let a = lamina(rng, c, ma, length, speed);
    let b = match set {
        Set::Barrier => None,
        Set::Heavy => {
            let l = length * rng.log_uniform(-1.0, 1.0);
            let mb = a.mass * rng.log_uniform(6.0, 12.0);
            Some(lamina(rng, c, mb, l, speed))
        }
        _ => {
            let l = length * rng.log_uniform(-1.0, 1.0);
            let s = speed * rng.log_uniform(-1.0, 1.0);
            let mb = mass * rng.log_uniform(-1.5, 1.5);
            Some(lamina(rng, c, mb, l, s))
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
        1 => {
            let mb = mass * rng.log_uniform(-1.0, 1.0);
            Some(central(rng, mb))
        }
        _ => {
            let mb = mass * rng.log_uniform(-1.0, 1.0);
            Some(lamina(rng, [0.0, 0.0], mb, length, speed))
        }
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
        mass: {
            let den = rng.pick(&[1.0, 2.0, 4.0]);
            dy(rng, 1, 8, den)
        },
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

/// A dyadic scene built so that the kept impulse has the ratio `μ* = k/8`
/// exactly, under friction or tangential restitution with `f = |μ*|` or one
/// ulp either side. Masses, inertias and `|n|²` are powers of two, so `W̃` is
/// dyadic and the velocities that give `ũ ∝ ((1 + e_t) D̃(μ*), (1 + e)(W̃_21 +
/// μ* W̃_22))` are exact doubles. `None` when `D̃(μ*) ≤ 0`.
fn built_on_cap(rng: &mut Rng) -> Option<(BodiesImpact, bool)> {
    let mut impact = dyadic_scene(rng);
    let pow2 = |rng: &mut Rng, lo: i64, hi: i64| 2f64.powi(dy(rng, lo, hi, 1.0) as i32);
    for l in std::iter::once(&mut impact.a).chain(impact.b.as_mut()) {
        l.mass = pow2(rng, -2, 3);
        l.inertia = pow2(rng, -2, 3);
    }
    let axis = rng.pick(&[
        [1.0, 0.0],
        [0.0, 1.0],
        [-1.0, 0.0],
        [0.0, -1.0],
        [1.0, 1.0],
        [-1.0, 1.0],
        [1.0, -1.0],
    ]);
    let scale = pow2(rng, -2, 2);
    impact.contact.normal = [axis[0] * scale, axis[1] * scale];
    let e = dy(rng, 0, 4, 4.0);
    let et = if rng.chance(0.5) {
        None
    } else {
        Some(dy(rng, -3, 4, 4.0))
    };
    let mu = q(dy(rng, -8, 8, 8.0));
    let s = Scene::new(&impact);
    let d = s.d(&mu);
    if !d.is_positive() {
        return None;
    }
    let lambda = q(pow2(rng, -3, 0));
    let u = [
        -(&lambda * (Q::one() + q(et.unwrap_or(0.0))) * &d),
        -(&lambda * (Q::one() + q(e)) * (&s.w[1][0] + &mu * &s.w[1][1])),
    ];
    // The world u, and v_A = u + u_B − ω_A ẑ × r_A.
    let uw = [
        (&u[0] * &s.n[0] + &u[1] * &s.t[0]) / &s.n2,
        (&u[0] * &s.n[1] + &u[1] * &s.t[1]) / &s.n2,
    ];
    let ub = match s.bodies.get(1) {
        Some(b) => b.point_velocity(&b.v, &b.w),
        None => [Q::zero(), Q::zero()],
    };
    let a = &s.bodies[0];
    let va = [&uw[0] + &ub[0] + &a.w * &a.r[1], &uw[1] + &ub[1] - &a.w * &a.r[0]];
    impact.a.velocity = [exactly(&va[0]), exactly(&va[1])];
    let cap = to_f64(&mu.abs());
    let f = match rng.next_u64() % 4 {
        0 | 1 => cap,
        2 => f64::from_bits(cap.to_bits() + 1),
        _ if cap > 0.0 => f64::from_bits(cap.to_bits() - 1),
        _ => cap,
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
    let s = Scene::new(&impact);
    assert_eq!(s.u, u, "built ũ");
    assert_eq!(
        s.target_ratio(&q(e), &q(et.unwrap_or(0.0))),
        Some(mu.clone()),
        "built μ*"
    );
    Some((impact, q(f) == mu.abs()))
}

/// Friction or tangential restitution with `f` at the rounded `|μ_target|`
/// or one ulp either side; `None` where the target has `P_n = 0`.
fn at_cap(rng: &mut Rng) -> Option<(BodiesImpact, bool)> {
    if rng.chance(0.5) {
        return built_on_cap(rng);
    }
    let dyadic = rng.chance(0.6);
    let mut impact = if dyadic {
        dyadic_scene(rng)
    } else {
        let set = rng.pick(&[Set::Pairs, Set::Barrier, Set::Heavy]);
        float_scene(rng, set)
    };
    impact = approaching(rng, impact);
    let e = if dyadic { dy(rng, 0, 4, 4.0) } else { random_e(rng) };
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

/// A case with its exact scene and reference answer.
struct Solved {
    case: Case,
    scene: Scene,
    reference: Result<Answer, exact::Refusal>,
}

/// The cases and their reference answers, computed once for both precision tests.
fn solved() -> &'static [Solved] {
    static SOLVED: std::sync::OnceLock<Vec<Solved>> = std::sync::OnceLock::new();
    SOLVED.get_or_init(|| {
        cases(0x00b0_d1e5_eac7, SIZE)
            .into_iter()
            .map(|case| {
                let scene = Scene::new(&case.impact);
                let reference = exact::solve_scene(&scene, case.impact.law);
                Solved {
                    case,
                    scene,
                    reference,
                }
            })
            .collect()
    })
}

fn cases(seed: u64, size: usize) -> Vec<Case> {
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    for (set, count) in SETS {
        let mut made = 0;
        while made < count * size {
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
            let boundary = boundary || exact::kept_on_cap(&impact);
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

fn rational_check(bad: &mut Vec<String>, name: String, got: f64, x: &Q) {
    let want = to_f64(x);
    if !same(got, want) {
        bad.push(format!("{name}: got {got:e}, want {want:e} (exact {x})"));
    }
}

fn root_check(bad: &mut Vec<String>, name: String, got: f64, x: &Q, y: &Q) {
    if !is_correctly_rounded_sqrt(got, x, y) {
        let approx = to_f64(&(x * sqrt_approx(y)));
        bad.push(format!("{name}: got {got:e}, not the rounding of ≈ {approx:e}"));
    }
}

/// Every disagreement of an `exact` answer with the reference.
fn exact_mismatches(o: &BodiesOutcome, a: &Answer) -> Vec<String> {
    let mut bad = Vec::new();
    for (k, b) in a.bodies.iter().enumerate() {
        let g = &o.bodies[k];
        rational_check(
            &mut bad,
            format!("bodies[{k}].velocity.x"),
            g.velocity[0],
            &b.v[0],
        );
        rational_check(
            &mut bad,
            format!("bodies[{k}].velocity.y"),
            g.velocity[1],
            &b.v[1],
        );
        rational_check(
            &mut bad,
            format!("bodies[{k}].angular_velocity"),
            g.angular_velocity,
            &b.w,
        );
        rational_check(
            &mut bad,
            format!("bodies[{k}].velocity_change.x"),
            g.velocity_change[0],
            &b.dv[0],
        );
        rational_check(
            &mut bad,
            format!("bodies[{k}].velocity_change.y"),
            g.velocity_change[1],
            &b.dv[1],
        );
        rational_check(
            &mut bad,
            format!("bodies[{k}].angular_velocity_change"),
            g.angular_velocity_change,
            &b.dw,
        );
    }
    rational_check(&mut bad, "impulse.x".into(), o.impulse.x, &a.p[0]);
    rational_check(&mut bad, "impulse.y".into(), o.impulse.y, &a.p[1]);
    rational_check(&mut bad, "impulse_ratio".into(), o.impulse_ratio, &a.mu);
    rational_check(&mut bad, "restitution".into(), o.restitution, &a.e);
    rational_check(
        &mut bad,
        "kinetic_restitution".into(),
        o.kinetic_restitution,
        &a.r,
    );
    match (&o.energy, &a.t_max) {
        (Some(en), t_max) => {
            rational_check(&mut bad, "energy.initial".into(), en.initial, &a.t_initial);
            rational_check(&mut bad, "energy.final".into(), en.r#final, &a.t_final);
            rational_check(&mut bad, "energy.loss".into(), en.loss, &a.t_loss);
            rational_check(&mut bad, "energy.max_loss".into(), en.max_loss, t_max);
            rational_check(
                &mut bad,
                "energy.normalized_loss".into(),
                en.normalized_loss,
                &(&a.t_loss / t_max),
            );
        }
        (None, _) => bad.push("energy missing".into()),
    }
    match (o.critical_impulse_ratio, &a.mu_c) {
        (Some(got), Some(x)) => rational_check(&mut bad, "critical_impulse_ratio".into(), got, x),
        (None, None) => {}
        (got, want) => bad.push(format!("critical_impulse_ratio: got {got:?}, want {want:?}")),
    }
    for (k, b) in a.bodies.iter().enumerate() {
        root_check(
            &mut bad,
            format!("bodies[{k}].delta_v"),
            o.bodies[k].delta_v,
            &Q::one(),
            &b.dv2,
        );
    }
    let cv = &o.contact_velocity;
    root_check(
        &mut bad,
        "contact_velocity.initial.normal".into(),
        cv.initial.normal,
        &(&a.u[0] / &a.n2),
        &a.n2,
    );
    root_check(
        &mut bad,
        "contact_velocity.initial.tangential".into(),
        cv.initial.tangential,
        &(&a.u[1] / &a.n2),
        &a.n2,
    );
    root_check(
        &mut bad,
        "contact_velocity.final.normal".into(),
        cv.r#final.normal,
        &(&a.uf[0] / &a.n2),
        &a.n2,
    );
    root_check(
        &mut bad,
        "contact_velocity.final.tangential".into(),
        cv.r#final.tangential,
        &(&a.uf[1] / &a.n2),
        &a.n2,
    );
    root_check(
        &mut bad,
        "impulse.normal".into(),
        o.impulse.normal,
        &a.q[0],
        &a.n2,
    );
    root_check(
        &mut bad,
        "impulse.tangential".into(),
        o.impulse.tangential,
        &a.q[1],
        &a.n2,
    );
    if o.regime.as_str() != a.regime {
        bad.push(format!("regime: got {}, want {}", o.regime.as_str(), a.regime));
    }
    if o.body_count != a.bodies.len() {
        bad.push(format!(
            "body_count: got {}, want {}",
            o.body_count,
            a.bodies.len()
        ));
    }
    bad
}

#[test]
fn exact_precision_is_the_correctly_rounded_reference_for_every_output() {
    let (mut answered, mut refused, mut on_cap, mut zero_slip_sliding) = (0usize, 0usize, 0usize, 0usize);
    let mut refusals = std::collections::BTreeMap::new();
    let mut regimes = std::collections::BTreeMap::new();
    for Solved {
        case,
        reference: want,
        ..
    } in solved()
    {
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
                // Sliding with no initial slip: the direction comes from the sticking impulse.
                zero_slip_sliding +=
                    usize::from(case.set == Set::ZeroSlip && a.regime == "sliding" && !a.q[1].is_zero());
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
    }
    eprintln!(
        "exact: {answered} answered, {refused} refused {refusals:?}; regimes {regimes:?}; \
         {on_cap} answered with f = |μ_target| exactly, {zero_slip_sliding} sliding from zero slip"
    );
    assert!(zero_slip_sliding > 0, "no sliding answer from zero slip");
    assert!(
        answered > 2000 * SIZE / 4 && refused > 0,
        "answered {answered}, refused {refused}"
    );
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
    measured: usize,
    refused: usize,
    /// Cases on or one ulp either side of a cap (all decided as the reference does).
    at_boundary: usize,
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
    fn merge(&mut self, other: Errors) {
        for (name, err, case) in other.rows {
            self.record(name, err, &|| case.clone());
        }
        self.measured += other.measured;
        self.refused += other.refused;
        self.at_boundary += other.at_boundary;
    }
    fn report(&self) {
        let mut table = format!(
            "fast: {} measured, {} refused alike, {} at a cap (decided exactly); max ulps of scale:",
            self.measured, self.refused, self.at_boundary
        );
        for (name, err, _) in &self.rows {
            table.push_str(&format!("\n  {name:<26} {err:>8.3}"));
        }
        eprintln!("{table}");
    }
}

fn f(x: &Q) -> f64 {
    to_f64(x)
}

/// The error of `fast` in ulps of `scale` (or of the exact value where larger).
fn ulps_of(fast: f64, exact: &Q, scale: f64) -> f64 {
    let diff = to_f64(&(q(fast) - exact)).abs();
    diff / ulp_of(scale.abs().max(f(exact).abs()))
}

/// Compares a `fast` answer with the reference, output by output, in ulps of
/// its scale (computed in f64: it is only a magnitude).
fn measure(errors: &mut Errors, s: &Scene, impact: &BodiesImpact, o: &BodiesOutcome, a: &Answer) {
    let case = || format!("{impact:?}");
    struct Terms {
        m: f64,
        i: f64,
        lever: f64,
        v: f64,
        w: f64,
    }
    // σ_v: every velocity term of the contact, initial and final.
    let bodies: Vec<Terms> = s
        .bodies
        .iter()
        .zip(&a.bodies)
        .map(|(b, fa)| Terms {
            m: f(&b.m),
            i: f(&b.i),
            lever: f(&b.r[0]).abs() + f(&b.r[1]).abs(),
            v: [&b.v[0], &b.v[1], &fa.v[0], &fa.v[1]]
                .iter()
                .fold(0.0f64, |acc, x| acc.max(f(x).abs())),
            w: f(&b.w).abs().max(f(&fa.w).abs()),
        })
        .collect();
    let sv = bodies
        .iter()
        .fold(0.0f64, |acc, b| acc.max(b.v).max(2.0 * b.w * b.lever));
    let kappa = f(&a.kappa);
    let m_red = 1.0 / bodies.iter().map(|b| 1.0 / b.m).sum::<f64>();
    // σ_P: an impulse from velocity changes ≤ σ_v through ‖W⁻¹‖ ≤ m_red, with the solve's conditioning.
    let sp = m_red * sv * kappa;
    let root = sqrt_approx(&a.n2);
    let norm = f(&root);
    // Final contact velocities combine each body's final V and Ω |r| terms.
    let mut svf = sv * kappa;
    for (k, (b, fa)) in bodies.iter().zip(&a.bodies).enumerate() {
        let g = &o.bodies[k];
        let sdv = sp / b.m;
        let sdw = sp * b.lever / b.i;
        let svb = b.v.max(sdv);
        let swb = b.w.max(sdw);
        svf = svf.max(svb).max(swb * b.lever);
        errors.record("velocity", ulps_of(g.velocity[0], &fa.v[0], svb), &case);
        errors.record("velocity", ulps_of(g.velocity[1], &fa.v[1], svb), &case);
        errors.record("angular_velocity", ulps_of(g.angular_velocity, &fa.w, swb), &case);
        errors.record(
            "velocity_change",
            ulps_of(g.velocity_change[0], &fa.dv[0], sdv),
            &case,
        );
        errors.record(
            "velocity_change",
            ulps_of(g.velocity_change[1], &fa.dv[1], sdv),
            &case,
        );
        errors.record("delta_v", ulps_of(g.delta_v, &sqrt_approx(&fa.dv2), sdv), &case);
        errors.record(
            "angular_velocity_change",
            ulps_of(g.angular_velocity_change, &fa.dw, sdw),
            &case,
        );
    }
    let cv = &o.contact_velocity;
    let initial = [&a.u[0] / &root, &a.u[1] / &root];
    let last = [&a.uf[0] / &root, &a.uf[1] / &root];
    errors.record(
        "contact_velocity.initial",
        ulps_of(cv.initial.normal, &initial[0], sv),
        &case,
    );
    errors.record(
        "contact_velocity.initial",
        ulps_of(cv.initial.tangential, &initial[1], sv),
        &case,
    );
    errors.record(
        "contact_velocity.final",
        ulps_of(cv.r#final.normal, &last[0], svf),
        &case,
    );
    errors.record(
        "contact_velocity.final",
        ulps_of(cv.r#final.tangential, &last[1], svf),
        &case,
    );
    errors.record(
        "impulse.normal",
        ulps_of(o.impulse.normal, &(&a.q[0] * &root), sp),
        &case,
    );
    errors.record(
        "impulse.tangential",
        ulps_of(o.impulse.tangential, &(&a.q[1] * &root), sp),
        &case,
    );
    errors.record("impulse.x", ulps_of(o.impulse.x, &a.p[0], sp), &case);
    errors.record("impulse.y", ulps_of(o.impulse.y, &a.p[1], sp), &case);
    // μ = P_t/P_n: both parts within σ_P.
    let pn = f(&a.q[0]) * norm;
    let smu = sp * (1.0 + f(&a.mu).abs()) / pn;
    errors.record("impulse_ratio", ulps_of(o.impulse_ratio, &a.mu, smu), &case);
    match (o.critical_impulse_ratio, &a.mu_c) {
        (Some(got), Some(mu_c)) => {
            let pn_c = f(&a.qn_c).abs() * norm;
            let scale = m_red * sv * f(&a.kappa_c) * (1.0 + f(mu_c).abs()) / pn_c;
            errors.record("critical_impulse_ratio", ulps_of(got, mu_c, scale), &case);
        }
        (got, want) => assert_eq!(got.is_some(), want.is_some(), "μ_c presence: {}", case()),
    }
    // e: the input, or R D(μ_R)/D(μ_A) with both D's conditioning.
    let se = match impact.law {
        Law::KineticRestitution {
            approach_impulse_ratio,
            rebound_impulse_ratio,
            ..
        } => {
            let (mu_a, mu_r) = (q(approach_impulse_ratio), q(rebound_impulse_ratio));
            f(&a.r) * f(&s.d_size(&mu_r)) / f(&s.d(&mu_a)) + f(&a.e) * f(&s.kappa_ratio(&mu_a))
        }
        _ => f(&a.e),
    };
    errors.record("restitution", ulps_of(o.restitution, &a.e, se), &case);
    errors.record(
        "kinetic_restitution",
        ulps_of(o.kinetic_restitution, &a.r, f(&a.r)),
        &case,
    );
    let en = o.energy.expect("energy requested");
    let t_initial = f(&a.t_initial);
    errors.record(
        "energy.initial",
        ulps_of(en.initial, &a.t_initial, t_initial),
        &case,
    );
    // ½ m V² + ½ I Ω² with V, Ω within their scales.
    let sf: f64 = bodies
        .iter()
        .map(|b| {
            let (svb, swb) = (b.v.max(sp / b.m), b.w.max(sp * b.lever / b.i));
            b.m * svb * svb + b.i * swb * swb
        })
        .sum();
    errors.record("energy.final", ulps_of(en.r#final, &a.t_final, sf), &case);
    // T_L = −½ P·(u + U): an impulse within σ_P times contact velocities within their scale.
    let sl = sp * svf;
    errors.record("energy.loss", ulps_of(en.loss, &a.t_loss, sl), &case);
    // T_M = ½ ũᵀ W̃⁻¹ ũ: W̃'s conditioning, and ũ within σ_v.
    let t_max = f(&a.t_max);
    let sm = t_max * f(&a.kappa_c) + m_red * sv * sv;
    errors.record("energy.max_loss", ulps_of(en.max_loss, &a.t_max, sm), &case);
    let tls = &a.t_loss / &a.t_max;
    let sls = (sl + f(&tls) * sm) / t_max;
    errors.record(
        "energy.normalized_loss",
        ulps_of(en.normalized_loss, &tls, sls),
        &case,
    );
}

/// `fast`'s promised error (docs/accuracy.md) on every scene of the set,
/// near-singular, heavy-partner and on-the-cap ones included: each number
/// within `2⁻³² max(|x|, S)` of the correctly rounded exact answer, or the
/// impact escalated.
#[test]
fn fast_keeps_its_promised_error_on_every_scene() {
    let mut tally = crate::common::accuracy::PromiseTally::default();
    for Solved { case, .. } in solved() {
        crate::common::accuracy::check_promise(&case.impact, &mut tally);
    }
    println!("two bodies, fast's promise: {tally:?}");
    assert!(
        tally.impacts > 1000 * SIZE && tally.outputs > 20 * tally.impacts,
        "{tally:?}"
    );
}

/// Measures `fast` on `solved`: the largest errors, and the counts
/// (measured, refused alike, at a cap); any regime or refusal unlike the reference fails.
fn fast_errors<'a>(solved: impl Iterator<Item = &'a Solved>) -> Errors {
    let mut errors = Errors::default();
    for Solved {
        case,
        scene,
        reference: want,
    } in solved
    {
        let got = solve(&case.impact, Outputs::ALL, Precision::Fast);
        match (want, &got) {
            (Ok(a), Ok(o)) if o.regime.as_str() == a.regime => {
                measure(&mut errors, scene, &case.impact, o, a);
                errors.measured += 1;
            }
            (Err(r), Err(e)) if r.slug() == e.slug() => errors.refused += 1,
            (want, got) => panic!(
                // Every decision of `fast` is the exact one: on the cap, one
                // ulp either side of it, and at T_L = 0 alike.
                "{:?} {:?}: reference {:?}, fast {:?}",
                case.set,
                case.impact,
                want.as_ref().map(|a| a.regime),
                got.as_ref().map(|o| o.regime).map_err(ImpactError::slug)
            ),
        }
        if case.boundary {
            errors.at_boundary += 1;
        }
    }
    errors
}

#[test]
fn fast_precision_is_within_its_bound_of_the_reference() {
    let errors = fast_errors(solved().iter());
    errors.report();
    for (name, err, case) in &errors.rows {
        assert!(
            *err <= FAST_BOUND_ULPS,
            "{name}: {err} ulps (bound {FAST_BOUND_ULPS}) for {case}"
        );
    }
    assert!(errors.measured > 2000 * SIZE / 4, "measured {}", errors.measured);
    assert!(errors.at_boundary > 100, "at a cap {}", errors.at_boundary);
}

/// The same over 20 times as many cases, in batches (about three minutes in
/// release): `cargo test --release --test bodies_reference -- --ignored --nocapture`.
#[test]
#[ignore]
fn fast_precision_survey() {
    let mut all = Errors::default();
    for batch in 0..10 {
        let solved: Vec<Solved> = cases(0x5u64 << 32 | batch, 4)
            .into_iter()
            .map(|case| {
                let scene = Scene::new(&case.impact);
                let reference = exact::solve_scene(&scene, case.impact.law);
                Solved {
                    case,
                    scene,
                    reference,
                }
            })
            .collect();
        all.merge(fast_errors(solved.iter()));
    }
    all.report();
    for (name, err, case) in &all.rows {
        eprintln!("worst {name}: {err:.3} for {case}");
    }
}

/// The reference against the one-body reference of `testkit/src/reference.rs`
/// (a separate derivation, Gaussian elimination in the `(n, t)` frame): a body
/// against the barrier in the four axis-aligned frames, exactly.
#[test]
fn the_reference_reproduces_the_one_body_reference() {
    let mut rng = Rng::new(0x0e_b0d7);
    let frames = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
    let (mut answered, mut refused) = (0, 0);
    for i in 0..300 * SIZE {
        let inp = crate::common::accuracy::random_inputs(&mut rng);
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
            } => one::bilinear(
                &scene,
                restitution,
                friction,
                tangential_restitution,
                "restitution",
            ),
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => one::kinetic(&scene, value, approach_impulse_ratio, rebound_impulse_ratio),
            Law::KineticFriction { .. } => unreachable!("the random laws are planar"),
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
                assert_eq!(
                    (&g.mu, &g.mu_c, &g.e, &g.r),
                    (&e.mu, &e.mu_c, &e.e, &e.r),
                    "{impact:?}"
                );
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
            (e, g) => panic!(
                "{impact:?}: one body {:?}, two-body {:?}",
                e.map(|o| o.regime),
                g.map(|o| o.regime)
            ),
        }
    }
    assert!(
        answered > 100 * SIZE && refused > 0,
        "answered {answered}, refused {refused}"
    );
}

/// The rounding checks themselves: against `to_f64` (num-rational's correctly
/// rounded conversion) on random rationals, on exact ties, and on roots.
#[test]
fn the_rounding_checks_accept_exactly_the_correctly_rounded_double() {
    let mut rng = Rng::new(0x0123);
    let up = |a: f64| {
        if a == 0.0 {
            f64::from_bits(1)
        } else if a > 0.0 {
            f64::from_bits(a.to_bits() + 1)
        } else {
            f64::from_bits(a.to_bits() - 1)
        }
    };
    let down = |a: f64| -up(-a);
    for _ in 0..2000 {
        let x = q(rng.sign() * rng.log_uniform(-30.0, 30.0)) / q(rng.log_uniform(-30.0, 30.0));
        let a = to_f64(&x);
        assert!(is_correctly_rounded(a, &x), "{x}");
        assert!(
            !is_correctly_rounded(up(a), &x) && !is_correctly_rounded(down(a), &x),
            "{x}"
        );
        // x √y with y a non-square, and with y a square.
        let y = q(rng.log_uniform(-20.0, 20.0));
        let approx = to_f64(&(&x * sqrt_approx(&y)));
        let hits = [
            down(down(approx)),
            down(approx),
            approx,
            up(approx),
            up(up(approx)),
        ]
        .into_iter()
        .filter(|&c| is_correctly_rounded_sqrt(c, &x, &y))
        .count();
        assert_eq!(hits, 1, "{x} √{y}");
        let root = q(rng.log_uniform(-10.0, 10.0));
        let y = &root * &root;
        assert!(
            is_correctly_rounded_sqrt(to_f64(&(&x * &root)), &x, &y),
            "{x} · {root}"
        );
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
