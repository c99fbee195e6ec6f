//! Shared helpers of the integration tests.
#![allow(dead_code)]

pub mod accuracy;
pub mod bodies_reference;
pub mod examples;
pub mod linear;
pub mod plain;
pub mod process;
pub mod reference;
mod rng;
pub mod rotation;
pub mod server;
pub mod spatial_reference;
pub mod sweep_rows;
pub mod validation;

pub use rng::Rng;
