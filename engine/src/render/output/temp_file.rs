//! A temporary file that becomes the target file only when committed.

use std::fs::{self, File};
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::OutputError;

/// Counter that keeps temporary names unique within the process.
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// A file being written beside `target`; renamed over it by [`TempFile::commit`],
/// removed on drop otherwise.
pub(crate) struct TempFile {
    target: PathBuf,
    temp: PathBuf,
    file: Option<File>,
    committed: bool,
}

impl TempFile {
    /// Creates an empty temporary file in the directory of `target`.
    pub(crate) fn create(target: &Path) -> Result<Self, OutputError> {
        let io_err = |source| OutputError::Io {
            path: target.to_path_buf(),
            source,
        };
        let name = target.file_name().ok_or_else(|| {
            io_err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "the path has no file name",
            ))
        })?;
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let temp = dir.join(format!(
            ".{}.tmp{}-{}",
            name.to_string_lossy(),
            std::process::id(),
            NEXT_ID.fetch_add(1, Ordering::Relaxed)
        ));
        let file = fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create_new(true)
            .open(&temp)
            .map_err(io_err)?;
        Ok(Self {
            target: target.to_path_buf(),
            temp,
            file: Some(file),
            committed: false,
        })
    }

    /// The final path of the file.
    pub(crate) fn target(&self) -> &Path {
        &self.target
    }

    /// The open file handle.
    pub(crate) fn file(&mut self) -> &mut File {
        self.file.as_mut().expect("the file is open until commit")
    }

    /// A buffered writer on a second handle to the same file, for encoders
    /// that take ownership of their writer.
    pub(crate) fn buffered_clone(&self) -> Result<BufWriter<File>, OutputError> {
        let file = self
            .file
            .as_ref()
            .expect("the file is open until commit")
            .try_clone()
            .map_err(|e| self.io_error(e))?;
        Ok(BufWriter::with_capacity(1 << 16, file))
    }

    /// Wraps an I/O error with the target path.
    pub(crate) fn io_error(&self, source: io::Error) -> OutputError {
        OutputError::Io {
            path: self.target.clone(),
            source,
        }
    }

    /// Syncs the file to disk and renames it over the target.
    pub(crate) fn commit(mut self) -> Result<(), OutputError> {
        let file = self.file.take().expect("the file is open until commit");
        let result = file.sync_all().and_then(|()| {
            drop(file);
            fs::rename(&self.temp, &self.target)
        });
        match result {
            Ok(()) => {
                self.committed = true;
                Ok(())
            }
            Err(e) => Err(self.io_error(e)),
        }
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if !self.committed {
            self.file = None;
            let _ = fs::remove_file(&self.temp);
        }
    }
}
