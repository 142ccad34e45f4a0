//! One module per subcommand, plus what `run` and `bench` share.

pub mod bench;
pub mod paper;
pub mod run;
pub mod scenes;

use rayon::ThreadPool;

use crate::cli::{CliError, SceneArgs};
use crate::runner::RunOptions;
use crate::scene::Scene;
use crate::scene_source::resolve_scene;

/// The scene and the run options the shared arguments ask for (rendering on, no hash).
pub(crate) fn scene_and_options(args: &SceneArgs) -> Result<(Scene, RunOptions), CliError> {
    let scene = resolve_scene(&args.scene)?;
    let mut options = RunOptions::from_scene(&scene);
    if let Some(steps) = args.steps {
        options.steps = steps;
    } else if let Some(seconds) = args.seconds {
        options.steps = scene.sim.steps_for(seconds);
    }
    options.threads = args.threads.map_or_else(default_threads, |t| t as usize);
    Ok((scene, options))
}

fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// A local pool of `threads` workers (not the global rayon pool).
pub(crate) fn thread_pool(threads: usize) -> Result<ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|k| format!("softwalk-{k}"))
        .build()
        .map_err(|source| CliError::Threads { threads, source })
}
