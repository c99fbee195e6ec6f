//! The closed forms against the exact rational reference, on random and
//! adversarial inputs over magnitudes 1e-150…1e150.
//!
//! Error measure (see docs/physics.md, "Accuracy"): the error of each output in
//! units in the last place of its *scale*, the magnitude of the terms the
//! output combines: `σ_v = max(|v_n|, |v_t|, |ω| L, |V_n|, |V_t|, |Ω| L)` for
//! velocities (`L = max(|d_c|, |d_d|, k)`), `σ_v / L` for `Ω`, `m σ_v` for impulses,
//! `m σ_v²` for energies, `σ_v / Δn` for `μ` and `σ_v (1 + |μ_c|) / Δn_c` for `μ_c`, `σ_E / T_M` for `T_L*`,
//! each times the conditioning `κ_D = (k² + d_c² + |d_c μ d_d|) / |D k²|` of the
//! denominator `D`. Where no cancellation occurs the scale is the value itself.

use crate::common::Rng;
use crate::common::accuracy::{BOUND_ULPS, Errors, Inputs, compare, kappa, random_inputs, refusal_kind};
use crate::common::reference::{self as exact, Outcome, Refusal, q, ulps};
use num_traits::Signed;

use crate::common::plain::oblique::{self, KineticRestitution, TangentialLaw};
use crate::common::plain::tangential;
use restitution::{BarrierOutcome, BarrierScene, Contact, ImpactError, Outputs, PlanarVelocity};

/// Runs one case over `n` random scenes; `law` gives the fast and exact answers.
fn run_case(
    name: &str,
    seed: u64,
    n: usize,
    mut law: impl FnMut(
        &mut Rng,
        &Inputs,
        &BarrierScene,
    ) -> (Result<BarrierOutcome, ImpactError>, Result<Outcome, Refusal>),
) {
    let mut rng = Rng::new(seed);
    let mut errors = Errors::default();
    for _ in 0..n {
        let inp = random_inputs(&mut rng);
        let scene = inp.scene().expect("valid random scene");
        let (fast, reference) = law(&mut rng, &inp, &scene);
        match (fast, reference) {
            (Ok(f), Ok(r)) => {
                errors.answered += 1;
                let k = kappa(&inp, f.impulse_ratio);
                compare(&mut errors, &inp, &f, &r, k);
            }
            (Err(ImpactError::OutputNotFinite { .. }), Ok(r)) => {
                // Only allowed when an exact output really exceeds f64.
                let limit = q(f64::MAX);
                let too_big = [&r.pn, &r.pt, &r.t_initial, &r.t_final, &r.t_max, &r.w]
                    .iter()
                    .any(|x| x.abs() > limit);
                assert!(too_big, "{name}: spurious overflow for {inp:?}");
                errors.refused += 1;
            }
            (Err(e), Err(r)) => {
                assert_eq!(
                    refusal_kind(&e),
                    Some(r),
                    "{name}: refusals differ for {inp:?}: {e}"
                );
                errors.refused += 1;
            }
            (Ok(f), Err(r)) => {
                panic!("{name}: fast answered {f:?} but the reference refuses ({r:?}) for {inp:?}")
            }
            (Err(e), Ok(_)) => panic!("{name}: fast refused ({e}) but the reference answers for {inp:?}"),
        }
    }
    errors.assert_within(name, BOUND_ULPS);
}

fn random_e(rng: &mut Rng) -> f64 {
    if rng.chance(0.2) {
        rng.pick(&[0.0, 1.0, 1.0 - 1e-12, 0.5])
    } else {
        rng.unit()
    }
}

#[test]
fn prescribed_ratio_matches_the_exact_reference() {
    run_case("prescribed μ", 1, 3000, |rng, inp, scene| {
        let e = random_e(rng);
        // Mostly inside the admissible interval, sometimes outside it.
        let interval = scene.admissible_interval(e);
        let lo = interval.lower.unwrap_or(-2.0).max(-2.0);
        let hi = interval.upper.unwrap_or(2.0).min(2.0);
        let mu = if rng.chance(0.8) {
            rng.range(lo, hi) * 0.999
        } else {
            rng.range(-3.0, 3.0)
        };
        let fast = oblique::solve(scene, e, TangentialLaw::ImpulseRatio(mu), Outputs::ALL);
        (fast, exact::prescribed(&inp.exact(), e, mu))
    });
}

#[test]
fn coulomb_friction_matches_the_exact_reference() {
    run_case("friction f", 2, 3000, |rng, inp, scene| {
        let e = random_e(rng);
        let f = if rng.chance(0.1) { 0.0 } else { rng.range(0.0, 1.5) };
        let fast = oblique::solve(scene, e, TangentialLaw::Friction(f), Outputs::ALL);
        (fast, exact::bilinear(&inp.exact(), e, f, 0.0, "sticking"))
    });
}

#[test]
fn tangential_restitution_matches_the_exact_reference() {
    run_case("tangential e_t", 3, 3000, |rng, inp, scene| {
        let e = random_e(rng);
        let f = rng.range(0.0, 1.5);
        let et = if rng.chance(0.2) {
            rng.pick(&[-1.0, 0.0, 1.0])
        } else {
            rng.range(-1.0, 1.0)
        };
        let fast = tangential::solve(scene, e, f, et, Outputs::ALL);
        (fast, exact::bilinear(&inp.exact(), e, f, et, "restitution"))
    });
}

#[test]
fn kinetic_restitution_matches_the_exact_reference() {
    run_case("kinetic R", 4, 3000, |rng, inp, scene| {
        let r = random_e(rng);
        let mu_a = rng.range(-0.4, 0.4);
        let mu_r = if rng.chance(0.3) {
            mu_a
        } else {
            rng.range(-0.4, 0.4)
        };
        let kinetic = KineticRestitution {
            value: r,
            approach_impulse_ratio: mu_a,
            rebound_impulse_ratio: mu_r,
        };
        let fast = oblique::solve_kinetic(scene, kinetic, Outputs::ALL);
        (fast, exact::kinetic(&inp.exact(), r, mu_a, mu_r))
    });
}

#[test]
fn frictionless_normal_impact_matches_the_exact_reference() {
    run_case("frictionless", 5, 2000, |rng, inp, _scene| {
        let e = random_e(rng);
        let impact = crate::common::plain::normal::NormalImpact {
            mass: inp.m,
            inertia: Some(inp.inertia),
            contact: Some(Contact {
                tangential_offset: inp.dc,
                normal_offset: inp.dd,
            }),
            velocity: PlanarVelocity {
                normal: inp.vn,
                tangential: inp.vt,
                angular: inp.w,
            },
            restitution: e,
        };
        let fast = crate::common::plain::normal::solve(&impact, Outputs::ALL);
        (fast, exact::frictionless(&inp.exact(), e))
    });
}

#[test]
fn torsional_matches_the_exact_reference() {
    let mut rng = Rng::new(6);
    let mut errors = Errors::default();
    for _ in 0..3000 {
        let m = rng.log_uniform(-100.0, 100.0);
        let radius = rng.log_uniform(-50.0, 50.0);
        let i_n = m * radius * radius * rng.range(0.1, 1.0);
        let vn = -rng.log_uniform(-100.0, 100.0);
        let rho = radius * rng.range(0.01, 1.0);
        let (e, ez, mu_z) = (random_e(&mut rng), rng.unit(), rng.range(0.0, 1.0));
        let switch = mu_z * rho * (1.0 + e) * -vn * m / i_n;
        let spin = if rng.chance(0.5) {
            switch * rng.range(-3.0, 3.0)
        } else {
            rng.pick(&[switch, -switch])
        };
        let impact = restitution::TorsionalImpact {
            mass: m,
            normal_inertia: i_n,
            normal_velocity: vn,
            spin,
            restitution: e,
            torsional_restitution: ez,
            torsional_friction: mu_z,
            pitch_radius: rho,
        };
        let Ok(fast) = crate::common::plain::torsional::solve(&impact, true) else {
            continue;
        };
        let (spin_x, moment_x, regime, switch_x, loss_x) =
            exact::torsional(m, i_n, vn, spin, e, ez, mu_z, rho);
        errors.answered += 1;
        let scale = spin.abs().max(exact::to_f64(&switch_x));
        if fast.regime.as_str() == regime {
            errors.record("Ω_n", ulps(fast.final_spin, &spin_x, &q(scale)));
            errors.record(
                "M_n",
                ulps(fast.torsional_impulse, &moment_x, &(q(scale) * q(i_n))),
            );
            errors.record(
                "T_L",
                ulps(fast.energy.unwrap().loss, &loss_x, &(q(scale * scale) * q(i_n))),
            );
        } else {
            // Only at the switch itself may rounding pick the other (continuous) branch.
            errors.refused += 1;
            assert!(ulps(fast.final_spin, &spin_x, &q(scale)) <= BOUND_ULPS);
        }
        errors.record("ω_s", ulps(fast.switch_spin, &switch_x, &switch_x));
    }
    errors.assert_within("torsional", BOUND_ULPS);
}

#[test]
fn point_mass_matches_the_exact_reference() {
    let mut rng = Rng::new(7);
    let mut errors = Errors::default();
    for _ in 0..2000 {
        let m = rng.log_uniform(-100.0, 100.0);
        let speed = rng.log_uniform(-100.0, 100.0);
        let (vn, vt, e) = (
            -speed * rng.range(0.01, 2.0),
            speed * rng.range(-2.0, 2.0),
            random_e(&mut rng),
        );
        let impact = crate::common::plain::normal::NormalImpact {
            mass: m,
            inertia: None,
            contact: None,
            velocity: PlanarVelocity {
                normal: vn,
                tangential: vt,
                angular: 0.0,
            },
            restitution: e,
        };
        let fast = crate::common::plain::normal::solve(&impact, Outputs::ALL).unwrap();
        let (qm, qvn, qvt, qe) = (q(m), q(vn), q(vt), q(e));
        let one = q(1.0);
        let final_vn = -(&qe * &qvn);
        let pn = &qm * (&one + &qe) * (-&qvn);
        let loss = q(0.5) * &qm * (&qvn * &qvn - &final_vn * &final_vn);
        let initial = q(0.5) * &qm * (&qvn * &qvn + &qvt * &qvt);
        errors.answered += 1;
        errors.record("V_n", ulps(fast.final_velocity.normal, &final_vn, &final_vn));
        errors.record("P_n", ulps(fast.impulse.normal, &pn, &pn));
        let energy = fast.energy.unwrap();
        errors.record("T_L", ulps(energy.loss, &loss, &loss));
        errors.record("T_i", ulps(energy.initial, &initial, &initial));
        errors.record(
            "T_L*",
            ulps(energy.normalized_loss, &(&loss / &initial), &(&loss / &initial)),
        );
    }
    errors.assert_within("point mass", BOUND_ULPS);
}

/// Adversarial sets: μ at and next to μ_c, μ next to the root of D, f at and
/// next to |μ_c| and to the tangential switch (central contacts, where the
/// bilinear models are continuous).
#[test]
fn adversarial_boundaries_match_the_exact_reference() {
    run_case("μ at and next to μ_c", 11, 1500, |rng, inp, scene| {
        let e = random_e(rng);
        let critical = oblique::solve(scene, e, TangentialLaw::Friction(1e300), Outputs::ALL)
            .ok()
            .and_then(|o| o.critical_impulse_ratio)
            .unwrap_or(0.5);
        let mu = rng.pick(&[critical, critical.next_up(), critical.next_down()]);
        (
            oblique::solve(scene, e, TangentialLaw::ImpulseRatio(mu), Outputs::ALL),
            exact::prescribed(&inp.exact(), e, mu),
        )
    });
    run_case("μ next to the root of D", 12, 1500, |rng, inp, scene| {
        let e = random_e(rng);
        let c = scene.contact();
        let k2 = scene.body().gyration_squared();
        let product = c.tangential_offset * c.normal_offset;
        let root = if product != 0.0 {
            (k2 + c.tangential_offset.powi(2)) / product
        } else {
            1.0
        };
        let mu = root * (1.0 - rng.pick(&[1e-15, 1e-12, 1e-9, -1e-12]));
        (
            oblique::solve(scene, e, TangentialLaw::ImpulseRatio(mu), Outputs::ALL),
            exact::prescribed(&inp.exact(), e, mu),
        )
    });
    run_case("f at and next to |μ_c|, central", 13, 1500, |rng, inp, _| {
        let central = Inputs {
            dc: 0.0,
            vn: inp.vn + inp.dc * inp.w,
            ..*inp
        };
        let scene = central.scene().expect("central scene");
        let e = random_e(rng);
        let et = if rng.chance(0.5) {
            0.0
        } else {
            rng.range(-1.0, 1.0)
        };
        let capped = tangential::solve(&scene, e, 1e300, et, Outputs::MINIMAL);
        let switch = capped.map_or(0.5, |o| o.impulse_ratio.abs());
        let f = rng.pick(&[switch, switch.next_up(), switch.next_down()]).max(0.0);
        let capped_name = if et == 0.0 { "sticking" } else { "restitution" };
        let fast = if et == 0.0 {
            oblique::solve(&scene, e, TangentialLaw::Friction(f), Outputs::ALL)
        } else {
            tangential::solve(&scene, e, f, et, Outputs::ALL)
        };
        (fast, exact::bilinear(&central.exact(), e, f, et, capped_name))
    });
}
