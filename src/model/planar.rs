//! The planar model: one rigid lamina (or a point mass) against a massive
//! barrier, every tangential law of the paper.
//!
//! The momentum equations (Eqs A-1…A-3)
//!
//! ```text
//! m (V_n − v_n) = P_n,   m (V_t − v_t) = P_t,   I (Ω − ω) = d_c P_n − d_d P_t
//! ```
//!
//! give the contact-point velocity change `ΔV_c = W P` with
//! `W = [[k² + d_c², −d_c d_d], [−d_c d_d, k² + d_d²]] / (m k²)` in `(n, t)` order.
//! An answer is fixed in one of two ways: by a given impulse ratio `μ`
//! ([`Scene::ratio_answer`], Eqs 5–7) or by a given final contact velocity
//! ([`Scene::target_answer`], Eqs 1, 20 and 3 together). Every law is one or
//! two of those with a decision between them. Impulses are carried per unit
//! mass (`Δn = P_n / m`, `Δt = P_t / m`) and scaled by `k²` so that no `1/k²`
//! can overflow.

use std::cell::OnceCell;
use std::cmp::Ordering;

use super::{Exact, abs, half, out, sign};
use crate::arith::Field;
use crate::error::{ImpactError, Input, Output};
use crate::impact::Law;
use crate::outcome::{ContactVelocities, Impulse, Outputs, PlanarEnergy, PlanarOutcome, Regime};
use crate::scene::{ContactVelocity, PlanarScene, PlanarVelocity};

/// A planar scene in the field: every input exactly, and `v_cn`, `v_ct`, `k²`, `S`.
struct Scene<'a, N> {
    /// The validated f64 scene (for error payloads and the fused contact velocities).
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

/// One answer in the field: per-unit-mass impulses, spin change, final contact
/// velocity, the sums `v_c + V_c` the work needs, and the impulse ratio
/// (absent when `Δn = 0`).
#[derive(Clone)]
struct Answer<N> {
    /// `q_n = (1 + e) s`, the change of `v_cn` restitution asks.
    qn: N,
    dn: N,
    dt: N,
    dw: N,
    /// `V_cn`.
    vcn: N,
    /// `V_ct`.
    vct: N,
    /// `v_cn + V_cn`, formed as `(1 − e) v_cn` (no cancellation for `e → 1`).
    normal_sum: N,
    /// `v_ct + V_ct`, formed without cancellation where the law allows.
    tangential_sum: N,
    mu: Option<N>,
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
        let vcn = dc.mul_add(&w, &vn);
        let vct = dd.neg().mul_add(&w, &vt);
        // k² = I/m, already rounded by the scene: f64 does not divide again.
        let k2 = N::quotient_of(fast.body.inertia(), fast.body.mass(), fast.k2);
        let dd2 = dd.mul(&dd);
        let k2_dc2 = dc.mul_add(&dc, &k2);
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

    /// Whether `d_c = 0` exactly: then `D = 1`, `S = k² + d_d²` and `Δn = q_n` in every answer.
    #[inline(always)]
    fn central(&self) -> bool {
        self.fast.contact.tangential_offset == 0.0
    }

    /// `1 / S`, formed once.
    #[inline(always)]
    fn inv_total(&self) -> &N {
        self.inv_total.get_or_init(|| N::of(1.0).div(&self.total))
    }

    /// `q_n = (1 + e)(−v_cn)`: the change of `v_cn` that restitution `e` asks (Eq 1).
    #[inline(always)]
    fn normal_target(&self, e: &N) -> N {
        N::of(1.0).add(e).mul(&self.s)
    }

    /// `(d_c − μ d_d, D(μ) k²)` with `D(μ) k² = k² + d_c (d_c − μ d_d)` (after
    /// Eq 7), refused (naming `law`) unless `D > 0`.
    #[inline(always)]
    fn positive_dk2(&self, mu: f64, law: Input) -> Exact<N, (N, N)> {
        let lever = N::of(-mu).mul_add(&self.dd, &self.dc);
        let dk2 = self.dc.mul_add(&lever, &self.k2);
        if sign(&dk2)? == Ordering::Greater {
            Ok((lever, dk2))
        } else {
            Err(self.fast.no_impulse_solution(mu, law).into())
        }
    }

    /// `(Δn, Δt, ΔΩ, ΔV_ct)` for ratio `μ` with `Δn D(μ) k² = q_n k²` (Eqs 5–7):
    /// `ΔΩ = (d_c − μ d_d) q_n / (D k²)`, `ΔV_ct = [μ (k² + d_d²) − d_c d_d] q_n / (D k²)`.
    #[inline(always)]
    fn ratio_parts(&self, qn: &N, mu: f64, lever: &N, dk2: &N) -> [N; 4] {
        let mu = N::of(mu);
        let per = qn.div(dk2);
        // Central contact: D k² = k², so Δn = q_n exactly (a tie stays decidable).
        let dn = if self.central() {
            qn.clone()
        } else {
            self.k2.mul(&per)
        };
        let dt = mu.mul(&dn);
        let dw = lever.mul(&per);
        let dvct = mu.mul_add(&self.k2_dd2, &self.cross.neg()).mul(&per);
        [dn, dt, dw, dvct]
    }

    /// The answer for a prescribed ratio `μ` with restitution `e` (`q_n` its
    /// [`Scene::normal_target`]).
    #[inline(always)]
    fn ratio_answer(&self, e: &N, qn: &N, mu: f64, law: Input) -> Exact<N, Answer<N>> {
        let (lever, dk2) = self.positive_dk2(mu, law)?;
        let [dn, dt, dw, dvct] = self.ratio_parts(qn, mu, &lever, &dk2);
        Ok(Answer {
            qn: qn.clone(),
            dn,
            dt,
            dw,
            vcn: e.mul(&self.vcn).neg(),
            normal_sum: N::of(1.0).sub(e).mul(&self.vcn),
            tangential_sum: N::of(2.0).mul_add(&self.vct, &dvct),
            vct: self.vct.add(&dvct),
            mu: Some(N::of(mu)),
        })
    }

    /// `S Δn = (k² + d_d²) q_n − d_c d_d q_t` and `S Δt = d_c d_d q_n − (k² + d_c²) q_t`:
    /// the impulses that change `v_cn` by `q_n` and `v_ct` by `−q_t`.
    #[inline(always)]
    fn scaled_impulses(&self, qn: &N, qt: &N) -> (N, N) {
        (
            self.k2_dd2.mul_add(qn, &self.cross.mul(qt).neg()),
            self.cross.mul_add(qn, &self.k2_dc2.mul(qt).neg()),
        )
    }

    /// The answer with `V_cn = −e v_cn` and `V_ct = −e_t v_ct` (Eqs 1, 20, 3),
    /// `q_t = (1 + e_t) v_ct`:
    /// `Δn = [(k² + d_d²) q_n − d_c d_d q_t] / S`, `Δt = [d_c d_d q_n − (k² + d_c²) q_t] / S`,
    /// `ΔΩ = [d_c q_n + d_d q_t] / S`, `S = k² + d_c² + d_d²`; for `d_c = 0` these
    /// are Eqs 21–23 and 25 (with `λ = ρ²/k²`). Also returns `S Δn` and `S Δt`,
    /// whose signs and ratio decide the bilinear law without a quotient.
    #[inline(always)]
    fn target_answer(&self, e: &N, qn: &N, et: f64) -> Exact<N, (Answer<N>, N, N)> {
        let qt = N::of(1.0).add(&N::of(et)).mul(&self.vct);
        let (sdn, sdt) = self.scaled_impulses(qn, &qt);
        let mu = (sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn));
        let inv_total = self.inv_total();
        let answer = Answer {
            vcn: e.mul(&self.vcn).neg(),
            vct: N::of(et).mul(&self.vct).neg(),
            normal_sum: N::of(1.0).sub(e).mul(&self.vcn),
            tangential_sum: N::of(1.0).sub(&N::of(et)).mul(&self.vct),
            dn: if self.central() {
                qn.clone()
            } else {
                sdn.mul(inv_total)
            },
            dt: sdt.mul(inv_total),
            dw: self.dc.mul_add(qn, &self.dd.mul(&qt)).mul(inv_total),
            qn: qn.clone(),
            mu,
        };
        Ok((answer, sdn, sdt))
    }

    /// `μ_c`: the ratio `Δt / Δn` of the answer that ends with `V_ct = 0`
    /// (`q_t = v_ct`) and changes `v_cn` by `q_n` (Eq 14 for `d_c = 0`),
    /// `None` if its `Δn = 0`.
    #[inline(always)]
    fn critical_ratio(&self, qn: &N) -> Exact<N, Option<N>> {
        let (sdn, sdt) = self.scaled_impulses(qn, &self.vct);
        Ok((sign(&sdn)? != Ordering::Equal).then(|| sdt.div(&sdn)))
    }

    /// The bilinear law (section 3; Coulomb friction for `e_t = 0`): the
    /// target answer `V_ct = −e_t v_ct` when its ratio satisfies `|μ| ≤ f`
    /// (regime `capped`), else sliding through separation with `|μ| = f`
    /// opposing the initial slip.
    fn bilinear(&self, e: &N, f: f64, et: f64, capped: Regime, outputs: Outputs) -> Exact<N, PlanarOutcome> {
        let qn = self.normal_target(e);
        let (target, sdn, sdt) = self.target_answer(e, &qn, et)?;
        // For e_t = 0 the target ratio is the critical ratio μ_c itself.
        let known_critical = (et == 0.0).then(|| target.mu.clone());
        if let Some(mu_target) = &target.mu {
            // |S Δt| ≤ f |S Δn|, i.e. |μ_target| ≤ f, decided without a quotient.
            let room = N::of(f).mul(&abs(&sdn)?).sub(&abs(&sdt)?);
            if sign(&room)? != Ordering::Less {
                if sign(&sdn)? == Ordering::Less {
                    return Err(self
                        .fast
                        .no_impulse_solution(mu_target.approx(), Input::Friction)
                        .into());
                }
                return self.assemble(e, None, capped, &target, known_critical, outputs, Input::Friction);
            }
        }
        // Sliding opposes the slip; with no initial slip it follows μ_target
        // (which exists then: v_ct = 0 gives Δn > 0).
        let direction = match sign(&self.vct)? {
            Ordering::Greater => -1.0,
            Ordering::Less => 1.0,
            Ordering::Equal => match (sign(&sdt)?, sign(&sdn)?) {
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
    /// `P_n^R = R P_n^A` with `μ_R`; `e = R D(μ_R) / D(μ_A)` (Eq 11, A-16). The
    /// reported ratio is the overall `μ = P_t / P_n`.
    fn kinetic(&self, r: f64, mu_a: f64, mu_r: f64, outputs: Outputs) -> Exact<N, PlanarOutcome> {
        let (lever_a, dk_a) = self.positive_dk2(mu_a, Input::ApproachImpulseRatio)?;
        let rebound = if r > 0.0 {
            Some(self.positive_dk2(mu_r, Input::ReboundImpulseRatio)?)
        } else {
            None
        };
        let e = match &rebound {
            Some((_, dk_r)) => N::of(r).mul(&dk_r.div(&dk_a)),
            None => N::of(0.0),
        };
        let approach = self.ratio_parts(&self.s, mu_a, &lever_a, &dk_a);
        let [dn, dt, dw, dvct] = match &rebound {
            Some((lever_r, dk_r)) => {
                let rebound = self.ratio_parts(&e.mul(&self.s), mu_r, lever_r, dk_r);
                [0, 1, 2, 3].map(|i| approach[i].add(&rebound[i]))
            }
            None => approach,
        };
        let answer = Answer {
            qn: self.normal_target(&e),
            mu: Some(dt.div(&dn)),
            vcn: e.mul(&self.vcn).neg(),
            normal_sum: N::of(1.0).sub(&e).mul(&self.vcn),
            tangential_sum: N::of(2.0).mul_add(&self.vct, &dvct),
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

    /// The outcome of one answer: refuses energy creation, rounds each output
    /// once. `T_L = −½ m [Δn (v_cn + V_cn) + Δt (v_ct + V_ct)]` is the work of
    /// the impulses (Kelvin and Tait, as in the Appendix), which never
    /// subtracts two nearly equal energies.
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
        let work = a.dn.mul_add(&a.normal_sum, &a.dt.mul(&a.tangential_sum));
        if sign(&work)? == Ordering::Greater {
            return Err(ImpactError::CreatesEnergy {
                input: law,
                impulse_ratio: mu.approx(),
                energy_loss: -0.5 * self.m.mul(&work).approx(),
                admissible: self.fast.admissible_interval(e.approx()),
            }
            .into());
        }
        let w = self.w.add(&a.dw);
        // V_n = v_n + Δn and V_t = v_t + Δt, except where an offset is exactly 0:
        // then V_n = V_cn (d_c = 0) and V_t = V_ct (d_d = 0) by the definitions of
        // the contact velocities, so a sticking or plastic zero stays structural and
        // is decided without a quotient. (Forming V_t = V_ct + d_d Ω always would
        // cancel two terms d_d²/k² times larger than V_t when d_d² ≫ k².)
        let vn = if self.central() {
            a.vcn.clone()
        } else {
            self.vn.add(&a.dn)
        };
        let vt = if self.fast.contact.normal_offset == 0.0 {
            a.vct.clone()
        } else {
            self.vt.add(&a.dt)
        };
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
    /// `T_0 − T_f` exactly, by the moment equation), and
    /// `T_M / m = ½ [k² (v_cn² + v_ct²) + (d_d v_cn + d_c v_ct)²] / S`: the
    /// largest loss any impulse at C can produce (the contact point ends at
    /// rest, `P = −W⁻¹ v_c`); `T_L(P)` is a concave quadratic with its maximum
    /// there, hence `T_L* = T_L / T_M ≤ 1`. Losses are formed per unit mass and
    /// multiplied by `m` last, so `T_L*` never divides two underflowed energies.
    #[inline(always)]
    fn energy(&self, work: &N) -> Exact<N, PlanarEnergy> {
        let half_m = half::<N>().mul(&self.m);
        let half_i = half::<N>().mul(&self.inertia);
        let initial = half_m
            .mul(&self.vn.mul_add(&self.vn, &self.vt.mul(&self.vt)))
            .add(&half_i.mul(&self.w.mul(&self.w)));
        let loss_per_mass = half::<N>().mul(work).neg();
        let loss = self.m.mul(&loss_per_mass);
        let inv_total = self.inv_total();
        let speed2 = self.vcn.mul_add(&self.vcn, &self.vct.mul(&self.vct));
        let lever = self.dd.mul_add(&self.vcn, &self.dc.mul(&self.vct));
        let max_per_mass = half::<N>().mul(
            &self
                .k2
                .mul(inv_total)
                .mul_add(&speed2, &lever.mul(&lever.mul(inv_total))),
        );
        // The clamps only act on f64 roundings: the exact values satisfy them.
        Ok(PlanarEnergy {
            initial: out(Output::InitialEnergy, &initial)?,
            r#final: out(Output::FinalEnergy, &initial.sub(&loss))?.max(0.0),
            loss: out(Output::EnergyLoss, &loss)?,
            max_loss: out(Output::MaxEnergyLoss, &self.m.mul(&max_per_mass))?,
            normalized_loss: out(Output::NormalizedEnergyLoss, &loss_per_mass.div(&max_per_mass))?.min(1.0),
        })
    }
}

/// A planar impact of a rigid body in the field `N`, in a validated scene
/// under a validated law.
pub(crate) fn rigid<N: Field>(scene: &PlanarScene, law: &Law, outputs: Outputs) -> Exact<N, PlanarOutcome> {
    let sc = Scene::<N>::new(scene);
    match *law {
        Law::Frictionless { restitution } => {
            let e = N::of(restitution);
            let answer = sc.ratio_answer(&e, &sc.normal_target(&e), 0.0, Input::Restitution)?;
            sc.assemble(
                &e,
                None,
                Regime::Frictionless,
                &answer,
                None,
                outputs,
                Input::Restitution,
            )
        }
        Law::ImpulseRatio {
            restitution,
            impulse_ratio,
        } => {
            let e = N::of(restitution);
            let answer = sc.ratio_answer(&e, &sc.normal_target(&e), impulse_ratio, Input::ImpulseRatio)?;
            sc.assemble(
                &e,
                None,
                Regime::Prescribed,
                &answer,
                None,
                outputs,
                Input::ImpulseRatio,
            )
        }
        Law::Friction {
            restitution,
            friction,
        } => sc.bilinear(&N::of(restitution), friction, 0.0, Regime::Sticking, outputs),
        Law::TangentialRestitution {
            restitution,
            friction,
            tangential_restitution,
        } => sc.bilinear(
            &N::of(restitution),
            friction,
            tangential_restitution,
            Regime::Restitution,
            outputs,
        ),
        Law::KineticRestitution {
            value,
            approach_impulse_ratio,
            rebound_impulse_ratio,
        } => sc.kinetic(value, approach_impulse_ratio, rebound_impulse_ratio, outputs),
    }
}

/// The validated inputs of a point-mass impact: `m > 0`, `v_n < 0`, `e ∈ [0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PointMass {
    pub mass: f64,
    pub vn: f64,
    pub vt: f64,
    pub e: f64,
}

/// A point mass (section 2.1): `V_n = −e v_n`, `P_n = m (1 + e)(−v_n)`, `V_t = v_t`;
/// `μ_c = v_t / ((1 + e) v_n)`, the limit of Eq 14 for `k → ∞`; `T_M` is the
/// whole initial energy (the mass stops), `T_L = ½ m (1 − e)(1 + e) v_n²`.
pub(crate) fn point_mass<N: Field>(p: &PointMass, outputs: Outputs) -> Exact<N, PlanarOutcome> {
    let PointMass { mass, vn, vt, e } = *p;
    let (m, vn_n, vt_n, e_n) = (N::of(mass), N::of(vn), N::of(vt), N::of(e));
    let one = N::of(1.0);
    let s = vn_n.neg();
    let final_normal = out(Output::FinalNormalVelocity, &e_n.mul(&vn_n).neg())?;
    let qn = one.add(&e_n).mul(&s);
    let normal_impulse = out(Output::NormalImpulse, &m.mul(&qn))?;
    let critical_impulse_ratio = if outputs.critical_impulse_ratio {
        Some(out(Output::CriticalImpulseRatio, &vt_n.div(&qn.neg()))?)
    } else {
        None
    };
    let energy = if outputs.energy {
        let half_m = half::<N>().mul(&m);
        let vt2 = vt_n.mul(&vt_n);
        let initial = half_m.mul(&vn_n.mul_add(&vn_n, &vt2));
        let rebound = e_n.mul(&vn_n);
        let loss = half_m.mul(&one.sub(&e_n).mul(&s)).mul(&qn);
        let initial_out = out(Output::InitialEnergy, &initial)?;
        // The clamps only act on f64 roundings: the exact values satisfy them.
        Some(PlanarEnergy {
            initial: initial_out,
            r#final: out(Output::FinalEnergy, &half_m.mul(&rebound.mul_add(&rebound, &vt2)))?,
            loss: out(Output::EnergyLoss, &loss)?.max(0.0),
            max_loss: initial_out,
            normalized_loss: out(Output::NormalizedEnergyLoss, &loss.div(&initial))?.min(1.0),
        })
    } else {
        None
    };
    Ok(PlanarOutcome {
        final_velocity: PlanarVelocity {
            normal: final_normal,
            tangential: vt + 0.0,
            angular: 0.0,
        },
        contact_velocity: ContactVelocities {
            initial: ContactVelocity {
                normal: vn,
                tangential: vt + 0.0,
            },
            r#final: ContactVelocity {
                normal: final_normal,
                tangential: vt + 0.0,
            },
        },
        impulse: Impulse {
            normal: normal_impulse,
            tangential: 0.0,
        },
        impulse_ratio: 0.0,
        critical_impulse_ratio,
        restitution: e + 0.0,
        kinetic_restitution: e + 0.0,
        regime: Regime::Frictionless,
        energy,
    })
}
