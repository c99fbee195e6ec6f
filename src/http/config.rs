//! Command line and environment configuration (clap).

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;

use clap::{Args, Parser, Subcommand};

/// restitution: rigid-body impact outcomes over HTTP.
#[derive(Debug, Parser)]
#[command(name = "restitution", version, about, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// What to do (default: serve).
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Service settings when no subcommand is given.
    #[command(flatten)]
    pub serve: ServiceConfig,
    /// Which compiled copy of the solver's hot code runs: `auto` (the
    /// x86-64-v3 copy where the CPU has AVX2 and FMA, else the portable one)
    /// or `portable` (the same answers, slower).
    #[arg(long, global = true, env = "RESTITUTION_KERNELS", default_value = "auto",
          value_parser = ["auto", "portable"])]
    pub kernels: String,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the HTTP service (the default).
    Serve(ServiceConfig),
    /// Print the OpenAPI 3.1 document.
    Openapi,
    /// Print which compiled copy of the hot code runs: `x86-64-v3` or
    /// `portable` (what `--kernels` selects on this CPU, in this build).
    Kernels,
    /// Exit 0 when the service at ADDR answers `GET /healthz` with 200 (for container health checks).
    Healthcheck {
        /// Address of the service.
        #[arg(long, env = "RESTITUTION_HEALTHCHECK_ADDR", default_value = "127.0.0.1:8080")]
        addr: SocketAddr,
    },
    /// Answer impact requests from standard input without a server: one JSON
    /// request per line (or one document), one answer or problem+json per line
    /// on standard output; exits 1 when any request was refused.
    Solve {
        /// The case: normal, oblique, tangential, torsional, planar or spatial.
        #[arg(value_parser = ["normal", "oblique", "tangential", "torsional", "planar", "spatial"])]
        case: String,
    },
    /// Compute a sweep (or one shard of it) without a server, as `POST /v1/sweeps` would.
    Sweep {
        /// A file holding the sweep request (the body of `POST /v1/sweeps`).
        #[arg(long)]
        request: PathBuf,
        /// Where to write (default: standard output).
        #[arg(long)]
        output: Option<PathBuf>,
        /// csv, ndjson, arrow, json or svg (default: from the output's extension, else csv;
        /// a request with "reduce" is answered as json).
        #[arg(long)]
        format: Option<String>,
        /// Split the sweep into this many ranges (as POST /v1/sweeps/plan does) ...
        #[arg(long, requires = "index")]
        shards: Option<u64>,
        /// ... and compute the one with this index (0-based; a Kubernetes Indexed Job's
        /// JOB_COMPLETION_INDEX).
        #[arg(long, requires = "shards")]
        index: Option<u64>,
    },
    /// Join the Arrow parts of a sharded sweep into one stream, after checking
    /// that they are slices of one sweep (the same request hash, model version,
    /// precision and columns) whose ranges tile it in order; exits 1, naming
    /// the part, when they are not.
    Collect {
        /// Where to write the joined Arrow stream.
        #[arg(long)]
        output: PathBuf,
        /// The parts, in index order (`part-0.arrow part-1.arrow …`).
        #[arg(required = true)]
        parts: Vec<PathBuf>,
    },
}

/// A limit of sweeps at once: 1 to 100,000 (0 would refuse every sweep of
/// its kind for ever).
fn sweeps_at_once(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(n) if (1..=100_000).contains(&n) => Ok(n),
        _ => Err(format!("{text:?} is not a whole number from 1 to 100000")),
    }
}

/// Settings of the HTTP service.
#[derive(Debug, Clone, Args)]
pub struct ServiceConfig {
    /// Address to listen on.
    #[arg(long, env = "RESTITUTION_BIND", default_value = "127.0.0.1:8080")]
    pub bind: SocketAddr,
    /// Largest accepted request body, in bytes.
    #[arg(long, env = "RESTITUTION_BODY_LIMIT", default_value_t = 1 << 20)]
    pub body_limit: usize,
    /// Time allowed to answer one request, in milliseconds (then 408).
    #[arg(long, env = "RESTITUTION_REQUEST_TIMEOUT_MS", default_value_t = 10_000)]
    pub request_timeout_ms: u64,
    /// Requests served at once; more are refused at once with 503 and Retry-After.
    #[arg(long, env = "RESTITUTION_CONCURRENCY_LIMIT", default_value_t = 512)]
    pub concurrency_limit: usize,
    /// After a request is shed at the concurrency limit, `/readyz` answers 503
    /// for this many milliseconds (longer than the readiness probe's period,
    /// so that the probe sees it).
    #[arg(long, env = "RESTITUTION_SHEDDING_WINDOW_MS",
          default_value_t = crate::http::telemetry::DEFAULT_SHEDDING_WINDOW_MS)]
    pub shedding_window_ms: u64,
    /// Most points a streamed sweep (CSV, NDJSON) may have.
    #[arg(long, env = "RESTITUTION_MAX_SWEEP_POINTS", default_value_t = 10_000_000)]
    pub max_sweep_points: u64,
    /// Most points a buffered sweep (JSON table, SVG plot) may have.
    #[arg(
        long,
        env = "RESTITUTION_MAX_BUFFERED_SWEEP_POINTS",
        default_value_t = 200_000
    )]
    pub max_buffered_sweep_points: u64,
    /// Buffered sweeps (JSON table, SVG plot) computed at once; more are
    /// refused with 503 and Retry-After. Each holds its whole answer (a
    /// spatial JSON table of the most points: about 220 MiB).
    #[arg(long, env = "RESTITUTION_MAX_BUFFERED_SWEEPS", default_value_t = 4, value_parser = sweeps_at_once)]
    pub max_buffered_sweeps: usize,
    /// Streamed sweeps (CSV, NDJSON, Arrow) computed at once; more are
    /// refused with 503 and Retry-After. Each holds a few chunks (up to about
    /// 10 MiB for Arrow to a slow reader).
    #[arg(long, env = "RESTITUTION_MAX_STREAMED_SWEEPS", default_value_t = 64, value_parser = sweeps_at_once)]
    pub max_streamed_sweeps: usize,
    /// A streamed sweep whose client reads nothing for this long is dropped, in milliseconds.
    #[arg(long, env = "RESTITUTION_SWEEP_STALL_TIMEOUT_MS", default_value_t = 30_000)]
    pub sweep_stall_timeout_ms: u64,
    /// A connection must send a request's complete headers within this many milliseconds.
    #[arg(long, env = "RESTITUTION_HEADER_READ_TIMEOUT_MS", default_value_t = 5_000)]
    pub header_read_timeout_ms: u64,
    /// A connection whose client takes none of the bytes sent to it for this many
    /// milliseconds is closed, and what was queued for it dropped.
    #[arg(long, env = "RESTITUTION_WRITE_TIMEOUT_MS", default_value_t = 30_000,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub write_timeout_ms: u64,
    /// After SIGTERM or SIGINT, keep serving with `/readyz` answering 503 for this many
    /// milliseconds before the listener closes (let a load balancer see it first).
    #[arg(long, env = "RESTITUTION_SHUTDOWN_DRAIN_MS", default_value_t = 0)]
    pub shutdown_drain_ms: u64,
    /// After SIGTERM or SIGINT, in-flight requests may finish for this many milliseconds.
    #[arg(long, env = "RESTITUTION_SHUTDOWN_GRACE_MS", default_value_t = 10_000)]
    pub shutdown_grace_ms: u64,
    /// Record request metrics for `/metrics` (`--metrics false` to turn the
    /// per-request recording off; sweep and exact-stage counts stay).
    #[arg(long, env = "RESTITUTION_METRICS", default_value_t = true, action = clap::ArgAction::Set)]
    pub metrics: bool,
    /// A file holding a bearer token; when given, every route but /healthz needs
    /// `Authorization: Bearer <token>`.
    #[arg(long, env = "RESTITUTION_API_KEY_FILE")]
    pub api_key_file: Option<PathBuf>,
    /// Origins allowed by CORS (repeat the flag or separate by commas); CORS is off when none.
    #[arg(
        long = "cors-allow-origin",
        env = "RESTITUTION_CORS_ALLOW_ORIGINS",
        value_delimiter = ','
    )]
    pub cors_allow_origins: Vec<String>,
    /// The bearer token itself, read from `api_key_file` by [`ServiceConfig::load_api_key`].
    #[arg(skip)]
    pub api_key: Option<Arc<str>>,
}

impl ServiceConfig {
    /// Reads the bearer token from `api_key_file`, refusing an empty one.
    pub fn load_api_key(&mut self) -> std::io::Result<()> {
        if let Some(path) = &self.api_key_file {
            let text = std::fs::read_to_string(path)?;
            let token = text.trim();
            if token.is_empty() {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!("the API key file {} is empty", path.display()),
                ));
            }
            self.api_key = Some(Arc::from(token));
        }
        Ok(())
    }
}

impl Default for ServiceConfig {
    fn default() -> Self {
        ServiceConfig {
            bind: SocketAddr::from(([127, 0, 0, 1], 8080)),
            body_limit: 1 << 20,
            request_timeout_ms: 10_000,
            concurrency_limit: 512,
            shedding_window_ms: crate::http::telemetry::DEFAULT_SHEDDING_WINDOW_MS,
            max_sweep_points: 10_000_000,
            max_buffered_sweep_points: 200_000,
            max_buffered_sweeps: 4,
            max_streamed_sweeps: 64,
            sweep_stall_timeout_ms: 30_000,
            header_read_timeout_ms: 5_000,
            write_timeout_ms: 30_000,
            shutdown_drain_ms: 0,
            metrics: true,
            shutdown_grace_ms: 10_000,
            api_key_file: None,
            cors_allow_origins: Vec::new(),
            api_key: None,
        }
    }
}
