//! One point contact in space: body A against body B or a fixed barrier,
//! with full inertia tensors, slip in any direction and an optional twist
//! about the normal (section 4 generalised).
//!
//! Each body `b` has mass `m_b`, inertia tensor `I_b` about its mass centre
//! (world axes), velocity `v_b`, angular velocity `ω_b` and `r_b = C − G_b`;
//! the normal `n` (from B into A) is not normalised. The unknowns are the
//! impulse `P` on A (`−P` on B) and the couple `κ n` about the normal
//! (`κ = M/|n|`); the velocities they change are the relative contact-point
//! velocity `u = Σ± (v_b + ω_b × r_b)` and the scaled relative spin
//! `s̃ = (ω_A − ω_B)·n = |n| s`. Then
//!
//! ```text
//! Δu = W P + w κ,   Δs̃ = wᵀ P + k κ,
//! W = Σ_b (1/m_b + [r_b]×ᵀ I_b⁻¹ [r_b]×),  w = Σ_b (I_b⁻¹ n) × r_b,  k = Σ_b nᵀ I_b⁻¹ n,
//! ```
//!
//! the symmetric positive definite 4×4 contact matrix `𝒲̃` (`J = |n|²/k`).
//! With `ν = |n|²`, the normal part of a vector `x` is `(x·n)/ν n`, so every
//! law but sliding is rational in the inputs:
//!
//! - kept tangential branch (stick, or `e_t` restitution): `Δu = q n/ν − (1 + e_t) u_t`,
//!   `q = −(1 + e) u·n` (Eqs 1, 20);
//! - sliding (and a prescribed ratio `μ`): `P = p̃ (n + c √(ν/|w_s|²) w_s)` with
//!   `c = f` (or `μ`), `w_s = −u_t` (or the sticking impulse's `P_t` when
//!   `u_t = 0`): one square root per answer, held exactly by [`crate::arith::Surd`];
//! - twist restitution: `Δs̃ = −(1 + e_z) s̃` (Eq 28); twist sliding:
//!   `κ = −e_z s̃/k + τ μ_z ρ_p (P·n)/ν` (Eqs 29–30 divided by `|n|`), `τ = −sgn s̃`
//!   (or the sign of the restitution branch's couple when `s̃ = 0`).
//!
//! When both laws have two branches, the answer is the one combination in
//! which each kept branch holds its cap and each sliding branch is taken only
//! where its kept branch (with the same partner) fails; none or several:
//! refused as not unique (conventions, rules 1–8).

use std::cmp::Ordering;

use super::{Exact, Fail, abs, half, out, out_times_sqrt, sign};
use crate::arith::{Field, Radical};
use crate::error::{ImpactError, Input, Output};
use crate::input::{Law, RigidBody, SpatialImpact, Twist};
use crate::outcome::{
    Outputs, PlanarEnergy, Regime, SPATIAL_BODY_OUTPUTS, SpatialBodyOutcome, SpatialContactVelocities,
    SpatialContactVelocity, SpatialImpulse, SpatialOutcome, TorsionalRegime,
};

type V3<N> = [N; 3];

#[inline(always)]
fn vector<N: Field>(x: [f64; 3]) -> V3<N> {
    [N::of(x[0]), N::of(x[1]), N::of(x[2])]
}

#[inline(always)]
fn dot<N: Field>(a: &V3<N>, b: &V3<N>) -> N {
    a[0].mul_add(&b[0], &a[1].mul_add(&b[1], &a[2].mul(&b[2])))
}

#[inline(always)]
fn cross<N: Field>(a: &V3<N>, b: &V3<N>) -> V3<N> {
    [
        a[1].mul_add(&b[2], &a[2].mul(&b[1]).neg()),
        a[2].mul_add(&b[0], &a[0].mul(&b[2]).neg()),
        a[0].mul_add(&b[1], &a[1].mul(&b[0]).neg()),
    ]
}

#[inline(always)]
fn map<N: Field>(a: &V3<N>, f: impl Fn(&N) -> N) -> V3<N> {
    [f(&a[0]), f(&a[1]), f(&a[2])]
}

#[inline(always)]
fn zip<N: Field>(a: &V3<N>, b: &V3<N>, f: impl Fn(&N, &N) -> N) -> V3<N> {
    [f(&a[0], &b[0]), f(&a[1], &b[1]), f(&a[2], &b[2])]
}

/// `k a + b`.
#[inline(always)]
fn axpy<N: Field>(k: &N, a: &V3<N>, b: &V3<N>) -> V3<N> {
    zip(a, b, |x, y| k.mul_add(x, y))
}

/// A symmetric 3×3 matrix as `[xx, yy, zz, xy, xz, yz]`.
type Sym<N> = [N; 6];

#[inline(always)]
fn sym_mul<N: Field>(m: &Sym<N>, x: &V3<N>) -> V3<N> {
    let [xx, yy, zz, xy, xz, yz] = m;
    [
        xx.mul_add(&x[0], &xy.mul_add(&x[1], &xz.mul(&x[2]))),
        xy.mul_add(&x[0], &yy.mul_add(&x[1], &yz.mul(&x[2]))),
        xz.mul_add(&x[0], &yz.mul_add(&x[1], &zz.mul(&x[2]))),
    ]
}

/// The adjugate and the determinant of a symmetric matrix.
fn adjugate<N: Field>(m: &Sym<N>) -> (Sym<N>, N) {
    let [a, b, c, d, e, f] = m;
    let adj = [
        b.mul_add(c, &f.mul(f).neg()),
        a.mul_add(c, &e.mul(e).neg()),
        a.mul_add(b, &d.mul(d).neg()),
        e.mul_add(f, &d.mul(c).neg()),
        d.mul_add(f, &b.mul(e).neg()),
        d.mul_add(e, &a.mul(f).neg()),
    ];
    let det = a.mul_add(&adj[0], &d.mul_add(&adj[3], &e.mul(&adj[4])));
    (adj, det)
}

/// The leading principal minors `I_xx`, `I_xx I_yy − I_xy²` and `det I` of a
/// tensor `[xx, yy, zz, xy, xz, yz]`: it is positive definite when all three
/// are positive (Sylvester's criterion).
pub(crate) fn leading_minors<N: Field>(tensor: &[f64; 6]) -> [N; 3] {
    let m = tensor.map(N::of);
    let second = m[0].mul_add(&m[1], &m[3].mul(&m[3]).neg());
    let (_, det) = adjugate(&m);
    [m[0].clone(), second, det]
}

/// One body in the field.
#[derive(Clone)]
struct Body<N> {
    m: N,
    inv_m: N,
    tensor: Sym<N>,
    inv_i: Sym<N>,
    r: V3<N>,
    v: V3<N>,
    w: V3<N>,
}

impl<N: Field> Body<N> {
    fn new(body: &RigidBody, c: &V3<N>) -> Self {
        let m = N::of(body.mass);
        let tensor = body.inertia.map(N::of);
        let (adj, det) = adjugate(&tensor);
        let inv_det = N::of(1.0).div(&det);
        let position = vector(body.position);
        Body {
            inv_m: N::of(1.0).div(&m),
            inv_i: adj.map(|x| x.mul(&inv_det)),
            r: zip(c, &position, |c, g| c.sub(g)),
            v: vector(body.velocity),
            w: vector(body.angular_velocity),
            m,
            tensor,
        }
    }

    /// The contact-point velocity `v + ω × r`.
    fn contact_velocity(&self) -> V3<N> {
        point_velocity(&self.v, &self.w, &self.r)
    }
}

/// `v + ω × r`.
#[inline(always)]
fn point_velocity<N: Field>(v: &V3<N>, w: &V3<N>, r: &V3<N>) -> V3<N> {
    zip(v, &cross(w, r), |a, b| a.add(b))
}

/// The relative normal contact velocity `u·n` (unnormalised), by the same
/// operations as the scene: what validation decides the approach on.
pub(crate) fn approach<N: Field>(impact: &SpatialImpact) -> N {
    let c: V3<N> = vector(impact.contact.point);
    let n = vector(impact.contact.normal);
    // Only the velocities: no tensor inverse, which the decision does not need.
    let velocity = |b: &RigidBody| {
        let r = zip(&c, &vector(b.position), |c, g| c.sub(g));
        point_velocity(&vector(b.velocity), &vector(b.angular_velocity), &r)
    };
    let mut u = velocity(&impact.a);
    if let Some(b) = &impact.b {
        u = zip(&u, &velocity(b), |x, y| x.sub(y));
    }
    dot(&u, &n)
}

/// A branch of the tangential law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tangential {
    /// The target `U_t = −e_t u_t` (stick for `e_t = 0`).
    Kept,
    /// `|P_t| = c P_n` opposing the slip (frictionless: `c = 0`).
    Sliding,
}

/// A branch of the twist law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Spin {
    /// No twist law: no couple.
    Off,
    /// `S = −e_z s` (Eq 28).
    Restitution,
    /// `M = −e_z J s − sgn(s) μ_z ρ_p P_n` (Eq 29–30).
    Sliding,
}

/// An impulse and couple `(P, κ)`.
#[derive(Clone)]
struct Solution<N> {
    p: V3<N>,
    kappa: N,
    /// `P·n`.
    pn: N,
    /// `P_t = P − (P·n)/ν n`.
    pt: V3<N>,
}

/// The law's reading: branches, coefficients and the pointers of refusals.
struct Reading {
    e: f64,
    /// `e_t` of the kept branch (0: stick), when the law has one.
    kept: Option<f64>,
    /// `c` of the sliding branch (`f`, `μ` or 0).
    c: f64,
    /// The cap `f` of a two-branch law.
    cap: f64,
    regimes: (Regime, Regime),
    pointers: (Input, Input),
    /// A prescribed ratio: a zero direction is refused, not dropped.
    prescribed: bool,
}

impl Reading {
    fn of(law: &Law, twist: bool) -> Reading {
        let single = |e, c, regime, pointer| Reading {
            e,
            kept: None,
            c,
            cap: 0.0,
            regimes: (regime, regime),
            pointers: (pointer, pointer),
            prescribed: regime == Regime::Prescribed,
        };
        match *law {
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => single(
                restitution,
                impulse_ratio,
                Regime::Prescribed,
                Input::ImpulseRatio,
            ),
            Law::Friction {
                restitution,
                friction,
            } => Reading {
                e: restitution,
                kept: Some(0.0),
                c: friction,
                cap: friction,
                regimes: (Regime::Sticking, Regime::Sliding),
                pointers: (Input::Friction, Input::Friction),
                prescribed: false,
            },
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => Reading {
                e: restitution,
                kept: Some(tangential_restitution),
                c: friction,
                cap: friction,
                regimes: (Regime::Restitution, Regime::Sliding),
                pointers: (Input::TangentialRestitution, Input::Friction),
                prescribed: false,
            },
            // The kinetic law is planar; validation refuses it in space.
            Law::Frictionless { restitution }
            | Law::KineticRestitution {
                value: restitution, ..
            } => {
                let pointer = if twist { Input::Torsion } else { Input::Restitution };
                single(restitution, 0.0, Regime::Frictionless, pointer)
            }
        }
    }
}

/// A validated contact in the field.
struct Scene<'a, N> {
    n: V3<N>,
    nu: N,
    bodies: Vec<Body<N>>,
    /// `u` (relative contact-point velocity), `u·n`, `u_t`, `s̃`.
    u: V3<N>,
    un: N,
    ut: V3<N>,
    s: N,
    w_matrix: Sym<N>,
    adj: Sym<N>,
    det: N,
    /// `w` and `k` of the couple.
    w: V3<N>,
    k: N,
    /// `q = −(1 + e) u·n`.
    q: N,
    law: Reading,
    twist: Option<&'a Twist>,
    /// Solutions found so far, by `(branch, spin)`; the sticking one for `μ_c`.
    cache: [Option<Option<Solution<N>>>; 12],
}

/// `|x|²` of a vector `x`.
#[inline(always)]
fn norm2<N: Field>(x: &V3<N>) -> N {
    dot(x, x)
}

impl<'a, N: Radical> Scene<'a, N> {
    fn new(impact: &'a SpatialImpact) -> Self {
        let c: V3<N> = vector(impact.contact.point);
        let n = vector(impact.contact.normal);
        let nu = norm2(&n);
        let mut bodies = vec![Body::new(&impact.a, &c)];
        if let Some(b) = &impact.b {
            bodies.push(Body::new(b, &c));
        }
        let mut u = bodies[0].contact_velocity();
        let mut spin = bodies[0].w.clone();
        if let Some(b) = bodies.get(1) {
            u = zip(&u, &b.contact_velocity(), |x, y| x.sub(y));
            spin = zip(&spin, &b.w, |x, y| x.sub(y));
        }
        let un = dot(&u, &n);
        let ut = axpy(&un.div(&nu).neg(), &n, &u);
        let s = dot(&spin, &n);
        // W = Σ 1/m + Σ cᵢᵀ I⁻¹ cⱼ with cᵢ = r × eᵢ; w = Σ (I⁻¹ n) × r; k = Σ nᵀ I⁻¹ n.
        let zero = N::of(0.0);
        let mut w_matrix: Sym<N> = std::array::from_fn(|_| zero.clone());
        let mut w = [zero.clone(), zero.clone(), zero.clone()];
        let mut k = zero.clone();
        for b in &bodies {
            let [rx, ry, rz] = &b.r;
            let columns = [
                [zero.clone(), rz.clone(), ry.neg()],
                [rz.neg(), zero.clone(), rx.clone()],
                [ry.clone(), rx.neg(), zero.clone()],
            ];
            let turned = [
                sym_mul(&b.inv_i, &columns[0]),
                sym_mul(&b.inv_i, &columns[1]),
                sym_mul(&b.inv_i, &columns[2]),
            ];
            let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
            for (slot, (i, j)) in pairs.into_iter().enumerate() {
                let mut entry = dot(&columns[i], &turned[j]);
                if i == j {
                    entry = entry.add(&b.inv_m);
                }
                w_matrix[slot] = w_matrix[slot].add(&entry);
            }
            let about = sym_mul(&b.inv_i, &n);
            w = zip(&w, &cross(&about, &b.r), |x, y| x.add(y));
            k = k.add(&dot(&n, &about));
        }
        let (adj, det) = adjugate(&w_matrix);
        let law = Reading::of(&impact.law, impact.torsion.is_some());
        let q = N::of(1.0).add(&N::of(law.e)).mul(&un).neg();
        Scene {
            n,
            nu,
            bodies,
            u,
            un,
            ut,
            s,
            w_matrix,
            adj,
            det,
            w,
            k,
            q,
            law,
            twist: impact.torsion.as_ref(),
            cache: Default::default(),
        }
    }

    /// `(P, κ)` with its `P·n` and `P_t`.
    fn solution(&self, p: V3<N>, kappa: N) -> Solution<N> {
        let pn = dot(&p, &self.n);
        let pt = axpy(&pn.div(&self.nu).neg(), &self.n, &p);
        Solution { p, kappa, pn, pt }
    }

    /// The cache slot of `(t, z)`; the kept branch's sticking (`e_t = 0`)
    /// and restitution targets apart.
    fn slot(t: Tangential, z: Spin, et: f64) -> usize {
        let stick = t == Tangential::Kept && et == 0.0;
        (t as usize) * 6 + (z as usize) * 2 + stick as usize
    }

    /// The solution of branches `(t, z)` (`None`: its system is singular),
    /// the kept branch targeting `U_t = −e_t u_t`.
    fn solve(&mut self, t: Tangential, z: Spin, et: f64) -> Exact<N, Option<Solution<N>>> {
        let slot = Self::slot(t, z, et);
        if let Some(found) = &self.cache[slot] {
            return Ok(found.clone());
        }
        let found = self.compute(t, z, et)?;
        self.cache[slot] = Some(found.clone());
        Ok(found)
    }

    /// `κ = c₀ + c₁ (P·n)` of the sliding twist: `c₀ = −e_z s̃/k`,
    /// `c₁ = τ μ_z ρ_p/ν`, `τ = −sgn s̃` or, without spin, the sign of the
    /// restitution branch's couple with the same tangential branch.
    fn twist_terms(&mut self, t: Tangential, et: f64) -> Exact<N, (N, N)> {
        let Some(twist) = self.twist else {
            return Ok((N::of(0.0), N::of(0.0)));
        };
        let c0 = N::of(twist.restitution).mul(&self.s).div(&self.k).neg();
        let tau = match sign(&self.s)? {
            Ordering::Greater => -1.0,
            Ordering::Less => 1.0,
            Ordering::Equal => match self.solve(t, Spin::Restitution, et)? {
                Some(rest) => match sign(&rest.kappa)? {
                    Ordering::Greater => 1.0,
                    Ordering::Less => -1.0,
                    Ordering::Equal => 0.0,
                },
                None => 0.0,
            },
        };
        let c1 = N::of(tau * twist.friction)
            .mul(&N::of(twist.pitch_radius))
            .div(&self.nu);
        Ok((c0, c1))
    }

    fn compute(&mut self, t: Tangential, z: Spin, et: f64) -> Exact<N, Option<Solution<N>>> {
        let ds = match self.twist {
            Some(tw) => N::of(1.0).add(&N::of(tw.restitution)).mul(&self.s).neg(),
            None => N::of(0.0),
        };
        match t {
            Tangential::Kept => {
                let target = axpy(
                    &self.q.div(&self.nu),
                    &self.n,
                    &map(&self.ut, |x| N::of(1.0).add(&N::of(et)).mul(x).neg()),
                );
                let a = sym_mul(&self.adj, &target);
                match z {
                    Spin::Off => Ok(Some(self.solution(map(&a, |x| x.div(&self.det)), N::of(0.0)))),
                    Spin::Restitution => {
                        let b = sym_mul(&self.adj, &self.w);
                        let schur = self.k.mul_add(&self.det, &dot(&self.w, &b).neg());
                        let kappa = ds.mul_add(&self.det, &dot(&self.w, &a).neg()).div(&schur);
                        let p = map(&axpy(&kappa.neg(), &b, &a), |x| x.div(&self.det));
                        Ok(Some(self.solution(p, kappa)))
                    }
                    Spin::Sliding => {
                        let (c0, c1) = self.twist_terms(t, et)?;
                        let rhs = axpy(&c0.neg(), &self.w, &target);
                        let a = sym_mul(&self.adj, &rhs);
                        let b = sym_mul(&self.adj, &self.w);
                        let den = c1.mul_add(&dot(&self.n, &b), &self.det);
                        if sign(&den)? == Ordering::Equal {
                            return Ok(None);
                        }
                        let na = dot(&self.n, &a);
                        let scale = self.det.mul(&den);
                        let p = zip(&a, &b, |ai, bi| {
                            ai.mul(&den).sub(&c1.mul(bi).mul(&na)).div(&scale)
                        });
                        let kappa = c1.mul_add(&dot(&p, &self.n), &c0);
                        Ok(Some(self.solution(p, kappa)))
                    }
                }
            }
            Tangential::Sliding => {
                let Some((d, along_normal)) = self.direction(z)? else {
                    return Ok(None);
                };
                let wd = sym_mul(&self.w_matrix, &d);
                let a11 = dot(&self.n, &wd);
                let (p_scale, kappa) = match z {
                    Spin::Off => {
                        if sign(&a11)? == Ordering::Equal {
                            return Ok(None);
                        }
                        (self.q.div(&a11), N::of(0.0))
                    }
                    Spin::Restitution => {
                        let a12 = dot(&self.n, &self.w);
                        let a21 = dot(&self.w, &d);
                        let det2 = a11.mul_add(&self.k, &a12.mul(&a21).neg());
                        if sign(&det2)? == Ordering::Equal {
                            return Ok(None);
                        }
                        (
                            self.q.mul_add(&self.k, &a12.mul(&ds).neg()).div(&det2),
                            a11.mul_add(&ds, &a21.mul(&self.q).neg()).div(&det2),
                        )
                    }
                    Spin::Sliding => {
                        let (c0, c1) = self.twist_terms(t, et)?;
                        let nw = dot(&self.n, &self.w);
                        let den = c1.mul(&self.nu).mul_add(&nw, &a11);
                        if sign(&den)? == Ordering::Equal {
                            return Ok(None);
                        }
                        let p_scale = nw.neg().mul_add(&c0, &self.q).div(&den);
                        let kappa = c1.mul(&self.nu).mul_add(&p_scale, &c0);
                        (p_scale, kappa)
                    }
                };
                let mut found = self.solution(map(&d, |x| p_scale.mul(x)), kappa);
                if along_normal {
                    // P ∥ n: no tangential part, exactly (not a cancellation
                    // the bounded stages could not certify as zero).
                    found.pt = [N::of(0.0), N::of(0.0), N::of(0.0)];
                }
                Ok(Some(found))
            }
        }
    }

    /// The sliding impulse's direction `n + c √(ν/|w_s|²) w_s`, and whether
    /// it is `n` itself; `None` when the sticking system it needs is singular.
    fn direction(&mut self, z: Spin) -> Exact<N, Option<(V3<N>, bool)>> {
        if self.law.c == 0.0 {
            return Ok(Some((self.n.clone(), true)));
        }
        let slip = norm2(&self.ut);
        let (ws, size) = if sign(&slip)? == Ordering::Greater {
            (map(&self.ut, |x| x.neg()), slip)
        } else {
            let Some(stick) = self.solve(Tangential::Kept, z, 0.0)? else {
                return Ok(None);
            };
            let size = norm2(&stick.pt);
            if sign(&size)? == Ordering::Equal {
                if self.law.prescribed {
                    return Err(Fail::Refused(ImpactError::NoSlipDirection {
                        input: Input::ImpulseRatio,
                    }));
                }
                return Ok(Some((self.n.clone(), true)));
            }
            (stick.pt, size)
        };
        let root = self.nu.div(&size).sqrt().map_err(Fail::Undecided)?;
        let scale = N::of(self.law.c).mul(&root);
        Ok(Some((axpy(&scale, &ws, &self.n), false)))
    }

    /// Whether the kept tangential branch holds: `P·n ≠ 0`, `ν |P_t|² ≤ f² (P·n)²`.
    fn tangential_holds(&self, s: &Option<Solution<N>>) -> Exact<N, bool> {
        let Some(s) = s else { return Ok(false) };
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(false);
        }
        let f = N::of(self.law.cap);
        let cap = f.mul(&s.pn);
        let room = cap.mul(&cap).sub(&self.nu.mul(&norm2(&s.pt)));
        Ok(sign(&room)? != Ordering::Less)
    }

    /// Whether the twist's restitution branch holds: `P·n ≠ 0`,
    /// `(κ + e_z s̃/k)² ≤ (μ_z ρ_p P·n/ν)²`.
    fn spin_holds(&self, s: &Option<Solution<N>>) -> Exact<N, bool> {
        let (Some(s), Some(twist)) = (s, self.twist) else {
            return Ok(false);
        };
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(false);
        }
        let beyond = N::of(twist.restitution).mul(&self.s).div(&self.k).add(&s.kappa);
        let cap = N::of(twist.friction)
            .mul(&N::of(twist.pitch_radius))
            .mul(&s.pn)
            .div(&self.nu);
        Ok(sign(&cap.mul(&cap).sub(&beyond.mul(&beyond)))? != Ordering::Less)
    }

    /// The one valid combination of branches, with its solution.
    fn choose(&mut self) -> Exact<N, (Tangential, Spin, Option<Solution<N>>)> {
        let et = self.law.kept.unwrap_or(0.0);
        let tangentials: &[Tangential] = if self.law.kept.is_some() {
            &[Tangential::Kept, Tangential::Sliding]
        } else {
            &[Tangential::Sliding]
        };
        let spins: &[Spin] = if self.twist.is_some() {
            &[Spin::Restitution, Spin::Sliding]
        } else {
            &[Spin::Off]
        };
        // The count of valid combinations and the last one (no allocation per solve).
        let (mut count, mut chosen) = (0, (Tangential::Sliding, Spin::Off));
        for &t in tangentials {
            for &z in spins {
                let t_ok = match t {
                    Tangential::Kept => {
                        let s = self.solve(t, z, et)?;
                        self.tangential_holds(&s)?
                    }
                    Tangential::Sliding if self.law.kept.is_some() => {
                        let s = self.solve(Tangential::Kept, z, et)?;
                        !self.tangential_holds(&s)?
                    }
                    Tangential::Sliding => true,
                };
                if !t_ok {
                    continue;
                }
                let z_ok = match z {
                    Spin::Off => true,
                    Spin::Restitution => {
                        let s = self.solve(t, z, et)?;
                        self.spin_holds(&s)?
                    }
                    Spin::Sliding => {
                        let s = self.solve(t, Spin::Restitution, et)?;
                        !self.spin_holds(&s)?
                    }
                };
                if z_ok {
                    count += 1;
                    chosen = (t, z);
                }
            }
        }
        if count != 1 {
            return Err(Fail::Refused(ImpactError::NotUnique {
                input: Input::Torsion,
                combinations: count,
            }));
        }
        let (t, z) = chosen;
        Ok((t, z, self.solve(t, z, et)?))
    }

    /// `|P_t|/|P_n| = √(ν |P_t|²) / |P·n|` of a solution, a magnitude
    /// (`None` when `P·n = 0`).
    fn ratio(&self, s: &Solution<N>, output: Output) -> Exact<N, Option<f64>> {
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(None);
        }
        let size = self.nu.mul(&norm2(&s.pt));
        Ok(Some(out_times_sqrt(
            output,
            &N::of(1.0).div(&abs(&s.pn)?),
            &size,
        )?))
    }

    /// `x/|n|` correctly rounded.
    fn along(&self, output: Output, x: &N) -> Exact<N, f64> {
        out_times_sqrt(output, &x.div(&self.nu), &self.nu)
    }

    fn vector_out(outputs: [Output; 3], x: &V3<N>) -> Exact<N, [f64; 3]> {
        Ok([
            out(outputs[0], &x[0])?,
            out(outputs[1], &x[1])?,
            out(outputs[2], &x[2])?,
        ])
    }

    /// `T_M = ½ (u, s̃)ᵀ 𝒲̃⁻¹ (u, s̃)` (with twist) or `½ uᵀ W⁻¹ u`, by the
    /// adjugate and the Schur complement of `W`.
    fn max_loss(&self) -> N {
        let a = sym_mul(&self.adj, &self.u);
        let mut twice = dot(&self.u, &a).div(&self.det);
        if self.twist.is_some() {
            let b = sym_mul(&self.adj, &self.w);
            let schur = self.k.mul_add(&self.det, &dot(&self.w, &b).neg());
            let lever = self.s.mul_add(&self.det, &dot(&self.w, &a).neg());
            twice = twice.add(&lever.mul(&lever).div(&self.det.mul(&schur)));
        }
        half::<N>().mul(&twice)
    }

    fn initial_energy(&self) -> N {
        let mut total = N::of(0.0);
        for b in &self.bodies {
            let linear = b.m.mul(&norm2(&b.v));
            let angular = dot(&b.w, &sym_mul(&b.tensor, &b.w));
            total = total.add(&half::<N>().mul(&linear.add(&angular)));
        }
        total
    }
}

fn three(o: &[Output], from: usize) -> [Output; 3] {
    [o[from], o[from + 1], o[from + 2]]
}

/// A validated spatial contact in the field `N`: refused unless it
/// approaches (`u·n < 0`, decided exactly in the exact fields).
#[inline(always)]
pub(crate) fn spatial<N: Radical>(
    impact: &SpatialImpact,
    outputs: Outputs,
    outcome: &mut SpatialOutcome,
) -> Exact<N, ()> {
    let mut sc = Scene::<N>::new(impact);
    if sign(&sc.un)? != Ordering::Less {
        return Err(ImpactError::NotApproaching {
            input: Input::VelocityA,
            normal_contact_velocity: sc.un.approx() / sc.nu.approx().sqrt(),
        }
        .into());
    }
    let (t, z, found) = sc.choose()?;
    let (regime, pointer) = match t {
        Tangential::Kept => (sc.law.regimes.0, sc.law.pointers.0),
        Tangential::Sliding => (sc.law.regimes.1, sc.law.pointers.1),
    };
    let no_impulse = || Fail::Refused(ImpactError::NoImpulse { input: pointer });
    let s = found.ok_or_else(no_impulse)?;
    if sign(&s.pn)? != Ordering::Greater {
        return Err(no_impulse());
    }
    let one = N::of(1.0);
    let e = N::of(sc.law.e);
    // Δu = W P + w κ, Δs̃ = wᵀ P + k κ.
    let du = axpy(&s.kappa, &sc.w, &sym_mul(&sc.w_matrix, &s.p));
    let dspin = sc.k.mul_add(&s.kappa, &dot(&sc.w, &s.p));
    let (final_ut, slip_sum) = match t {
        Tangential::Kept => {
            let et = N::of(sc.law.kept.unwrap_or(0.0));
            (
                map(&sc.ut, |x| et.mul(x).neg()),
                map(&sc.ut, |x| one.sub(&et).mul(x)),
            )
        }
        Tangential::Sliding => {
            let dun = dot(&du, &sc.n).div(&sc.nu);
            let dut = axpy(&dun.neg(), &sc.n, &du);
            (
                zip(&sc.ut, &dut, |x, y| x.add(y)),
                zip(&sc.ut, &dut, |x, y| N::of(2.0).mul_add(x, y)),
            )
        }
    };
    let (final_spin, spin_sum) = match (z, sc.twist) {
        (Spin::Restitution, Some(tw)) => {
            let ez = N::of(tw.restitution);
            (ez.mul(&sc.s).neg(), one.sub(&ez).mul(&sc.s))
        }
        _ => (sc.s.add(&dspin), N::of(2.0).mul_add(&sc.s, &dspin)),
    };
    // work = P·(u + U) + κ (s̃ + S̃), with u + U = (1 − e)(u·n) n/ν + (u_t + U_t).
    let normal_work = one.sub(&e).mul(&sc.un).mul(&s.pn).div(&sc.nu);
    let work = s
        .kappa
        .mul_add(&spin_sum, &dot(&s.p, &slip_sum).add(&normal_work));
    if sign(&work)? == Ordering::Greater {
        return Err(ImpactError::EnergyCreated {
            input: pointer,
            energy_loss: -0.5 * work.approx(),
        }
        .into());
    }
    let mut bodies = [SpatialBodyOutcome::default(); 2];
    let p2 = norm2(&s.p);
    for (index, b) in sc.bodies.iter().enumerate() {
        let names = &SPATIAL_BODY_OUTPUTS[index];
        let signed = |x: N| if index == 0 { x } else { x.neg() };
        let dv = map(&s.p, |x| signed(x.mul(&b.inv_m)));
        let moment = axpy(&s.kappa, &sc.n, &cross(&b.r, &s.p));
        let dw = map(&sym_mul(&b.inv_i, &moment), |x| signed(x.clone()));
        bodies[index] = SpatialBodyOutcome {
            velocity: Scene::<N>::vector_out(three(names, 0), &zip(&b.v, &dv, |x, y| x.add(y)))?,
            angular_velocity: Scene::<N>::vector_out(three(names, 3), &zip(&b.w, &dw, |x, y| x.add(y)))?,
            velocity_change: Scene::<N>::vector_out(three(names, 6), &dv)?,
            delta_v: out_times_sqrt(names[9], &b.inv_m, &p2)?,
            angular_velocity_change: Scene::<N>::vector_out(three(names, 10), &dw)?,
        };
    }
    let contact_velocity = SpatialContactVelocities {
        initial: SpatialContactVelocity {
            normal: sc.along(Output::InitialNormalContactVelocity, &sc.un)?,
            tangential: Scene::<N>::vector_out(
                [
                    Output::InitialTangentialContactVelocityX,
                    Output::InitialTangentialContactVelocityY,
                    Output::InitialTangentialContactVelocityZ,
                ],
                &sc.ut,
            )?,
            spin: sc.along(Output::InitialContactSpin, &sc.s)?,
        },
        r#final: SpatialContactVelocity {
            normal: sc.along(Output::FinalNormalContactVelocity, &e.mul(&sc.un).neg())?,
            tangential: Scene::<N>::vector_out(
                [
                    Output::FinalTangentialContactVelocityX,
                    Output::FinalTangentialContactVelocityY,
                    Output::FinalTangentialContactVelocityZ,
                ],
                &final_ut,
            )?,
            spin: sc.along(Output::FinalContactSpin, &final_spin)?,
        },
    };
    let impulse = SpatialImpulse {
        normal: sc.along(Output::NormalImpulse, &s.pn)?,
        tangential: Scene::<N>::vector_out(
            [
                Output::TangentialImpulseX,
                Output::TangentialImpulseY,
                Output::TangentialImpulseZ,
            ],
            &s.pt,
        )?,
        torsional: out_times_sqrt(Output::TorsionalImpulse, &s.kappa, &sc.nu)?,
        x: out(Output::ImpulseX, &s.p[0])?,
        y: out(Output::ImpulseY, &s.p[1])?,
        z: out(Output::ImpulseZ, &s.p[2])?,
    };
    let impulse_ratio = match t {
        Tangential::Kept => sc.ratio(&s, Output::ImpulseRatio)?.unwrap_or(0.0),
        // |P_t| = c P_n exactly, unless there is no direction to slide in.
        Tangential::Sliding if sign(&norm2(&s.pt))? == Ordering::Equal => 0.0,
        Tangential::Sliding => out(Output::ImpulseRatio, &N::of(sc.law.c))?,
    };
    let critical_impulse_ratio = if outputs.critical_impulse_ratio || regime == Regime::Sticking {
        let stick = sc.solve(Tangential::Kept, z, 0.0)?;
        match stick {
            Some(stick) => sc.ratio(&stick, Output::CriticalImpulseRatio)?,
            None => None,
        }
    } else {
        None
    };
    let energy = if outputs.energy {
        let initial = sc.initial_energy();
        let loss = half::<N>().mul(&work).neg();
        let max_loss = sc.max_loss();
        Some(PlanarEnergy {
            initial: out(Output::InitialEnergy, &initial)?,
            r#final: out(Output::FinalEnergy, &initial.sub(&loss))?.max(0.0),
            loss: out(Output::EnergyLoss, &loss)?,
            max_loss: out(Output::MaxEnergyLoss, &max_loss)?,
            normalized_loss: out(Output::NormalizedEnergyLoss, &loss.div(&max_loss))?.min(1.0),
        })
    } else {
        None
    };
    *outcome = SpatialOutcome {
        body_count: sc.bodies.len(),
        bodies,
        contact_velocity,
        impulse,
        impulse_ratio,
        critical_impulse_ratio,
        restitution: out(Output::Restitution, &e)?,
        regime,
        torsional_regime: match z {
            Spin::Off => None,
            Spin::Restitution => Some(TorsionalRegime::Restitution),
            Spin::Sliding => Some(TorsionalRegime::Sliding),
        },
        energy,
    };
    Ok(())
}
