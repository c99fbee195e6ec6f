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
}

impl Default for ServiceConfig {
    fn default() -> Self {
        ServiceConfig {
            bind: SocketAddr::from(([127, 0, 0, 1], 8080)),
            body_limit: 1 << 20,
            request_timeout_ms: 10_000,
            concurrency_limit: 512,
        }
    }
}
