//! The planar and torsional models written once over a [`Field`], from the
//! momentum equations (Eqs A-1…A-3) closed by Eq 1 and one tangential law.
//!
//! Every output is formed as its exact value in the field and rounded once at
//! the end; every regime decision is the exact sign of a field value. In the
//! compensated and double-double fields a sign or a rounding may be undecided
//! ([`Fail::Undecided`]); the caller then repeats the whole answer in the next
//! field, and last in rationals, where that variant is uninhabited.
//!
//! The model's steps are `#[inline(always)]`: the field values (four words in
//! the compensated field) then stay in registers instead of being copied
//! through the stack between steps (with the two-division quotient, 296–336 →
//! 233–288 ns per typical planar solve in `cargo run --release --example
//! accuracy_report`; docs/accuracy.md).
//! Unlike the fast path, no formula here is chosen for its rounding: any
//! algebraically equal form has the same exact value.

use std::cell::OnceCell;
use std::cmp::Ordering;

use super::field::Field;
use crate::energy::PlanarEnergy;
use crate::error::{ImpactError, Input, Output};
use crate::normal::PointMass;
use crate::planar::{
    ContactVelocities, Impulse, Outputs, PlanarOutcome, Regime, admissible_interval, no_impulse_solution,
};
use crate::scene::{ContactVelocity, PlanarScene, PlanarVelocity};
use crate::torsional::{RotationalEnergy, TorsionalOutcome, TorsionalRegime, Validated};

/// Why the exact model gave no answer in a field whose undecided signs and
/// roundings are reported as `U` ([`Field::Undecided`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Fail<U> {
    /// A sign or a rounding the field could not decide.
    Undecided(U),
    /// The model's own refusal (the same in every field).
    Refused(ImpactError),
}

impl<U> From<ImpactError> for Fail<U> {
    fn from(e: ImpactError) -> Self {
        Fail::Refused(e)
    }
}

/// The model's result in the field `N`.
pub(crate) type Exact<N, T> = Result<T, Fail<<N as Field>::Undecided>>;

#[inline(always)]
fn sign<N: Field>(x: &N) -> Exact<N, Ordering> {
    x.sign().map_err(Fail::Undecided)
}

fn abs<N: Field>(x: &N) -> Exact<N, N> {
    Ok(if sign(x)? == Ordering::Less {
        x.neg()
    } else {
        x.clone()
    })
}

/// The output correctly rounded, or its refusal when it rounds beyond the f64 range.
#[inline(always)]
fn out<N: Field>(output: Output, x: &N) -> Exact<N, f64> {
    let v = x.round().map_err(Fail::Undecided)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ImpactError::OutputNotFinite { output }.into())
    }
}

fn half<N: Field>() -> N {
    N::of(0.5)
}

/// The planar tangential laws the exact model evaluates, inputs validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PlanarLaw {
    /// `μ = 0`.
    Frictionless,
    /// A prescribed `μ`.
    Ratio(f64),
    /// Friction `f` with tangential restitution `e_t` (`e_t = 0`: Coulomb), capped regime named.
    Bilinear { f: f64, et: f64, capped: Regime },
    /// The two-phase model: `R`, `μ_A`, `μ_R`.
    Kinetic { r: f64, mu_a: f64, mu_r: f64 },
}

/// A planar scene in the field: every input exactly, and `v_cn`, `v_ct`, `k²`, `S`.
struct Scene<'a, N> {
    fast: &'a PlanarScene,
    m: N,
    inertia: N,
    k2: N,
    dc: N,
    dd: N,
    vn: N,
    vt: N,
    w: N,
    vcn: N,
    vct: N,
    /// `s = −v_cn > 0`.
    s: N,
    /// `k² + d_c²`.
    k2_dc2: N,
    /// `k² + d_d²`.
    k2_dd2: N,
    /// `d_c d_d`.
    cross: N,
    /// `S = k² + d_c² + d_d²`.
    total: N,
    /// `1 / S`, formed when first needed.
    inv_total: OnceCell<N>,
}

impl<'a, N: Field> Scene<'a, N> {
    #[inline(always)]
    fn new(fast: &'a PlanarScene) -> Self {
        let m = N::of(fast.body.mass());
        let inertia = N::of(fast.body.inertia());
        let dc = N::of(fast.contact.tangential_offset);
        let dd = N::of(fast.contact.normal_offset);
        let vn = N::of(fast.velocity.normal);
        let vt = N::of(fast.velocity.tangential);
        let w = N::of(fast.velocity.angular);
        let vcn = vn.add(&dc.mul(&w));
        let vct = vt.sub(&dd.mul(&w));
        let k2 = inertia.div(&m);
        let dd2 = dd.mul(&dd);
        let k2_dc2 = k2.add(&dc.mul(&dc));
        Scene {
            fast,
            s: vcn.neg(),
            k2_dd2: k2.add(&dd2),
            cross: dc.mul(&dd),
            total: k2_dc2.add(&dd2),
            inv_total: OnceCell::new(),
            k2_dc2,
            k2,
            m,
            inertia,
            dc,
            dd,
            vn,
            vt,
            w,
            vcn,
            vct,
        }
    }

    /// `D(μ) k² = k² + d_c (d_c − μ d_d)`, refused unless `> 0`.
    #[inline(always)]
    fn positive_dk2(&self, mu: f64, law: Input) -> Exact<N, N> {
        let dk2 = self.k2.add(&self.dc.mul(&self.dc.sub(&N::of(mu).mul(&self.dd))));
        if sign(&dk2)? == Ordering::Greater {
            Ok(dk2)
        } else {
            Err(no_impulse_solution(self.fast, mu, law).into())
        }
    }

    /// `(Δn, Δt, ΔΩ, ΔV_ct)` for ratio `μ` with `Δn D(μ) k² = q_n k²` (Eqs 5–7).
    #[inline(always)]
    fn ratio_parts(&self, qn: &N, mu: &N, dk2: &N) -> [N; 4] {
        let per = qn.div(dk2);
        // Central contact: D k² = k², so Δn = q_n exactly (a tie stays decidable).
        let dn = if self.central() {
            qn.clone()
        } else {
            self.k2.mul(&per)
        };
        let dt = mu.mul(&dn);
        let dw = self.dc.sub(&mu.mul(&self.dd)).mul(&per);
        let lever = mu.mul(&self.k2_dd2).sub(&self.cross);
        [dn, dt, dw, lever.mul(&per)]
    }

    /// `q_n = (1 + e)(−v_cn)`: the change of `v_cn` that restitution `e` asks (Eq 1).
    #[inline(always)]
    fn normal_target(&self, e: &N) -> N {
        N::of(1.0).add(e).mul(&self.s)
    }

    /// The answer for a prescribed ratio `μ` with restitution `e` (`q_n` its [`Scene::normal_target`]).
    #[inline(always)]
    fn ratio_answer(&self, e: &N, qn: &N, mu: f64, law: Input) -> Exact<N, Answer<N>> {
        let dk2 = self.positive_dk2(mu, law)?;
        let mu = N::of(mu);
        let [dn, dt, dw, dvct] = self.ratio_parts(qn, &mu, &dk2);
        Ok(Answer {
            qn: qn.clone(),
            dn,
            dt,
            dw,
            vcn: e.mul(&self.vcn).neg(),
            vct: self.vct.add(&dvct),
            mu: Some(mu),
        })
    }

    /// `S Δn = (k² + d_d²) q_n − d_c d_d q_t` and `S Δt = d_c d_d q_n − (k² + d_c²) q_t`:
    /// the impulses that change `v_cn` by `q_n` and `v_ct` by `−q_t`.
    #[inline(always)]
    fn scaled_impulses(&self, qn: &N, qt: &N) -> (N, N) {
        let cross = &self.cross;
        (
            self.k2_dd2.mul(qn).sub(&cross.mul(qt)),
            cross.mul(qn).sub(&self.k2_dc2.mul(qt)),
        )
    }

    /// The answer with `V_cn = −e v_cn` and `V_ct = −e_t v_ct` (Eqs 1, 20, 3):
    /// `Δn = [(k² + d_d²) q_n − d_c d_d q_t] / S`, `Δt = [d_c d_d q_n − (k² + d_c²) q_t] / S`,
    /// `ΔΩ = [d_c q_n + d_d q_t] / S`, `S = k² + d_c² + d_d²`. Its ratio
    /// `Δt / Δn` is set only where `Δn ≠ 0`.
    #[inline(always)]
    fn target_answer(&self, e: &N, qn: &N, et: f64) -> Exact<N, Answer<N>> {
        let qt = N::of(1.0).add(&N::of(et)).mul(&self.vct);
        let (sdn, sdt) = self.scaled_impulses(qn, &qt);
        let mu = (sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn));
        let inv_total = self.inv_total();
        Ok(Answer {
            vcn: e.mul(&self.vcn).neg(),
            vct: N::of(et).mul(&self.vct).neg(),
            dn: if self.central() {
                qn.clone()
            } else {
                sdn.mul(inv_total)
            },
            dt: sdt.mul(inv_total),
            dw: self.dc.mul(qn).add(&self.dd.mul(&qt)).mul(inv_total),
            qn: qn.clone(),
            mu,
        })
    }

    /// Whether `d_c = 0` exactly: then `S = k² + d_d²` and `Δn = q_n` in every answer.
    fn central(&self) -> bool {
        self.fast.contact.tangential_offset == 0.0
    }

    /// `1 / S`, formed once.
    #[inline(always)]
    fn inv_total(&self) -> &N {
        self.inv_total.get_or_init(|| N::of(1.0).div(&self.total))
    }

    /// `μ_c`: the ratio `Δt / Δn` of the answer that ends with `V_ct = 0`
    /// (`q_t = v_ct`) and changes `v_cn` by `q_n`, `None` if its `Δn = 0`.
    #[inline(always)]
    fn critical_ratio(&self, qn: &N) -> Exact<N, Option<N>> {
        let (sdn, sdt) = self.scaled_impulses(qn, &self.vct);
        Ok((sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn)))
    }

    /// The bilinear law (Coulomb friction for `e_t = 0`).
    fn bilinear(&self, e: &N, f: f64, et: f64, capped: Regime, outputs: Outputs) -> Exact<N, PlanarOutcome> {
        let qn = self.normal_target(e);
        let target = self.target_answer(e, &qn, et)?;
        let known_critical = (et == 0.0).then(|| target.mu.clone());
        let f_n = N::of(f);
        if let Some(mu_target) = &target.mu {
            let room = f_n.mul(&abs(&target.dn)?).sub(&abs(&target.dt)?);
            if sign(&room)? != Ordering::Less {
                if sign(&target.dn)? == Ordering::Less {
                    return Err(no_impulse_solution(self.fast, mu_target.approx(), Input::Friction).into());
                }
                return self.assemble(e, None, capped, &target, known_critical, outputs, Input::Friction);
            }
        }
        // Sliding opposes the slip; with no initial slip it follows μ_target
        // (which exists then: v_ct = 0 gives Δn > 0).
        let direction = match sign(&self.vct)? {
            Ordering::Greater => -1.0,
            Ordering::Less => 1.0,
            Ordering::Equal => match (sign(&target.dt)?, sign(&target.dn)?) {
                (Ordering::Less, Ordering::Greater) | (Ordering::Greater, Ordering::Less) => -1.0,
                _ => 1.0,
            },
        };
        let sliding = self.ratio_answer(e, &qn, direction * f + 0.0, Input::Friction)?;
        self.assemble(
            e,
            None,
            Regime::Sliding,
            &sliding,
            known_critical,
            outputs,
            Input::Friction,
        )
    }

    /// The Appendix's two phases: approach to `v̄_cn = 0` with `μ_A`, rebound
    /// `P_n^R = R P_n^A` with `μ_R`; `e = R D(μ_R) / D(μ_A)` (Eq 11, A-16).
    fn kinetic(&self, r: f64, mu_a: f64, mu_r: f64, outputs: Outputs) -> Exact<N, PlanarOutcome> {
        let dk_a = self.positive_dk2(mu_a, Input::ApproachImpulseRatio)?;
        let dk_r = if r > 0.0 {
            Some(self.positive_dk2(mu_r, Input::ReboundImpulseRatio)?)
        } else {
            None
        };
        let e = match &dk_r {
            Some(dk_r) => N::of(r).mul(dk_r).div(&dk_a),
            None => N::of(0.0),
        };
        let approach = self.ratio_parts(&self.s, &N::of(mu_a), &dk_a);
        let [dn, dt, dw, dvct] = match &dk_r {
            Some(dk_r) => {
                let rebound = self.ratio_parts(&e.mul(&self.s), &N::of(mu_r), dk_r);
                [0, 1, 2, 3].map(|i| approach[i].add(&rebound[i]))
            }
            None => approach,
        };
        let answer = Answer {
            qn: self.normal_target(&e),
            mu: Some(dt.div(&dn)),
            vcn: e.mul(&self.vcn).neg(),
            vct: self.vct.add(&dvct),
            dn,
            dt,
            dw,
        };
        self.assemble(
            &e,
            Some(r),
            Regime::Prescribed,
            &answer,
            None,
            outputs,
            Input::KineticRestitution,
        )
    }

    /// The outcome of one answer: refuses energy creation (`T_L < 0`), rounds
    /// each output once. `T_L = −½ m [Δn (v_cn + V_cn) + Δt (v_ct + V_ct)]`.
    #[allow(clippy::too_many_arguments)] // each argument is one named part of the answer
    #[inline(always)]
    fn assemble(
        &self,
        e: &N,
        kinetic_restitution: Option<f64>,
        regime: Regime,
        a: &Answer<N>,
        known_critical: Option<Option<N>>,
        outputs: Outputs,
        law: Input,
    ) -> Exact<N, PlanarOutcome> {
        let mu = a.mu.as_ref().ok_or(ImpactError::OutputNotFinite {
            output: Output::ImpulseRatio,
        })?;
        let work =
            a.dn.mul(&self.vcn.add(&a.vcn))
                .add(&a.dt.mul(&self.vct.add(&a.vct)));
        if sign(&work)? == Ordering::Greater {
            return Err(ImpactError::CreatesEnergy {
                input: law,
                impulse_ratio: mu.approx(),
                energy_loss: -0.5 * self.m.mul(&work).approx(),
                admissible: admissible_interval(self.fast, e.approx()),
            }
            .into());
        }
        let w = self.w.add(&a.dw);
        // V_n = V_cn − d_c Ω and V_t = V_ct + d_d Ω (the definitions of the contact
        // velocities), equal in exact arithmetic to v_n + Δn and v_t + Δt: formed
        // so, a zero of V_ct (sticking) or of d_d, d_c stays structural and is
        // decided without a quotient.
        let vn = a.vcn.sub(&self.dc.mul(&w));
        let vt = a.vct.add(&self.dd.mul(&w));
        let final_velocity = PlanarVelocity {
            normal: out(Output::FinalNormalVelocity, &vn)?,
            tangential: out(Output::FinalTangentialVelocity, &vt)?,
            angular: out(Output::FinalAngularVelocity, &w)?,
        };
        let final_contact = ContactVelocity {
            normal: out(Output::FinalNormalContactVelocity, &a.vcn)?,
            tangential: out(Output::FinalTangentialContactVelocity, &a.vct)?,
        };
        let impulse = Impulse {
            normal: out(Output::NormalImpulse, &self.m.mul(&a.dn))?,
            tangential: out(Output::TangentialImpulse, &self.m.mul(&a.dt))?,
        };
        let impulse_ratio = out(Output::ImpulseRatio, mu)?;
        let critical = match known_critical {
            Some(known) if outputs.critical_impulse_ratio || known.is_some() => Some(known),
            None if outputs.critical_impulse_ratio => Some(self.critical_ratio(&a.qn)?),
            _ => None,
        };
        let critical_impulse_ratio = match critical {
            Some(Some(mu_c)) => Some(out(Output::CriticalImpulseRatio, &mu_c)?),
            Some(None) => {
                return Err(ImpactError::OutputNotFinite {
                    output: Output::CriticalImpulseRatio,
                }
                .into());
            }
            None => None,
        };
        let energy = if outputs.energy {
            Some(self.energy(&work)?)
        } else {
            None
        };
        let restitution = out(Output::Restitution, e)?;
        let fused = self.fast.contact_velocity;
        // One FMA each: already the correctly rounded values, but a zero may
        // hide a value below the f64 range (or carry the sign of a −0 input).
        let initial = ContactVelocity {
            normal: if fused.normal == 0.0 {
                out(Output::InitialNormalContactVelocity, &self.vcn)?
            } else {
                fused.normal
            },
            tangential: if fused.tangential == 0.0 {
                out(Output::InitialTangentialContactVelocity, &self.vct)?
            } else {
                fused.tangential
            },
        };
        Ok(PlanarOutcome {
            final_velocity,
            contact_velocity: ContactVelocities {
                initial,
                r#final: final_contact,
            },
            impulse,
            impulse_ratio,
            critical_impulse_ratio,
            restitution,
            kinetic_restitution: kinetic_restitution.unwrap_or(restitution),
            regime,
            energy,
        })
    }

    /// The initial energy `½ m (v_n² + v_t²) + ½ I ω²`, the loss from the work
    /// (Eq 8), the final energy as their difference (the work form equals
    /// `T_0 − T_f` exactly, by the moment equation),
    /// `T_M = ½ m [k² (v_cn² + v_ct²) + (d_d v_cn + d_c v_ct)²] / S` and `T_L* = T_L / T_M`.
    #[inline(always)]
    fn energy(&self, work: &N) -> Exact<N, PlanarEnergy> {
        // ½ m and ½ I are exact (unless below the normal range, where the bound says so).
        let half_m = half::<N>().mul(&self.m);
        let half_i = half::<N>().mul(&self.inertia);
        let initial = half_m
            .mul(&self.vn.mul(&self.vn).add(&self.vt.mul(&self.vt)))
            .add(&half_i.mul(&self.w.mul(&self.w)));
        let loss = half_m.mul(work).neg();
        let speed2 = self.vcn.mul(&self.vcn).add(&self.vct.mul(&self.vct));
        let lever = self.dd.mul(&self.vcn).add(&self.dc.mul(&self.vct));
        let max_loss = half_m
            .mul(&self.k2.mul(&speed2).add(&lever.mul(&lever)))
            .mul(self.inv_total());
        Ok(PlanarEnergy {
            initial: out(Output::InitialEnergy, &initial)?,
            r#final: out(Output::FinalEnergy, &initial.sub(&loss))?,
            loss: out(Output::EnergyLoss, &loss)?,
            max_loss: out(Output::MaxEnergyLoss, &max_loss)?,
            normalized_loss: out(Output::NormalizedEnergyLoss, &loss.div(&max_loss))?,
        })
    }
}

/// One answer in the field: per-unit-mass impulses, spin change, final contact
/// velocity and the impulse ratio (absent when `Δn = 0`).
#[derive(Clone)]
struct Answer<N> {
    /// `q_n`, the change of `v_cn` (its `V_cn = v_cn + q_n`).
    qn: N,
    dn: N,
    dt: N,
    dw: N,
    vcn: N,
    vct: N,
    mu: Option<N>,
}

/// A planar impact in the field `N`, in a scene whose inputs are validated.
pub(crate) fn planar<N: Field>(
    scene: &PlanarScene,
    e: f64,
    law: PlanarLaw,
    outputs: Outputs,
) -> Exact<N, PlanarOutcome> {
    let sc = Scene::<N>::new(scene);
    let e_n = N::of(e);
    match law {
        PlanarLaw::Frictionless => {
            let answer = sc.ratio_answer(&e_n, &sc.normal_target(&e_n), 0.0, Input::Restitution)?;
            sc.assemble(
                &e_n,
                None,
                Regime::Frictionless,
                &answer,
                None,
                outputs,
                Input::Restitution,
            )
        }
        PlanarLaw::Ratio(mu) => {
            let answer = sc.ratio_answer(&e_n, &sc.normal_target(&e_n), mu, Input::ImpulseRatio)?;
            sc.assemble(
                &e_n,
                None,
                Regime::Prescribed,
                &answer,
                None,
                outputs,
                Input::ImpulseRatio,
            )
        }
        PlanarLaw::Bilinear { f, et, capped } => sc.bilinear(&e_n, f, et, capped, outputs),
        PlanarLaw::Kinetic { r, mu_a, mu_r } => sc.kinetic(r, mu_a, mu_r, outputs),
    }
}

/// A point mass: `V_n = −e v_n`, `P_n = m (1 + e)(−v_n)`, `μ_c = v_t / ((1 + e) v_n)`,
/// `T_M` the whole initial energy, `T_L = ½ m (1 − e)(1 + e) v_n²`.
pub(crate) fn point_mass<N: Field>(p: &PointMass, outputs: Outputs) -> Exact<N, PlanarOutcome> {
    let PointMass { mass: m, vn, vt, e } = *p;
    let (m_n, vn_n, vt_n, e_n) = (N::of(m), N::of(vn), N::of(vt), N::of(e));
    let one = N::of(1.0);
    let final_normal = out(Output::FinalNormalVelocity, &e_n.mul(&vn_n).neg())?;
    let qn = one.add(&e_n).mul(&vn_n).neg();
    let normal_impulse = out(Output::NormalImpulse, &m_n.mul(&qn))?;
    let critical_impulse_ratio = if outputs.critical_impulse_ratio {
        Some(out(Output::CriticalImpulseRatio, &vt_n.div(&qn.neg()))?)
    } else {
        None
    };
    let energy = if outputs.energy {
        let translation = |vn: &N| half::<N>().mul(&m_n).mul(&vn.mul(vn).add(&vt_n.mul(&vt_n)));
        let initial = translation(&vn_n);
        let loss = half::<N>()
            .mul(&m_n)
            .mul(&one.sub(&e_n))
            .mul(&one.add(&e_n))
            .mul(&vn_n.mul(&vn_n));
        let initial_out = out(Output::InitialEnergy, &initial)?;
        Some(PlanarEnergy {
            initial: initial_out,
            r#final: out(Output::FinalEnergy, &translation(&e_n.mul(&vn_n)))?,
            loss: out(Output::EnergyLoss, &loss)?,
            max_loss: initial_out,
            normalized_loss: out(Output::NormalizedEnergyLoss, &loss.div(&initial))?,
        })
    } else {
        None
    };
    Ok(p.outcome(final_normal, normal_impulse, critical_impulse_ratio, energy))
}

/// The torsional model (Eqs 28–31) in the field: switch
/// `ω_s = μ_z ρ_p m (1 + e)(−v_n) / I_n`; `Ω_n = −e_z ω_n` for `|ω_n| ≤ ω_s`,
/// else `Ω_n = sgn(ω_n) [(1 − e_z)|ω_n| − ω_s]`.
pub(crate) fn torsional<N: Field>(v: &Validated, energy: bool) -> Exact<N, TorsionalOutcome> {
    let one = N::of(1.0);
    let (m, i_n, vn, w, e, ez) = (
        N::of(v.m),
        N::of(v.i_n),
        N::of(v.vn),
        N::of(v.w),
        N::of(v.e),
        N::of(v.ez),
    );
    let qn = one.add(&e).mul(&vn).neg();
    let switch = N::of(v.mu_z).mul(&N::of(v.rho)).mul(&qn).mul(&m).div(&i_n);
    let magnitude = abs(&w)?;
    let (regime, spin) = if sign(&switch.sub(&magnitude))? != Ordering::Less {
        (TorsionalRegime::Restitution, ez.mul(&w).neg())
    } else {
        let remaining = one.sub(&ez).mul(&magnitude).sub(&switch);
        let spin = if v.w < 0.0 { remaining.neg() } else { remaining };
        (TorsionalRegime::Sliding, spin)
    };
    let energy = if energy {
        let half_i = half::<N>().mul(&i_n);
        Some(RotationalEnergy {
            initial: out(Output::InitialEnergy, &half_i.mul(&w.mul(&w)))?,
            r#final: out(Output::FinalEnergy, &half_i.mul(&spin.mul(&spin)))?,
            loss: out(Output::EnergyLoss, &half_i.mul(&w.sub(&spin)).mul(&w.add(&spin)))?,
        })
    } else {
        None
    };
    Ok(TorsionalOutcome {
        final_normal_velocity: out(Output::FinalNormalVelocity, &e.mul(&vn).neg())?,
        final_spin: out(Output::FinalSpin, &spin)?,
        normal_impulse: out(Output::NormalImpulse, &m.mul(&qn))?,
        torsional_impulse: out(Output::TorsionalImpulse, &i_n.mul(&spin.sub(&w)))?,
        regime,
        switch_spin: out(Output::SwitchSpin, &switch)?,
        energy,
    })
}
