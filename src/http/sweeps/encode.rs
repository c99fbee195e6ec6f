//! The row encoders: CSV, NDJSON and the JSON table, written chunk by chunk
//! with shortest round-trip numbers.

use super::negotiate::Format;
use crate::impact::Precision;
use crate::sweep::{Cell, Row, Sweep, SweepCase};

/// Bytes per chunk of formatted rows: the unit of parallel work and of
/// streaming. A stream holds at most `QUEUED_CHUNKS` chunks in its queue and
/// two per worker thread in flight, so its memory is a few MiB whatever its size.
const CHUNK_BYTES: u64 = 256 * 1024;
/// Bytes a formatted cell takes at most (a shortest-round-trip double and a separator).
const CELL_BYTES: u64 = 24;

impl RowWriter {
    /// Points per chunk: about `CHUNK_BYTES` of output, between 64 and 4,096 rows.
    pub(super) fn chunk_points(&self) -> u64 {
        (CHUNK_BYTES / (CELL_BYTES * (self.names.len() as u64 + 1))).clamp(64, 4096)
    }
}
/// Writes one point in a format.
#[derive(Clone)]
pub(super) struct RowWriter {
    pub(super) format: Format,
    pub(super) precision: Precision,
    /// Axis paths, then output pointers.
    pub(super) names: Vec<&'static str>,
    /// Index of the sweep's first point (its range's start).
    pub(super) first: u64,
}

impl RowWriter {
    pub(super) fn header(&self) -> Vec<u8> {
        let mut out = Vec::new();
        match self.format {
            Format::Csv => {
                for name in &self.names {
                    out.extend_from_slice(name.as_bytes());
                    out.push(b',');
                }
                out.extend_from_slice(b"error\r\n");
            }
            Format::Json => {
                out.extend_from_slice(b"{\"columns\":[");
                for name in &self.names {
                    push_string(&mut out, name);
                    out.push(b',');
                }
                out.extend_from_slice(b"\"error\"],\"rows\":[");
            }
            Format::Ndjson | Format::Svg | Format::Arrow => {}
        }
        out
    }

    fn row(&self, out: &mut Vec<u8>, row: &Row<'_>) {
        let mut number = ryu::Buffer::new();
        let mut cells = row
            .axis_values
            .iter()
            .map(|&v| Some(Cell::Number(v)))
            .chain(Cells::new(row, self.names.len() - row.axis_values.len()));
        let error = row.outcome.err().map(|e| e.title());
        match self.format {
            Format::Csv => {
                for cell in cells.by_ref() {
                    match cell {
                        Some(Cell::Number(x)) => push_number(out, &mut number, x),
                        Some(Cell::Text(s)) => out.extend_from_slice(s.as_bytes()),
                        None => {}
                    }
                    out.push(b',');
                }
                if let Some(title) = error {
                    out.extend_from_slice(title.as_bytes());
                }
                out.extend_from_slice(b"\r\n");
            }
            Format::Json => {
                if row.index > self.first {
                    out.push(b',');
                }
                out.push(b'[');
                for cell in cells.by_ref() {
                    push_cell(out, &mut number, cell);
                    out.push(b',');
                }
                push_error(out, error);
                out.push(b']');
            }
            Format::Ndjson => {
                out.push(b'{');
                for (name, cell) in self.names.iter().zip(cells.by_ref()) {
                    push_string(out, name);
                    out.push(b':');
                    push_cell(out, &mut number, cell);
                    out.push(b',');
                }
                out.extend_from_slice(b"\"error\":");
                push_error(out, error);
                out.extend_from_slice(b"}\n");
            }
            Format::Svg | Format::Arrow => {}
        }
    }
}

/// The output cells of a row, `None` for each when the point has no answer.
struct Cells<'a> {
    cells: Result<std::slice::Iter<'a, Cell>, std::ops::Range<usize>>,
}

impl<'a> Cells<'a> {
    fn new(row: &Row<'a>, outputs: usize) -> Self {
        Cells {
            cells: row.outcome.map(|c| c.iter()).map_err(|_| 0..outputs),
        }
    }
}

impl Iterator for Cells<'_> {
    type Item = Option<Cell>;
    fn next(&mut self) -> Option<Option<Cell>> {
        match &mut self.cells {
            Ok(iter) => iter.next().map(|c| Some(*c)),
            Err(range) => range.next().map(|_| None),
        }
    }
}

fn push_number(out: &mut Vec<u8>, buffer: &mut ryu::Buffer, x: f64) {
    if x.is_finite() {
        out.extend_from_slice(buffer.format_finite(x).as_bytes());
    }
}

fn push_cell(out: &mut Vec<u8>, buffer: &mut ryu::Buffer, cell: Option<Cell>) {
    match cell {
        Some(Cell::Number(x)) if x.is_finite() => push_number(out, buffer, x),
        Some(Cell::Text(s)) => push_string(out, s),
        _ => out.extend_from_slice(b"null"),
    }
}

fn push_error(out: &mut Vec<u8>, error: Option<&str>) {
    match error {
        Some(title) => push_string(out, title),
        None => out.extend_from_slice(b"null"),
    }
}

fn push_string(out: &mut Vec<u8>, s: &str) {
    // Names and titles are fixed ASCII-safe strings; serde_json escapes anyway.
    let _ = serde_json::to_writer(&mut *out, s);
}

/// The JSON table, computed in parallel chunks.
pub(super) fn table<C: SweepCase>(
    sweep: &Sweep<C>,
    writer: &RowWriter,
    stop: impl Fn() -> bool + Sync,
) -> Vec<u8> {
    let mut out = writer.header();
    let mut errors = 0u64;
    sweep.run_parallel(
        writer.chunk_points(),
        |range| (!stop()).then(|| chunk(sweep, writer, range)),
        |chunk| match chunk {
            Some((bytes, failed)) => {
                out.extend_from_slice(&bytes);
                errors += failed;
                true
            }
            None => false,
        },
    );
    out.extend_from_slice(
        format!(
            "],\"points\":{},\"total_points\":{},\"range\":{{\"start\":{},\"end\":{}}},\
             \"errors\":{errors},\"precision\":\"{}\"}}",
            sweep.points(),
            sweep.total_points(),
            sweep.range().start,
            sweep.range().end,
            writer.precision.as_str()
        )
        .as_bytes(),
    );
    out
}

/// One chunk of rows and its number of failed points.
pub(super) fn chunk<C: SweepCase>(
    sweep: &Sweep<C>,
    writer: &RowWriter,
    range: std::ops::Range<u64>,
) -> (Vec<u8>, u64) {
    let mut out =
        Vec::with_capacity(((range.end - range.start) * CELL_BYTES) as usize * (writer.names.len() + 1));
    let mut failed = 0;
    sweep.for_each_in(range, |row| {
        failed += u64::from(row.outcome.is_err());
        writer.row(&mut out, &row);
    });
    (out, failed)
}
