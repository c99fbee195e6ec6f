//! The error measure of the fast closed forms against the exact reference:
//! errors in ulps of each output's scale (the magnitude of the terms it
//! combines) times the conditioning of `D`; see tests/reference.rs.

use super::Rng;
use super::reference::{self as exact, Outcome, Q, Refusal, q, ulps};
use num_traits::Signed;
use restitution::{BarrierOutcome, BarrierScene, Body, Contact, ImpactError, PlanarVelocity};

/// The largest error allowed, in ulps of the scale defined above. Each output
/// is a short chain of at most ~8 correctly rounded operations (fused where
/// possible) on terms bounded by the scale, and `k² = I/m` carries one
/// rounding amplified by `κ_D`; 16 ulps leaves room for that chain.
pub const BOUND_ULPS: f64 = 16.0;

#[derive(Clone, Copy, Debug)]
pub struct Inputs {
    pub m: f64,
    pub inertia: f64,
    pub dc: f64,
    pub dd: f64,
    pub vn: f64,
    pub vt: f64,
    pub w: f64,
}

impl Inputs {
    pub fn scene(&self) -> Result<BarrierScene, ImpactError> {
        BarrierScene::new(
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
    pub fn exact(&self) -> exact::Scene {
        exact::Scene::new(self.m, self.inertia, self.dc, self.dd, self.vn, self.vt, self.w)
    }
}

/// A random scene: mass, length and velocity scales over 1e-150…1e150, shapes random.
pub fn random_inputs(rng: &mut Rng) -> Inputs {
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
pub struct Errors {
    pub names: Vec<&'static str>,
    pub max: Vec<f64>,
    pub answered: usize,
    pub refused: usize,
}

impl Errors {
    pub fn record(&mut self, name: &'static str, e: f64) {
        match self.names.iter().position(|n| *n == name) {
            Some(i) => self.max[i] = self.max[i].max(e),
            None => {
                self.names.push(name);
                self.max.push(e);
            }
        }
    }
    pub fn assert_within(&self, case: &str, bound: f64) {
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
pub fn compare(errors: &mut Errors, inp: &Inputs, fast: &BarrierOutcome, reference: &Outcome, kappa: Q) {
    let s = inp.exact();
    // k only sets a length scale; clamp k² into the f64 range to take its root.
    let k = exact::to_f64(&s.k2).clamp(f64::MIN_POSITIVE, f64::MAX).sqrt();
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
    // The regime is a decision: `fast` takes it exactly, at a switch too.
    assert_eq!(
        fast.regime.as_str(),
        reference.regime,
        "regime differs for {inp:?}"
    );
}

pub fn kappa(inp: &Inputs, mu: f64) -> Q {
    let s = inp.exact();
    let dk2 = &s.k2 + &s.dc * (&s.dc - q(mu) * &s.dd);
    let size = &s.k2 + &s.dc * &s.dc + (&s.dc * q(mu) * &s.dd).abs();
    if dk2.is_positive() { size / dk2 } else { q(1.0) }
}

pub fn refusal_kind(e: &ImpactError) -> Option<Refusal> {
    match e {
        ImpactError::NotApproaching { .. } => Some(Refusal::NotApproaching),
        ImpactError::NoImpulseSolution { .. } => Some(Refusal::NoImpulseSolution),
        ImpactError::CreatesEnergy { .. } => Some(Refusal::CreatesEnergy),
        _ => None,
    }
}

/// What [`check_promise`] saw over a set of impacts.
#[derive(Debug, Default, Clone, Copy)]
pub struct PromiseTally {
    /// Impacts both modes answered.
    pub impacts: usize,
    /// Of those, the `fast` answers the exact stages gave.
    pub escalated: usize,
    /// Numbers compared.
    pub outputs: usize,
    /// The largest `|fast − exact| / max(|exact|, S)` seen.
    pub worst: f64,
}

/// Checks `fast`'s promise on one impact: every number of its answer within
/// `PROMISED_RELATIVE_ERROR · max(|x|, S)` of the exact mode's correctly
/// rounded `x` (plus that rounding, an ulp of `x` at most), `S` the scale of
/// the output's unit ([`restitution::ErrorScales`]). Refusals are compared
/// by each survey's own checks.
pub fn check_promise<C: restitution::Case>(impact: &C, tally: &mut PromiseTally) {
    use restitution::impact::{Arithmetic, Stage, solve_in};
    use restitution::quantity::Value;
    let (fast, stage) = solve_in(impact, restitution::Outputs::ALL, Arithmetic::Fast);
    let (exact, _) = solve_in(impact, restitution::Outputs::ALL, Arithmetic::Exact);
    let (Ok(fast), Ok(exact)) = (fast, exact) else {
        return;
    };
    tally.impacts += 1;
    tally.escalated += usize::from(stage != Stage::Fast);
    let scales = impact.error_scales();
    for &output in C::OUTPUTS {
        let (Some(Value::Number(h)), Some(Value::Number(x))) =
            (C::output(&fast, output), C::output(&exact, output))
        else {
            continue;
        };
        if h.is_nan() && x.is_nan() {
            continue; // not an output of this impact
        }
        let measure = x.abs().max(scales.of_output(output));
        let error = (h - x).abs();
        let allowed = restitution::PROMISED_RELATIVE_ERROR * measure + 2.0 * f64::EPSILON * x.abs();
        assert!(
            error <= allowed,
            "{output:?}: fast {h:e}, exact {x:e}: {:.3e} of max(|x|, S = {:e}), past the promise: {impact:?}",
            error / measure,
            scales.of_output(output)
        );
        tally.outputs += 1;
        if measure > 0.0 {
            tally.worst = tally.worst.max(error / measure);
        }
    }
}
