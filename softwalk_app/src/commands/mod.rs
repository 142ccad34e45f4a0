//! One module per subcommand, plus what `run` and `bench` share.

pub mod bench;
pub mod inspect;
pub mod paper;
pub mod run;
pub mod scenes;
pub mod snapshot;
mod threads;
pub mod view;

use rayon::ThreadPool;

use crate::cli::{CliError, SceneArgs};
use crate::memory_estimate::{MemoryEstimate, check_steps};
use crate::runner::RunOptions;
use crate::scene::Scene;
use crate::scene_source::resolve_scene;

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
