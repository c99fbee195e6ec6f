//! One point contact between two laminae, or one against a fixed barrier, in
//! world axes: the general planar contact whose special case is the paper's
//! one body against a barrier (`barrier.rs`).
//!
//! Each body `b` has mass `m_b`, inertia `I_b` about its mass centre `G_b`,
//! velocity `v_b` and angular velocity `ω_b`; the contact is a point `C` and a
//! normal `n` from B into A, not necessarily of unit length. With
//! `r_b = C − G_b`, `t = ẑ × n` and `N = [n t]`, the impulse on A is
//! `P = N q` (and `−P` on B) and the relative contact velocity in the
//! unnormalised frame is `ũ = Nᵀ u`; then `Δũ = W̃ q` with
//!
//! ```text
//! W̃ = α 1 + Σ_b ρ_b ρ_bᵀ / I_b,   α = |n|² Σ_b 1/m_b,   ρ_b = (r_b × n, r_b · n),
//! ```
//!
//! which is `|n|²` times the contact-space `W` of `ΔU = W P`. No square root
//! enters the laws: impulse ratios, decisions and energies are rational in the
//! inputs, and only outputs along `n̂ = n/|n|` (contact velocities, `P_n`,
//! `P_t`) and the magnitudes `|ΔV|` are `x √y`, rounded as such.
//!
//! For one body against a barrier with `n = x̂` and `r_A = −(d_d, d_c)` this
//! is `W̃ = W` of `barrier.rs` divided by `m k²`; the laws (`contact.rs`) are the same code.

use std::cmp::Ordering;

use super::contact::{Assembly, ContactSpace, Reduced, under_law};
use super::{Exact, half, outs, outs_times_sqrt, sign};
use crate::arith::Field;
use crate::error::{ImpactError, Input, Output};
use crate::input::{BodiesImpact, Lamina, Law};
use crate::outcome::{
    BODY_OUTPUTS, BodiesOutcome, BodyOutcome, ContactVelocities, Outputs, PlanarEnergy, WorldImpulse,
};
use crate::scene::ContactVelocity;

/// One body's geometry in the field: its mass and inertia, `1/m`, `1/I`,
/// `r = C − G` and `ρ`.
#[derive(Clone)]
struct Body<N> {
    m: N,
    inertia: N,
    inv_m: N,
    inv_i: N,
    r: [N; 2],
    /// `(r × n, r · n)`.
    rho: [N; 2],
}

impl<N: Field> Body<N> {
    /// Lamina `l`'s body terms for contact point `c` and normal `n` (a
    /// function, not a closure: inlined into the compiled copy that runs).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of(l: &Lamina, c: &[N; 2], n: &[N; 2]) -> Self {
        let r = contact_arm(l, c);
        let m = N::of(l.mass);
        let inertia = N::of(l.inertia);
        let one = N::of(1.0);
        Body {
            inv_m: one.div(&m),
            inv_i: one.div(&inertia),
            rho: [
                r[0].mul_add(&n[1], &r[1].mul(&n[0]).neg()),
                r[0].mul_add(&n[0], &r[1].mul(&n[1])),
            ],
            r,
            m,
            inertia,
        }
    }
}

/// One body's velocities in the field.
#[derive(Clone)]
struct Motion<N> {
    v: [N; 2],
    w: N,
}

impl<N: Field> Motion<N> {
    /// The velocities of lamina `l(i)` in lane `i`, with its contact-point
    /// velocity's normal and tangential parts (arm `r`, normal `n`, tangent
    /// `t`).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of<'l>(l: impl Fn(usize) -> &'l Lamina, r: &[N; 2], n: &[N; 2], t: &[N; 2]) -> (Self, N, N) {
        let motion = Motion {
            v: [
                N::of_lanes(|i| l(i).velocity[0]),
                N::of_lanes(|i| l(i).velocity[1]),
            ],
            w: N::of_lanes(|i| l(i).angular_velocity),
        };
        let u = contact_point_velocity(&motion.v, &motion.w, r);
        (motion, along(&u, n), along(&u, t))
    }
}

/// What a contact's masses, inertias, positions, point and normal give,
/// whatever the velocities: `n`, `t`, `|n|²`, the bodies' geometry and
/// `W̃`. A sweep that changes none of those inputs forms it once
/// (`crate::impact::bodies`).
#[derive(Clone)]
pub(crate) struct Geometry<N> {
    n: [N; 2],
    t: [N; 2],
    /// `|n|²`.
    nn: N,
    /// Body A, and B when `count` is 2 (else a copy of A, unused).
    bodies: [Body<N>; 2],
    count: usize,
    /// `W̃`: `W̃_nn`, `W̃_nt`, `W̃_tt`.
    w: [N; 3],
    alpha: N,
    inv_det: N,
}

impl<N: Field> Geometry<N> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn new(fast: &BodiesImpact) -> Self {
        let n = [N::of(fast.contact.normal[0]), N::of(fast.contact.normal[1])];
        let c = [N::of(fast.contact.point[0]), N::of(fast.contact.point[1])];
        let nn = n[0].mul_add(&n[0], &n[1].mul(&n[1]));
        let t = [n[1].neg(), n[0].clone()];
        let a = Body::of(&fast.a, &c, &n);
        let (bodies, count) = match &fast.b {
            Some(l) => ([a, Body::of(l, &c, &n)], 2),
            None => ([a.clone(), a], 1),
        };
        let bodies_in = &bodies[..count];
        let mut inv_mass = bodies_in[0].inv_m.clone();
        let mut wnn = N::of(0.0);
        let mut wnt = N::of(0.0);
        let mut wtt = N::of(0.0);
        let mut spread = N::of(0.0);
        for (k, b) in bodies_in.iter().enumerate() {
            if k > 0 {
                inv_mass = inv_mass.add(&b.inv_m);
            }
            let [rn, rt] = &b.rho;
            wnn = wnn.add(&rn.mul(rn).mul(&b.inv_i));
            wnt = wnt.add(&rn.mul(rt).mul(&b.inv_i));
            wtt = wtt.add(&rt.mul(rt).mul(&b.inv_i));
            spread = spread.add(&rn.mul_add(rn, &rt.mul(rt)).mul(&b.inv_i));
        }
        let alpha = nn.mul(&inv_mass);
        // det W̃ = α (α + Σ |ρ_b|²/I_b) + (ρ_A × ρ_B)² / (I_A I_B): a sum of
        // non-negative terms, never a difference of nearly equal products.
        let mut det = alpha.mul(&alpha.add(&spread));
        if let [a, b] = bodies_in {
            let cross = a.rho[0].mul_add(&b.rho[1], &a.rho[1].mul(&b.rho[0]).neg());
            det = det.add(&cross.mul(&cross).mul(&a.inv_i).mul(&b.inv_i));
        }
        Geometry {
            w: [alpha.add(&wnn), wnt, alpha.add(&wtt)],
            inv_det: N::of(1.0).div(&det),
            alpha,
            nn,
            n,
            t,
            bodies,
            count,
        }
    }
}

/// The relative normal contact velocity `ũ_n = (u_A − u_B) · n`, with
/// `u_b = v_b + ω_b ẑ × r_b`: the same operations in every field, so the f64
/// value the fast evaluation decides on is the one validation checked.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn approach<N: Field>(impact: &BodiesImpact) -> N {
    let n = [N::of(impact.contact.normal[0]), N::of(impact.contact.normal[1])];
    let c = [N::of(impact.contact.point[0]), N::of(impact.contact.point[1])];
    let mut un = body_normal_velocity(&impact.a, &c, &n);
    if let Some(b) = &impact.b {
        un = un.sub(&body_normal_velocity(b, &c, &n));
    }
    un
}

/// `u_b · n` of one body.
#[cfg_attr(not(debug_assertions), inline(always))]
fn body_normal_velocity<N: Field>(l: &Lamina, c: &[N; 2], n: &[N; 2]) -> N {
    let v = [N::of(l.velocity[0]), N::of(l.velocity[1])];
    let w = N::of(l.angular_velocity);
    along(&contact_point_velocity(&v, &w, &contact_arm(l, c)), n)
}

/// `r = C − G` of one body.
#[cfg_attr(not(debug_assertions), inline(always))]
fn contact_arm<N: Field>(l: &Lamina, c: &[N; 2]) -> [N; 2] {
    [c[0].sub(&N::of(l.position[0])), c[1].sub(&N::of(l.position[1]))]
}

/// The contact-point velocity `u = (v_x − ω r_y, v_y + ω r_x)` of a body
/// moving at `v`, `ω` with arm `r`.
#[cfg_attr(not(debug_assertions), inline(always))]
fn contact_point_velocity<N: Field>(v: &[N; 2], w: &N, r: &[N; 2]) -> [N; 2] {
    let ux = w.neg().mul_add(&r[1], &v[0]);
    let uy = w.mul_add(&r[0], &v[1]);
    [ux, uy]
}

/// `u · d`, fused as the approach decision forms it.
#[cfg_attr(not(debug_assertions), inline(always))]
fn along<N: Field>(u: &[N; 2], d: &[N; 2]) -> N {
    u[0].mul_add(&d[0], &u[1].mul(&d[1]))
}

/// A validated contact in the field: its geometry, its bodies' velocities
/// and its contact space; the contacts of `L` points sharing one geometry
/// and law in a field of `L` lanes ([`crate::arith::Lanes`]), of one point
/// in every other.
struct Scene<'g, N, const L: usize> {
    g: &'g Geometry<N>,
    /// Body A's, and B's when the geometry's `count` is 2.
    motion: [Motion<N>; 2],
    /// `ũ_n`, `ũ_t`, `s = −ũ_n` and `W̃`.
    reduced: Reduced<N>,
}

impl<'g, N: Field, const L: usize> Scene<'g, N, L> {
    /// The scene of the impacts `fast`, each with body B where the geometry
    /// has it (the caller's to check).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn new(g: &'g Geometry<N>, fast: &[BodiesImpact; L]) -> Self {
        let (n, t) = (&g.n, &g.t);
        // ũ_n by the operations of `approach`, which validation decided on.
        let (a, mut un, mut ut) = Motion::of(|i| &fast[i].a, &g.bodies[0].r, n, t);
        let motion = if g.count == 2 {
            let body_b = |i: usize| fast[i].b.as_ref().unwrap_or(&fast[i].a);
            let (b, bun, but) = Motion::of(body_b, &g.bodies[1].r, n, t);
            un = un.sub(&bun);
            ut = ut.sub(&but);
            [a, b]
        } else {
            [a.clone(), a]
        };
        let [wnn, wnt, wtt] = g.w.clone();
        Scene {
            g,
            motion,
            reduced: Reduced {
                s: un.neg(),
                un,
                ut,
                wnn,
                wnt,
                wtt,
            },
        }
    }

    /// `ũ_n / |n|` and friends: `x / |n|` correctly rounded, lane by lane.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn along(&self, output: Output, x: &N) -> Exact<N, [f64; L]> {
        outs_times_sqrt::<N, L>(output, &x.div(&self.g.nn), &self.g.nn)
    }

    /// The energies of the pair: `T = Σ ½ m v² + ½ I ω²`, the loss `−½ q·(ũ + Ũ)`
    /// (the work of the impulse), and `T_M = ½ ũᵀ W̃⁻¹ ũ` formed from
    /// `adj W̃ = α 1 + Σ ρ⊥ρ⊥ᵀ/I_b` as `½ [α |ũ|² + Σ (ρ_t ũ_n − ρ_n ũ_t)²/I_b] / det`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn energy(&self, work: &N) -> Exact<N, [PlanarEnergy; L]> {
        let h = half::<N>();
        let mut initial = N::of(0.0);
        let Reduced { un, ut, .. } = &self.reduced;
        let mut adjugate = self.g.alpha.mul(&un.mul_add(un, &ut.mul(ut)));
        for (b, motion) in self.g.bodies.iter().zip(&self.motion).take(self.g.count) {
            let (v, w) = (&motion.v, &motion.w);
            let linear = v[0].mul_add(&v[0], &v[1].mul(&v[1])).mul(&b.m);
            initial = initial.add(&h.mul(&b.inertia.mul(w).mul_add(w, &linear)));
            let lever = b.rho[1].mul_add(un, &b.rho[0].mul(ut).neg());
            adjugate = adjugate.add(&lever.mul(&lever).mul(&b.inv_i));
        }
        let loss = h.mul(work).neg();
        let max_loss = h.mul(&adjugate).mul(&self.g.inv_det);
        // Each output of every lane, in a single solve's order, then each
        // lane's energies. The clamps only act on f64 roundings: the exact
        // values satisfy them.
        let initial_energy = outs::<N, L>(Output::InitialEnergy, &initial)?;
        let final_energy = outs::<N, L>(Output::FinalEnergy, &initial.sub(&loss))?;
        let energy_loss = outs::<N, L>(Output::EnergyLoss, &loss)?;
        let max_energy_loss = outs::<N, L>(Output::MaxEnergyLoss, &max_loss)?;
        let normalized_loss = outs::<N, L>(Output::NormalizedEnergyLoss, &loss.div(&max_loss))?;
        Ok(std::array::from_fn(|lane| PlanarEnergy {
            initial: initial_energy[lane],
            r#final: final_energy[lane].max(0.0),
            loss: energy_loss[lane],
            max_loss: max_energy_loss[lane],
            normalized_loss: normalized_loss[lane].min(1.0),
        }))
    }
}

impl<N: Field, const L: usize> ContactSpace<N> for Scene<'_, N, L> {
    /// The spins follow from `q` at assembly.
    type Turn = ();
    type Outcome = [BodiesOutcome; L];

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn reduced(&self) -> &Reduced<N> {
        &self.reduced
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_coefficient(&self, mu: f64) -> (N, ()) {
        (N::of(mu).mul_add(&self.reduced.wnt, &self.reduced.wnn), ())
    }
    /// `D(μ) = (A + μ B) / α`: the one-body `D` for a barrier.
    fn no_impulse_solution(&self, mu: f64, law: Input) -> ImpactError {
        ImpactError::NoImpulseSolution {
            input: law,
            impulse_ratio: mu,
            d: self.ratio_coefficient(mu).0.div(&self.g.alpha).approx(),
        }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_normal(&self, _qn: &N, per: &N) -> N {
        per.clone()
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ratio_turn(&self, _lever: &(), _per: &N) {}
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn inv_det(&self) -> N {
        self.g.inv_det.clone()
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn target_normal(&self, _qn: &N, sdn: &N, inv_det: &N) -> N {
        sdn.mul(inv_det)
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn target_turn(&self, _qn: &N, _qt: &N, _inv_det: &N) {}
    fn creates_energy(&self, e: &N, mu: &N, work: &N, law: Input) -> ImpactError {
        ImpactError::CreatesEnergy {
            input: law,
            impulse_ratio: mu.approx(),
            energy_loss: -0.5 * work.approx(),
            admissible: crate::scene::admissible_interval(
                [
                    self.reduced.wnn.approx(),
                    self.reduced.wnt.approx(),
                    self.reduced.wtt.approx(),
                ],
                self.reduced.s.approx(),
                self.reduced.ut.approx(),
                e.approx(),
            ),
        }
    }
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add_turns(_a: &(), _b: &()) {}

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn assemble(&self, x: &Assembly<'_, N, ()>, outcomes: &mut [BodiesOutcome; L]) -> Exact<N, ()> {
        let a = x.answer;
        let (qn, qt) = (&a.dn, &a.dt);
        let [nx, ny] = &self.g.n;
        // P = q_n n + q_t t, t = (−n_y, n_x).
        let p = [nx.mul_add(qn, &ny.mul(qt).neg()), ny.mul_add(qn, &nx.mul(qt))];
        let p2 = p[0].mul_add(&p[0], &p[1].mul(&p[1]));
        // Each output of every lane, in the order a single solve tests them
        // (the first refused is the one reported), then each lane's outcome.
        let mut bodies = [[BodyOutcome::default(); 2]; L];
        for (k, (b, motion)) in self
            .g
            .bodies
            .iter()
            .zip(&self.motion)
            .take(self.g.count)
            .enumerate()
        {
            let names = &BODY_OUTPUTS[k];
            let signed = |v: N| if k == 0 { v } else { v.neg() };
            let dv = [signed(p[0].mul(&b.inv_m)), signed(p[1].mul(&b.inv_m))];
            let dw = signed(b.rho[0].mul_add(qn, &b.rho[1].mul(qt)).mul(&b.inv_i));
            let velocity = [
                outs::<N, L>(names[0], &motion.v[0].add(&dv[0]))?,
                outs::<N, L>(names[1], &motion.v[1].add(&dv[1]))?,
            ];
            let angular_velocity = outs::<N, L>(names[2], &motion.w.add(&dw))?;
            let velocity_change = [outs::<N, L>(names[3], &dv[0])?, outs::<N, L>(names[4], &dv[1])?];
            let delta_v = outs_times_sqrt::<N, L>(names[5], &b.inv_m, &p2)?;
            let angular_velocity_change = outs::<N, L>(names[6], &dw)?;
            for (lane, body) in bodies.iter_mut().enumerate() {
                body[k] = BodyOutcome {
                    velocity: [velocity[0][lane], velocity[1][lane]],
                    angular_velocity: angular_velocity[lane],
                    velocity_change: [velocity_change[0][lane], velocity_change[1][lane]],
                    delta_v: delta_v[lane],
                    angular_velocity_change: angular_velocity_change[lane],
                };
            }
        }
        let initial_contact = [
            self.along(Output::InitialNormalContactVelocity, &self.reduced.un)?,
            self.along(Output::InitialTangentialContactVelocity, &self.reduced.ut)?,
        ];
        let final_contact = [
            self.along(Output::FinalNormalContactVelocity, &a.un)?,
            self.along(Output::FinalTangentialContactVelocity, &a.ut)?,
        ];
        let impulse = [
            outs_times_sqrt::<N, L>(Output::NormalImpulse, qn, &self.g.nn)?,
            outs_times_sqrt::<N, L>(Output::TangentialImpulse, qt, &self.g.nn)?,
            outs::<N, L>(Output::ImpulseX, &p[0])?,
            outs::<N, L>(Output::ImpulseY, &p[1])?,
        ];
        let impulse_ratio = outs::<N, L>(Output::ImpulseRatio, x.mu)?;
        // `null` where the sticking impulse has no normal part (conventions, rule 5).
        let critical_impulse_ratio = match &x.critical {
            Some(Some(mu_c)) => outs::<N, L>(Output::CriticalImpulseRatio, mu_c)?.map(Some),
            Some(None) | None => [None; L],
        };
        let restitution = outs::<N, L>(Output::Restitution, x.e)?;
        let energy = if x.outputs.energy {
            Some(self.energy(&x.work)?)
        } else {
            None
        };
        for (lane, outcome) in outcomes.iter_mut().enumerate() {
            *outcome = BodiesOutcome {
                bodies: bodies[lane],
                body_count: self.g.count,
                contact_velocity: ContactVelocities {
                    initial: ContactVelocity {
                        normal: initial_contact[0][lane],
                        tangential: initial_contact[1][lane],
                    },
                    r#final: ContactVelocity {
                        normal: final_contact[0][lane],
                        tangential: final_contact[1][lane],
                    },
                },
                impulse: WorldImpulse {
                    normal: impulse[0][lane],
                    tangential: impulse[1][lane],
                    x: impulse[2][lane],
                    y: impulse[3][lane],
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

/// A validated planar contact in the field `N` under its validated law, with
/// its geometry when a sweep formed it once:
/// refused unless the contact approaches (`ũ_n < 0`, decided exactly in the
/// exact fields; the fast evaluation is only asked where validation found the
/// f64 sign certain).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn bodies<N: Field>(
    impact: &BodiesImpact,
    prepared: Option<&Geometry<N>>,
    outputs: Outputs,
    out: &mut BodiesOutcome,
) -> Exact<N, ()> {
    let formed;
    let geometry = match prepared {
        Some(geometry) => geometry,
        None => {
            formed = Geometry::new(impact);
            &formed
        }
    };
    bodies_lanes::<N, 1>(
        std::array::from_ref(impact),
        &impact.law,
        geometry,
        outputs,
        std::array::from_mut(out),
    )
}

/// The contacts of `L` points in a field of `L` lanes
/// ([`crate::arith::Lanes`]) under one validated law, sharing `geometry`
/// (each point with body B where the geometry has it): every outcome
/// written, or an error (in lanes, that the points are to be solved one by
/// one). Refused unless the contacts approach.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(crate) fn bodies_lanes<N: Field, const L: usize>(
    impacts: &[BodiesImpact; L],
    law: &Law,
    geometry: &Geometry<N>,
    outputs: Outputs,
    out: &mut [BodiesOutcome; L],
) -> Exact<N, ()> {
    let scene = Scene::<N, L>::new(geometry, impacts);
    if sign(&scene.reduced.s)? != Ordering::Greater {
        return Err(ImpactError::NotApproaching {
            input: Input::VelocityA,
            normal_contact_velocity: scene.reduced.un.approx() / geometry.nn.approx().sqrt(),
        }
        .into());
    }
    under_law(&scene, law, outputs, out)
}
