//! `softwalk run`: run a scene and write its outputs.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use super::{check_memory, scene_and_options, thread_pool};
use crate::cli::{CliError, RunArgs};
use crate::inputs::InputScript;
use crate::out_dir::{prepare_output_dir, remove_partial_files};
use crate::out_files::check_output_files;
use crate::output::{
    AnimationWriter, ContactSheet, FrameThread, FrameWriter, HeightmapReport, HeightmapWriter,
    MetricsCsv, PlotCollector, RunReport, StatsCollector, text_summary, write_summary_json,
};
use crate::progress::Progress;
use crate::runner::{self, Frame, ObserverError, Observers, RunObserver, RunOptions, RunSummary};
use crate::scene::Scene;

/// What a run writes of its frames: the PNG files, the animation and the
/// contact sheet's thumbnails.
struct FrameOutputs {
    files: FrameWriter,
    animation: AnimationWriter,
    sheet: ContactSheet,
}

impl RunObserver for FrameOutputs {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        self.files.on_frame(frame)?;
        self.animation.on_frame(frame)?;
        self.sheet.on_frame(frame)
    }
}

/// Resolves the scene, checks the output folder and every output file's path
/// (before any work, removing partial files a killed run left), runs the
/// simulation in a local thread pool and writes `metrics.csv` (streamed),
/// `summary.json`, the plots and, unless `--no-render`,
/// `frames/frame_NNNNNN.png`; then prints a summary. A plot that cannot be
/// written is skipped with a warning on standard error.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = scene_and_options(&args.scene)?;
    let inputs = args.inputs.as_deref().map(InputScript::load).transpose()?;
    for warning in scene.warnings() {
        eprintln!("warning: {warning}");
    }
    options.render = !args.no_render;
    options.hash = args.hash;
    options.width = args.width.unwrap_or(options.width);
    options.height = args.height.unwrap_or(options.height);
    check_memory(&scene, &options, &args.scene)?;
    let paths = OutputPaths::prepare(&args.out, &scene, &options)?;
    let pool = thread_pool(options.threads)?;

    let names: Vec<String> = scene.characters.iter().map(|c| c.name.clone()).collect();
    let mut metrics = MetricsCsv::create(&paths.metrics, names.clone())?;
    let mut stats = StatsCollector::new(scene.characters.len());
    let mut plots = PlotCollector::new(names);
    let mut heightmaps = HeightmapWriter::new(&paths.dir);
    // Frames are encoded on their own thread while the next ones are drawn.
    let mut frame_outputs = FrameThread::spawn(frame_outputs(&paths, &scene, &options)?);
    let mut progress = Progress::new(options.steps);

    let start = Instant::now();
    let summary = {
        let mut observers = Observers(vec![
            &mut metrics,
            &mut stats,
            &mut plots,
            &mut heightmaps,
            &mut progress,
        ]);
        if options.render {
            observers.0.push(&mut frame_outputs);
        }
        pool.install(|| runner::run_with_inputs(&scene, &options, inputs.as_ref(), &mut observers))
    };
    progress.finish();
    let written = frame_outputs.finish().map_err(CliError::Output);
    let summary = summary?;
    let FrameOutputs {
        animation, sheet, ..
    } = written?;
    metrics.finish()?;
    if let Some(sheet_path) = &paths.sheet {
        animation.finish().map_err(CliError::Output)?;
        sheet.save(sheet_path).map_err(CliError::Output)?;
    }
    let wall = start.elapsed().as_secs_f64();
    for warning in plots.save(&paths.plots).skipped {
        eprintln!("warning: {warning}");
    }

    let text = write_report(
        &paths,
        &scene,
        &options,
        &summary,
        &stats,
        &heightmaps,
        wall,
    )?;
    out.write_all(text.as_bytes()).map_err(CliError::Stdout)
}

/// Writes `summary.json` and returns the text summary printed at the end.
fn write_report(
    paths: &OutputPaths,
    scene: &Scene,
    options: &RunOptions,
    summary: &RunSummary,
    stats: &StatsCollector,
    heightmaps: &HeightmapWriter,
    wall: f64,
) -> Result<String, CliError> {
    let mut report = RunReport::new(scene, options, summary, &stats.stats(), wall);
    report.heightmaps = heightmaps
        .written
        .iter()
        .map(|(path, info)| HeightmapReport::new(path, info))
        .collect();
    write_summary_json(&paths.summary, &report)?;
    let mut text = text_summary(&report);
    if options.hash && summary.world_hash.is_none() {
        text.push_str("world hash: not computed by this simulation\n");
    }
    text.push_str(&format!("outputs in {}\n", paths.dir.display()));
    Ok(text)
}

/// Where a run's outputs go.
struct OutputPaths {
    /// The output folder.
    dir: PathBuf,
    /// `frames/`, the PNG frames.
    frames: PathBuf,
    /// `plots/`.
    plots: PathBuf,
    /// `metrics.csv`.
    metrics: PathBuf,
    /// `summary.json`.
    summary: PathBuf,
    /// `animation.gif`, when one is written.
    gif: Option<PathBuf>,
    /// `animation.apng`, when one is written.
    apng: Option<PathBuf>,
    /// `contact_sheet.png`, when frames are drawn.
    sheet: Option<PathBuf>,
}

impl OutputPaths {
    /// Creates the output folder `out` and its sub-folders, removes the
    /// frames a run without rendering would leave stale, and checks every
    /// file the run will write, before any work.
    fn prepare(out: &Path, scene: &Scene, options: &RunOptions) -> Result<Self, CliError> {
        let dir = prepare_output_dir(out)?;
        let frames = dir.join("frames");
        if options.render {
            prepare_output_dir(&frames)?;
        } else {
            remove_partial_files(&frames)?;
        }
        let plots = prepare_output_dir(&dir.join("plots"))?;
        let animation =
            |wanted: bool, file: &str| (options.render && wanted).then(|| dir.join(file));
        let paths = OutputPaths {
            gif: animation(scene.render.gif, "animation.gif"),
            apng: animation(scene.render.apng, "animation.apng"),
            sheet: options.render.then(|| dir.join("contact_sheet.png")),
            metrics: dir.join("metrics.csv"),
            summary: dir.join("summary.json"),
            frames,
            plots,
            dir,
        };
        check_output_files(paths.files().iter().map(PathBuf::as_path))?;
        Ok(paths)
    }

    /// Every file the run writes.
    fn files(&self) -> Vec<PathBuf> {
        [self.metrics.clone(), self.summary.clone()]
            .into_iter()
            .chain(["terrain_initial.png", "terrain_final.png"].map(|f| self.dir.join(f)))
            .chain(self.gif.clone())
            .chain(self.apng.clone())
            .chain(PlotCollector::files().map(|f| self.plots.join(f)))
            .chain(self.sheet.clone())
            .collect()
    }
}

/// The frame writers of a run: PNG files, the animation (GIF and APNG, each
/// when asked for) and the contact sheet.
fn frame_outputs(
    paths: &OutputPaths,
    scene: &Scene,
    options: &RunOptions,
) -> Result<FrameOutputs, CliError> {
    let frame_ms = (options.dt * f64::from(options.render_every) * 1000.0).round() as u32;
    let animation = AnimationWriter::create(paths.gif.as_deref(), paths.apng.as_deref(), frame_ms)
        .map_err(CliError::Output)?;
    let expected_frames = options
        .steps
        .div_ceil(u64::from(options.render_every.max(1)));
    Ok(FrameOutputs {
        files: FrameWriter::new(&paths.frames),
        animation,
        sheet: ContactSheet::new(expected_frames, 12, scene.render.contact_sheet_columns),
    })
}
