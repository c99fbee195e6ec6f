//! `restitution collect`: the Arrow parts of a sharded sweep (a Kubernetes
//! Indexed Job's `part-I.arrow`, or `restitution sweep --shards N --index I`)
//! checked and joined into one stream. Each part's schema metadata says what
//! it is a slice of (`restitution.sweep_sha256`, the model version, the
//! precision, the total number of points, its range); the parts are joined
//! only when they are slices of one sweep, in order, covering it exactly,
//! with the same columns. Anything else fails, naming the part and what
//! differs.

use std::collections::HashMap;
use std::io::{Read, Write};

use arrow_ipc::reader::StreamReader;
use arrow_ipc::writer::{DictionaryHandling, IpcWriteOptions, StreamWriter};
use arrow_schema::Schema;

/// Why the parts cannot be joined.
#[derive(Debug, thiserror::Error)]
pub enum CollectError {
    /// Reading a part or writing the whole failed.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// A part is not an Arrow stream of a sweep.
    #[error("{part}: {reason}")]
    NotASweep {
        /// The part's name.
        part: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The parts are not the slices of one sweep that tile it in order.
    #[error("{part}: {reason}")]
    Mismatch {
        /// The first part that does not fit.
        part: String,
        /// How it differs.
        reason: String,
    },
}

/// The metadata keys that must agree across the parts.
const SAME: [&str; 4] = [
    "restitution.sweep_sha256",
    "restitution.model_version",
    "restitution.precision",
    "restitution.total_points",
];

/// One part as read: its schema (with metadata) and its batches.
struct Part {
    name: String,
    schema: Schema,
    batches: Vec<arrow_array::RecordBatch>,
    start: u64,
    end: u64,
}

fn read_part(name: String, reader: impl Read) -> Result<Part, CollectError> {
    let not_a_sweep = |reason: String| CollectError::NotASweep {
        part: name.clone(),
        reason,
    };
    let stream = StreamReader::try_new(reader, None)
        .map_err(|e| not_a_sweep(format!("not an Arrow IPC stream ({e})")))?;
    let schema = stream.schema().as_ref().clone();
    let batches = stream
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| not_a_sweep(format!("a record batch cannot be read ({e})")))?;
    let number = |key: &str| -> Result<u64, CollectError> {
        schema
            .metadata()
            .get(key)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| {
                not_a_sweep(format!(
                    "its schema has no {key} (not written by restitution sweep)"
                ))
            })
    };
    let (start, end) = (
        number("restitution.range_start")?,
        number("restitution.range_end")?,
    );
    for key in SAME {
        if !schema.metadata().contains_key(key) {
            return Err(not_a_sweep(format!(
                "its schema has no {key} (not written by restitution sweep)"
            )));
        }
    }
    let rows: usize = batches.iter().map(|b| b.num_rows()).sum();
    if rows as u64 != end - start {
        return Err(not_a_sweep(format!(
            "it holds {rows} rows, but its range {start}..{end} has {}",
            end - start
        )));
    }
    Ok(Part {
        name,
        schema,
        batches,
        start,
        end,
    })
}

/// Joins `parts` (each a name and a reader, in index order) into one Arrow
/// stream on `output`, whose metadata says it is the whole sweep (range
/// `0..total`). Returns the number of rows written.
pub fn collect<R: Read>(parts: Vec<(String, R)>, output: impl Write) -> Result<u64, CollectError> {
    let parts = parts
        .into_iter()
        .map(|(name, reader)| read_part(name, reader))
        .collect::<Result<Vec<_>, _>>()?;
    let Some(first) = parts.first() else {
        return Err(CollectError::Mismatch {
            part: "(none)".to_owned(),
            reason: "no parts were given".to_owned(),
        });
    };
    let total: u64 = first.schema.metadata()["restitution.total_points"]
        .parse()
        .expect("checked when read");
    let mut next = 0;
    for part in &parts {
        let mismatch = |reason: String| CollectError::Mismatch {
            part: part.name.clone(),
            reason,
        };
        for key in SAME {
            let (ours, theirs) = (&part.schema.metadata()[key], &first.schema.metadata()[key]);
            if ours != theirs {
                return Err(mismatch(format!(
                    "{key} is {ours}, but {} has {theirs}: a part of another sweep",
                    first.name
                )));
            }
        }
        if part.schema.fields() != first.schema.fields() {
            return Err(mismatch(format!("its columns differ from {}'s", first.name)));
        }
        if part.start != next {
            return Err(mismatch(format!(
                "its range starts at point {}, where {next} was expected (a part missing, repeated or out of order)",
                part.start
            )));
        }
        next = part.end;
    }
    if next != total {
        return Err(CollectError::Mismatch {
            part: parts.last().expect("at least one").name.clone(),
            reason: format!("the parts end at point {next} of the sweep's {total}: parts are missing"),
        });
    }
    let mut metadata: HashMap<String, String> = first.schema.metadata().clone().into_iter().collect();
    metadata.insert("restitution.range_start".to_owned(), "0".to_owned());
    metadata.insert("restitution.range_end".to_owned(), total.to_string());
    let schema = Schema::new_with_metadata(first.schema.fields().clone(), metadata);
    // The regimes are dictionary columns; each part has its own dictionary,
    // which the stream extends (a delta) or replaces as the service does.
    let options = IpcWriteOptions::default().with_dictionary_handling(DictionaryHandling::Delta);
    let mut writer =
        StreamWriter::try_new_with_options(output, &schema, options).map_err(std::io::Error::other)?;
    let schema = std::sync::Arc::new(schema);
    for batch in parts.iter().flat_map(|p| &p.batches) {
        let batch = arrow_array::RecordBatch::try_new(schema.clone(), batch.columns().to_vec())
            .map_err(std::io::Error::other)?;
        writer.write(&batch).map_err(std::io::Error::other)?;
    }
    writer.finish().map_err(std::io::Error::other)?;
    Ok(total)
}
