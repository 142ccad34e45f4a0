//! Test scenes shared by the renderer's tests: a bumpy ground, and a square
//! floating above the ground to cast a shadow.

use glam::{Vec2, Vec3};

use super::{Lighting, TerrainRenderer, TerrainStyle, UniformColor};
use crate::geom::{HeightGrid, TriMesh};

/// A bumpy `n` x `n` grid over 4 x 4 m: as a terrain lit by the default
/// lighting, and as one dense mesh of the same heights.
pub(crate) fn ground(n: usize) -> (TerrainRenderer, TriMesh) {
    let grid = HeightGrid::from_fn(Vec2::splat(-2.0), 4.0 / (n - 1) as f32, n, n, |x, z| {
        0.2 * (x * 1.7).sin() * (z * 1.3).cos() + 0.02 * (x * 9.0 + z * 7.0).sin()
    })
    .unwrap();
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).unwrap();
    terrain
        .update(
            &grid,
            &UniformColor(Vec3::new(0.6, 0.5, 0.35)),
            &Lighting::default(),
        )
        .unwrap();
    (terrain, grid.to_tri_mesh())
}

/// The two triangles of a 1 m square floating 1 m above the ground,
/// centred over the origin, facing down.
pub(crate) fn floating_square() -> Vec<[Vec3; 3]> {
    let corner = |x: f32, z: f32| Vec3::new(x, 1.0, z);
    let (a, b, c, d) = (
        corner(-0.5, -0.5),
        corner(0.5, -0.5),
        corner(0.5, 0.5),
        corner(-0.5, 0.5),
    );
    vec![[a, c, b], [a, d, c]]
}
