//! An independent reference of the contact in space (body A against body B
//! or a fixed barrier, full inertia tensors, one tangential law and an
//! optional twist law), in exact rational arithmetic.
//!
//! Derived from the momentum equations alone, sharing no code or formulas
//! with `src/model/spatial.rs`:
//!
//! - each body `b` (sign `σ_b = +1` for A, `−1` for B) takes the impulse
//!   `σ_b P` at `C` and the couple `σ_b M n̂`: `m_b ΔV_b = σ_b P`,
//!   `I_b Δω_b = σ_b (r_b × P + M n̂)` (`I_b⁻¹` by our own elimination);
//! - the couple is carried as `κ = M/|n|` (so `M n̂ = κ n`) and the spin as
//!   `s̃ = (ω_A − ω_B)·n = |n| s`, which keeps every coefficient rational with
//!   the normal `n` left unnormalised (`ν = |n|²`);
//! - the linear response `(ΔU, ΔS̃) = 𝒲̃ (P, κ)` is found by applying those
//!   equations to the four unit impulses (no closed form of `W`);
//! - each branch is a 5×5 linear system in `(P, κ, λ)` solved by Gaussian
//!   elimination: three rows for the tangential law (kept: `ΔU = −(1 + e)
//!   (u·n/ν) n − (1 + e_t) u_t`; sliding: `P = λ d` and `ΔU·n = −(1 + e) u·n`)
//!   and one for the twist law (none: `κ = 0`; restitution: `ΔS̃ = −(1 + e_z)
//!   s̃`; sliding: `κ = −e_z s̃/k + τ μ_z ρ_p (P·n)/ν`, `k = Σ_b nᵀ I_b⁻¹ n`,
//!   `τ = −sgn s̃`, or the sign of the restitution couple with the same
//!   tangential branch when `s̃ = 0`);
//! - the final velocities come from the momentum equations again, and the
//!   laws, the work form of the loss and `T_M` are checked on them.
//!
//! The sliding direction `d = n + c √(ν/|w|²) w` (`w = −u_t`, or the
//! sticking impulse's `P_t` when `u_t = 0`) holds the one irrational number of
//! an answer, `ρ = √(ν/|w|²)`. The reference evaluates everything twice, with
//! rational bounds `ρ_lo ≤ ρ ≤ ρ_hi` 2⁻¹⁹⁹ apart (relative): where no root is
//! needed both evaluations are the same exact rationals; otherwise each output
//! lies between its two evaluations (a rational function of `ρ` is monotone
//! over so short an interval; its curvature would show only 2⁻⁴⁰⁰ away), and
//! its correctly rounded double is known when both ends round alike.
//!
//! Every output is `x √y` with rational `x` and `y` (`y = 1` for a rational
//! one; `y = ν` for components along `n̂`, spins and the couple).
//!
//! The arithmetic is [`R`], exact fractions left unreduced (but for common
//! factors of two): num-bigint's binary gcd is quadratic in the length, and
//! reducing after every operation, as `BigRational` does, took nine tenths
//! of the time. Elimination is fraction-free (Bareiss).
#![allow(clippy::needless_range_loop)]

use super::bodies_reference::is_correctly_rounded_sqrt;
use super::reference::{Q, to_f64};
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use restitution::{Law, RigidBody, SpatialImpact};
use std::cmp::Ordering;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// An exact fraction `n/d`, `d > 0`, not reduced (but for common factors
/// of two); equality and order are by value.
#[derive(Clone, Debug)]
pub struct R {
    n: BigInt,
    d: BigInt,
}

fn twos(x: &BigInt) -> u64 {
    x.trailing_zeros().unwrap_or(0)
}

impl R {
    fn make(mut n: BigInt, mut d: BigInt) -> R {
        assert!(!d.is_zero(), "division by zero");
        if n.is_zero() {
            return R::zero();
        }
        if d.is_negative() {
            n = -n;
            d = -d;
        }
        let t = twos(&n).min(twos(&d));
        if t > 0 {
            n >>= t;
            d >>= t;
        }
        R { n, d }
    }

    pub fn zero() -> R {
        R {
            n: BigInt::zero(),
            d: BigInt::one(),
        }
    }

    pub fn one() -> R {
        R {
            n: BigInt::one(),
            d: BigInt::one(),
        }
    }

    pub fn int(i: i64) -> R {
        R::make(BigInt::from(i), BigInt::one())
    }

    /// A finite double, exactly.
    pub fn f(x: f64) -> R {
        R::of(&Q::from_float(x).expect("finite input"))
    }

    pub fn of(x: &Q) -> R {
        R::make(x.numer().clone(), x.denom().clone())
    }

    /// The value as a `BigRational` (not reduced; its comparisons and
    /// conversions are by value).
    pub fn q(&self) -> Q {
        Q::new_raw(self.n.clone(), self.d.clone())
    }

    /// The value in lowest terms (one gcd).
    pub fn reduced(&self) -> R {
        let q = Q::new(self.n.clone(), self.d.clone());
        R {
            n: q.numer().clone(),
            d: q.denom().clone(),
        }
    }

    pub fn to_f64(&self) -> f64 {
        self.q().to_f64().unwrap_or(f64::NAN)
    }

    pub fn is_zero(&self) -> bool {
        self.n.is_zero()
    }

    pub fn is_positive(&self) -> bool {
        self.n.is_positive()
    }

    pub fn is_negative(&self) -> bool {
        self.n.is_negative()
    }

    pub fn signum(&self) -> R {
        R::int(match self.n.sign() {
            num_bigint::Sign::Minus => -1,
            num_bigint::Sign::NoSign => 0,
            num_bigint::Sign::Plus => 1,
        })
    }

    pub fn abs(&self) -> R {
        R {
            n: self.n.abs(),
            d: self.d.clone(),
        }
    }

    fn plus(&self, o: &R) -> R {
        if self.is_zero() {
            return o.clone();
        }
        if o.is_zero() {
            return self.clone();
        }
        if self.d == o.d {
            return R::make(&self.n + &o.n, self.d.clone());
        }
        // Denominators that differ by a power of two share their odd part.
        let (ta, tb) = (twos(&self.d), twos(&o.d));
        let odd = &self.d >> ta;
        if odd == (&o.d >> tb) {
            let t = ta.max(tb);
            return R::make((&self.n << (t - ta)) + (&o.n << (t - tb)), odd << t);
        }
        R::make(&self.n * &o.d + &o.n * &self.d, &self.d * &o.d)
    }

    fn times(&self, o: &R) -> R {
        if self.is_zero() || o.is_zero() {
            return R::zero();
        }
        R::make(&self.n * &o.n, &self.d * &o.d)
    }

    fn over(&self, o: &R) -> R {
        R::make(&self.n * &o.d, &self.d * &o.n)
    }

    fn negated(&self) -> R {
        R {
            n: -&self.n,
            d: self.d.clone(),
        }
    }
}

impl PartialEq for R {
    fn eq(&self, o: &R) -> bool {
        &self.n * &o.d == &o.n * &self.d
    }
}

impl Eq for R {}

impl PartialOrd for R {
    fn partial_cmp(&self, o: &R) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for R {
    fn cmp(&self, o: &R) -> Ordering {
        (&self.n * &o.d).cmp(&(&o.n * &self.d))
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $impl:ident) => {
        impl $trait<&R> for &R {
            type Output = R;
            fn $method(self, o: &R) -> R {
                self.$impl(o)
            }
        }
        impl $trait<R> for &R {
            type Output = R;
            fn $method(self, o: R) -> R {
                self.$impl(&o)
            }
        }
        impl $trait<&R> for R {
            type Output = R;
            fn $method(self, o: &R) -> R {
                (&self).$impl(o)
            }
        }
        impl $trait<R> for R {
            type Output = R;
            fn $method(self, o: R) -> R {
                (&self).$impl(&o)
            }
        }
    };
}

binary!(Add, add, plus);
binary!(Mul, mul, times);
binary!(Div, div, over);

impl Sub<&R> for &R {
    type Output = R;
    fn sub(self, o: &R) -> R {
        self.plus(&o.negated())
    }
}
impl Sub<R> for &R {
    type Output = R;
    fn sub(self, o: R) -> R {
        self.plus(&o.negated())
    }
}
impl Sub<&R> for R {
    type Output = R;
    fn sub(self, o: &R) -> R {
        self.plus(&o.negated())
    }
}
impl Sub<R> for R {
    type Output = R;
    fn sub(self, o: R) -> R {
        self.plus(&o.negated())
    }
}

impl Neg for &R {
    type Output = R;
    fn neg(self) -> R {
        self.negated()
    }
}

impl Neg for R {
    type Output = R;
    fn neg(self) -> R {
        self.negated()
    }
}

impl AddAssign<R> for R {
    fn add_assign(&mut self, o: R) {
        *self = self.plus(&o);
    }
}

impl AddAssign<&R> for R {
    fn add_assign(&mut self, o: &R) {
        *self = self.plus(o);
    }
}

impl SubAssign<R> for R {
    fn sub_assign(&mut self, o: R) {
        *self = self.plus(&o.negated());
    }
}

impl SubAssign<&R> for R {
    fn sub_assign(&mut self, o: &R) {
        *self = self.plus(&o.negated());
    }
}

pub fn r(x: f64) -> R {
    R::f(x)
}

fn half() -> R {
    R::make(BigInt::one(), BigInt::from(2))
}

pub type V3 = [R; 3];
type M3 = [[R; 3]; 3];

pub fn zero3() -> V3 {
    [R::zero(), R::zero(), R::zero()]
}

pub fn v3(x: [f64; 3]) -> V3 {
    [r(x[0]), r(x[1]), r(x[2])]
}

pub fn dot(a: &V3, b: &V3) -> R {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub fn cross(a: &V3, b: &V3) -> V3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

pub fn add(a: &V3, b: &V3) -> V3 {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

pub fn sub(a: &V3, b: &V3) -> V3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub fn scale(k: &R, a: &V3) -> V3 {
    [k * &a[0], k * &a[1], k * &a[2]]
}

fn mat_vec(m: &M3, x: &V3) -> V3 {
    [dot(&m[0], x), dot(&m[1], x), dot(&m[2], x)]
}

/// Solves `a x = b` (`a` square) by Gaussian elimination; `None` when
/// singular. Each row is brought to integers over a common denominator,
/// eliminated fraction-free (Bareiss: every division exact), and solved back
/// fraction-free: `x_i = N_i/D` with `D` the last pivot (the determinant).
pub fn gauss(a: Vec<Vec<R>>, b: Vec<R>) -> Option<Vec<R>> {
    let n = b.len();
    let mut m: Vec<Vec<BigInt>> = a
        .into_iter()
        .zip(b)
        .map(|(mut row, rhs)| {
            row.push(rhs);
            // A common multiple of the denominators: their odd parts, each
            // once unless it divides those already taken, times a power of two.
            let (mut odd, mut t) = (BigInt::one(), 0u64);
            for x in &row {
                let tx = twos(&x.d);
                t = t.max(tx);
                let ox = &x.d >> tx;
                if !ox.is_one() && !(&odd % &ox).is_zero() {
                    odd *= ox;
                }
            }
            let den = odd << t;
            row.iter().map(|x| &x.n * (&den / &x.d)).collect()
        })
        .collect();
    let mut prev = BigInt::one();
    for k in 0..n {
        let pivot = (k..n).find(|&r| !m[r][k].is_zero())?;
        m.swap(k, pivot);
        let top = m[k].clone();
        for row in m.iter_mut().skip(k + 1) {
            for j in k + 1..=n {
                row[j] = (&row[j] * &top[k] - &row[k] * &top[j]) / &prev;
            }
            row[k] = BigInt::zero();
        }
        prev = top[k].clone();
    }
    let det = m[n - 1][n - 1].clone();
    let mut num = vec![BigInt::zero(); n];
    for i in (0..n).rev() {
        let mut acc = &m[i][n] * &det;
        for j in i + 1..n {
            acc -= &m[i][j] * &num[j];
        }
        let (quotient, rest) = num_integer_div_rem(&acc, &m[i][i]);
        assert!(rest.is_zero(), "fraction-free back substitution is exact");
        num[i] = quotient;
    }
    Some(num.into_iter().map(|x| R::make(x, det.clone())).collect())
}

fn num_integer_div_rem(a: &BigInt, b: &BigInt) -> (BigInt, BigInt) {
    let q = a / b;
    let r = a - &q * b;
    (q, r)
}

/// Whether a symmetric matrix is positive definite (its leading minors, exactly).
fn positive_definite(m: &M3) -> bool {
    let d1 = m[0][0].clone();
    let d2 = &m[0][0] * &m[1][1] - &m[0][1] * &m[1][0];
    let d3 = &m[0][0] * (&m[1][1] * &m[2][2] - &m[1][2] * &m[2][1])
        - &m[0][1] * (&m[1][0] * &m[2][2] - &m[1][2] * &m[2][0])
        + &m[0][2] * (&m[1][0] * &m[2][1] - &m[1][1] * &m[2][0]);
    d1.is_positive() && d2.is_positive() && d3.is_positive()
}

/// One body in exact arithmetic, its lever `r = C − G`.
#[derive(Clone, Debug)]
pub struct Body {
    pub m: R,
    pub tensor: M3,
    pub inverse: M3,
    pub r: V3,
    pub v: V3,
    pub w: V3,
}

impl Body {
    /// `None` when the tensor is not positive definite.
    pub fn new(b: &RigidBody, c: &V3) -> Option<Body> {
        let [xx, yy, zz, xy, xz, yz] = b.inertia.map(r);
        let tensor = [[xx, xy.clone(), xz.clone()], [xy, yy, yz.clone()], [xz, yz, zz]];
        if !positive_definite(&tensor) {
            return None;
        }
        // I⁻¹ column by column: I x = e_j.
        let mut inverse: M3 = [zero3(), zero3(), zero3()];
        for j in 0..3 {
            let a = tensor.iter().map(|row| row.to_vec()).collect();
            let mut e = vec![R::zero(); 3];
            e[j] = R::one();
            let x = gauss(a, e)?;
            for i in 0..3 {
                inverse[i][j] = x[i].clone();
            }
        }
        Some(Body {
            m: r(b.mass),
            tensor,
            inverse,
            r: sub(c, &v3(b.position)),
            v: v3(b.velocity),
            w: v3(b.angular_velocity),
        })
    }

    /// The contact point's velocity `v + ω × r`.
    pub fn point_velocity(&self, v: &V3, w: &V3) -> V3 {
        add(v, &cross(w, &self.r))
    }

    /// `½ m |v|² + ½ ωᵀ I ω`.
    pub fn kinetic(&self, v: &V3, w: &V3) -> R {
        half() * (&self.m * dot(v, v) + dot(w, &mat_vec(&self.tensor, w)))
    }

    /// `(ΔV, Δω, L)` under the impulse `σ P` at `C` and the couple `σ κ n`:
    /// `m ΔV = σ P`, `I Δω = L = σ (r × P + κ n)`.
    pub fn change(&self, sign: &R, p: &V3, kappa: &R, n: &V3) -> (V3, V3, V3) {
        let dv = scale(&(sign / &self.m), p);
        let moment = scale(sign, &add(&cross(&self.r, p), &scale(kappa, n)));
        let dw = mat_vec(&self.inverse, &moment);
        (dv, dw, moment)
    }
}

/// A body's final state after an impulse.
pub struct FinalState {
    pub v: V3,
    pub w: V3,
    pub dv: V3,
    pub dw: V3,
    /// `L = I Δω`.
    pub moment: V3,
}

/// A contact in exact arithmetic.
#[derive(Clone, Debug)]
pub struct Scene {
    /// A, then B when there is one.
    pub bodies: Vec<Body>,
    /// The unnormalised normal and `ν = |n|²`.
    pub n: V3,
    pub nu: R,
    /// `u = u_A − u_B`, `u·n`, the slip `u_t = u − (u·n/ν) n`.
    pub u: V3,
    pub un: R,
    pub ut: V3,
    /// `s̃ = (ω_A − ω_B)·n`, and `ν Σ_b |ω_b|²`, the size of `s̃²`'s terms.
    pub s: R,
    pub spin_size: R,
    /// `(ΔU, ΔS̃) = resp (P, κ)`: `resp[i][j]` is component `i` of the
    /// response to the unit impulse `j`.
    pub resp: [[R; 4]; 4],
    pub t_initial: R,
}

fn sign_of(k: usize) -> R {
    if k == 0 { R::one() } else { R::int(-1) }
}

/// `u·n` alone (what decides the approach), without the rest of the scene.
pub fn approach(impact: &SpatialImpact) -> R {
    let c = v3(impact.contact.point);
    let n = v3(impact.contact.normal);
    let mut total = R::zero();
    for (k, b) in std::iter::once(&impact.a).chain(impact.b.as_ref()).enumerate() {
        let rb = sub(&c, &v3(b.position));
        let point = add(&v3(b.velocity), &cross(&v3(b.angular_velocity), &rb));
        total += sign_of(k) * dot(&point, &n);
    }
    total
}

impl Scene {
    /// `None` when a tensor is not positive definite.
    pub fn new(impact: &SpatialImpact) -> Option<Scene> {
        let c = v3(impact.contact.point);
        let n = v3(impact.contact.normal);
        let nu = dot(&n, &n);
        let mut bodies = vec![Body::new(&impact.a, &c)?];
        if let Some(b) = &impact.b {
            bodies.push(Body::new(b, &c)?);
        }
        let mut u = zero3();
        let mut spin = zero3();
        let mut t_initial = R::zero();
        let mut spin_size = R::zero();
        for (k, b) in bodies.iter().enumerate() {
            let sg = sign_of(k);
            u = add(&u, &scale(&sg, &b.point_velocity(&b.v, &b.w)));
            spin = add(&spin, &scale(&sg, &b.w));
            t_initial += b.kinetic(&b.v, &b.w);
            spin_size += &nu * dot(&b.w, &b.w);
        }
        let un = dot(&u, &n);
        let ut = sub(&u, &scale(&(&un / &nu), &n));
        let s = dot(&spin, &n);
        let mut scene = Scene {
            bodies,
            n,
            nu,
            u,
            un,
            ut,
            s,
            spin_size,
            resp: std::array::from_fn(|_| std::array::from_fn(|_| R::zero())),
            t_initial,
        };
        for j in 0..4 {
            let mut x = [R::zero(), R::zero(), R::zero(), R::zero()];
            x[j] = R::one();
            let (du, ds) = scene.effect(&[x[0].clone(), x[1].clone(), x[2].clone()], &x[3]);
            for i in 0..3 {
                scene.resp[i][j] = du[i].clone();
            }
            scene.resp[3][j] = ds;
        }
        Some(scene)
    }

    /// Each body's final state after `P` on A (`−P` on B) and `κ n` on A (`−κ n` on B).
    pub fn finals(&self, p: &V3, kappa: &R) -> Vec<FinalState> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(k, b)| {
                let (dv, dw, moment) = b.change(&sign_of(k), p, kappa, &self.n);
                FinalState {
                    v: add(&b.v, &dv),
                    w: add(&b.w, &dw),
                    dv,
                    dw,
                    moment,
                }
            })
            .collect()
    }

    /// The final relative contact velocity `U` and scaled spin `S̃`.
    pub fn contact_after(&self, finals: &[FinalState]) -> (V3, R) {
        let mut u = zero3();
        let mut spin = zero3();
        for (k, (b, f)) in self.bodies.iter().zip(finals).enumerate() {
            let sg = sign_of(k);
            u = add(&u, &scale(&sg, &b.point_velocity(&f.v, &f.w)));
            spin = add(&spin, &scale(&sg, &f.w));
        }
        let s = dot(&spin, &self.n);
        (u, s)
    }

    /// `(ΔU, ΔS̃)` of `(P, κ)`, from the bodies' changes.
    fn effect(&self, p: &V3, kappa: &R) -> (V3, R) {
        let mut du = zero3();
        let mut dspin = zero3();
        for (k, b) in self.bodies.iter().enumerate() {
            let sg = sign_of(k);
            let (dv, dw, _) = b.change(&sg, p, kappa, &self.n);
            du = add(&du, &scale(&sg, &add(&dv, &cross(&dw, &b.r))));
            dspin = add(&dspin, &scale(&sg, &dw));
        }
        (du, dot(&dspin, &self.n))
    }

    /// The kinetic energy after the impulse: `½ m |V|²` and, with `I Δω = L`,
    /// `½ Ωᵀ I Ω = ½ ωᵀ I ω + ω·L + ½ Δω·L`.
    pub fn kinetic_after(&self, finals: &[FinalState]) -> R {
        let mut total = R::zero();
        for (b, f) in self.bodies.iter().zip(finals) {
            total += half() * (&b.m * dot(&f.v, &f.v) + dot(&b.w, &mat_vec(&b.tensor, &b.w)))
                + dot(&b.w, &f.moment)
                + half() * dot(&f.dw, &f.moment);
        }
        total
    }

    /// `k = Σ_b nᵀ I_b⁻¹ n`, the scaled spin change per unit `κ`.
    pub fn k(&self) -> R {
        self.resp[3][3].clone()
    }

    /// The largest loss any impulse (and couple, with a twist law) can make:
    /// that of the one that stops the contact, `U = 0` (and `S̃ = 0`), in
    /// work form `−½ (P·u + κ s̃)` (the work form is checked against the
    /// kinetic energies on every answer).
    pub fn max_loss(&self, twist: bool) -> R {
        let rows = if twist { 4 } else { 3 };
        let a = (0..rows).map(|i| self.resp[i][..rows].to_vec()).collect();
        let mut b: Vec<R> = self.u.iter().map(|x| -x).collect();
        if twist {
            b.push(-&self.s);
        }
        let x = gauss(a, b).expect("𝒲 is positive definite");
        let kappa = if twist { x[3].clone() } else { R::zero() };
        let p = [x[0].clone(), x[1].clone(), x[2].clone()];
        -(half() * (dot(&p, &self.u) + &kappa * &self.s))
    }
}

/// Rational bounds `lo ≤ √y ≤ hi`, `hi − lo ≤ 2⁻¹⁹⁹ lo`, equal when `√y`
/// is rational. The bounds are dyadic, `m/2^e` with `m` of about 200 bits,
/// which keeps the numbers of a sliding answer small.
pub fn sqrt_bounds(y: &R) -> (R, R) {
    assert!(!y.is_negative());
    if y.is_zero() {
        return (R::zero(), R::zero());
    }
    let y = y.reduced();
    let (a, b) = (&y.n, &y.d);
    let (ra, rb) = (a.sqrt(), b.sqrt());
    if &ra * &ra == *a && &rb * &rb == *b {
        let root = R::make(ra, rb);
        return (root.clone(), root);
    }
    // m = ⌊√(y 4^e)⌋ = ⌊√⌊a 4^e / b⌋⌋ with 2^199 ≤ m.
    let log2 = a.bits() as i64 - b.bits() as i64;
    let e = ((402 - log2).max(0) as usize).div_ceil(2);
    let m = ((a << (2 * e)) / b).sqrt();
    let den = BigInt::one() << e;
    (R::make(m.clone(), den.clone()), R::make(m + BigInt::one(), den))
}

/// `√y` from below (to 2⁻¹⁹⁹), for measurements.
pub fn sqrt_lower(y: &Q) -> Q {
    sqrt_bounds(&R::of(y)).0.q()
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    NotApproaching,
    NoImpulse,
    EnergyCreated,
    NotUnique,
    NoSlipDirection,
}

impl Refusal {
    pub fn slug(self) -> &'static str {
        match self {
            Refusal::NotApproaching => "not-approaching",
            Refusal::NoImpulse => "no-impulse-solution",
            Refusal::EnergyCreated => "creates-energy",
            Refusal::NotUnique => "not-unique",
            Refusal::NoSlipDirection => "no-slip-direction",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tb {
    Kept,
    Sliding,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Zb {
    Off,
    Rest,
    Slide,
}

/// Which bound of every root an evaluation takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Lower,
    Upper,
}

/// The law, read.
#[derive(Clone, Debug)]
struct Reading {
    e: R,
    /// `(f, e_t, regime)` of a two-branch law.
    kept: Option<(R, R, &'static str)>,
    /// The sliding coefficient (`f`, `μ` or 0).
    c: R,
    prescribed: bool,
    slide_regime: &'static str,
    /// The two-phase law, evaluated apart ([`Evaluator::run_kinetic`]).
    kinetic: Option<KineticR>,
}

/// The two-phase law: `R`, the approach's ratio `μ_A` or Coulomb `f_A`, and `μ_R`.
#[derive(Clone, Debug)]
struct KineticR {
    r: R,
    approach: R,
    coulomb: bool,
    rebound: R,
}

impl Reading {
    fn of(law: &Law) -> Reading {
        let single = |e: f64, c: f64, regime| Reading {
            e: r(e),
            kept: None,
            c: r(c),
            prescribed: regime == "prescribed",
            slide_regime: regime,
            kinetic: None,
        };
        let kinetic = |value: f64, approach: f64, coulomb: bool, rebound: f64| Reading {
            kinetic: Some(KineticR {
                r: r(value),
                approach: r(approach),
                coulomb,
                rebound: r(rebound),
            }),
            ..single(value, 0.0, "prescribed")
        };
        match *law {
            Law::Frictionless { restitution } => single(restitution, 0.0, "frictionless"),
            Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            } => single(restitution, impulse_ratio, "prescribed"),
            Law::Friction {
                restitution,
                friction,
            } => Reading {
                e: r(restitution),
                kept: Some((r(friction), R::zero(), "sticking")),
                c: r(friction),
                prescribed: false,
                slide_regime: "sliding",
                kinetic: None,
            },
            Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            } => Reading {
                e: r(restitution),
                kept: Some((r(friction), r(tangential_restitution), "restitution")),
                c: r(friction),
                prescribed: false,
                slide_regime: "sliding",
                kinetic: None,
            },
            Law::KineticRestitution {
                value,
                approach_impulse_ratio,
                rebound_impulse_ratio,
            } => kinetic(value, approach_impulse_ratio, false, rebound_impulse_ratio),
            Law::KineticFriction {
                value,
                approach_friction,
                rebound_impulse_ratio,
            } => kinetic(value, approach_friction, true, rebound_impulse_ratio),
        }
    }
}

/// `(e_z, μ_z, ρ_p)`.
#[derive(Clone, Debug)]
struct TwistR {
    ez: R,
    muz: R,
    rho: R,
}

/// An impulse and couple `(P, κ)` with `P·n`, `P_t`, and for sliding `λ`
/// (`P = λ d`) and the coefficient `c` of the root in `d` (0: `d = n`).
#[derive(Clone, Debug)]
struct Sol {
    p: V3,
    kappa: R,
    pn: R,
    pt: V3,
    lambda: R,
    c_root: R,
}

/// One output, `x √y`.
#[derive(Clone, Debug)]
struct Out {
    name: String,
    x: R,
    y: R,
}

/// What one evaluation answers (all roots at one bound).
#[derive(Clone, Debug)]
struct Eval {
    regime: &'static str,
    torsional: Option<&'static str>,
    outs: Vec<Out>,
    critical: Option<(R, R)>,
    /// Magnitudes for the fast measurement.
    sizes: Sizes,
    inside_margin: f64,
    critical_margin: f64,
}

/// Magnitudes of the answer's terms (f64: only sizes), for the error scales.
#[derive(Clone, Debug, Default)]
pub struct Sizes {
    /// Per body: `max(|v|, |V|)`, `max(|ω|, |Ω|)`, `|r|`, `m`, `‖I⁻¹‖`
    /// (`|x|` the largest component).
    pub v: Vec<f64>,
    pub w: Vec<f64>,
    pub lever: Vec<f64>,
    pub m: Vec<f64>,
    pub inv_i: Vec<f64>,
    /// `|P|`, `|M|`, `P_n`, the sticking `|P_n|` (0 without), `|n|`.
    pub p: f64,
    pub couple: f64,
    pub pn: f64,
    pub pn_c: f64,
    pub norm: f64,
    /// `T_i`, `T_f`, `T_M`.
    pub t_initial: f64,
    pub t_final: f64,
    pub t_max: f64,
    /// The Jacobi-scaled condition number of the contact matrix.
    pub kappa: f64,
}

/// What an answer hands to [`Evaluator::finish`].
struct Parts<'a> {
    sol: &'a Sol,
    finals: &'a Vec<FinalState>,
    /// `U` and `S̃`.
    uf: (&'a V3, &'a R),
    /// `e`, or the two-phase law's equivalent `e`.
    e: &'a R,
    regime: &'static str,
    z: Zb,
    /// Per body `|ΔV|` as `x √y`.
    delta_v: Vec<(R, R)>,
    /// `|P_t|/P_n` as `x √y`.
    ratio: (R, R),
    /// `μ_c` as `x √y`.
    critical: Option<(R, R)>,
    /// The sticking `|P·n|` (f64, a size).
    pn_c: f64,
    inside_margin: f64,
    critical_margin: f64,
}

/// Solutions found: the branches, the solution, whether it depends on a
/// root's bound, and the smallest margin of the decisions inside it.
type Cache = Vec<((Tb, Zb, R), Option<Sol>, bool, f64)>;

struct Evaluator<'a> {
    s: &'a Scene,
    law: Reading,
    twist: Option<TwistR>,
    mode: Mode,
    /// Solutions found, with whether they depend on a root's bound.
    cache: Cache,
    /// Whether a root was taken.
    rooted: bool,
    /// Whether the solution being computed depends on a root's bound.
    depends: bool,
    /// `T_M` (rational, the same for both bounds).
    t_max: R,
    /// The smallest relative margin of a decision (to a tie).
    margin: f64,
    /// The same, of the decisions inside the solution being computed.
    local: f64,
}

fn rel_margin(a: &R, b: &R) -> f64 {
    let total = a.abs() + b.abs();
    if total.is_zero() {
        0.0
    } else {
        ((a - b).abs() / total).to_f64()
    }
}

impl Evaluator<'_> {
    /// A comparison `a` against `b`.
    fn note(&mut self, a: &R, b: &R) {
        let m = rel_margin(a, b);
        self.margin = self.margin.min(m);
        self.local = self.local.min(m);
    }

    /// A sign decision on `x`, of terms of size `size`.
    fn note_sign(&mut self, x: &R, size: &R) {
        let m = if size.is_zero() {
            0.0
        } else {
            (x.abs() / size).to_f64()
        };
        self.margin = self.margin.min(m);
        self.local = self.local.min(m);
    }

    fn root(&mut self, y: &R) -> R {
        let (lo, hi) = sqrt_bounds(y);
        if lo != hi {
            self.rooted = true;
            self.depends = true;
        }
        match self.mode {
            Mode::Lower => lo,
            Mode::Upper => hi,
        }
    }

    fn solve(&mut self, t: Tb, z: Zb, et: &R) -> Result<Option<Sol>, Refusal> {
        let key = (t, z, et.clone());
        if let Some((_, found, depends, margin)) = self.cache.iter().find(|(k, ..)| *k == key) {
            self.depends |= *depends;
            self.local = self.local.min(*margin);
            return Ok(found.clone());
        }
        let outer = std::mem::replace(&mut self.depends, false);
        let outer_local = std::mem::replace(&mut self.local, f64::INFINITY);
        let found = self.compute(t, z, et)?;
        let (depends, margin) = (self.depends, self.local);
        self.cache.push((key, found.clone(), depends, margin));
        self.depends |= outer;
        self.local = outer_local.min(margin);
        Ok(found)
    }

    /// `(c₀, c₁)` of the sliding twist row `κ − c₁ (P·n) = c₀`.
    fn twist_terms(&mut self, t: Tb, et: &R) -> Result<(R, R), Refusal> {
        let tw = self.twist.clone().expect("twist law");
        let k = self.s.k();
        let c0 = -(&tw.ez * &self.s.s / &k);
        self.note_sign(&(&self.s.s * &self.s.s), &self.s.spin_size);
        let tau = if self.s.s.is_positive() {
            R::int(-1)
        } else if self.s.s.is_negative() {
            R::one()
        } else {
            match self.solve(t, Zb::Rest, et)? {
                Some(rest) => {
                    // Only an exact zero counts as a tie here.
                    let tie = if rest.kappa.is_zero() { R::zero() } else { R::one() };
                    self.note_sign(&tie, &R::one());
                    rest.kappa.signum()
                }
                None => R::zero(),
            }
        };
        let c1 = tau * &tw.muz * &tw.rho / &self.s.nu;
        Ok((c0, c1))
    }

    /// The sliding direction `d` for the twist branch `z`, with the
    /// coefficient of its root (0: `d = n`); `None` when the sticking system
    /// it needs is singular.
    fn direction(&mut self, z: Zb) -> Result<Option<(V3, R)>, Refusal> {
        let s = self.s;
        if self.law.c.is_zero() {
            return Ok(Some((s.n.clone(), R::zero())));
        }
        let slip = dot(&s.ut, &s.ut);
        self.note_sign(&slip, &dot(&s.u, &s.u));
        let w = if slip.is_positive() {
            [-&s.ut[0], -&s.ut[1], -&s.ut[2]]
        } else {
            let Some(stick) = self.solve(Tb::Kept, z, &R::zero())? else {
                return Ok(None);
            };
            self.note_sign(&dot(&stick.pt, &stick.pt), &dot(&stick.p, &stick.p));
            if stick.pt.iter().all(R::is_zero) {
                if self.law.prescribed {
                    return Err(Refusal::NoSlipDirection);
                }
                return Ok(Some((s.n.clone(), R::zero())));
            }
            stick.pt
        };
        let rho = self.root(&(&s.nu / dot(&w, &w)));
        let c = self.law.c.clone();
        Ok(Some((add(&s.n, &scale(&(&c * rho), &w)), c)))
    }

    fn compute(&mut self, t: Tb, z: Zb, et: &R) -> Result<Option<Sol>, Refusal> {
        let s = self.s;
        let mut a = vec![vec![R::zero(); 5]; 5];
        let mut b = vec![R::zero(); 5];
        let mut c_root = R::zero();
        match t {
            Tb::Kept => {
                let normal = scale(&(-((R::one() + &self.law.e) * &s.un) / &s.nu), &s.n);
                let target = sub(&normal, &scale(&(R::one() + et), &s.ut));
                for i in 0..3 {
                    for j in 0..4 {
                        a[i][j] = s.resp[i][j].clone();
                    }
                    b[i] = target[i].clone();
                }
                a[3][4] = R::one();
            }
            Tb::Sliding => {
                let Some((d, c)) = self.direction(z)? else {
                    return Ok(None);
                };
                c_root = c;
                for i in 0..3 {
                    a[i][i] = R::one();
                    a[i][4] = -&d[i];
                }
                for j in 0..4 {
                    a[3][j] = (0..3).fold(R::zero(), |acc, i| acc + &s.n[i] * &s.resp[i][j]);
                }
                b[3] = -((R::one() + &self.law.e) * &s.un);
            }
        }
        match z {
            Zb::Off => a[4][3] = R::one(),
            Zb::Rest => {
                let tw = self.twist.clone().expect("twist law");
                for j in 0..4 {
                    a[4][j] = s.resp[3][j].clone();
                }
                b[4] = -((R::one() + &tw.ez) * &s.s);
            }
            Zb::Slide => {
                let (c0, c1) = self.twist_terms(t, et)?;
                a[4][3] = R::one();
                for j in 0..3 {
                    a[4][j] = -(&c1 * &s.n[j]);
                }
                b[4] = c0;
            }
        }
        let Some(x) = gauss(a, b) else {
            return Ok(None);
        };
        let p = [x[0].clone(), x[1].clone(), x[2].clone()];
        let pn = dot(&p, &s.n);
        let pt = sub(&p, &scale(&(&pn / &s.nu), &s.n));
        Ok(Some(Sol {
            p,
            kappa: x[3].clone(),
            pn,
            pt,
            lambda: x[4].clone(),
            c_root,
        }))
    }

    /// The kept branch holds: `P·n ≠ 0` and `ν |P_t|² ≤ f² (P·n)²`.
    fn tangential_holds(&mut self, sol: &Option<Sol>) -> bool {
        let Some(sol) = sol else { return false };
        if sol.pn.is_zero() {
            return false;
        }
        let f = self.law.kept.as_ref().expect("two-branch law").0.clone();
        let cap = &f * &f * &sol.pn * &sol.pn;
        let value = &self.s.nu * dot(&sol.pt, &sol.pt);
        self.note(&cap, &value);
        value <= cap
    }

    /// The twist restitution branch holds: `P·n ≠ 0` and
    /// `(κ + e_z s̃/k)² ≤ (μ_z ρ_p (P·n)/ν)²`.
    fn spin_holds(&mut self, sol: &Option<Sol>) -> bool {
        let (Some(sol), Some(tw)) = (sol, self.twist.clone()) else {
            return false;
        };
        if sol.pn.is_zero() {
            return false;
        }
        let beyond = &sol.kappa + &tw.ez * &self.s.s / self.s.k();
        let cap = &tw.muz * &tw.rho * &sol.pn / &self.s.nu;
        let (b2, c2) = (&beyond * &beyond, &cap * &cap);
        self.note(&c2, &b2);
        b2 <= c2
    }

    /// The one valid combination of branches.
    fn choose(&mut self) -> Result<(Tb, Zb), Refusal> {
        let et = self.law.kept.as_ref().map_or_else(R::zero, |k| k.1.clone());
        let two = self.law.kept.is_some();
        let ts: &[Tb] = if two {
            &[Tb::Kept, Tb::Sliding]
        } else {
            &[Tb::Sliding]
        };
        let zs: &[Zb] = if self.twist.is_some() {
            &[Zb::Rest, Zb::Slide]
        } else {
            &[Zb::Off]
        };
        let mut valid = Vec::new();
        for &t in ts {
            for &z in zs {
                let t_ok = match t {
                    Tb::Kept => {
                        let sol = self.solve(Tb::Kept, z, &et)?;
                        self.tangential_holds(&sol)
                    }
                    Tb::Sliding if two => {
                        let sol = self.solve(Tb::Kept, z, &et)?;
                        !self.tangential_holds(&sol)
                    }
                    Tb::Sliding => true,
                };
                if !t_ok {
                    continue;
                }
                let z_ok = match z {
                    Zb::Off => true,
                    Zb::Rest => {
                        let sol = self.solve(t, Zb::Rest, &et)?;
                        self.spin_holds(&sol)
                    }
                    Zb::Slide => {
                        let sol = self.solve(t, Zb::Rest, &et)?;
                        !self.spin_holds(&sol)
                    }
                };
                if z_ok {
                    valid.push((t, z));
                }
            }
        }
        match valid[..] {
            [one] => Ok(one),
            _ => Err(Refusal::NotUnique),
        }
    }

    fn run(&mut self) -> Result<Eval, Refusal> {
        let s = self.s;
        if !s.un.is_negative() {
            return Err(Refusal::NotApproaching);
        }
        if let Some(k) = self.law.kinetic.clone() {
            return self.run_kinetic(&k);
        }
        let (t, z) = self.choose()?;
        let et = match (t, &self.law.kept) {
            (Tb::Kept, Some(k)) => k.1.clone(),
            _ => R::zero(),
        };
        let regime = match (t, &self.law.kept) {
            (Tb::Kept, Some(k)) => k.2,
            _ => self.law.slide_regime,
        };
        self.local = f64::INFINITY;
        let sol = self.solve(t, z, &et)?.ok_or(Refusal::NoImpulse)?;
        let inside_margin = self.local;
        // P·n against |P| |n|, squared.
        self.note_sign(&(&sol.pn * &sol.pn), &(&s.nu * dot(&sol.p, &sol.p)));
        if !sol.pn.is_positive() {
            return Err(Refusal::NoImpulse);
        }
        let finals = s.finals(&sol.p, &sol.kappa);
        let (uf, sf) = s.contact_after(&finals);
        let ufn = dot(&uf, &s.n);
        let uft = sub(&uf, &scale(&(&ufn / &s.nu), &s.n));
        // Self-checks: the laws hold on the velocities the momentum equations give.
        assert!(ufn == -(&self.law.e * &s.un), "U·n = −e u·n");
        if t == Tb::Kept {
            assert!(uft == scale(&-&et, &s.ut), "U_t = −e_t u_t");
        }
        if let (Zb::Rest, Some(tw)) = (z, &self.twist) {
            assert!(sf == -(&tw.ez * &s.s), "S = −e_z s");
        }
        if z == Zb::Off {
            assert!(sol.kappa.is_zero());
        }
        let one = R::one();
        let nu = &s.nu;
        // |ΔV| = |P|/m; sliding: |P| = λ |d| with |d|² = ν (1 + c²) exactly.
        let delta_v = s
            .bodies
            .iter()
            .map(|b| match t {
                Tb::Kept => (&one / &b.m, dot(&sol.p, &sol.p)),
                Tb::Sliding => (&sol.lambda / &b.m, nu * (&one + &sol.c_root * &sol.c_root)),
            })
            .collect();
        // |P_t|/P_n = √(ν |P_t|²)/(P·n); sliding: c exactly (0 when d = n).
        let ratio = match t {
            Tb::Kept => (&one / &sol.pn, nu * dot(&sol.pt, &sol.pt)),
            Tb::Sliding => (sol.c_root.clone(), one.clone()),
        };
        // μ_c = |P_t|/|P_n| of the sticking impulse with the answer's twist
        // branch: the magnitude the cap compares with f (sticking holds its
        // cap exactly when f ≥ μ_c), so positive also where that P_n < 0.
        self.local = f64::INFINITY;
        let stick = self.solve(Tb::Kept, z, &R::zero())?;
        let critical_margin = self.local;
        let critical = match &stick {
            Some(st) if !st.pn.is_zero() => Some((&one / st.pn.abs(), nu * dot(&st.pt, &st.pt))),
            _ => None,
        };
        let e = self.law.e.clone();
        self.finish(Parts {
            sol: &sol,
            finals: &finals,
            uf: (&uf, &sf),
            e: &e,
            regime,
            z,
            delta_v,
            ratio,
            critical,
            pn_c: stick.as_ref().map_or(0.0, |st| st.pn.to_f64().abs()),
            inside_margin,
            critical_margin,
        })
    }

    /// The two-phase law from its own equations: the approach `P^A` (the
    /// sticking impulse `W P = −u` where Coulomb's cap holds it, else
    /// `λ (n + μ_A t)` with `(W P^A)·n = −u·n`), then `P^R = λ_R (n + μ_R t)`
    /// with `P^R·n = R P^A·n`, `t = ρ w` one direction for both (`w = −u_t`,
    /// or the sticking impulse's `P_t`; that `P_t` itself after sticking).
    /// Outputs with a root are enclosed by the root's bounds, those that are
    /// roots of such numbers by their own roots' bounds (to about 2⁻¹⁹⁰).
    fn run_kinetic(&mut self, k: &KineticR) -> Result<Eval, Refusal> {
        let s = self.s;
        let nu = &s.nu;
        let one = R::one();
        let w_rows = |x: &V3| -> V3 {
            std::array::from_fn(|i| (0..3).fold(R::zero(), |acc, j| acc + &s.resp[i][j] * &x[j]))
        };
        let a3: Vec<Vec<R>> = (0..3).map(|i| s.resp[i][..3].to_vec()).collect();
        let x = gauss(a3, s.u.iter().map(|x| -x).collect()).expect("W is positive definite");
        let stick_p = [x[0].clone(), x[1].clone(), x[2].clone()];
        let stick_pn = dot(&stick_p, &s.n);
        let stick_pt = sub(&stick_p, &scale(&(&stick_pn / nu), &s.n));
        let kept = k.coulomb && !stick_pn.is_zero() && {
            let cap = &k.approach * &k.approach * &stick_pn * &stick_pn;
            let value = nu * dot(&stick_pt, &stick_pt);
            self.note(&cap, &value);
            value <= cap
        };
        let slip = dot(&s.ut, &s.ut);
        self.note_sign(&slip, &dot(&s.u, &s.u));
        let w = if !kept && slip.is_positive() {
            Some([-&s.ut[0], -&s.ut[1], -&s.ut[2]])
        } else if stick_pt.iter().any(|x| !x.is_zero()) {
            Some(stick_pt.clone())
        } else {
            None
        };
        let rebound = k.r.is_positive();
        let rebound_slides = rebound && k.rebound.is_positive();
        if w.is_none() && ((!k.coulomb && k.approach.is_positive()) || rebound_slides) {
            return Err(Refusal::NoSlipDirection);
        }
        let sliding = !kept && k.approach.is_positive();
        let t = match &w {
            Some(w) if sliding || rebound_slides => {
                let rho = self.root(&(nu / dot(w, w)));
                Some(scale(&rho, w))
            }
            _ => None,
        };
        let direction = |mu: &R| match &t {
            Some(t) if mu.is_positive() => add(&s.n, &scale(mu, t)),
            _ => s.n.clone(),
        };
        let pa = if kept {
            if !stick_pn.is_positive() {
                return Err(Refusal::NoImpulse);
            }
            stick_p
        } else {
            let d = direction(&if sliding { k.approach.clone() } else { R::zero() });
            let normal = dot(&s.n, &w_rows(&d));
            if !normal.is_positive() {
                return Err(Refusal::NoImpulse);
            }
            scale(&(-&s.un / normal), &d)
        };
        let d_r = direction(&k.rebound);
        if rebound && !dot(&s.n, &w_rows(&d_r)).is_positive() {
            return Err(Refusal::NoImpulse);
        }
        let pa_n = dot(&pa, &s.n);
        let pr = scale(&(&k.r * &pa_n / nu), &d_r);
        let p = add(&pa, &pr);
        // Self-checks: the approach ends at U·n = 0; the rebound is R times it.
        let (ua, _) = s.contact_after(&s.finals(&pa, &R::zero()));
        assert!(dot(&ua, &s.n).is_zero(), "U·n = 0 after the approach");
        assert!(dot(&pr, &s.n) == &k.r * &pa_n, "P_n^R = R P_n^A");
        let pn = dot(&p, &s.n);
        let pt = sub(&p, &scale(&(&pn / nu), &s.n));
        let sol = Sol {
            p: p.clone(),
            kappa: R::zero(),
            pn,
            pt,
            lambda: R::zero(),
            c_root: R::zero(),
        };
        let finals = s.finals(&p, &R::zero());
        let (uf, sf) = s.contact_after(&finals);
        let e = -(dot(&uf, &s.n) / &s.un);
        let rooted = t.is_some();
        // x √y, or with a root inside y, the root's bounds.
        let mut root_form = |x: R, y: R| {
            if rooted {
                (x * self.root(&y), one.clone())
            } else {
                (x, y)
            }
        };
        let delta_v = s
            .bodies
            .iter()
            .map(|b| root_form(&one / &b.m, dot(&p, &p)))
            .collect();
        let ratio = root_form(&one / &sol.pn, nu * dot(&sol.pt, &sol.pt));
        // μ_c: the sticking impulse with the equivalent e (rule 5).
        let target = sub(&scale(&(-((&one + &e) * &s.un) / nu), &s.n), &s.ut);
        let a3: Vec<Vec<R>> = (0..3).map(|i| s.resp[i][..3].to_vec()).collect();
        let x = gauss(a3, target.to_vec()).expect("W is positive definite");
        let c_p = [x[0].clone(), x[1].clone(), x[2].clone()];
        let c_pn = dot(&c_p, &s.n);
        let c_pt = sub(&c_p, &scale(&(&c_pn / nu), &s.n));
        let critical = (!c_pn.is_zero()).then(|| root_form(&one / c_pn.abs(), nu * dot(&c_pt, &c_pt)));
        let regime = match (k.coulomb, kept) {
            (false, _) => "prescribed",
            (true, true) => "sticking",
            (true, false) => "sliding",
        };
        self.finish(Parts {
            sol: &sol,
            finals: &finals,
            uf: (&uf, &sf),
            e: &e,
            regime,
            z: Zb::Off,
            delta_v,
            ratio,
            critical,
            pn_c: c_pn.to_f64().abs(),
            inside_margin: f64::INFINITY,
            critical_margin: f64::INFINITY,
        })
    }

    /// The checks and outputs every answer shares.
    fn finish(&mut self, parts: Parts<'_>) -> Result<Eval, Refusal> {
        let s = self.s;
        let Parts {
            sol,
            finals,
            uf: (uf, sf),
            e,
            regime,
            z,
            delta_v,
            ratio,
            critical,
            pn_c,
            inside_margin,
            critical_margin,
        } = parts;
        let finals = finals.as_slice();
        let ufn = dot(uf, &s.n);
        let uft = sub(uf, &scale(&(&ufn / &s.nu), &s.n));
        let sf = sf.clone();
        let t_final = s.kinetic_after(finals);
        let t_loss = &s.t_initial - &t_final;
        let work = dot(&sol.p, &add(&s.u, uf)) + &sol.kappa * (&s.s + &sf);
        assert!(t_loss == -(half() * work), "T_L in work form");
        self.note_sign(&t_loss, &s.t_initial);
        if t_loss.is_negative() {
            return Err(Refusal::EnergyCreated);
        }
        assert!(t_loss <= self.t_max, "T_L ≤ T_M");
        let t_max = self.t_max.clone();
        let nu = &s.nu;
        let one = R::one();
        let mut outs = Vec::new();
        let mut put = |name: String, x: R, y: &R| {
            outs.push(Out {
                name,
                x,
                y: y.clone(),
            })
        };
        for (k, (f, (x, y))) in finals.iter().zip(delta_v).enumerate() {
            for i in 0..3 {
                put(format!("bodies[{k}].velocity[{i}]"), f.v[i].clone(), &one);
                put(format!("bodies[{k}].angular_velocity[{i}]"), f.w[i].clone(), &one);
                put(format!("bodies[{k}].velocity_change[{i}]"), f.dv[i].clone(), &one);
                put(
                    format!("bodies[{k}].angular_velocity_change[{i}]"),
                    f.dw[i].clone(),
                    &one,
                );
            }
            put(format!("bodies[{k}].delta_v"), x, &y);
        }
        put("contact_velocity.initial.normal".into(), &s.un / nu, nu);
        put("contact_velocity.final.normal".into(), &ufn / nu, nu);
        for i in 0..3 {
            put(
                format!("contact_velocity.initial.tangential[{i}]"),
                s.ut[i].clone(),
                &one,
            );
            put(
                format!("contact_velocity.final.tangential[{i}]"),
                uft[i].clone(),
                &one,
            );
        }
        put("contact_velocity.initial.spin".into(), &s.s / nu, nu);
        put("contact_velocity.final.spin".into(), &sf / nu, nu);
        put("impulse.normal".into(), &sol.pn / nu, nu);
        for i in 0..3 {
            put(format!("impulse.tangential[{i}]"), sol.pt[i].clone(), &one);
        }
        put("impulse.torsional".into(), sol.kappa.clone(), nu);
        for (i, c) in ["x", "y", "z"].iter().enumerate() {
            put(format!("impulse.{c}"), sol.p[i].clone(), &one);
        }
        put("impulse_ratio".into(), ratio.0, &ratio.1);
        put("restitution".into(), e.clone(), &one);
        put("energy.initial".into(), s.t_initial.clone(), &one);
        put("energy.final".into(), t_final.clone(), &one);
        put("energy.loss".into(), t_loss.clone(), &one);
        put("energy.max_loss".into(), t_max.clone(), &one);
        put("energy.normalized_loss".into(), &t_loss / &t_max, &one);
        let norm = nu.to_f64().sqrt();
        let sizes = Sizes {
            v: finals
                .iter()
                .zip(&s.bodies)
                .map(|(f, b)| inf(&b.v).max(inf(&f.v)))
                .collect(),
            w: finals
                .iter()
                .zip(&s.bodies)
                .map(|(f, b)| inf(&b.w).max(inf(&f.w)))
                .collect(),
            lever: s.bodies.iter().map(|b| inf(&b.r)).collect(),
            m: s.bodies.iter().map(|b| b.m.to_f64()).collect(),
            inv_i: s
                .bodies
                .iter()
                .map(|b| b.inverse.iter().map(inf).fold(0.0, f64::max))
                .collect(),
            p: inf(&sol.p),
            couple: sol.kappa.to_f64().abs() * norm,
            pn: sol.pn.to_f64() / norm,
            pn_c: pn_c / norm,
            norm,
            t_initial: s.t_initial.to_f64(),
            t_final: t_final.to_f64(),
            t_max: t_max.to_f64(),
            kappa: condition(s, self.twist.is_some()),
        };
        Ok(Eval {
            regime,
            torsional: match z {
                Zb::Off => None,
                Zb::Rest => Some("restitution"),
                Zb::Slide => Some("sliding"),
            },
            outs,
            critical,
            sizes,
            inside_margin,
            critical_margin,
        })
    }
}

/// `max |x_i|` in f64.
fn inf(x: &V3) -> f64 {
    x.iter().map(|c| c.to_f64().abs()).fold(0.0, f64::max)
}

/// The condition number (Frobenius norms) of the contact matrix `𝒲̃`
/// (3×3, or 4×4 with a twist law) after Jacobi scaling `D 𝒲̃ D`,
/// `D = diag(1/√𝒲̃_ii)`: free of units, in f64.
fn condition(s: &Scene, twist: bool) -> f64 {
    let n = if twist { 4 } else { 3 };
    let d: Vec<f64> = (0..n).map(|i| 1.0 / s.resp[i][i].to_f64().sqrt()).collect();
    let a: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| s.resp[i][j].to_f64() * d[i] * d[j]).collect())
        .collect();
    let norm = |m: &Vec<Vec<f64>>| m.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    // Inverse by Gauss–Jordan in f64 (a measurement only).
    let mut aug: Vec<Vec<f64>> = a
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut r = row.clone();
            r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
            r
        })
        .collect();
    for col in 0..n {
        let p = (col..n)
            .max_by(|&x, &y| aug[x][col].abs().total_cmp(&aug[y][col].abs()))
            .unwrap();
        aug.swap(col, p);
        let pivot = aug[col][col];
        for c in 0..2 * n {
            aug[col][c] /= pivot;
        }
        for r in 0..n {
            if r != col {
                let factor = aug[r][col];
                for c in 0..2 * n {
                    aug[r][c] -= factor * aug[col][c];
                }
            }
        }
    }
    let inv: Vec<Vec<f64>> = aug.iter().map(|r| r[n..].to_vec()).collect();
    (norm(&a) * norm(&inv)).max(1.0)
}

/// One expected output: `x √y` with `x` between `lo` and `hi` (equal when exact).
#[derive(Clone, Debug)]
pub struct Expect {
    pub name: String,
    pub lo: Q,
    pub hi: Q,
    pub y: Q,
    /// [`Expect::value`], once asked for (a rational square root to 2⁻¹⁹⁹
    /// is most of what measuring an output costs).
    value: std::sync::OnceLock<Q>,
}

impl Expect {
    pub fn exact(&self) -> bool {
        self.lo == self.hi
    }

    /// The reference value (the lower evaluation) to 2⁻¹⁹⁹.
    pub fn value(&self) -> &Q {
        self.value.get_or_init(|| {
            if self.y == Q::one() {
                self.lo.clone()
            } else {
                &self.lo * sqrt_lower(&self.y)
            }
        })
    }

    /// The reference value, approximately.
    pub fn approx(&self) -> f64 {
        to_f64(self.value())
    }
}

/// The reference's answer.
#[derive(Clone, Debug)]
pub struct Answer {
    pub regime: &'static str,
    pub torsional: Option<&'static str>,
    pub outs: Vec<Expect>,
    pub critical: Option<Expect>,
    /// Whether a root was needed (the answer is then known to 2⁻¹⁹⁹).
    pub rooted: bool,
    pub sizes: Sizes,
    /// The smallest margin of the decisions inside the answer's solution
    /// (the sliding direction from zero slip, the twist's sign from zero
    /// spin), and inside the sticking solution behind `μ_c`: a tie there
    /// changes the outputs but not the regimes.
    pub inside_margin: f64,
    pub critical_margin: f64,
}

/// The reference's verdict on one contact.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Reference {
    Answer(Answer),
    Refused(Refusal),
    /// The two bounds of a root decide a branch or a refusal differently:
    /// a decision exactly at (or within 2⁻¹⁹⁹ of) its tie.
    Undecided,
}

/// The verdict and the smallest relative margin of any decision it took.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub reference: Reference,
    pub margin: f64,
}

/// One evaluation with every root at `mode`'s bound, starting from the
/// root-free solutions of an earlier one. Returns the answer, whether a
/// root was taken, the smallest margin, and the root-free solutions.
fn evaluate(
    scene: &Scene,
    impact: &SpatialImpact,
    mode: Mode,
    t_max: &R,
    known: Cache,
) -> (Result<Eval, Refusal>, bool, f64, Cache) {
    let mut ev = Evaluator {
        s: scene,
        law: Reading::of(&impact.law),
        twist: impact.torsion.map(|t| TwistR {
            ez: r(t.restitution),
            muz: r(t.friction),
            rho: r(t.pitch_radius),
        }),
        mode,
        cache: known,
        rooted: false,
        depends: false,
        t_max: t_max.clone(),
        margin: f64::INFINITY,
        local: f64::INFINITY,
    };
    let result = ev.run();
    let known = ev.cache.into_iter().filter(|c| !c.2).collect();
    (result, ev.rooted, ev.margin, known)
}

fn expect(name: String, lo: &R, hi: &R, y: &R) -> Expect {
    Expect {
        name,
        lo: lo.q(),
        hi: hi.q(),
        y: y.q(),
        value: std::sync::OnceLock::new(),
    }
}

/// Solves `impact` (its scene already built) exactly, or to 2⁻¹⁹⁹ where it slides.
pub fn solve_scene(scene: &Scene, impact: &SpatialImpact) -> Verdict {
    let t_max = scene.max_loss(impact.torsion.is_some());
    let (lower, rooted, margin, known) = evaluate(scene, impact, Mode::Lower, &t_max, Vec::new());
    let upper = if rooted {
        Some(evaluate(scene, impact, Mode::Upper, &t_max, known).0)
    } else {
        None
    };
    let reference = match (lower, upper) {
        (Err(r), None) => Reference::Refused(r),
        (Err(r), Some(Err(r2))) if r == r2 => Reference::Refused(r),
        (Ok(a), None) => Reference::Answer(Answer {
            regime: a.regime,
            torsional: a.torsional,
            outs: a
                .outs
                .iter()
                .map(|o| expect(o.name.clone(), &o.x, &o.x, &o.y))
                .collect(),
            critical: a
                .critical
                .map(|(x, y)| expect("critical_impulse_ratio".into(), &x, &x, &y)),
            rooted: false,
            sizes: a.sizes,
            inside_margin: a.inside_margin,
            critical_margin: a.critical_margin,
        }),
        (Ok(a), Some(Ok(b))) if a.regime == b.regime && a.torsional == b.torsional => {
            let outs = a
                .outs
                .iter()
                .zip(&b.outs)
                .map(|(o, p)| {
                    assert!(o.name == p.name && o.y == p.y);
                    expect(o.name.clone(), &o.x, &p.x, &o.y)
                })
                .collect();
            let critical = match (a.critical, b.critical) {
                (Some((x, y)), Some((x2, y2))) => {
                    assert!(y == y2);
                    Some(expect("critical_impulse_ratio".into(), &x, &x2, &y))
                }
                (None, None) => None,
                _ => {
                    return Verdict {
                        reference: Reference::Undecided,
                        margin,
                    };
                }
            };
            Reference::Answer(Answer {
                regime: a.regime,
                torsional: a.torsional,
                outs,
                critical,
                rooted: true,
                sizes: a.sizes,
                inside_margin: a.inside_margin.min(b.inside_margin),
                critical_margin: a.critical_margin.min(b.critical_margin),
            })
        }
        _ => Reference::Undecided,
    };
    Verdict { reference, margin }
}

/// Solves `impact`; `None` when a tensor is not positive definite.
pub fn solve(impact: &SpatialImpact) -> Option<Verdict> {
    Scene::new(impact).map(|s| solve_scene(&s, impact))
}

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

/// The double nearest `x √y` (ties to even; `+0.0` for 0), found by the exact test.
pub fn round_sqrt(x: &Q, y: &Q) -> f64 {
    if x.is_zero() || y.is_zero() {
        return 0.0;
    }
    let guess = if y == &Q::one() {
        to_f64(x)
    } else {
        to_f64(&(x * sqrt_lower(y)))
    };
    round_sqrt_near(guess, x, y)
}

/// The double nearest `x √y` (`x √y ≠ 0`), within two ulps of `guess`:
/// tried from `guess` outwards, since one double only is correctly rounded
/// and the guess is most often it (each try compares squares of rationals).
fn round_sqrt_near(guess: f64, x: &Q, y: &Q) -> f64 {
    let (down, up) = (next_down(guess), next_up(guess));
    [guess, down, up, next_down(down), next_up(up)]
        .into_iter()
        .find(|&c| is_correctly_rounded_sqrt(c, x, y))
        .unwrap_or_else(|| panic!("no double rounds {x} √{y}"))
}

/// How an `exact` output compares with its expectation.
#[derive(Clone, Debug, PartialEq)]
pub enum Check {
    Pass,
    Fail(String),
    /// The interval of a sliding answer straddles a rounding boundary.
    Straddles,
}

pub fn check(got: f64, e: &Expect) -> Check {
    if e.exact() {
        if is_correctly_rounded_sqrt(got, &e.lo, &e.y) {
            Check::Pass
        } else {
            Check::Fail(format!(
                "{}: got {got:e}, want {:e} (x = {}, y = {})",
                e.name,
                round_sqrt(&e.lo, &e.y),
                Q::new(e.lo.numer().clone(), e.lo.denom().clone()),
                Q::new(e.y.numer().clone(), e.y.denom().clone()),
            ))
        }
    } else {
        // Both within two ulps of the lower value (`hi − lo ≤ 2⁻¹⁹⁹ lo`).
        let (a, b) = if e.lo.is_zero() || e.y.is_zero() {
            (round_sqrt(&e.lo, &e.y), round_sqrt(&e.hi, &e.y))
        } else {
            let guess = e.approx();
            (
                round_sqrt_near(guess, &e.lo, &e.y),
                round_sqrt_near(guess, &e.hi, &e.y),
            )
        };
        if a.to_bits() != b.to_bits() {
            Check::Straddles
        } else if got.to_bits() == a.to_bits() {
            Check::Pass
        } else {
            Check::Fail(format!("{}: got {got:e}, want {a:e} (to 2⁻¹⁹⁹)", e.name))
        }
    }
}
