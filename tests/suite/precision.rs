//! Numerical stress suite for both precision modes against the exact rational
//! reference (testkit/src/reference.rs, Gaussian elimination, shares no code
//! with the solver).
//!
//! - `exact`: every output is the correctly rounded f64 of the reference value
//!   (checked by placing the reference between the rounding midpoints around the
//!   answer, in rationals), every regime and refusal is the reference's, an exact
//!   zero is `+0.0`, and an overflow refusal names an output whose exact value
//!   really rounds beyond `f64::MAX`.
//! - `fast`: never NaN, infinity or a panic; answers within [`BOUND_ULPS`] of the
//!   scale of the terms each output combines (testkit/src/accuracy.rs); regimes
//!   and refusals the reference's, on the decision boundaries too.
//!
//! The sets: magnitudes 1e-300…1e300 in every input, mixed scales, D near, at
//! and below 0, grazing and near-normal impacts, e at 0, 1 and 1 − 1e-12, μ and
//! f at and one ulp from μ_c and the bilinear switch, and results that are
//! exactly zero. `report_*` (ignored) runs a larger grid and prints the tables.

use crate::common::Rng;
use crate::common::accuracy::{
    BOUND_ULPS, Errors, Inputs, PromiseTally, check_promise, compare, kappa, refusal_kind,
};
use crate::common::reference::{self as reference, Outcome, Q, Refusal, q};
use num_traits::{Signed, Zero};
use restitution::impact::{Arithmetic, Stage, solve_in};
use restitution::{
    BarrierImpact, BarrierOutcome, Contact, ImpactError, Output, Outputs, PlanarVelocity, Precision, Regime,
    TorsionalImpact, solve,
};

/// A planar law with its coefficients.
#[derive(Clone, Copy, Debug)]
enum Law {
    Frictionless,
    Ratio(f64),
    Friction(f64),
    Tangential(f64, f64),
    Kinetic(f64, f64, f64),
}

#[derive(Clone, Copy, Debug)]
struct Case {
    inp: Inputs,
    e: f64,
    law: Law,
}

impl Case {
    fn impact(&self) -> BarrierImpact {
        let i = &self.inp;
        let restitution = self.e;
        let law = match self.law {
            Law::Frictionless => restitution::Law::Frictionless { restitution },
            Law::Ratio(impulse_ratio) => restitution::Law::ImpulseRatio {
                restitution,
                impulse_ratio,
            },
            Law::Friction(friction) => restitution::Law::Friction {
                restitution,
                friction,
            },
            Law::Tangential(friction, tangential_restitution) => restitution::Law::TangentialRestitution {
                restitution,
                friction,
                tangential_restitution,
            },
            Law::Kinetic(value, approach_impulse_ratio, rebound_impulse_ratio) => {
                restitution::Law::KineticRestitution {
                    value,
                    approach_impulse_ratio,
                    rebound_impulse_ratio,
                }
            }
        };
        BarrierImpact::rigid(
            i.m,
            i.inertia,
            Contact {
                tangential_offset: i.dc,
                normal_offset: i.dd,
            },
            PlanarVelocity {
                normal: i.vn,
                tangential: i.vt,
                angular: i.w,
            },
            law,
        )
    }

    fn is_finite(&self) -> bool {
        let i = &self.inp;
        let law = match self.law {
            Law::Frictionless => vec![],
            Law::Ratio(a) | Law::Friction(a) => vec![a],
            Law::Tangential(a, b) => vec![a, b],
            Law::Kinetic(a, b, c) => vec![a, b, c],
        };
        [i.m, i.inertia, i.dc, i.dd, i.vn, i.vt, i.w, self.e]
            .into_iter()
            .chain(law)
            .all(f64::is_finite)
    }

    fn reference(&self) -> Result<Outcome, Refusal> {
        let s = self.inp.exact();
        match self.law {
            Law::Frictionless => reference::frictionless(&s, self.e),
            Law::Ratio(mu) => reference::prescribed(&s, self.e, mu),
            Law::Friction(f) => reference::bilinear(&s, self.e, f, 0.0, "sticking"),
            Law::Tangential(f, et) => reference::bilinear(&s, self.e, f, et, "restitution"),
            Law::Kinetic(r, a, b) => reference::kinetic(&s, r, a, b),
        }
    }
}

/// Whether `x` is the f64 nearest to `exact` (either neighbour at an exact tie).
fn correctly_rounded(x: f64, exact: &Q) -> bool {
    if !x.is_finite() {
        return false;
    }
    if exact.is_zero() && x.is_sign_negative() {
        return false; // an exact zero is +0.0
    }
    let (down, up) = (x.next_down(), x.next_up());
    let gap_down = if down.is_finite() {
        q(x) - q(down)
    } else {
        q(up) - q(x)
    };
    let gap_up = if up.is_finite() {
        q(up) - q(x)
    } else {
        q(x) - q(down)
    };
    let half = q(0.5);
    let low = q(x) - &half * gap_down;
    let high = q(x) + half * gap_up;
    &low <= exact && exact <= &high
}

/// Whether an exact value rounds beyond the largest double.
fn overflows(exact: &Q) -> bool {
    exact.abs() >= q(f64::MAX) + q(2f64.powi(970))
}

/// Every planar output of an answer with its reference value.
fn planar_outputs(o: &BarrierOutcome, r: &Outcome, inp: &Inputs) -> Vec<(&'static str, f64, Q)> {
    let s = inp.exact();
    let energy = o.energy.expect("energies requested");
    let mut list = vec![
        ("V_n", o.final_velocity.normal, r.vn.clone()),
        ("V_t", o.final_velocity.tangential, r.vt.clone()),
        ("Ω", o.final_velocity.angular, r.w.clone()),
        ("v_cn", o.contact_velocity.initial.normal, s.vcn()),
        ("v_ct", o.contact_velocity.initial.tangential, s.vct()),
        ("V_cn", o.contact_velocity.r#final.normal, r.vcn.clone()),
        ("V_ct", o.contact_velocity.r#final.tangential, r.vct.clone()),
        ("P_n", o.impulse.normal, r.pn.clone()),
        ("P_t", o.impulse.tangential, r.pt.clone()),
        ("μ", o.impulse_ratio, r.mu.clone()),
        ("e", o.restitution, r.e.clone()),
        ("T_i", energy.initial, r.t_initial.clone()),
        ("T_f", energy.r#final, r.t_final.clone()),
        ("T_L", energy.loss, r.t_loss.clone()),
        ("T_M", energy.max_loss, r.t_max.clone()),
        ("T_L*", energy.normalized_loss, &r.t_loss / &r.t_max),
    ];
    if let (Some(c), Some(rc)) = (o.critical_impulse_ratio, &r.mu_c) {
        list.push(("μ_c", c, rc.clone()));
    }
    list
}

/// The reference value of one output, for overflow refusals.
fn reference_output(r: &Outcome, inp: &Inputs, output: Output) -> Option<Q> {
    Some(match output {
        Output::InitialNormalContactVelocity => inp.exact().vcn(),
        Output::InitialTangentialContactVelocity => inp.exact().vct(),
        Output::FinalNormalVelocity => r.vn.clone(),
        Output::FinalTangentialVelocity => r.vt.clone(),
        Output::FinalAngularVelocity => r.w.clone(),
        Output::FinalNormalContactVelocity => r.vcn.clone(),
        Output::FinalTangentialContactVelocity => r.vct.clone(),
        Output::NormalImpulse => r.pn.clone(),
        Output::TangentialImpulse => r.pt.clone(),
        Output::ImpulseRatio => r.mu.clone(),
        Output::CriticalImpulseRatio => r.mu_c.clone()?,
        Output::Restitution => r.e.clone(),
        Output::InitialEnergy => r.t_initial.clone(),
        Output::FinalEnergy => r.t_final.clone(),
        Output::EnergyLoss => r.t_loss.clone(),
        Output::MaxEnergyLoss => r.t_max.clone(),
        Output::NormalizedEnergyLoss => &r.t_loss / &r.t_max,
        _ => return None,
    })
}

/// Whether a refusal names an initial contact velocity that really overflows:
/// every answer carries it, so it may precede the model's own refusals.
fn initial_overflow(inp: &Inputs, output: Output) -> bool {
    match output {
        Output::InitialNormalContactVelocity => overflows(&inp.exact().vcn()),
        Output::InitialTangentialContactVelocity => overflows(&inp.exact().vct()),
        _ => false,
    }
}

/// Counts of one stress set.
#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    answered: usize,
    refused: usize,
    /// Settled by the first, compensated stage (refusals of the inputs included).
    compensated: usize,
    rational: usize,
    /// Cases of a set on a decision boundary (each decided by `fast` as the reference).
    at_boundary: usize,
    /// `fast`'s promised error, checked on every case both modes answer.
    promise: PromiseTally,
}

/// Checks both modes on one case. `boundary`: the set sits on a decision
/// boundary (counted: `fast` must decide it exactly all the same).
fn check(name: &str, case: &Case, boundary: bool, tally: &mut Tally, errors: &mut Errors) {
    let impact = case.impact();
    let reference = case.reference();
    let (exact_answer, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
    check_promise(&impact, &mut tally.promise);
    tally.cases += 1;
    tally.compensated += usize::from(stage == Stage::Compensated);
    tally.rational += usize::from(stage == Stage::Rational);
    match (&exact_answer, &reference) {
        (Ok(o), Ok(r)) => {
            tally.answered += 1;
            for (label, value, exact) in planar_outputs(o, r, &case.inp) {
                assert!(
                    correctly_rounded(value, &exact),
                    "{name}: exact {label} = {value:e} is not the rounding of {:e} for {case:?}",
                    reference::to_f64(&exact)
                );
            }
            assert_eq!(o.regime.as_str(), r.regime, "{name}: exact regime for {case:?}");
        }
        (Err(ImpactError::OutputNotFinite { output }), Ok(r)) => {
            tally.refused += 1;
            let value = reference_output(r, &case.inp, *output).expect("an output of the outcome");
            assert!(overflows(&value), "{name}: exact refused {output:?} for {case:?}");
        }
        (Err(ImpactError::OutputNotFinite { output }), Err(_)) if initial_overflow(&case.inp, *output) => {
            tally.refused += 1;
        }
        (Err(e), Err(r)) => {
            tally.refused += 1;
            assert_eq!(
                refusal_kind(e).as_ref(),
                Some(r),
                "{name}: exact refusal {e} for {case:?}"
            );
        }
        (a, r) => panic!("{name}: exact {a:?} but reference {r:?} for {case:?}"),
    }
    tally.at_boundary += usize::from(boundary);
    let fast = solve(&impact, Outputs::ALL, Precision::Fast);
    match (&fast, &reference) {
        (Ok(o), Ok(r)) => {
            errors.answered += 1;
            for (label, value, _) in planar_outputs(o, r, &case.inp) {
                assert!(value.is_finite(), "{name}: fast {label} = {value} for {case:?}");
            }
            assert_eq!(o.regime.as_str(), r.regime, "{name}: fast regime for {case:?}");
            let k = kappa(&case.inp, o.impulse_ratio);
            compare(errors, &case.inp, o, r, k);
        }
        (Err(ImpactError::OutputNotFinite { output }), Ok(r)) => {
            let value = reference_output(r, &case.inp, *output).expect("an output of the outcome");
            assert!(overflows(&value), "{name}: fast refused {output:?} for {case:?}");
        }
        (Err(e), Err(r)) if refusal_kind(e).as_ref() == Some(r) => {}
        (Ok(o), Err(Refusal::NoImpulseSolution)) => {
            panic!("{name}: fast answered {o:?} where D ≤ 0 for {case:?}")
        }
        (Err(ImpactError::OutputNotFinite { output }), Err(_)) if initial_overflow(&case.inp, *output) => {}
        (f, r) => panic!("{name}: fast {f:?} but reference {r:?} for {case:?}"),
    }
}

/// A scene with independent magnitudes `10^[lo, hi]` for mass, inertia, offsets and velocities.
fn wild_inputs(rng: &mut Rng, lo: f64, hi: f64) -> Inputs {
    let mut mag = |zero: f64| {
        if rng.chance(zero) {
            0.0
        } else {
            let sign = if rng.chance(0.5) { -1.0 } else { 1.0 };
            sign * rng.log_uniform(lo, hi)
        }
    };
    let (m, inertia) = (mag(0.0).abs(), mag(0.0).abs());
    let (dc, dd, vt, w) = (mag(0.2), mag(0.1), mag(0.1), mag(0.2));
    let vn = -mag(0.0).abs();
    Inputs {
        m,
        inertia,
        dc,
        dd,
        vn,
        vt,
        w,
    }
}

/// A scene of unit scales with random shape, as in tests/reference.rs.
fn unit_inputs(rng: &mut Rng) -> Inputs {
    let k = rng.log_uniform(-1.0, 0.5);
    let dc = if rng.chance(0.3) {
        0.0
    } else {
        rng.range(-2.0, 2.0)
    };
    let dd = if rng.chance(0.1) {
        0.0
    } else {
        rng.range(-2.0, 2.0)
    };
    let w = rng.range(-3.0, 3.0);
    let vcn = -rng.range(0.05, 2.0);
    Inputs {
        m: rng.log_uniform(-1.0, 1.0),
        inertia: k * k,
        dc,
        dd,
        vn: vcn - dc * w,
        vt: rng.range(-3.0, 3.0),
        w,
    }
}

fn random_law(rng: &mut Rng) -> Law {
    match rng.pick(&[0, 1, 2, 3, 4]) {
        0 => Law::Frictionless,
        1 => Law::Ratio(rng.range(-0.5, 0.5)),
        2 => Law::Friction(rng.range(0.0, 1.0)),
        3 => Law::Tangential(rng.range(0.0, 1.0), rng.range(-1.0, 1.0)),
        _ => Law::Kinetic(rng.unit(), rng.range(-0.3, 0.3), rng.range(-0.3, 0.3)),
    }
}

fn random_e(rng: &mut Rng) -> f64 {
    let any = rng.unit();
    rng.pick(&[0.0, 1.0, 1.0 - 1e-12, 0.5, any])
}

/// The critical ratio and the |μ| of the capped bilinear answer, from the exact mode.
fn capped_ratio(case: &Case, et: f64) -> Option<f64> {
    let probe = Case {
        law: Law::Tangential(f64::MAX, et),
        ..*case
    };
    let impact = probe.impact();
    solve(&impact, Outputs::MINIMAL, Precision::Exact)
        .ok()
        .map(|o| o.impulse_ratio)
}

/// Runs `n` cases of one set and prints its line.
fn run(name: &str, seed: u64, n: usize, boundary: bool, mut make: impl FnMut(&mut Rng) -> Case) -> Tally {
    let mut rng = Rng::new(seed);
    let mut tally = Tally::default();
    let mut errors = Errors::default();
    for _ in 0..n {
        let case = make(&mut rng);
        if !case.is_finite() {
            continue; // a generator stepped past f64::MAX (e.g. next_up of it)
        }
        check(name, &case, boundary, &mut tally, &mut errors);
    }
    println!("{name}: {tally:?}");
    if errors.answered > 0 {
        errors.assert_within(&format!("{name} (fast)"), BOUND_ULPS);
    }
    assert!(tally.cases * 2 > n, "{name}: most cases skipped");
    tally
}

fn stress_sets(scale: usize) {
    run("magnitudes 1e-300…1e300", 101, 60 * scale, false, |rng| Case {
        inp: wild_inputs(rng, -300.0, 300.0),
        e: random_e(rng),
        law: random_law(rng),
    });
    run(
        "mixed scales (heavy slow, light fast)",
        102,
        40 * scale,
        false,
        |rng| {
            let heavy = rng.chance(0.5);
            let (m, v) = if heavy { (1e200, 1e-100) } else { (1e-200, 1e100) };
            let mut inp = unit_inputs(rng);
            inp.m *= m;
            inp.inertia *= m;
            inp.vn *= v;
            inp.vt *= v;
            inp.w *= v;
            Case {
                inp,
                e: random_e(rng),
                law: random_law(rng),
            }
        },
    );
    run("D near, at and below 0", 103, 40 * scale, true, |rng| {
        let mut inp = unit_inputs(rng);
        if inp.dc == 0.0 || inp.dd == 0.0 {
            inp.dc = 0.75;
            inp.dd = 1.5;
            inp.vn = -1.0 - inp.dc * inp.w;
        }
        let k2 = inp.inertia / inp.m;
        let root = (k2 + inp.dc * inp.dc) / (inp.dc * inp.dd);
        let mu = match rng.pick(&[0, 1, 2, 3, 4]) {
            // D exactly 0: m = 1, k² = 1/4, d_c = d_d = 1, μ = 5/4.
            0 => {
                inp = Inputs {
                    m: 1.0,
                    inertia: 0.25,
                    dc: 1.0,
                    dd: 1.0,
                    vn: -2.0,
                    ..inp
                };
                1.25
            }
            1 => root * (1.0 - 1e-15),
            2 => root * (1.0 + 1e-15),
            3 => root.next_up(),
            _ => root * (1.0 - rng.pick(&[1e-12, 1e-9, -1e-12])),
        };
        Case {
            inp,
            e: random_e(rng),
            law: Law::Ratio(mu),
        }
    });
    run("grazing and near-normal", 104, 40 * scale, false, |rng| {
        let mut inp = unit_inputs(rng);
        let ratio = rng.log_uniform(-15.0, -3.0);
        if rng.chance(0.5) {
            // Grazing: |v_cn| ≪ |v_ct|.
            inp.w = 0.0;
            inp.vn = -ratio;
            inp.vt = rng.pick(&[-1.0, 1.0]) * rng.range(0.5, 2.0);
        } else {
            inp.w = 0.0;
            inp.vn = -rng.range(0.5, 2.0);
            inp.vt = ratio * rng.pick(&[-1.0, 1.0]);
        }
        Case {
            inp,
            e: random_e(rng),
            law: random_law(rng),
        }
    });
    run(
        "e at 0, 1 and 1 − 1e-12, small μ",
        105,
        40 * scale,
        false,
        |rng| Case {
            inp: unit_inputs(rng),
            e: rng.pick(&[0.0, 1.0, 1.0 - 1e-12]),
            law: {
                let mu = rng.log_uniform(-12.0, -1.0) * rng.pick(&[-1.0, 1.0]);
                let f = rng.log_uniform(-12.0, 0.0);
                rng.pick(&[Law::Frictionless, Law::Ratio(mu), Law::Friction(f)])
            },
        },
    );
    run(
        "μ and f at and one ulp from μ_c and the switch",
        106,
        40 * scale,
        true,
        |rng| {
            let mut inp = unit_inputs(rng);
            if rng.chance(0.5) {
                // Central contacts, where the bilinear models are continuous.
                inp.vn += inp.dc * inp.w;
                inp.dc = 0.0;
            }
            let mut case = Case {
                inp,
                e: random_e(rng),
                law: Law::Frictionless,
            };
            let et = rng.pick(&[0.0, 0.0, 0.34, -0.5]);
            let capped = capped_ratio(&case, et).unwrap_or(0.25);
            let pick = rng.pick(&[0, 1, 2]);
            let near = |x: f64| [x, x.next_up(), x.next_down()][pick];
            case.law = match rng.pick(&[0, 1]) {
                0 if et == 0.0 => Law::Ratio(near(capped)),
                _ => Law::Tangential(near(capped.abs()).max(0.0), et),
            };
            case
        },
    );
    run(
        "exact zeros (sticking, plastic, no spin)",
        107,
        30 * scale,
        false,
        |rng| {
            let mut inp = unit_inputs(rng);
            inp.vn += inp.dc * inp.w;
            inp.dc = 0.0;
            let law = rng.pick(&[Law::Friction(10.0), Law::Tangential(10.0, 0.0), Law::Frictionless]);
            Case { inp, e: 0.0, law }
        },
    );
}

#[test]
fn both_modes_survive_the_stress_sets() {
    stress_sets(1);
}

/// Typical unit-scale scenes under every law: every exact answer correctly
/// rounded, and the first, compensated stage settles all but a handful (what
/// makes the exact mode cost about 5× the fast one, docs/accuracy.md).
#[test]
fn exact_settles_typical_scenes_in_the_compensated_stage() {
    let n = 400;
    let tally = run("typical unit scenes", 131, n, false, |rng| Case {
        inp: unit_inputs(rng),
        e: rng.unit(),
        law: random_law(rng),
    });
    assert_eq!(tally.cases, n);
    assert!(tally.answered > n / 2, "{tally:?}");
    assert!(tally.compensated * 100 >= n * 99, "{tally:?}");
    assert_eq!(tally.rational, 0, "{tally:?}");
    // Every answered case's numbers were checked against fast's promise.
    assert_eq!(tally.promise.impacts, tally.answered, "{tally:?}");
}

#[test]
fn exact_zeros_are_positive_zero() {
    // Central contact, Coulomb friction far above |μ_c|: V_ct = 0 exactly; e = 0:
    // V_cn = 0 and, with no spin, V_n = v_n + (1 + e)(−v_n) = 0 by cancellation.
    let case = Case {
        inp: Inputs {
            m: 1.0,
            inertia: 0.1,
            dc: 0.0,
            dd: 0.3,
            vn: -1.0,
            vt: -0.7,
            w: 0.0,
        },
        e: 0.0,
        law: Law::Friction(10.0),
    };
    let impact = case.impact();
    let (o, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
    let o = o.unwrap();
    assert_eq!(o.regime, Regime::Sticking);
    assert_eq!(o.contact_velocity.r#final.tangential.to_bits(), 0.0f64.to_bits());
    assert_eq!(o.contact_velocity.r#final.normal.to_bits(), 0.0f64.to_bits());
    assert_eq!(o.final_velocity.normal.to_bits(), 0.0f64.to_bits());
    // V_n is formed as V_cn − d_c Ω = −e v_cn − 0 · Ω: with e = 0 a product with
    // exact zeros, decided in the first, compensated stage, like V_ct = −0 · v_ct.
    assert_eq!(stage, Stage::Compensated);
    // With e > 0 the structural zero V_ct = −0 · v_ct is still certified in the
    // compensated stage (a product with an exact zero is exact).
    let impact = Case { e: 0.5, ..case }.impact();
    let (o, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
    assert_eq!(
        o.unwrap().contact_velocity.r#final.tangential.to_bits(),
        0.0f64.to_bits()
    );
    assert_eq!(stage, Stage::Compensated);

    // Non-central (S = k² + d_c² + d_d² = 1): Ω = ω + (d_c q_n + d_d q_t)/S cancels
    // to exactly 0 through a quotient, whose bound cannot exclude zero: the
    // rationals decide it.
    let case = Case {
        inp: Inputs {
            m: 1.0,
            inertia: 0.5,
            dc: 0.5,
            dd: 0.5,
            vn: -1.0,
            vt: 0.5,
            w: -1.5,
        },
        e: 0.0,
        law: Law::Tangential(10.0, 0.0),
    };
    let impact = case.impact();
    let (o, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
    assert_eq!(o.unwrap().final_velocity.angular.to_bits(), 0.0f64.to_bits());
    assert_eq!(stage, Stage::Rational);
}

#[test]
fn exact_torsional_is_correctly_rounded_under_stress() {
    let mut rng = Rng::new(108);
    let mut rational = 0;
    let mut promise = PromiseTally::default();
    for i in 0..300 {
        let wide = i % 2 == 0;
        let mag = |rng: &mut Rng| {
            if wide {
                rng.log_uniform(-300.0, 300.0)
            } else {
                rng.log_uniform(-2.0, 2.0)
            }
        };
        let (m, i_n, rho) = (mag(&mut rng), mag(&mut rng), mag(&mut rng));
        let vn = -mag(&mut rng);
        let any = rng.unit();
        let (e, ez, mu_z) = (random_e(&mut rng), rng.pick(&[0.0, 1.0, any]), rng.unit());
        let switch = mu_z * rho * (1.0 + e) * -vn * m / i_n;
        let spin = match rng.pick(&[0, 1, 2, 3]) {
            0 => mag(&mut rng) * rng.pick(&[-1.0, 1.0]),
            1 => switch,
            2 => -switch.next_up(),
            _ => switch.next_down(),
        };
        let impact = TorsionalImpact {
            mass: m,
            normal_inertia: i_n,
            normal_velocity: vn,
            spin: if spin.is_finite() { spin } else { 1.0 },
            restitution: e,
            torsional_restitution: ez,
            torsional_friction: mu_z,
            pitch_radius: rho,
        };
        let (spin_x, moment_x, regime, switch_x, loss_x) =
            reference::torsional(m, i_n, vn, impact.spin, e, ez, mu_z, rho);
        let (qm, qi, qw, qe, qvn) = (q(m), q(i_n), q(impact.spin), q(e), q(vn));
        let half = q(0.5);
        let values = [
            ("V_n", -(&qe * &qvn)),
            ("P_n", &qm * (q(1.0) + &qe) * -&qvn),
            ("Ω_n", spin_x.clone()),
            ("M_n", moment_x),
            ("ω_s", switch_x),
            ("T_i", &half * &qi * &qw * &qw),
            ("T_f", &half * &qi * &spin_x * &spin_x),
            ("T_L", loss_x),
        ];
        let (answer, stage) = solve_in(&impact, Outputs::ALL, Arithmetic::Exact);
        check_promise(&impact, &mut promise);
        rational += usize::from(stage == Stage::Rational);
        match answer {
            Ok(o) => {
                assert_eq!(o.regime.as_str(), regime, "{impact:?}");
                let energy = o.energy.unwrap();
                let got = [
                    o.final_normal_velocity,
                    o.normal_impulse,
                    o.final_spin,
                    o.torsional_impulse,
                    o.switch_spin,
                    energy.initial,
                    energy.r#final,
                    energy.loss,
                ];
                for ((label, exact), value) in values.iter().zip(got) {
                    assert!(
                        correctly_rounded(value, exact),
                        "{label} = {value:e} for {impact:?}"
                    );
                }
            }
            Err(ImpactError::OutputNotFinite { .. }) => {
                assert!(values.iter().any(|(_, v)| overflows(v)), "{impact:?}");
            }
            Err(e) => panic!("exact torsional refused {e} for {impact:?}"),
        }
        let fast = solve(&impact, Outputs::ALL, Precision::Fast);
        if let Ok(o) = fast {
            assert!(o.final_spin.is_finite() && o.energy.unwrap().loss.is_finite());
        }
    }
    println!("torsional stress: {rational} of 300 needed rationals; fast's promise: {promise:?}");
    assert!(promise.impacts > 100 && promise.outputs > 1000, "{promise:?}");
}

#[test]
fn exact_point_mass_is_correctly_rounded_over_the_whole_range() {
    let mut rng = Rng::new(109);
    for _ in 0..300 {
        let (m, vn, vt) = (
            rng.log_uniform(-300.0, 300.0),
            -rng.log_uniform(-300.0, 300.0),
            rng.log_uniform(-300.0, 300.0) * rng.pick(&[-1.0, 1.0]),
        );
        let e = random_e(&mut rng);
        let point = BarrierImpact::point_mass(m, vn, vt, e);
        let (qm, qvn, qvt, qe) = (q(m), q(vn), q(vt), q(e));
        let half = q(0.5);
        let initial = &half * &qm * (&qvn * &qvn + &qvt * &qvt);
        let loss = &half * &qm * (q(1.0) - &qe * &qe) * &qvn * &qvn;
        let expected = [
            ("V_n", -(&qe * &qvn)),
            ("P_n", &qm * (q(1.0) + &qe) * -&qvn),
            ("T_i", initial.clone()),
            ("T_L", loss.clone()),
            ("T_L*", &loss / &initial),
            ("μ_c", &qvt / ((q(1.0) + &qe) * &qvn)),
        ];
        match solve(&point, Outputs::ALL, Precision::Exact) {
            Ok(o) => {
                let energy = o.energy.unwrap();
                let got = [
                    o.final_velocity.normal,
                    o.impulse.normal,
                    energy.initial,
                    energy.loss,
                    energy.normalized_loss,
                    o.critical_impulse_ratio.unwrap(),
                ];
                for ((label, exact), value) in expected.iter().zip(got) {
                    assert!(
                        correctly_rounded(value, exact),
                        "{label} = {value:e} for {point:?}"
                    );
                }
            }
            Err(ImpactError::OutputNotFinite { .. }) => {
                assert!(expected.iter().any(|(_, v)| overflows(v)), "{point:?}");
            }
            Err(e) => panic!("point mass refused {e} for {point:?}"),
        }
    }
}

/// The larger grid (`cargo test --release --test precision -- --ignored --nocapture`).
#[test]
#[ignore = "a larger grid of the stress sets; minutes in debug"]
fn report_larger_stress_grid() {
    stress_sets(20);
}
