//! `softwalk run`: run a scene and write its outputs.

use std::fs;
use std::io::Write;
use std::time::Instant;

use super::{scene_and_options, thread_pool};
use crate::cli::{CliError, RunArgs};
use crate::out_dir::{OutputDirError, prepare_output_dir};
use crate::output::{
    FrameWriter, MetricsCsv, RunReport, StatsCollector, text_summary, write_summary_json,
};
use crate::progress::Progress;
use crate::sim::{self, Observers};

/// Resolves the scene, checks the output folder (before any work), runs the
/// simulation in a local thread pool and writes `metrics.csv`, `summary.json`
/// and, unless `--no-render`, `frames/frame_NNNNNN.png`; then prints a summary.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = scene_and_options(&args.scene)?;
    options.render = !args.no_render;
    options.hash = args.hash;
    options.width = args.width.unwrap_or(options.width);
    options.height = args.height.unwrap_or(options.height);

    let dir = prepare_output_dir(&args.out)?;
    let frames_dir = dir.join("frames");
    if options.render {
        fs::create_dir_all(&frames_dir).map_err(|source| OutputDirError {
            path: frames_dir.clone(),
            problem: "cannot be created".into(),
            source,
        })?;
    }
    let pool = thread_pool(options.threads)?;

    let names = scene.characters.iter().map(|c| c.name.clone()).collect();
    let mut metrics = MetricsCsv::create(&dir.join("metrics.csv"), names)?;
    let mut stats = StatsCollector::new(scene.characters.len());
    let mut frames = FrameWriter::new(&frames_dir);
    let mut progress = Progress::new(options.steps);

    let start = Instant::now();
    let summary = {
        let mut observers = Observers(vec![&mut metrics, &mut stats, &mut progress]);
        if options.render {
            observers.0.push(&mut frames);
        }
        pool.install(|| sim::run(&scene, &options, &mut observers))
    };
    progress.finish();
    let summary = summary?;
    metrics.finish()?;
    let wall = start.elapsed().as_secs_f64();

    let report = RunReport::new(&scene, &options, &summary, &stats.stats(), wall);
    write_summary_json(&dir.join("summary.json"), &report)?;
    let mut text = text_summary(&report);
    if options.hash && summary.world_hash.is_none() {
        text.push_str("world hash: not computed by this simulation\n");
    }
    text.push_str(&format!("outputs in {}\n", dir.display()));
    out.write_all(text.as_bytes()).map_err(CliError::Stdout)
}
