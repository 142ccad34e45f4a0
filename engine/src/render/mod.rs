//! Software rendering: a z-buffered triangle rasterizer with perspective-correct
//! colours, a camera, height-grid terrain drawn by patches with level of detail,
//! mesh instances, grass blades and terrain shading that makes footprints readable
//! (Lambert, sky-view ambient occlusion, soft terrain shadows, sun shadows of
//! meshes and grass, fog). `raster` explains how triangles become pixels.
//! Frames go out through [`crate::output`]; overlays, text and plots are
//! drawn on them by [`crate::canvas`].
//!
//! ```
//! use engine::glam::{Vec2, Vec3};
//! use engine::geom::HeightGrid;
//! use engine::render::{
//!     Camera, FrameScene, Lighting, Renderer, TerrainRenderer, TerrainStyle, UniformColor,
//! };
//!
//! let grid = HeightGrid::new(Vec2::ZERO, 0.1, 33, 33, 0.0).unwrap();
//! let lighting = Lighting::default();
//! let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).unwrap();
//! terrain.update(&grid, &UniformColor(Vec3::new(0.7, 0.6, 0.45)), &lighting).unwrap();
//! let scene = FrameScene { terrain: Some(&terrain), lighting, ..FrameScene::new() };
//! let camera = Camera::perspective(1.0, 64, 48, 0.05, 100.0)
//!     .unwrap()
//!     .look_at(Vec3::new(1.6, 2.0, -1.0), Vec3::new(1.6, 0.0, 1.6), Vec3::Y);
//! let image = Renderer::new(64, 48).unwrap().render(&scene, &camera);
//! assert_eq!(image.dimensions(), (64, 48));
//! ```

#![forbid(unsafe_code)]
mod blade_span;
mod camera;
mod error;
mod follow;
mod frame;
mod frame_view;
mod grass;
mod grass_blade;
mod mesh;
pub(crate) mod raster;
mod shade_pyramid;
mod shading;
mod shadow_fit;
mod shadow_map;
mod terrain;
mod terrain_colors;
mod terrain_light;
mod terrain_patch;
#[cfg(test)]
mod test_ground;
mod window_spans;

pub use camera::Camera;
pub use error::RenderError;
pub use follow::CameraFollow;
pub use frame::{FrameScene, FrameStats, Renderer};
pub use grass_blade::GrassBlade;
pub use mesh::MeshInstance;
pub use raster::CullMode;
pub use shading::{Lighting, Sun, encode_display};
pub use terrain::{TerrainRenderer, TerrainStyle};
pub use terrain_colors::{SampleColors, TerrainColors, UniformColor};
