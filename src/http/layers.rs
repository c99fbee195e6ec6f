//! The service's own middleware as plain `tower` services: each request
//! passes them without a boxed future or a clone of the stack below (which
//! `axum::middleware::from_fn` and `HandleErrorLayer` cost per request).
//!
//! - [`ObserveLayer`]: the access log line and the request metrics.
//! - [`ShedLayer`]: at most `limit` requests at once across every route; one
//!   more is answered 503 at once (load shedding).
//! - [`DeadlineLayer`]: a request not answered within the limit is answered
//!   408; the timer is armed only if the answer is not ready at once.

use std::future::Future;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll, ready};
use std::time::Instant;

use axum::extract::Request;
use axum::http::{HeaderValue, Method, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use tower::{Layer, Service};
use tower_http::request_id::RequestId;
use tracing::Level;

use super::log;
use super::problem::ApiError;
use super::telemetry::{self, Recording, Telemetry};

/// Logs each request (one line, at its status's level) and records its
/// metrics in `telemetry` (none: not recorded, as for the load test's
/// baseline).
#[derive(Debug, Clone, Default)]
pub(crate) struct ObserveLayer {
    pub(crate) telemetry: Option<Telemetry>,
}

impl<S> Layer<S> for ObserveLayer {
    type Service = Observe<S>;

    fn layer(&self, inner: S) -> Observe<S> {
        Observe {
            inner,
            telemetry: self.telemetry.clone(),
        }
    }
}

/// See [`ObserveLayer`].
#[derive(Debug, Clone)]
pub(crate) struct Observe<S> {
    inner: S,
    telemetry: Option<Telemetry>,
}

/// What the access line needs of the request: clones that share its buffers
/// (no allocation per request).
struct Seen {
    request_id: Option<HeaderValue>,
    method: Method,
    uri: Uri,
}

impl<S, B> Service<Request> for Observe<S>
where
    S: Service<Request, Response = axum::http::Response<B>>,
{
    type Response = axum::http::Response<B>;
    type Error = S::Error;
    type Future = ObserveFuture<S::Future>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, request: Request) -> Self::Future {
        let seen = Seen {
            request_id: request
                .extensions()
                .get::<RequestId>()
                .map(|id| id.header_value().clone()),
            method: request.method().clone(),
            uri: request.uri().clone(),
        };
        let recording = self
            .telemetry
            .as_ref()
            .and_then(|t| Recording::start(t, &request));
        let start = Instant::now();
        ObserveFuture {
            inner: self.inner.call(request),
            start,
            seen: Some(seen),
            recording,
        }
    }
}

pin_project_lite::pin_project! {
    /// The answer of an [`Observe`]d request.
    pub(crate) struct ObserveFuture<F> {
        #[pin]
        inner: F,
        start: Instant,
        seen: Option<Seen>,
        // Counts the request in flight until answered or dropped.
        recording: Option<Recording>,
    }
}

impl<F, B, E> Future for ObserveFuture<F>
where
    F: Future<Output = Result<axum::http::Response<B>, E>>,
{
    type Output = Result<axum::http::Response<B>, E>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let this = self.project();
        let result = ready!(this.inner.poll(cx));
        let elapsed = this.start.elapsed();
        if let Ok(response) = &result {
            if let Some(recording) = this.recording.take() {
                recording.finish(response, elapsed);
            }
            if let Some(seen) = this.seen.take() {
                access_line(seen, response, elapsed.as_micros() as u64);
            }
        }
        Poll::Ready(result)
    }
}

/// The request's access-log line. A server-side failure is logged at error
/// level (warn for load shedding, which the client is told to retry), with
/// the panic message if any; the request id ties it to the answer the
/// client saw.
fn access_line<B>(seen: Seen, response: &axum::http::Response<B>, latency_us: u64) {
    let status = response.status();
    let level = if status == StatusCode::SERVICE_UNAVAILABLE {
        Level::WARN
    } else if status.is_server_error() {
        Level::ERROR
    } else {
        Level::INFO
    };
    if !log::access_enabled(level) {
        return;
    }
    let panic = (level == Level::ERROR).then(|| {
        response
            .extensions()
            .get::<super::PanicMessage>()
            .map_or("", |p| p.0.as_str())
    });
    let request_id = seen.request_id.as_ref().and_then(|v| v.to_str().ok());
    log::access(
        level,
        request_id.unwrap_or("-"),
        &seen.method,
        seen.uri.path(),
        status.as_u16(),
        latency_us,
        panic,
    );
}

/// At most `limit` requests answered at once (one semaphore for every route
/// the layer wraps: `Router::layer` applies a layer to each route, and the
/// clones share it); one more is refused at once with 503 and `Retry-After`.
#[derive(Debug, Clone)]
pub(crate) struct ShedLayer {
    permits: Arc<tokio::sync::Semaphore>,
}

impl ShedLayer {
    pub(crate) fn new(limit: usize) -> Self {
        ShedLayer {
            permits: Arc::new(tokio::sync::Semaphore::new(
                limit.min(tokio::sync::Semaphore::MAX_PERMITS),
            )),
        }
    }
}

impl<S> Layer<S> for ShedLayer {
    type Service = Shed<S>;

    fn layer(&self, inner: S) -> Shed<S> {
        Shed {
            inner,
            permits: self.permits.clone(),
        }
    }
}

/// See [`ShedLayer`].
#[derive(Debug, Clone)]
pub(crate) struct Shed<S> {
    inner: S,
    permits: Arc<tokio::sync::Semaphore>,
}

impl<S> Service<Request> for Shed<S>
where
    S: Service<Request, Response = Response>,
{
    type Response = Response;
    type Error = S::Error;
    type Future = ShedFuture<S::Future>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, request: Request) -> Self::Future {
        match self.permits.clone().try_acquire_owned() {
            Ok(permit) => ShedFuture::Admitted {
                inner: self.inner.call(request),
                permit: Some(permit),
            },
            Err(_) => ShedFuture::Refused {
                response: Some(overloaded()),
            },
        }
    }
}

pin_project_lite::pin_project! {
    /// The answer of a [`Shed`] service.
    #[project = ShedProjection]
    pub(crate) enum ShedFuture<F> {
        /// Answered by the inner service, holding a permit until then.
        Admitted {
            #[pin]
            inner: F,
            permit: Option<tokio::sync::OwnedSemaphorePermit>,
        },
        /// Refused at the limit.
        Refused { response: Option<Response> },
    }
}

impl<F, E> Future for ShedFuture<F>
where
    F: Future<Output = Result<Response, E>>,
{
    type Output = Result<Response, E>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        match self.project() {
            ShedProjection::Admitted { inner, permit } => {
                let result = ready!(inner.poll(cx));
                // The slot is free once the head is answered (a streamed body
                // continues without it).
                drop(permit.take());
                Poll::Ready(result)
            }
            ShedProjection::Refused { response } => {
                Poll::Ready(Ok(response.take().unwrap_or_else(overloaded)))
            }
        }
    }
}

/// The load-shedding answer: 503, retry in a second.
fn overloaded() -> Response {
    let mut response = ApiError::new(
        StatusCode::SERVICE_UNAVAILABLE,
        "overloaded",
        "Service overloaded",
        "the server is at its concurrency limit; retry shortly",
    )
    .retry_after(1)
    .into_response();
    response.extensions_mut().insert(telemetry::Shed);
    response
}

/// A request not answered within `limit_ms` milliseconds is answered 408.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DeadlineLayer {
    pub(crate) limit_ms: u64,
}

impl<S> Layer<S> for DeadlineLayer {
    type Service = Deadline<S>;

    fn layer(&self, inner: S) -> Deadline<S> {
        Deadline {
            inner,
            limit_ms: self.limit_ms,
        }
    }
}

/// See [`DeadlineLayer`].
#[derive(Debug, Clone)]
pub(crate) struct Deadline<S> {
    inner: S,
    limit_ms: u64,
}

impl<S> Service<Request> for Deadline<S>
where
    S: Service<Request, Response = Response>,
{
    type Response = Response;
    type Error = S::Error;
    type Future = DeadlineFuture<S::Future>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, request: Request) -> Self::Future {
        DeadlineFuture {
            deadline: tokio::time::Instant::now() + std::time::Duration::from_millis(self.limit_ms),
            inner: self.inner.call(request),
            timer: None,
            limit_ms: self.limit_ms,
        }
    }
}

pin_project_lite::pin_project! {
    /// The answer of a [`Deadline`] service.
    pub(crate) struct DeadlineFuture<F> {
        #[pin]
        inner: F,
        // Armed at the first poll that finds the answer not ready: an answer
        // ready at once (most of them) never touches the timer wheel.
        #[pin]
        timer: Option<tokio::time::Sleep>,
        deadline: tokio::time::Instant,
        limit_ms: u64,
    }
}

impl<F, E> Future for DeadlineFuture<F>
where
    F: Future<Output = Result<Response, E>>,
{
    type Output = Result<Response, E>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let mut this = self.project();
        if let Poll::Ready(result) = this.inner.poll(cx) {
            return Poll::Ready(result);
        }
        if this.timer.is_none() {
            this.timer.set(Some(tokio::time::sleep_until(*this.deadline)));
        }
        match this.timer.as_pin_mut() {
            Some(timer) => {
                ready!(timer.poll(cx));
                Poll::Ready(Ok(ApiError::new(
                    StatusCode::REQUEST_TIMEOUT,
                    "timeout",
                    "Request timeout",
                    format!("the request did not complete within {} ms", this.limit_ms),
                )
                .into_response()))
            }
            None => Poll::Pending,
        }
    }
}
