//! The `softwalk` command line: arguments (clap derive) and the error type;
//! [`crate::commands::execute`] dispatches a parsed command line.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use thiserror::Error;

use crate::out_dir::OutputDirError;
use crate::runner::SimError;
use crate::scene::{MAX_FRAME_SIDE, SceneError};

/// Walk characters over loose ground (sand, soil, mud, snow, grass) and record what happens.
#[derive(Debug, Parser)]
#[command(name = "softwalk", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a scene and write metrics.csv, summary.json and frames to a folder.
    Run(RunArgs),
    /// List the built-in scenes, or print one as TOML.
    Scenes(ScenesArgs),
    /// Run a scene without rendering and print per-step costs.
    Bench(BenchArgs),
    /// Reproduce the paper's claims: measure them, render a gallery, write paper-results.md.
    Paper(PaperArgs),
    /// Check a scene's frames against golden PNGs (or bless them).
    Snapshot(SnapshotArgs),
    /// Print a character model's (.glb, .gltf) or mocap clip's (.bvh) rig, clips and leg chains.
    Inspect(InspectArgs),
    /// Open a window with the live simulation: steer a character with the keyboard.
    View(ViewArgs),
}

/// Arguments of `softwalk view`.
#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    /// Scene, step limit (`--steps` or `--seconds`: close after so many) and threads.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Window width in pixels.
    #[arg(long, default_value_t = 960, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub width: u32,
    /// Window height in pixels.
    #[arg(long, default_value_t = 540, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub height: u32,
    /// Write every input, with its step number, to this TOML file on exit.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Play recorded inputs (as `run --inputs` does); keys still act on top.
    #[arg(long, value_name = "FILE")]
    pub inputs: Option<PathBuf>,
    /// Save a screenshot once this many steps have run, then close.
    #[arg(long, value_name = "STEPS")]
    pub screenshot_after: Option<u64>,
    /// Where screenshots go (the P key numbers them beside it).
    #[arg(long, value_name = "FILE", default_value = "softwalk-view.png")]
    pub screenshot: PathBuf,
    /// Folder the F key records frames to.
    #[arg(long, value_name = "DIR", default_value = "softwalk-frames")]
    pub frames: PathBuf,
}

/// Arguments of `softwalk inspect`.
#[derive(Debug, Clone, Args)]
pub struct InspectArgs {
    /// A `.glb`, `.gltf` or `.bvh` file.
    pub file: PathBuf,
}

/// Which scene and for how long; shared by `run` and `bench`.
#[derive(Debug, Clone, Args)]
pub struct SceneArgs {
    /// A built-in scene name (see `softwalk scenes`) or a path to a scene TOML file.
    #[arg(default_value = "default")]
    pub scene: String,
    /// Simulate this many steps instead of the scene's duration.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=crate::scene::MAX_STEPS), conflicts_with = "seconds")]
    pub steps: Option<u64>,
    /// Simulate this many seconds instead of the scene's duration.
    #[arg(long, value_parser = parse_seconds)]
    pub seconds: Option<f64>,
    /// Memory budget: a run whose memory estimate exceeds it is refused before
    /// anything is allocated (e.g. `8G`, `512M`; binary units).
    #[arg(long, value_name = "SIZE", default_value = "8G", value_parser = crate::memory_estimate::parse_bytes)]
    pub max_memory: u64,
    /// Worker threads (default: all cores; more than the cores are clamped, with a warning).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
}

/// Arguments of `softwalk snapshot`.
#[derive(Debug, Clone, Args)]
pub struct SnapshotArgs {
    /// Scene, duration and threads.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Folder of golden frames (`frame_NNNNNN.png`, one per rendered frame).
    #[arg(long)]
    pub golden: PathBuf,
    /// Write missing goldens and rewrite those that fail (goldens that pass stay).
    #[arg(long)]
    pub bless: bool,
    /// Folder for the actual, expected and diff PNGs of failing frames.
    #[arg(long, short, default_value = "snapshot-failures")]
    pub out: PathBuf,
    /// Per-pixel YIQ colour delta that counts as a difference, 0 to 1.
    #[arg(long, default_value_t = 0.1, value_parser = parse_threshold)]
    pub threshold: f32,
    /// Differing pixels (after forgiving anti-aliasing) a frame may have.
    #[arg(long, default_value_t = 24)]
    pub max_diff_pixels: usize,
    /// Frame width in pixels (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub width: Option<u32>,
    /// Frame height in pixels (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub height: Option<u32>,
}

fn parse_threshold(text: &str) -> Result<f32, String> {
    let value: f32 = text.parse().map_err(|e| format!("{e}"))?;
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} is not in [0, 1]"))
    }
}

/// Arguments of `softwalk run`.
#[derive(Debug, Clone, Args)]
pub struct RunArgs {
    /// Scene, duration and threads.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output folder (created if missing; must be writable).
    #[arg(long, short, default_value = "out")]
    pub out: PathBuf,
    /// Do not render frames (metrics and summary only).
    #[arg(long)]
    pub no_render: bool,
    /// Compute and print a hash of the final world.
    #[arg(long)]
    pub hash: bool,
    /// Frame width in pixels (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub width: Option<u32>,
    /// Frame height in pixels (overrides the scene).
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=MAX_FRAME_SIDE as i64))]
    pub height: Option<u32>,
    /// Replay recorded inputs (TOML: step numbers and events) steering a character.
    #[arg(long, value_name = "FILE")]
    pub inputs: Option<PathBuf>,
}

/// Arguments of `softwalk scenes`.
#[derive(Debug, Clone, Args)]
pub struct ScenesArgs {
    /// Print this built-in scene as TOML instead of listing.
    #[arg(long, value_name = "NAME")]
    pub dump: Option<String>,
}

/// Arguments of `softwalk bench`.
#[derive(Debug, Clone, Args)]
pub struct BenchArgs {
    /// Scene, duration and threads.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Run the scene this many times and report the median and the fastest
    /// run (single runs vary a lot on a shared machine).
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: u32,
    /// Samples along the terrain's longer side (overrides the scene; same extent, finer or coarser cells).
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=8192))]
    pub resolution: Option<u32>,
    /// The `crowd` scene's make-up (only with the `crowd` scene).
    #[command(flatten)]
    pub crowd: CrowdArgs,
}

/// Options of `softwalk bench crowd`: the crowd scene generated from these
/// numbers instead of the built-in one's.
#[derive(Debug, Clone, Default, Args)]
pub struct CrowdArgs {
    /// Number of walkers.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub walkers: Option<u32>,
    /// Side of the square field, metres.
    #[arg(long, value_parser = parse_metres)]
    pub field: Option<f64>,
    /// Fraction of the field covered by 0.9 m grass (0 to 1).
    #[arg(long, value_parser = parse_fraction)]
    pub grass: Option<f64>,
    /// Walk parallel lanes this many metres apart (instead of crossing paths).
    #[arg(long, value_parser = parse_metres)]
    pub lanes: Option<f64>,
    /// Sand everywhere (no snow or soil bands).
    #[arg(long)]
    pub sand_only: bool,
}

impl CrowdArgs {
    /// True when any option is given.
    pub fn any(&self) -> bool {
        self.walkers.is_some()
            || self.field.is_some()
            || self.grass.is_some()
            || self.lanes.is_some()
            || self.sand_only
    }
}

/// Arguments of `softwalk paper`.
#[derive(Debug, Clone, Args)]
pub struct PaperArgs {
    /// Output folder for paper-results.md and gallery/ (use `docs` in the repository).
    #[arg(long, short, default_value = "docs")]
    pub out: PathBuf,
    /// Shorten the ten-minute robustness walk to one minute.
    #[arg(long)]
    pub quick: bool,
}

fn parse_metres(text: &str) -> Result<f64, String> {
    let v: f64 = text
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number"))?;
    if v.is_finite() && v > 0.0 && v <= 1.0e4 {
        Ok(v)
    } else {
        Err(format!("{text} must be a number of metres in (0, 10000]"))
    }
}

fn parse_fraction(text: &str) -> Result<f64, String> {
    let v: f64 = text
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number"))?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{text} must be a fraction in [0, 1]"))
    }
}

fn parse_seconds(text: &str) -> Result<f64, String> {
    let v: f64 = text
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number"))?;
    if v.is_finite() && v > 0.0 && v <= 1.0e6 {
        Ok(v)
    } else {
        Err(format!(
            "{text} must be a number of seconds in (0, 1000000]"
        ))
    }
}

/// A command-line parsing error (wrong, missing or conflicting arguments).
pub type ArgsError = clap::Error;

impl Cli {
    /// Parses arguments (the first is the program name) without exiting on error.
    pub fn parse_args<I, T>(args: I) -> Result<Cli, ArgsError>
    where
        I: IntoIterator<Item = T>,
        T: Into<std::ffi::OsString> + Clone,
    {
        <Cli as Parser>::try_parse_from(args)
    }
}

/// Everything a command can fail with.
#[derive(Debug, Error)]
pub enum CliError {
    /// The scene could not be found, read or validated.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The run would need more memory or steps than allowed.
    #[error(transparent)]
    Budget(#[from] crate::memory_estimate::BudgetError),
    /// The output folder cannot be used.
    #[error(transparent)]
    OutputDir(#[from] OutputDirError),
    /// An output file's path cannot be written (found before the run).
    #[error(transparent)]
    OutputFile(#[from] crate::out_files::OutputFileError),
    /// An output file could not be written.
    #[error(transparent)]
    Write(#[from] engine::io::WriteError),
    /// The simulation failed.
    #[error("the run failed")]
    Sim(#[from] SimError),
    /// The thread pool could not be built.
    #[error("cannot start {threads} worker threads")]
    Threads {
        /// Threads asked for.
        threads: usize,
        /// Why it failed.
        #[source]
        source: rayon::ThreadPoolBuildError,
    },
    /// The paper report could not be produced.
    #[error("the paper report failed")]
    Paper(#[source] Box<crate::paper::PaperError>),
    /// Printing to standard output failed.
    #[error("cannot print to standard output")]
    Stdout(#[source] std::io::Error),
    /// An animation, contact sheet or plot could not be written.
    #[error("writing the outputs failed")]
    Output(#[source] crate::runner::ObserverError),
    /// Frames differ from their goldens beyond the tolerance.
    #[error("{failed} of {total} frame(s) differ from their goldens (reports above)")]
    Snapshot {
        /// Frames that failed.
        failed: usize,
        /// Frames checked.
        total: usize,
    },
    /// Crowd options were given for another scene than `crowd`.
    #[error(
        "--walkers, --field, --grass, --lanes and --sand-only apply to the crowd scene only, not to {scene}"
    )]
    CrowdOptions {
        /// The scene named.
        scene: String,
    },
    /// A model or clip could not be loaded.
    #[error("cannot inspect the file")]
    Inspect(#[source] Box<dyn std::error::Error + Send + Sync>),
    /// `inspect` was given a file that is neither glTF nor BVH.
    #[error("{path}: not a .glb, .gltf or .bvh file")]
    UnknownFileKind {
        /// The file.
        path: PathBuf,
    },
    /// An input file could not be read or checked.
    #[error(transparent)]
    Inputs(#[from] crate::inputs::InputError),
    /// No window can be opened (no display, as on CI).
    #[error("cannot open a window: {reason}")]
    NoWindow {
        /// Why.
        reason: String,
    },
    /// Repeated runs of one scene ended in different worlds.
    #[error("scene {scene}: repeated runs ended in different worlds (world hashes differ)")]
    Nondeterministic {
        /// The scene's name.
        scene: String,
    },
}

/// An error and its causes on one line, `a: b: c`; a cause already spelled out
/// at the end of the message before it is not repeated.
pub fn error_line(error: &(dyn std::error::Error + 'static)) -> String {
    let mut line = error.to_string();
    let mut cause = error.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !line.ends_with(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
        cause = c.source();
    }
    line.replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_line_joins_causes_without_repeats() {
        let io = std::io::Error::other("disk full");
        let write = engine::io::WriteError {
            path: "a.csv".into(),
            source: io,
        };
        let e = CliError::Write(write);
        assert_eq!(error_line(&e), "cannot write a.csv: disk full");
        let sim = CliError::Sim(SimError::Observer("boom".into()));
        assert_eq!(
            error_line(&sim),
            "the run failed: writing the run's output failed: boom"
        );
    }
}
