//! The torsional case (section 4): spin about the contact normal.

use super::{Arithmetic, Case, LANES, Model, Stage, StaticBounds, evaluate};
use crate::accuracy::{ErrorScales, ScalesOf};
use crate::arith::{Lanes, Radical};
use crate::error::{ImpactError, Input, Result, finite, in_range, positive};
use crate::input::TorsionalImpact;
use crate::model::Exact;
use crate::model::torsional::{Torsion, torsional, torsional_lanes};
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
    #[cfg_attr(not(debug_assertions), inline(always))]
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

    /// Every input is the point's own: any sweep runs in lanes.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_lanes(_fixed: &()) -> bool {
        true
    }

    /// The points in lanes, each validated as its single solve validates it
    /// (else the points are solved one by one).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_lanes(
        impacts: &[Self; LANES],
        _fixed: &(),
        outputs: Outputs,
        out: &mut [TorsionalOutcome; LANES],
    ) -> bool {
        let mut torsions = [Torsion::default(); LANES];
        let mut scales = [ErrorScales::UNPROMISED; LANES];
        for ((torsion, scale), impact) in torsions.iter_mut().zip(&mut scales).zip(impacts) {
            match impact.validate() {
                Ok(valid) => *torsion = valid,
                Err(_) => return false,
            }
            *scale = impact.error_scales();
        }
        crate::arith::measure_lanes_against(&scales);
        // A compiled body of its own, as the laminae's lanes
        // (`impact::barrier`).
        crate::kernels::run(
            #[cfg_attr(not(debug_assertions), inline(always))]
            || torsional_lanes::<Lanes<LANES>, LANES>(&torsions, outputs.energy, out),
        )
        .is_ok()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::testing::block_answers_as_single_solves;
    use crate::impact::{Precision, Solver, solve};

    /// A body whose switch spin is exactly `ω_s = 1.5`:
    /// `μ_z ρ_p m (1 + e) |v_n| / I_n = 0.25 · 0.5 · 2 · 1.5 · 2 / 0.5`.
    fn body(spin: f64, mass: f64) -> TorsionalImpact {
        TorsionalImpact {
            mass,
            normal_inertia: 0.5,
            normal_velocity: -2.0,
            spin,
            restitution: 0.5,
            torsional_restitution: 0.25,
            torsional_friction: 0.25,
            pitch_radius: 0.5,
        }
    }

    /// Blocks through the sweep's door, with and without energies: each
    /// point's answer or refusal is its single solve's, whether in lanes or
    /// one by one (lanes in both regimes, on the switch itself, a zero spin
    /// of either sign, a refusal, a spin beyond the fast range, a tail).
    #[test]
    fn a_block_answers_each_point_as_its_single_solve() {
        let swept = [Input::Spin, Input::NormalVelocity, Input::Mass];
        let mut spins: Vec<f64> = (0..24).map(|k| -9.0 + 0.75 * k as f64).collect();
        // The switch in a group of its own, and beside sticking spins.
        spins.extend([1.5, 1.5, -1.5, 1.5, 1.0, -1.5, 0.5, -0.25]);
        spins.extend([0.0, -0.0, 0.0, -0.0, 1e300, 2.0, 3.0, 4.0, 7.0]);
        let points: Vec<TorsionalImpact> = spins
            .iter()
            .enumerate()
            .map(|(k, &spin)| {
                // Each lane its own mass, so its own switch (the exact one
                // only at a mass of 2).
                let mass = if spin.abs() == 1.5 {
                    2.0
                } else {
                    1.0 + (k % 3) as f64
                };
                let mut p = body(spin, mass);
                if k == 5 {
                    p.normal_velocity = 1.0;
                }
                if k == 13 {
                    p.mass = f64::NAN;
                }
                p
            })
            .collect();
        for outputs in [Outputs::ALL, Outputs::MINIMAL] {
            let solver = Solver::new(&body(3.0, 2.0), &swept, outputs, Precision::Fast);
            assert!(solver.in_lanes());
            // Point 5 separates, point 13 has no mass, and point 36's
            // energies overflow.
            let refused = block_answers_as_single_solves(&solver, &points);
            match outputs.energy {
                true => assert_eq!(refused, [5, 13, 36]),
                false => assert_eq!(refused, [5, 13]),
            }
            let mut together = Vec::new();
            for (g, group) in points.chunks_exact(LANES).enumerate() {
                let group: &[TorsionalImpact; LANES] = group.try_into().expect("four");
                let mut out = [TorsionalOutcome::default(); LANES];
                if TorsionalImpact::evaluate_lanes(group, &(), outputs, &mut out) {
                    together.push(g);
                    for (impact, outcome) in group.iter().zip(&out) {
                        let single = solve(impact, outputs, Precision::Fast);
                        assert_eq!(format!("{single:?}"), format!("{:?}", Ok::<_, ()>(outcome)));
                    }
                }
            }
            // Together: the sliding groups of one sign, and the zero spins
            // (restitution). One by one: a refusal (1, 3), both regimes
            // (2), the switch's tie (6), spins of both signs (7). Group 9's
            // spin beyond the fast range is the sweep's to test (above),
            // not `evaluate_lanes`'s: called directly, the lanes refuse
            // only its overflowing energies.
            match outputs.energy {
                true => assert_eq!(together, [0, 4, 5, 8]),
                false => assert_eq!(together, [0, 4, 5, 8, 9]),
            }
        }
    }

    /// Lanes answer `fast` alone.
    #[test]
    fn which_solvers_run_lanes() {
        let base = body(3.0, 2.0);
        let solver = |precision| Solver::new(&base, &[Input::Spin], Outputs::ALL, precision);
        assert!(solver(Precision::Fast).in_lanes());
        assert!(!solver(Precision::Exact).in_lanes());
    }
}
