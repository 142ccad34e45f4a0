//! The geometry stage: clip-space vertices and triangles become a [`ScreenBatch`]
//! of set-up triangles (culled, clipped, wound clockwise on screen, covering at
//! least one pixel centre), binned by bands, which the bands then fill.

use glam::{Vec3, Vec4};
use multiversion::multiversion;

use super::centre_box::{SpanLanes, screen_limits, triangle_span};
use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle};
use super::four_small_triangles::{FourSetUp, FourSmallTriangles, FourSpans};
use super::kernels::{Kernels, run_baseline};
use super::project::{
    ClipSource, LANES, ProjectedVertex, VertexShader, position_lanes, project_vertices,
};
use super::raster::{
    Band, BigTriangle, Dot, Edges, ONE, PixelSpan, Planes, ScreenVertex, Triangle, signed_area,
};
use super::small_triangle::{SmallSetUp, SmallTriangle};

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
    /// The index the triangles give the vertex slice's first vertex
    /// (subtracted from every index as it is read, so that a batch over a
    /// run of a mesh's vertices reads the mesh's own indices).
    pub first_vertex: u32,
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
    /// The projected vertices of the last build: not needed once the
    /// triangles are set up, kept for their capacity.
    vertices: Vec<ProjectedVertex>,
}

/// Items binned by the bands of rows they touch (band `k`: rows
/// `k * BAND_ROWS ..`), each band's in the order they were pushed (so depth
/// ties resolve the same way whatever the thread count). Filled as items are
/// kept: no binning pass after. A batch's entries index its `tris`, or its
/// `dots` with [`DOT_ENTRY`] set; the grass layer's index its pieces.
#[derive(Debug, Default)]
pub(crate) struct BandEntries(Vec<Vec<u32>>);

impl BandEntries {
    /// No entries in the bands of a screen `height` pixels tall.
    pub(crate) fn new(height: i32) -> BandEntries {
        let mut entries = BandEntries::default();
        entries.reset(height);
        entries
    }

    /// Empties the entries, now for the bands of a screen `height` pixels
    /// tall, keeping what the lists have allocated.
    pub(crate) fn reset(&mut self, height: i32) {
        let bands = (height.max(0) + BAND_ROWS - 1) >> BAND_SHIFT;
        self.0.resize_with(bands as usize, Vec::new);
        self.0.iter_mut().for_each(Vec::clear);
    }

    /// Appends `entry` to the bands of pixel rows `y0..=y1` (`0 <= y0 <= y1 <
    /// height`).
    #[inline(always)]
    pub(crate) fn push(&mut self, entry: u32, (y0, y1): (i32, i32)) {
        let (first, last) = ((y0 >> BAND_SHIFT) as usize, (y1 >> BAND_SHIFT) as usize);
        for band in &mut self.0[first..=last] {
            band.push(entry);
        }
    }

    /// The entries of band `band`, in submission order.
    #[inline]
    pub(crate) fn band(&self, band: i32) -> &[u32] {
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

/// Clip vertices given whole: each with its position and its colour.
#[derive(Clone, Copy)]
pub(crate) struct ClipVertexList<'a>(pub &'a [ClipVertex]);

impl ClipSource for ClipVertexList<'_> {
    fn len(&self) -> usize {
        self.0.len()
    }

    #[inline]
    fn clip(&self, k: usize) -> Vec4 {
        self.0[k].pos
    }

    #[inline(always)]
    fn lanes(&self, group: usize) -> ([Vec4; LANES], [Vec4; 3]) {
        position_lanes(std::array::from_fn(|k| self.0[LANES * group + k].pos))
    }
}

impl VertexShader for ClipVertexList<'_> {
    fn color(&self, k: usize) -> Vec3 {
        self.0[k].color
    }
}

impl ScreenBatch {
    /// Projects `verts` and sets up every triangle of `groups`.
    pub fn build(
        verts: &[ClipVertex],
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
        kernels: Kernels,
    ) -> ScreenBatch {
        let mut batch = ScreenBatch::default();
        batch.rebuild(verts, groups, vp, kernels);
        batch
    }

    /// [`ScreenBatch::build`] into this batch, replacing what it held and
    /// keeping what its buffers have allocated (a renderer reuses its batches
    /// from frame to frame).
    pub fn rebuild(
        &mut self,
        verts: &[ClipVertex],
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
        kernels: Kernels,
    ) {
        let verts = ClipVertexList(verts);
        self.rebuild_shaded(verts, verts, groups, vp, kernels);
    }

    /// Projects the vertices of `positions`, colours them four at a time
    /// with `shader` and sets up every triangle of `groups`, with the machine
    /// code `kernels` selects, into this batch (as [`ScreenBatch::rebuild`]).
    pub fn rebuild_shaded<P: ClipSource, S: VertexShader>(
        &mut self,
        positions: P,
        shader: S,
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
        kernels: Kernels,
    ) {
        match kernels {
            Kernels::Dispatched => build_dispatched(self, positions, shader, groups, vp),
            Kernels::Baseline => run_baseline(|| build_batch(self, positions, shader, groups, vp)),
        }
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
    #[inline(always)]
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
        self.push_in_span([&pa.screen, &pb.screen, &pc.screen], cull, span);
    }

    /// [`ScreenBatch::push`] for a triangle whose pixel span `span` is known
    /// to hold a pixel centre.
    #[inline(always)]
    fn push_in_span(&mut self, v: [&ScreenVertex; 3], cull: CullMode, span: PixelSpan) {
        let (vertices, area, small) = match SmallTriangle::set_up(v, span, cull) {
            SmallSetUp::Kept {
                vertices,
                area,
                triangle,
            } => (vertices, area, triangle),
            SmallSetUp::Dropped => return,
            SmallSetUp::TooBig => {
                let Some((v, area)) = clockwise(v, cull) else {
                    return;
                };
                let tri = BigTriangle::of(v, span).triangle(v, area, &mut self.edges);
                self.push_triangle(tri, span);
                return;
            }
        };
        let mask = small.coverage(span);
        if mask != 0 {
            self.push_covered(small.planes(vertices, area), span, mask);
        }
    }

    /// Sets up four triangles that need no clipping, whose pixel spans hold
    /// a pixel centre, together where they are small enough
    /// ([`FourSmallTriangles`]), and keeps them in order.
    #[inline(always)]
    fn push_four(&mut self, kept: &[KeptTriangle<'_>; 4], cull: CullMode) {
        let spans = FourSpans::of(kept.map(|k| k.lanes));
        if spans.in_window().count_ones() < FOUR_AT_A_TIME_MIN {
            for k in kept {
                self.push_in_span(k.screen(), cull, k.lanes.span());
            }
            return;
        }
        let four = FourSmallTriangles::set_up(kept.map(|k| k.screen()), &spans, cull);
        // Each triangle's vertices read again from `kept` (keeping the twelve
        // in registers for the loop costs more).
        for (t, k) in kept.iter().enumerate() {
            match four.lane(t, k.screen()) {
                FourSetUp::OneAtATime => self.push_in_span(k.screen(), cull, k.lanes.span()),
                FourSetUp::Empty => {}
                FourSetUp::Covered {
                    vertices,
                    weights,
                    mask,
                } => self.push_covered(
                    Planes::from_weights(vertices, weights),
                    k.lanes.span(),
                    mask,
                ),
            }
        }
    }

    /// Keeps a small triangle with attribute planes `planes` over box `span`
    /// that covers the centres of `mask` (not empty; see
    /// [`Triangle::masked`]): as a [`Dot`] when that is a single centre.
    #[inline(always)]
    fn push_covered(&mut self, planes: Planes, span: PixelSpan, mask: u64) {
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

/// The triangle `v` wound clockwise on screen with its positive doubled area,
/// or `None` when it has no area or `cull` drops its facing.
#[inline]
fn clockwise(v: [&ScreenVertex; 3], cull: CullMode) -> Option<([&ScreenVertex; 3], i64)> {
    let [a, b, c] = v;
    let area = signed_area(a, b, c);
    // Counter-clockwise in the world, seen from the front, projects to a
    // negative area on the y-down screen. (`SmallTriangle::set_up` applies
    // the same rule to its exact `f32` area; shared through one function, the
    // rule cost the hot loop 1.5 % more instructions, so it is written twice.)
    if area < 0 {
        Some(([a, c, b], -area))
    } else if area > 0 && cull == CullMode::None {
        Some((v, area))
    } else {
        None
    }
}

/// [`build_batch`] in the best machine code for the CPU (see [`Kernels`]).
#[multiversion(targets("x86_64+avx2"))]
fn build_dispatched<P: ClipSource, S: VertexShader>(
    batch: &mut ScreenBatch,
    positions: P,
    shader: S,
    groups: &[TriangleGroup<'_>],
    vp: Viewport,
) {
    build_batch(batch, positions, shader, groups, vp);
}

/// Fills `batch` with `groups` over the vertices of `positions` coloured by
/// `shader` (see [`ScreenBatch::rebuild_shaded`]); inlined into each copy of
/// its callers.
#[inline(always)]
fn build_batch(
    batch: &mut ScreenBatch,
    positions: impl ClipSource,
    shader: impl VertexShader,
    groups: &[TriangleGroup<'_>],
    vp: Viewport,
) {
    let mut projected = std::mem::take(&mut batch.vertices);
    project_vertices(&positions, &shader, vp, &mut projected);
    // What clipping needs of a vertex (the projected ones keep neither):
    // vertex k of the sources is projected vertex k.
    let first_projected = projected.as_ptr() as usize;
    let clip_vertex = |v: &ProjectedVertex| {
        let k = (v as *const ProjectedVertex as usize - first_projected)
            / std::mem::size_of::<ProjectedVertex>();
        ClipVertex {
            pos: positions.clip(k),
            color: shader.color(k),
        }
    };
    let submitted = groups.iter().map(|g| g.triangles.len()).sum();
    // Growing these would copy them; untouched capacity costs nothing.
    batch.tris.clear();
    batch.tris.reserve(submitted);
    batch.dots.clear();
    batch.dots.reserve(submitted);
    batch.edges.clear();
    batch.bands.reset(vp.height);
    let mut polygon = Vec::with_capacity(9);
    let limits = screen_limits(vp.width, vp.height);
    // The vertices of the polygon being clipped.
    let mut clipped = Vec::with_capacity(9);
    // One selected triangle on its own: set up, or clipped first.
    let mut push_kept = |batch: &mut ScreenBatch, kept: &KeptTriangle<'_>, cull: CullMode| {
        if !kept.clip {
            batch.push_in_span(kept.screen(), cull, kept.lanes.span());
            return;
        }
        clip_triangle(kept.vertices.map(clip_vertex), &mut polygon);
        if polygon.is_empty() {
            return;
        }
        // Not clipped again: no outcode needed.
        clipped.clear();
        clipped.extend(
            polygon
                .iter()
                .map(|v| ProjectedVertex::new(vp.project(v), 0)),
        );
        for k in 1..clipped.len() as u32 - 1 {
            batch.push(&clipped, [0, k, k + 1], cull, limits);
        }
    };
    let mut kept = [KeptTriangle::UNUSED; KEEP_CHUNK];
    for group in groups {
        for chunk in group.triangles.chunks(KEEP_CHUNK) {
            // First the triangles that may draw, in order, selected without
            // branches (whether a small triangle's box holds a pixel centre is
            // data-random), then their set-up.
            let mut count = 0;
            for &tri in chunk {
                let vertices = tri.map(|k| &projected[(k - group.first_vertex) as usize]);
                let [pa, pb, pc] = vertices;
                let (ca, cb, cc) = (pa.code, pb.code, pc.code);
                let lanes = SpanLanes::of(pa.centre_box, pb.centre_box, pc.centre_box, limits);
                let clip = (ca | cb | cc) & (OUT_NEAR | OUT_GUARD) != 0;
                let visible = ca & cb & cc & OUT_FRUSTUM == 0;
                // `count` is below the chunk's length: the mask only spares
                // the bounds check.
                kept[count & (KEEP_CHUNK - 1)] = KeptTriangle {
                    vertices,
                    lanes,
                    clip,
                };
                count += usize::from(visible & (clip | !lanes.is_empty()));
            }
            // Four at a time where none needs clipping, in order.
            let (fours, rest) = kept[..count].as_chunks::<4>();
            for four in fours {
                if four.iter().any(|k| k.clip) {
                    for k in four {
                        push_kept(batch, k, group.cull);
                    }
                } else {
                    batch.push_four(four, group.cull);
                }
            }
            for k in rest {
                push_kept(batch, k, group.cull);
            }
        }
    }
    batch.vertices = projected;
}

/// Of four triangles, at least this many must fit the window of
/// [`FourSmallTriangles`] for the four to be set up together (the others are
/// set up again one at a time).
const FOUR_AT_A_TIME_MIN: u32 = 2;

/// Triangles selected at a time before their set-up (a power of two).
const KEEP_CHUNK: usize = 256;

/// A triangle that may draw: not outside the frustum, and either to be
/// clipped or with a pixel centre in its box.
#[derive(Debug, Clone, Copy)]
struct KeptTriangle<'a> {
    /// Its projected vertices.
    vertices: [&'a ProjectedVertex; 3],
    /// Its pixel span.
    lanes: SpanLanes,
    /// Whether it crosses the near plane or the guard band.
    clip: bool,
}

impl<'a> KeptTriangle<'a> {
    /// A placeholder for the slots of a chunk not yet selected.
    const UNUSED: KeptTriangle<'static> = KeptTriangle {
        vertices: [&ProjectedVertex::UNUSED; 3],
        lanes: SpanLanes::EMPTY,
        clip: false,
    };

    /// The screen vertices of its projected vertices.
    #[inline(always)]
    fn screen(&self) -> [&'a ScreenVertex; 3] {
        self.vertices.map(|v| &v.screen)
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
    fn band_entries_keep_order_and_repeat_items_spanning_bands() {
        let b = BAND_ROWS;
        let items = [
            (7, (b + 3, b + 3)),
            (1, (2 * b - 1, 3 * b + 2)),
            (4, (b, 2 * b - 1)),
            (9, (3 * b, 3 * b)),
        ];
        let mut bins = BandEntries::new(5 * b);
        for (id, rows) in items {
            bins.push(id, rows);
        }
        assert!(bins.band(0).is_empty());
        assert_eq!(bins.band(1), &[7, 1, 4]);
        assert_eq!(bins.band(2), &[1]);
        assert_eq!(bins.band(3), &[1, 9]);
        assert!(bins.band(4).is_empty());
        assert!(bins.band(-1).is_empty());
        assert!(BandEntries::new(0).band(0).is_empty());
    }
}
