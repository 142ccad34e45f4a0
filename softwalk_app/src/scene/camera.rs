//! `[camera]`: how frames are framed.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::{finite3, in_range};

/// Largest accepted camera coordinate or offset component, metres.
pub const MAX_CAMERA_COORDINATE: f32 = 100_000.0;

/// Each component of `v` finite and within [`MAX_CAMERA_COORDINATE`] of zero.
fn coordinates(field: &str, v: [f32; 3]) -> Result<(), SceneError> {
    finite3(field, v)?;
    for (k, c) in v.iter().enumerate() {
        in_range(
            &format!("{field}[{k}]"),
            *c,
            -MAX_CAMERA_COORDINATE,
            MAX_CAMERA_COORDINATE,
        )?;
    }
    Ok(())
}

/// The `[camera]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Vertical field of view, degrees, in `[5, 150]`.
    pub fov_deg: f32,
    /// Where the camera is.
    pub mode: CameraMode,
}

/// Camera placement, selected by `kind`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum CameraMode {
    /// Follows a character's centre of mass at a fixed world offset.
    Follow {
        /// The character to follow; none = the first one.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        character: Option<String>,
        /// Eye position relative to the followed point `[x, y, z]`, metres.
        offset: [f32; 3],
    },
    /// A fixed eye looking at a fixed target.
    Fixed {
        /// Eye position `[x, y, z]`.
        eye: [f32; 3],
        /// Point looked at `[x, y, z]`.
        target: [f32; 3],
    },
}

impl Default for CameraSpec {
    fn default() -> Self {
        CameraSpec {
            fov_deg: 50.0,
            mode: CameraMode::Follow {
                character: None,
                offset: [-2.5, 1.6, 3.5],
            },
        }
    }
}

impl CameraSpec {
    /// Checks the camera; `characters` are the scene's character names.
    pub(crate) fn validate(&self, characters: &[&str]) -> Result<(), SceneError> {
        in_range("camera.fov_deg", self.fov_deg, 5.0, 150.0)?;
        match &self.mode {
            CameraMode::Follow { character, offset } => {
                coordinates("camera.mode.offset", *offset)?;
                if offset.iter().all(|c| *c == 0.0) {
                    return Err(SceneError::invalid(
                        "camera.mode.offset",
                        "must not be [0, 0, 0]",
                    ));
                }
                if let Some(name) = character
                    && !characters.contains(&name.as_str())
                {
                    return Err(SceneError::invalid(
                        "camera.mode.character",
                        format!(
                            "no character named \"{name}\" (characters: {})",
                            characters.join(", ")
                        ),
                    ));
                }
            }
            CameraMode::Fixed { eye, target } => {
                coordinates("camera.mode.eye", *eye)?;
                coordinates("camera.mode.target", *target)?;
                if eye == target {
                    return Err(SceneError::invalid(
                        "camera.mode.target",
                        "must differ from camera.mode.eye",
                    ));
                }
            }
        }
        Ok(())
    }
}
