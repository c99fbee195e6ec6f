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

mod common;

use common::Rng;
use common::reference::{self as exact, Outcome, Q, Refusal, q, ulps};
use num_traits::{Signed, ToPrimitive};
use restitution::oblique::{self, KineticRestitution, TangentialLaw};
use restitution::{
    Body, Contact, ImpactError, Outputs, PlanarOutcome, PlanarScene, PlanarVelocity, tangential,
};

/// The largest error allowed, in ulps of the scale defined above. Each output
/// is a short chain of at most ~8 correctly rounded operations (fused where
/// possible) on terms bounded by the scale, and `k² = I/m` carries one
/// rounding amplified by `κ_D`; 16 ulps leaves room for that chain.
const BOUND_ULPS: f64 = 16.0;

thread_local! {
    /// Set by the adversarial sets that sit exactly on a regime switch, where
    /// rounding may pick either (continuous) branch.
    static ALLOW_FLIP: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[derive(Clone, Copy, Debug)]
struct Inputs {
    m: f64,
    inertia: f64,
    dc: f64,
    dd: f64,
    vn: f64,
    vt: f64,
    w: f64,
}

impl Inputs {
    fn scene(&self) -> Result<PlanarScene, ImpactError> {
        PlanarScene::new(
            Body::new(self.m, self.inertia)?,
            Contact {
                tangential_offset: self.dc,
                normal_offset: self.dd,
            },
            PlanarVelocity {
                normal: self.vn,
                tangential: self.vt,
                angular: self.w,
            },
        )
    }
    fn exact(&self) -> exact::Scene {
        exact::Scene::new(self.m, self.inertia, self.dc, self.dd, self.vn, self.vt, self.w)
    }
}

/// A random scene: mass, length and velocity scales over 1e-150…1e150, shapes random.
fn random_inputs(rng: &mut Rng) -> Inputs {
    // Every input stays within 1e-150…1e150: I = m k² and ω = v / L included.
    let a = rng.range(-150.0, 150.0);
    let b = rng.range(((-150.0 - a) / 2.0).max(-74.0), ((150.0 - a) / 2.0).min(74.0));
    let c = rng.range((b - 148.0).max(-148.0), (b + 148.0).min(148.0));
    let (mass, length, speed) = (10f64.powf(a), 10f64.powf(b), 10f64.powf(c));
    let k = length * rng.log_uniform(-1.5, 1.0);
    let shape = rng.pick(&[0, 1, 2, 3]);
    let dc = if shape == 0 {
        0.0
    } else {
        length * rng.range(-2.0, 2.0)
    };
    let dd = if shape == 1 {
        0.0
    } else {
        length * rng.range(-2.0, 2.0)
    };
    let w = if rng.chance(0.2) {
        0.0
    } else {
        speed / length * rng.range(-3.0, 3.0)
    };
    let vt = speed * rng.range(-3.0, 3.0);
    // An approaching contact: choose v_cn < 0, then v_n = v_cn − d_c ω.
    let vcn = -speed
        * if rng.chance(0.15) {
            rng.log_uniform(-15.0, -3.0)
        } else {
            rng.range(0.01, 2.0)
        };
    let vn = vcn - dc * w;
    Inputs {
        m: mass,
        inertia: mass * k * k,
        dc,
        dd,
        vn,
        vt,
        w,
    }
}

#[derive(Default)]
struct Errors {
    names: Vec<&'static str>,
    max: Vec<f64>,
    answered: usize,
    refused: usize,
}

impl Errors {
    fn record(&mut self, name: &'static str, e: f64) {
        match self.names.iter().position(|n| *n == name) {
            Some(i) => self.max[i] = self.max[i].max(e),
            None => {
                self.names.push(name);
                self.max.push(e);
            }
        }
    }
    fn assert_within(&self, case: &str, bound: f64) {
        let mut line = format!(
            "{case}: {} answered, {} refused; max ulps:",
            self.answered, self.refused
        );
        for (n, e) in self.names.iter().zip(&self.max) {
            line.push_str(&format!(" {n}={e:.2}"));
        }
        println!("{line}");
        for (n, e) in self.names.iter().zip(&self.max) {
            assert!(*e <= bound, "{case}: {n} off by {e} ulps (bound {bound})");
        }
        assert!(self.answered > 0, "{case}: nothing answered");
    }
}

fn max_abs(values: &[Q]) -> Q {
    values.iter().map(|v| v.abs()).max().unwrap_or_else(|| q(0.0))
}

/// Compares one answer with the reference, output by output.
fn compare(errors: &mut Errors, inp: &Inputs, fast: &PlanarOutcome, reference: &Outcome, kappa: Q) {
    let s = inp.exact();
    let k = q(inp.inertia / inp.m).to_f64().unwrap().sqrt();
    let length = max_abs(&[s.dc.clone(), s.dd.clone(), q(k)]);
    let sv = max_abs(&[
        s.vn.clone(),
        s.vt.clone(),
        &s.w * &length,
        reference.vn.clone(),
        reference.vt.clone(),
        &reference.w * &length,
    ]) * &kappa;
    let sw = &sv / &length;
    let sp = &s.m * &sv;
    let se = &s.m * &sv * &sv;
    let dn = &reference.pn / &s.m;
    let smu = &sv / &dn;
    errors.record("V_n", ulps(fast.final_velocity.normal, &reference.vn, &sv));
    errors.record("V_t", ulps(fast.final_velocity.tangential, &reference.vt, &sv));
    errors.record("Ω", ulps(fast.final_velocity.angular, &reference.w, &sw));
    errors.record(
        "V_cn",
        ulps(fast.contact_velocity.r#final.normal, &reference.vcn, &sv),
    );
    errors.record(
        "V_ct",
        ulps(fast.contact_velocity.r#final.tangential, &reference.vct, &sv),
    );
    errors.record("P_n", ulps(fast.impulse.normal, &reference.pn, &sp));
    errors.record("P_t", ulps(fast.impulse.tangential, &reference.pt, &sp));
    errors.record("μ", ulps(fast.impulse_ratio, &reference.mu, &smu));
    if let (Some(fast_c), Some(exact_c)) = (fast.critical_impulse_ratio, &reference.mu_c) {
        let dn_c = exact::critical_normal_change(&s, &reference.e).abs();
        // μ_c = Δt/Δn of the sticking answer: both are differences of terms ≤ σ_v.
        let scale = &sv * (q(1.0) + exact_c.abs()) / dn_c;
        let err = ulps(fast_c, exact_c, &scale);
        if err > BOUND_ULPS {
            println!(
                "μ_c off {err}: {inp:?} fast {fast_c} exact {}",
                exact::to_f64(exact_c)
            );
        }
        errors.record("μ_c", err);
    }
    errors.record("e", ulps(fast.restitution, &reference.e, &kappa));
    let energy = fast.energy.expect("energy requested");
    errors.record(
        "T_i",
        ulps(energy.initial, &reference.t_initial, &reference.t_initial),
    );
    errors.record("T_f", ulps(energy.r#final, &reference.t_final, &se));
    errors.record("T_L", ulps(energy.loss, &reference.t_loss, &se));
    errors.record("T_M", ulps(energy.max_loss, &reference.t_max, &reference.t_max));
    let tls = &reference.t_loss / &reference.t_max;
    errors.record(
        "T_L*",
        ulps(energy.normalized_loss, &tls, &(&se / &reference.t_max)),
    );
    // The regime is a decision; away from its boundaries it must agree exactly.
    if !ALLOW_FLIP.with(|flip| flip.get()) {
        assert_eq!(
            fast.regime.as_str(),
            reference.regime,
            "regime differs for {inp:?}"
        );
    }
}

fn kappa(inp: &Inputs, mu: f64) -> Q {
    let s = inp.exact();
    let dk2 = &s.k2 + &s.dc * (&s.dc - q(mu) * &s.dd);
    let size = &s.k2 + &s.dc * &s.dc + (&s.dc * q(mu) * &s.dd).abs();
    if dk2.is_positive() { size / dk2 } else { q(1.0) }
}

fn refusal_kind(e: &ImpactError) -> Option<Refusal> {
    match e {
        ImpactError::NotApproaching { .. } => Some(Refusal::NotApproaching),
        ImpactError::NoImpulseSolution { .. } => Some(Refusal::NoImpulseSolution),
        ImpactError::CreatesEnergy { .. } => Some(Refusal::CreatesEnergy),
        _ => None,
    }
}

/// Runs one case over `n` random scenes; `law` gives the fast and exact answers.
fn run_case(
    name: &str,
    seed: u64,
    n: usize,
    mut law: impl FnMut(
        &mut Rng,
        &Inputs,
        &PlanarScene,
    ) -> (Result<PlanarOutcome, ImpactError>, Result<Outcome, Refusal>),
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
        let interval = restitution::planar::admissible_interval(scene, e);
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
        let impact = restitution::normal::NormalImpact {
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
        let fast = restitution::normal::solve(&impact, Outputs::ALL);
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
        let impact = restitution::torsional::TorsionalImpact {
            mass: m,
            normal_inertia: i_n,
            normal_velocity: vn,
            spin,
            restitution: e,
            torsional_restitution: ez,
            torsional_friction: mu_z,
            pitch_radius: rho,
        };
        let Ok(fast) = restitution::torsional::solve(&impact, true) else {
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
        let impact = restitution::normal::NormalImpact {
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
        let fast = restitution::normal::solve(&impact, Outputs::ALL).unwrap();
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
    ALLOW_FLIP.with(|flip| flip.set(true));
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
    ALLOW_FLIP.with(|flip| flip.set(false));
}
