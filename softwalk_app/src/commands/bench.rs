//! `softwalk bench`: run a scene several times without rendering or files and
//! print per-step costs (median and fastest run), set-up excluded.

use std::io::Write;

use super::{check_memory, scene_and_options, thread_pool};
use crate::cli::{BenchArgs, CliError, CrowdArgs};
use crate::runner::{self, RunOptions, RunSummary};
use crate::scene::{CrowdLayout, CrowdSpec, Scene};

/// Runs the scene headless `args.repeats` times and prints the set-up time,
/// the wall time per step after set-up and each system's cost per step: the
/// median over the runs and the fastest run. Every run must end in the same
/// world (same hash).
pub fn bench(args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = bench_scene(args)?;
    for warning in scene.warnings() {
        eprintln!("warning: {warning}");
    }
    options.render = false;
    options.hash = true;
    check_memory(&scene, &options, &args.scene)?;
    let pool = thread_pool(options.threads)?;
    let mut runs: Vec<RunSummary> = Vec::with_capacity(args.repeats as usize);
    for _ in 0..args.repeats {
        runs.push(pool.install(|| runner::run(&scene, &options, &mut ()))?);
    }
    write_table(out, &scene, &options, &runs)?;
    let first = &runs[0];
    let same_world = runs.iter().all(|s| s.world_hash == first.world_hash);
    let hash = first
        .world_hash
        .map_or_else(|| "none".to_string(), |h| format!("{h:016x}"));
    let verdict = if same_world {
        "same in every run"
    } else {
        "DIFFERS between runs"
    };
    writeln!(out, "world hash {hash}: {verdict}").map_err(CliError::Stdout)?;
    if same_world {
        Ok(())
    } else {
        Err(CliError::Nondeterministic { scene: scene.name })
    }
}

/// Prints the runs' costs: set-up, wall time per step and the sum of the
/// systems, then each system, as the median and the fastest run.
fn write_table(
    out: &mut dyn Write,
    scene: &Scene,
    options: &RunOptions,
    runs: &[RunSummary],
) -> Result<(), CliError> {
    let first = &runs[0];
    let steps = first.steps.max(1) as f64;
    let setup = per_run(runs, |s| Some(s.setup_seconds * 1e3));
    let wall = per_run(runs, |s| Some(s.stepping_seconds * 1e6 / steps));
    let systems = per_run(runs, |s| {
        Some(s.timings.iter().map(|t| t.mean_ns / 1000.0).sum())
    });
    let mut text = format!(
        "scene {}: {} walkers, {} steps on {} thread(s), {} run(s)\n",
        scene.name,
        scene.characters.len(),
        first.steps,
        options.threads,
        runs.len(),
    );
    text += &format!("  {:<24} {:>10} {:>10}\n", "per run", "median", "fastest");
    text += &cost_row("set-up (ms)", &setup);
    text += &cost_row("step, wall (us)", &wall);
    text += &cost_row("sum of systems (us/step)", &systems);
    text += &format!(
        "  {:<24} {:>10} {:>10}\n",
        "system (us/step)", "median", "fastest"
    );
    for (k, timing) in first.timings.iter().enumerate() {
        let costs = per_run(runs, |s| s.timings.get(k).map(|t| t.mean_ns / 1000.0));
        text += &cost_row(&timing.name, &costs);
    }
    out.write_all(text.as_bytes()).map_err(CliError::Stdout)
}

/// `f` of each run that has it.
fn per_run(runs: &[RunSummary], f: impl Fn(&RunSummary) -> Option<f64>) -> Vec<f64> {
    runs.iter().filter_map(f).collect()
}

/// One line of the table: `label`, then the median and the fastest of `values`.
fn cost_row(label: &str, values: &[f64]) -> String {
    format!(
        "  {label:<24} {:>10.1} {:>10.1}\n",
        median(values),
        fastest(values)
    )
}

/// The scene to measure: the named one, or the crowd generated from the
/// crowd options; `--resolution` applied to either.
fn bench_scene(args: &BenchArgs) -> Result<(Scene, RunOptions), CliError> {
    let (mut scene, mut options) = scene_and_options(&args.scene)?;
    if args.crowd.any() {
        if scene.name != "crowd" {
            return Err(CliError::CrowdOptions { scene: scene.name });
        }
        let mut spec = crowd_spec(&args.crowd);
        if let Some(r) = args.resolution {
            spec.resolution = r;
        }
        let toml = spec.toml("crowd");
        let crowd = Scene::from_toml_str(&toml, std::path::Path::new(""))?;
        let steps = options.steps;
        let threads = options.threads;
        options = RunOptions::from_scene(&crowd);
        if args.scene.steps.is_some() || args.scene.seconds.is_some() {
            options.steps = steps;
        }
        options.threads = threads;
        scene = crowd;
    } else if let Some(r) = args.resolution {
        scene.terrain.resolution = r;
        scene.validate()?;
    }
    Ok((scene, options))
}

/// The crowd spec the options describe (defaults: the built-in `crowd`).
fn crowd_spec(args: &CrowdArgs) -> CrowdSpec {
    let mut spec = CrowdSpec::default();
    if let Some(n) = args.walkers {
        spec.walkers = n as usize;
    }
    if let Some(size) = args.field {
        spec.size_m = size as f32;
    }
    if let Some(f) = args.grass {
        spec.grass_fraction = f as f32;
    }
    if let Some(spacing) = args.lanes {
        spec.layout = CrowdLayout::Lanes;
        spec.spacing_m = spacing as f32;
    }
    if args.sand_only {
        spec.mixed_ground = false;
    }
    spec
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
