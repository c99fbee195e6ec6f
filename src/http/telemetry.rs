//! Readiness and metrics: `GET /readyz` (not ready while draining for
//! shutdown or shedding load) and `GET /metrics` (Prometheus text format:
//! requests by route and status, latency histograms by route, requests in
//! flight, shed requests, sweep points by case and precision, and the impacts
//! each stage of the exact evaluation settled).
//!
//! Recording is a few atomic operations per request in the metrics
//! middleware (label sets are looked up under a read lock); the text is
//! formatted only when scraped.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use axum::Json;
use axum::extract::{MatchedPath, Request, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use prometheus_client::encoding::EncodeLabelSet;
use prometheus_client::metrics::counter::Counter;
use prometheus_client::metrics::family::Family;
use prometheus_client::metrics::gauge::Gauge;
use prometheus_client::metrics::histogram::{Histogram, exponential_buckets};
use prometheus_client::registry::Registry;
use serde::Serialize;
use utoipa::ToSchema;

/// A request's route (its matched path, or `unmatched`), method and status.
/// The route shares the router's own path and `Method` the request's: looking
/// a series up allocates nothing.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct RequestLabels {
    route: Route,
    method: MethodLabel,
    status: u16,
}

/// A route.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct RouteLabels {
    route: Route,
}

/// A route label: the matched path (axum's `MatchedPath`, a shared string
/// of the router's), or `unmatched` for a request no route took.
#[derive(Debug, Clone)]
enum Route {
    Matched(MatchedPath),
    Unmatched,
}

impl Route {
    fn as_str(&self) -> &str {
        match self {
            Route::Matched(path) => path.as_str(),
            Route::Unmatched => "unmatched",
        }
    }
}

impl PartialEq for Route {
    fn eq(&self, other: &Route) -> bool {
        self.as_str() == other.as_str()
    }
}

impl Eq for Route {}

impl std::hash::Hash for Route {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.as_str().hash(state);
    }
}

impl prometheus_client::encoding::EncodeLabelValue for Route {
    fn encode(
        &self,
        encoder: &mut prometheus_client::encoding::LabelValueEncoder<'_>,
    ) -> Result<(), std::fmt::Error> {
        std::fmt::Write::write_str(encoder, self.as_str())
    }
}

/// A method label.
#[derive(Debug, Clone, Hash, PartialEq, Eq)]
struct MethodLabel(axum::http::Method);

impl prometheus_client::encoding::EncodeLabelValue for MethodLabel {
    fn encode(
        &self,
        encoder: &mut prometheus_client::encoding::LabelValueEncoder<'_>,
    ) -> Result<(), std::fmt::Error> {
        std::fmt::Write::write_str(encoder, self.0.as_str())
    }
}

/// A sweep's case and precision.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct SweepLabels {
    case: String,
    precision: String,
}

/// An exact-evaluation stage.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct StageLabels {
    stage: String,
}

/// Why a `fast` answer went to the exact evaluation.
#[derive(Debug, Clone, Hash, PartialEq, Eq, EncodeLabelSet)]
struct ReasonLabels {
    reason: String,
}

/// Marks a load-shedding answer for the metrics middleware.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shed;

/// The service's readiness state and metrics, shared by its handlers,
/// middleware and serve loop.
#[derive(Debug, Clone)]
pub struct Telemetry(Arc<Inner>);

#[derive(Debug)]
struct Inner {
    registry: Registry,
    requests: Family<RequestLabels, Counter>,
    latency: Family<RouteLabels, Histogram>,
    in_flight: Gauge,
    shed: Counter,
    sweep_points: Family<SweepLabels, Counter>,
    started: Instant,
    /// Milliseconds since `started` of the last shed request (0: none).
    last_shed_ms: AtomicU64,
    /// How long after a shed request the service reports not ready, in milliseconds.
    shedding_window_ms: AtomicU64,
    draining: AtomicBool,
    /// Whether requests are recorded (`--metrics`).
    recording: AtomicBool,
}

/// How long after a shed request `/readyz` answers 503 unless configured
/// (`--shedding-window-ms`), in milliseconds.
pub const DEFAULT_SHEDDING_WINDOW_MS: u64 = 1_000;

impl Default for Telemetry {
    fn default() -> Self {
        let mut registry = Registry::with_prefix("restitution");
        let requests = Family::<RequestLabels, Counter>::default();
        let latency = Family::<RouteLabels, Histogram>::new_with_constructor(|| {
            // 10 µs to about 42 s.
            Histogram::new(exponential_buckets(1e-5, 4.0, 12))
        });
        let in_flight = Gauge::default();
        let shed = Counter::default();
        let sweep_points = Family::<SweepLabels, Counter>::default();
        registry.register(
            "http_requests",
            "HTTP requests answered, by route, method and status",
            requests.clone(),
        );
        registry.register(
            "http_request_duration_seconds",
            "Time to the response head (streamed bodies continue after), by route",
            latency.clone(),
        );
        registry.register(
            "http_requests_in_flight",
            "Requests being answered",
            in_flight.clone(),
        );
        registry.register(
            "http_requests_shed",
            "Requests refused at the concurrency limit (503)",
            shed.clone(),
        );
        registry.register(
            "sweep_points",
            "Sweep points computed (rows streamed or reduced, or tabulated), by case and precision",
            sweep_points.clone(),
        );
        Telemetry(Arc::new(Inner {
            registry,
            requests,
            latency,
            in_flight,
            shed,
            sweep_points,
            started: Instant::now(),
            last_shed_ms: AtomicU64::new(0),
            shedding_window_ms: AtomicU64::new(DEFAULT_SHEDDING_WINDOW_MS),
            draining: AtomicBool::new(false),
            recording: AtomicBool::new(true),
        }))
    }
}

impl Telemetry {
    /// Turns the per-request recording on or off.
    pub fn set_recording(&self, on: bool) {
        self.0.recording.store(on, Ordering::Relaxed);
    }

    /// Sets how long after a shed request `/readyz` answers 503, in milliseconds.
    pub fn set_shedding_window(&self, ms: u64) {
        self.0.shedding_window_ms.store(ms, Ordering::Relaxed);
    }

    /// Marks the service as draining: `/readyz` answers 503 from now on.
    pub fn start_draining(&self) {
        self.0.draining.store(true, Ordering::Release);
    }

    /// Counts `points` computed points of a sweep.
    pub fn sweep_points(&self, case: &str, precision: &str, points: u64) {
        self.0
            .sweep_points
            .get_or_create(&SweepLabels {
                case: case.to_owned(),
                precision: precision.to_owned(),
            })
            .inc_by(points);
    }

    /// A counter of sweep points for one case and precision, to bump from the workers.
    pub fn sweep_counter(&self, case: &str, precision: &str) -> Counter {
        self.0
            .sweep_points
            .get_or_create(&SweepLabels {
                case: case.to_owned(),
                precision: precision.to_owned(),
            })
            .clone()
    }

    /// Why the service is not ready, if it is not.
    fn not_ready(&self) -> Option<&'static str> {
        if self.0.draining.load(Ordering::Acquire) {
            return Some("draining");
        }
        let last = self.0.last_shed_ms.load(Ordering::Relaxed);
        let now = self.0.started.elapsed().as_millis() as u64;
        let window = self.0.shedding_window_ms.load(Ordering::Relaxed);
        (last > 0 && now.saturating_sub(last) < window).then_some("shedding")
    }

    /// The metrics in the Prometheus text format.
    pub fn encode(&self) -> String {
        let mut text = String::new();
        let mut stages = Registry::with_prefix("restitution");
        let settled = Family::<StageLabels, Counter>::default();
        for (stage, count) in crate::impact::settled_by_stage() {
            let name = match stage {
                crate::impact::Stage::Compensated => "compensated",
                crate::impact::Stage::DoubleDouble => "double_double",
                crate::impact::Stage::Rational => "exact",
                crate::impact::Stage::Fast => "fast",
            };
            settled
                .get_or_create(&StageLabels {
                    stage: name.to_owned(),
                })
                .inc_by(count);
        }
        stages.register(
            "exact_settled",
            "Impacts settled by each stage of the adaptive exact evaluation, since start",
            settled,
        );
        let escalated = Family::<ReasonLabels, Counter>::default();
        for (reason, count) in [
            ("decision", crate::impact::fast_decisions_escalated()),
            ("accuracy", crate::impact::fast_outputs_escalated()),
        ] {
            escalated
                .get_or_create(&ReasonLabels {
                    reason: reason.to_owned(),
                })
                .inc_by(count);
        }
        stages.register(
            "fast_escalated",
            "Fast answers sent to the exact evaluation since start, by reason: a decision too close to its tie, or an output whose f64 error bound exceeded the promised error (2^-32 of the larger of its magnitude and its scale)",
            escalated,
        );
        let _ = prometheus_client::encoding::text::encode_registry(&mut text, &self.0.registry);
        let _ = prometheus_client::encoding::text::encode_registry(&mut text, &stages);
        let _ = prometheus_client::encoding::text::encode_eof(&mut text);
        text
    }
}

/// One request being recorded: counted in flight until finished or dropped
/// (a client that goes away), then its count, latency and (for a shed one)
/// the shedding time.
pub(crate) struct Recording {
    telemetry: Telemetry,
    route: Route,
    method: MethodLabel,
}

impl Recording {
    /// Starts recording `request` for `telemetry`; `None` with the recording
    /// off.
    pub(crate) fn start(telemetry: &Telemetry, request: &Request) -> Option<Recording> {
        if !telemetry.0.recording.load(Ordering::Relaxed) {
            return None;
        }
        let route = match request.extensions().get::<MatchedPath>() {
            Some(path) => Route::Matched(path.clone()),
            None => Route::Unmatched,
        };
        telemetry.0.in_flight.inc();
        Some(Recording {
            telemetry: telemetry.clone(),
            route,
            method: MethodLabel(request.method().clone()),
        })
    }

    /// Records the answer, given `elapsed` since the request came in.
    pub(crate) fn finish<B>(self, response: &axum::http::Response<B>, elapsed: Duration) {
        let inner = &self.telemetry.0;
        if response.extensions().get::<Shed>().is_some() {
            inner.shed.inc();
            let now = (inner.started.elapsed().as_millis() as u64).max(1);
            inner.last_shed_ms.store(now, Ordering::Relaxed);
        }
        inner
            .latency
            .get_or_create(&RouteLabels {
                route: self.route.clone(),
            })
            .observe(elapsed.as_secs_f64());
        inner
            .requests
            .get_or_create(&RequestLabels {
                route: self.route.clone(),
                method: self.method.clone(),
                status: response.status().as_u16(),
            })
            .inc();
    }
}

impl Drop for Recording {
    fn drop(&mut self) {
        self.telemetry.0.in_flight.dec();
    }
}

/// Readiness answer.
#[derive(Debug, Serialize, ToSchema)]
pub struct Readiness {
    /// `ready`, `draining` (shutting down) or `shedding` (at the concurrency limit).
    pub status: &'static str,
}

/// Readiness probe: 503 while the service drains for shutdown or sheds load.
#[utoipa::path(get, path = "/readyz", tag = "service", responses(
    (status = 200, description = "Ready for traffic", body = Readiness),
    (status = 503, description = "Draining for shutdown, or shedding load", body = Readiness),
))]
pub(crate) async fn readyz(State(telemetry): State<Telemetry>) -> Response {
    match telemetry.not_ready() {
        None => Json(Readiness { status: "ready" }).into_response(),
        Some(status) => (StatusCode::SERVICE_UNAVAILABLE, Json(Readiness { status })).into_response(),
    }
}

/// Metrics in the Prometheus text exposition format.
#[utoipa::path(get, path = "/metrics", tag = "service", responses(
    (status = 200, description = "Prometheus text format", body = String, content_type = "text/plain; version=0.0.4"),
))]
pub(crate) async fn metrics(State(telemetry): State<Telemetry>) -> Response {
    let text = telemetry.encode();
    (
        [(header::CONTENT_TYPE, "text/plain; version=0.0.4; charset=utf-8")],
        text,
    )
        .into_response()
}
