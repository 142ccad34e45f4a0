//! Golden-image snapshot tests.
//!
//! A rendered image is compared with a golden PNG, decoded pixel by pixel
//! (never by file bytes, which change with the encoder):
//! 1. an exact match passes at once;
//! 2. otherwise each pixel's YIQ colour delta is tested against a
//!    [`Tolerance::threshold`] (as pixelmatch does), anti-aliased edge pixels
//!    are forgiven, and the check passes if at most
//!    [`Tolerance::max_diff_pixels`] pixels still differ.
//!
//! On failure `actual.png`, `expected.png` and `diff.png` are written under
//! `<target dir>/snapshots/<name>/` and the error names them.
//!
//! Environment: `UPDATE_SNAPSHOTS=1` writes missing goldens and rewrites
//! those that fail their tolerance (the check passes); a golden that still
//! passes is left as it is. A missing golden is written locally (with a note on stderr) but
//! fails when `CI` is set.
//!
//! ```no_run
//! use engine::snapshot::Tolerance;
//! let frame = image::RgbaImage::new(64, 64);
//! engine::snapshot!("terrain_bumpy")
//!     .tolerance(Tolerance { threshold: 0.1, max_diff_pixels: 20 })
//!     .assert_matches(&frame);
//! ```

#![forbid(unsafe_code)]

mod error;
mod pixelmatch;

use std::path::{Path, PathBuf};

use image::RgbaImage;

pub use error::{Mismatch, SnapshotError};

use crate::output::save_png;

/// How different an image may be from its golden and still pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Per-pixel YIQ colour delta, 0 (exact) to 1; 0.1 is pixelmatch's default.
    pub threshold: f32,
    /// How many pixels may exceed the threshold (after forgiving anti-aliasing).
    pub max_diff_pixels: usize,
}

impl Tolerance {
    /// Only an exact match passes.
    pub const EXACT: Self = Self {
        threshold: 0.0,
        max_diff_pixels: 0,
    };
}

impl Default for Tolerance {
    /// Threshold 0.1, no differing pixel allowed (anti-aliasing is forgiven).
    fn default() -> Self {
        Self {
            threshold: 0.1,
            max_diff_pixels: 0,
        }
    }
}

/// The environment settings that steer a check (see [`SnapshotEnv::from_env`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SnapshotEnv {
    /// Write or refresh goldens instead of comparing (`UPDATE_SNAPSHOTS`).
    pub update: bool,
    /// Running on continuous integration (`CI`): a missing golden fails.
    pub ci: bool,
}

impl SnapshotEnv {
    /// Reads `UPDATE_SNAPSHOTS` and `CI`; a variable counts as set unless it
    /// is empty, `0`, `false` or `no`.
    pub fn from_env() -> Self {
        let flag = |name| {
            std::env::var(name).is_ok_and(|v| !matches!(v.trim(), "" | "0" | "false" | "no"))
        };
        Self {
            update: flag("UPDATE_SNAPSHOTS"),
            ci: flag("CI"),
        }
    }
}

/// How a passing check ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The decoded pixels are identical.
    Identical,
    /// Some pixels differ, within the tolerance.
    WithinTolerance {
        /// Pixels over the threshold that are not anti-aliasing.
        diff_pixels: usize,
        /// Pixels over the threshold forgiven as anti-aliasing.
        aa_pixels: usize,
        /// Largest per-pixel delta, on the threshold's 0..=1 scale.
        max_delta: f32,
    },
    /// No golden existed; it was written from the actual image.
    Created(PathBuf),
    /// `UPDATE_SNAPSHOTS` replaced a differing golden with the actual image.
    Updated(PathBuf),
}

/// The workspace root of the crate at `manifest_dir`: the nearest ancestor
/// (or itself) whose `Cargo.toml` declares `[workspace]`, or `manifest_dir`
/// itself if there is none.
pub fn workspace_root(manifest_dir: &Path) -> PathBuf {
    manifest_dir
        .ancestors()
        .find(|dir| {
            std::fs::read_to_string(dir.join("Cargo.toml"))
                .is_ok_and(|toml| toml.lines().any(|l| l.trim() == "[workspace]"))
        })
        .unwrap_or(manifest_dir)
        .to_path_buf()
}

/// A snapshot whose goldens live in `<workspace root>/tests/snapshots/`, the
/// workspace being found from the calling crate's `CARGO_MANIFEST_DIR`.
#[macro_export]
macro_rules! snapshot {
    ($name:expr) => {
        $crate::snapshot::Snapshot::for_manifest_dir(
            $name,
            ::std::path::Path::new(env!("CARGO_MANIFEST_DIR")),
        )
    };
}

/// One named golden-image check.
#[derive(Debug, Clone)]
pub struct Snapshot {
    name: String,
    golden_dir: PathBuf,
    artifact_dir: PathBuf,
    tolerance: Tolerance,
}

impl Snapshot {
    /// A snapshot of the crate under test: goldens in
    /// `<workspace root>/tests/snapshots/`, the workspace found from the
    /// `CARGO_MANIFEST_DIR` that cargo sets when running tests (or from the
    /// current directory). The [`snapshot!`](crate::snapshot!) macro resolves
    /// the directory at compile time instead.
    pub fn new(name: &str) -> Self {
        let manifest_dir = std::env::var_os("CARGO_MANIFEST_DIR")
            .map(PathBuf::from)
            .or_else(|| std::env::current_dir().ok())
            .unwrap_or_else(|| PathBuf::from("."));
        Self::for_manifest_dir(name, &manifest_dir)
    }

    /// A snapshot with goldens in `golden_dir` and failure artifacts under
    /// `artifact_dir/<name>/`, with the default [`Tolerance`].
    pub fn in_dirs(
        name: &str,
        golden_dir: impl Into<PathBuf>,
        artifact_dir: impl Into<PathBuf>,
    ) -> Self {
        Self {
            name: name.to_owned(),
            golden_dir: golden_dir.into(),
            artifact_dir: artifact_dir.into(),
            tolerance: Tolerance::default(),
        }
    }

    /// A snapshot for a crate of the workspace at `manifest_dir`: goldens in
    /// `<workspace root>/tests/snapshots/`, artifacts in
    /// `<target dir>/snapshots/` (`CARGO_TARGET_DIR` or `<workspace root>/target`).
    pub fn for_manifest_dir(name: &str, manifest_dir: &Path) -> Self {
        let root = workspace_root(manifest_dir);
        let target = std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| root.join("target"));
        Self::in_dirs(
            name,
            root.join("tests").join("snapshots"),
            target.join("snapshots"),
        )
    }

    /// Sets the tolerance.
    pub fn tolerance(mut self, tolerance: Tolerance) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Path of the golden PNG.
    pub fn golden_path(&self) -> PathBuf {
        self.golden_dir.join(format!("{}.png", self.name))
    }

    /// Directory where failure artifacts are written.
    pub fn artifact_path(&self) -> PathBuf {
        self.artifact_dir.join(&self.name)
    }

    /// Checks `actual` against the golden, steered by the process environment.
    pub fn check(&self, actual: &RgbaImage) -> Result<Outcome, SnapshotError> {
        self.check_with(actual, SnapshotEnv::from_env())
    }

    /// Checks `actual` against the golden with explicit environment settings.
    ///
    /// With `env.update` a golden is rewritten only when `actual` fails its
    /// tolerance (or has another size), so blessing never churns goldens
    /// that still pass.
    pub fn check_with(
        &self,
        actual: &RgbaImage,
        env: SnapshotEnv,
    ) -> Result<Outcome, SnapshotError> {
        self.check_name()?;
        let golden = self.golden_path();
        if !golden.exists() {
            return self.create_golden(actual, env);
        }
        let expected = image::open(&golden)
            .map_err(|source| SnapshotError::ReadGolden {
                path: golden.clone(),
                source,
            })?
            .into_rgba8();
        if expected == *actual {
            self.remove_stale_artifacts();
            return Ok(Outcome::Identical);
        }
        let comparison = (expected.dimensions() == actual.dimensions())
            .then(|| pixelmatch::compare(&expected, actual, self.tolerance.threshold));
        if let Some(c) = comparison
            .as_ref()
            .filter(|c| c.diff_pixels <= self.tolerance.max_diff_pixels)
        {
            self.remove_stale_artifacts();
            return Ok(Outcome::WithinTolerance {
                diff_pixels: c.diff_pixels,
                aa_pixels: c.aa_pixels,
                max_delta: c.max_delta,
            });
        }
        if env.update {
            save_png(&golden, actual)?;
            self.remove_stale_artifacts();
            eprintln!(
                "snapshot '{}': updated golden {}",
                self.name,
                golden.display()
            );
            return Ok(Outcome::Updated(golden));
        }
        Err(self.report_failure(&expected, actual, comparison)?)
    }

    /// Refuses names that are not plain file stems.
    fn check_name(&self) -> Result<(), SnapshotError> {
        let valid = !self.name.is_empty()
            && self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if valid {
            Ok(())
        } else {
            Err(SnapshotError::InvalidName {
                name: self.name.clone(),
            })
        }
    }

    /// Writes a missing golden, or fails on CI (unless updating) after
    /// saving the actual image.
    fn create_golden(
        &self,
        actual: &RgbaImage,
        env: SnapshotEnv,
    ) -> Result<Outcome, SnapshotError> {
        let golden = self.golden_path();
        if env.ci && !env.update {
            let actual_path = self.artifact_path().join("actual.png");
            save_png_creating_dir(&actual_path, actual)?;
            return Err(SnapshotError::MissingGolden {
                name: self.name.clone(),
                golden,
                actual: actual_path,
            });
        }
        save_png_creating_dir(&golden, actual)?;
        eprintln!(
            "snapshot '{}': created golden {}",
            self.name,
            golden.display()
        );
        Ok(Outcome::Created(golden))
    }

    /// Writes the actual, expected and (for same-sized images) diff PNGs of
    /// a failed check and returns the error naming them.
    fn report_failure(
        &self,
        expected: &RgbaImage,
        actual: &RgbaImage,
        comparison: Option<pixelmatch::Comparison>,
    ) -> Result<SnapshotError, SnapshotError> {
        let artifacts = self.artifact_path();
        let (actual_path, expected_path) =
            (artifacts.join("actual.png"), artifacts.join("expected.png"));
        save_png_creating_dir(&actual_path, actual)?;
        save_png(&expected_path, expected)?;
        let Some(comparison) = comparison else {
            return Ok(SnapshotError::SizeMismatch {
                name: self.name.clone(),
                expected_width: expected.width(),
                expected_height: expected.height(),
                actual_width: actual.width(),
                actual_height: actual.height(),
                actual: actual_path,
                expected: expected_path,
            });
        };
        let diff_path = artifacts.join("diff.png");
        save_png(&diff_path, &comparison.diff_image)?;
        Ok(SnapshotError::Mismatch(Box::new(Mismatch {
            name: self.name.clone(),
            diff_pixels: comparison.diff_pixels,
            allowed: self.tolerance.max_diff_pixels,
            aa_pixels: comparison.aa_pixels,
            max_delta: comparison.max_delta,
            threshold: self.tolerance.threshold,
            actual: actual_path,
            expected: expected_path,
            diff: diff_path,
        })))
    }

    /// Checks `actual` (see [`Snapshot::check`]) and panics with the failure
    /// report if it does not pass.
    #[track_caller]
    pub fn assert_matches(&self, actual: &RgbaImage) {
        if let Err(e) = self.check(actual) {
            panic!("{e}");
        }
    }

    /// Removes artifacts of an earlier failure once the snapshot passes.
    fn remove_stale_artifacts(&self) {
        let _ = std::fs::remove_dir_all(self.artifact_path());
    }
}

/// Saves a PNG, creating its directory first.
fn save_png_creating_dir(path: &Path, image: &RgbaImage) -> Result<(), SnapshotError> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|source| crate::output::OutputError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    }
    Ok(save_png(path, image)?)
}
