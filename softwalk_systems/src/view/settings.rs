//! How a [`super::WorldView`] draws: frame size, lens, threads, light, extras.

use engine::render::{Lighting, TerrainStyle};

/// The settings of a [`super::WorldView`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewSettings {
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
    /// Vertical field of view, degrees.
    pub fov_deg: f32,
    /// Worker threads drawing a frame (frames are the same for any number).
    pub threads: usize,
    /// Sun, sky and fog.
    pub lighting: Lighting,
    /// How the ground is cut, levelled and shaded.
    pub terrain: TerrainStyle,
    /// Whether characters, props and grass cast sun shadows.
    pub shadows: bool,
    /// Whether the debug overlays (centre of mass, support, rays, platforms)
    /// are drawn over the frame.
    pub overlays: bool,
}

impl Default for ViewSettings {
    /// 960 x 540, 50 degrees, one thread, default light, shadows, no overlays.
    fn default() -> Self {
        ViewSettings {
            width: 960,
            height: 540,
            fov_deg: 50.0,
            threads: 1,
            lighting: Lighting::default(),
            terrain: TerrainStyle::default(),
            shadows: true,
            overlays: false,
        }
    }
}
