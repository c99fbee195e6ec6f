//! `fast` precision takes every decision exactly: the regime at
//! each switch, the torsional branch, `D > 0`, `T_L ≥ 0`, approaching or not.
//!
//! The adversarial sets: for random scenes of every case and law, and for each
//! coefficient or velocity a switch depends on, the switch is found in exact
//! arithmetic by bisection over the doubles (two adjacent doubles on which
//! the exact regime or refusal differs), and the doubles within `REACH` ulps
//! either side of it are solved in `fast` and in `exact` precision: the
//! regime (and torsional branch) or refusal must be the same, every time.
//! The test counts how many of those points the plain f64 evaluation (without
//! the filter) decides the other way, and asserts there are some: the sets do
//! reach the ties the filter exists for.

use crate::common::Rng;
use crate::common::sweep_rows::sweep_is_single_solves;
use restitution::impact::{Arithmetic, solve_in};
use restitution::{
    BarrierImpact, BodiesImpact, Case, Contact, Input, Lamina, Law, Outputs, PlanarContact, PlanarVelocity,
    RigidBody, SpatialContact, SpatialImpact, TorsionalImpact, Twist,
};

/// How many doubles either side of a switch are checked.
const REACH: i128 = 3;

/// A double's place in the total order of doubles (adjacent doubles differ by one).
fn key(x: f64) -> i128 {
    let b = x.to_bits() as i64;
    i128::from(b ^ (((b >> 63) as u64) >> 1) as i64)
}

/// The double at a place in the total order ([`key`]'s inverse).
fn from_key(k: i128) -> f64 {
    let k = k as i64;
    f64::from_bits((k ^ (((k >> 63) as u64) >> 1) as i64) as u64)
}

/// What a case's answer decided: its regime(s), or the refusal's kind.
trait Decided: Case {
    fn decided(result: &restitution::Result<Self::Outcome>) -> String;
}

/// The regime an answer took, or its refusal's kind.
fn decided_by<O>(r: &restitution::Result<O>, regime: impl Fn(&O) -> String) -> String {
    r.as_ref().map(regime).unwrap_or_else(|e| e.slug().to_string())
}

impl Decided for BarrierImpact {
    fn decided(r: &restitution::Result<Self::Outcome>) -> String {
        decided_by(r, |o| o.regime.as_str().to_string())
    }
}

impl Decided for TorsionalImpact {
    fn decided(r: &restitution::Result<Self::Outcome>) -> String {
        decided_by(r, |o| o.regime.as_str().to_string())
    }
}

impl Decided for BodiesImpact {
    fn decided(r: &restitution::Result<Self::Outcome>) -> String {
        decided_by(r, |o| o.regime.as_str().to_string())
    }
}

impl Decided for SpatialImpact {
    fn decided(r: &restitution::Result<Self::Outcome>) -> String {
        decided_by(r, |o| {
            format!(
                "{}/{:?}",
                o.regime.as_str(),
                o.torsional_regime.map(|t| t.as_str())
            )
        })
    }
}

#[derive(Default, Debug)]
struct Tally {
    /// Switches found by bisection.
    switches: usize,
    /// Points solved in both precisions around them.
    points: usize,
    /// Of those, where plain f64 (no filter) decides unlike `exact`.
    plain_wrong: usize,
}

fn with<C: Case>(base: &C, input: Input, x: f64) -> C {
    let mut impact = *base;
    *impact.input_mut(input).expect("the impact reads the input") = x;
    impact
}

fn decide<C: Decided>(impact: &C, arithmetic: Arithmetic) -> String {
    C::decided(&solve_in(impact, Outputs::ALL, arithmetic).0)
}

/// Finds a switch of the exact decision for `input` in `[lo, hi]` by
/// bisection, then asserts that `fast` decides as `exact` on the doubles
/// around it.
fn check_switch<C: Decided>(base: &C, input: Input, lo: f64, hi: f64, tally: &mut Tally) {
    let at = |x: f64, arithmetic| decide(&with(base, input, x), arithmetic);
    let exact_at = |x: f64| at(x, Arithmetic::Exact);
    let class_lo = exact_at(lo);
    if class_lo == exact_at(hi) {
        return;
    }
    // Narrow the interval with the cheap plain f64 decisions first (its switch
    // is near the exact one), keeping it only if exact arithmetic confirms
    // the switch inside; then bisect in exact arithmetic.
    let (mut a, mut b) = (key(lo), key(hi));
    let plain_lo = at(lo, Arithmetic::Unfiltered);
    let (mut pa, mut pb) = (a, b);
    while pb - pa > 1 {
        let mid = pa + (pb - pa) / 2;
        if at(from_key(mid), Arithmetic::Unfiltered) == plain_lo {
            pa = mid;
        } else {
            pb = mid;
        }
    }
    let (wa, wb) = ((pa - (1 << 16)).max(a), (pb + (1 << 16)).min(b));
    if exact_at(from_key(wa)) == class_lo && exact_at(from_key(wb)) != class_lo {
        (a, b) = (wa, wb);
    }
    while b - a > 1 {
        let mid = a + (b - a) / 2;
        if exact_at(from_key(mid)) == class_lo {
            a = mid;
        } else {
            b = mid;
        }
    }
    tally.switches += 1;
    // The same doubles through a sweep: its rows are the single solves.
    let around: Vec<f64> = ((a - REACH + 1)..=(b + REACH - 1)).map(from_key).collect();
    sweep_is_single_solves(base, input, &around);
    for k in (a - REACH + 1)..=(b + REACH - 1) {
        let impact = with(base, input, from_key(k));
        let exact = decide(&impact, Arithmetic::Exact);
        let fast = decide(&impact, Arithmetic::Fast);
        assert_eq!(
            fast,
            exact,
            "{input:?} = {:e} (switch between {:e} and {:e}): {impact:?}",
            from_key(k),
            from_key(a),
            from_key(b)
        );
        tally.points += 1;
        tally.plain_wrong += usize::from(decide(&impact, Arithmetic::Unfiltered) != exact);
    }
}

/// A small dyadic number (ties and exact zeros) or a general one.
fn draw(rng: &mut Rng, lo: f64, hi: f64, dyadic: bool) -> f64 {
    let x = rng.range(lo, hi);
    if dyadic { (x * 8.0).round() / 8.0 } else { x }
}

fn lamina(rng: &mut Rng, dyadic: bool, law: Law) -> BarrierImpact {
    let mass = draw(rng, 0.5, 4.0, dyadic).max(0.125);
    let k2 = draw(rng, 0.1, 2.0, dyadic).max(0.125);
    BarrierImpact::rigid(
        mass,
        mass * k2,
        Contact {
            tangential_offset: draw(rng, -1.5, 1.5, dyadic),
            normal_offset: draw(rng, -1.5, 1.5, dyadic),
        },
        PlanarVelocity {
            normal: -draw(rng, 0.5, 5.0, dyadic).max(0.125),
            tangential: draw(rng, -5.0, 5.0, dyadic),
            angular: draw(rng, -3.0, 3.0, dyadic),
        },
        law,
    )
}

#[test]
fn fast_decides_every_planar_switch_exactly() {
    let mut rng = Rng::new(0xdec1_5105);
    let mut tally = Tally::default();
    for n in 0..60 {
        let dyadic = n % 2 == 0;
        let e = draw(&mut rng, 0.0, 1.0, dyadic);
        let f = draw(&mut rng, 0.0, 1.0, dyadic);
        let friction = lamina(
            &mut rng,
            dyadic,
            Law::Friction {
                restitution: e,
                friction: f,
            },
        );
        // Sliding/sticking at f = |μ_c|; the slip direction and approach with ω.
        check_switch(&friction, Input::Friction, 0.0, 20.0, &mut tally);
        check_switch(&friction, Input::AngularVelocity, -50.0, 50.0, &mut tally);
        check_switch(&friction, Input::TangentialVelocity, -50.0, 50.0, &mut tally);
        let e_t = draw(&mut rng, -1.0, 1.0, dyadic);
        let bilinear = lamina(
            &mut rng,
            dyadic,
            Law::TangentialRestitution {
                restitution: e,
                friction: f,
                tangential_restitution: e_t,
            },
        );
        // The bilinear switch in f and in e_t, and in the velocities (whose
        // sweeps evaluate points in lanes, lanes that disagree included).
        check_switch(&bilinear, Input::Friction, 0.0, 20.0, &mut tally);
        check_switch(&bilinear, Input::TangentialRestitution, -1.0, 1.0, &mut tally);
        check_switch(&bilinear, Input::AngularVelocity, -50.0, 50.0, &mut tally);
        check_switch(&bilinear, Input::TangentialVelocity, -50.0, 50.0, &mut tally);
        let ratio = lamina(
            &mut rng,
            dyadic,
            Law::ImpulseRatio {
                restitution: e,
                impulse_ratio: 0.0,
            },
        );
        // The admissible interval's ends (D > 0, T_L ≥ 0).
        check_switch(&ratio, Input::ImpulseRatio, 0.0, 1e3, &mut tally);
        check_switch(&ratio, Input::ImpulseRatio, -1e3, 0.0, &mut tally);
        let approach = draw(&mut rng, -0.5, 0.5, dyadic);
        let kinetic = lamina(
            &mut rng,
            dyadic,
            Law::KineticRestitution {
                value: e,
                approach_impulse_ratio: approach,
                rebound_impulse_ratio: 0.0,
            },
        );
        check_switch(&kinetic, Input::ReboundImpulseRatio, 0.0, 1e3, &mut tally);
        check_switch(&kinetic, Input::ReboundImpulseRatio, -1e3, 0.0, &mut tally);
        check_switch(&kinetic, Input::ApproachImpulseRatio, -1e3, 1e3, &mut tally);
        check_switch(&kinetic, Input::AngularVelocity, -50.0, 50.0, &mut tally);
    }
    eprintln!("planar: {tally:?}");
    assert!(tally.switches > 300, "{tally:?}");
    assert!(
        tally.plain_wrong > 0,
        "the sets never reach a tie f64 gets wrong: {tally:?}"
    );
}

#[test]
fn fast_decides_the_torsional_branch_exactly() {
    let mut rng = Rng::new(0x7015);
    let mut tally = Tally::default();
    for n in 0..150 {
        let dyadic = n % 2 == 0;
        let impact = TorsionalImpact {
            mass: draw(&mut rng, 0.5, 4.0, dyadic).max(0.125),
            normal_inertia: draw(&mut rng, 0.1, 2.0, dyadic).max(0.125),
            normal_velocity: -draw(&mut rng, 0.5, 5.0, dyadic).max(0.125),
            spin: draw(&mut rng, -30.0, 30.0, dyadic),
            restitution: draw(&mut rng, 0.0, 1.0, dyadic),
            torsional_restitution: draw(&mut rng, 0.0, 1.0, dyadic),
            torsional_friction: draw(&mut rng, 0.0, 1.0, dyadic),
            pitch_radius: draw(&mut rng, 0.01, 0.5, dyadic).max(0.125),
        };
        check_switch(&impact, Input::TorsionalFriction, 0.0, 50.0, &mut tally);
        check_switch(&impact, Input::Spin, 0.0, 1e3, &mut tally);
        check_switch(&impact, Input::Spin, -1e3, 0.0, &mut tally);
    }
    eprintln!("torsional: {tally:?}");
    assert!(tally.switches > 150, "{tally:?}");
}

/// Coulomb friction, or (every third scene) the bilinear law, with `f = 0.3`.
fn contact_law(rng: &mut Rng, n: usize, dyadic: bool) -> Law {
    let restitution = draw(rng, 0.0, 1.0, dyadic);
    if n % 3 == 0 {
        Law::TangentialRestitution {
            restitution,
            friction: 0.3,
            tangential_restitution: draw(rng, -1.0, 1.0, dyadic),
        }
    } else {
        Law::Friction {
            restitution,
            friction: 0.3,
        }
    }
}

fn body2(rng: &mut Rng, dyadic: bool, x: f64) -> Lamina {
    let mass = draw(rng, 0.5, 4.0, dyadic).max(0.125);
    Lamina {
        mass,
        inertia: mass * draw(rng, 0.1, 2.0, dyadic).max(0.125),
        position: [x, draw(rng, -1.0, 1.0, dyadic)],
        velocity: [draw(rng, -5.0, 5.0, dyadic), draw(rng, -5.0, 5.0, dyadic)],
        angular_velocity: draw(rng, -3.0, 3.0, dyadic),
    }
}

#[test]
fn fast_decides_two_body_switches_exactly() {
    let mut rng = Rng::new(0xb0d1e5);
    let mut tally = Tally::default();
    for n in 0..60 {
        let dyadic = n % 2 == 0;
        let law = contact_law(&mut rng, n, dyadic);
        let mut a = body2(&mut rng, dyadic, -1.0);
        let b = body2(&mut rng, dyadic, 1.0);
        // A approaches B along x.
        a.velocity[0] = b.velocity[0] + draw(&mut rng, 1.0, 6.0, dyadic);
        let impact = BodiesImpact {
            a,
            b: Some(b),
            contact: PlanarContact {
                point: [0.0, draw(&mut rng, -0.5, 0.5, dyadic)],
                normal: [-1.0, draw(&mut rng, -0.5, 0.5, dyadic)],
            },
            law,
        };
        check_switch(&impact, Input::Friction, 0.0, 20.0, &mut tally);
        check_switch(&impact, Input::AngularVelocityA, -50.0, 50.0, &mut tally);
        check_switch(&impact, Input::VelocityAY, -50.0, 50.0, &mut tally);
    }
    eprintln!("two bodies: {tally:?}");
    assert!(tally.switches > 60, "{tally:?}");
}

fn body3(rng: &mut Rng, dyadic: bool, z: f64) -> RigidBody {
    let mass = draw(rng, 0.5, 4.0, dyadic).max(0.125);
    let i = [0, 1, 2].map(|_| mass * draw(rng, 0.2, 1.0, dyadic).max(0.125));
    let v = |rng: &mut Rng| [0, 1, 2].map(|_| draw(rng, -3.0, 3.0, dyadic));
    RigidBody {
        mass,
        inertia: [i[0], i[1], i[2], 0.0, 0.0, 0.0],
        position: [draw(rng, -0.5, 0.5, dyadic), draw(rng, -0.5, 0.5, dyadic), z],
        velocity: v(rng),
        angular_velocity: v(rng),
    }
}

#[test]
fn fast_decides_spatial_switches_exactly() {
    let mut rng = Rng::new(0x05ba_71a1);
    let mut tally = Tally::default();
    for n in 0..40 {
        let dyadic = n % 2 == 0;
        let law = contact_law(&mut rng, n, dyadic);
        let mut a = body3(&mut rng, dyadic, 1.0);
        let b = (n % 2 == 1).then(|| body3(&mut rng, dyadic, -1.0));
        // A approaches along −z.
        a.velocity[2] = b.map_or(0.0, |b| b.velocity[2]) - draw(&mut rng, 1.0, 6.0, dyadic);
        let torsion = (n % 4 < 2).then(|| Twist {
            restitution: draw(&mut rng, 0.0, 1.0, dyadic),
            friction: draw(&mut rng, 0.0, 0.5, dyadic),
            pitch_radius: 0.25,
        });
        let impact = SpatialImpact {
            a,
            b,
            contact: SpatialContact {
                point: [0.0, 0.0, 0.0],
                normal: [
                    draw(&mut rng, -0.3, 0.3, dyadic),
                    draw(&mut rng, -0.3, 0.3, dyadic),
                    1.0,
                ],
            },
            law,
            torsion,
        };
        check_switch(&impact, Input::Friction, 0.0, 20.0, &mut tally);
        if torsion.is_some() {
            check_switch(&impact, Input::TorsionalFriction, 0.0, 20.0, &mut tally);
        }
        check_switch(&impact, Input::AngularVelocityAX, -50.0, 50.0, &mut tally);
    }
    eprintln!("spatial: {tally:?}");
    assert!(tally.switches > 40, "{tally:?}");
}
