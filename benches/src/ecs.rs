//! The `ecs` group of the peers harness.

use crate::Row;

/// Runs the group and returns one row per workload.
pub fn run() -> Vec<Row> {
    Vec::new()
}
