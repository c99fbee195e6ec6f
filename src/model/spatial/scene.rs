//! A validated contact in space in the field `N`: each body's mass and
//! inverse inertia in world axes, the contact matrix with the couple, and the
//! impulse of each combination of tangential and twist branches.

use super::*;

/// One body's mass properties and lever arm in the field.
#[derive(Clone)]
pub(super) struct Inertial<N> {
    pub(super) m: N,
    pub(super) inv_m: N,
    pub(super) tensor: Sym<N>,
    pub(super) inv_i: Sym<N>,
    pub(super) r: V3<N>,
}

impl<N: Field> Inertial<N> {
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn new(body: &RigidBody, c: &V3<N>) -> Self {
        let m = N::of(body.mass);
        let tensor = sym::<N>(&body.inertia);
        let (adj, det) = adjugate(&tensor);
        let inv_det = N::of(1.0).div(&det);
        let position = vector(body.position);
        Inertial {
            inv_m: N::of(1.0).div(&m),
            inv_i: sym_times(&adj, &inv_det),
            r: sub(c, &position),
            m,
            tensor,
        }
    }
}

/// One body's motion in the field: velocity `v` and angular velocity `ω`.
#[derive(Clone)]
pub(super) struct Motion<N> {
    pub(super) v: V3<N>,
    pub(super) w: V3<N>,
}

impl<N: Field> Motion<N> {
    /// The motion of each lane's body, `body(i)` its velocity and angular
    /// velocity at lane `i`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn of_lanes(body: impl Fn(usize) -> ([f64; 3], [f64; 3])) -> Self {
        Motion {
            v: lanes_vector(|i| body(i).0),
            w: lanes_vector(|i| body(i).1),
        }
    }

    /// The contact-point velocity `v + ω × r` of a body with lever arm `r`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn contact_velocity(&self, r: &V3<N>) -> V3<N> {
        point_velocity(&self.v, &self.w, r)
    }
}

/// The part of `x` normal to `n`, `x − a n` with `a = (x·n)/ν` given. Where
/// `n` lies along a coordinate axis (one non-zero component, read off the
/// inputs), that component of the part is the exact zero it is, rather than
/// the difference of two equal rounded values that no bound can tell from a
/// tiny one (a sphere on a level plane: the exact stages would otherwise
/// fall through to fractions). Every field gets the same value; in f64 the
/// difference is already `+0` for a normal of length a power of two.
#[cfg_attr(not(debug_assertions), inline(always))]
fn tangential_part<N: Field>(x: &V3<N>, a: &N, n: &V3<N>, axis: Option<usize>) -> V3<N> {
    let mut part = axpy(&a.neg(), n, x);
    if let Some(k) = axis {
        part[k] = N::of(0.0);
    }
    part
}

/// A contact in space before its velocities, in the field `N`: the normal,
/// the bodies' mass properties and lever arms, and the contact matrix with
/// the couple. It reads only masses, tensors, positions, the contact point
/// and the normal, so a sweep whose axes change none of them forms it once.
#[derive(Clone)]
pub(crate) struct Geometry<N> {
    pub(super) n: V3<N>,
    pub(super) nu: N,
    /// The coordinate axis `n` lies along, if it does ([`tangential_part`]).
    pub(super) axis: Option<usize>,
    pub(super) bodies: Vec<Inertial<N>>,
    pub(super) w_matrix: Sym<N>,
    pub(super) adj: Sym<N>,
    pub(super) det: N,
    /// `w` and `k` of the couple.
    pub(super) w: V3<N>,
    pub(super) k: N,
}

impl<N: Field> Geometry<N> {
    /// The geometry of a validated `impact`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn new(impact: &SpatialImpact) -> Self {
        let c: V3<N> = vector(impact.contact.point);
        let n = vector(impact.contact.normal);
        let nu = norm2(&n);
        let axis = match impact.contact.normal.map(|c| c != 0.0) {
            [true, false, false] => Some(0),
            [false, true, false] => Some(1),
            [false, false, true] => Some(2),
            _ => None,
        };
        let mut bodies = vec![Inertial::new(&impact.a, &c)];
        if let Some(b) = &impact.b {
            bodies.push(Inertial::new(b, &c));
        }
        // W = Σ 1/m + Σ cᵢᵀ I⁻¹ cⱼ with cᵢ = r × eᵢ; w = Σ (I⁻¹ n) × r; k = Σ nᵀ I⁻¹ n.
        let zero = N::of(0.0);
        let mut w_matrix: Sym<N> = std::array::from_fn(|_| zero.clone());
        let mut w = [zero.clone(), zero.clone(), zero.clone()];
        let mut k = zero.clone();
        for b in &bodies {
            let [rx, ry, rz] = &b.r;
            let columns = [
                [zero.clone(), rz.clone(), ry.neg()],
                [rz.neg(), zero.clone(), rx.clone()],
                [ry.clone(), rx.neg(), zero.clone()],
            ];
            let turned = [
                sym_mul(&b.inv_i, &columns[0]),
                sym_mul(&b.inv_i, &columns[1]),
                sym_mul(&b.inv_i, &columns[2]),
            ];
            let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
            for (slot, (i, j)) in pairs.into_iter().enumerate() {
                let mut entry = dot(&columns[i], &turned[j]);
                if i == j {
                    entry = entry.add(&b.inv_m);
                }
                w_matrix[slot] = w_matrix[slot].add(&entry);
            }
            let about = sym_mul(&b.inv_i, &n);
            w = add(&w, &cross(&about, &b.r));
            k = k.add(&dot(&n, &about));
        }
        let (adj, det) = adjugate(&w_matrix);
        Geometry {
            n,
            nu,
            axis,
            bodies,
            w_matrix,
            adj,
            det,
            w,
            k,
        }
    }
}

/// A validated contact in the field: its geometry and the velocities.
pub(super) struct Scene<'a, N> {
    pub(super) g: &'a Geometry<N>,
    /// Each body's motion (the second unused without a body B).
    pub(super) motion: [Motion<N>; 2],
    /// `u` (relative contact-point velocity), `u·n`, `u_t`, `s̃`.
    pub(super) u: V3<N>,
    pub(super) un: N,
    pub(super) ut: V3<N>,
    pub(super) s: N,
    /// `q = −(1 + e) u·n`.
    pub(super) q: N,
    pub(super) law: Reading,
    pub(super) twist: Option<&'a Twist>,
    /// Solutions found so far, by `(branch, spin)`; the sticking one for `μ_c`.
    pub(super) cache: [Option<Option<Solution<N>>>; 12],
}

impl<'a, N: Radical> Scene<'a, N> {
    /// The scene of validated `impacts` whose geometry is `g`, one in each
    /// of the field's `L` lanes: points of one sweep that differ in the
    /// bodies' velocities alone (the law and twist read are the first's).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn new<const L: usize>(impacts: &'a [SpatialImpact; L], g: &'a Geometry<N>) -> Self {
        let impact = &impacts[0];
        let motion = |b: &RigidBody| (b.velocity, b.angular_velocity);
        let a = Motion::of_lanes(|i| motion(&impacts[i].a));
        let mut u = a.contact_velocity(&g.bodies[0].r);
        let mut spin = a.w.clone();
        let b = match (&impact.b, g.bodies.get(1)) {
            (Some(_), Some(inertial)) => {
                // Every lane has a body B where the first has (a sweep's
                // points share the base's bodies).
                let b = Motion::of_lanes(|i| impacts[i].b.as_ref().map_or(([0.0; 3], [0.0; 3]), motion));
                u = sub(&u, &b.contact_velocity(&inertial.r));
                spin = sub(&spin, &b.w);
                b
            }
            _ => Motion {
                v: vector([0.0; 3]),
                w: vector([0.0; 3]),
            },
        };
        let un = dot(&u, &g.n);
        let ut = tangential_part(&u, &un.div(&g.nu), &g.n, g.axis);
        let s = dot(&spin, &g.n);
        let law = Reading::of(&impact.law, impact.torsion.is_some());
        let q = N::of(1.0).add(&N::of(law.e)).mul(&un).neg();
        Scene {
            g,
            motion: [a, b],
            u,
            un,
            ut,
            s,
            q,
            law,
            twist: impact.torsion.as_ref(),
            cache: Default::default(),
        }
    }

    /// `(P, κ)` with its `P·n` and `P_t`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn solution(&self, p: V3<N>, kappa: N) -> Solution<N> {
        let pn = dot(&p, &self.g.n);
        let pt = tangential_part(&p, &pn.div(&self.g.nu), &self.g.n, self.g.axis);
        Solution { p, kappa, pn, pt }
    }

    /// The cache slot of `(t, z)`; the kept branch's sticking (`e_t = 0`)
    /// and restitution targets apart.
    pub(super) fn slot(t: Tangential, z: Spin, et: f64) -> usize {
        let stick = t == Tangential::Kept && et == 0.0;
        (t as usize) * 6 + (z as usize) * 2 + stick as usize
    }

    /// The solution of branches `(t, z)` (`None`: its system is singular),
    /// the kept branch targeting `U_t = −e_t u_t`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn solve(&mut self, t: Tangential, z: Spin, et: f64) -> Exact<N, Option<Solution<N>>> {
        let slot = Self::slot(t, z, et);
        if let Some(found) = &self.cache[slot] {
            return Ok(found.clone());
        }
        // `compute` reaches `solve` again (a branch may need another's
        // solution): the cycle's one out-of-line function is `run`'s, so it
        // is compiled into the copy that runs (its `fma`s one instruction).
        let found = crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || self.compute(t, z, et),
        )?;
        self.cache[slot] = Some(found.clone());
        Ok(found)
    }

    /// `κ = c₀ + c₁ (P·n)` of the sliding twist: `c₀ = −e_z s̃/k`,
    /// `c₁ = τ μ_z ρ_p/ν`, `τ = −sgn s̃` or, without spin, the sign of the
    /// restitution branch's couple with the same tangential branch.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn twist_terms(&mut self, t: Tangential, et: f64) -> Exact<N, (N, N)> {
        let Some(twist) = self.twist else {
            return Ok((N::of(0.0), N::of(0.0)));
        };
        let c0 = N::of(twist.restitution).mul(&self.s).div(&self.g.k).neg();
        let tau = match sign(&self.s)? {
            Ordering::Greater => -1.0,
            Ordering::Less => 1.0,
            Ordering::Equal => match self.solve(t, Spin::Restitution, et)? {
                Some(rest) => match sign(&rest.kappa)? {
                    Ordering::Greater => 1.0,
                    Ordering::Less => -1.0,
                    Ordering::Equal => 0.0,
                },
                None => 0.0,
            },
        };
        let c1 = N::of(tau * twist.friction)
            .mul(&N::of(twist.pitch_radius))
            .div(&self.g.nu);
        Ok((c0, c1))
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn compute(&mut self, t: Tangential, z: Spin, et: f64) -> Exact<N, Option<Solution<N>>> {
        let ds = match self.twist {
            Some(tw) => N::of(1.0).add(&N::of(tw.restitution)).mul(&self.s).neg(),
            None => N::of(0.0),
        };
        match t {
            Tangential::Kept => {
                let target = axpy(
                    &self.q.div(&self.g.nu),
                    &self.g.n,
                    &map(
                        &self.ut,
                        #[cfg_attr(not(debug_assertions), inline(always))]
                        |x| N::of(1.0).add(&N::of(et)).mul(x).neg(),
                    ),
                );
                let a = sym_mul(&self.g.adj, &target);
                match z {
                    Spin::Off => Ok(Some(self.solution(divide(&a, &self.g.det), N::of(0.0)))),
                    Spin::Restitution => {
                        let b = sym_mul(&self.g.adj, &self.g.w);
                        let schur = self.g.k.mul_add(&self.g.det, &dot(&self.g.w, &b).neg());
                        let kappa = ds.mul_add(&self.g.det, &dot(&self.g.w, &a).neg()).div(&schur);
                        let p = divide(&axpy(&kappa.neg(), &b, &a), &self.g.det);
                        Ok(Some(self.solution(p, kappa)))
                    }
                    Spin::Sliding => {
                        let (c0, c1) = self.twist_terms(t, et)?;
                        let rhs = axpy(&c0.neg(), &self.g.w, &target);
                        let a = sym_mul(&self.g.adj, &rhs);
                        let b = sym_mul(&self.g.adj, &self.g.w);
                        let den = c1.mul_add(&dot(&self.g.n, &b), &self.g.det);
                        if sign(&den)? == Ordering::Equal {
                            return Ok(None);
                        }
                        let na = dot(&self.g.n, &a);
                        let scale = self.g.det.mul(&den);
                        let p = zip(
                            &a,
                            &b,
                            #[cfg_attr(not(debug_assertions), inline(always))]
                            |ai, bi| ai.mul(&den).sub(&c1.mul(bi).mul(&na)).div(&scale),
                        );
                        let kappa = c1.mul_add(&dot(&p, &self.g.n), &c0);
                        Ok(Some(self.solution(p, kappa)))
                    }
                }
            }
            Tangential::Sliding => {
                let Some((d, along_normal)) = self.direction(z)? else {
                    return Ok(None);
                };
                let wd = sym_mul(&self.g.w_matrix, &d);
                let a11 = dot(&self.g.n, &wd);
                let (p_scale, kappa) = match z {
                    Spin::Off => {
                        if sign(&a11)? == Ordering::Equal {
                            return Ok(None);
                        }
                        (self.q.div(&a11), N::of(0.0))
                    }
                    Spin::Restitution => {
                        let a12 = dot(&self.g.n, &self.g.w);
                        let a21 = dot(&self.g.w, &d);
                        let det2 = a11.mul_add(&self.g.k, &a12.mul(&a21).neg());
                        if sign(&det2)? == Ordering::Equal {
                            return Ok(None);
                        }
                        (
                            self.q.mul_add(&self.g.k, &a12.mul(&ds).neg()).div(&det2),
                            a11.mul_add(&ds, &a21.mul(&self.q).neg()).div(&det2),
                        )
                    }
                    Spin::Sliding => {
                        let (c0, c1) = self.twist_terms(t, et)?;
                        let nw = dot(&self.g.n, &self.g.w);
                        let den = c1.mul(&self.g.nu).mul_add(&nw, &a11);
                        if sign(&den)? == Ordering::Equal {
                            return Ok(None);
                        }
                        let p_scale = nw.neg().mul_add(&c0, &self.q).div(&den);
                        let kappa = c1.mul(&self.g.nu).mul_add(&p_scale, &c0);
                        (p_scale, kappa)
                    }
                };
                let mut found = self.solution(scale(&p_scale, &d), kappa);
                if along_normal {
                    // P ∥ n: no tangential part, exactly (not a cancellation
                    // the bounded stages could not certify as zero).
                    found.pt = [N::of(0.0), N::of(0.0), N::of(0.0)];
                }
                Ok(Some(found))
            }
        }
    }

    /// The sliding impulse's direction `n + c √(ν/|w_s|²) w_s`, and whether
    /// it is `n` itself; `None` when the sticking system it needs is singular.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn direction(&mut self, z: Spin) -> Exact<N, Option<(V3<N>, bool)>> {
        if self.law.c == 0.0 {
            return Ok(Some((self.g.n.clone(), true)));
        }
        let slip = norm2(&self.ut);
        let (ws, size) = if sign(&slip)? == Ordering::Greater {
            (neg(&self.ut), slip)
        } else {
            let Some(stick) = self.solve(Tangential::Kept, z, 0.0)? else {
                return Ok(None);
            };
            let size = norm2(&stick.pt);
            if sign(&size)? == Ordering::Equal {
                if self.law.prescribed {
                    return Err(Fail::Refused(ImpactError::NoSlipDirection {
                        input: Input::ImpulseRatio,
                    }));
                }
                return Ok(Some((self.g.n.clone(), true)));
            }
            (stick.pt, size)
        };
        let root = self.g.nu.div(&size).sqrt().map_err(Fail::Undecided)?;
        let scale = N::of(self.law.c).mul(&root);
        Ok(Some((axpy(&scale, &ws, &self.g.n), false)))
    }

    /// Whether the kept tangential branch holds: `P·n ≠ 0`, `ν |P_t|² ≤ f² (P·n)²`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn tangential_holds(&self, s: &Option<Solution<N>>) -> Exact<N, bool> {
        let Some(s) = s else { return Ok(false) };
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(false);
        }
        let f = N::of(self.law.cap);
        let cap = f.mul(&s.pn);
        let room = cap.mul(&cap).sub(&self.g.nu.mul(&norm2(&s.pt)));
        Ok(sign(&room)? != Ordering::Less)
    }

    /// Whether the twist's restitution branch holds: `P·n ≠ 0`,
    /// `(κ + e_z s̃/k)² ≤ (μ_z ρ_p P·n/ν)²`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn spin_holds(&self, s: &Option<Solution<N>>) -> Exact<N, bool> {
        let (Some(s), Some(twist)) = (s, self.twist) else {
            return Ok(false);
        };
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(false);
        }
        let beyond = N::of(twist.restitution).mul(&self.s).div(&self.g.k).add(&s.kappa);
        let cap = N::of(twist.friction)
            .mul(&N::of(twist.pitch_radius))
            .mul(&s.pn)
            .div(&self.g.nu);
        Ok(sign(&cap.mul(&cap).sub(&beyond.mul(&beyond)))? != Ordering::Less)
    }

    /// The one valid combination of branches, with its solution.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn choose(&mut self) -> Exact<N, (Tangential, Spin, Option<Solution<N>>)> {
        let et = self.law.kept.unwrap_or(0.0);
        let tangentials: &[Tangential] = if self.law.kept.is_some() {
            &[Tangential::Kept, Tangential::Sliding]
        } else {
            &[Tangential::Sliding]
        };
        let spins: &[Spin] = if self.twist.is_some() {
            &[Spin::Restitution, Spin::Sliding]
        } else {
            &[Spin::Off]
        };
        // The count of valid combinations and the last one (no allocation per solve).
        let (mut count, mut chosen) = (0, (Tangential::Sliding, Spin::Off));
        for &t in tangentials {
            for &z in spins {
                let t_ok = match t {
                    Tangential::Kept => {
                        let s = self.solve(t, z, et)?;
                        self.tangential_holds(&s)?
                    }
                    Tangential::Sliding if self.law.kept.is_some() => {
                        let s = self.solve(Tangential::Kept, z, et)?;
                        !self.tangential_holds(&s)?
                    }
                    Tangential::Sliding => true,
                };
                if !t_ok {
                    continue;
                }
                let z_ok = match z {
                    Spin::Off => true,
                    Spin::Restitution => {
                        let s = self.solve(t, z, et)?;
                        self.spin_holds(&s)?
                    }
                    Spin::Sliding => {
                        let s = self.solve(t, Spin::Restitution, et)?;
                        !self.spin_holds(&s)?
                    }
                };
                if z_ok {
                    count += 1;
                    chosen = (t, z);
                }
            }
        }
        if count != 1 {
            return Err(Fail::Refused(ImpactError::NotUnique {
                input: Input::Torsion,
                combinations: count,
            }));
        }
        let (t, z) = chosen;
        Ok((t, z, self.solve(t, z, et)?))
    }

    /// `|P_t|/|P_n| = √(ν |P_t|²) / |P·n|` of a solution, a magnitude
    /// (`None` when `P·n = 0`), in each of `L` lanes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn ratio<const L: usize>(
        &self,
        s: &Solution<N>,
        output: Output,
    ) -> Exact<N, Option<[f64; L]>> {
        if sign(&s.pn)? == Ordering::Equal {
            return Ok(None);
        }
        let size = self.g.nu.mul(&norm2(&s.pt));
        Ok(Some(outs_times_sqrt::<N, L>(
            output,
            &N::of(1.0).div(&abs(&s.pn)?),
            &size,
        )?))
    }

    /// `x/|n|` correctly rounded, in each of `L` lanes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn along<const L: usize>(&self, output: Output, x: &N) -> Exact<N, [f64; L]> {
        outs_times_sqrt::<N, L>(output, &x.div(&self.g.nu), &self.g.nu)
    }

    /// A vector's three outputs, in each of `L` lanes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn vector_out<const L: usize>(outputs: [Output; 3], x: &V3<N>) -> Exact<N, [[f64; 3]; L]> {
        let x0 = outs::<N, L>(outputs[0], &x[0])?;
        let x1 = outs::<N, L>(outputs[1], &x[1])?;
        let x2 = outs::<N, L>(outputs[2], &x[2])?;
        Ok(std::array::from_fn(|i| [x0[i], x1[i], x2[i]]))
    }

    /// `(U_t, u_t + U_t)` of an answer that changes `u` by `Δu`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn slip_after(&self, du: &V3<N>) -> (V3<N>, V3<N>) {
        let dun = dot(du, &self.g.n).div(&self.g.nu);
        let dut = tangential_part(du, &dun, &self.g.n, self.g.axis);
        (
            add(&self.ut, &dut),
            zip(
                &self.ut,
                &dut,
                #[cfg_attr(not(debug_assertions), inline(always))]
                |x, y| N::of(2.0).mul_add(x, y),
            ),
        )
    }

    /// The work `P·(u + U) + κ (s̃ + S̃)` (`−2 T_L`), with
    /// `u + U = (1 − e)(u·n) n/ν + (u_t + U_t)` (Kelvin and Tait, as Eq 8).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn work(&self, s: &Solution<N>, e: &N, slip_sum: &V3<N>, spin_sum: &N) -> N {
        let normal_work = N::of(1.0).sub(e).mul(&self.un).mul(&s.pn).div(&self.g.nu);
        s.kappa.mul_add(spin_sum, &dot(&s.p, slip_sum).add(&normal_work))
    }

    /// The contact velocity at one instant (`u·n`, `u_t`, `s̃`) as outputs,
    /// named by its normal, slip (x, y, z) and spin outputs.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn contact_velocity_at<const L: usize>(
        &self,
        [normal, x, y, z, spin]: [Output; 5],
        un: &N,
        ut: &V3<N>,
        s: &N,
    ) -> Exact<N, [SpatialContactVelocity; L]> {
        let normal = self.along::<L>(normal, un)?;
        let tangential = Self::vector_out::<L>([x, y, z], ut)?;
        let spin = self.along::<L>(spin, s)?;
        Ok(std::array::from_fn(|i| SpatialContactVelocity {
            normal: normal[i],
            tangential: tangential[i],
            spin: spin[i],
        }))
    }

    /// `T_M = ½ (u, s̃)ᵀ 𝒲̃⁻¹ (u, s̃)` (with twist) or `½ uᵀ W⁻¹ u`, by the
    /// adjugate and the Schur complement of `W`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn max_loss(&self) -> N {
        let a = sym_mul(&self.g.adj, &self.u);
        let mut twice = dot(&self.u, &a).div(&self.g.det);
        if self.twist.is_some() {
            let b = sym_mul(&self.g.adj, &self.g.w);
            let schur = self.g.k.mul_add(&self.g.det, &dot(&self.g.w, &b).neg());
            let lever = self.s.mul_add(&self.g.det, &dot(&self.g.w, &a).neg());
            twice = twice.add(&lever.mul(&lever).div(&self.g.det.mul(&schur)));
        }
        half::<N>().mul(&twice)
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn initial_energy(&self) -> N {
        let mut total = N::of(0.0);
        for (b, motion) in self.g.bodies.iter().zip(&self.motion) {
            let linear = b.m.mul(&norm2(&motion.v));
            let angular = dot(&motion.w, &sym_mul(&b.tensor, &motion.w));
            total = total.add(&half::<N>().mul(&linear.add(&angular)));
        }
        total
    }
}
