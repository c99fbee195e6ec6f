//! `precision: "exact"`: every numeric output is the correctly rounded f64 of
//! the model's exact value for the given f64 inputs, and every regime decision
//! and refusal is the exact one.
//!
//! Adaptive precision in the manner of Shewchuk's robust predicates: the model
//! (`model.rs`) is written once over a `Field` (`field.rs`) and evaluated in up to
//! four arithmetics, each dearer and more decisive than the last:
//!
//! 1. `Compensated` (`compensated.rs`): the plain f64 evaluation and its rounding
//!    errors, gathered by error-free transformations, with a static error
//!    bound (about 5× the fast mode, docs/accuracy.md; answers every typical input);
//! 2. `Bounded` (`bounded.rs`) double-doubles with a bound tracked operation by
//!    operation, where stage 1 failed for range reasons (ill-conditioned
//!    quotients, exponents near the ends of the range);
//! 3. the same keeping exact sums and products exact (`Bounded<true>`: exact
//!    rounding ties and cancelled zeros formed without a quotient), where
//!    stage 2 failed or stage 1 found a value too close to a zero or a
//!    rounding midpoint;
//! 4. exact fractions of big integers, which always decide.
//!
//! When every sign the model decides and every output it rounds is certified,
//! the answer of that arithmetic stands; otherwise the whole answer is
//! evaluated again in the next.
//!
//! An output whose exact value is zero is `+0.0` in this mode. Inputs are
//! validated as in the fast mode, except that whether the contact approaches
//! is decided on the exact `v_cn = v_n + d_c ω`, even below the f64 range.

mod bounded;
mod compensated;
mod field;
mod model;

use std::convert::Infallible;

use self::bounded::Bounded;
use self::compensated::{Compensated, Unsettled};
use self::field::{Field, Fraction, Undecided};
use self::model::{Fail, PlanarLaw as Law};
use crate::error::{ImpactError, Input, Result, finite, in_range};
use crate::normal::PointMass;
use crate::planar::{Outputs, PlanarOutcome, Regime};
use crate::scene::{Body, Contact, PlanarScene, PlanarVelocity};
use crate::sweep::planar::{PlanarLaw, PlanarPoint};
use crate::torsional::{TorsionalImpact, TorsionalOutcome};

/// Which arithmetic answers a request.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// Plain f64 closed forms with special paths: fastest, error bounded
    /// relative to the terms each output combines (`docs/accuracy.md`).
    #[default]
    Fast,
    /// Correctly rounded outputs and exact decisions (this module).
    Exact,
}

impl Precision {
    /// The mode's name as the API spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            Precision::Fast => "fast",
            Precision::Exact => "exact",
        }
    }
}

/// Which arithmetic produced an exact answer (or refusal).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Compensated f64 evaluation with a static error bound (also: inputs
    /// refused before any arithmetic).
    Compensated,
    /// Double-double with a certified error bound.
    DoubleDouble,
    /// Exact rationals, after the compensated and double-double stages could not decide.
    Rational,
}

/// Runs the model compensated (`compensated`); if that cannot decide because
/// of the range, in double-double (`double_double`); if that cannot decide
/// either, or the compensated value was too close to a zero or a rounding
/// midpoint (perhaps exactly on it), in double-double tracking exact
/// operations (`tracked`: decides ties and cancelled zeros formed without a
/// quotient); and last in exact fractions (`rational`), which decide
/// everything: its undecided case is uninhabited.
fn adaptive<T>(
    compensated: impl FnOnce() -> std::result::Result<T, Fail<Unsettled>>,
    double_double: impl FnOnce() -> std::result::Result<T, Fail<Undecided>>,
    tracked: impl FnOnce() -> std::result::Result<T, Fail<Undecided>>,
    rational: impl FnOnce() -> std::result::Result<T, Fail<Infallible>>,
) -> (Result<T>, Stage) {
    let settled = |result| match result {
        Ok(v) => Some(Ok(v)),
        Err(Fail::Refused(e)) => Some(Err(e)),
        Err(Fail::Undecided(Undecided)) => None,
    };
    let why = match compensated() {
        Ok(v) => return (Ok(v), Stage::Compensated),
        Err(Fail::Refused(e)) => return (Err(e), Stage::Compensated),
        Err(Fail::Undecided(why)) => why,
    };
    let double_double = match why {
        Unsettled::Range => settled(double_double()),
        Unsettled::Close => None,
    };
    if let Some(answer) = double_double.or_else(|| settled(tracked())) {
        return (answer, Stage::DoubleDouble);
    }
    (decided(rational()), Stage::Rational)
}

/// The rational pass's result: an answer or the model's refusal.
fn decided<T>(result: std::result::Result<T, Fail<Infallible>>) -> Result<T> {
    result.map_err(|fail| match fail {
        Fail::Refused(e) => e,
        Fail::Undecided(never) => match never {},
    })
}

/// Builds a planar scene like [`PlanarScene::new`], deciding whether the
/// contact approaches on the exact `v_cn` (the fused `v_cn` keeps the exact
/// sign except when it underflows to zero).
pub fn scene(body: Body, contact: Contact, velocity: PlanarVelocity) -> Result<PlanarScene> {
    match PlanarScene::new(body, contact, velocity) {
        Err(ImpactError::NotApproaching {
            normal_contact_velocity: 0.0,
            ..
        }) => {
            let exact = <Fraction as Field>::of(velocity.normal).add(
                &<Fraction as Field>::of(contact.tangential_offset)
                    .mul(&<Fraction as Field>::of(velocity.angular)),
            );
            if exact.sign() == Ok(std::cmp::Ordering::Less) {
                Ok(PlanarScene::approaching_below_range(body, contact, velocity))
            } else {
                Err(ImpactError::NotApproaching {
                    input: Input::NormalVelocity,
                    normal_contact_velocity: 0.0,
                })
            }
        }
        other => other,
    }
}

/// The law and its validated coefficients, checked in the fast mode's order.
fn planar_law(law: PlanarLaw, p: &PlanarPoint) -> Result<(f64, Law)> {
    let e = || in_range(Input::Restitution, p.restitution, 0.0, 1.0);
    Ok(match law {
        PlanarLaw::PointMass | PlanarLaw::Frictionless => (e()?, Law::Frictionless),
        PlanarLaw::ImpulseRatio => (e()?, Law::Ratio(finite(Input::ImpulseRatio, p.impulse_ratio)?)),
        PlanarLaw::Friction => {
            let e = e()?;
            let f = in_range(Input::Friction, p.friction, 0.0, f64::INFINITY)?;
            (
                e,
                Law::Bilinear {
                    f,
                    et: 0.0,
                    capped: Regime::Sticking,
                },
            )
        }
        PlanarLaw::TangentialRestitution => {
            let e = e()?;
            let f = in_range(Input::Friction, p.friction, 0.0, f64::INFINITY)?;
            let et = in_range(Input::TangentialRestitution, p.tangential_restitution, -1.0, 1.0)?;
            (
                e,
                Law::Bilinear {
                    f,
                    et,
                    capped: Regime::Restitution,
                },
            )
        }
        PlanarLaw::KineticRestitution => {
            let r = in_range(Input::KineticRestitution, p.kinetic.value, 0.0, 1.0)?;
            let mu_a = finite(Input::ApproachImpulseRatio, p.kinetic.approach_impulse_ratio)?;
            let mu_r = finite(Input::ReboundImpulseRatio, p.kinetic.rebound_impulse_ratio)?;
            (r, Law::Kinetic { r, mu_a, mu_r })
        }
    })
}

/// Solves one planar impact exactly, reporting which stage answered.
pub fn solve_planar_staged(
    law: PlanarLaw,
    p: &PlanarPoint,
    outputs: Outputs,
) -> (Result<PlanarOutcome>, Stage) {
    if law == PlanarLaw::PointMass {
        let v = match PointMass::validate(&p.point_mass_impact()) {
            Ok(v) => v,
            Err(e) => return (Err(e), Stage::Compensated),
        };
        return adaptive(
            || model::point_mass::<Compensated>(&v, outputs),
            || model::point_mass::<Bounded>(&v, outputs),
            || model::point_mass::<Bounded<true>>(&v, outputs),
            || model::point_mass::<Fraction>(&v, outputs),
        );
    }
    let prepared = Body::new(p.mass, p.inertia)
        .and_then(|body| scene(body, p.contact, p.velocity))
        .and_then(|scene| Ok((scene, planar_law(law, p)?)));
    let (scene, (e, law)) = match prepared {
        Ok(v) => v,
        Err(e) => return (Err(e), Stage::Compensated),
    };
    adaptive(
        || model::planar::<Compensated>(&scene, e, law, outputs),
        || model::planar::<Bounded>(&scene, e, law, outputs),
        || model::planar::<Bounded<true>>(&scene, e, law, outputs),
        || model::planar::<Fraction>(&scene, e, law, outputs),
    )
}

/// Solves one planar impact exactly.
pub fn solve_planar(law: PlanarLaw, p: &PlanarPoint, outputs: Outputs) -> Result<PlanarOutcome> {
    solve_planar_staged(law, p, outputs).0
}

/// Solves one torsional impact exactly, reporting which stage answered.
pub fn solve_torsional_staged(impact: &TorsionalImpact, energy: bool) -> (Result<TorsionalOutcome>, Stage) {
    let v = match impact.validate() {
        Ok(v) => v,
        Err(e) => return (Err(e), Stage::Compensated),
    };
    adaptive(
        || model::torsional::<Compensated>(&v, energy),
        || model::torsional::<Bounded>(&v, energy),
        || model::torsional::<Bounded<true>>(&v, energy),
        || model::torsional::<Fraction>(&v, energy),
    )
}

/// Solves one torsional impact exactly.
pub fn solve_torsional(impact: &TorsionalImpact, energy: bool) -> Result<TorsionalOutcome> {
    solve_torsional_staged(impact, energy).0
}

/// Solves one planar impact in exact rationals only (no earlier stage):
/// the pure rational evaluation, for comparisons and benchmarks.
pub fn solve_planar_rational(law: PlanarLaw, p: &PlanarPoint, outputs: Outputs) -> Result<PlanarOutcome> {
    if law == PlanarLaw::PointMass {
        return solve_planar(law, p, outputs);
    }
    let body = Body::new(p.mass, p.inertia)?;
    let scene = scene(body, p.contact, p.velocity)?;
    let (e, exact_law) = planar_law(law, p)?;
    decided(model::planar::<Fraction>(&scene, e, exact_law, outputs))
}

/// Solves one torsional impact in exact rationals only.
pub fn solve_torsional_rational(impact: &TorsionalImpact, energy: bool) -> Result<TorsionalOutcome> {
    let v = impact.validate()?;
    decided(model::torsional::<Fraction>(&v, energy))
}
