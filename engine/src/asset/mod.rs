//! Assets in and out: OBJ meshes (through tobj) and grayscale PNG heightmaps.
//!
//! Every loader returns an [`AssetError`] naming the file and the reason, never
//! panics; every writer goes through [`crate::io::write_atomic`], so an output
//! file is written whole or not at all.

#![forbid(unsafe_code)]

mod error;
mod heightmap;
mod obj;

pub use error::AssetError;
pub use heightmap::{HeightmapInfo, load_heightmap, load_heightmap_restored, save_heightmap_png16};
pub use obj::{load_obj, load_obj_from_str, save_grid_obj, save_obj};
