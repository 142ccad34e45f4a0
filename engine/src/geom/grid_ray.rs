//! Exact ray intersection with the triangulated surface of a [`HeightGrid`].
//!
//! The ray is walked cell by cell (a 2D DDA over the XZ grid). Along the ray
//! the signed height above the surface, `f(t) = ray_y(t) - surface(t)`, is
//! piecewise linear: its breakpoints are where the ray crosses a cell edge or
//! a cell diagonal. `f` is evaluated once at every breakpoint and the value is
//! carried into the next piece, so a sign change can never fall between two
//! pieces: a ray exactly along a cell edge or through a corner is not lost.

use glam::{Vec2, Vec3};

use super::aabb::slab;
use super::ray::usable_max_t;
use super::{GridRect, HeightGrid, Hit, HitTarget, MeshPart, Ray, TriMesh};

impl HeightGrid {
    /// Number of cells along X and Z (`nx - 1`, `nz - 1`).
    pub fn cell_counts(&self) -> (usize, usize) {
        (self.nx() - 1, self.nz() - 1)
    }

    /// All cells as a rectangle of cell indices.
    pub fn full_cell_rect(&self) -> GridRect {
        let (cx, cz) = self.cell_counts();
        GridRect::new(0, 0, cx, cz)
    }

    /// The closest intersection of `ray` with the triangulated surface within
    /// distance `max_t` (both sides of the surface count), walking every cell
    /// the ray crosses. [`crate::geom::GridBvh`] gives the same answers faster.
    ///
    /// ```
    /// use engine::geom::{HeightGrid, Ray};
    /// use engine::glam::{Vec2, Vec3};
    /// let g = HeightGrid::new(Vec2::ZERO, 0.5, 9, 9, 1.0).unwrap();
    /// let ray = Ray::new(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, -1.0, 1.0)).unwrap();
    /// let hit = g.intersect_ray(&ray, f32::INFINITY).unwrap();
    /// assert!((hit.point - Vec3::new(2.0, 1.0, 2.0)).length() < 1e-5);
    /// ```
    pub fn intersect_ray(&self, ray: &Ray, max_t: f32) -> Option<Hit> {
        self.intersect_ray_in_cells(ray, self.full_cell_rect(), 0.0, max_t)
    }

    /// What a vertical ray going down from `(x, from_y, z)` hits: the surface at
    /// [`HeightGrid::height_at`] when it is not above `from_y`, else `None`.
    /// Agrees exactly with [`HeightGrid::intersect_ray`] on the same ray.
    pub fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<Hit> {
        // No `Ray` needed: a non-finite x or z misses in `locate_cell`.
        if !from_y.is_finite() {
            return None;
        }
        self.vertical_hit(
            Vec3::new(x, from_y, z),
            -1.0,
            self.full_cell_rect(),
            f32::INFINITY,
        )
    }

    /// Like [`HeightGrid::intersect_ray`] but only over the cells in `cells`
    /// (cell indices, half-open) and distances `min_t..=max_t`. Callers that clip
    /// `min_t` must only cut away parts of the ray where no crossing can be.
    pub(crate) fn intersect_ray_in_cells(
        &self,
        ray: &Ray,
        cells: GridRect,
        min_t: f32,
        max_t: f32,
    ) -> Option<Hit> {
        if cells.is_empty() || !usable_max_t(max_t) {
            return None;
        }
        let cell = self.cell_size();
        let (o, d) = (ray.origin(), ray.dir());
        let g0 = self.to_grid(o.x, o.z);
        let gd = Vec2::new(d.x / cell, d.z / cell);
        if gd == Vec2::ZERO {
            return self.vertical_hit(o, d.y, cells, max_t);
        }
        let (ax, bx) = slab(g0.x, gd.x, cells.i0 as f32, cells.i1 as f32)?;
        let (az, bz) = slab(g0.y, gd.y, cells.j0 as f32, cells.j1 as f32)?;
        let t_lo = ax.max(az).max(min_t).max(0.0);
        let t_hi = bx.min(bz).min(max_t);
        if t_lo > t_hi {
            return None;
        }
        let walk = CellWalk {
            grid: self,
            g0,
            gd,
            oy: o.y,
            dy: d.y,
        };
        let start = walk.grid_at(t_lo);
        let mut ci = clamp_index(start.x, cells.i0, cells.i1);
        let mut cj = clamp_index(start.y, cells.j0, cells.j1);
        let mut t_prev = t_lo;
        let mut f_prev = walk.f(t_lo, ci, cj);
        if f_prev == 0.0 {
            return Some(walk.hit(ray, t_lo, ci, cj));
        }
        loop {
            let tx = next_edge(g0.x, gd.x, ci);
            let tz = next_edge(g0.y, gd.y, cj);
            let t_exit = tx.min(tz).min(t_hi).max(t_prev);
            if let Some(td) = walk.diagonal_crossing(ci, cj)
                && td > t_prev
                && td < t_exit
            {
                let f_d = walk.f(td, ci, cj);
                if let Some(t) = walk.crossing(ci, cj, (t_prev, f_prev), (td, f_d)) {
                    return Some(walk.hit(ray, t, ci, cj));
                }
                (t_prev, f_prev) = (td, f_d);
            }
            let f_exit = walk.f(t_exit, ci, cj);
            if let Some(t) = walk.crossing(ci, cj, (t_prev, f_prev), (t_exit, f_exit)) {
                return Some(walk.hit(ray, t, ci, cj));
            }
            (t_prev, f_prev) = (t_exit, f_exit);
            if t_exit >= t_hi {
                return None;
            }
            if tx <= tz {
                ci = step_index(ci, gd.x, cells.i0, cells.i1)?;
            } else {
                cj = step_index(cj, gd.y, cells.j0, cells.j1)?;
            }
        }
    }

    /// A vertical ray: straight to the cell [`HeightGrid::height_at`] uses.
    /// `dy` is the direction's Y component: exactly `1` or `-1`.
    fn vertical_hit(&self, o: Vec3, dy: f32, cells: GridRect, max_t: f32) -> Option<Hit> {
        let (i, j, fx, fz) = self.locate_cell(o.x, o.z)?;
        if !cells.contains(i, j) {
            return None;
        }
        let h = self.cell_surface_height(i, j, fx, fz);
        let t = (h - o.y) / dy;
        (t >= 0.0 && t <= max_t).then(|| Hit {
            point: Vec3::new(o.x, h, o.z),
            normal: self.cell_triangle_normal(i, j, fx >= fz),
            distance: t,
            target: HitTarget::Grid { i, j },
        })
    }

    /// Unit up-facing normal of one triangle of cell `(i, j)`: the lower-right
    /// one (`fx >= fz`) or the upper-left one.
    pub fn cell_triangle_normal(&self, i: usize, j: usize, lower_right: bool) -> Vec3 {
        let h00 = self.height(i, j);
        let h10 = self.height(i + 1, j);
        let h01 = self.height(i, j + 1);
        let h11 = self.height(i + 1, j + 1);
        let (dx, dz) = if lower_right {
            (h10 - h00, h11 - h10)
        } else {
            (h11 - h01, h01 - h00)
        };
        let c = self.cell_size();
        Vec3::new(-dx, c, -dz).normalize()
    }

    /// The surface as a triangle mesh: sample `(i, j)` is vertex `j * nx + i`;
    /// cell `(i, j)` gives triangles `2 * (j * (nx - 1) + i)` (lower-right, `fx >= fz`)
    /// and the next one (upper-left), both counter-clockwise seen from above.
    pub fn to_tri_mesh(&self) -> TriMesh {
        let (nx, nz) = (self.nx(), self.nz());
        let mut positions = Vec::with_capacity(nx * nz);
        let mut normals = Vec::with_capacity(nx * nz);
        for j in 0..nz {
            for i in 0..nx {
                positions.push(self.sample_position(i, j));
                normals.push(self.sample_normal(i, j));
            }
        }
        let (cx, cz) = self.cell_counts();
        let mut triangles = Vec::with_capacity(2 * cx * cz);
        for j in 0..cz {
            for i in 0..cx {
                let a = (j * nx + i) as u32;
                let (b, c, d) = (a + 1, a + 1 + nx as u32, a + nx as u32);
                triangles.push([a, c, b]);
                triangles.push([a, d, c]);
            }
        }
        let count = triangles.len();
        TriMesh {
            positions,
            normals,
            triangles,
            parts: vec![MeshPart {
                name: "terrain".into(),
                triangles: 0..count,
            }],
        }
    }
}

/// A ray expressed in grid coordinates, with the surface it walks over.
struct CellWalk<'a> {
    grid: &'a HeightGrid,
    /// Ray origin in grid coordinates.
    g0: Vec2,
    /// Ray direction in grid cells per unit distance.
    gd: Vec2,
    oy: f32,
    dy: f32,
}

impl CellWalk<'_> {
    #[inline]
    fn grid_at(&self, t: f32) -> Vec2 {
        self.g0 + self.gd * t
    }

    /// Fractions of the ray's point at `t` inside cell `(i, j)`, clamped to the cell.
    #[inline]
    fn fractions(&self, t: f32, i: usize, j: usize) -> (f32, f32) {
        let g = self.grid_at(t);
        (
            (g.x - i as f32).clamp(0.0, 1.0),
            (g.y - j as f32).clamp(0.0, 1.0),
        )
    }

    /// Signed height of the ray above the surface of cell `(i, j)` at `t`.
    #[inline]
    fn f(&self, t: f32, i: usize, j: usize) -> f32 {
        let (fx, fz) = self.fractions(t, i, j);
        self.oy + self.dy * t - self.grid.cell_surface_height(i, j, fx, fz)
    }

    /// Where the ray crosses the line `fx = fz` of cell `(i, j)`, if not parallel.
    #[inline]
    fn diagonal_crossing(&self, i: usize, j: usize) -> Option<f32> {
        let slope = self.gd.x - self.gd.y;
        (slope != 0.0).then(|| ((self.g0.y - j as f32) - (self.g0.x - i as f32)) / slope)
    }

    /// Where `f` changes sign over the piece `a..b` inside one triangle of cell
    /// `(i, j)`, if it does. The root is solved on the triangle's plane from the
    /// cell alone, not from the piece's ends, so that every walk that reaches
    /// this triangle (whatever its start) finds the very same distance.
    #[inline]
    fn crossing(&self, i: usize, j: usize, a: (f32, f32), b: (f32, f32)) -> Option<f32> {
        let ((t0, f0), (t1, f1)) = (a, b);
        if !((f0 > 0.0 && f1 <= 0.0) || (f0 < 0.0 && f1 >= 0.0)) {
            return None;
        }
        let mid = self.grid_at(0.5 * (t0 + t1));
        let lower_right = mid.x - i as f32 >= mid.y - j as f32;
        let g = self.grid;
        let h00 = g.height(i, j);
        // The plane h = h00 + bx * fx + bz * fz of the triangle.
        let (bx, bz) = if lower_right {
            (
                g.height(i + 1, j) - h00,
                g.height(i + 1, j + 1) - g.height(i + 1, j),
            )
        } else {
            (
                g.height(i + 1, j + 1) - g.height(i, j + 1),
                g.height(i, j + 1) - h00,
            )
        };
        let c0 = self.oy - h00 - bx * (self.g0.x - i as f32) - bz * (self.g0.y - j as f32);
        let c1 = self.dy - bx * self.gd.x - bz * self.gd.y;
        let t = if c1 != 0.0 {
            -c0 / c1
        } else {
            t0 + (t1 - t0) * (f0 / (f0 - f1))
        };
        Some(t.clamp(t0, t1))
    }

    fn hit(&self, ray: &Ray, t: f32, i: usize, j: usize) -> Hit {
        let (fx, fz) = self.fractions(t, i, j);
        let p = ray.at(t);
        Hit {
            point: Vec3::new(p.x, self.grid.cell_surface_height(i, j, fx, fz), p.z),
            normal: self.grid.cell_triangle_normal(i, j, fx >= fz),
            distance: t,
            target: HitTarget::Grid { i, j },
        }
    }
}

/// Distance at which `g0 + gd * t` leaves cell `c` along one axis (infinite when parallel).
#[inline]
fn next_edge(g0: f32, gd: f32, c: usize) -> f32 {
    if gd > 0.0 {
        ((c + 1) as f32 - g0) / gd
    } else if gd < 0.0 {
        (c as f32 - g0) / gd
    } else {
        f32::INFINITY
    }
}

/// The neighbouring cell index in the direction of `gd`, or `None` past `lo..hi`.
#[inline]
fn step_index(c: usize, gd: f32, lo: usize, hi: usize) -> Option<usize> {
    if gd > 0.0 {
        (c + 1 < hi).then_some(c + 1)
    } else {
        (c > lo).then(|| c - 1)
    }
}

#[inline]
fn clamp_index(g: f32, lo: usize, hi: usize) -> usize {
    g.floor().clamp(lo as f32, (hi - 1) as f32) as usize
}
