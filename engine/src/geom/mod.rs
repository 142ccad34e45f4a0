//! Geometry: rays, boxes, grid rectangles, triangle meshes and the deformable [`HeightGrid`],
//! and BVH ray casts over them ([`GridBvh`], [`MeshBvh`], [`RayScene`]).

mod aabb;
mod binned_bvh;
mod error;
mod grid_bvh;
mod grid_ray;
mod grid_rect;
mod grid_tiling;
mod height_grid;
mod mesh_bvh;
mod prefetch;
mod ray;
mod ray_scene;
mod solid_mass;
mod tri_mesh;
mod triangle;
mod wide_bvh;

pub use aabb::Aabb;
pub use error::GeomError;
pub use grid_bvh::GridBvh;
pub use grid_rect::GridRect;
pub use grid_tiling::GridTiling;
pub use height_grid::{HeightGrid, MAX_GRID_SAMPLES};
pub use mesh_bvh::MeshBvh;
pub use ray::{Hit, HitTarget, MeshId, Ray};
pub use ray_scene::RayScene;
pub use solid_mass::SolidMass;
pub use tri_mesh::{MeshPart, TriMesh};
pub use triangle::ray_triangle;
