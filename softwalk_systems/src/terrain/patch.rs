//! A window of the terrain copied into contiguous local buffers, so the
//! smoothing and settling loops run on small dense arrays and write back once.

use engine::geom::GridRect;

use super::heightfield::{TerrainParts, held_mask};

/// Heights, trodden marks, held flags and material ids of one window,
/// indexed `(j - j0) * width + (i - i0)`.
pub(crate) struct Patch {
    pub rect: GridRect,
    pub width: usize,
    pub heights: Vec<f32>,
    pub disturbed: Vec<u8>,
    pub held: Vec<bool>,
    pub material: Vec<u8>,
}

impl Patch {
    /// Copies `rect` (non-empty, inside the grid) out of the terrain.
    pub fn load(parts: &TerrainParts<'_>, rect: GridRect) -> Self {
        let (nx, width) = (parts.nx, rect.width());
        let mut heights = Vec::with_capacity(rect.area());
        let mut disturbed = Vec::with_capacity(rect.area());
        let mut material = Vec::with_capacity(rect.area());
        for j in rect.j0..rect.j1 {
            let row = j * nx + rect.i0..j * nx + rect.i1;
            heights.extend_from_slice(&parts.heights[row.clone()]);
            disturbed.extend_from_slice(&parts.disturbed[row.clone()]);
            material.extend_from_slice(&parts.material[row]);
        }
        Patch {
            rect,
            width,
            heights,
            disturbed,
            held: held_mask(&parts.changes.held, nx, rect).into_vec(),
            material,
        }
    }

    /// Writes heights and trodden marks back into the terrain.
    pub fn store(&self, parts: &mut TerrainParts<'_>) {
        let (nx, w) = (parts.nx, self.width);
        for (r, j) in (self.rect.j0..self.rect.j1).enumerate() {
            let row = j * nx + self.rect.i0..j * nx + self.rect.i1;
            parts.heights[row.clone()].copy_from_slice(&self.heights[r * w..(r + 1) * w]);
            parts.disturbed[row].copy_from_slice(&self.disturbed[r * w..(r + 1) * w]);
        }
    }

    /// The grid rectangle of local rectangle `local` (local column/row ranges).
    pub fn to_grid(&self, local: GridRect) -> GridRect {
        if local.is_empty() {
            return GridRect::EMPTY;
        }
        GridRect::new(
            local.i0 + self.rect.i0,
            local.j0 + self.rect.j0,
            local.i1 + self.rect.i0,
            local.j1 + self.rect.j0,
        )
    }
}
