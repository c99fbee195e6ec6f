//! The planar scene: body, contact geometry, initial velocities and the
//! contact-point kinematics every planar case starts from.
//!
//! Frame (see `docs/physics.md`): `n` is the barrier's outward normal, `t` the
//! tangent; the centre of mass G sits at `(d_c, d_d)` from the contact point C;
//! `ω` is positive in the sense that turns `n` toward `t`. Then the contact
//! point moves with `v_cn = v_n + d_c ω` and `v_ct = v_t − d_d ω`.

use crate::error::{ImpactError, Input, Output, Result, finite, finite_output, positive};

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
pub struct PlanarScene {
    pub(crate) body: Body,
    pub(crate) contact: Contact,
    pub(crate) velocity: PlanarVelocity,
    /// `k² = I / m`.
    pub(crate) k2: f64,
    /// Initial contact-point velocity.
    pub(crate) contact_velocity: ContactVelocity,
}

impl PlanarScene {
    /// Builds the scene, checking that every number is finite and that the
    /// contact approaches the barrier (`v_cn = v_n + d_c ω < 0`).
    ///
    /// `v_cn` and `v_ct` are each evaluated with one fused multiply-add, so
    /// their signs (which decide approach and slip direction) are exact.
    pub fn new(body: Body, contact: Contact, velocity: PlanarVelocity) -> Result<Self> {
        finite(Input::TangentialOffset, contact.tangential_offset)?;
        finite(Input::NormalOffset, contact.normal_offset)?;
        finite(Input::NormalVelocity, velocity.normal)?;
        finite(Input::TangentialVelocity, velocity.tangential)?;
        finite(Input::AngularVelocity, velocity.angular)?;
        let contact_velocity = ContactVelocity {
            normal: contact
                .tangential_offset
                .mul_add(velocity.angular, velocity.normal),
            tangential: (-contact.normal_offset).mul_add(velocity.angular, velocity.tangential),
        };
        // A v_cn beyond the f64 range still has its sign: separating is decided first.
        if contact_velocity.normal >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: contact_velocity.normal,
            });
        }
        finite_output(Output::InitialNormalContactVelocity, contact_velocity.normal)?;
        finite_output(
            Output::InitialTangentialContactVelocity,
            contact_velocity.tangential,
        )?;
        Ok(Self {
            body,
            contact,
            velocity,
            k2: body.gyration_squared(),
            contact_velocity,
        })
    }

    /// A scene whose fused `v_cn` rounded to zero although the exact `v_cn`
    /// is negative (it lies below the f64 range); only [`crate::exact::scene`]
    /// decides that.
    pub(crate) fn approaching_below_range(body: Body, contact: Contact, velocity: PlanarVelocity) -> Self {
        Self {
            body,
            contact,
            velocity,
            k2: body.gyration_squared(),
            contact_velocity: ContactVelocity {
                normal: contact
                    .tangential_offset
                    .mul_add(velocity.angular, velocity.normal),
                tangential: (-contact.normal_offset).mul_add(velocity.angular, velocity.tangential),
            },
        }
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
}
