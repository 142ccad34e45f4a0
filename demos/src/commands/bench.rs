//! `softwalk bench`: run a scene several times without rendering or files and
//! print per-step costs (median and fastest run).

use std::io::Write;
use std::time::Instant;

use super::{scene_and_options, thread_pool};
use crate::cli::{BenchArgs, CliError};
use crate::runner::{self, RunSummary};

/// Runs the scene headless `args.repeats` times and prints the wall time per
/// step and each system's cost per step: the median over the runs and the
/// fastest run. Every run must end in the same world (same hash).
pub fn bench(args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = scene_and_options(&args.scene)?;
    options.render = false;
    options.hash = true;
    let pool = thread_pool(options.threads)?;
    let mut runs: Vec<(f64, RunSummary)> = Vec::with_capacity(args.repeats as usize);
    for _ in 0..args.repeats {
        let start = Instant::now();
        let summary = pool.install(|| runner::run(&scene, &options, &mut ()))?;
        let us_per_step = start.elapsed().as_secs_f64() * 1e6 / summary.steps.max(1) as f64;
        runs.push((us_per_step, summary));
    }
    let (_, first) = &runs[0];
    let same_world = runs.iter().all(|(_, s)| s.world_hash == first.world_hash);
    let print =
        |out: &mut dyn Write, line: String| writeln!(out, "{line}").map_err(CliError::Stdout);
    let wall: Vec<f64> = runs.iter().map(|(us, _)| *us).collect();
    print(
        out,
        format!(
            "scene {}: {} steps on {} thread(s), {} run(s): median {:.1} us/step, fastest {:.1} us/step",
            scene.name,
            first.steps,
            options.threads,
            runs.len(),
            median(&wall),
            fastest(&wall)
        ),
    )?;
    print(
        out,
        format!(
            "  {:<24} {:>10} {:>10}",
            "system (us/step)", "median", "fastest"
        ),
    )?;
    for (k, timing) in first.timings.iter().enumerate() {
        let costs: Vec<f64> = runs
            .iter()
            .filter_map(|(_, s)| s.timings.get(k))
            .map(|t| t.mean_ns / 1000.0)
            .collect();
        print(
            out,
            format!(
                "  {:<24} {:>10.1} {:>10.1}",
                timing.name,
                median(&costs),
                fastest(&costs)
            ),
        )?;
    }
    let hash = first
        .world_hash
        .map_or_else(|| "none".to_string(), |h| format!("{h:016x}"));
    let verdict = if same_world {
        "same in every run"
    } else {
        "DIFFERS between runs"
    };
    print(out, format!("world hash {hash}: {verdict}"))?;
    if same_world {
        Ok(())
    } else {
        Err(CliError::Nondeterministic { scene: scene.name })
    }
}

/// The median of `values` (the mean of the two middle ones for an even count).
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    match sorted.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// The smallest of `values`.
fn fastest(values: &[f64]) -> f64 {
    values.iter().copied().fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[5.0, 1.0, 3.0]), 3.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(&[]).is_nan());
        assert_eq!(fastest(&[4.0, 1.5, 3.0]), 1.5);
    }
}
