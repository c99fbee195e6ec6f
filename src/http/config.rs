//! Command line and environment configuration (clap).

use std::net::SocketAddr;

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
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the HTTP service (the default).
    Serve(ServiceConfig),
    /// Print the OpenAPI 3.1 document.
    Openapi,
    /// Exit 0 when the service at ADDR answers `GET /healthz` with 200 (for container health checks).
    Healthcheck {
        /// Address of the service.
        #[arg(long, env = "RESTITUTION_HEALTHCHECK_ADDR", default_value = "127.0.0.1:8080")]
        addr: SocketAddr,
    },
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
    /// A streamed sweep whose client reads nothing for this long is dropped, in milliseconds.
    #[arg(long, env = "RESTITUTION_SWEEP_STALL_TIMEOUT_MS", default_value_t = 30_000)]
    pub sweep_stall_timeout_ms: u64,
}

impl Default for ServiceConfig {
    fn default() -> Self {
        ServiceConfig {
            bind: SocketAddr::from(([127, 0, 0, 1], 8080)),
            body_limit: 1 << 20,
            request_timeout_ms: 10_000,
            concurrency_limit: 512,
            max_sweep_points: 10_000_000,
            max_buffered_sweep_points: 200_000,
            sweep_stall_timeout_ms: 30_000,
        }
    }
}
