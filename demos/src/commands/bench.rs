//! `softwalk bench`: run a scene without rendering or files and print per-step costs.

use std::io::Write;
use std::time::Instant;

use super::{scene_and_options, thread_pool};
use crate::cli::{BenchArgs, CliError};
use crate::sim;

/// Runs the scene headless and prints the wall time per step and each system's share.
pub fn bench(args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = scene_and_options(&args.scene)?;
    options.render = false;
    let pool = thread_pool(options.threads)?;
    let start = Instant::now();
    let summary = pool.install(|| sim::run(&scene, &options, &mut ()))?;
    let wall = start.elapsed().as_secs_f64();
    let per_step_us = wall * 1e6 / summary.steps.max(1) as f64;
    let print =
        |out: &mut dyn Write, line: String| writeln!(out, "{line}").map_err(CliError::Stdout);
    print(
        out,
        format!(
            "scene {}: {} steps on {} thread(s), {:.3} s wall, {:.1} us/step",
            scene.name, summary.steps, options.threads, wall, per_step_us
        ),
    )?;
    for t in &summary.timings {
        print(
            out,
            format!("  {:<24} {:>10.1} us/step", t.name, t.mean_ns / 1000.0),
        )?;
    }
    Ok(())
}
