//! `softwalk snapshot`: checks a scene's frames against golden images, so a
//! user can guard their own scenes without writing Rust.
//!
//! Each frame the scene renders (every `render.every` steps) is compared
//! with `GOLDEN/frame_NNNNNN.png` through [`engine::snapshot`]: decoded
//! pixels, a YIQ threshold and a number of pixels allowed to differ. A failing
//! frame writes `actual.png`, `expected.png` and `diff.png` under
//! `OUT/frame_NNNNNN/`. With `--bless`, missing goldens are written and
//! failing ones rewritten; goldens that still pass are left alone.

use std::io::Write;
use std::path::{Path, PathBuf};

use engine::snapshot::{Outcome, Snapshot, SnapshotEnv, SnapshotError, Tolerance};

use super::{check_memory, scene_and_options, thread_pool};
use crate::cli::{CliError, SnapshotArgs};
use crate::runner::{self, Frame, ObserverError, RunObserver};

/// How the frames of one run compared with their goldens.
#[derive(Debug, Default)]
pub struct SnapshotTally {
    /// Frames identical to their golden.
    pub identical: usize,
    /// Frames within the tolerance.
    pub within: usize,
    /// Goldens written because none existed (`--bless`).
    pub created: usize,
    /// Goldens rewritten because the frame failed (`--bless`).
    pub updated: usize,
    /// Frames that failed, each with its report.
    pub failed: Vec<String>,
}

impl SnapshotTally {
    /// Frames checked in all.
    pub fn total(&self) -> usize {
        self.identical + self.within + self.created + self.updated + self.failed.len()
    }
}

/// The observer that checks every rendered frame.
struct GoldenFrames {
    golden_dir: PathBuf,
    artifact_dir: PathBuf,
    tolerance: Tolerance,
    env: SnapshotEnv,
    tally: SnapshotTally,
}

impl GoldenFrames {
    fn snapshot(&self, step: u64) -> Snapshot {
        Snapshot::in_dirs(
            &format!("frame_{step:06}"),
            &self.golden_dir,
            &self.artifact_dir,
        )
        .tolerance(self.tolerance)
    }
}

impl RunObserver for GoldenFrames {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        match self.snapshot(frame.step).check_with(frame.image, self.env) {
            Ok(Outcome::Identical) => self.tally.identical += 1,
            Ok(Outcome::WithinTolerance { .. }) => self.tally.within += 1,
            Ok(Outcome::Created(_)) => self.tally.created += 1,
            Ok(Outcome::Updated(_)) => self.tally.updated += 1,
            Err(e @ (SnapshotError::ReadGolden { .. } | SnapshotError::Write(_))) => {
                return Err(Box::new(e));
            }
            Err(e) => self.tally.failed.push(e.to_string()),
        }
        Ok(())
    }
}

/// Runs the scene, checks each frame against its golden and prints a tally;
/// fails when any frame does not pass (each failure is reported).
pub fn snapshot(args: &SnapshotArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, mut options) = scene_and_options(&args.scene)?;
    options.render = true;
    options.width = args.width.unwrap_or(options.width);
    options.height = args.height.unwrap_or(options.height);
    check_memory(&scene, &options, &args.scene)?;
    let pool = thread_pool(options.threads)?;
    let mut golden = GoldenFrames {
        golden_dir: args.golden.clone(),
        artifact_dir: args.out.clone(),
        tolerance: Tolerance {
            threshold: args.threshold,
            max_diff_pixels: args.max_diff_pixels,
        },
        env: SnapshotEnv {
            update: args.bless,
            ci: !args.bless,
        },
        tally: SnapshotTally::default(),
    };
    pool.install(|| runner::run(&scene, &options, &mut golden))?;
    let tally = golden.tally;
    print_tally(out, &tally, &args.golden).map_err(CliError::Stdout)?;
    if tally.failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::Snapshot {
            failed: tally.failed.len(),
            total: tally.total(),
        })
    }
}

fn print_tally(out: &mut dyn Write, tally: &SnapshotTally, golden: &Path) -> std::io::Result<()> {
    writeln!(
        out,
        "{} frame(s) against {}: {} identical, {} within tolerance, {} created, {} updated, {} failed",
        tally.total(),
        golden.display(),
        tally.identical,
        tally.within,
        tally.created,
        tally.updated,
        tally.failed.len()
    )?;
    for failure in &tally.failed {
        writeln!(out, "  {failure}")?;
    }
    if !tally.failed.is_empty() {
        writeln!(out, "re-run with --bless to accept the actual frames")?;
    }
    Ok(())
}
