//! One module per subcommand, plus what `run` and `bench` share.

pub mod bench;
pub mod inspect;
pub mod paper;
pub mod run;
pub mod scenes;
pub mod snapshot;
mod threads;
pub mod view;

use std::io::Write;

use rayon::ThreadPool;

use crate::cli::{Cli, CliError, Command, SceneArgs};
use crate::memory_estimate::{MemoryEstimate, check_steps};
use crate::runner::RunOptions;
use crate::scene::Scene;
use crate::scene_source::resolve_scene;

/// Runs one parsed command line, printing to `stdout`.
pub fn execute(cli: Cli, stdout: &mut dyn Write) -> Result<(), CliError> {
    match cli.command {
        Command::Run(args) => run::run(&args, stdout),
        Command::Scenes(args) => scenes::scenes(&args, stdout),
        Command::Bench(args) => bench::bench(&args, stdout),
        Command::Paper(args) => paper::paper(&args, stdout),
        Command::Snapshot(args) => snapshot::snapshot(&args, stdout),
        Command::Inspect(args) => inspect::inspect(&args, stdout),
        Command::View(args) => view::view(&args, stdout),
    }
}

/// The scene and the run options the shared arguments ask for (rendering on,
/// no hash); a thread count above the machine's cores is clamped with a warning.
pub(crate) fn scene_and_options(args: &SceneArgs) -> Result<(Scene, RunOptions), CliError> {
    let scene = resolve_scene(&args.scene)?;
    let mut options = RunOptions::from_scene(&scene);
    if let Some(steps) = args.steps {
        options.steps = steps;
    } else if let Some(seconds) = args.seconds {
        options.steps = scene.sim.steps_for(seconds);
        check_steps(
            options.steps,
            &format!("--seconds {seconds} at sim.dt {}", scene.sim.dt),
        )?;
    }
    let (threads, warning) = threads::clamp_threads(args.threads, threads::available_cores());
    if let Some(warning) = warning {
        eprintln!("warning: {warning}");
    }
    options.threads = threads;
    Ok((scene, options))
}

/// Refuses a run whose memory estimate is above `--max-memory`, before anything is allocated.
pub(crate) fn check_memory(
    scene: &Scene,
    options: &RunOptions,
    args: &SceneArgs,
) -> Result<(), CliError> {
    MemoryEstimate::of(scene, options).check(args.max_memory)?;
    Ok(())
}

/// A local pool of `threads` workers (not the global rayon pool).
pub(crate) fn thread_pool(threads: usize) -> Result<ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|k| format!("softwalk-{k}"))
        .build()
        .map_err(|source| CliError::Threads { threads, source })
}
