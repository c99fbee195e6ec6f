//! The header-read timeout as one watchdog per connection: a connection that
//! is not answering a request must send a complete request head within the
//! timeout of its start or of the end of its last answer, or it is closed
//! (slow or stalled headers, idle keep-alive connections).
//!
//! hyper's own `header_read_timeout` does the same with a timer armed for
//! every request head (a boxed `Sleep`, registered with the timer wheel while
//! the head is awaited, dropped when it is read): on a busy keep-alive
//! connection that is a timer per request. Here a request costs two counter
//! updates and a clock read; the connection's one timer fires at most once
//! per timeout and is re-armed from what the counters say. Measured side by
//! side against hyper's `header_read_timeout`, that saving did not show:
//! with hyper's timer the service served 1.00 and 1.03 times the requests
//! per second of the same build without it, at the same CPU per request,
//! within the spread of two identical servers (docs/performance-log.md,
//! 2026-11-27, "hand-written against the crates";
//! `benches/scripts/hand-vs-crates`).
//!
//! An HTTP/2 connection is left alone once its first request is seen (hyper
//! applies its header timeout to HTTP/1 only).

use std::future::Future;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::task::{Context, Poll, ready};
use std::time::Duration;

use axum::http::{Request, Response, Version};
use hyper::body::{Body, Frame, SizeHint};
use tokio::time::Instant;
use tower::Service;

/// What the watchdog of one connection reads: requests begun and ended, and
/// when the last one ended.
#[derive(Debug)]
pub(crate) struct Watch {
    /// When the connection was accepted: the origin of `idle_since_us`.
    origin: Instant,
    /// Requests whose head was read.
    begun: AtomicU64,
    /// Requests whose answer ended (the body sent or dropped).
    ended: AtomicU64,
    /// Microseconds from `origin` to the end of the last answer.
    idle_since_us: AtomicU64,
    /// An HTTP/2 request was seen: no header timeout.
    http2: AtomicBool,
}

impl Watch {
    pub(crate) fn new() -> Arc<Watch> {
        Arc::new(Watch {
            origin: Instant::now(),
            begun: AtomicU64::new(0),
            ended: AtomicU64::new(0),
            idle_since_us: AtomicU64::new(0),
            http2: AtomicBool::new(false),
        })
    }

    fn begin(&self, version: Version) {
        if version == Version::HTTP_2 {
            self.http2.store(true, Ordering::Relaxed);
        }
        self.begun.fetch_add(1, Ordering::Relaxed);
    }

    fn end(&self) {
        let since = self.origin.elapsed().as_micros() as u64;
        self.idle_since_us.store(since, Ordering::Relaxed);
        self.ended.fetch_add(1, Ordering::Release);
    }

    /// When to look again, at `now`; `None`: the connection waited longer
    /// than `timeout` for a request head, close it.
    fn next_check(&self, now: Instant, timeout: Duration) -> Option<Instant> {
        let ended = self.ended.load(Ordering::Acquire);
        if self.http2.load(Ordering::Relaxed) || self.begun.load(Ordering::Relaxed) != ended {
            // Answering: the request timeout governs it, not this one.
            return Some(now + timeout);
        }
        let idle_since = self.origin + Duration::from_micros(self.idle_since_us.load(Ordering::Relaxed));
        let deadline = idle_since + timeout;
        (deadline > now).then_some(deadline)
    }
}

/// Runs `connection` until it ends, or until it waits longer than `timeout`
/// for a request head (then it is dropped, which closes it): its output, or
/// `None` if it was cut off.
pub(crate) async fn watch<C: Future>(
    connection: C,
    watch: Arc<Watch>,
    timeout: Duration,
) -> Option<C::Output> {
    let mut connection = std::pin::pin!(connection);
    let timer = tokio::time::sleep_until(watch.origin + timeout);
    let mut timer = std::pin::pin!(timer);
    std::future::poll_fn(|cx| {
        if let Poll::Ready(output) = connection.as_mut().poll(cx) {
            return Poll::Ready(Some(output));
        }
        while timer.as_mut().poll(cx).is_ready() {
            match watch.next_check(Instant::now(), timeout) {
                Some(next) => timer.as_mut().reset(next),
                None => return Poll::Ready(None),
            }
        }
        Poll::Pending
    })
    .await
}

/// A service whose requests are counted for the connection's [`Watch`].
#[derive(Debug, Clone)]
pub(crate) struct Watched<S> {
    pub(crate) inner: S,
    pub(crate) watch: Arc<Watch>,
}

impl<S, B, ReqBody> Service<Request<ReqBody>> for Watched<S>
where
    S: Service<Request<ReqBody>, Response = Response<B>>,
{
    type Response = Response<WatchedBody<B>>;
    type Error = S::Error;
    type Future = WatchedFuture<S::Future>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, request: Request<ReqBody>) -> Self::Future {
        self.watch.begin(request.version());
        WatchedFuture {
            guard: Some(Guard(self.watch.clone())),
            inner: self.inner.call(request),
        }
    }
}

/// Ends its request for the watchdog when dropped.
#[derive(Debug)]
struct Guard(Arc<Watch>);

impl Drop for Guard {
    fn drop(&mut self) {
        self.0.end();
    }
}

pin_project_lite::pin_project! {
    /// The answer of a [`Watched`] service: its body carries the request's
    /// guard to its end.
    pub(crate) struct WatchedFuture<F> {
        #[pin]
        inner: F,
        guard: Option<Guard>,
    }
}

impl<F, B, E> Future for WatchedFuture<F>
where
    F: Future<Output = Result<Response<B>, E>>,
{
    type Output = Result<Response<WatchedBody<B>>, E>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let this = self.project();
        let result = ready!(this.inner.poll(cx));
        let guard = this.guard.take();
        Poll::Ready(result.map(|response| response.map(|inner| WatchedBody { inner, _guard: guard })))
    }
}

pin_project_lite::pin_project! {
    /// A response body that ends its request for the watchdog when dropped
    /// (hyper drops it once sent, or when the connection goes).
    pub(crate) struct WatchedBody<B> {
        #[pin]
        inner: B,
        _guard: Option<Guard>,
    }
}

impl<B: Body> Body for WatchedBody<B> {
    type Data = B::Data;
    type Error = B::Error;

    fn poll_frame(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<B::Data>, B::Error>>> {
        self.project().inner.poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> SizeHint {
        self.inner.size_hint()
    }
}
