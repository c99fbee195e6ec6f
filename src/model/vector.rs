//! Small vectors and symmetric 3×3 matrices over any [`Field`], for the
//! contact in space.

use crate::arith::Field;

pub(super) type V3<N> = [N; 3];

#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn vector<N: Field>(x: [f64; 3]) -> V3<N> {
    [N::of(x[0]), N::of(x[1]), N::of(x[2])]
}

/// The vector `x(i)` of each lane `i` (in a field of one point, [`vector`]
/// of `x(0)`).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn lanes_vector<N: Field>(x: impl Fn(usize) -> [f64; 3]) -> V3<N> {
    [
        N::of_lanes(|i| x(i)[0]),
        N::of_lanes(|i| x(i)[1]),
        N::of_lanes(|i| x(i)[2]),
    ]
}

#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn dot<N: Field>(a: &V3<N>, b: &V3<N>) -> N {
    a[0].mul_add(&b[0], &a[1].mul_add(&b[1], &a[2].mul(&b[2])))
}

#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn cross<N: Field>(a: &V3<N>, b: &V3<N>) -> V3<N> {
    [
        a[1].mul_add(&b[2], &a[2].mul(&b[1]).neg()),
        a[2].mul_add(&b[0], &a[0].mul(&b[2]).neg()),
        a[0].mul_add(&b[1], &a[1].mul(&b[0]).neg()),
    ]
}

/// `f` applied to each component. `f` is a closure marked
/// `#[inline(always)]` (in an optimised build): unmarked, a closure called three times is a function
/// of its own to the compiler, which may leave it out of line, and then out
/// of the compiled copy that runs (`crate::kernels`; nine such closures of the
/// spatial model, unmarked, made two bodies in space 4–6 % slower in `fast`
/// and one body 7–8 % in `exact`: `benches/scripts/solve-cost`,
/// docs/performance-log.md, 2026-11-29). Which ones the compiler leaves out moves
/// other inlining too: marking one more (the two-phase law's sliding
/// approach) made one body in `fast` 4 % slower, so it is left unmarked.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn map<N: Field>(a: &V3<N>, f: impl Fn(&N) -> N) -> V3<N> {
    [f(&a[0]), f(&a[1]), f(&a[2])]
}

/// `f` applied to each pair of components; `f` as in [`map`].
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn zip<N: Field>(a: &V3<N>, b: &V3<N>, f: impl Fn(&N, &N) -> N) -> V3<N> {
    [f(&a[0], &b[0]), f(&a[1], &b[1]), f(&a[2], &b[2])]
}

// The common maps below are written out rather than through `map` and
// `zip`, for the reason given at `map`.

/// `k a + b`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn axpy<N: Field>(k: &N, a: &V3<N>, b: &V3<N>) -> V3<N> {
    [
        k.mul_add(&a[0], &b[0]),
        k.mul_add(&a[1], &b[1]),
        k.mul_add(&a[2], &b[2]),
    ]
}

/// `a + b`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn add<N: Field>(a: &V3<N>, b: &V3<N>) -> V3<N> {
    [a[0].add(&b[0]), a[1].add(&b[1]), a[2].add(&b[2])]
}

/// `a − b`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn sub<N: Field>(a: &V3<N>, b: &V3<N>) -> V3<N> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

/// `−a`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn neg<N: Field>(a: &V3<N>) -> V3<N> {
    [a[0].neg(), a[1].neg(), a[2].neg()]
}

/// `k a`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn scale<N: Field>(k: &N, a: &V3<N>) -> V3<N> {
    [k.mul(&a[0]), k.mul(&a[1]), k.mul(&a[2])]
}

/// `a / d`, each component divided.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn divide<N: Field>(a: &V3<N>, d: &N) -> V3<N> {
    [a[0].div(d), a[1].div(d), a[2].div(d)]
}

/// A symmetric 3×3 matrix as `[xx, yy, zz, xy, xz, yz]`.
pub(super) type Sym<N> = [N; 6];

/// A tensor of f64 inputs, exactly.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn sym<N: Field>(m: &[f64; 6]) -> Sym<N> {
    [
        N::of(m[0]),
        N::of(m[1]),
        N::of(m[2]),
        N::of(m[3]),
        N::of(m[4]),
        N::of(m[5]),
    ]
}

/// `m k`, each entry multiplied.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn sym_times<N: Field>(m: &Sym<N>, k: &N) -> Sym<N> {
    [
        m[0].mul(k),
        m[1].mul(k),
        m[2].mul(k),
        m[3].mul(k),
        m[4].mul(k),
        m[5].mul(k),
    ]
}

#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn sym_mul<N: Field>(m: &Sym<N>, x: &V3<N>) -> V3<N> {
    let [xx, yy, zz, xy, xz, yz] = m;
    [
        xx.mul_add(&x[0], &xy.mul_add(&x[1], &xz.mul(&x[2]))),
        xy.mul_add(&x[0], &yy.mul_add(&x[1], &yz.mul(&x[2]))),
        xz.mul_add(&x[0], &yz.mul_add(&x[1], &zz.mul(&x[2]))),
    ]
}

/// The adjugate and the determinant of a symmetric matrix.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn adjugate<N: Field>(m: &Sym<N>) -> (Sym<N>, N) {
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

/// `v + ω × r`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn point_velocity<N: Field>(v: &V3<N>, w: &V3<N>, r: &V3<N>) -> V3<N> {
    add(v, &cross(w, r))
}

/// `|x|²` of a vector `x`.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn norm2<N: Field>(x: &V3<N>) -> N {
    dot(x, x)
}
