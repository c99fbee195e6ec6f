//! The HTTP service: axum routes over the solver, problem+json errors, the
//! generated OpenAPI 3.1 document and the middleware stack.
//!
//! A request flows: socket → request id → access log → panic guard → load
//! shedding at the concurrency limit → timeout → body limit → router →
//! `ApiJson` extractor (DTO) → solver → response DTO.

#[macro_use]
pub mod accept;
mod auth;
pub mod collect;
pub mod commands;
pub mod config;
pub mod dto;
pub mod extract;
pub mod fits;
pub mod impacts;
mod layers;
pub mod log;
pub mod offline;
pub mod problem;
pub mod quantities;
pub mod sweeps;
pub mod telemetry;
pub mod web;
mod write_timeout;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use axum::extract::{DefaultBodyLimit, Request};
use axum::http::{HeaderName, HeaderValue, StatusCode};
use axum::middleware;
use axum::response::{IntoResponse, Response};
use axum::{Json, Router};
use serde::Serialize;
use tower::ServiceBuilder;
use tower_http::catch_panic::CatchPanicLayer;
use tower_http::request_id::{MakeRequestId, PropagateRequestIdLayer, RequestId, SetRequestIdLayer};
use tower_http::set_header::SetResponseHeaderLayer;
use utoipa::openapi::OpenApi as OpenApiDocument;
use utoipa::{OpenApi, ToSchema};
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;
use utoipa_swagger_ui::SwaggerUi;

pub use config::ServiceConfig;
use problem::ApiError;

/// The header that carries the request id.
pub const REQUEST_ID: &str = "x-request-id";

#[derive(OpenApi)]
#[openapi(
    info(
        title = "restitution",
        description = "Rigid-body point-collision outcomes (final velocities, impulses, energy loss) from \
                       coefficients of restitution and friction, after R. M. Brach, \"Restitution in Point \
                       Collisions\" (1991). Frame: n is the barrier's outward normal, t the tangent; the \
                       centre of mass sits at (d_c, d_d) from the contact point; ω turns n toward t. Any \
                       consistent unit system. Errors are RFC 9457 problem+json with a JSON `pointer`.",
    ),
    components(schemas(problem::Problem, problem::IntervalDto)),
    tags((name = "impacts", description = "One impact per request"), (name = "sweeps", description = "One case over a grid of inputs"), (name = "fits", description = "Coefficients identified from measured impacts"), (name = "service", description = "The service itself: liveness, readiness, metrics and the quantity table"))
)]
struct ApiDoc;

/// Declares the bearer token of a service run with `--api-key-file`: the
/// scheme, and a requirement on every operation but `/healthz` (the routes the
/// `require_api_key` middleware guards). Applied only to the document served
/// by such a service; without a key the document declares no security.
struct BearerRequired;

impl utoipa::Modify for BearerRequired {
    fn modify(&self, doc: &mut OpenApiDocument) {
        use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityRequirement, SecurityScheme};
        doc.components
            .get_or_insert_with(Default::default)
            .add_security_scheme(
                "bearer",
                SecurityScheme::Http(
                    HttpBuilder::new()
                        .scheme(HttpAuthScheme::Bearer)
                        .description(Some(
                            "The service's API key (from --api-key-file): `Authorization: Bearer <key>`",
                        ))
                        .build(),
                ),
            );
        for (path, item) in doc.paths.paths.iter_mut() {
            if OPEN_ROUTES.contains(&path.as_str()) {
                continue;
            }
            for operation in operations_mut(item) {
                operation.security = Some(vec![SecurityRequirement::new("bearer", Vec::<String>::new())]);
            }
        }
    }
}

/// The operations of a path item.
fn operations_mut(
    item: &mut utoipa::openapi::PathItem,
) -> impl Iterator<Item = &mut utoipa::openapi::path::Operation> {
    [
        &mut item.get,
        &mut item.put,
        &mut item.post,
        &mut item.delete,
        &mut item.options,
        &mut item.head,
        &mut item.patch,
        &mut item.trace,
        &mut item.query,
    ]
    .into_iter()
    .filter_map(Option::as_mut)
}

/// The liveness route.
const HEALTHZ: &str = "/healthz";
/// The routes open even when the service has an API key: the probes and the
/// metrics scrape (which carry no key).
const OPEN_ROUTES: [&str; 3] = [HEALTHZ, "/readyz", "/metrics"];

/// Liveness answer.
#[derive(Serialize, ToSchema)]
pub struct Health {
    /// Always `ok`.
    pub status: &'static str,
}

/// Liveness probe.
#[utoipa::path(get, path = "/healthz", tag = "service", responses((status = 200, description = "The service is up", body = Health)))]
async fn healthz() -> Json<Health> {
    Json(Health { status: "ok" })
}

/// The routes behind the middleware stack (load shedding included).
fn served_routes() -> OpenApiRouter<Shared> {
    OpenApiRouter::with_openapi(ApiDoc::openapi())
        .merge(impacts::router())
        .merge(sweeps::router())
        .merge(fits::router())
        .merge(quantities::router())
        .routes(routes!(telemetry::readyz))
}

/// Every route, for the document: the served ones, and the liveness probe and
/// metrics, which the application serves outside the stack so that a
/// saturated service still answers them (a shed liveness probe would have
/// the orchestrator restart the busiest replicas).
fn routes() -> OpenApiRouter<Shared> {
    served_routes()
        .routes(routes!(healthz))
        .routes(routes!(telemetry::metrics))
}

/// What the handlers share, as the router's state (a field of the state
/// costs nothing per request; a request extension is a map insert).
#[derive(Debug, Clone)]
struct Shared {
    config: Arc<ServiceConfig>,
    streams: sweeps::Streams,
    telemetry: telemetry::Telemetry,
}

impl axum::extract::FromRef<Shared> for Arc<ServiceConfig> {
    fn from_ref(shared: &Shared) -> Self {
        shared.config.clone()
    }
}

impl axum::extract::FromRef<Shared> for sweeps::Streams {
    fn from_ref(shared: &Shared) -> Self {
        shared.streams.clone()
    }
}

impl axum::extract::FromRef<Shared> for telemetry::Telemetry {
    fn from_ref(shared: &Shared) -> Self {
        shared.telemetry.clone()
    }
}

/// The OpenAPI 3.1 document generated from the code, for a service without
/// an API key (no security); [`openapi_for`] gives the one a service serves.
pub fn openapi() -> OpenApiDocument {
    let mut doc = routes().into_openapi();
    doc.info.version = env!("CARGO_PKG_VERSION").to_owned();
    doc.info.license = Some(utoipa::openapi::License::new(env!("CARGO_PKG_LICENSE")));
    doc
}

/// The OpenAPI document a service with `config` serves at `/openapi.json`:
/// with an API key, the bearer scheme is declared and required by every
/// operation but `/healthz`.
pub fn openapi_for(config: &ServiceConfig) -> OpenApiDocument {
    let mut doc = openapi();
    if config.api_key.is_some() {
        utoipa::Modify::modify(&BearerRequired, &mut doc);
    }
    doc
}

/// The OpenAPI document as pretty JSON with a final newline (the committed form).
pub fn openapi_json() -> String {
    let mut text = openapi().to_pretty_json().unwrap_or_default();
    text.push('\n');
    text
}

/// The application: routes, documentation and middleware, ready to serve.
pub fn app(config: &ServiceConfig) -> Router {
    app_with(config, AppState::default())
}

/// What one application shares across requests, for its handlers and for
/// whoever serves it.
#[derive(Debug, Clone, Default)]
pub struct AppState {
    /// Streamed sweeps still computing.
    pub streams: sweeps::Streams,
    /// Readiness and metrics.
    pub telemetry: telemetry::Telemetry,
}

/// The application with the given state (tests keep a handle on it).
pub fn app_with(config: &ServiceConfig, state: AppState) -> Router {
    let shared = Shared {
        config: Arc::new(config.clone()),
        streams: state
            .streams
            .limited(config.max_buffered_sweeps, config.max_streamed_sweeps),
        telemetry: state.telemetry.clone(),
    };
    let (router, _) = served_routes().split_for_parts();
    let router = router
        .with_state(shared)
        .merge(SwaggerUi::new("/docs").url("/openapi.json", openapi_for(config)))
        .merge(web::router());
    state.telemetry.set_recording(config.metrics);
    state.telemetry.set_shedding_window(config.shedding_window_ms);
    // The probes outside the stack.
    stack(router, config, Some(state.telemetry.clone()))
        .route(HEALTHZ, axum::routing::get(healthz))
        .route(
            "/metrics",
            axum::routing::get(telemetry::metrics).with_state(state.telemetry),
        )
}

/// Wraps `router` in the service's middleware and fallbacks (request ids,
/// access log, panic guard, load shedding, timeout, body limit, API key,
/// CORS). The load-test harness serves its baseline handler through this too;
/// its requests are logged, not counted in metrics.
pub fn with_middleware(router: Router, config: &ServiceConfig) -> Router {
    stack(router, config, None)
}

/// [`with_middleware`], the requests recorded in `telemetry` if given.
///
/// `Router::layer` wraps every route in what it is given, boxed, and each
/// request clones its route's box, every layer inside it: so the whole stack
/// is given in one call (one box, one clone per request), not layer by layer.
fn stack(router: Router, config: &ServiceConfig, telemetry: Option<telemetry::Telemetry>) -> Router {
    let router = router
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .layer(
            ServiceBuilder::new()
                .layer(SetRequestIdLayer::new(
                    HeaderName::from_static(REQUEST_ID),
                    SequentialId::default(),
                ))
                .layer(PropagateRequestIdLayer::new(HeaderName::from_static(REQUEST_ID)))
                .layer(SetResponseHeaderLayer::overriding(
                    axum::http::header::X_CONTENT_TYPE_OPTIONS,
                    HeaderValue::from_static("nosniff"),
                ))
                .layer(layers::ObserveLayer { telemetry })
                .layer(CatchPanicLayer::custom(panic_response))
                // One semaphore for every route: `Router::layer` applies the
                // stack to each route, and a plain concurrency limit would
                // give each route its own.
                .layer(layers::ShedLayer::new(config.concurrency_limit))
                .layer(layers::DeadlineLayer {
                    limit_ms: config.request_timeout_ms,
                })
                .layer(DefaultBodyLimit::max(config.body_limit)),
        );
    let router = match &config.api_key {
        Some(key) => router.layer(middleware::from_fn_with_state(key.clone(), auth::require_api_key)),
        None => router,
    };
    match cors(&config.cors_allow_origins) {
        Some(layer) => router.layer(layer),
        None => router,
    }
}

/// CORS for the allowed origins; `None` (CORS off) when there are none.
fn cors(origins: &[String]) -> Option<tower_http::cors::CorsLayer> {
    use axum::http::{Method, header};
    use tower_http::cors::{AllowOrigin, CorsLayer};
    let origins: Vec<HeaderValue> = origins
        .iter()
        .filter_map(|o| HeaderValue::from_str(o.trim()).ok())
        .collect();
    if origins.is_empty() {
        return None;
    }
    Some(
        CorsLayer::new()
            .allow_origin(AllowOrigin::list(origins))
            .allow_methods([Method::GET, Method::POST])
            .allow_headers([header::CONTENT_TYPE, header::ACCEPT, header::AUTHORIZATION])
            .expose_headers([
                axum::http::HeaderName::from_static(REQUEST_ID),
                axum::http::HeaderName::from_static("x-sweep-points"),
            ]),
    )
}

async fn not_found(request: Request) -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not-found",
        "Not found",
        format!("no route for {}", request.uri().path()),
    )
}

async fn method_not_allowed(request: Request) -> ApiError {
    ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method-not-allowed",
        "Method not allowed",
        format!("{} is not allowed on {}", request.method(), request.uri().path()),
    )
}

/// The message of a handler's panic, carried on its 500 answer to the access log.
#[derive(Clone)]
pub(crate) struct PanicMessage(pub(crate) String);

/// The 500 problem for a handler that panicked.
fn panic_response(panic: Box<dyn std::any::Any + Send + 'static>) -> Response {
    let message = if let Some(text) = panic.downcast_ref::<&str>() {
        (*text).to_owned()
    } else if let Some(text) = panic.downcast_ref::<String>() {
        text.clone()
    } else {
        "a non-text panic payload".to_owned()
    };
    let mut response = ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        "internal",
        "Internal error",
        "the request failed",
    )
    .into_response();
    response.extensions_mut().insert(PanicMessage(message));
    response
}

/// Request ids `<process start in hex>-<sequence>`: unique per process, cheap.
#[derive(Clone, Default)]
struct SequentialId {
    next: Arc<AtomicU64>,
}

impl MakeRequestId for SequentialId {
    fn make_request_id<B>(&mut self, _: &axum::http::Request<B>) -> Option<RequestId> {
        let n = self.next.fetch_add(1, Ordering::Relaxed);
        // Written into a per-thread block shared by the ids cut from it: no
        // formatting machinery and no allocation per id.
        let value = ID_BLOCK.with(|block| {
            let mut block = block.borrow_mut();
            if block.capacity() - block.len() < PROCESS_TAG.len() + 20 {
                *block = bytes::BytesMut::with_capacity(4096);
            }
            block.extend_from_slice(PROCESS_TAG.as_bytes());
            block.extend_from_slice(itoa::Buffer::new().format(n).as_bytes());
            block.split().freeze()
        });
        HeaderValue::from_maybe_shared(value).ok().map(RequestId::new)
    }
}

thread_local! {
    /// Where this thread writes request ids.
    static ID_BLOCK: std::cell::RefCell<bytes::BytesMut> = std::cell::RefCell::new(bytes::BytesMut::new());
}

/// `<process start in microseconds, hex>-`, the request ids' prefix.
static PROCESS_TAG: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    let start = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_micros() as u64)
        .unwrap_or(0);
    format!("{start:x}-")
});

/// Serves `app` on `listener` until SIGINT or SIGTERM, letting in-flight requests finish.
pub async fn serve(listener: tokio::net::TcpListener, config: &ServiceConfig) -> std::io::Result<()> {
    serve_until(listener, config, shutdown_signal()).await
}

/// Serves until `signal` completes. Connections must send complete request
/// headers within `header_read_timeout_ms`. On the signal the listener closes
/// (new connections are refused), idle keep-alive connections close, and
/// in-flight requests (streamed sweeps included) have `shutdown_grace_ms` to
/// finish before the remaining connections are dropped. A connection whose
/// first bytes the server has not read yet when the signal arrives counts as
/// idle and is closed (hyper-util's protocol detection is cancelled).
pub async fn serve_until(
    listener: tokio::net::TcpListener,
    config: &ServiceConfig,
    signal: impl std::future::Future<Output = ()>,
) -> std::io::Result<()> {
    serve_app_until(listener, config, AppState::default(), signal).await
}

/// Serves the application with `state` until `signal` completes, as
/// [`serve_until`]; on the signal, `/readyz` first answers 503 for
/// `shutdown_drain_ms` while everything else is still served (so a load
/// balancer stops sending before the listener closes).
pub async fn serve_app_until(
    listener: tokio::net::TcpListener,
    config: &ServiceConfig,
    state: AppState,
    signal: impl std::future::Future<Output = ()>,
) -> std::io::Result<()> {
    let telemetry = state.telemetry.clone();
    let drain = Duration::from_millis(config.shutdown_drain_ms);
    let signal = async move {
        signal.await;
        telemetry.start_draining();
        if !drain.is_zero() {
            tracing::info!(
                drain_ms = drain.as_millis() as u64,
                "draining: not ready, still serving"
            );
            tokio::time::sleep(drain).await;
        }
    };
    serve_router_until(listener, app_with(config, state), config, signal).await
}

/// Serves any router (already wrapped by [`with_middleware`]) the way the
/// service serves its own: see [`serve_until`].
pub async fn serve_router_until(
    listener: tokio::net::TcpListener,
    router: Router,
    config: &ServiceConfig,
    signal: impl std::future::Future<Output = ()>,
) -> std::io::Result<()> {
    use hyper_util::rt::{TokioExecutor, TokioIo};
    use hyper_util::server::conn::auto;
    use hyper_util::server::graceful::GracefulShutdown;
    use hyper_util::service::TowerToHyperService;

    // `with_state` turns the handlers into routes once, so that each route's
    // middleware (the concurrency limit's semaphore above all) is built once
    // and shared, not rebuilt per request.
    let router: Router = router.with_state(());
    let mut builder = auto::Builder::new(TokioExecutor::new());
    // hyper's own header-read timeout: a connection that is not answering a
    // request must send a complete request head within the timeout of its
    // start or of its last answer's end (HTTP/1; measured against a
    // hand-written per-connection watchdog in docs/performance-log.md: the
    // same within the spread of identical servers).
    builder
        .http1()
        .timer(hyper_util::rt::TokioTimer::new())
        .header_read_timeout(Duration::from_millis(config.header_read_timeout_ms));
    let write_timeout = Duration::from_millis(config.write_timeout_ms);
    let graceful = GracefulShutdown::new();
    tokio::pin!(signal);
    loop {
        tokio::select! {
            accepted = listener.accept() => {
                let stream = match accepted {
                    Ok((stream, _)) => stream,
                    Err(error) => {
                        // Out of file descriptors and the like: wait, do not die.
                        tracing::warn!(%error, "accept failed");
                        tokio::time::sleep(Duration::from_millis(20)).await;
                        continue;
                    }
                };
                let _ = stream.set_nodelay(true);
                let service = TowerToHyperService::new(router.clone());
                let stream = write_timeout::WriteTimeout::new(stream, write_timeout);
                let connection = builder.serve_connection_with_upgrades(TokioIo::new(stream), service);
                let connection = graceful.watch(connection.into_owned());
                tokio::spawn(async move {
                    if let Err(error) = connection.await {
                        tracing::debug!(%error, "connection ended with an error");
                    }
                });
            }
            () = &mut signal => break,
        }
    }
    drop(listener);
    let grace = Duration::from_millis(config.shutdown_grace_ms);
    match tokio::time::timeout(grace, graceful.shutdown()).await {
        Ok(()) => tracing::info!("every connection closed; exiting"),
        Err(_) => tracing::warn!(
            grace_ms = config.shutdown_grace_ms,
            "grace period over; dropping the remaining connections"
        ),
    }
    Ok(())
}

/// Resolves on SIGINT or SIGTERM. The handlers are installed when this is
/// called (not when the future is first polled), so a signal that arrives
/// while the application is still being built is not the default
/// terminate-at-once. Call it within the runtime.
pub fn shutdown_signal() -> impl std::future::Future<Output = ()> {
    #[cfg(unix)]
    let (mut terminate, mut interrupt) = {
        use tokio::signal::unix::{SignalKind, signal};
        (
            signal(SignalKind::terminate()).ok(),
            signal(SignalKind::interrupt()).ok(),
        )
    };
    async move {
        #[cfg(unix)]
        {
            let terminate = async {
                match &mut terminate {
                    Some(s) => {
                        s.recv().await;
                    }
                    None => std::future::pending::<()>().await,
                }
            };
            let interrupt = async {
                match &mut interrupt {
                    Some(s) => {
                        s.recv().await;
                    }
                    None => std::future::pending::<()>().await,
                }
            };
            tokio::select! {
                () = terminate => {},
                () = interrupt => {},
            }
        }
        #[cfg(not(unix))]
        {
            let _ = tokio::signal::ctrl_c().await;
        }
        tracing::info!("shutdown signal received; finishing in-flight requests");
    }
}
