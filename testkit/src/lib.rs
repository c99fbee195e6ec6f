//! The helpers the tests, benches and examples share, compiled once: random
//! scenes, the independent rational references of each case, the promise's
//! error measure, the comparison solvers (`linear`), the validation data's
//! readers, and a server on a loopback port. A dev-dependency of
//! `restitution` only (`publish = false`).

pub mod accuracy;
pub mod bodies_reference;
pub mod examples;
pub mod linear;
pub mod plain;
pub mod process;
pub mod reference;
pub mod rng;
pub mod rotation;
pub mod server;
pub mod spatial_reference;
pub mod sweep_rows;
pub mod tosses;
pub mod validation;

pub use rng::Rng;

/// The repository's root (`testkit/..`): where `examples/` and `tests/data/` are.
pub const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
