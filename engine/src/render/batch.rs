//! The geometry stage: clip-space vertices and triangles become a [`ScreenBatch`]
//! of set-up triangles (culled, clipped, wound clockwise on screen, covering at
//! least one pixel centre), binned by bands, which the bands then fill.

use glam::{Vec3, Vec4};

use super::centre_box::{screen_limits, triangle_span};
use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle};
use super::project::{
    ClipPositions, ClipSource, LANES, ProjectedVertex, VertexShader, project_vertices,
};
use super::raster::{
    Band, BigTriangle, Dot, Edges, ONE, PixelSpan, ScreenVertex, Triangle, signed_area,
};
use super::small_triangle::SmallTriangle;

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
pub(crate) const BAND_ROWS: i32 = 1 << BAND_SHIFT;
/// `log2(BAND_ROWS)`: a non-negative row's band is `row >> BAND_SHIFT`.
const BAND_SHIFT: u32 = 5;

/// Bit of a [`ScreenBatch`] entry that marks a [`Dot`] (else a [`Triangle`]).
const DOT_ENTRY: u32 = 1 << 31;

/// Screen-space triangles ready to fill, binned by the bands of rows they touch.
#[derive(Debug, Default)]
pub(crate) struct ScreenBatch {
    /// Set-up triangles covering more than one pixel centre.
    tris: Vec<Triangle>,
    /// Triangles covering one pixel centre, kept as that pixel.
    dots: Vec<Dot>,
    /// Edge functions of the triangles too big for a coverage mask.
    edges: Vec<Edges>,
    /// The kept triangles of each band, in submission order.
    bands: BandEntries,
}

/// The entries of each band of rows (band `k`: rows `k * BAND_ROWS ..`), each
/// an index into a batch's `tris`, or into its `dots` with [`DOT_ENTRY`] set,
/// in submission order. Filled as triangles are kept: no binning pass after.
#[derive(Debug, Default)]
struct BandEntries(Vec<Vec<u32>>);

impl BandEntries {
    /// No entries in the bands of a screen `height` pixels tall.
    fn new(height: i32) -> BandEntries {
        let bands = (height.max(0) + BAND_ROWS - 1) >> BAND_SHIFT;
        BandEntries(vec![Vec::new(); bands as usize])
    }

    /// Appends `entry` to the bands of pixel rows `y0..=y1` (`0 <= y0 <= y1 <
    /// height`).
    #[inline(always)]
    fn push(&mut self, entry: u32, (y0, y1): (i32, i32)) {
        let (first, last) = ((y0 >> BAND_SHIFT) as usize, (y1 >> BAND_SHIFT) as usize);
        for band in &mut self.0[first..=last] {
            band.push(entry);
        }
    }

    /// The entries of band `band`, in submission order.
    #[inline]
    fn band(&self, band: i32) -> &[u32] {
        usize::try_from(band)
            .ok()
            .and_then(|k| self.0.get(k))
            .map_or(&[], Vec::as_slice)
    }
}

/// The viewport a batch is built for.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Viewport {
    pub width: i32,
    pub height: i32,
}

impl Viewport {
    /// The screen vertex of clip position `pos`, its colour not yet set.
    #[inline]
    pub(crate) fn project_position(&self, pos: Vec4) -> ScreenVertex {
        self.project(&ClipVertex {
            pos,
            color: Vec3::ZERO,
        })
    }

    /// The screen vertex of a clip vertex.
    #[inline]
    pub(crate) fn project(&self, v: &ClipVertex) -> ScreenVertex {
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

/// Where clipping finds the clip position and colour of a batch's vertex
/// (the projected vertices keep neither).
trait ClipVertices {
    /// The clip vertex `k` (position and colour).
    fn clip_vertex(&self, k: usize) -> ClipVertex;
}

/// Colours already projected with the positions.
struct EagerColors<'a>(&'a [ClipVertex]);

impl ClipVertices for EagerColors<'_> {
    fn clip_vertex(&self, k: usize) -> ClipVertex {
        self.0[k]
    }
}

impl VertexShader for EagerColors<'_> {
    fn color(&self, k: usize) -> Vec3 {
        self.0[k].color
    }

    fn colors(&self, group: usize) -> [Vec3; LANES] {
        std::array::from_fn(|k| self.color(LANES * group + k))
    }
}

/// Colours set before the triangles are set up, for all vertices.
struct ShadedColors<P, S> {
    positions: P,
    shader: S,
}

impl<P: ClipSource, S: VertexShader> ClipVertices for ShadedColors<P, S> {
    fn clip_vertex(&self, k: usize) -> ClipVertex {
        ClipVertex {
            pos: self.positions.clip(k),
            color: self.shader.color(k),
        }
    }
}

impl ScreenBatch {
    /// Projects `verts` and sets up every triangle of `groups`.
    pub fn build(verts: &[ClipVertex], groups: &[TriangleGroup<'_>], vp: Viewport) -> ScreenBatch {
        let clip: Vec<Vec4> = verts.iter().map(|v| v.pos).collect();
        let projected = project_vertices(&ClipPositions(&clip), &EagerColors(verts), vp);
        ScreenBatch::build_from(projected, EagerColors(verts), groups, vp)
    }

    /// Projects the vertices of `positions`, colours them four at a time
    /// with `shader` and sets up every triangle of `groups`.
    pub fn build_shaded<P: ClipSource, S: VertexShader>(
        positions: P,
        shader: S,
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
    ) -> ScreenBatch {
        let projected = project_vertices(&positions, &shader, vp);
        let clip_vertices = ShadedColors { positions, shader };
        ScreenBatch::build_from(projected, clip_vertices, groups, vp)
    }

    /// Sets up every triangle of `groups` over the `projected` vertices.
    fn build_from(
        mut projected: Vec<ProjectedVertex>,
        clip_vertices: impl ClipVertices,
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
    ) -> ScreenBatch {
        let submitted = groups.iter().map(|g| g.triangles.len()).sum();
        // Growing these would copy them; untouched capacity costs nothing.
        let mut batch = ScreenBatch {
            tris: Vec::with_capacity(submitted),
            dots: Vec::with_capacity(submitted),
            edges: Vec::new(),
            bands: BandEntries::new(vp.height),
        };
        let mut polygon = Vec::with_capacity(9);
        let limits = screen_limits(vp.width, vp.height);
        for group in groups {
            for &tri in group.triangles {
                let [a, b, c] = tri.map(|k| k as usize);
                let (ca, cb, cc) = (projected[a].code, projected[b].code, projected[c].code);
                if ca & cb & cc & OUT_FRUSTUM != 0 {
                    continue;
                }
                if (ca | cb | cc) & (OUT_NEAR | OUT_GUARD) == 0 {
                    batch.push(&projected, tri, group.cull, limits);
                    continue;
                }
                clip_triangle(
                    [a, b, c].map(|k| clip_vertices.clip_vertex(k)),
                    &mut polygon,
                );
                if polygon.is_empty() {
                    continue;
                }
                // Clipped polygons append their (already shaded) vertices,
                // dropped with the batch's.
                let base = projected.len() as u32;
                // Not clipped again: no outcode needed.
                let vertices = polygon
                    .iter()
                    .map(|v| ProjectedVertex::new(vp.project(v), 0));
                projected.extend(vertices);
                for k in 1..polygon.len() as u32 - 1 {
                    let tri = [base, base + k, base + k + 1];
                    batch.push(&projected, tri, group.cull, limits);
                }
            }
        }
        batch
    }

    /// How many kept triangles became dots, and how many are full triangles.
    #[cfg(test)]
    pub fn kinds(&self) -> (usize, usize) {
        (self.dots.len(), self.tris.len())
    }

    /// Number of set-up triangles (dots included).
    pub fn len(&self) -> usize {
        self.tris.len() + self.dots.len()
    }

    /// Fills the band (band index `band`, of [`BAND_ROWS`] rows) with the
    /// triangles touching it, in submission order.
    #[inline]
    pub fn draw_band(&self, band: i32, target: &mut Band<'_>) {
        for &t in self.bands.band(band) {
            if t & DOT_ENTRY != 0 {
                self.dots[(t & !DOT_ENTRY) as usize].draw(target);
            } else {
                self.tris[t as usize].draw(&self.edges, target);
            }
        }
    }

    /// Culls, orients, sets up and keeps one triangle if it covers a pixel
    /// centre.
    #[inline(always)]
    fn push(&mut self, projected: &[ProjectedVertex], tri: [u32; 3], cull: CullMode, limits: Vec4) {
        let [a, b, c] = tri.map(|k| k as usize);
        // Most sub-pixel triangles have no pixel centre in their box: drop them
        // first (the box does not depend on the winding).
        let (pa, pb, pc) = (&projected[a], &projected[b], &projected[c]);
        let Some(span) = triangle_span(pa.centre_box, pb.centre_box, pc.centre_box, limits) else {
            return;
        };
        let (sa, sb, sc) = (&pa.screen, &pb.screen, &pc.screen);
        let area = signed_area(sa, sb, sc);
        // Counter-clockwise in the world, seen from the front, projects to a
        // negative area on the y-down screen. (The vertices already looked
        // up are reordered, not their indices: no second bounds check.)
        let (v, area) = if area < 0 {
            ([sa, sc, sb], -area)
        } else if area > 0 && cull == CullMode::None {
            ([sa, sb, sc], area)
        } else {
            return;
        };
        let Some(small) = SmallTriangle::of(v, span) else {
            let tri = BigTriangle::of(v, span).triangle(v, area, &mut self.edges);
            self.push_triangle(tri, span);
            return;
        };
        let mask = small.coverage(span);
        if mask == 0 {
            return;
        }
        let planes = small.planes(v, area);
        if mask.is_power_of_two() {
            let dot = Dot::in_box(&planes, span, mask);
            self.bands
                .push(self.dots.len() as u32 | DOT_ENTRY, (dot.row(), dot.row()));
            self.dots.push(dot);
        } else {
            self.push_triangle(Triangle::masked(planes, span, mask), span);
        }
    }

    /// Keeps a set-up triangle whose box is `span`.
    #[inline]
    fn push_triangle(&mut self, tri: Triangle, span: PixelSpan) {
        self.bands.push(self.tris.len() as u32, (span.y0, span.y1));
        self.tris.push(tri);
    }
}

/// Items binned by the bands of rows they touch: a counting sort that keeps
/// each band's items in the order given (so depth ties resolve the same way
/// whatever the thread count). Used by the grass layer, whose pieces are sorted
/// before they are binned.
#[derive(Debug, Default)]
pub(crate) struct BandBins {
    /// First band any item touches.
    first_band: i32,
    /// `starts[k]..starts[k + 1]` indexes `binned` for band `first_band + k`.
    starts: Vec<u32>,
    /// Items of each band, in the order given.
    binned: Vec<u32>,
}

impl BandBins {
    /// Bins `items`, each an id and its first and last pixel row (`0 <= y0 <=
    /// y1`); the iterator is walked three times.
    pub(crate) fn new<I>(items: I) -> BandBins
    where
        I: Iterator<Item = (u32, (i32, i32))> + Clone,
    {
        let (first, last) = items
            .clone()
            .fold((i32::MAX, i32::MIN), |(lo, hi), (_, (y0, y1))| {
                (lo.min(y0), hi.max(y1))
            });
        if first > last {
            return BandBins::default();
        }
        let first_band = first >> BAND_SHIFT;
        let bands = ((last >> BAND_SHIFT) - first_band + 1) as usize;
        // Rows are non-negative: shifts, not signed divisions.
        let band_range = |(y0, y1): (i32, i32)| {
            (
                ((y0 >> BAND_SHIFT) - first_band) as usize,
                ((y1 >> BAND_SHIFT) - first_band) as usize,
            )
        };
        let mut starts = vec![0u32; bands + 1];
        for (_, rows) in items.clone() {
            let (b0, b1) = band_range(rows);
            // Most items touch one band: no range to iterate.
            starts[b0 + 1] += 1;
            for b in b0 + 1..=b1 {
                starts[b + 1] += 1;
            }
        }
        for b in 0..bands {
            starts[b + 1] += starts[b];
        }
        let mut fill = starts.clone();
        let mut binned = vec![0; starts[bands] as usize];
        for (id, rows) in items {
            let (b0, b1) = band_range(rows);
            for b in b0..=b1 {
                binned[fill[b] as usize] = id;
                fill[b] += 1;
            }
        }
        BandBins {
            first_band,
            starts,
            binned,
        }
    }

    /// The items touching band `band` (of [`BAND_ROWS`] rows), in the order given.
    #[inline]
    pub(crate) fn band(&self, band: i32) -> &[u32] {
        let k = band - self.first_band;
        if k < 0 || k as usize + 1 >= self.starts.len() {
            return &[];
        }
        let k = k as usize;
        &self.binned[self.starts[k] as usize..self.starts[k + 1] as usize]
    }
}

/// A clip-space position from a world point and a world-to-clip matrix.
#[inline]
pub(crate) fn to_clip(view_proj: &glam::Mat4, p: glam::Vec3) -> Vec4 {
    *view_proj * p.extend(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_bins_keep_order_and_repeat_items_spanning_bands() {
        let b = BAND_ROWS;
        let items = [
            (7, (b + 3, b + 3)),
            (1, (2 * b - 1, 3 * b + 2)),
            (4, (b, 2 * b - 1)),
            (9, (3 * b, 3 * b)),
        ];
        let bins = BandBins::new(items.iter().copied());
        assert!(bins.band(0).is_empty());
        assert_eq!(bins.band(1), &[7, 1, 4]);
        assert_eq!(bins.band(2), &[1]);
        assert_eq!(bins.band(3), &[1, 9]);
        assert!(bins.band(4).is_empty());
        assert!(bins.band(-1).is_empty());
        assert!(BandBins::new(std::iter::empty()).band(0).is_empty());
    }
}
