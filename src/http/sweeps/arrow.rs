//! The Arrow encoder: a sweep as an Arrow IPC stream, one record batch per
//! chunk of points. Axis columns are non-null f64; number outputs are
//! nullable f64 (null where the point has no answer or the value is not
//! finite, as CSV leaves the cell empty); names (regimes) and the `error`
//! column are dictionary-encoded strings whose dictionaries grow by delta
//! messages as new names appear. The schema's metadata carries the request's
//! hash, the model version and the range.

use std::collections::HashMap;
use std::ops::Range;
use std::sync::{Arc, Mutex};

use arrow_array::builder::NullBufferBuilder;
use arrow_array::types::Int16Type;
use arrow_array::{ArrayRef, DictionaryArray, Float64Array, Int16Array, RecordBatch, StringArray};
use arrow_ipc::writer::{DictionaryHandling, IpcWriteOptions, StreamEncoder};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use axum::body::Bytes;

use super::stream::Sink;
use crate::quantity::Output;
use crate::sweep::{Cell, Column, Sweep, SweepCase};

/// Bytes of column data per record batch (about): large enough that the IPC
/// framing is noise, small enough that a stream holds a few MiB.
const BATCH_BYTES: u64 = 1 << 20;

/// An IPC buffer at least this large is sent as it is; smaller ones are
/// gathered with their neighbours.
const HANDED_OVER_BYTES: usize = 16 * 1024;

/// The names one dictionary column has met, in order of first appearance:
/// their positions are the keys, shared by every worker.
#[derive(Debug, Default)]
struct Names(Mutex<Vec<&'static str>>);

impl Names {
    fn key(&self, name: &'static str) -> i16 {
        let mut names = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let at = match names.iter().position(|&n| n == name) {
            Some(at) => at,
            None => {
                names.push(name);
                names.len() - 1
            }
        };
        i16::try_from(at).expect("fewer than 32,768 distinct names")
    }

    fn snapshot(&self) -> Vec<&'static str> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }
}

/// A worker's cache of keys, so the shared list is locked only on a new name.
#[derive(Default)]
struct Keys(Vec<(&'static str, i16)>);

impl Keys {
    #[inline]
    fn get(&mut self, names: &Names, name: &'static str) -> i16 {
        if let Some(&(_, k)) = self.0.iter().find(|(n, _)| std::ptr::eq(*n, name) || *n == name) {
            return k;
        }
        let k = names.key(name);
        self.0.push((name, k));
        k
    }
}

/// How the columns of a sweep map to Arrow: shared by the workers.
#[derive(Debug)]
pub(super) struct ArrowLayout {
    schema: SchemaRef,
    axes: usize,
    /// For each output column, whether it holds names.
    text: Vec<bool>,
    /// One list of names per name column (the text outputs in order, then `error`).
    names: Vec<Names>,
}

/// One chunk of columns, built on a worker.
pub(super) struct ArrowChunk {
    rows: usize,
    numbers: Vec<(Vec<f64>, NullBufferBuilder)>,
    keys: Vec<(Vec<i16>, NullBufferBuilder)>,
}

impl ArrowLayout {
    /// The layout of axis columns `axes` and output columns `outputs`, with
    /// `metadata` on the schema.
    pub(super) fn new(axes: &[&'static str], outputs: &[Output], metadata: HashMap<String, String>) -> Self {
        let dictionary = DataType::Dictionary(Box::new(DataType::Int16), Box::new(DataType::Utf8));
        let mut fields: Vec<Field> = axes
            .iter()
            .map(|a| Field::new(*a, DataType::Float64, false))
            .collect();
        let text: Vec<bool> = outputs.iter().map(|o| o.is_name()).collect();
        for (o, &is_text) in outputs.iter().zip(&text) {
            let kind = if is_text {
                dictionary.clone()
            } else {
                DataType::Float64
            };
            fields.push(Field::new(o.path(), kind, true));
        }
        fields.push(Field::new("error", dictionary, true));
        let names = (0..=text.iter().filter(|&&t| t).count())
            .map(|_| Names::default())
            .collect();
        ArrowLayout {
            schema: Arc::new(Schema::new_with_metadata(fields, metadata)),
            axes: axes.len(),
            text,
            names,
        }
    }

    /// Points per record batch: about `BATCH_BYTES` of column data.
    pub(super) fn chunk_points(&self) -> u64 {
        (BATCH_BYTES / (8 * (self.axes + self.text.len() + 1) as u64)).clamp(1024, 65_536)
    }

    /// Computes the points of `range` into columns.
    pub(super) fn chunk<C: SweepCase>(&self, sweep: &Sweep<C>, range: Range<u64>) -> ArrowChunk {
        let rows = (range.end - range.start) as usize;
        let texts = self.names.len() - 1;
        let numbers = (0..self.axes + self.text.len() - texts)
            .map(|_| (Vec::with_capacity(rows), NullBufferBuilder::new(rows)))
            .collect();
        let keys = (0..=texts)
            .map(|_| (Vec::with_capacity(rows), NullBufferBuilder::new(rows)))
            .collect();
        let mut chunk = ArrowChunk { rows, numbers, keys };
        let mut caches: Vec<Keys> = (0..=texts).map(|_| Keys::default()).collect();
        // Column by column, a block of points at a time: one tight loop per
        // column rather than a pass over every column per point.
        sweep.for_each_block_in(range, |block| {
            let answered = block.answered();
            for (axis, (values, valid)) in chunk.numbers.iter_mut().take(self.axes).enumerate() {
                values.extend(block.axis(axis));
                valid.append_n_non_nulls(block.len());
            }
            let (mut number, mut text) = (self.axes, 0);
            for (i, &is_text) in self.text.iter().enumerate() {
                if is_text {
                    let (keys, valid) = &mut chunk.keys[text];
                    // (A column of names is read into cells: numbers hold no name.)
                    let column = block.column(i);
                    for (k, &ok) in answered.iter().enumerate() {
                        let cell = match column {
                            Column::Cells(cells) => cells[k],
                            Column::Numbers(numbers) => Cell::Number(numbers[k]),
                        };
                        match cell {
                            Cell::Text(name) if ok => {
                                keys.push(caches[text].get(&self.names[text], name));
                                valid.append(true);
                            }
                            _ => {
                                keys.push(0);
                                valid.append(false);
                            }
                        }
                    }
                    text += 1;
                } else {
                    let (values, valid) = &mut chunk.numbers[number];
                    let start = values.len();
                    match block.column(i) {
                        Column::Numbers(numbers) => values.extend_from_slice(numbers),
                        Column::Cells(cells) => values.extend(cells.iter().map(|cell| cell.number())),
                    }
                    // Every point answered with a finite value (the common
                    // block) in one step; else a null, with a zero, at each
                    // other.
                    let block_values = &mut values[start..];
                    if block.refusals().is_empty() && block_values.iter().all(|x| x.is_finite()) {
                        valid.append_n_non_nulls(block_values.len());
                    } else {
                        for (x, &ok) in block_values.iter_mut().zip(answered) {
                            let shown = ok && x.is_finite();
                            if !shown {
                                *x = 0.0;
                            }
                            valid.append(shown);
                        }
                    }
                    number += 1;
                }
            }
            let (keys, valid) = &mut chunk.keys[texts];
            if block.refusals().is_empty() {
                keys.resize(keys.len() + block.len(), 0);
                valid.append_n_nulls(block.len());
            } else {
                let mut refused = block.refusals().iter().peekable();
                for k in 0..block.len() {
                    match refused.next_if(|(i, _)| *i == k) {
                        Some((_, e)) => {
                            keys.push(caches[texts].get(&self.names[texts], e.title()));
                            valid.append(true);
                        }
                        None => {
                            keys.push(0);
                            valid.append(false);
                        }
                    }
                }
            }
        });
        chunk
    }
}

/// Writes the IPC stream: the schema, then one batch (and any dictionary
/// deltas) per chunk, then the end-of-stream marker.
pub(super) struct ArrowSink {
    layout: Arc<ArrowLayout>,
    /// The IPC stream's encoder, made by [`Sink::header`].
    encoder: Option<StreamEncoder>,
    /// Each name column's dictionary as last sent (reused while no name is new).
    dictionaries: Vec<ArrayRef>,
}

impl ArrowSink {
    pub(super) fn new(layout: Arc<ArrowLayout>) -> Self {
        ArrowSink {
            layout,
            encoder: None,
            dictionaries: Vec::new(),
        }
    }

    fn batch(&mut self, chunk: ArrowChunk) -> RecordBatch {
        let nulls = |mut valid: NullBufferBuilder| valid.finish();
        let mut numbers = chunk.numbers.into_iter();
        let mut keys = chunk.keys.into_iter().enumerate();
        let mut columns: Vec<ArrayRef> = Vec::with_capacity(self.layout.schema.fields().len());
        let mut number = |columns: &mut Vec<ArrayRef>| {
            let (values, valid) = numbers.next().expect("a number column");
            columns.push(Arc::new(Float64Array::new(values.into(), nulls(valid))));
        };
        for _ in 0..self.layout.axes {
            number(&mut columns);
        }
        let texts: Vec<bool> = self.layout.text.iter().copied().chain([true]).collect();
        for is_text in texts {
            if !is_text {
                number(&mut columns);
                continue;
            }
            let (i, (values, valid)) = keys.next().expect("a name column");
            let names = self.layout.names[i].snapshot();
            if self.dictionaries.get(i).is_none_or(|d| d.len() != names.len()) {
                let dictionary: ArrayRef = Arc::new(StringArray::from(names));
                match self.dictionaries.get_mut(i) {
                    Some(d) => *d = dictionary,
                    None => self.dictionaries.push(dictionary),
                }
            }
            let keys = Int16Array::new(values.into(), nulls(valid));
            // Every key was taken from the list before this batch was built.
            let column = DictionaryArray::<Int16Type>::try_new(keys, self.dictionaries[i].clone())
                .expect("keys within the dictionary");
            columns.push(Arc::new(column));
        }
        debug_assert!(columns.iter().all(|c| c.len() == chunk.rows));
        RecordBatch::try_new(self.layout.schema.clone(), columns).expect("columns match the schema")
    }
}

impl Sink<ArrowChunk> for ArrowSink {
    /// Nothing: the encoder puts the schema message before the first batch
    /// (or the end-of-stream marker of a sweep with no batch).
    fn header(&mut self) -> Vec<u8> {
        let options = IpcWriteOptions::default().with_dictionary_handling(DictionaryHandling::Delta);
        self.encoder =
            Some(StreamEncoder::try_new_with_options(&self.layout.schema, options).expect("an IPC schema"));
        Vec::new()
    }

    /// The batch's messages as the encoder built them: each column's values
    /// handed over, not copied; the small pieces between them (framing,
    /// message headers, validity) gathered into one piece each run, so a
    /// batch is a few body frames, not dozens.
    fn encode(&mut self, chunk: ArrowChunk) -> Vec<Bytes> {
        let batch = self.batch(chunk);
        let encoder = self.encoder.as_mut().expect("the header is written first");
        let buffers = encoder.encode(&batch).expect("an IPC record batch");
        let mut pieces = Vec::new();
        let mut small = Vec::new();
        for buffer in buffers {
            if buffer.len() < HANDED_OVER_BYTES {
                small.extend_from_slice(buffer.as_slice());
            } else {
                if !small.is_empty() {
                    pieces.push(Bytes::from(std::mem::take(&mut small)));
                }
                pieces.push(Bytes::from(buffer));
            }
        }
        if !small.is_empty() {
            pieces.push(Bytes::from(small));
        }
        pieces
    }

    fn trailer(&mut self) -> Vec<u8> {
        let encoder = self.encoder.take().expect("the header is written first");
        let buffers = encoder.finish().expect("the end-of-stream marker");
        buffers.iter().flat_map(|b| b.as_slice()).copied().collect()
    }
}
