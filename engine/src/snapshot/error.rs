//! Why a snapshot check failed.

use std::path::PathBuf;

use thiserror::Error;

use crate::output::OutputError;

/// A snapshot check failed or could not run.
#[derive(Debug, Error)]
pub enum SnapshotError {
    /// The snapshot name cannot be used as a file name.
    #[error("invalid snapshot name {name:?}: use letters, digits, '_' and '-' only")]
    InvalidName {
        /// The rejected name.
        name: String,
    },
    /// No golden exists and the run is on CI, where goldens are never created.
    #[error(
        "snapshot '{name}': golden {golden} is missing (bless to create it: UPDATE_SNAPSHOTS=1 in tests); actual image: {actual}"
    )]
    MissingGolden {
        /// Snapshot name.
        name: String,
        /// Where the golden was expected.
        golden: PathBuf,
        /// Where the actual image was written.
        actual: PathBuf,
    },
    /// The golden could not be read or decoded.
    #[error("snapshot golden {path} cannot be read: {source}")]
    ReadGolden {
        /// The golden file.
        path: PathBuf,
        /// The decoder's error.
        #[source]
        source: image::ImageError,
    },
    /// The images have different sizes.
    #[error(
        "snapshot '{name}': size differs: golden is {expected_width}x{expected_height}, actual is {actual_width}x{actual_height}\n  actual:   {actual}\n  expected: {expected}"
    )]
    SizeMismatch {
        /// Snapshot name.
        name: String,
        /// Golden width.
        expected_width: u32,
        /// Golden height.
        expected_height: u32,
        /// Actual width.
        actual_width: u32,
        /// Actual height.
        actual_height: u32,
        /// The actual image, written for inspection.
        actual: PathBuf,
        /// A copy of the golden.
        expected: PathBuf,
    },
    /// More pixels differ than the tolerance allows.
    #[error(transparent)]
    Mismatch(Box<Mismatch>),
    /// A golden or an artifact could not be written.
    #[error(transparent)]
    Write(#[from] OutputError),
}

/// The report of a snapshot that differs from its golden beyond the tolerance.
#[derive(Debug, Error)]
#[error(
    "snapshot '{name}': {diff_pixels} pixels differ (allowed {allowed}), {aa_pixels} anti-aliased pixels forgiven, max delta {max_delta:.3} (threshold {threshold})\n  actual:   {actual}\n  expected: {expected}\n  diff:     {diff}\n  (bless to accept the actual image: UPDATE_SNAPSHOTS=1 in tests)"
)]
pub struct Mismatch {
    /// Snapshot name.
    pub name: String,
    /// Pixels over the threshold that are not anti-aliasing.
    pub diff_pixels: usize,
    /// The allowed count of differing pixels.
    pub allowed: usize,
    /// Pixels over the threshold forgiven as anti-aliasing.
    pub aa_pixels: usize,
    /// Largest per-pixel delta, on the threshold's 0..=1 scale.
    pub max_delta: f32,
    /// The per-pixel threshold in use.
    pub threshold: f32,
    /// The actual image.
    pub actual: PathBuf,
    /// A copy of the golden.
    pub expected: PathBuf,
    /// The difference image (red: differs, yellow: anti-aliasing forgiven).
    pub diff: PathBuf,
}
