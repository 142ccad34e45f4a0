//! A window of the terrain copied into contiguous local buffers with a
//! one-sample frame, so the smoothing and settling loops run on small dense
//! arrays without bounds tests and write back once. A patch belongs to the
//! stage's scratch ([`super::SmoothScratch`], [`super::SettleScratch`]) and is
//! reused from call to call (not reallocated once it has grown to the largest
//! window).

use engine::geom::GridRect;

use super::heightfield::{Heightfield, TerrainParts};

/// Flag of a sample that is disturbed (its edges may move).
pub(crate) const DISTURBED: u8 = 1;
/// Flag of a sample that never moves: held by a sole this step, or the frame
/// around the window (outside it, or off the grid).
pub(crate) const FIXED: u8 = 2;

/// True when the edge between samples of flags `a` and `b` may carry
/// material: one end disturbed, neither end fixed.
#[inline(always)]
pub(crate) fn edge_moves(a: u8, b: u8) -> bool {
    (a | b) & (DISTURBED | FIXED) == DISTURBED
}

/// Heights, trodden marks, flags and material ids of one window plus a
/// one-sample frame of [`FIXED`] samples, indexed
/// `(j - j0 + 1) * stride + (i - i0 + 1)` (see [`Patch::local`]).
#[derive(Default, Clone)]
pub(crate) struct Patch {
    /// The window, in grid samples (non-empty, inside the grid).
    pub rect: GridRect,
    /// Samples per local row: the window width plus the frame.
    pub stride: usize,
    pub heights: Vec<f32>,
    /// Firm floor per sample ([`super::Heightfield::firm_floor`]; the frame's
    /// equals its height 0, so it has nothing to give).
    pub floor: Vec<f32>,
    pub disturbed: Vec<u8>,
    /// [`DISTURBED`] and [`FIXED`] bits, plus bits of the stage's own.
    pub flags: Vec<u8>,
    pub material: Vec<u8>,
}

impl Patch {
    /// Copies `rect` (non-empty, inside the grid) out of the terrain, framed,
    /// reusing the buffers.
    pub fn load(&mut self, hf: &Heightfield, rect: GridRect) {
        let nx = hf.grid().nx();
        let (heights, disturbed, material) =
            (hf.grid().heights(), hf.disturbed(), hf.material_map());
        let stride = rect.width() + 2;
        let len = stride * (rect.height() + 2);
        self.rect = rect;
        self.stride = stride;
        for (buf, fill) in [(&mut self.disturbed, 0u8), (&mut self.material, 0)] {
            buf.clear();
            buf.resize(len, fill);
        }
        self.flags.clear();
        self.flags.resize(len, FIXED);
        for buf in [&mut self.heights, &mut self.floor] {
            buf.clear();
            buf.resize(len, 0.0);
        }
        for (r, j) in (rect.j0..rect.j1).enumerate() {
            let grid = j * nx + rect.i0..j * nx + rect.i1;
            let local = (r + 1) * stride + 1..(r + 2) * stride - 1;
            self.heights[local.clone()].copy_from_slice(&heights[grid.clone()]);
            self.disturbed[local.clone()].copy_from_slice(&disturbed[grid.clone()]);
            self.material[local.clone()].copy_from_slice(&material[grid.clone()]);
            for (f, k) in self.floor[local.clone()].iter_mut().zip(grid) {
                *f = hf.firm_floor(k);
            }
            for (f, &d) in self.flags[local.clone()]
                .iter_mut()
                .zip(&self.disturbed[local])
            {
                *f = u8::from(d != 0) * DISTURBED;
            }
        }
        for k in hf.changes().held.near(rect) {
            let (i, j) = (k % nx, k / nx);
            if rect.contains(i, j) {
                let l = self.local(i, j);
                self.flags[l] = FIXED;
            }
        }
    }

    /// Local index of grid sample `(i, j)` (inside the window or its frame).
    #[inline]
    pub fn local(&self, i: usize, j: usize) -> usize {
        (j + 1 - self.rect.j0) * self.stride + (i + 1 - self.rect.i0)
    }

    /// Grid index (row-major in a grid `nx` wide) of local sample `l` of the window.
    #[inline]
    pub fn grid_index(&self, l: usize, nx: usize) -> usize {
        let (r, c) = (l / self.stride, l % self.stride);
        (self.rect.j0 + r - 1) * nx + self.rect.i0 + c - 1
    }

    /// Local index of the first window sample of window row `r` (0-based).
    #[inline]
    pub fn row_start(&self, r: usize) -> usize {
        (r + 1) * self.stride + 1
    }

    /// Writes the heights and trodden marks of the grid rectangle `rect`
    /// (inside the window) back into the terrain.
    pub fn store(&self, parts: &mut TerrainParts<'_>, rect: GridRect) {
        let nx = parts.nx;
        for j in rect.j0..rect.j1 {
            let grid = j * nx + rect.i0..j * nx + rect.i1;
            let l = self.local(rect.i0, j);
            let local = l..l + rect.width();
            parts.heights[grid.clone()].copy_from_slice(&self.heights[local.clone()]);
            parts.disturbed[grid].copy_from_slice(&self.disturbed[local]);
        }
    }

    /// The bounding rectangle (grid samples) of the window samples for which
    /// `pick(local index)` is true, or empty.
    pub fn bounds_of(&self, mut pick: impl FnMut(usize) -> bool) -> GridRect {
        let mut found = GridRect::EMPTY;
        for r in 0..self.rect.height() {
            let start = self.row_start(r);
            let mut first = None;
            let mut last = 0;
            for c in 0..self.rect.width() {
                if pick(start + c) {
                    first.get_or_insert(c);
                    last = c;
                }
            }
            if let Some(first) = first {
                let (i0, j0) = (self.rect.i0 + first, self.rect.j0 + r);
                found = found.union(&GridRect::new(i0, j0, self.rect.i0 + last + 1, j0 + 1));
            }
        }
        found
    }
}
