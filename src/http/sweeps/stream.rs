//! Streaming a sweep: rows computed in parallel chunks on a blocking thread
//! and handed to the response body in order through a bounded channel, so a
//! streamed sweep holds a few chunks in memory whatever its size, and stops
//! when the client goes away or stops reading.

use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use axum::body::{Body, Bytes};
use axum::http::StatusCode;
use tokio::sync::{OwnedSemaphorePermit, Semaphore, mpsc};

use super::encode::RowWriter;
use crate::http::problem::ApiError;
use crate::sweep::{Sweep, SweepCase};

/// Chunks queued between the workers and the socket.
const QUEUED_CHUNKS: usize = 4;

/// The sweeps of one application at work (part of its state): how many
/// streamed or reduced sweeps are still computing (for tests, diagnostics and
/// shutdown), and the permits that bound how many buffered and streamed
/// sweeps compute at once, which bounds the memory they hold
/// (docs/scaling.md).
#[derive(Debug, Clone)]
pub struct Streams {
    active: Arc<AtomicUsize>,
    buffered: Arc<Semaphore>,
    streamed: Arc<Semaphore>,
}

impl Default for Streams {
    fn default() -> Self {
        let defaults = crate::http::ServiceConfig::default();
        Streams {
            active: Arc::default(),
            buffered: Arc::new(Semaphore::new(defaults.max_buffered_sweeps)),
            streamed: Arc::new(Semaphore::new(defaults.max_streamed_sweeps)),
        }
    }
}

impl Streams {
    /// The number of streamed sweeps whose producer is still working.
    pub fn active(&self) -> usize {
        self.active.load(Ordering::Acquire)
    }

    /// The same count, with at most `buffered` buffered and `streamed`
    /// streamed sweeps computing at once.
    pub fn limited(&self, buffered: usize, streamed: usize) -> Streams {
        Streams {
            active: self.active.clone(),
            buffered: Arc::new(Semaphore::new(buffered)),
            streamed: Arc::new(Semaphore::new(streamed)),
        }
    }

    pub(super) fn start(&self) -> ActiveStream {
        self.active.fetch_add(1, Ordering::AcqRel);
        ActiveStream(self.active.clone())
    }

    /// A permit to compute a buffered sweep (JSON table, SVG plot), held
    /// until its computation ends; 503 when all are taken.
    pub(super) fn buffered_permit(&self) -> Result<OwnedSemaphorePermit, ApiError> {
        self.buffered.clone().try_acquire_owned().map_err(|_| {
            busy(
                "buffered (application/json, image/svg+xml)",
                "or ask for a streamed format",
            )
        })
    }

    /// A permit to stream a sweep (CSV, NDJSON, Arrow), held by its producer;
    /// 503 when all are taken.
    pub(super) fn streamed_permit(&self) -> Result<OwnedSemaphorePermit, ApiError> {
        self.streamed.clone().try_acquire_owned().map_err(|_| {
            busy(
                "streamed (text/csv, application/x-ndjson, Arrow)",
                "or ask for a reduction",
            )
        })
    }
}

/// The refusal of a sweep beyond its kind's limit: 503, retry in a second.
fn busy(kind: &str, instead: &str) -> ApiError {
    ApiError::new(
        StatusCode::SERVICE_UNAVAILABLE,
        "sweeps-busy",
        "Too many sweeps at once",
        format!(
            "the server is computing as many {kind} sweeps as it takes at once; retry shortly, {instead}"
        ),
    )
    .retry_after(1)
}

/// Counts a producer as active while it lives.
pub(super) struct ActiveStream(Arc<AtomicUsize>);

impl Drop for ActiveStream {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Turns computed chunks into the bytes of a streamed format, in point order,
/// on the streaming thread (the chunks themselves are computed on the workers).
pub(super) trait Sink<T>: Send + 'static {
    /// The bytes before the first chunk.
    fn header(&mut self) -> Vec<u8>;
    /// The bytes of one chunk, in one or more pieces (an encoder may hand
    /// over the buffers it built rather than copy them into one).
    fn encode(&mut self, chunk: T) -> Vec<Bytes>;
    /// The bytes after the last chunk.
    fn trailer(&mut self) -> Vec<u8> {
        Vec::new()
    }
}

/// Text rows: chunks are already formatted on the workers.
impl Sink<Vec<u8>> for RowWriter {
    fn header(&mut self) -> Vec<u8> {
        RowWriter::header(self)
    }
    fn encode(&mut self, chunk: Vec<u8>) -> Vec<Bytes> {
        vec![Bytes::from(chunk)]
    }
}

/// Computes `sweep` in parallel chunks of `chunk_points` with `produce` and
/// hands the sink's bytes to `send`, in order; stops, returning `false`, as
/// soon as `send` returns `false` (the reader went away) or `stop()` is true
/// (checked by the workers before each chunk).
pub(super) fn drive<C, T, P, S>(
    sweep: &Sweep<C>,
    chunk_points: u64,
    produce: P,
    mut sink: S,
    stop: impl Fn() -> bool + Sync,
    mut send: impl FnMut(Vec<Bytes>) -> bool,
) -> bool
where
    C: SweepCase,
    T: Send,
    P: Fn(&Sweep<C>, Range<u64>) -> T + Sync,
    S: Sink<T>,
{
    if !send(vec![Bytes::from(sink.header())]) {
        return false;
    }
    let finished = sweep.run_parallel(
        chunk_points,
        |range| (!stop()).then(|| produce(sweep, range)),
        |chunk| chunk.is_some_and(|chunk| send(sink.encode(chunk))),
    );
    finished && send(vec![Bytes::from(sink.trailer())])
}

/// Streams a sweep through a bounded channel. The producer stops when the
/// client disconnects (the channel closes) or stops reading for `stall`; an
/// incomplete stream ends with an error so the client sees a broken body, not
/// a short one.
pub(super) fn stream<C, T, P, S>(
    sweep: Arc<Sweep<C>>,
    chunk_points: u64,
    produce: P,
    sink: S,
    stall: Duration,
    streams: &Streams,
    permit: OwnedSemaphorePermit,
) -> Body
where
    C: SweepCase + Send + 'static,
    T: Send + 'static,
    P: Fn(&Sweep<C>, Range<u64>) -> T + Send + Sync + 'static,
    S: Sink<T>,
{
    let (tx, rx) = mpsc::channel::<Vec<Bytes>>(QUEUED_CHUNKS);
    let complete = Arc::new(AtomicBool::new(false));
    let done = complete.clone();
    let runtime = tokio::runtime::Handle::current();
    let active = streams.start();
    tokio::task::spawn_blocking(move || {
        let (_active, _permit) = (active, permit);
        let send = |pieces: Vec<Bytes>| runtime.block_on(tx.send_timeout(pieces, stall)).is_ok();
        if drive(&sweep, chunk_points, produce, sink, || tx.is_closed(), send) {
            done.store(true, Ordering::Release);
        } else {
            tracing::info!("sweep stream stopped: the client went away or stopped reading");
        }
    });
    body_of(rx, complete)
}

/// A buffered answer (a JSON table, an SVG plot) sent as a stream is: in
/// chunks through the bounded channel, its permit and bytes held until the
/// client has them, or has read nothing for `stall` (then both are dropped
/// and the response ends with an error). Each chunk is a copy, so the
/// answer's memory goes with the sender, not with the queued chunks.
pub(super) fn buffered(bytes: Vec<u8>, stall: Duration, permit: OwnedSemaphorePermit) -> Body {
    const CHUNK: usize = 256 * 1024;
    let (tx, rx) = mpsc::channel::<Vec<Bytes>>(QUEUED_CHUNKS);
    let complete = Arc::new(AtomicBool::new(false));
    let done = complete.clone();
    tokio::spawn(async move {
        let _permit = permit;
        for chunk in bytes.chunks(CHUNK) {
            if tx
                .send_timeout(vec![Bytes::copy_from_slice(chunk)], stall)
                .await
                .is_err()
            {
                tracing::info!("buffered sweep dropped: the client went away or stopped reading");
                return;
            }
        }
        done.store(true, Ordering::Release);
    });
    body_of(rx, complete)
}

/// The response body of chunks from `rx`, each sent piece by piece: it
/// ends cleanly once `complete` is set, and with an error when the sender
/// stopped before its end.
fn body_of(rx: mpsc::Receiver<Vec<Bytes>>, complete: Arc<AtomicBool>) -> Body {
    use futures_util::StreamExt;
    let chunks = futures_util::stream::unfold((rx, complete), |(mut rx, complete)| async move {
        match rx.recv().await {
            Some(pieces) => Some((Ok::<_, std::io::Error>(pieces), (rx, complete))),
            None if complete.load(Ordering::Acquire) => None,
            None => {
                complete.store(true, Ordering::Release);
                Some((
                    Err(std::io::Error::other("sweep stopped before its end")),
                    (rx, complete),
                ))
            }
        }
    });
    let pieces = chunks.flat_map(|chunk| {
        let pieces: Vec<Result<Bytes, std::io::Error>> = match chunk {
            Ok(pieces) => pieces.into_iter().filter(|p| !p.is_empty()).map(Ok).collect(),
            Err(e) => vec![Err(e)],
        };
        futures_util::stream::iter(pieces)
    });
    Body::from_stream(pieces)
}
