//! The planar scene: body, contact geometry, initial velocities and the
//! contact-point kinematics every planar case starts from.
//!
//! Frame (see `docs/physics.md`): `n` is the barrier's outward normal, `t` the
//! tangent; the centre of mass G sits at `(d_c, d_d)` from the contact point C;
//! `ω` is positive in the sense that turns `n` toward `t`. Then the contact
//! point moves with `v_cn = v_n + d_c ω` and `v_ct = v_t − d_d ω`.

use crate::arith::{Field, Fraction};
use crate::error::{AdmissibleInterval, ImpactError, Input, Output, Result, finite, finite_output, positive};

/// The earlier name of [`BarrierScene`], kept for callers.
#[allow(deprecated)]
pub use crate::deprecated_names::PlanarScene;

/// A rigid lamina: mass `m` and centroidal moment of inertia `I = m k²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    mass: f64,
    inertia: f64,
}

impl Body {
    /// A body with mass `m > 0` and centroidal moment of inertia `I > 0`.
    pub fn new(mass: f64, inertia: f64) -> Result<Self> {
        Ok(Self {
            mass: positive(Input::Mass, mass)?,
            inertia: positive(Input::Inertia, inertia)?,
        })
    }

    /// Mass `m`.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Centroidal moment of inertia `I`.
    pub fn inertia(&self) -> f64 {
        self.inertia
    }

    /// Squared centroidal radius of gyration `k² = I / m`.
    pub fn gyration_squared(&self) -> f64 {
        self.inertia / self.mass
    }
}

/// Where the centre of mass G sits relative to the contact point C.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Contact {
    /// `d_c`: G's offset from C along the tangent `t`.
    pub tangential_offset: f64,
    /// `d_d`: G's offset from C along the normal `n`.
    pub normal_offset: f64,
}

impl Contact {
    /// Central contact (`d_c = 0`) with G at height `d_d` above C, e.g. a disc of radius `d_d`.
    pub fn central(normal_offset: f64) -> Self {
        Self {
            tangential_offset: 0.0,
            normal_offset,
        }
    }
}

/// Planar velocity of the centre of mass and angular velocity.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlanarVelocity {
    /// Normal component (`v_n` initially, `V_n` finally).
    pub normal: f64,
    /// Tangential component (`v_t` initially, `V_t` finally).
    pub tangential: f64,
    /// Angular velocity (`ω` initially, `Ω` finally).
    pub angular: f64,
}

/// Velocity of the contact point C.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactVelocity {
    /// Normal component `v_cn` (or `V_cn`).
    pub normal: f64,
    /// Tangential component `v_ct` (or `V_ct`).
    pub tangential: f64,
}

/// A validated planar scene: a body, its contact with the barrier and its
/// initial velocities, with the contact point approaching the barrier.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarrierScene {
    pub(crate) body: Body,
    pub(crate) contact: Contact,
    pub(crate) velocity: PlanarVelocity,
    /// `k² = I / m`.
    pub(crate) k2: f64,
    /// Initial contact-point velocity.
    pub(crate) contact_velocity: ContactVelocity,
}

/// A body at its contact, validated before any velocity: what the scenes of
/// a sweep over velocities share, checked and formed once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Placed {
    body: Body,
    contact: Contact,
    /// `k² = I / m`.
    k2: f64,
}

impl Placed {
    /// Checks that the offsets are finite.
    pub(crate) fn new(body: Body, contact: Contact) -> Result<Self> {
        finite(Input::TangentialOffset, contact.tangential_offset)?;
        finite(Input::NormalOffset, contact.normal_offset)?;
        Ok(Placed {
            body,
            contact,
            k2: body.gyration_squared(),
        })
    }

    /// The body.
    pub(crate) fn body(&self) -> Body {
        self.body
    }

    /// The scene of the body moving at `velocity`: [`BarrierScene::new`]'s
    /// checks of the velocity.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn moving(&self, velocity: PlanarVelocity) -> Result<BarrierScene> {
        let scene = self.moving_unchecked(velocity);
        scene.check_velocity()?;
        Ok(scene)
    }

    /// The scene of the body moving at `velocity`, its velocity not yet
    /// checked ([`BarrierScene::check_velocity`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn moving_unchecked(&self, velocity: PlanarVelocity) -> BarrierScene {
        let Placed { body, contact, k2 } = *self;
        BarrierScene {
            body,
            contact,
            velocity,
            k2,
            contact_velocity: ContactVelocity {
                normal: contact
                    .tangential_offset
                    .mul_add(velocity.angular, velocity.normal),
                tangential: (-contact.normal_offset).mul_add(velocity.angular, velocity.tangential),
            },
        }
    }
}

impl BarrierScene {
    /// Builds the scene, checking that every number is finite and that the
    /// contact approaches the barrier (`v_cn = v_n + d_c ω < 0`).
    ///
    /// `v_cn` and `v_ct` are each evaluated with one fused multiply-add, so
    /// their signs (which decide approach and slip direction) are exact, but
    /// for a `v_cn` below the f64 range, whose sign is then decided in exact
    /// arithmetic.
    pub fn new(body: Body, contact: Contact, velocity: PlanarVelocity) -> Result<Self> {
        let scene = Placed::new(body, contact)?.moving_unchecked(velocity);
        scene.check_velocity()?;
        Ok(scene)
    }

    /// Checks that the velocities are finite and that the contact
    /// approaches, and that its contact velocities are in the f64 range.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(crate) fn check_velocity(&self) -> Result<()> {
        let (velocity, contact_velocity) = (self.velocity, self.contact_velocity);
        finite(Input::NormalVelocity, velocity.normal)?;
        finite(Input::TangentialVelocity, velocity.tangential)?;
        finite(Input::AngularVelocity, velocity.angular)?;
        // A v_cn beyond the f64 range still has its sign: separating is decided first.
        let approaching = contact_velocity.normal < 0.0
            || (contact_velocity.normal == 0.0 && below_range_approaching(self.contact, velocity));
        if !approaching {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: contact_velocity.normal + 0.0,
            });
        }
        finite_output(Output::InitialNormalContactVelocity, contact_velocity.normal)?;
        finite_output(
            Output::InitialTangentialContactVelocity,
            contact_velocity.tangential,
        )?;
        Ok(())
    }

    /// The body.
    pub fn body(&self) -> Body {
        self.body
    }

    /// The contact geometry.
    pub fn contact(&self) -> Contact {
        self.contact
    }

    /// The initial velocities.
    pub fn velocity(&self) -> PlanarVelocity {
        self.velocity
    }

    /// Initial contact-point velocity `(v_cn, v_ct)`.
    pub fn contact_velocity(&self) -> ContactVelocity {
        self.contact_velocity
    }

    /// Whether the contact is central (`d_c = 0`): normal and tangential
    /// impulses then do not couple through rotation.
    pub fn is_central(&self) -> bool {
        self.contact.tangential_offset == 0.0
    }

    /// `D(μ) = 1 + d_c (d_c − μ d_d) / k²` (after Eq 7).
    pub fn d(&self, impulse_ratio: f64) -> f64 {
        self.dk2(impulse_ratio) / self.k2
    }

    /// `D(μ) k² = k² + d_c (d_c − μ d_d)`, the overflow-safe form used inside.
    pub(crate) fn dk2(&self, impulse_ratio: f64) -> f64 {
        let Contact {
            tangential_offset: dc,
            normal_offset: dd,
        } = self.contact;
        dc.mul_add((-impulse_ratio).mul_add(dd, dc), self.k2)
    }

    /// The interval of impulse ratios `μ` whose answer is physical: `D(μ) > 0`
    /// and `T_L(μ) ≥ 0`. It always contains `μ = 0`.
    ///
    /// `T_L(μ) D(μ)² k² · 2 / (m (1 + e) s)` is the quadratic
    /// `Q(μ) = (1 − e) s (k² + d_c²) + 2 μ [e s d_c d_d − v_ct (k² + d_c²)]
    ///        + μ² [2 v_ct d_c d_d − (1 + e) s (k² + d_d²)]`,
    /// and `D` has its single root at `μ* = (k² + d_c²) / (d_c d_d)` where `Q < 0`,
    /// so the set is one interval (possibly unbounded on one side).
    pub fn admissible_interval(&self, e: f64) -> AdmissibleInterval {
        let Contact {
            tangential_offset: dc,
            normal_offset: dd,
        } = self.contact;
        admissible_interval(
            [dc.mul_add(dc, self.k2), -(dc * dd), dd.mul_add(dd, self.k2)],
            -self.contact_velocity.normal,
            self.contact_velocity.tangential,
            e,
        )
    }

    /// The error for an answer with `D(μ) ≤ 0`.
    pub(crate) fn no_impulse_solution(&self, mu: f64, law: Input) -> ImpactError {
        ImpactError::NoImpulseSolution {
            input: law,
            impulse_ratio: mu,
            d: self.d(mu),
        }
    }
}

/// The interval of impulse ratios `μ` whose answer is physical in a contact
/// space `W̃ = [[a, b], [b, c]]` (any positive scaling) with approach speed
/// `s = −u_n` and slip `u_t`: `a + μ b > 0` and `T_L(μ) ≥ 0`. It always
/// contains `μ = 0`.
///
/// `T_L(μ) (a + μ b)² · 2 / ((1 + e) s)` is, up to a positive factor, the quadratic
/// `Q(μ) = (1 − e) s a − 2 μ [e s b + u_t a] + μ² [−2 u_t b − (1 + e) s c]`,
/// and `a + μ b` has its single root at `μ* = −a / b` where `Q < 0`, so the set
/// is one interval (possibly unbounded on one side).
pub(crate) fn admissible_interval(w: [f64; 3], s: f64, vct: f64, e: f64) -> AdmissibleInterval {
    let [a, wnt, c] = w;
    let b = -wnt;
    let c0 = (1.0 - e) * s * a;
    let c1 = 2.0 * (e * s).mul_add(b, -(vct * a));
    let c2 = (2.0 * vct).mul_add(b, -((1.0 + e) * s * c));
    let mut lower = f64::NEG_INFINITY;
    let mut upper = f64::INFINITY;
    if b != 0.0 {
        let mu_star = a / b;
        if mu_star > 0.0 {
            upper = upper.min(mu_star);
        } else {
            lower = lower.max(mu_star);
        }
    }
    if c2 != 0.0 {
        let disc = c1.mul_add(c1, -4.0 * c2 * c0).max(0.0);
        let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
        let (mut r1, mut r2) = if q == 0.0 { (0.0, 0.0) } else { (q / c2, c0 / q) };
        if r1 > r2 {
            std::mem::swap(&mut r1, &mut r2);
        }
        if c2 < 0.0 {
            lower = lower.max(r1);
            upper = upper.min(r2);
        } else if r1 >= 0.0 {
            upper = upper.min(r1);
        } else {
            lower = lower.max(r2);
        }
    } else if c1 > 0.0 {
        lower = lower.max(-c0 / c1);
    } else if c1 < 0.0 {
        upper = upper.min(-c0 / c1);
    }
    AdmissibleInterval {
        lower: Some(lower).filter(|x| x.is_finite()),
        upper: Some(upper).filter(|x| x.is_finite()),
    }
}

/// Whether the exact `v_cn = v_n + d_c ω` is negative, for a fused `v_cn` that
/// rounded to zero (the exact value may lie below the f64 range).
#[cold]
fn below_range_approaching(contact: Contact, velocity: PlanarVelocity) -> bool {
    let exact = Fraction::of(contact.tangential_offset)
        .mul(&Fraction::of(velocity.angular))
        .add(&Fraction::of(velocity.normal));
    exact.sign() == Ok(std::cmp::Ordering::Less)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{BarrierImpact, Law, Precision, solve};
    use crate::outcome::Outputs;

    fn scenes() -> impl Iterator<Item = BarrierScene> {
        let mut rng = crate::rng::Rng::new(0x2545_f491_4f6c_dd1d);
        let mut unit = move || rng.unit();
        (0..1000).map(move |_| {
            let k = 0.01 + unit();
            let contact = Contact {
                tangential_offset: 2.0 * unit() - 1.0,
                normal_offset: 2.0 * unit() - 1.0,
            };
            let angular = 4.0 * unit() - 2.0;
            let velocity = PlanarVelocity {
                normal: -0.01 - unit() - contact.tangential_offset * angular,
                tangential: 4.0 * unit() - 2.0,
                angular,
            };
            BarrierScene::new(Body::new(1.0, k * k).unwrap(), contact, velocity).unwrap()
        })
    }

    #[test]
    fn the_admissible_interval_contains_zero_and_every_ratio_inside_it_is_answered() {
        for scene in scenes() {
            for e in [0.0, 0.5, 1.0] {
                let interval = scene.admissible_interval(e);
                assert!(interval.contains(0.0));
                for bound in [interval.lower, interval.upper].into_iter().flatten() {
                    let inside = bound * (1.0 - 1e-9);
                    let impact = BarrierImpact::in_scene(
                        &scene,
                        Law::ImpulseRatio {
                            restitution: e,
                            impulse_ratio: inside,
                        },
                    );
                    let answer = solve(&impact, Outputs::MINIMAL, Precision::Exact);
                    assert!(answer.is_ok(), "{scene:?} e {e} μ {inside}: {answer:?}");
                }
            }
        }
    }
}
