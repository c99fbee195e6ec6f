//! Streaming a sweep: rows computed in parallel chunks on a blocking thread
//! and handed to the response body in order through a bounded channel, so a
//! streamed sweep holds a few chunks in memory whatever its size, and stops
//! when the client goes away or stops reading.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use axum::body::{Body, Bytes};
use tokio::sync::mpsc;

use super::encode::{RowWriter, chunk};
use crate::sweep::{Sweep, SweepCase};

/// Chunks queued between the workers and the socket.
const QUEUED_CHUNKS: usize = 4;

/// How many streamed sweeps of one application are still computing (part of
/// the application's state; for tests and diagnostics).
#[derive(Debug, Clone, Default)]
pub struct Streams(Arc<AtomicUsize>);

impl Streams {
    /// The number of streamed sweeps whose producer is still working.
    pub fn active(&self) -> usize {
        self.0.load(Ordering::Acquire)
    }

    fn start(&self) -> ActiveStream {
        self.0.fetch_add(1, Ordering::AcqRel);
        ActiveStream(self.0.clone())
    }
}

/// Counts a producer as active while it lives.
struct ActiveStream(Arc<AtomicUsize>);

impl Drop for ActiveStream {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

/// Streams the rows through a bounded channel. The producer stops when the
/// client disconnects (the channel closes) or stops reading for `stall`; an
/// incomplete stream ends with an error so the client sees a broken body, not
/// a short one.
pub(super) fn stream<C>(sweep: Arc<Sweep<C>>, writer: RowWriter, stall: Duration, streams: &Streams) -> Body
where
    C: SweepCase + Send + 'static,
{
    let (tx, rx) = mpsc::channel::<Bytes>(QUEUED_CHUNKS);
    let complete = Arc::new(AtomicBool::new(false));
    let done = complete.clone();
    let runtime = tokio::runtime::Handle::current();
    let active = streams.start();
    tokio::task::spawn_blocking(move || {
        let _active = active;
        let send = |bytes: Vec<u8>| {
            runtime
                .block_on(tx.send_timeout(Bytes::from(bytes), stall))
                .is_ok()
        };
        if !send(writer.header()) {
            return;
        }
        let finished = sweep.run_parallel(
            writer.chunk_points(),
            |range| {
                if tx.is_closed() {
                    return Vec::new();
                }
                chunk(&sweep, &writer, range).0
            },
            &send,
        );
        if finished {
            done.store(true, Ordering::Release);
        } else {
            tracing::info!("sweep stream stopped: the client went away or stopped reading");
        }
    });
    let stream = futures_util::stream::unfold((rx, complete), |(mut rx, complete)| async move {
        match rx.recv().await {
            Some(bytes) => Some((Ok::<_, std::io::Error>(bytes), (rx, complete))),
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
    Body::from_stream(stream)
}
