//! Geometry: rays, boxes, grid rectangles, triangle meshes and the deformable [`HeightGrid`].

mod error;
mod grid_rect;
mod height_grid;
mod tri_mesh;

pub use error::GeomError;
pub use grid_rect::GridRect;
pub use height_grid::{HeightGrid, MAX_GRID_SAMPLES};
pub use tri_mesh::{MeshPart, TriMesh};
