//! A bumpy test ground shared by the renderer's whole-frame tests.

use glam::Vec2;

use crate::geom::{HeightGrid, TriMesh};

/// A bumpy `n` x `n` grid over 4 x 4 m and the same heights as one dense mesh.
pub(crate) fn ground(n: usize) -> (HeightGrid, TriMesh) {
    let grid = HeightGrid::from_fn(Vec2::splat(-2.0), 4.0 / (n - 1) as f32, n, n, |x, z| {
        0.2 * (x * 1.7).sin() * (z * 1.3).cos() + 0.02 * (x * 9.0 + z * 7.0).sin()
    })
    .unwrap();
    let mesh = grid.to_tri_mesh();
    (grid, mesh)
}
