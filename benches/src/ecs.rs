//! The `ecs` group of the peers harness: the ecs_bench_suite workloads on our
//! ECS, hecs and bevy_ecs, measured in the same run.
//!
//! Rules: cached queries everywhere (our `PreparedQuery`, hecs `PreparedQuery`
//! or its internally cached `query_mut`, bevy `QueryState`); thread pools made
//! before timing (the rayon global pool and bevy's `ComputeTaskPool` are
//! initialised by the untimed warm-up run); batch size 64 for parallel work;
//! the same glam types for all. hecs has no scheduler, so its `schedule` entry
//! is `None`.

mod bevy_peer;
mod hecs_peer;
mod ours;
mod workload;

use crate::{Row, time_ns};

/// Time budget per measurement, in milliseconds.
const BUDGET_MS: u64 = 400;

/// One implementation of every workload: each method prepares its world
/// untimed and returns the median time of the timed part in nanoseconds.
pub(crate) trait Contender {
    fn simple_insert(&self) -> f64;
    fn simple_iter(&self) -> f64;
    fn fragmented_iter(&self) -> f64;
    fn heavy_compute(&self) -> f64;
    fn heavy_compute_parallel(&self) -> f64;
    fn add_remove(&self) -> f64;
    /// `None` when the peer has no scheduler.
    fn schedule(&self) -> Option<f64>;
}

/// Measures one workload on one contender.
type Measure = fn(&dyn Contender) -> Option<f64>;

/// Runs the group and returns one row per workload.
pub fn run() -> Vec<Row> {
    bevy_peer::init_task_pool();
    let contenders: [(&'static str, &dyn Contender); 3] = [
        ("ours_ns", &ours::Ours),
        ("hecs_ns", &hecs_peer::Hecs),
        ("bevy_ns", &bevy_peer::Bevy),
    ];
    let workloads: [(&str, Measure); 7] = [
        ("simple_insert", |c| Some(c.simple_insert())),
        ("simple_iter", |c| Some(c.simple_iter())),
        ("fragmented_iter", |c| Some(c.fragmented_iter())),
        ("heavy_compute", |c| Some(c.heavy_compute())),
        ("heavy_compute_parallel", |c| {
            Some(c.heavy_compute_parallel())
        }),
        ("add_remove", |c| Some(c.add_remove())),
        ("schedule", |c| c.schedule()),
    ];
    workloads
        .iter()
        .map(|(name, measure)| {
            let times = contenders
                .iter()
                .map(|(key, contender)| (*key, measure(*contender)))
                .collect();
            Row::new(*name, times)
        })
        .collect()
}

/// Median of the timed closure under the group's budget.
pub(crate) fn measure(f: impl FnMut()) -> f64 {
    time_ns(BUDGET_MS, f)
}
