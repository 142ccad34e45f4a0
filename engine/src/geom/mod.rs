//! Geometry: rays, boxes, grid rectangles and the deformable [`HeightGrid`].

mod error;
mod grid_rect;
mod height_grid;

pub use error::GeomError;
pub use grid_rect::GridRect;
pub use height_grid::{HeightGrid, MAX_GRID_SAMPLES};
