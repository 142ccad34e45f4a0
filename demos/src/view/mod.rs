//! Drawing a simulated world: terrain, characters, grass and debug overlays,
//! through the engine's software renderer. Reads the world, never changes it.

mod overlays;
mod palette;
mod scene_view;

pub use palette::{TerrainPaint, material_albedo};
pub use scene_view::{SceneView, ViewError};
