use glam::{Vec2, Vec3};

use super::{GeomError, GridRect};

/// The largest number of samples a [`HeightGrid`] may hold (8192², 256 MiB of `f32`).
/// Larger requests are refused before anything is allocated.
pub const MAX_GRID_SAMPLES: usize = 8192 * 8192;

/// Heights on a regular grid in the XZ plane (Y up).
///
/// Sample `(i, j)` sits at `x = origin.x + i * cell`, `z = origin.y + j * cell`
/// and is stored at `heights[j * nx + i]`.
///
/// The surface is triangulated per cell with the diagonal from `(i, j)` to
/// `(i + 1, j + 1)`: [`HeightGrid::height_at`] and ray casts see that exact
/// surface; [`HeightGrid::height_bilinear`] gives the smooth bilinear height.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    origin: Vec2,
    cell: f32,
    nx: usize,
    nz: usize,
    heights: Vec<f32>,
}

impl HeightGrid {
    /// A grid of `nx` x `nz` samples, `cell` metres apart, every height `fill`.
    ///
    /// Refuses fewer than 2 samples per side, a non-finite or non-positive cell
    /// size, a non-finite origin or fill, and grids above [`MAX_GRID_SAMPLES`].
    pub fn new(
        origin: Vec2,
        cell: f32,
        nx: usize,
        nz: usize,
        fill: f32,
    ) -> Result<Self, GeomError> {
        Self::validate(origin, cell, nx, nz)?;
        if !fill.is_finite() {
            return Err(GeomError::InvalidParameter {
                name: "fill",
                reason: format!("{fill} is not finite"),
            });
        }
        Ok(HeightGrid {
            origin,
            cell,
            nx,
            nz,
            heights: vec![fill; nx * nz],
        })
    }

    /// A grid whose height at each sample is `f(x, z)` in world coordinates.
    pub fn from_fn(
        origin: Vec2,
        cell: f32,
        nx: usize,
        nz: usize,
        mut f: impl FnMut(f32, f32) -> f32,
    ) -> Result<Self, GeomError> {
        Self::validate(origin, cell, nx, nz)?;
        let mut heights = Vec::with_capacity(nx * nz);
        for j in 0..nz {
            for i in 0..nx {
                let h = f(origin.x + i as f32 * cell, origin.y + j as f32 * cell);
                if !h.is_finite() {
                    return Err(GeomError::InvalidParameter {
                        name: "height",
                        reason: format!("sample ({i}, {j}) is {h}"),
                    });
                }
                heights.push(h);
            }
        }
        Ok(HeightGrid {
            origin,
            cell,
            nx,
            nz,
            heights,
        })
    }

    /// A grid over existing heights (row-major, `nx * nz` values, all finite).
    pub fn from_heights(
        origin: Vec2,
        cell: f32,
        nx: usize,
        nz: usize,
        heights: Vec<f32>,
    ) -> Result<Self, GeomError> {
        Self::validate(origin, cell, nx, nz)?;
        if heights.len() != nx * nz {
            return Err(GeomError::InvalidParameter {
                name: "heights",
                reason: format!("{} values for a {nx} x {nz} grid", heights.len()),
            });
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(GeomError::InvalidParameter {
                name: "heights",
                reason: format!("sample ({}, {}) is {}", k % nx, k / nx, heights[k]),
            });
        }
        Ok(HeightGrid {
            origin,
            cell,
            nx,
            nz,
            heights,
        })
    }

    fn validate(origin: Vec2, cell: f32, nx: usize, nz: usize) -> Result<(), GeomError> {
        if !(cell.is_finite() && cell > 0.0) {
            return Err(GeomError::InvalidParameter {
                name: "cell",
                reason: format!("{cell} must be finite and > 0"),
            });
        }
        if !origin.is_finite() {
            return Err(GeomError::InvalidParameter {
                name: "origin",
                reason: format!("{origin} is not finite"),
            });
        }
        if nx < 2 || nz < 2 {
            return Err(GeomError::InvalidParameter {
                name: "resolution",
                reason: format!("{nx} x {nz}: need at least 2 x 2 samples"),
            });
        }
        if nx.checked_mul(nz).is_none_or(|n| n > MAX_GRID_SAMPLES) {
            return Err(GeomError::GridTooLarge {
                nx,
                nz,
                limit: MAX_GRID_SAMPLES,
            });
        }
        Ok(())
    }

    /// World XZ position of sample `(0, 0)`.
    pub fn origin(&self) -> Vec2 {
        self.origin
    }

    /// Distance between neighbouring samples, in metres.
    pub fn cell_size(&self) -> f32 {
        self.cell
    }

    /// Samples along X.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Samples along Z.
    pub fn nz(&self) -> usize {
        self.nz
    }

    /// World XZ size covered by the samples.
    pub fn extent(&self) -> Vec2 {
        Vec2::new(
            (self.nx - 1) as f32 * self.cell,
            (self.nz - 1) as f32 * self.cell,
        )
    }

    /// The whole grid as a rectangle.
    pub fn full_rect(&self) -> GridRect {
        GridRect::new(0, 0, self.nx, self.nz)
    }

    /// Row-major index of sample `(i, j)`.
    #[inline]
    pub fn index(&self, i: usize, j: usize) -> usize {
        debug_assert!(i < self.nx && j < self.nz);
        j * self.nx + i
    }

    /// Height of sample `(i, j)`. Panics when out of range, like slice indexing.
    #[inline]
    pub fn height(&self, i: usize, j: usize) -> f32 {
        self.heights[j * self.nx + i]
    }

    /// Sets the height of sample `(i, j)`. Panics when out of range.
    #[inline]
    pub fn set_height(&mut self, i: usize, j: usize, h: f32) {
        self.heights[j * self.nx + i] = h;
    }

    /// All heights, row-major.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// All heights, row-major, writable. Callers that edit heights report the
    /// edited rectangle to whatever caches them (BVH tiles, render patches).
    pub fn heights_mut(&mut self) -> &mut [f32] {
        &mut self.heights
    }

    /// World position of sample `(i, j)`.
    pub fn sample_position(&self, i: usize, j: usize) -> Vec3 {
        Vec3::new(
            self.origin.x + i as f32 * self.cell,
            self.height(i, j),
            self.origin.y + j as f32 * self.cell,
        )
    }

    /// Continuous grid coordinates `(u, v)` of world `(x, z)`: sample `(i, j)` is at `(i, j)`.
    #[inline]
    pub fn to_grid(&self, x: f32, z: f32) -> Vec2 {
        Vec2::new(
            (x - self.origin.x) / self.cell,
            (z - self.origin.y) / self.cell,
        )
    }

    /// True when world `(x, z)` lies over the grid.
    pub fn contains_xz(&self, x: f32, z: f32) -> bool {
        let g = self.to_grid(x, z);
        g.x >= 0.0 && g.y >= 0.0 && g.x <= (self.nx - 1) as f32 && g.y <= (self.nz - 1) as f32
    }

    /// Cell `(i, j)` holding grid coordinates `g` and the fractions inside it, or
    /// `None` outside the grid (or for NaN).
    #[inline]
    fn locate(&self, x: f32, z: f32) -> Option<(usize, usize, f32, f32)> {
        let g = self.to_grid(x, z);
        let (mx, mz) = ((self.nx - 1) as f32, (self.nz - 1) as f32);
        if !(g.x >= 0.0 && g.y >= 0.0 && g.x <= mx && g.y <= mz) {
            return None;
        }
        let i = (g.x.floor() as usize).min(self.nx - 2);
        let j = (g.y.floor() as usize).min(self.nz - 2);
        Some((i, j, g.x - i as f32, g.y - j as f32))
    }

    /// Height of the triangulated surface at world `(x, z)` (what a vertical ray hits),
    /// or `None` off the grid.
    pub fn height_at(&self, x: f32, z: f32) -> Option<f32> {
        let (i, j, fx, fz) = self.locate(x, z)?;
        Some(self.cell_surface_height(i, j, fx, fz))
    }

    /// Height of the triangulated surface inside cell `(i, j)` at fractions
    /// `(fx, fz)`. The one formula shared by [`HeightGrid::height_at`] and ray casts,
    /// so that a vertical ray hits exactly `height_at`.
    #[inline]
    pub(crate) fn cell_surface_height(&self, i: usize, j: usize, fx: f32, fz: f32) -> f32 {
        let h00 = self.height(i, j);
        let h10 = self.height(i + 1, j);
        let h01 = self.height(i, j + 1);
        let h11 = self.height(i + 1, j + 1);
        // Diagonal (i, j) -> (i + 1, j + 1): the lower-right triangle has fx >= fz.
        if fx >= fz {
            h00 + (h10 - h00) * fx + (h11 - h10) * fz
        } else {
            h00 + (h01 - h00) * fz + (h11 - h01) * fx
        }
    }

    /// Cell `(i, j)` and fractions `(fx, fz)` holding world `(x, z)`, exactly as
    /// [`HeightGrid::height_at`] chooses them, or `None` off the grid.
    #[inline]
    pub(crate) fn locate_cell(&self, x: f32, z: f32) -> Option<(usize, usize, f32, f32)> {
        self.locate(x, z)
    }

    /// Bilinear height at world `(x, z)`, or `None` off the grid.
    pub fn height_bilinear(&self, x: f32, z: f32) -> Option<f32> {
        let (i, j, fx, fz) = self.locate(x, z)?;
        let a = self.height(i, j) * (1.0 - fx) + self.height(i + 1, j) * fx;
        let b = self.height(i, j + 1) * (1.0 - fx) + self.height(i + 1, j + 1) * fx;
        Some(a * (1.0 - fz) + b * fz)
    }

    /// Unit normal at sample `(i, j)` from central differences (one-sided at the border).
    pub fn sample_normal(&self, i: usize, j: usize) -> Vec3 {
        let il = i.saturating_sub(1);
        let ir = (i + 1).min(self.nx - 1);
        let jl = j.saturating_sub(1);
        let jr = (j + 1).min(self.nz - 1);
        let dhdx = (self.height(ir, j) - self.height(il, j)) / ((ir - il) as f32 * self.cell);
        let dhdz = (self.height(i, jr) - self.height(i, jl)) / ((jr - jl) as f32 * self.cell);
        Vec3::new(-dhdx, 1.0, -dhdz).normalize()
    }

    /// Smooth unit normal at world `(x, z)`: the bilinear blend of the sample
    /// normals, or `None` off the grid.
    pub fn normal_at(&self, x: f32, z: f32) -> Option<Vec3> {
        let (i, j, fx, fz) = self.locate(x, z)?;
        let n = self.sample_normal(i, j) * (1.0 - fx) * (1.0 - fz)
            + self.sample_normal(i + 1, j) * fx * (1.0 - fz)
            + self.sample_normal(i, j + 1) * (1.0 - fx) * fz
            + self.sample_normal(i + 1, j + 1) * fx * fz;
        Some(n.normalize())
    }

    /// The rectangle of samples whose world position lies within `[min, max]`
    /// (XZ), clipped to the grid; empty when the box misses the grid.
    pub fn rect_covering(&self, min_xz: Vec2, max_xz: Vec2) -> GridRect {
        let a = self.to_grid(min_xz.x, min_xz.y);
        let b = self.to_grid(max_xz.x, max_xz.y);
        if !(a.is_finite() && b.is_finite()) {
            return GridRect::EMPTY;
        }
        let i0 = a.x.ceil().max(0.0);
        let j0 = a.y.ceil().max(0.0);
        let i1 = (b.x.floor() + 1.0).min(self.nx as f32);
        let j1 = (b.y.floor() + 1.0).min(self.nz as f32);
        if i1 <= i0 || j1 <= j0 {
            return GridRect::EMPTY;
        }
        GridRect::new(i0 as usize, j0 as usize, i1 as usize, j1 as usize)
    }

    /// Sum of heights times cell area: the volume above `y = 0` (signed).
    /// Accumulated in `f64` so that conservation checks hold to 1e-6.
    pub fn volume(&self) -> f64 {
        let a = (self.cell as f64) * (self.cell as f64);
        self.heights.iter().map(|&h| h as f64).sum::<f64>() * a
    }

    /// Lowest and highest height inside `rect` (which must be non-empty and in range).
    pub fn min_max_in(&self, rect: &GridRect) -> (f32, f32) {
        let mut lo = f32::INFINITY;
        let mut hi = f32::NEG_INFINITY;
        for j in rect.j0..rect.j1 {
            let row = &self.heights[j * self.nx + rect.i0..j * self.nx + rect.i1];
            // Plain comparisons (heights are finite) let the compiler vectorise.
            for &h in row {
                if h < lo {
                    lo = h;
                }
                if h > hi {
                    hi = h;
                }
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slope() -> HeightGrid {
        HeightGrid::from_fn(Vec2::new(-1.0, -1.0), 0.5, 5, 5, |x, z| 0.5 * x + 0.25 * z).unwrap()
    }

    #[test]
    fn planar_heights_are_exact() {
        let g = slope();
        for &(x, z) in &[(0.0, 0.0), (0.3, -0.7), (0.99, 0.99), (-1.0, 1.0)] {
            let want = 0.5 * x + 0.25 * z;
            assert!((g.height_at(x, z).unwrap() - want).abs() < 1e-5);
            assert!((g.height_bilinear(x, z).unwrap() - want).abs() < 1e-5);
        }
        assert_eq!(g.height_at(1.1, 0.0), None);
        assert_eq!(g.height_at(f32::NAN, 0.0), None);
        let n = g.normal_at(0.2, 0.2).unwrap();
        let want = Vec3::new(-0.5, 1.0, -0.25).normalize();
        assert!((n - want).length() < 1e-5);
    }

    #[test]
    fn refuses_bad_sizes_before_allocating() {
        assert!(matches!(
            HeightGrid::new(Vec2::ZERO, 0.1, 100_000, 100_000, 0.0),
            Err(GeomError::GridTooLarge { .. })
        ));
        assert!(HeightGrid::new(Vec2::ZERO, f32::NAN, 4, 4, 0.0).is_err());
        assert!(HeightGrid::new(Vec2::ZERO, -1.0, 4, 4, 0.0).is_err());
        assert!(HeightGrid::new(Vec2::ZERO, 1.0, 1, 4, 0.0).is_err());
        assert!(HeightGrid::new(Vec2::ZERO, 1.0, 4, 4, f32::INFINITY).is_err());
    }

    #[test]
    fn rect_covering_clips() {
        let g = slope();
        assert_eq!(
            g.rect_covering(Vec2::new(-0.6, -0.6), Vec2::new(0.1, 0.1)),
            GridRect::new(1, 1, 3, 3)
        );
        assert_eq!(
            g.rect_covering(Vec2::new(-9.0, -9.0), Vec2::new(9.0, 9.0)),
            g.full_rect()
        );
        assert!(
            g.rect_covering(Vec2::new(5.0, 5.0), Vec2::new(6.0, 6.0))
                .is_empty()
        );
    }
}
