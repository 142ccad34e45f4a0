//! The output files of a run, checked before the run starts: a path that
//! cannot be written is reported then, not after the whole run.

use std::fs;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// An output file's path cannot be written.
#[derive(Debug, Error)]
#[error("output file \"{}\" {problem}", path.display())]
pub struct OutputFileError {
    /// The file.
    pub path: PathBuf,
    /// What is wrong (e.g. "is a folder").
    pub problem: String,
    /// The underlying I/O error, when there is one.
    #[source]
    pub source: Option<std::io::Error>,
}

/// Checks that each of `files` can be written: it is not a folder, and its
/// partial file (`.NAME.partial`, where it is written first) can be created
/// beside it. Leaves nothing behind.
pub fn check_output_files<'a>(
    files: impl IntoIterator<Item = &'a Path>,
) -> Result<(), OutputFileError> {
    for path in files {
        let fail = |problem: &str, source| OutputFileError {
            path: path.to_path_buf(),
            problem: problem.to_owned(),
            source,
        };
        if path.is_dir() {
            return Err(fail("is a folder", None));
        }
        let partial =
            engine::io::partial_path(path).map_err(|e| fail("has no file name", Some(e)))?;
        fs::write(&partial, b"").map_err(|e| fail("cannot be written", Some(e)))?;
        fs::remove_file(&partial).map_err(|e| fail("cannot be written", Some(e)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_in_place_of_a_file_is_named() {
        let tmp = tempfile::tempdir().unwrap();
        let ok = tmp.path().join("summary.json");
        let folder = tmp.path().join("metrics.csv");
        fs::create_dir(&folder).unwrap();
        check_output_files([ok.as_path()]).unwrap();
        let e = check_output_files([ok.as_path(), folder.as_path()]).unwrap_err();
        assert_eq!(e.path, folder);
        assert!(e.to_string().contains("metrics.csv\" is a folder"), "{e}");
        assert_eq!(fs::read_dir(tmp.path()).unwrap().count(), 1);
    }
}
