//! Finds the scene a command names: a built-in name or a TOML file.

use std::path::Path;

use crate::scene::{BuiltinScene, Scene, SceneError};

/// A built-in scene when `name` is one; otherwise a scene file when `name` looks
/// like a path (ends in `.toml`, contains a separator, or exists); otherwise an
/// error listing the built-in names.
pub fn resolve_scene(name: &str) -> Result<Scene, SceneError> {
    if let Ok(builtin) = BuiltinScene::find(name) {
        return Scene::from_toml_str(&builtin.toml, Path::new(""));
    }
    let path = Path::new(name);
    let looks_like_path =
        name.ends_with(".toml") || name.contains(std::path::MAIN_SEPARATOR) || name.contains('/');
    if looks_like_path || path.exists() {
        return Scene::load(path);
    }
    Err(BuiltinScene::find(name).unwrap_err())
}
