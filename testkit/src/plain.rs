//! The model's f64 evaluation over any magnitudes (`Arithmetic::Plain`: no
//! range check, every decision exact as in `fast`; exact arithmetic where a
//! decision is too close to call or the f64 evaluation leaves the f64 range),
//! called per case: what the reference and paper tests measure.

use restitution::impact::{Arithmetic, solve_in};
use restitution::{BarrierImpact, BarrierOutcome, BarrierScene, Law, Outputs, Result};

/// The rigid-body impact of a validated scene under `law`.
pub fn impact(scene: &BarrierScene, law: Law) -> BarrierImpact {
    BarrierImpact::in_scene(scene, law)
}

/// `law` in `scene`, evaluated in plain f64.
pub fn solve(scene: &BarrierScene, law: Law, outputs: Outputs) -> Result<BarrierOutcome> {
    solve_in(&impact(scene, law), outputs, Arithmetic::Plain).0
}

pub mod oblique {
    use super::*;

    /// The tangential law closing the planar equations.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub enum TangentialLaw {
        ImpulseRatio(f64),
        Friction(f64),
    }

    /// The Appendix's kinetic restitution.
    #[derive(Debug, Clone, Copy, PartialEq, Default)]
    pub struct KineticRestitution {
        pub value: f64,
        pub approach_impulse_ratio: f64,
        pub rebound_impulse_ratio: f64,
    }

    pub fn solve(
        scene: &BarrierScene,
        e: f64,
        law: TangentialLaw,
        outputs: Outputs,
    ) -> Result<BarrierOutcome> {
        let law = match law {
            TangentialLaw::ImpulseRatio(mu) => Law::ImpulseRatio {
                restitution: e,
                impulse_ratio: mu,
            },
            TangentialLaw::Friction(f) => Law::Friction {
                restitution: e,
                friction: f,
            },
        };
        super::solve(scene, law, outputs)
    }

    pub fn solve_kinetic(
        scene: &BarrierScene,
        k: KineticRestitution,
        outputs: Outputs,
    ) -> Result<BarrierOutcome> {
        let law = Law::KineticRestitution {
            value: k.value,
            approach_impulse_ratio: k.approach_impulse_ratio,
            rebound_impulse_ratio: k.rebound_impulse_ratio,
        };
        super::solve(scene, law, outputs)
    }
}

pub mod tangential {
    use super::*;

    pub fn solve(scene: &BarrierScene, e: f64, f: f64, et: f64, outputs: Outputs) -> Result<BarrierOutcome> {
        let law = Law::TangentialRestitution {
            restitution: e,
            friction: f,
            tangential_restitution: et,
        };
        super::solve(scene, law, outputs)
    }
}

pub mod normal {
    use super::*;
    use restitution::{BarrierBody, Contact, PlanarVelocity};

    /// A normal impact: a point mass when `inertia` is `None`.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct NormalImpact {
        pub mass: f64,
        pub inertia: Option<f64>,
        pub contact: Option<Contact>,
        pub velocity: PlanarVelocity,
        pub restitution: f64,
    }

    impl NormalImpact {
        pub fn impact(&self) -> BarrierImpact {
            BarrierImpact {
                body: match self.inertia {
                    Some(inertia) => BarrierBody::Rigid {
                        mass: self.mass,
                        inertia,
                        contact: self.contact.unwrap_or_default(),
                    },
                    None => BarrierBody::PointMass { mass: self.mass },
                },
                velocity: self.velocity,
                law: Law::Frictionless {
                    restitution: self.restitution,
                },
            }
        }
    }

    pub fn solve(impact: &NormalImpact, outputs: Outputs) -> Result<BarrierOutcome> {
        solve_in(&impact.impact(), outputs, Arithmetic::Plain).0
    }
}

pub mod torsional {
    use super::*;
    pub use restitution::TorsionalImpact;
    #[allow(unused_imports)]
    pub use restitution::outcome::TorsionalRegime;

    pub fn solve(impact: &TorsionalImpact, energy: bool) -> Result<restitution::TorsionalOutcome> {
        let outputs = Outputs {
            critical_impulse_ratio: false,
            energy,
        };
        solve_in(impact, outputs, Arithmetic::Plain).0
    }
}
