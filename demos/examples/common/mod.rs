//! Helpers shared by the examples (a module folder, so cargo does not build it
//! as an example of its own).

use std::path::PathBuf;

/// The folder an example writes to: the first command-line argument, or
/// `target/examples/<name>/` under the current directory. Created if missing.
pub fn output_dir(name: &str) -> std::io::Result<PathBuf> {
    let dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target").join("examples").join(name));
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}
