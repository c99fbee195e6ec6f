//! An independent exact reference of every case, in rational arithmetic.
//!
//! Every f64 input converts exactly to a rational; each answer is found by
//! Gaussian elimination of the 3×3 momentum system (Eqs 1, 2 or 20, 3), the
//! regimes are decided exactly, and energies are exact differences of kinetic
//! energies. Nothing here shares code or formulas with the closed forms.
#![allow(clippy::needless_range_loop, clippy::too_many_arguments)]

use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

pub type Q = BigRational;

pub fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite input")
}

fn half() -> Q {
    Q::new(1.into(), 2.into())
}

/// A planar scene in exact arithmetic.
#[derive(Clone, Debug)]
pub struct Scene {
    pub m: Q,
    pub k2: Q,
    pub dc: Q,
    pub dd: Q,
    pub vn: Q,
    pub vt: Q,
    pub w: Q,
}

impl Scene {
    pub fn new(m: f64, inertia: f64, dc: f64, dd: f64, vn: f64, vt: f64, w: f64) -> Self {
        let m = q(m);
        let k2 = q(inertia) / &m;
        Scene {
            m,
            k2,
            dc: q(dc),
            dd: q(dd),
            vn: q(vn),
            vt: q(vt),
            w: q(w),
        }
    }
    pub fn vcn(&self) -> Q {
        &self.vn + &self.dc * &self.w
    }
    pub fn vct(&self) -> Q {
        &self.vt - &self.dd * &self.w
    }
    fn kinetic(&self, vn: &Q, vt: &Q, w: &Q) -> Q {
        half() * &self.m * (vn * vn + vt * vt + &self.k2 * w * w)
    }
}

/// The second row of the system.
pub enum Closure {
    Ratio(Q),
    ContactTangential(Q),
}

/// Solves the 3×3 system with first row `V_cn = target_cn`; `None` if singular.
fn solve(s: &Scene, target_cn: Q, closure: &Closure) -> Option<[Q; 3]> {
    let (row2, rhs2) = match closure {
        Closure::Ratio(mu) => ([mu.clone(), -Q::one(), Q::zero()], mu * &s.vn - &s.vt),
        Closure::ContactTangential(v) => ([Q::zero(), Q::one(), -s.dd.clone()], v.clone()),
    };
    let mut a = [
        [Q::one(), Q::zero(), s.dc.clone(), target_cn],
        [row2[0].clone(), row2[1].clone(), row2[2].clone(), rhs2],
        [
            s.dc.clone(),
            -s.dd.clone(),
            -s.k2.clone(),
            &s.dc * &s.vn - &s.dd * &s.vt - &s.k2 * &s.w,
        ],
    ];
    for col in 0..3 {
        let pivot = (col..3).find(|&r| !a[r][col].is_zero())?;
        a.swap(col, pivot);
        for r in 0..3 {
            if r != col && !a[r][col].is_zero() {
                let factor = &a[r][col] / &a[col][col];
                for c in col..4 {
                    let sub = &factor * &a[col][c];
                    a[r][c] = &a[r][c] - sub;
                }
            }
        }
    }
    Some([&a[0][3] / &a[0][0], &a[1][3] / &a[1][1], &a[2][3] / &a[2][2]])
}

#[derive(Clone, Debug)]
pub struct Outcome {
    pub vn: Q,
    pub vt: Q,
    pub w: Q,
    pub vcn: Q,
    pub vct: Q,
    pub pn: Q,
    pub pt: Q,
    pub mu: Q,
    pub mu_c: Option<Q>,
    pub e: Q,
    pub r: Q,
    pub regime: &'static str,
    pub t_initial: Q,
    pub t_final: Q,
    pub t_loss: Q,
    pub t_max: Q,
}

#[derive(Debug, PartialEq)]
pub enum Refusal {
    NotApproaching,
    NoImpulseSolution,
    CreatesEnergy,
}

fn outcome(
    s: &Scene,
    x: [Q; 3],
    e: Q,
    r: Q,
    regime: &'static str,
    mu_c: Option<Q>,
) -> Result<Outcome, Refusal> {
    let [vn, vt, w] = x;
    let pn = &s.m * (&vn - &s.vn);
    if !pn.is_positive() {
        return Err(Refusal::NoImpulseSolution);
    }
    let pt = &s.m * (&vt - &s.vt);
    let t_initial = s.kinetic(&s.vn, &s.vt, &s.w);
    let t_final = s.kinetic(&vn, &vt, &w);
    let t_loss = &t_initial - &t_final;
    if t_loss.is_negative() {
        return Err(Refusal::CreatesEnergy);
    }
    let stop = solve(s, Q::zero(), &Closure::ContactTangential(Q::zero())).expect("stop solution");
    let t_max = &t_initial - s.kinetic(&stop[0], &stop[1], &stop[2]);
    Ok(Outcome {
        vcn: &vn + &s.dc * &w,
        vct: &vt - &s.dd * &w,
        mu: &pt / &pn,
        vn,
        vt,
        w,
        pn,
        pt,
        mu_c,
        e,
        r,
        regime,
        t_initial,
        t_final,
        t_loss,
        t_max,
    })
}

fn approaching(s: &Scene) -> Result<(), Refusal> {
    if s.vcn().is_negative() {
        Ok(())
    } else {
        Err(Refusal::NotApproaching)
    }
}

/// `μ` of the answer with `V_ct = target`, or `None` when `P_n = 0`; also the sign of `P_n`.
fn target_ratio(s: &Scene, e: &Q, target: Q) -> (Option<Q>, Option<[Q; 3]>) {
    let Some(x) = solve(s, -(e * s.vcn()), &Closure::ContactTangential(target)) else {
        return (None, None);
    };
    let dn = &x[0] - &s.vn;
    let dt = &x[1] - &s.vt;
    if dn.is_zero() {
        (None, Some(x))
    } else {
        (Some(dt / dn), Some(x))
    }
}

pub fn critical(s: &Scene, e: &Q) -> Option<Q> {
    target_ratio(s, e, Q::zero()).0
}

/// `Δn = P_n / m` of the sticking answer (`V_ct = 0`), the denominator of `μ_c`.
pub fn critical_normal_change(s: &Scene, e: &Q) -> Q {
    let x = solve(s, -(e * s.vcn()), &Closure::ContactTangential(Q::zero())).expect("regular");
    &x[0] - &s.vn
}

pub fn prescribed(s: &Scene, e: f64, mu: f64) -> Result<Outcome, Refusal> {
    approaching(s)?;
    let e = q(e);
    let mu_c = critical(s, &e);
    let x = solve(s, -(&e * s.vcn()), &Closure::Ratio(q(mu))).ok_or(Refusal::NoImpulseSolution)?;
    outcome(s, x, e.clone(), e, "prescribed", mu_c)
}

pub fn frictionless(s: &Scene, e: f64) -> Result<Outcome, Refusal> {
    let mut o = prescribed(s, e, 0.0)?;
    o.regime = "frictionless";
    Ok(o)
}

/// The bilinear law: capped answer `V_ct = −e_t v_ct` when its `|μ| ≤ f`, else sliding.
pub fn bilinear(s: &Scene, e: f64, f: f64, et: f64, capped: &'static str) -> Result<Outcome, Refusal> {
    approaching(s)?;
    let e = q(e);
    let f = q(f);
    let mu_c = critical(s, &e);
    let (mu_t, x) = target_ratio(s, &e, -(q(et) * s.vct()));
    if let (Some(mu_t), Some(x)) = (&mu_t, x) {
        if mu_t.abs() <= f {
            return outcome(s, x, e.clone(), e, capped, mu_c);
        }
    }
    let direction = if !s.vct().is_zero() {
        -s.vct().signum()
    } else {
        mu_t.expect("finite target ratio when v_ct = 0").signum()
    };
    let mu = direction * f;
    let x = solve(s, -(&e * s.vcn()), &Closure::Ratio(mu)).ok_or(Refusal::NoImpulseSolution)?;
    outcome(s, x, e.clone(), e, "sliding", mu_c)
}

/// The Appendix's two phases, each its own linear system.
pub fn kinetic(s: &Scene, r: f64, mu_a: f64, mu_r: f64) -> Result<Outcome, Refusal> {
    approaching(s)?;
    let r = q(r);
    // Approach: ends with v̄_cn = 0, ratio μ_A.
    let bar = solve(s, Q::zero(), &Closure::Ratio(q(mu_a))).ok_or(Refusal::NoImpulseSolution)?;
    let pn_a = &s.m * (&bar[0] - &s.vn);
    if !pn_a.is_positive() {
        return Err(Refusal::NoImpulseSolution);
    }
    // Rebound from the barred state: P_n^R = R P_n^A, ratio μ_R, momentum (A-7…A-9).
    let pn_r = &r * &pn_a;
    let pt_r = q(mu_r) * &pn_r;
    let vn = &bar[0] + &pn_r / &s.m;
    let vt = &bar[1] + &pt_r / &s.m;
    let w = &bar[2] + (&s.dc * &pn_r - &s.dd * &pt_r) / (&s.m * &s.k2);
    let vcn_final = &vn + &s.dc * &w;
    if !r.is_zero() && vcn_final.is_negative() {
        return Err(Refusal::NoImpulseSolution);
    }
    let e = -(vcn_final / s.vcn());
    let mu_c = critical(s, &e);
    outcome(s, [vn, vt, w], e, r, "prescribed", mu_c)
}

/// Torsional reference: `(Ω_n, M_n, regime, switch, loss)`.
pub fn torsional(
    m: f64,
    i_n: f64,
    vn: f64,
    w: f64,
    e: f64,
    ez: f64,
    mu_z: f64,
    rho: f64,
) -> (Q, Q, &'static str, Q, Q) {
    let (m, i_n, vn, w, e, ez, mu_z, rho) = (q(m), q(i_n), q(vn), q(w), q(e), q(ez), q(mu_z), q(rho));
    let pn = &m * (Q::one() + &e) * (-&vn);
    let switch = &mu_z * &rho * &pn / &i_n;
    let (spin, regime) = if w.abs() <= switch {
        (-(&ez * &w), "restitution")
    } else {
        let friction = w.signum() * &mu_z * &rho * &pn;
        let moment = -friction - &ez * &i_n * &w;
        (&w + moment / &i_n, "sliding")
    };
    let moment = &i_n * (&spin - &w);
    let loss = half() * &i_n * (&w * &w - &spin * &spin);
    (spin, moment, regime, switch, loss)
}

/// The error of `fast` in units in the last place of `scale` (≥ the exact value's magnitude).
pub fn ulps(fast: f64, exact: &Q, scale: &Q) -> f64 {
    let diff = (q(fast) - exact).abs();
    let reference = scale.abs().max(exact.abs());
    // Below the smallest subnormal the unit is the smallest subnormal itself.
    let r = reference.to_f64().unwrap_or(f64::MAX).abs();
    let ulp = ulp_of(r);
    (diff / q(ulp)).to_f64().unwrap_or(f64::INFINITY)
}

pub fn ulp_of(x: f64) -> f64 {
    let x = x.abs();
    if x < f64::MIN_POSITIVE {
        return f64::from_bits(1);
    }
    let biased = (x.to_bits() >> 52) & 0x7ff;
    if biased > 52 {
        f64::from_bits((biased - 52) << 52)
    } else {
        f64::from_bits(1u64 << (biased - 1))
    }
}

pub fn to_f64(x: &Q) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}
