//! `softwalk scenes`: list the built-in scenes or dump one as TOML.

use std::io::Write;

use crate::cli::{CliError, ScenesArgs};
use crate::scene::{Scene, builtin_scenes};

/// Lists built-in scenes (`name  description`, names padded to one width), or
/// prints the one named by `--dump` as TOML.
pub fn scenes(args: &ScenesArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if let Some(name) = &args.dump {
        let text = Scene::builtin(name)?.to_toml_string()?;
        return out.write_all(text.as_bytes()).map_err(CliError::Stdout);
    }
    let mut rows = Vec::new();
    for b in builtin_scenes() {
        let scene = Scene::builtin(&b.name)?;
        rows.push((b.name, scene.description));
    }
    let width = rows.iter().map(|(n, _)| n.len()).max().unwrap_or(0);
    for (name, description) in rows {
        writeln!(out, "{name:width$}  {description}").map_err(CliError::Stdout)?;
    }
    Ok(())
}
