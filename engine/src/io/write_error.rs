//! The error of an output file that could not be written.

use std::io;
use std::path::PathBuf;

use thiserror::Error;

/// An output file could not be written; names the file.
#[derive(Debug, Error)]
#[error("cannot write {}: {source}", path.display())]
pub struct WriteError {
    /// The file that was being written (the target, not its partial file).
    pub path: PathBuf,
    /// The underlying I/O error.
    #[source]
    pub source: io::Error,
}
