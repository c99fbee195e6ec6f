//! The integration tests, in one binary that links once; their helpers are
//! the `restitution-testkit` crate (`testkit/`), compiled once for the tests,
//! benches and examples. Three tests keep binaries of their
//! own: `allocation.rs` (a counting global allocator), `logging.rs` (a
//! captured log is thread-local: alone in its process) and `kernels.rs` (CI
//! runs its executable again against the release binary).

use restitution_testkit as common;

mod access_log;
mod bodies;
mod bodies_reference;
mod cli;
mod decisions;
mod fits;
mod http;
mod invariants;
mod paper;
mod precision;
mod promise;
mod reference;
mod robustness;
mod shutdown;
mod spatial;
mod spatial_fits;
mod spatial_reference;
mod sweep_rows;
mod sweeps;
mod telemetry;
mod tosses;
mod validation;
mod web;
