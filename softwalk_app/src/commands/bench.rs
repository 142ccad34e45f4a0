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
    let first = &runs[0];
    let same_world = runs.iter().all(|s| s.world_hash == first.world_hash);
    let print =
        |out: &mut dyn Write, line: String| writeln!(out, "{line}").map_err(CliError::Stdout);
    let steps = first.steps.max(1) as f64;
    let setup: Vec<f64> = runs.iter().map(|s| s.setup_seconds * 1e3).collect();
    let wall: Vec<f64> = runs
        .iter()
        .map(|s| s.stepping_seconds * 1e6 / steps)
        .collect();
    let systems: Vec<f64> = runs
        .iter()
        .map(|s| s.timings.iter().map(|t| t.mean_ns / 1000.0).sum())
        .collect();
    print(
        out,
        format!(
            "scene {}: {} walkers, {} steps on {} thread(s), {} run(s)",
            scene.name,
            scene.characters.len(),
            first.steps,
            options.threads,
            runs.len(),
        ),
    )?;
    print(
        out,
        format!("  {:<24} {:>10} {:>10}", "per run", "median", "fastest"),
    )?;
    for (label, values) in [
        ("set-up (ms)", &setup),
        ("step, wall (us)", &wall),
        ("sum of systems (us/step)", &systems),
    ] {
        print(
            out,
            format!(
                "  {label:<24} {:>10.1} {:>10.1}",
                median(values),
                fastest(values)
            ),
        )?;
    }
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
            .filter_map(|s| s.timings.get(k))
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
