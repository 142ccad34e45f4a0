//! The geometry stage: clip-space vertices and triangles become a [`ScreenBatch`]
//! of set-up triangles (culled, clipped, wound clockwise on screen, covering at
//! least one pixel centre), binned by bands, which the bands then fill.

use glam::Vec4;

use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle, outcode};
use super::raster::{Band, Edges, ONE, PixelSpan, ScreenVertex, Triangle, signed_area};

/// Which triangles to drop by their facing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CullMode {
    /// Draw both sides.
    None,
    /// Drop triangles whose vertices run clockwise seen from the camera
    /// (meshes are counter-clockwise from the front).
    Back,
}

/// A run of triangles sharing one cull mode, indexing a vertex slice.
pub(crate) struct TriangleGroup<'a> {
    /// Triangles as three vertex indices.
    pub triangles: &'a [[u32; 3]],
    /// Facing to drop.
    pub cull: CullMode,
}

/// Rows per band: the unit of parallel rasterization. Fixed, so that the
/// result does not depend on the number of threads.
pub(crate) const BAND_ROWS: i32 = 32;

/// Screen-space triangles ready to fill, binned by the bands of rows they touch.
#[derive(Debug, Default)]
pub(crate) struct ScreenBatch {
    /// Set-up triangles, in submission order.
    tris: Vec<Triangle>,
    /// Edge functions of the triangles too big for a coverage mask.
    edges: Vec<Edges>,
    /// First band any triangle touches.
    first_band: i32,
    /// `bins[k]..bins[k + 1]` indexes `binned` for band `first_band + k`.
    bins: Vec<u32>,
    /// Triangle indices of each band, in submission order.
    binned: Vec<u32>,
}

/// The viewport a batch is built for.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Viewport {
    pub width: i32,
    pub height: i32,
}

impl Viewport {
    #[inline]
    fn project(&self, v: &ClipVertex) -> ScreenVertex {
        let inv_w = 1.0 / v.pos.w;
        let sx = (v.pos.x * inv_w * 0.5 + 0.5) * self.width as f32;
        let sy = (0.5 - v.pos.y * inv_w * 0.5) * self.height as f32;
        let scale = ONE as f32;
        ScreenVertex {
            // Saturating casts: off-screen garbage (for vertices that are clipped
            // anyway) cannot overflow.
            // Rounds to nearest on screen; truncates (still consistently per
            // vertex) off the top and left, which only changes clipped geometry.
            x: (sx * scale + 0.5) as i32,
            y: (sy * scale + 0.5) as i32,
            inv_w,
            color_w: v.color * inv_w,
        }
    }
}

impl ScreenBatch {
    /// Projects `verts` and sets up every triangle of `groups`.
    pub fn build(verts: &[ClipVertex], groups: &[TriangleGroup<'_>], vp: Viewport) -> ScreenBatch {
        let submitted = groups.iter().map(|g| g.triangles.len()).sum();
        let mut batch = ScreenBatch {
            tris: Vec::with_capacity(submitted),
            ..ScreenBatch::default()
        };
        let mut screen: Vec<ScreenVertex> = verts.iter().map(|v| vp.project(v)).collect();
        let codes: Vec<u8> = verts.iter().map(|v| outcode(v.pos)).collect();
        let mut polygon = Vec::with_capacity(9);
        for group in groups {
            for &tri in group.triangles {
                let [a, b, c] = tri.map(|k| k as usize);
                let (ca, cb, cc) = (codes[a], codes[b], codes[c]);
                if ca & cb & cc & OUT_FRUSTUM != 0 {
                    continue;
                }
                if (ca | cb | cc) & (OUT_NEAR | OUT_GUARD) == 0 {
                    batch.push(&screen, tri, group.cull, vp);
                    continue;
                }
                clip_triangle([verts[a], verts[b], verts[c]], &mut polygon);
                if polygon.is_empty() {
                    continue;
                }
                // Clipped polygons append their vertices, dropped with the batch's.
                let base = screen.len() as u32;
                screen.extend(polygon.iter().map(|v| vp.project(v)));
                for k in 1..polygon.len() as u32 - 1 {
                    batch.push(&screen, [base, base + k, base + k + 1], group.cull, vp);
                }
            }
        }
        batch.bin();
        batch
    }

    /// Sorts the triangles into per-band lists (counting sort, order kept).
    fn bin(&mut self) {
        let rows: Vec<(i32, i32)> = self.tris.iter().map(Triangle::rows).collect();
        let Some(first) = rows.iter().map(|r| r.0).min() else {
            return;
        };
        let last = rows.iter().map(|r| r.1).max().unwrap_or(first);
        self.first_band = first / BAND_ROWS;
        let bands = (last / BAND_ROWS - self.first_band + 1) as usize;
        let mut counts = vec![0u32; bands + 1];
        let band_range = |(y0, y1): (i32, i32)| {
            (y0 / BAND_ROWS - self.first_band) as usize
                ..=(y1 / BAND_ROWS - self.first_band) as usize
        };
        for &r in &rows {
            for b in band_range(r) {
                counts[b + 1] += 1;
            }
        }
        for b in 0..bands {
            counts[b + 1] += counts[b];
        }
        let mut fill = counts.clone();
        self.binned = vec![0; counts[bands] as usize];
        for (t, &r) in rows.iter().enumerate() {
            for b in band_range(r) {
                self.binned[fill[b] as usize] = t as u32;
                fill[b] += 1;
            }
        }
        self.bins = counts;
    }

    /// Number of set-up triangles.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Fills the band (band index `band`, of [`BAND_ROWS`] rows) with the
    /// triangles touching it, in submission order.
    #[inline]
    pub fn draw_band(&self, band: i32, target: &mut Band<'_>) {
        let k = band - self.first_band;
        if k < 0 || k as usize + 1 >= self.bins.len() {
            return;
        }
        let k = k as usize;
        for &t in &self.binned[self.bins[k] as usize..self.bins[k + 1] as usize] {
            self.tris[t as usize].draw(&self.edges, target);
        }
    }

    /// Culls, orients, sets up and keeps one triangle if it covers a pixel centre.
    #[inline]
    fn push(&mut self, screen: &[ScreenVertex], tri: [u32; 3], cull: CullMode, vp: Viewport) {
        let [a, b, c] = tri.map(|k| &screen[k as usize]);
        // Most sub-pixel triangles have no pixel centre in their box: drop them
        // first (the box does not depend on the winding).
        let span = PixelSpan::of([a, b, c], vp.width, vp.height);
        if span.is_empty() {
            return;
        }
        let area = signed_area(a, b, c);
        // Counter-clockwise in the world, seen from the front, projects to a
        // negative area on the y-down screen.
        let (v, area) = if area < 0 {
            ([a, c, b], -area)
        } else if area > 0 && cull == CullMode::None {
            ([a, b, c], area)
        } else {
            return;
        };
        if let Some(t) = Triangle::setup(v, area, span, &mut self.edges) {
            self.tris.push(t);
        }
    }
}

/// A clip-space position from a world point and a world-to-clip matrix.
#[inline]
pub(crate) fn to_clip(view_proj: &glam::Mat4, p: glam::Vec3) -> Vec4 {
    *view_proj * p.extend(1.0)
}
