//! The camera and settings a scene file chooses for its [`WorldView`].

use engine::ecs::{Entity, World};
use softwalk_systems::view::{CameraRig, ViewError, ViewSettings, WorldView};

use crate::scene::{CameraMode, Scene};

/// A view of `world` (built from `scene`; `walkers` in scene order) through
/// the scene's camera, drawing `width` x `height` frames with `threads`
/// worker threads and the scene's overlays setting.
pub fn scene_view(
    scene: &Scene,
    world: &World,
    walkers: &[Entity],
    width: u32,
    height: u32,
    threads: usize,
) -> Result<WorldView, ViewError> {
    let settings = ViewSettings {
        width,
        height,
        fov_deg: scene.camera.fov_deg,
        threads,
        overlays: scene.render.overlays,
        ..ViewSettings::default()
    };
    WorldView::new(world, camera_rig(scene, walkers), &settings)
}

/// The scene's camera: fixed, or following its named character (the first
/// one when unnamed or unknown).
fn camera_rig(scene: &Scene, walkers: &[Entity]) -> CameraRig {
    match &scene.camera.mode {
        CameraMode::Fixed { eye, target } => CameraRig::fixed(*eye, *target),
        CameraMode::Follow { character, offset } => {
            let index = character
                .as_ref()
                .and_then(|name| scene.characters.iter().position(|c| &c.name == name))
                .unwrap_or(0);
            match walkers.get(index) {
                Some(&walker) => CameraRig::follow(walker, *offset),
                None => CameraRig::fixed([0.0, 2.0, -3.0], [0.0, 0.0, 0.0]),
            }
        }
    }
}
