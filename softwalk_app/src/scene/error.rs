//! The typed error for everything that can be wrong with a scene.

use std::path::PathBuf;

use softwalk_systems::sim::SimError;
use thiserror::Error;

/// A scene could not be read, parsed or validated.
///
/// Every variant names the offending field as a dotted path with array
/// indices (`characters[1].alpha`), so a message points at one place.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The TOML text is malformed, a field is missing, has the wrong type or is unknown.
    #[error("{field}: {message} (line {line}, column {column})")]
    Syntax {
        /// The table or key the parser stopped at (`terrain.size_x`), or `<root>`.
        field: String,
        /// The parser's explanation.
        message: String,
        /// 1-based line of the problem.
        line: usize,
        /// 1-based column of the problem.
        column: usize,
    },
    /// A value is out of range, NaN, empty or inconsistent with another field.
    #[error("{field}: {problem}")]
    Invalid {
        /// The offending field.
        field: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A material name is neither built in nor defined under `[[materials]]`.
    #[error("{field}: unknown material \"{name}\" (known: {known})")]
    UnknownMaterial {
        /// The field that names the material.
        field: String,
        /// The unknown name.
        name: String,
        /// The known names, comma separated.
        known: String,
    },
    /// A file the scene refers to does not exist.
    #[error("{field}: file \"{}\" does not exist", path.display())]
    MissingFile {
        /// The field holding the path.
        field: String,
        /// The path as resolved against the scene's folder.
        path: PathBuf,
    },
    /// A file the scene refers to exists but cannot be used.
    #[error("{field}: cannot use \"{}\": {reason}", path.display())]
    BadFile {
        /// The field holding the path.
        field: String,
        /// The path as resolved against the scene's folder.
        path: PathBuf,
        /// Why it cannot be used.
        reason: String,
    },
    /// The scene file itself cannot be read.
    #[error("cannot read scene file \"{}\": {source}", path.display())]
    Read {
        /// The scene file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The scene path is not a regular file (a folder, a FIFO, a device).
    #[error("scene file \"{}\" is not a regular file", path.display())]
    NotAFile {
        /// The scene path.
        path: PathBuf,
    },
    /// The scene file is larger than any scene needs.
    #[error("scene file \"{}\" is {bytes} bytes, more than the limit {}", path.display(), super::MAX_SCENE_FILE_BYTES)]
    FileTooLarge {
        /// The scene path.
        path: PathBuf,
        /// Its size.
        bytes: u64,
    },
    /// An error inside a scene file, with the file named.
    #[error("scene file \"{}\": {error}", path.display())]
    InFile {
        /// The scene file.
        path: PathBuf,
        /// The error found in it.
        error: Box<SceneError>,
    },
    /// An error on a field, with the line of the scene text the field is on
    /// (or, for a field left to its default, the line of its table).
    #[error("{error} (line {line})")]
    AtLine {
        /// 1-based line.
        line: usize,
        /// The error on the field.
        error: Box<SceneError>,
    },
    /// No built-in scene has this name.
    #[error("unknown scene \"{name}\": neither a built-in scene ({known}) nor an existing file")]
    UnknownBuiltin {
        /// The name asked for.
        name: String,
        /// The built-in names, comma separated.
        known: String,
    },
    /// A valid scene could not be turned into a simulation; `part` names the
    /// scene part that failed (`terrain`, `grass[0]`, `characters[1]`, `sim`).
    #[error("{part}: {source}")]
    Setup {
        /// The scene part.
        part: String,
        /// The simulation's refusal.
        #[source]
        source: SimError,
    },
    /// The scene could not be written back to TOML.
    #[error("cannot write the scene as TOML: {0}")]
    Serialize(String),
}

impl SceneError {
    /// An [`SceneError::Invalid`] for `field`.
    pub fn invalid(field: impl Into<String>, problem: impl Into<String>) -> Self {
        SceneError::Invalid {
            field: field.into(),
            problem: problem.into(),
        }
    }

    /// The innermost error, looking through [`SceneError::InFile`].
    pub fn innermost(&self) -> &SceneError {
        match self {
            SceneError::InFile { error, .. } | SceneError::AtLine { error, .. } => {
                error.innermost()
            }
            other => other,
        }
    }

    /// The line of the scene text the error is on, when known.
    pub fn line(&self) -> Option<usize> {
        match self {
            SceneError::InFile { error, .. } => error.line(),
            SceneError::AtLine { line, .. } | SceneError::Syntax { line, .. } => Some(*line),
            _ => None,
        }
    }

    /// The field this error names, if it names one.
    pub fn field(&self) -> Option<&str> {
        match self.innermost() {
            SceneError::Syntax { field, .. }
            | SceneError::Invalid { field, .. }
            | SceneError::UnknownMaterial { field, .. }
            | SceneError::MissingFile { field, .. }
            | SceneError::BadFile { field, .. }
            | SceneError::Setup { part: field, .. } => Some(field),
            _ => None,
        }
    }
}
