use super::*;

/// A toy case: the output is the sum of the point's two inputs; negative sums fail.
#[derive(Debug)]
struct Sum;

impl SweepCase for Sum {
    type Point = [f64; 2];
    type Param = usize;
    type Outcome = f64;
    fn set(point: &mut [f64; 2], param: usize, value: f64) {
        point[param] = value;
    }
    fn columns(&self) -> usize {
        1
    }
    fn evaluate(&self, p: &[f64; 2], out: &mut f64) -> Result<(), ImpactError> {
        if p[0] + p[1] < 0.0 {
            return Err(ImpactError::NotFinite {
                input: crate::error::Input::Mass,
            });
        }
        *out = p[0] + p[1];
        Ok(())
    }
    fn read(&self, _: usize, outcomes: &[f64], cells: &mut [Cell]) {
        for (&x, cell) in outcomes.iter().zip(cells) {
            *cell = Cell::Number(x);
        }
    }
}

/// The first input over `first`, the second over `count` values in `[start, stop]`.
fn grid(first: Vec<f64>, [start, stop]: [f64; 2], count: u64, combine: Combine) -> Sweep<Sum> {
    let axes = vec![
        Axis {
            param: 0,
            values: AxisValues::List(first),
        },
        Axis {
            param: 1,
            values: AxisValues::Linspace { start, stop, count },
        },
    ];
    Sweep::new(Sum, [0.0; 2], axes, combine, 1000).unwrap()
}

fn sweep(combine: Combine) -> Sweep<Sum> {
    grid(vec![-10.0, 10.0, 20.0], [0.0, 2.0], 3, combine)
}

fn collect(s: &Sweep<Sum>, range: Range<u64>) -> Vec<(u64, Vec<f64>, Option<f64>)> {
    let mut rows = Vec::new();
    s.for_each_in(range, |row| {
        let out = row.outcome.ok().map(|c| match c[0] {
            Cell::Number(x) => x,
            Cell::Text(_) => f64::NAN,
        });
        rows.push((row.index, row.axis_values.to_vec(), out));
    });
    rows
}

/// The sweep's rows through [`Sweep::run_parallel`] in chunks of `chunk`.
fn collect_parallel(s: &Sweep<Sum>, chunk: u64) -> Vec<(u64, Vec<f64>, Option<f64>)> {
    let mut rows = Vec::new();
    assert!(s.run_parallel(
        chunk,
        |r| collect(s, r),
        |part| {
            rows.extend(part);
            true
        }
    ));
    rows
}

/// The blocks hold the rows' points, column by column: over several
/// blocks (a grid of 3 × 150 points), refusals included, the whole grid
/// and a range from its middle.
#[test]
fn blocks_hold_the_rows_column_by_column() {
    let s = grid(vec![-1.0, 0.5, 3.0], [-2.0, 2.0], 150, Combine::Product);
    for range in [0..450, 100..401] {
        let rows = collect(&s, range.clone());
        let mut from_blocks = Vec::new();
        let mut blocks = 0;
        s.for_each_block_in(range.clone(), |block| {
            blocks += 1;
            assert!(!block.is_empty() && block.len() <= BLOCK);
            let refused: Vec<usize> = block.refusals().iter().map(|(k, _)| *k).collect();
            let (first, second): (Vec<f64>, Vec<f64>) = (block.axis(0).collect(), block.axis(1).collect());
            for k in 0..block.len() {
                assert_eq!(block.answered()[k], !refused.contains(&k));
                // This case reads cells alone.
                let Column::Cells(cells) = block.column(0) else {
                    panic!("a column of cells")
                };
                let out = match cells[k] {
                    Cell::Number(x) if block.answered()[k] => Some(x),
                    _ => None,
                };
                from_blocks.push((block.start() + k as u64, vec![first[k], second[k]], out));
            }
        });
        assert_eq!(from_blocks, rows);
        assert_eq!(blocks, (range.end - range.start).div_ceil(BLOCK as u64));
        assert!(rows.iter().any(|r| r.2.is_none()) && rows.iter().any(|r| r.2.is_some()));
    }
}

#[test]
fn product_varies_the_first_axis_slowest_and_keeps_errors_per_point() {
    let s = sweep(Combine::Product);
    assert_eq!(s.points(), 9);
    let rows = collect(&s, 0..9);
    assert_eq!(rows[0], (0, vec![-10.0, 0.0], None));
    assert_eq!(rows[2], (2, vec![-10.0, 2.0], None));
    assert_eq!(rows[3], (3, vec![10.0, 0.0], Some(10.0)));
    assert_eq!(rows[8], (8, vec![20.0, 2.0], Some(22.0)));
    // Any sub-range gives the same rows as the whole.
    assert_eq!(collect(&s, 4..7), rows[4..7].to_vec());
}

#[test]
fn ranges_compute_their_own_points_and_tile_the_whole() {
    let whole = collect(&sweep(Combine::Product), 0..9);
    let axes = sweep(Combine::Product).axes;
    let mut tiled = Vec::new();
    for r in [0..4, 4..4, 4..9] {
        // The limit applies to the range: a grid of 9 points in slices of at most 5.
        let s = Sweep::slice(Sum, [0.0; 2], axes.clone(), Combine::Product, Some(r.clone()), 5).unwrap();
        assert_eq!((s.points(), s.total_points()), (r.end - r.start, 9));
        let rows = collect_parallel(&s, 2);
        assert_eq!(rows, collect(&s, 0..9));
        tiled.extend(rows);
    }
    assert_eq!(tiled, whole);
    let slice =
        |r: Range<u64>, limit| Sweep::slice(Sum, [0.0; 2], axes.clone(), Combine::Product, Some(r), limit);
    assert_eq!(
        slice(3..10, 100).unwrap_err(),
        GridError::RangeOutside {
            start: 3,
            end: 10,
            points: 9
        }
    );
    #[allow(clippy::reversed_empty_ranges)]
    let reversed = 5..3;
    assert!(matches!(
        slice(reversed, 100),
        Err(GridError::RangeOutside { .. })
    ));
    assert_eq!(
        slice(0..9, 8).unwrap_err(),
        GridError::RangeTooLarge {
            start: 0,
            end: 9,
            limit: 8
        }
    );
}

#[test]
fn parallel_chunks_arrive_in_order_from_inside_the_pool_too() {
    let s = sweep(Combine::Product);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    assert_eq!(pool.install(|| collect_parallel(&s, 2)), collect(&s, 0..9));
}

#[test]
fn zip_pairs_values() {
    let s = sweep(Combine::Zip);
    let rows = collect(&s, 0..3);
    assert_eq!(rows[1], (1, vec![10.0, 1.0], Some(11.0)));
    assert_eq!(rows[2], (2, vec![20.0, 2.0], Some(22.0)));
}

#[test]
fn parallel_chunks_arrive_in_order_and_stop_on_request() {
    let s = sweep(Combine::Product);
    assert_eq!(collect_parallel(&s, 2), collect(&s, 0..9));
    let mut calls = 0;
    assert!(!s.run_parallel(
        1,
        |r| r,
        |_| {
            calls += 1;
            calls < 2
        }
    ));
    assert_eq!(calls, 2);
}
