//! A file written beside its target under a fixed hidden name and renamed
//! over the target only when committed.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use super::partial::partial_path;
use super::write_error::WriteError;

/// An output file being written: the bytes go to `.NAME.partial` beside the
/// target; [`AtomicFile::commit`] syncs it and renames it over the target.
/// Dropped without a commit, it removes the partial file and the target is
/// left as it was.
///
/// Creating one first removes a partial file of the same target that a
/// killed process left behind. Two writers of one target at the same time are
/// not supported: the second removes the first one's partial file.
///
/// ```
/// use std::io::Write;
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("notes.txt");
/// let mut file = engine::io::AtomicFile::create(&path)?;
/// file.write_all(b"hello")?;
/// assert!(!path.exists());
/// file.commit()?;
/// assert_eq!(std::fs::read(&path)?, b"hello");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct AtomicFile {
    temp: NamedTempFile,
    target: PathBuf,
}

impl AtomicFile {
    /// Starts writing `target`: checks that it is not a folder, removes a
    /// leftover partial file and creates an empty one.
    pub fn create(target: &Path) -> Result<Self, WriteError> {
        let err = |source| WriteError {
            path: target.to_path_buf(),
            source,
        };
        if target.is_dir() {
            return Err(err(io::Error::new(
                io::ErrorKind::IsADirectory,
                "the path is a folder",
            )));
        }
        let partial = partial_path(target).map_err(err)?;
        match std::fs::remove_file(&partial) {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(err(e)),
        }
        let name = partial.file_name().expect("partial_path names a file");
        let dir = match partial.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let mut builder = tempfile::Builder::new();
        // The whole name is the prefix: no random part, so the name is fixed.
        builder.prefix(name).rand_bytes(0);
        // Outputs get the usual permissions (0666 less the umask), not the
        // owner-only ones of a temporary file.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        let temp = builder.tempfile_in(dir).map_err(err)?;
        Ok(Self {
            temp,
            target: target.to_path_buf(),
        })
    }

    /// The file the bytes end up in.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The partial file being written.
    pub fn partial(&self) -> &Path {
        self.temp.path()
    }

    /// The open partial file, for writers that seek or read back.
    pub fn file_mut(&mut self) -> &mut File {
        self.temp.as_file_mut()
    }

    /// A second handle to the partial file, for encoders that take ownership
    /// of their writer. Everything written through it must be flushed before
    /// [`AtomicFile::commit`].
    pub fn try_clone_file(&self) -> Result<File, WriteError> {
        self.temp
            .as_file()
            .try_clone()
            .map_err(|e| self.io_error(e))
    }

    /// Wraps an I/O error met while writing this file, naming the target.
    pub fn io_error(&self, source: io::Error) -> WriteError {
        WriteError {
            path: self.target.clone(),
            source,
        }
    }

    /// Syncs the partial file to disk and renames it over the target.
    pub fn commit(self) -> Result<(), WriteError> {
        self.temp
            .as_file()
            .sync_all()
            .map_err(|e| self.io_error(e))?;
        let Self { temp, target } = self;
        temp.persist(&target).map_err(|e| WriteError {
            path: target,
            source: e.error,
        })?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.temp.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.temp.write_all(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.temp.flush()
    }
}

#[cfg(test)]
mod tests {
    use std::fs;

    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writes_under_the_fixed_partial_name_until_commit() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("a.gif");
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"GIF").unwrap();
        assert_eq!(names(dir.path()), [".a.gif.partial"]);
        file.commit().unwrap();
        assert_eq!(names(dir.path()), ["a.gif"]);
        assert_eq!(fs::read(&target).unwrap(), b"GIF");
    }

    #[test]
    fn a_leftover_partial_file_is_replaced_and_a_drop_removes_it() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("m.csv");
        fs::write(dir.path().join(".m.csv.partial"), b"killed mid-write").unwrap();
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"new").unwrap();
        drop(file);
        assert!(names(dir.path()).is_empty());
    }

    #[test]
    fn a_folder_in_the_way_is_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("metrics.csv");
        fs::create_dir(&target).unwrap();
        let e = AtomicFile::create(&target).unwrap_err();
        assert_eq!(e.path, target);
        assert!(e.to_string().contains("metrics.csv"), "{e}");
        assert!(e.to_string().contains("folder"), "{e}");
        assert_eq!(names(dir.path()), ["metrics.csv"]);
    }

    #[cfg(unix)]
    #[test]
    fn committed_files_are_not_owner_only() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("x.png");
        AtomicFile::create(&target).unwrap().commit().unwrap();
        let mode = fs::metadata(&target).unwrap().permissions().mode();
        assert_ne!(mode & 0o044, 0, "mode {mode:o}");
    }
}
