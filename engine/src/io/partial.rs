//! The hidden `.NAME.partial` file an output is written into before it is
//! renamed into place, and the sweep that removes ones a killed process left.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// Suffix of a partial file: `.NAME.partial` for the target `NAME`.
const SUFFIX: &str = ".partial";

/// The partial file of `target`: `.NAME.partial` in the same folder (the
/// current folder for a bare file name). Fails when `target` has no file name.
///
/// ```
/// use std::path::Path;
/// let p = engine::io::partial_path(Path::new("out/metrics.csv")).unwrap();
/// assert_eq!(p, Path::new("out/.metrics.csv.partial"));
/// ```
pub fn partial_path(target: &Path) -> io::Result<PathBuf> {
    let name = target
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"))?;
    let mut partial = std::ffi::OsString::from(".");
    partial.push(name);
    partial.push(SUFFIX);
    Ok(target.with_file_name(partial))
}

/// True for the names of leftover partial files: `.NAME.partial`, and the
/// `.NAME.tmpPID` / `.NAME.tmpPID-N` names that earlier versions used.
fn is_partial_name(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('.') else {
        return false;
    };
    if rest.len() > SUFFIX.len() && rest.ends_with(SUFFIX) {
        return true;
    }
    // Earlier versions: `.NAME.tmp<pid>` or `.NAME.tmp<pid>-<n>`.
    rest.rsplit_once(".tmp").is_some_and(|(stem, id)| {
        !stem.is_empty()
            && id.split('-').count() <= 2
            && id
                .split('-')
                .all(|part| !part.is_empty() && part.bytes().all(|b| b.is_ascii_digit()))
    })
}

/// Removes the leftover partial files directly in `dir` (not in sub-folders)
/// and returns how many it removed. A missing folder has none.
pub fn remove_partials(dir: &Path) -> io::Result<usize> {
    let entries = match fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    let mut removed = 0;
    for entry in entries {
        let entry = entry?;
        let is_partial = entry.file_name().to_str().is_some_and(is_partial_name);
        if is_partial && entry.file_type()?.is_file() {
            match fs::remove_file(entry.path()) {
                Ok(()) => removed += 1,
                Err(e) if e.kind() == io::ErrorKind::NotFound => {}
                Err(e) => return Err(e),
            }
        }
    }
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partial_names_are_recognised() {
        for name in [
            ".metrics.csv.partial",
            ".frame_000012.png.partial",
            ".animation.gif.tmp7637-0",
            ".metrics.csv.tmp12",
        ] {
            assert!(is_partial_name(name), "{name}");
        }
        for name in [
            "metrics.csv",
            ".partial",
            ".gitignore",
            ".a.tmp",
            ".a.tmpx1",
            ".a.tmp1-2-3",
            "a.partial",
        ] {
            assert!(!is_partial_name(name), "{name}");
        }
    }

    #[test]
    fn sweep_removes_only_partial_files() {
        let dir = tempfile::tempdir().unwrap();
        for name in [".a.png.partial", ".b.gif.tmp99-1", "keep.png", ".keep"] {
            fs::write(dir.path().join(name), b"x").unwrap();
        }
        fs::create_dir(dir.path().join(".folder.partial")).unwrap();
        assert_eq!(remove_partials(dir.path()).unwrap(), 2);
        let mut left: Vec<String> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(left, [".folder.partial", ".keep", "keep.png"]);
        assert_eq!(remove_partials(&dir.path().join("missing")).unwrap(), 0);
    }
}
