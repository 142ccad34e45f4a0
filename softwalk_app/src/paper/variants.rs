//! The reproduction scenes: built-in scenes and variants of them (another
//! material, slope, body or path), so every measured run stays a scene that
//! `softwalk run` could replay.

use softwalk_systems::character::CharacterDesc;
use softwalk_systems::terrain::{GaitResponse, TerrainMaterial};

use super::PaperError;
use crate::scene::{CharacterSpec, PathSpec, Scene, TerrainShape};

/// Name of the material that does not deform: the "rigid ground" of the comparisons.
pub const RIGID: &str = "rigid";

/// A material that does not deform: the "rigid ground" of the comparisons.
pub fn rigid_material() -> TerrainMaterial {
    TerrainMaterial {
        name: RIGID.into(),
        depth: 0.0,
        compression: 1.0,
        smoothness: 0.0,
        repose_deg: 90.0,
        layer: 0.0,
        gait: GaitResponse::NEUTRAL,
    }
}

/// A built-in scene by name.
pub fn builtin(name: &str) -> Result<Scene, PaperError> {
    Scene::builtin(name).map_err(|source| PaperError::Scene {
        scene: name.to_owned(),
        source,
    })
}

/// Checks an edited scene, so a variant is as valid as a scene file.
pub fn checked(scene: Scene) -> Result<Scene, PaperError> {
    scene.validate().map_err(|source| PaperError::Scene {
        scene: scene.name.clone(),
        source,
    })?;
    Ok(scene)
}

/// `scene` with the whole terrain of `material`; `rigid` is added to the scene's materials.
pub fn with_material(mut scene: Scene, material: &str) -> Scene {
    if material == RIGID && !scene.materials.iter().any(|m| m.name == RIGID) {
        scene.materials.push(rigid_material());
    }
    scene.terrain.material = material.to_owned();
    scene.terrain.regions.clear();
    scene
}

/// `scene` on a plane rising `angle_deg` towards +X (flat at 0).
pub fn with_slope(mut scene: Scene, angle_deg: f32) -> Scene {
    scene.terrain.shape = if angle_deg == 0.0 {
        TerrainShape::Flat
    } else {
        TerrainShape::Slope {
            angle_deg,
            direction_deg: 0.0,
        }
    };
    scene
}

/// A walker named `name` with body `body` on `path`.
pub fn walker(name: &str, body: CharacterDesc, controller: bool, path: PathSpec) -> CharacterSpec {
    CharacterSpec {
        name: name.to_owned(),
        controller,
        body,
        path,
        model: crate::scene::HUMAN_MODEL.to_string(),
        bones: Default::default(),
        clip: None,
    }
}

/// A straight walk along +X from `(x, z)` for `length` metres.
pub fn along_x(x: f32, z: f32, length: f32) -> PathSpec {
    PathSpec::Straight {
        start: [x, z],
        heading_deg: 0.0,
        length,
    }
}
