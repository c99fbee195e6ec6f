//! An impact case over a grid: [`CaseSweep`], the base impact's solver
//! prepared once and the output columns, read through the case's readers.

use super::{Cell, SweepCase};
use crate::error::{ImpactError, Input, Output};
use crate::impact::{Arithmetic, Case, Precision, Solver};
use crate::outcome::{Answers, ColumnReader, NumberReader, Outputs};

/// An impact case over a grid: the base impact's [`Solver`] and the chosen
/// output columns.
#[derive(Debug, Clone)]
pub struct CaseSweep<C: Case> {
    solver: Solver<C>,
    columns: Vec<Output>,
    /// How each column is read off a block's outcomes (the case's
    /// declaration, looked up once).
    readers: Vec<ColumnReader<C::Outcome>>,
    /// How each number column is read straight into numbers (`None` for a
    /// column of names).
    numbers: Vec<Option<NumberReader<C::Outcome>>>,
}

/// Why a sweep of a case cannot be prepared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum CaseSweepError {
    /// An axis sets an input the base impact does not read.
    #[error("{} is not an input of this impact", .0.path())]
    NotRead(Input),
    /// A column names an output the case does not answer.
    #[error("{} is not an output of this case", .0.path())]
    NotAnswered(Output),
}

impl<C: Case> CaseSweep<C> {
    /// Prepares `base` for a sweep in which axes set `swept`, computing only
    /// what `columns` need. Refuses the first swept input the base impact
    /// does not read, and the first column the case does not answer.
    pub fn new(
        base: &C,
        swept: &[Input],
        columns: Vec<Output>,
        precision: Precision,
    ) -> Result<Self, CaseSweepError> {
        CaseSweep::in_arithmetic(base, swept, columns, precision.into())
    }

    /// The same in one `arithmetic` ([`Solver::in_arithmetic`]; a measurement hook).
    #[doc(hidden)]
    pub fn in_arithmetic(
        base: &C,
        swept: &[Input],
        columns: Vec<Output>,
        arithmetic: Arithmetic,
    ) -> Result<Self, CaseSweepError> {
        if let Some(&unread) = swept.iter().find(|&&i| base.input(i).is_none()) {
            return Err(CaseSweepError::NotRead(unread));
        }
        let readers = columns
            .iter()
            .map(|&c| C::Outcome::column(c).ok_or(CaseSweepError::NotAnswered(c)))
            .collect::<Result<_, _>>()?;
        let numbers = columns
            .iter()
            .map(|&c| if c.is_name() { None } else { C::Outcome::numbers(c) })
            .collect();
        Ok(CaseSweep {
            solver: Solver::in_arithmetic(base, swept, Outputs::needed_by(&columns), arithmetic),
            columns,
            readers,
            numbers,
        })
    }

    /// The optional outputs the columns need.
    pub fn outputs(&self) -> Outputs {
        self.solver.outputs()
    }

    /// The columns.
    pub fn columns(&self) -> &[Output] {
        &self.columns
    }

    /// Solves one point with every output the columns need.
    pub fn solve(&self, point: &C) -> Result<C::Outcome, ImpactError> {
        self.solver.solve(point)
    }
}

impl<C: Case> SweepCase for CaseSweep<C> {
    type Point = C;
    type Param = Input;
    type Outcome = C::Outcome;

    /// Sets an input the point reads ([`CaseSweep::new`] refuses axes of any other).
    #[inline]
    fn set(point: &mut C, input: Input, value: f64) {
        if let Some(slot) = point.input_mut(input) {
            *slot = value;
        }
    }

    fn columns(&self) -> usize {
        self.columns.len()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate(&self, point: &C, out: &mut C::Outcome) -> Result<(), ImpactError> {
        self.solver.solve_into(point, out)
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn in_blocks(&self) -> bool {
        self.solver.in_lanes()
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn evaluate_block(
        &self,
        points: &[C],
        outs: &mut [C::Outcome],
        refusals: &mut Vec<(usize, ImpactError)>,
    ) {
        self.solver
            .solve_block_into(points, outs, |k, e| refusals.push((k, e)))
    }

    #[inline]
    fn read(&self, column: usize, outcomes: &[C::Outcome], cells: &mut [Cell]) {
        (self.readers[column])(outcomes, cells)
    }

    #[inline]
    fn read_numbers(&self, column: usize, outcomes: &[C::Outcome], values: &mut [f64]) -> bool {
        match self.numbers[column] {
            Some(read) => {
                read(outcomes, values);
                true
            }
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{BarrierImpact, Law, TorsionalImpact, solve};
    use crate::input::BarrierBody;
    use crate::scene::{Contact, PlanarVelocity};
    use crate::sweep::{Axis, AxisValues, Column, Combine, Sweep};

    fn maw(friction: f64) -> BarrierImpact {
        BarrierImpact::rigid(
            1.0,
            0.5 * 0.05 * 0.05,
            Contact {
                tangential_offset: 0.0,
                normal_offset: 0.05,
            },
            PlanarVelocity {
                normal: -1.0,
                tangential: 2.0,
                angular: 0.0,
            },
            Law::TangentialRestitution {
                restitution: 0.93,
                friction,
                tangential_restitution: 0.34,
            },
        )
    }

    #[test]
    fn a_fixed_scene_gives_the_same_answers_as_one_built_per_point() {
        let columns = vec![Output::FinalTangentialContactVelocity, Output::EnergyLoss];
        let fixed =
            CaseSweep::new(&maw(0.123), &[Input::Friction], columns.clone(), Precision::Fast).unwrap();
        // Sweeping a velocity too: the scene and the law built per point.
        let per_point = CaseSweep::new(
            &maw(0.123),
            &[Input::TangentialVelocity, Input::Friction],
            columns,
            Precision::Fast,
        )
        .unwrap();
        assert!(fixed.outputs().energy && !fixed.outputs().critical_impulse_ratio);
        for f in [0.0, 0.05, 0.123, 0.5] {
            let p = maw(f);
            assert_eq!(fixed.solve(&p), per_point.solve(&p));
            assert_eq!(
                fixed.solve(&p).unwrap(),
                solve(&p, fixed.outputs(), Precision::Fast).unwrap()
            );
        }
    }

    #[test]
    fn a_fixed_law_gives_the_same_answers_and_refusals_as_one_validated_per_point() {
        let columns = vec![Output::FinalTangentialContactVelocity, Output::Regime];
        // The law is valid in one base and out of range (e_t > 1) in the other.
        for et in [0.34, 1.5] {
            let mut base = maw(0.123);
            base.law = Law::TangentialRestitution {
                restitution: 0.93,
                friction: 0.123,
                tangential_restitution: et,
            };
            let fixed_law = CaseSweep::new(
                &base,
                &[Input::TangentialVelocity],
                columns.clone(),
                Precision::Fast,
            )
            .unwrap();
            let per_point = CaseSweep::new(
                &base,
                &[Input::TangentialVelocity, Input::TangentialRestitution],
                columns.clone(),
                Precision::Fast,
            )
            .unwrap();
            for vt in [-3.0, 0.0, 0.01, 2.0] {
                let mut p = base;
                p.velocity.tangential = vt;
                let answer = fixed_law.solve(&p);
                assert_eq!(answer, per_point.solve(&p));
                assert_eq!(answer, solve(&p, fixed_law.outputs(), Precision::Fast));
                assert_eq!(answer.is_ok(), et <= 1.0, "{answer:?}");
            }
        }
    }

    /// A body no axis changes is validated once: where it is invalid, every
    /// point is refused as its single solve refuses it, with a fixed law (in
    /// lanes) and with a swept one.
    #[test]
    fn a_fixed_invalid_body_is_refused_as_single_solves_refuse_it() {
        let velocities = [-3.0, 0.0, 1.0, 2.0, 2.5, 4.0, 5.0, 6.0, 7.0];
        let columns = vec![Output::FinalTangentialContactVelocity];
        let mut invalid = [maw(0.123); 4];
        if let BarrierBody::Rigid { mass, inertia, .. } = &mut invalid[0].body {
            *mass = 0.0;
            *inertia = f64::NAN;
        }
        if let BarrierBody::Rigid { inertia, .. } = &mut invalid[1].body {
            *inertia = -1.0;
        }
        if let BarrierBody::Rigid { contact, .. } = &mut invalid[2].body {
            contact.normal_offset = f64::INFINITY;
        }
        // The last is valid: its points are answered, by lanes too.
        for base in invalid {
            for swept in [
                vec![Input::TangentialVelocity],
                vec![Input::TangentialVelocity, Input::Friction],
            ] {
                for precision in [Precision::Fast, Precision::Exact] {
                    let case = CaseSweep::new(&base, &swept, columns.clone(), precision).unwrap();
                    let axes = vec![Axis {
                        param: Input::TangentialVelocity,
                        values: AxisValues::List(velocities.to_vec()),
                    }];
                    let sweep = Sweep::new(case, base, axes, Combine::Product, 100).unwrap();
                    let mut k = 0;
                    sweep.for_each_in(0..sweep.points(), |row| {
                        let mut point = base;
                        point.velocity.tangential = velocities[k];
                        let single = solve(&point, Outputs::MINIMAL, precision);
                        match (row.outcome, single) {
                            (Ok(&[Cell::Number(x)]), Ok(one)) => {
                                assert_eq!(x.to_bits(), one.contact_velocity.r#final.tangential.to_bits())
                            }
                            (Err(e), Err(one)) => assert_eq!(*e, one),
                            (row, single) => panic!("{row:?} against {single:?}"),
                        }
                        k += 1;
                    });
                    assert_eq!(k, velocities.len());
                }
            }
        }
    }

    #[test]
    fn an_axis_the_law_does_not_read_is_refused() {
        let refused = CaseSweep::new(
            &maw(0.1),
            &[Input::ImpulseRatio],
            vec![Output::Regime],
            Precision::Fast,
        );
        assert_eq!(refused.err(), Some(CaseSweepError::NotRead(Input::ImpulseRatio)));
    }

    #[test]
    fn invalid_points_fail_alone() {
        let base = maw(0.123);
        let case = CaseSweep::new(
            &base,
            &[Input::NormalVelocity],
            vec![Output::Regime],
            Precision::Fast,
        )
        .unwrap();
        let axes = vec![Axis {
            param: Input::NormalVelocity,
            values: AxisValues::List(vec![-1.0, 0.5, -2.0]),
        }];
        let sweep = Sweep::new(case, base, axes, Combine::Product, 10).unwrap();
        let mut outcomes = Vec::new();
        sweep.for_each_in(0..3, |row| {
            outcomes.push(row.outcome.map(|c| c.to_vec()).map_err(|e| e.title()))
        });
        assert_eq!(outcomes[0], Ok(vec![Cell::Text("sliding")]));
        assert_eq!(outcomes[1], Err("Contact is not approaching"));
        assert_eq!(outcomes[2], Ok(vec![Cell::Text("sliding")]));
    }

    /// Out-of-range torsional inputs, fixed or swept, are answered as single solves answer them.
    #[test]
    fn extreme_fixed_and_swept_inputs_escalate_as_single_solves_do() {
        let base = TorsionalImpact {
            mass: 0.6,
            normal_inertia: 0.003456,
            normal_velocity: -3.0,
            spin: 0.0,
            restitution: 0.7,
            torsional_restitution: 0.2,
            torsional_friction: 0.3,
            pitch_radius: 0.01,
        };
        let spins = vec![20.0, 1e250, -3e-250, 0.0];
        for b in [base, TorsionalImpact { mass: 1e-250, ..base }] {
            let case = CaseSweep::new(&b, &[Input::Spin], vec![Output::FinalSpin], Precision::Fast).unwrap();
            let axes = vec![Axis {
                param: Input::Spin,
                values: AxisValues::List(spins.clone()),
            }];
            let sweep = Sweep::new(case, b, axes, Combine::Product, u64::MAX).expect("a sweep");
            let mut got = Vec::new();
            sweep.for_each_in(0..sweep.points(), |row| match row.outcome {
                Ok([Cell::Number(x)]) => got.push(*x),
                other => panic!("{other:?}"),
            });
            for (spin, got) in spins.iter().zip(got) {
                let one = solve(
                    &TorsionalImpact { spin: *spin, ..b },
                    Outputs::MINIMAL,
                    Precision::Fast,
                )
                .expect("an answer");
                assert_eq!(
                    got.to_bits(),
                    one.final_spin.to_bits(),
                    "spin {spin}, mass {}",
                    b.mass
                );
            }
        }
    }

    /// A sweep's blocks read each number column straight into numbers, and
    /// the columns of names into cells: every value the rows' cell, bit for
    /// bit (refusals, outputs not computed and names included).
    #[test]
    fn blocks_read_number_columns_as_the_rows_cells() {
        let base = maw(0.123);
        let columns = <BarrierImpact as Case>::Outcome::OUTPUTS.to_vec();
        let case = CaseSweep::new(
            &base,
            &[Input::NormalVelocity, Input::TangentialVelocity],
            columns,
            Precision::Fast,
        )
        .unwrap();
        let axes = vec![
            Axis {
                param: Input::NormalVelocity,
                values: AxisValues::List(vec![-1.0, 0.5, -2.0, -1e300]),
            },
            Axis {
                param: Input::TangentialVelocity,
                values: AxisValues::List((0..70).map(|k| -3.0 + 0.1 * k as f64).collect()),
            },
        ];
        let sweep = Sweep::new(case, base, axes, Combine::Product, u64::MAX).unwrap();
        let mut rows = Vec::new();
        sweep.for_each_in(0..sweep.points(), |row| {
            rows.push(row.outcome.map(|c| c.to_vec()).ok())
        });
        let mut seen = 0;
        sweep.for_each_block_in(0..sweep.points(), |block| {
            for (c, output) in sweep.case().columns().iter().enumerate() {
                let column = block.column(c);
                assert_eq!(output.is_name(), matches!(column, Column::Cells(_)), "{output:?}");
                for (k, &answered) in block.answered().iter().enumerate() {
                    let row = &rows[block.start() as usize + k];
                    assert_eq!(answered, row.is_some());
                    let Some(cells) = row else { continue };
                    match column {
                        Column::Numbers(values) => {
                            assert_eq!(values[k].to_bits(), cells[c].number().to_bits(), "{output:?}")
                        }
                        Column::Cells(cells_here) => assert_eq!(cells_here[k], cells[c]),
                    }
                }
            }
            seen += block.len();
        });
        assert_eq!(seen, rows.len());
        assert!(rows.iter().any(Option::is_none) && rows.iter().filter(|r| r.is_some()).count() > 100);
    }
}
