//! The batch kernel of the commonest sweep: Coulomb friction on one rigid
//! lamina against a barrier, [`LANES`] impacts at a time, in `fast` precision.
//!
//! It is the planar model of this directory (`planar.rs`'s scene and
//! assembly, `contact.rs`'s `bilinear` law with `e_t = 0`, `finish`)
//! evaluated operation for operation in [`Lanes`], whose every operation is
//! [`Filtered`](crate::arith::Filtered)'s rule lane by lane: each lane's
//! values, bounds and decisions are bit for bit those of the scalar
//! evaluation. Where lanes take different branches (sticking or sliding, a
//! central contact or not) both are formed and each lane keeps its own.
//!
//! A lane is answered only when every decision on its own path is certain
//! and its answer is accepted with finite outputs; every other lane (an
//! input outside the fast range or invalid, a decision within its error
//! bound of a tie, a refusal, an overflow) is left to the caller, who solves
//! it alone as a single impact is solved. So a sweep's answers are the
//! single solves' answers, bit for bit, which `tests/lanes.rs` checks on
//! random scenes and at every switch of the law.
//!
//! Keep it in step with the model: a change to the planar model's forms
//! must be made here too, or that test fails.

use std::cmp::Ordering;

use crate::arith::{LANES, Lanes};
#[cfg(test)]
use crate::impact::PlanarBody;
use crate::impact::in_fast_range;
use crate::outcome::{ContactVelocities, Impulse, Outputs, PlanarEnergy, PlanarOutcome, Regime};
use crate::scene::{ContactVelocity, PlanarVelocity};

/// The inputs of [`LANES`] impacts of a rigid lamina under Coulomb friction.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct CoulombLanes {
    pub mass: [f64; LANES],
    pub inertia: [f64; LANES],
    /// `d_c`.
    pub dc: [f64; LANES],
    /// `d_d`.
    pub dd: [f64; LANES],
    pub vn: [f64; LANES],
    pub vt: [f64; LANES],
    pub w: [f64; LANES],
    pub restitution: [f64; LANES],
    pub friction: [f64; LANES],
}

/// The lanes' outputs as the scalar `out` forms them (`h + 0`), clearing `ok`
/// where one is not finite.
#[inline(always)]
fn rounded(x: &Lanes, ok: &mut [bool; LANES]) -> [f64; LANES] {
    let h = x.values();
    std::array::from_fn(|i| {
        ok[i] &= h[i].is_finite();
        h[i] + 0.0
    })
}

/// Whether each lane's sign is decided and satisfies `want`, clearing `ok` where it is undecided.
#[inline(always)]
fn decided(signs: &[Option<Ordering>; LANES], ok: &mut [bool; LANES]) -> [Ordering; LANES] {
    std::array::from_fn(|i| {
        ok[i] &= signs[i].is_some();
        signs[i].unwrap_or(Ordering::Equal)
    })
}

/// Answers the lanes it can into `out` and returns which; see the module documentation.
#[inline(always)]
pub(crate) fn coulomb(x: &CoulombLanes, outputs: Outputs, out: &mut [PlanarOutcome; LANES]) -> [bool; LANES] {
    // The scene as `PlanarScene::new` forms it, validated as `PlanarImpact`
    // validates it (stricter: every input in the fast range).
    let k2_rounded: [f64; LANES] = std::array::from_fn(|i| x.inertia[i] / x.mass[i]);
    let vcn_fused: [f64; LANES] = std::array::from_fn(|i| x.dc[i].mul_add(x.w[i], x.vn[i]));
    let vct_fused: [f64; LANES] = std::array::from_fn(|i| (-x.dd[i]).mul_add(x.w[i], x.vt[i]));
    let mut ok: [bool; LANES] = std::array::from_fn(|i| {
        [
            x.mass[i],
            x.inertia[i],
            x.dc[i],
            x.dd[i],
            x.vn[i],
            x.vt[i],
            x.w[i],
            x.restitution[i],
            x.friction[i],
        ]
        .into_iter()
        .all(in_fast_range)
            && x.mass[i] > 0.0
            && x.inertia[i] > 0.0
            && (0.0..=1.0).contains(&x.restitution[i])
            && x.friction[i] >= 0.0
            && vcn_fused[i] < 0.0
    });
    let central: [bool; LANES] = std::array::from_fn(|i| x.dc[i] == 0.0);
    let on_normal: [bool; LANES] = std::array::from_fn(|i| x.dd[i] == 0.0);

    // planar.rs, Scene::new.
    let m = Lanes::exact(x.mass);
    let inertia = Lanes::exact(x.inertia);
    let dc = Lanes::exact(x.dc);
    let dd = Lanes::exact(x.dd);
    let vn = Lanes::exact(x.vn);
    let vt = Lanes::exact(x.vt);
    let w = Lanes::exact(x.w);
    let vcn = dc.mul_add(&w, &vn);
    let vct = dd.neg().mul_add(&w, &vt);
    let k2 = Lanes::quotient_of(x.inertia, k2_rounded);
    let dd2 = dd.mul(&dd);
    let k2_dc2 = dc.mul_add(&dc, &k2);
    let s = vcn.neg();
    let k2_dd2 = k2.add(&dd2);
    let wnt = dc.mul(&dd).neg();
    let total = k2_dc2.add(&dd2);
    let one = Lanes::splat(1.0);
    let inv_total = one.div(&total);

    // contact.rs, bilinear with e_t = 0: the target answer (U_t = 0).
    let e = Lanes::exact(x.restitution);
    let et = Lanes::splat(0.0);
    let qn = one.add(&e).mul(&s);
    let qt = one.add(&et).mul(&vct);
    let sdn = k2_dd2.mul_add(&qn, &wnt.mul(&qt));
    let sdt = wnt.neg().mul_add(&qn, &k2_dc2.mul(&qt).neg());
    let sdn_signs = sdn.signs();
    let sdn_sign = decided(&sdn_signs, &mut ok);
    let mu_target = sdt.div(&sdn);
    let has_target: [bool; LANES] = std::array::from_fn(|i| sdn_sign[i] != Ordering::Equal);
    let un = e.mul(&vcn).neg();
    let normal_sum = one.sub(&e).mul(&vcn);
    let target_ut = et.mul(&vct).neg();
    let target_sum = one.sub(&et).mul(&vct);
    let target_dn = Lanes::select(central, &qn, &sdn.mul(&inv_total));
    let target_dt = sdt.mul(&inv_total);
    let target_turn = dc.mul_add(&qn, &dd.mul(&qt)).mul(&inv_total);

    // |det Δt| ≤ f |det Δn|, where the target ratio exists.
    let sdt_signs = sdt.signs();
    let f = Lanes::exact(x.friction);
    let room = f.mul(&sdn.abs(&sdn_signs)).sub(&sdt.abs(&sdt_signs));
    let room_signs = room.signs();
    let mut sticking = [false; LANES];
    for i in 0..LANES {
        if has_target[i] {
            ok[i] &= sdt_signs[i].is_some() && room_signs[i].is_some();
            if room_signs[i] != Some(Ordering::Less) {
                // A negative normal impulse has no solution: the scalar path refuses it.
                ok[i] &= sdn_sign[i] == Ordering::Greater;
                sticking[i] = true;
            }
        }
    }

    // Sliding opposes the slip; with none it follows the target ratio.
    let vct_signs = vct.signs();
    let direction: [f64; LANES] = std::array::from_fn(|i| match vct_signs[i] {
        Some(Ordering::Greater) => -1.0,
        Some(Ordering::Less) => 1.0,
        Some(Ordering::Equal) => match (sdt_signs[i], sdn_signs[i]) {
            (Some(Ordering::Less), Some(Ordering::Greater))
            | (Some(Ordering::Greater), Some(Ordering::Less)) => -1.0,
            _ => 1.0,
        },
        None => 1.0,
    });
    let mu_sliding: [f64; LANES] = std::array::from_fn(|i| direction[i] * x.friction[i] + 0.0);
    // ratio_answer: D(μ) k² > 0, then ratio_parts.
    let lever = Lanes::exact(mu_sliding.map(|mu| -mu)).mul_add(&dd, &dc);
    let d = dc.mul_add(&lever, &k2);
    let d_signs = d.signs();
    let mu = Lanes::exact(mu_sliding);
    let per = qn.div(&d);
    let sliding_dn = Lanes::select(central, &qn, &k2.mul(&per));
    let sliding_dt = mu.mul(&sliding_dn);
    let sliding_turn = lever.mul(&per);
    let dut = mu.mul_add(&k2_dd2, &wnt).mul(&per);
    let sliding_sum = Lanes::splat(2.0).mul_add(&vct, &dut);
    let sliding_ut = vct.add(&dut);
    for i in 0..LANES {
        if !sticking[i] {
            ok[i] &= vct_signs[i].is_some() && d_signs[i] == Some(Ordering::Greater);
            if vct_signs[i] == Some(Ordering::Equal) {
                ok[i] &= sdt_signs[i].is_some();
            }
        }
    }

    // The answer of each lane's regime, then finish: no energy created.
    let dn = Lanes::select(sticking, &target_dn, &sliding_dn);
    let dt = Lanes::select(sticking, &target_dt, &sliding_dt);
    let turn = Lanes::select(sticking, &target_turn, &sliding_turn);
    let final_ut = Lanes::select(sticking, &target_ut, &sliding_ut);
    let tangential_sum = Lanes::select(sticking, &target_sum, &sliding_sum);
    let impulse_ratio = Lanes::select(sticking, &mu_target, &mu);
    let work = dn.mul_add(&normal_sum, &dt.mul(&tangential_sum));
    let work_sign = decided(&work.signs(), &mut ok);
    for i in 0..LANES {
        ok[i] &= work_sign[i] != Ordering::Greater;
        // μ_c is known for this law and always reported: it needs Δn ≠ 0.
        ok[i] &= has_target[i];
    }

    // planar.rs, assemble.
    let final_w = w.add(&turn);
    let final_vn = Lanes::select(central, &un, &vn.add(&dn));
    let final_vt = Lanes::select(on_normal, &final_ut, &vt.add(&dt));
    let vn_out = rounded(&final_vn, &mut ok);
    let vt_out = rounded(&final_vt, &mut ok);
    let w_out = rounded(&final_w, &mut ok);
    let un_out = rounded(&un, &mut ok);
    let ut_out = rounded(&final_ut, &mut ok);
    let pn_out = rounded(&m.mul(&dn), &mut ok);
    let pt_out = rounded(&m.mul(&dt), &mut ok);
    let mu_out = rounded(&impulse_ratio, &mut ok);
    let critical_out = rounded(&mu_target, &mut ok);
    let e_out = rounded(&e, &mut ok);
    let vcn_out = rounded(&vcn, &mut ok);
    let vct_out = rounded(&vct, &mut ok);
    let energy = outputs.energy.then(|| {
        // planar.rs, Scene::energy.
        let half = Lanes::splat(0.5);
        let half_m = half.mul(&m);
        let half_i = half.mul(&inertia);
        let initial = half_m
            .mul(&vn.mul_add(&vn, &vt.mul(&vt)))
            .add(&half_i.mul(&w.mul(&w)));
        let loss_per_mass = half.mul(&work).neg();
        let loss = m.mul(&loss_per_mass);
        let speed2 = vcn.mul_add(&vcn, &vct.mul(&vct));
        let lever = dd.mul_add(&vcn, &dc.mul(&vct));
        let max_per_mass = half.mul(
            &k2.mul(&inv_total)
                .mul_add(&speed2, &lever.mul(&lever.mul(&inv_total))),
        );
        (
            rounded(&initial, &mut ok),
            rounded(&initial.sub(&loss), &mut ok),
            rounded(&loss, &mut ok),
            rounded(&m.mul(&max_per_mass), &mut ok),
            rounded(&loss_per_mass.div(&max_per_mass), &mut ok),
        )
    });
    for i in 0..LANES {
        if !ok[i] {
            continue;
        }
        out[i] = PlanarOutcome {
            final_velocity: PlanarVelocity {
                normal: vn_out[i],
                tangential: vt_out[i],
                angular: w_out[i],
            },
            contact_velocity: ContactVelocities {
                // The scene's fused values, or the exact zero one stands for.
                initial: ContactVelocity {
                    normal: if vcn_fused[i] == 0.0 {
                        vcn_out[i]
                    } else {
                        vcn_fused[i]
                    },
                    tangential: if vct_fused[i] == 0.0 {
                        vct_out[i]
                    } else {
                        vct_fused[i]
                    },
                },
                r#final: ContactVelocity {
                    normal: un_out[i],
                    tangential: ut_out[i],
                },
            },
            impulse: Impulse {
                normal: pn_out[i],
                tangential: pt_out[i],
            },
            impulse_ratio: mu_out[i],
            critical_impulse_ratio: Some(critical_out[i]),
            restitution: e_out[i],
            kinetic_restitution: e_out[i],
            regime: if sticking[i] {
                Regime::Sticking
            } else {
                Regime::Sliding
            },
            energy: energy.map(|(initial, r#final, loss, max_loss, normalized)| PlanarEnergy {
                initial: initial[i],
                r#final: r#final[i].max(0.0),
                loss: loss[i],
                max_loss: max_loss[i],
                normalized_loss: normalized[i].min(1.0),
            }),
        };
    }
    ok
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{Law, PlanarImpact, Precision, solve};
    use crate::rng::Rng;
    use crate::scene::Contact;

    /// A random Coulomb impact: typical, dyadic (exact zeros and ties), central
    /// or on the normal, and now and then an input outside the fast range or
    /// not valid at all.
    fn impact(rng: &mut Rng, n: usize) -> PlanarImpact {
        let dyadic = n % 3 == 0;
        let mut draw = |lo: f64, hi: f64| {
            let x = lo + (hi - lo) * rng.unit();
            if dyadic { (x * 8.0).round() / 8.0 } else { x }
        };
        let mass = draw(0.125, 4.0).max(0.125);
        let mut inputs = [
            mass,
            mass * draw(0.01, 2.0).max(0.125),
            if n % 5 == 1 { 0.0 } else { draw(-1.5, 1.5) },
            if n % 7 == 2 { 0.0 } else { draw(-1.5, 1.5) },
            -draw(0.0, 5.0),
            draw(-5.0, 5.0),
            draw(-3.0, 3.0),
            draw(0.0, 1.0),
            draw(0.0, 1.5),
        ];
        if n % 13 == 4 {
            let odd = [1e-250, 3e250, -1.0, 0.0, f64::NAN, 2.0, f64::INFINITY][n % 7];
            inputs[(n / 13) % inputs.len()] = odd;
        }
        let [m, i, dc, dd, vn, vt, w, e, f] = inputs;
        PlanarImpact::rigid(
            m,
            i,
            Contact {
                tangential_offset: dc,
                normal_offset: dd,
            },
            PlanarVelocity {
                normal: vn,
                tangential: vt,
                angular: w,
            },
            Law::Friction {
                restitution: e,
                friction: f,
            },
        )
    }

    /// Every lane the kernel answers is the single `fast` solve, bit for bit
    /// (compared through `Debug`, which tells every non-NaN double apart,
    /// `-0` from `0` included), with and without the energies; and it
    /// answers nearly every valid lane.
    #[test]
    fn answered_lanes_are_the_single_solves_bit_for_bit() {
        let mut rng = Rng::new(0x1a9e5);
        let (mut answered, mut lanes) = (0, 0);
        for group in 0..20_000 {
            let impacts: [PlanarImpact; LANES] = std::array::from_fn(|k| impact(&mut rng, group * LANES + k));
            let mut x = CoulombLanes::default();
            for (i, p) in impacts.iter().enumerate() {
                let PlanarBody::Rigid {
                    mass,
                    inertia,
                    contact,
                } = p.body
                else {
                    unreachable!()
                };
                let Law::Friction {
                    restitution,
                    friction,
                } = p.law
                else {
                    unreachable!()
                };
                x.mass[i] = mass;
                x.inertia[i] = inertia;
                x.dc[i] = contact.tangential_offset;
                x.dd[i] = contact.normal_offset;
                x.vn[i] = p.velocity.normal;
                x.vt[i] = p.velocity.tangential;
                x.w[i] = p.velocity.angular;
                x.restitution[i] = restitution;
                x.friction[i] = friction;
            }
            let outputs = if group % 2 == 0 {
                Outputs::ALL
            } else {
                Outputs::MINIMAL
            };
            let mut out = [PlanarOutcome::default(); LANES];
            let ok = coulomb(&x, outputs, &mut out);
            for i in 0..LANES {
                lanes += 1;
                if !ok[i] {
                    continue;
                }
                answered += 1;
                let single =
                    solve(&impacts[i], outputs, Precision::Fast).expect("an answered lane has an answer");
                assert_eq!(format!("{:?}", out[i]), format!("{single:?}"), "{:?}", impacts[i]);
            }
        }
        // Invalid or out-of-range inputs are one lane in 13, separating ones a few more.
        assert!(answered * 10 > lanes * 8, "{answered} of {lanes} lanes answered");
    }
}
