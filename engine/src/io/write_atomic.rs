//! Writing a whole file in one call through an [`AtomicFile`].

use std::io::{self, BufWriter, Write};
use std::path::Path;

use super::atomic_file::AtomicFile;
use super::write_error::WriteError;

/// Writes a file atomically: `fill` writes (buffered) into the partial file
/// beside `path`, which is renamed over `path` only if `fill` succeeds. On any
/// failure the partial file is removed and `path` is left as it was.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), WriteError> {
    let mut file = AtomicFile::create(path)?;
    let result = {
        let mut writer = BufWriter::new(&mut file);
        fill(&mut writer).and_then(|()| writer.flush())
    };
    result.map_err(|e| file.io_error(e))?;
    file.commit()
}

/// Writes `bytes` to `path` atomically (see [`write_atomic`]).
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomic(path, |w| w.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use std::fs;

    use super::*;

    #[test]
    fn failure_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        write_bytes_atomic(&path, b"first").unwrap();
        let r = write_atomic(&path, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("boom"))
        });
        assert!(r.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"first");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn unwritable_directory_is_an_error() {
        let r = write_bytes_atomic(Path::new("/nonexistent-dir/x.png"), b"x");
        assert!(r.unwrap_err().to_string().contains("nonexistent-dir"));
    }
}
