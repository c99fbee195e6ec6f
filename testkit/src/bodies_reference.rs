//! An independent exact reference of the planar contact between two laminae
//! (or one lamina and a fixed barrier) in world axes, in rational arithmetic.
//!
//! Derived from the momentum equations of `conventions.md` alone, sharing no
//! code or formulas with the solver. The square root of `|n|` is avoided by
//! working in the unnormalised contact frame `N = [n t]`, `t = ẑ × n`
//! (`|t| = |n|`):
//!
//! - the scaled contact velocity `ũ = Nᵀ u = |n| (u_n, u_t)`;
//! - the impulse `P = q_n n + q_t t`, so `P_n = q_n |n|`, `P_t = q_t |n|`,
//!   `P_t / P_n = q_t / q_n` and `|P_t| ≤ f P_n ⟺ |q_t| ≤ f q_n` (`q_n > 0`);
//! - `Δũ = W̃ q` with `W̃ = Nᵀ W N = Σ_b (|n|²/m_b) 1 + a_b a_bᵀ / I_b`,
//!   `a_b = Nᵀ (ẑ × r_b)`, all rational.
//!
//! Every decision is therefore exact, and every output is either rational or
//! `x √y` with rational `x, y` (the components along `n̂, t̂` and `|ΔV|`).

use super::reference::{Q, q};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use restitution::{BodiesImpact, Lamina, Law};
use std::cmp::Ordering;

fn half() -> Q {
    Q::new(1.into(), 2.into())
}

fn dot(a: &[Q; 2], b: &[Q; 2]) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1]
}

/// `ẑ × r = (−r_y, r_x)`.
fn perp(r: &[Q; 2]) -> [Q; 2] {
    [-r[1].clone(), r[0].clone()]
}

/// One lamina in exact arithmetic, its lever `r = C − G`.
#[derive(Clone, Debug)]
pub struct Body {
    pub m: Q,
    pub i: Q,
    pub r: [Q; 2],
    pub v: [Q; 2],
    pub w: Q,
}

impl Body {
    fn new(l: &Lamina, c: &[Q; 2]) -> Body {
        Body {
            m: q(l.mass),
            i: q(l.inertia),
            r: [&c[0] - q(l.position[0]), &c[1] - q(l.position[1])],
            v: [q(l.velocity[0]), q(l.velocity[1])],
            w: q(l.angular_velocity),
        }
    }
    /// The contact point's velocity `v + ω ẑ × r`.
    pub fn point_velocity(&self, v: &[Q; 2], w: &Q) -> [Q; 2] {
        let s = perp(&self.r);
        [&v[0] + w * &s[0], &v[1] + w * &s[1]]
    }
    pub fn kinetic(&self, v: &[Q; 2], w: &Q) -> Q {
        half() * (&self.m * dot(v, v) + &self.i * w * w)
    }
}

/// A contact in exact arithmetic.
#[derive(Clone, Debug)]
pub struct Scene {
    /// A, then B when there is one.
    pub bodies: Vec<Body>,
    pub n: [Q; 2],
    pub t: [Q; 2],
    /// `|n|²`.
    pub n2: Q,
    /// `ũ = (u·n, u·t)`.
    pub u: [Q; 2],
    /// `W̃`, symmetric.
    pub w: [[Q; 2]; 2],
    /// `Σ_b |n|²/m_b`, the translational part of `W̃` (times the identity).
    pub translational: Q,
    /// `Σ_b |a_b|²/I_b = Σ_b |r_b|² |n|²/I_b`, the size of its rotational part
    /// whatever the direction of `n` (a rounded `n̂` moves the projections).
    pub rotational: Q,
}

impl Scene {
    pub fn new(impact: &BodiesImpact) -> Scene {
        let c = [q(impact.contact.point[0]), q(impact.contact.point[1])];
        let n = [q(impact.contact.normal[0]), q(impact.contact.normal[1])];
        let t = perp(&n);
        let n2 = dot(&n, &n);
        let mut bodies = vec![Body::new(&impact.a, &c)];
        if let Some(b) = &impact.b {
            bodies.push(Body::new(b, &c));
        }
        let mut u = [Q::zero(), Q::zero()];
        let mut w = [[Q::zero(), Q::zero()], [Q::zero(), Q::zero()]];
        let (mut translational, mut rotational) = (Q::zero(), Q::zero());
        for (k, b) in bodies.iter().enumerate() {
            let ub = b.point_velocity(&b.v, &b.w);
            let sign = if k == 0 { Q::one() } else { -Q::one() };
            u[0] += &sign * dot(&ub, &n);
            u[1] += &sign * dot(&ub, &t);
            let s = perp(&b.r);
            let a = [dot(&s, &n), dot(&s, &t)];
            let inv_m = &n2 / &b.m;
            w[0][0] += &inv_m + &a[0] * &a[0] / &b.i;
            w[1][1] += &inv_m + &a[1] * &a[1] / &b.i;
            let off = &a[0] * &a[1] / &b.i;
            translational += &inv_m;
            rotational += dot(&a, &a) / &b.i;
            w[0][1] += &off;
            w[1][0] += off;
        }
        Scene {
            bodies,
            n,
            t,
            n2,
            u,
            w,
            translational,
            rotational,
        }
    }

    pub fn det(&self) -> Q {
        &self.w[0][0] * &self.w[1][1] - &self.w[0][1] * &self.w[1][0]
    }

    /// `D̃(μ) = W̃_11 + μ W̃_12`, `|n|²` times the normal impulse coefficient.
    pub fn d(&self, mu: &Q) -> Q {
        &self.w[0][0] + mu * &self.w[0][1]
    }

    /// The magnitude of the terms of `D̃(μ)`.
    pub fn d_size(&self, mu: &Q) -> Q {
        &self.translational + (Q::one() + mu.abs()) * &self.rotational
    }

    /// The conditioning of the division by `D̃(μ)`: the magnitude of its terms over it.
    pub fn kappa_ratio(&self, mu: &Q) -> Q {
        self.d_size(mu) / self.d(mu)
    }

    /// The conditioning of the 2×2 solve, `(‖W̃‖ / λ_min)` bounded by
    /// `(translational + rotational)² / det W̃`.
    pub fn kappa_targets(&self) -> Q {
        let size = &self.translational + &self.rotational;
        &size * &size / self.det()
    }

    /// The impulse with ratio `μ` ending at `Ũ_n = −e ũ_n`; `None` when `D̃(μ) ≤ 0`.
    pub fn with_ratio(&self, mu: &Q, e: &Q) -> Option<[Q; 2]> {
        let d = self.d(mu);
        if !d.is_positive() {
            return None;
        }
        let qn = -((Q::one() + e) * &self.u[0]) / d;
        Some([qn.clone(), mu * qn])
    }

    /// The impulse ending at `Ũ = (−e ũ_n, −e_t ũ_t)` (Cramer's rule; `W̃` is
    /// positive definite, so it always exists).
    pub fn with_targets(&self, e: &Q, et: &Q) -> [Q; 2] {
        let b1 = -((Q::one() + e) * &self.u[0]);
        let b2 = -((Q::one() + et) * &self.u[1]);
        let det = self.det();
        assert!(det.is_positive(), "W̃ is positive definite");
        let qn = (&self.w[1][1] * &b1 - &self.w[0][1] * &b2) / &det;
        let qt = (&self.w[0][0] * &b2 - &self.w[1][0] * &b1) / &det;
        [qn, qt]
    }

    /// `P_t/P_n` of the impulse ending at `Ũ = (−e ũ_n, −e_t ũ_t)`; `None` when its `P_n = 0`.
    pub fn target_ratio(&self, e: &Q, et: &Q) -> Option<Q> {
        let [qn, qt] = self.with_targets(e, et);
        if qn.is_zero() { None } else { Some(qt / qn) }
    }

    /// `μ_c`, the ratio of the sticking impulse.
    pub fn critical(&self, e: &Q) -> Option<Q> {
        self.target_ratio(e, &Q::zero())
    }

    /// `T_M = ½ ũᵀ W̃⁻¹ ũ`.
    pub fn max_loss(&self) -> Q {
        let [u1, u2] = &self.u;
        let quad = &self.w[1][1] * u1 * u1 - Q::from_integer(2.into()) * &self.w[0][1] * u1 * u2
            + &self.w[0][0] * u2 * u2;
        half() * quad / self.det()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    NotApproaching,
    NoImpulseSolution,
    CreatesEnergy,
    /// A law the plane does not offer (the Coulomb approach phase).
    Unavailable,
}

impl Refusal {
    pub fn slug(self) -> &'static str {
        match self {
            Refusal::NotApproaching => "not-approaching",
            Refusal::NoImpulseSolution => "no-impulse-solution",
            Refusal::CreatesEnergy => "creates-energy",
            Refusal::Unavailable => "law-unavailable",
        }
    }
}

/// One body's answer.
#[derive(Clone, Debug)]
pub struct BodyAnswer {
    pub v: [Q; 2],
    pub w: Q,
    pub dv: [Q; 2],
    pub dw: Q,
    /// `|ΔV|²`.
    pub dv2: Q,
}

/// The exact answer.
#[derive(Clone, Debug)]
pub struct Answer {
    pub bodies: Vec<BodyAnswer>,
    /// `|n|²`: the components along `n̂, t̂` are `ũ/|n|` and `q |n|`.
    pub n2: Q,
    /// `ũ`, `Ũ` (scaled by `|n|`).
    pub u: [Q; 2],
    pub uf: [Q; 2],
    /// `P = q_n n + q_t t`.
    pub q: [Q; 2],
    /// `P` in world axes.
    pub p: [Q; 2],
    pub mu: Q,
    pub mu_c: Option<Q>,
    pub e: Q,
    pub r: Q,
    pub regime: &'static str,
    pub t_initial: Q,
    pub t_final: Q,
    pub t_loss: Q,
    pub t_max: Q,
    /// The conditioning of the solve that produced the answer (≥ 1).
    pub kappa: Q,
    /// The conditioning of the sticking solve behind `μ_c`.
    pub kappa_c: Q,
    /// `P_n/|n| = q_n` of the sticking impulse, the denominator of `μ_c`.
    pub qn_c: Q,
}

/// Solves `impact` exactly.
pub fn solve(impact: &BodiesImpact) -> Result<Answer, Refusal> {
    solve_scene(&Scene::new(impact), impact.law)
}

/// Solves the contact `s` under `law` exactly.
pub fn solve_scene(s: &Scene, law: Law) -> Result<Answer, Refusal> {
    if !s.u[0].is_negative() {
        return Err(Refusal::NotApproaching);
    }
    match law {
        Law::Frictionless { restitution } => {
            let e = q(restitution);
            let x = s.with_ratio(&Q::zero(), &e).ok_or(Refusal::NoImpulseSolution)?;
            let kappa = s.kappa_ratio(&Q::zero());
            finish(s, x, e.clone(), e, "frictionless", kappa)
        }
        Law::ImpulseRatio {
            restitution,
            impulse_ratio,
        } => {
            let (e, mu) = (q(restitution), q(impulse_ratio));
            let x = s.with_ratio(&mu, &e).ok_or(Refusal::NoImpulseSolution)?;
            let kappa = s.kappa_ratio(&mu);
            finish(s, x, e.clone(), e, "prescribed", kappa)
        }
        Law::Friction {
            restitution,
            friction,
        } => bilinear(s, q(restitution), q(friction), Q::zero(), "sticking"),
        Law::TangentialRestitution {
            restitution,
            friction,
            tangential_restitution,
        } => bilinear(
            s,
            q(restitution),
            q(friction),
            q(tangential_restitution),
            "restitution",
        ),
        Law::KineticRestitution {
            value,
            approach_impulse_ratio,
            rebound_impulse_ratio,
        } => {
            let (r, mu_a, mu_r) = (q(value), q(approach_impulse_ratio), q(rebound_impulse_ratio));
            // Approach: ratio μ_A until Ũ_n = 0.
            let approach = s
                .with_ratio(&mu_a, &Q::zero())
                .ok_or(Refusal::NoImpulseSolution)?;
            let d_a = s.d(&mu_a);
            let d_r = s.d(&mu_r);
            if r.is_positive() && !d_r.is_positive() {
                return Err(Refusal::NoImpulseSolution);
            }
            // Rebound: R P_n^A (n̂ + μ_R t̂).
            let qa = approach[0].clone();
            let x = [&qa * (Q::one() + &r), &qa * (&mu_a + &r * &mu_r)];
            let e = &r * &d_r / &d_a;
            let mut kappa = s.kappa_ratio(&mu_a);
            if r.is_positive() {
                kappa += s.kappa_ratio(&mu_r);
            }
            finish(s, x, e, r, "prescribed", kappa)
        }
        Law::KineticFriction { .. } => Err(Refusal::Unavailable),
    }
}

/// Whether the law's kept tangential branch sits exactly on its friction cap
/// (`|P_t| = f P_n`, `P_n ≠ 0`): a decision `fast` may take either way.
pub fn kept_on_cap(impact: &BodiesImpact) -> bool {
    let (e, f, et) = match impact.law {
        Law::Friction {
            restitution,
            friction,
        } => (restitution, friction, 0.0),
        Law::TangentialRestitution {
            restitution,
            friction,
            tangential_restitution,
        } => (restitution, friction, tangential_restitution),
        _ => return false,
    };
    let s = Scene::new(impact);
    let [qn, qt] = s.with_targets(&q(e), &q(et));
    let f = q(f);
    !qn.is_zero() && &qt * &qt == &f * &f * &qn * &qn
}

/// The bilinear law: the kept branch (target `Ũ_t = −e_t ũ_t`) when its
/// `P_n ≠ 0` and `|P_t| ≤ f |P_n|`, else sliding with `|P_t| = f P_n`.
fn bilinear(s: &Scene, e: Q, f: Q, et: Q, kept: &'static str) -> Result<Answer, Refusal> {
    let [qn, qt] = s.with_targets(&e, &et);
    if !qn.is_zero() && &qt * &qt <= &f * &f * &qn * &qn {
        if !qn.is_positive() {
            return Err(Refusal::NoImpulseSolution);
        }
        let kappa = s.kappa_targets();
        return finish(s, [qn, qt], e.clone(), e, kept, kappa);
    }
    // Sliding opposes the initial slip; with no slip, along the kept impulse's P_t/P_n.
    let direction = if !s.u[1].is_zero() {
        -s.u[1].signum()
    } else {
        (&qt * &qn).signum()
    };
    let mu = direction * f;
    let x = s.with_ratio(&mu, &e).ok_or(Refusal::NoImpulseSolution)?;
    let kappa = s.kappa_ratio(&mu);
    finish(s, x, e.clone(), e, "sliding", kappa)
}

fn finish(s: &Scene, x: [Q; 2], e: Q, r: Q, regime: &'static str, kappa: Q) -> Result<Answer, Refusal> {
    if !x[0].is_positive() {
        return Err(Refusal::NoImpulseSolution);
    }
    let p = [
        &x[0] * &s.n[0] + &x[1] * &s.t[0],
        &x[0] * &s.n[1] + &x[1] * &s.t[1],
    ];
    let mut bodies = Vec::new();
    let (mut t_initial, mut t_final) = (Q::zero(), Q::zero());
    let mut uf_world = [Q::zero(), Q::zero()];
    for (k, b) in s.bodies.iter().enumerate() {
        // +P on A, −P on B.
        let pb = if k == 0 {
            p.clone()
        } else {
            [-p[0].clone(), -p[1].clone()]
        };
        let dv = [&pb[0] / &b.m, &pb[1] / &b.m];
        let dw = (&b.r[0] * &pb[1] - &b.r[1] * &pb[0]) / &b.i;
        let v = [&b.v[0] + &dv[0], &b.v[1] + &dv[1]];
        let w = &b.w + &dw;
        t_initial += b.kinetic(&b.v, &b.w);
        t_final += b.kinetic(&v, &w);
        let ub = b.point_velocity(&v, &w);
        if k == 0 {
            uf_world = ub;
        } else {
            uf_world = [&uf_world[0] - &ub[0], &uf_world[1] - &ub[1]];
        }
        let dv2 = dot(&dv, &dv);
        bodies.push(BodyAnswer { v, w, dv, dw, dv2 });
    }
    let uf = [dot(&uf_world, &s.n), dot(&uf_world, &s.t)];
    // Self-checks: the contact-space form ΔŨ = W̃ q, and the work form of the loss.
    for ((row, after), before) in s.w.iter().zip(&uf).zip(&s.u) {
        let du = &row[0] * &x[0] + &row[1] * &x[1];
        assert_eq!(after - before, du, "ΔŨ = W̃ q");
    }
    let t_loss = &t_initial - &t_final;
    let work = -(half() * (&x[0] * (&s.u[0] + &uf[0]) + &x[1] * (&s.u[1] + &uf[1])));
    assert_eq!(t_loss, work, "T_L = −½ P·(u + U)");
    if t_loss.is_negative() {
        return Err(Refusal::CreatesEnergy);
    }
    let sticking = s.with_targets(&e, &Q::zero());
    let mu_c = if sticking[0].is_zero() {
        None
    } else {
        Some(&sticking[1] / &sticking[0])
    };
    let t_max = s.max_loss();
    assert!(t_loss <= t_max, "T_L ≤ T_M");
    Ok(Answer {
        bodies,
        n2: s.n2.clone(),
        u: s.u.clone(),
        uf,
        mu: &x[1] / &x[0],
        q: x,
        p,
        mu_c,
        e,
        r,
        regime,
        t_initial,
        t_final,
        t_loss,
        t_max,
        kappa: kappa.max(Q::one()),
        kappa_c: s.kappa_targets().max(Q::one()),
        qn_c: sticking[0].clone(),
    })
}

/// `x √y` compared with `m`, exactly.
fn cmp_sqrt(x: &Q, y: &Q, m: &Q) -> Ordering {
    let sv = if x.is_zero() || y.is_zero() {
        0
    } else if x.is_positive() {
        1
    } else {
        -1
    };
    let sm = if m.is_zero() {
        0
    } else if m.is_positive() {
        1
    } else {
        -1
    };
    if sv != sm || sv == 0 {
        return sv.cmp(&sm);
    }
    // x² y vs m², in integers (denominators are positive): no gcd.
    let lhs = x.numer() * x.numer() * y.numer() * m.denom() * m.denom();
    let rhs = m.numer() * m.numer() * x.denom() * x.denom() * y.denom();
    if sv > 0 { lhs.cmp(&rhs) } else { rhs.cmp(&lhs) }
}

/// The next double toward +∞ (−0 and +0 alike go to the smallest subnormal).
fn next_up(a: f64) -> f64 {
    if a == 0.0 {
        f64::from_bits(1)
    } else if a > 0.0 {
        f64::from_bits(a.to_bits() + 1)
    } else {
        f64::from_bits(a.to_bits() - 1)
    }
}

fn next_down(a: f64) -> f64 {
    -next_up(-a)
}

/// Whether `a` is `x √y` (`y ≥ 0`) correctly rounded to nearest, ties to even:
/// the exact value lies between the midpoints to `a`'s neighbours (a midpoint
/// itself only when `a` is even). An exact zero must be `+0.0`; a nonzero value
/// that rounds to zero must be a zero of its own sign.
pub fn is_correctly_rounded_sqrt(a: f64, x: &Q, y: &Q) -> bool {
    assert!(!y.is_negative(), "√ of a negative");
    if !a.is_finite() {
        return false;
    }
    if x.is_zero() || y.is_zero() {
        return a == 0.0 && a.is_sign_positive();
    }
    let even = a.to_bits() & 1 == 0;
    let two = Q::from_integer(2.into());
    let (below, above) = if a == 0.0 {
        let tiny = q(f64::from_bits(1)) / &two;
        if a.is_sign_positive() {
            (Q::zero(), tiny)
        } else {
            (-tiny, Q::zero())
        }
    } else {
        let qa = q(a);
        let up = next_up(a);
        let down = next_down(a);
        // Beyond ±MAX the virtual neighbour is one ulp away, as below it.
        let up = if up.is_finite() {
            q(up)
        } else {
            &qa + (&qa - q(down))
        };
        let down = if down.is_finite() {
            q(down)
        } else {
            &qa - (up.clone() - &qa)
        };
        ((&qa + down) / &two, (&qa + up) / &two)
    };
    if a == 0.0 {
        // Strictly inside the zero of a's sign (the value is nonzero).
        let lower_ok = if a.is_sign_positive() {
            cmp_sqrt(x, y, &below) == Ordering::Greater
        } else {
            cmp_sqrt(x, y, &below) != Ordering::Less
        };
        let upper_ok = if a.is_sign_positive() {
            cmp_sqrt(x, y, &above) != Ordering::Greater
        } else {
            cmp_sqrt(x, y, &above) == Ordering::Less
        };
        return lower_ok && upper_ok;
    }
    let lower_ok = match cmp_sqrt(x, y, &below) {
        Ordering::Greater => true,
        Ordering::Equal => even,
        Ordering::Less => false,
    };
    let upper_ok = match cmp_sqrt(x, y, &above) {
        Ordering::Less => true,
        Ordering::Equal => even,
        Ordering::Greater => false,
    };
    lower_ok && upper_ok
}

/// Whether `a` is the correctly rounded value of the rational `x` (`+0.0` for 0).
pub fn is_correctly_rounded(a: f64, x: &Q) -> bool {
    is_correctly_rounded_sqrt(a, x, &Q::one())
}

/// `√y` to about 2⁻¹²⁰ relative (`y ≥ 0`), for error measurements.
pub fn sqrt_approx(y: &Q) -> Q {
    if y.is_zero() {
        return Q::zero();
    }
    let bits = 120usize;
    let num = y.numer() * y.denom() * (BigInt::one() << (2 * bits));
    let den = y.denom() * (BigInt::one() << bits);
    Q::new(num.sqrt(), den)
}
