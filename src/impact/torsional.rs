//! The torsional case (section 4): spin about the contact normal.

use super::{Arithmetic, Case, Model, Stage, StaticBounds, evaluate};
use crate::accuracy::{ErrorScales, ScalesOf};
use crate::arith::Radical;
use crate::error::{ImpactError, Input, Result, finite, in_range, positive};
use crate::input::TorsionalImpact;
use crate::model::Exact;
use crate::model::torsional::{Torsion, torsional};
use crate::outcome::{Outputs, TorsionalOutcome};

impl TorsionalImpact {
    /// Checks every input's range and that the body approaches (`v_n < 0`).
    fn validate(&self) -> Result<Torsion> {
        let m = positive(Input::Mass, self.mass)?;
        let i_n = positive(Input::NormalInertia, self.normal_inertia)?;
        let vn = finite(Input::NormalVelocity, self.normal_velocity)?;
        let w = finite(Input::Spin, self.spin)?;
        let e = in_range(Input::Restitution, self.restitution, 0.0, 1.0)?;
        let ez = in_range(Input::TorsionalRestitution, self.torsional_restitution, 0.0, 1.0)?;
        let mu_z = in_range(
            Input::TorsionalFriction,
            self.torsional_friction,
            0.0,
            f64::INFINITY,
        )?;
        let rho = positive(Input::PitchRadius, self.pitch_radius)?;
        if vn >= 0.0 {
            return Err(ImpactError::NotApproaching {
                input: Input::NormalVelocity,
                normal_contact_velocity: vn + 0.0,
            });
        }
        Ok(Torsion {
            m,
            i_n,
            vn,
            w,
            e,
            ez,
            mu_z,
            rho,
        })
    }
}

struct TorsionModel {
    torsion: Torsion,
    energy: bool,
}

impl Model<TorsionalOutcome> for TorsionModel {
    #[inline(always)]
    fn run<N: Radical>(&self, out: &mut TorsionalOutcome) -> Exact<N, ()> {
        torsional::<N>(&self.torsion, self.energy, out)
    }
}

impl Case for TorsionalImpact {
    type Outcome = TorsionalOutcome;
    type Fixed = ();

    reads!(|impact, input| {
        Mass => Some(&mut impact.mass),
        NormalInertia => Some(&mut impact.normal_inertia),
        NormalVelocity => Some(&mut impact.normal_velocity),
        Spin => Some(&mut impact.spin),
        Restitution => Some(&mut impact.restitution),
        TorsionalRestitution => Some(&mut impact.torsional_restitution),
        TorsionalFriction => Some(&mut impact.torsional_friction),
        PitchRadius => Some(&mut impact.pitch_radius),
    });

    fn error_scales(&self) -> ErrorScales {
        ScalesOf::new()
            .body(
                self.mass,
                &[self.normal_velocity],
                &[self.spin],
                self.pitch_radius,
            )
            .scales()
    }

    fn describe(&self) -> &'static str {
        "a torsional impact"
    }

    fn fix(&self, _swept: &[Input]) {}

    #[inline(always)]
    fn evaluate(
        &self,
        _fixed: &(),
        outputs: Outputs,
        arithmetic: Arithmetic,
        in_range: bool,
        out: &mut TorsionalOutcome,
    ) -> (Result<()>, Stage) {
        match self.validate() {
            Ok(torsion) => evaluate(
                arithmetic,
                in_range,
                || self.error_scales(),
                StaticBounds::Tight,
                TorsionModel {
                    torsion,
                    energy: outputs.energy,
                },
                out,
            ),
            Err(e) => (Err(e), arithmetic.validating_stage()),
        }
    }
}
