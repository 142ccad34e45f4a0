//! Peer comparison harness: each module measures one group of workloads on our
//! engine and on peer crates in the same run (see `src/bin/peers.rs`).

pub mod ecs;
pub mod raster;
pub mod raycast;
mod row;

pub use row::{Row, time_interleaved_ns, time_ns};
