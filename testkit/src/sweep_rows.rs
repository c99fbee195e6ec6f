//! Sweeps against single solves: every row of a sweep must be the single
//! solve of its point, bit for bit (a sweep prepares what its axes do not
//! change once, and walks the grid with its own odometer).

use restitution::sweep::{Axis, AxisValues, CaseSweep, Cell, Combine, Sweep};
use restitution::{Case, Input, Outputs, Precision, solve};

/// A cell as comparable bits (a number's bit pattern, or a name).
fn bits(cell: &Cell) -> String {
    match cell {
        Cell::Number(x) => format!("{:016x}", x.to_bits()),
        Cell::Text(t) => (*t).to_string(),
    }
}

/// Sweeps `input` of `base` over `values` with every output, in `fast` and
/// in `exact` precision, and asserts each row is the single solve of its
/// point in the same precision (the same cells, or the same refusal).
/// Returns the number of rows answered in `fast`.
pub fn sweep_is_single_solves<C: Case>(base: &C, input: Input, values: &[f64]) -> usize {
    let answered = rows_are_single_solves(base, input, values, Precision::Fast);
    rows_are_single_solves(base, input, values, Precision::Exact);
    answered
}

/// [`sweep_is_single_solves`] in one precision.
fn rows_are_single_solves<C: Case>(base: &C, input: Input, values: &[f64], precision: Precision) -> usize {
    let columns = C::OUTPUTS.to_vec();
    let case = CaseSweep::new(base, &[input], columns.clone(), precision).expect("an input the law reads");
    let axes = vec![Axis {
        param: input,
        values: AxisValues::List(values.to_vec()),
    }];
    let sweep = Sweep::new(case, *base, axes, Combine::Product, u64::MAX).expect("a sweep");
    let mut answered = 0;
    let mut rows = 0;
    sweep.for_each_in(0..sweep.points(), |row| {
        rows += 1;
        let x = values[row.index as usize];
        let mut impact = *base;
        *impact.input_mut(input).expect("read") = x;
        let single = solve(&impact, Outputs::ALL, precision);
        match (row.outcome, single) {
            (Ok(cells), Ok(outcome)) => {
                answered += 1;
                for (cell, &column) in cells.iter().zip(&columns) {
                    if !impact.answers(column) {
                        continue;
                    }
                    assert_eq!(
                        bits(cell),
                        bits(&C::output(&outcome, column).expect("an output of the case")),
                        "{precision:?}: {column:?} at {input:?} = {x:e} (row {}): {impact:?}",
                        row.index
                    );
                }
            }
            // (Through `Debug`: a payload may hold a NaN.)
            (Err(e), Err(single)) => assert_eq!(
                format!("{e:?}"),
                format!("{single:?}"),
                "{precision:?}: {input:?} = {x:e}: {impact:?}"
            ),
            (sweep, single) => {
                panic!("{precision:?}: {input:?} = {x:e}: sweep {sweep:?}, single {single:?}: {impact:?}")
            }
        }
    });
    assert_eq!(rows, values.len());
    answered
}
