//! The output folder: created if missing, swept of the partial files a killed
//! run left, and checked for writability before any work.

use std::fs;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// The output folder cannot be used.
#[derive(Debug, Error)]
#[error("output folder \"{}\" {problem}", path.display())]
pub struct OutputDirError {
    /// The folder.
    pub path: PathBuf,
    /// What is wrong (e.g. "cannot be created").
    pub problem: String,
    /// The underlying I/O error.
    #[source]
    pub source: std::io::Error,
}

/// Creates `dir` (and its parents) if missing, removes the partial files
/// (`.NAME.partial`) a killed run left in it, and proves it writable by
/// creating and removing a probe file (itself named as a partial file, so a
/// kill between the two leaves nothing the next sweep misses). Returns the folder.
pub fn prepare_output_dir(dir: &Path) -> Result<PathBuf, OutputDirError> {
    let fail = |problem: &str, source| OutputDirError {
        path: dir.to_path_buf(),
        problem: problem.to_owned(),
        source,
    };
    fs::create_dir_all(dir).map_err(|e| fail("cannot be created", e))?;
    remove_partial_files(dir)?;
    let probe = dir.join(".softwalk-write-probe.partial");
    fs::write(&probe, b"probe").map_err(|e| fail("is not writable", e))?;
    fs::remove_file(&probe).map_err(|e| fail("is not writable", e))?;
    Ok(dir.to_path_buf())
}

/// Removes the partial files (`.NAME.partial`) a killed run left directly in
/// `dir`, if it exists, without creating it.
pub fn remove_partial_files(dir: &Path) -> Result<(), OutputDirError> {
    engine::io::remove_partials(dir)
        .map(|_| ())
        .map_err(|source| OutputDirError {
            path: dir.to_path_buf(),
            problem: "cannot be cleaned of partial files".to_owned(),
            source,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn creates_nested_folders_and_leaves_no_probe() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("a/b");
        prepare_output_dir(&dir).unwrap();
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 0);
    }

    #[test]
    fn partial_files_left_by_a_killed_run_are_removed() {
        let tmp = tempfile::tempdir().unwrap();
        for name in [
            ".metrics.csv.partial",
            ".animation.gif.tmp7637-0",
            "keep.csv",
        ] {
            fs::write(tmp.path().join(name), "x").unwrap();
        }
        prepare_output_dir(tmp.path()).unwrap();
        let left: Vec<_> = fs::read_dir(tmp.path()).unwrap().collect();
        assert_eq!(left.len(), 1);
    }

    #[test]
    fn a_folder_under_a_file_is_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("file");
        fs::write(&file, "x").unwrap();
        let e = prepare_output_dir(&file.join("out")).unwrap_err();
        assert!(e.to_string().contains("cannot be created"), "{e}");
    }
}
