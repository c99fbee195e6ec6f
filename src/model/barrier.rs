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
//! This is the contact space ([`ContactSpace`]) the laws of `contact.rs` are
//! written in, scaled by `m k²`: `W̃ = [[k² + d_c², −d_c d_d], [−d_c d_d, k² + d_d²]]`.
//! Impulses are carried per unit mass (`Δn = P_n / m`, `Δt = P_t / m`) and
//! scaled by `k²` so that no `1/k²` can overflow.

use std::cmp::Ordering;

use super::contact::{Assembly, ContactSpace, Reduced, critical_output, under_law};
use super::{Exact, half, out, outs, sign};
use crate::arith::Field;
use crate::error::{ImpactError, Input, Output};
use crate::input::Law;
use crate::outcome::{BarrierOutcome, ContactVelocities, Impulse, Outputs, PlanarEnergy, Regime};
use crate::scene::{BarrierScene, ContactVelocity, PlanarVelocity};

/// A planar scene in the field: every input exactly, and `v_cn`, `v_ct`, `k²`,
/// `S`; the scenes of `L` points at once in a field of `L` lanes
/// ([`crate::arith::Lanes`]), of one point in every other.
struct Scene<'a, N, const L: usize> {
    /// The validated f64 scenes, one per lane (for error payloads and the
    /// fused contact velocities).
    fast: &'a [BarrierScene; L],
    /// Whether `d_c = 0` exactly: then `D = 1`, `S = k² + d_d²` and `Δn = q_n` in every answer.
    central: bool,
    /// Whether `d_d = 0` exactly.
    level: bool,
    m: N,
    inertia: N,
    k2: N,
    dc: N,
    dd: N,
    vn: N,
    vt: N,
    w: N,
    /// `v_cn`, `v_ct`, `s = −v_cn` and `W̃ = [[k² + d_c², −d_c d_d], [−d_c d_d, k² + d_d²]]`.
    reduced: Reduced<N>,
    /// `S = k² + d_c² + d_d²`.
    total: N,
}

impl<'a, N: Field, const L: usize> Scene<'a, N, L> {
    /// The scene in the field.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn new(fast: &'a [BarrierScene; L]) -> Exact<N, Self> {
        let m = N::of_lanes(|i| fast[i].body.mass());
        let inertia = N::of_lanes(|i| fast[i].body.inertia());
        let dc = N::of_lanes(|i| fast[i].contact.tangential_offset);
        let dd = N::of_lanes(|i| fast[i].contact.normal_offset);
        let vn = N::of_lanes(|i| fast[i].velocity.normal);
        let vt = N::of_lanes(|i| fast[i].velocity.tangential);
        let w = N::of_lanes(|i| fast[i].velocity.angular);
        let central = zero_in_every_lane(fast, &dc, |s| s.contact.tangential_offset)?;
        let level = zero_in_every_lane(fast, &dd, |s| s.contact.normal_offset)?;
        let vcn = dc.mul_add(&w, &vn);
        let vct = dd.neg().mul_add(&w, &vt);
        // k² = I/m, already rounded by the scene: f64 does not divide again.
        let k2 = N::quotient_of_lanes(|i| (fast[i].body.inertia(), fast[i].body.mass(), fast[i].k2));
        let dd2 = dd.mul(&dd);
        let k2_dc2 = dc.mul_add(&dc, &k2);
        let total = k2_dc2.add(&dd2);
        Ok(Scene {
            fast,
            central,
            level,
            reduced: Reduced {
                s: vcn.neg(),
                wtt: k2.add(&dd2),
                wnt: dc.mul(&dd).neg(),
                wnn: k2_dc2,
                un: vcn,
                ut: vct,
            },
            total,
            k2,
            m,
            inertia,
            dc,
            dd,
            vn,
            vt,
            w,
        })
    }

    /// `1 / S`, formed where it is read (the target law, the energy), not
    /// kept: a lazy cell's out-of-line initialiser took the scene's address,
    /// so every value of the scene was stored and loaded again and no `λ` of
    /// `Filtered` was folded. A law and the energy that both read it each
    /// form it (the exact fields divide twice then).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn inv_total(&self) -> N {
        N::of(1.0).div(&self.total)
    }
}

/// Whether the input `x` of every lane (`x(scene)`, `value` in the field)
/// is exactly zero: lanes of which some are zero and some not are decided
/// as a sign, which stops them (a field of one point never gets there).
#[cfg_attr(not(debug_assertions), inline(always))]
fn zero_in_every_lane<N: Field, const L: usize>(
    scenes: &[BarrierScene; L],
    value: &N,
    x: impl Fn(&BarrierScene) -> f64,
) -> Exact<N, bool> {
    let zeros = scenes.iter().filter(|s| x(s) == 0.0).count();
    if zeros == L || zeros == 0 {
        Ok(zeros == L)
    } else {
        Ok(sign(value)? == Ordering::Equal)
    }
}

impl<N: Field, const L: usize> ContactSpace<N> for Scene<'_, N, L> {
    /// `ΔΩ`.
    type Turn = N;
    type Outcome = [BarrierOutcome; L];

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn reduced(&self) -> &Reduced<N> {
        &self.reduced
    }

    /// `(D(μ) k², d_c − μ d_d)` with `D(μ) k² = k² + d_c (d_c − μ d_d)` (after Eq 7).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_coefficient(&self, mu: f64) -> (N, N) {
        let lever = N::of(-mu).mul_add(&self.dd, &self.dc);
        (self.dc.mul_add(&lever, &self.k2), lever)
    }

    /// (In lanes, the first lane's refusal: lanes that refuse are solved
    /// one by one.)
    fn no_impulse_solution(&self, mu: f64, law: Input) -> ImpactError {
        self.fast[0].no_impulse_solution(mu, law)
    }

    /// `Δn = k² q_n / (D k²)`; for central contact `D k² = k²`, so `Δn = q_n`
    /// exactly (a tie stays decidable).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_normal(&self, qn: &N, per: &N) -> N {
        if self.central {
            qn.clone()
        } else {
            self.k2.mul(per)
        }
    }

    /// `ΔΩ = (d_c − μ d_d) q_n / (D k²)`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_turn(&self, lever: &N, per: &N) -> N {
        lever.mul(per)
    }

    /// `1 / S`, `S = k² + d_c² + d_d²` (`det W̃ = k² S` in units of `m k²`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn inv_det(&self) -> N {
        self.inv_total()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn target_normal(&self, qn: &N, sdn: &N, inv_det: &N) -> N {
        if self.central {
            qn.clone()
        } else {
            sdn.mul(inv_det)
        }
    }

    /// `ΔΩ = (d_c q_n + d_d q_t) / S`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn target_turn(&self, qn: &N, qt: &N, inv_det: &N) -> N {
        self.dc.mul_add(qn, &self.dd.mul(qt)).mul(inv_det)
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add_turns(a: &N, b: &N) -> N {
        a.add(b)
    }

    fn creates_energy(&self, e: &N, mu: &N, work: &N, law: Input) -> ImpactError {
        ImpactError::CreatesEnergy {
            input: law,
            impulse_ratio: mu.approx(),
            energy_loss: -0.5 * self.m.mul(work).approx(),
            admissible: self.fast[0].admissible_interval(e.approx()),
        }
    }

    /// The outcome of one answer, each output rounded once (lane by lane).
    /// `T_L = −½ m [Δn (v_cn + V_cn) + Δt (v_ct + V_ct)]` is the work of the
    /// impulses (Kelvin and Tait, as in the Appendix), which never subtracts
    /// two nearly equal energies.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn assemble(&self, x: &Assembly<'_, N, N>, outcomes: &mut [BarrierOutcome; L]) -> Exact<N, ()> {
        let a = x.answer;
        let e = x.e;
        let w = self.w.add(&a.turn);
        // V_n = v_n + Δn and V_t = v_t + Δt, except where an offset is exactly 0:
        // then V_n = V_cn (d_c = 0) and V_t = V_ct (d_d = 0) by the definitions of
        // the contact velocities, so a sticking or plastic zero stays structural and
        // is decided without a quotient. (Forming V_t = V_ct + d_d Ω always would
        // cancel two terms d_d²/k² times larger than V_t when d_d² ≫ k².)
        let vn = if self.central {
            a.un.clone()
        } else {
            self.vn.add(&a.dn)
        };
        let vt = if self.level {
            a.ut.clone()
        } else {
            self.vt.add(&a.dt)
        };
        // Each output of every lane, in the order a single solve tests them
        // (the first refused is the one reported), then each lane's outcome.
        let final_velocity = [
            outs::<N, L>(Output::FinalNormalVelocity, &vn)?,
            outs(Output::FinalTangentialVelocity, &vt)?,
            outs(Output::FinalAngularVelocity, &w)?,
        ];
        let final_contact = [
            outs::<N, L>(Output::FinalNormalContactVelocity, &a.un)?,
            outs(Output::FinalTangentialContactVelocity, &a.ut)?,
        ];
        let impulse = [
            outs::<N, L>(Output::NormalImpulse, &self.m.mul(&a.dn))?,
            outs(Output::TangentialImpulse, &self.m.mul(&a.dt))?,
        ];
        let impulse_ratio = outs::<N, L>(Output::ImpulseRatio, x.mu)?;
        let critical_impulse_ratio = critical_output::<N, L>(&x.critical)?;
        let energy = if x.outputs.energy {
            Some(self.energy(&x.work).outputs::<L>()?)
        } else {
            None
        };
        let restitution = outs::<N, L>(Output::Restitution, e)?;
        // One FMA each: already the correctly rounded values, but a zero may
        // hide a value below the f64 range (or carry the sign of a −0 input).
        let fused = self.fast.map(|scene| scene.contact_velocity);
        let initial_normal = if fused.iter().any(|v| v.normal == 0.0) {
            outs::<N, L>(Output::InitialNormalContactVelocity, &self.reduced.un)?
        } else {
            fused.map(|v| v.normal)
        };
        let initial_tangential = if fused.iter().any(|v| v.tangential == 0.0) {
            outs::<N, L>(Output::InitialTangentialContactVelocity, &self.reduced.ut)?
        } else {
            fused.map(|v| v.tangential)
        };
        for (lane, outcome) in outcomes.iter_mut().enumerate() {
            let initial = ContactVelocity {
                normal: if fused[lane].normal == 0.0 {
                    initial_normal[lane]
                } else {
                    fused[lane].normal
                },
                tangential: if fused[lane].tangential == 0.0 {
                    initial_tangential[lane]
                } else {
                    fused[lane].tangential
                },
            };
            *outcome = BarrierOutcome {
                final_velocity: PlanarVelocity {
                    normal: final_velocity[0][lane],
                    tangential: final_velocity[1][lane],
                    angular: final_velocity[2][lane],
                },
                contact_velocity: ContactVelocities {
                    initial,
                    r#final: ContactVelocity {
                        normal: final_contact[0][lane],
                        tangential: final_contact[1][lane],
                    },
                },
                impulse: Impulse {
                    normal: impulse[0][lane],
                    tangential: impulse[1][lane],
                },
                impulse_ratio: impulse_ratio[lane],
                critical_impulse_ratio: critical_impulse_ratio[lane],
                restitution: restitution[lane],
                kinetic_restitution: x.kinetic_restitution.unwrap_or(restitution[lane]),
                regime: x.regime,
                energy: energy.map(|energy| energy[lane]),
            };
        }
        Ok(())
    }
}

/// The energies of an answer in the field, before their rounding
/// ([`Energies::output`]).
struct Energies<N> {
    initial: N,
    loss: N,
    /// `T_L / m`.
    loss_per_mass: N,
    /// `T_M / m`.
    max_per_mass: N,
    m: N,
}

impl<N: Field> Energies<N> {
    /// Each of `L` lanes' energies, each rounded once.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn outputs<const L: usize>(&self) -> Exact<N, [PlanarEnergy; L]> {
        let initial = outs::<N, L>(Output::InitialEnergy, &self.initial)?;
        let r#final = outs::<N, L>(Output::FinalEnergy, &self.initial.sub(&self.loss))?;
        let loss = outs::<N, L>(Output::EnergyLoss, &self.loss)?;
        let max_loss = outs::<N, L>(Output::MaxEnergyLoss, &self.m.mul(&self.max_per_mass))?;
        let normalized_loss = outs::<N, L>(
            Output::NormalizedEnergyLoss,
            &self.loss_per_mass.div(&self.max_per_mass),
        )?;
        let mut energies = [PlanarEnergy::default(); L];
        for (lane, energy) in energies.iter_mut().enumerate() {
            // The clamps only act on f64 roundings: the exact values satisfy them.
            *energy = PlanarEnergy {
                initial: initial[lane],
                r#final: r#final[lane].max(0.0),
                loss: loss[lane],
                max_loss: max_loss[lane],
                normalized_loss: normalized_loss[lane].min(1.0),
            };
        }
        Ok(energies)
    }
}

impl<N: Field, const L: usize> Scene<'_, N, L> {
    /// The initial energy `½ m (v_n² + v_t²) + ½ I ω²`, the loss from the work
    /// (Eq 8), the final energy as their difference (the work form equals
    /// `T_0 − T_f` exactly, by the moment equation), and
    /// `T_M / m = ½ [k² (v_cn² + v_ct²) + (d_d v_cn + d_c v_ct)²] / S`: the
    /// largest loss any impulse at C can produce (the contact point ends at
    /// rest, `P = −W⁻¹ v_c`); `T_L(P)` is a concave quadratic with its maximum
    /// there, hence `T_L* = T_L / T_M ≤ 1`. Losses are formed per unit mass and
    /// multiplied by `m` last, so `T_L*` never divides two underflowed energies.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn energy(&self, work: &N) -> Energies<N> {
        let half_m = half::<N>().mul(&self.m);
        let half_i = half::<N>().mul(&self.inertia);
        let initial = half_m
            .mul(&self.vn.mul_add(&self.vn, &self.vt.mul(&self.vt)))
            .add(&half_i.mul(&self.w.mul(&self.w)));
        let loss_per_mass = half::<N>().mul(work).neg();
        let loss = self.m.mul(&loss_per_mass);
        let inv_total = self.inv_total();
        let Reduced { un, ut, .. } = &self.reduced;
        let speed2 = un.mul_add(un, &ut.mul(ut));
        let lever = self.dd.mul_add(un, &self.dc.mul(ut));
        let max_per_mass = half::<N>().mul(
            &self
                .k2
                .mul(&inv_total)
                .mul_add(&speed2, &lever.mul(&lever.mul(&inv_total))),
        );
        Energies {
            initial,
            loss,
            loss_per_mass,
            max_per_mass,
            m: self.m.clone(),
        }
    }
}

/// A planar impact of a rigid body in the field `N`, in a validated scene
/// under a validated law.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn rigid<N: Field>(
    scene: &BarrierScene,
    law: &Law,
    outputs: Outputs,
    out: &mut BarrierOutcome,
) -> Exact<N, ()> {
    rigid_lanes::<N, 1>(
        std::array::from_ref(scene),
        law,
        outputs,
        std::array::from_mut(out),
    )
}

/// The impacts of `L` rigid bodies under one law in a field of `L` lanes
/// ([`crate::arith::Lanes`]), each in a validated scene: every outcome
/// written, or an error (in lanes, that the points are to be solved one by
/// one).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn rigid_lanes<N: Field, const L: usize>(
    scenes: &[BarrierScene; L],
    law: &Law,
    outputs: Outputs,
    out: &mut [BarrierOutcome; L],
) -> Exact<N, ()> {
    debug_assert_eq!(N::LANES, L);
    under_law(&Scene::<N, L>::new(scenes)?, law, outputs, out)
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
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn point_mass<N: Field>(
    p: &PointMass,
    outputs: Outputs,
    outcome: &mut BarrierOutcome,
) -> Exact<N, ()> {
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
    *outcome = BarrierOutcome {
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
    };
    Ok(())
}
