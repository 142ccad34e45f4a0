//! The geometry stage: clip-space vertices and triangles become a [`ScreenBatch`]
//! of set-up triangles (culled, clipped, wound clockwise on screen, covering at
//! least one pixel centre), binned by bands, which the bands then fill.

use glam::{Vec3, Vec4};

use super::at_once::DrawnAtOnce;
use super::clip::ClipVertex;
use super::kernels::Kernels;
use super::project::{ClipSource, LANES, ProjectedVertex, VertexShader, position_lanes};
use super::raster::{Band, Dot, Edges, ONE, PixelSpan, ScreenVertex, Triangle};
use super::set_up::{TriangleSink, set_up};

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
        let submitted = groups.iter().map(|g| g.triangles.len()).sum();
        // Growing these would copy them; untouched capacity costs nothing.
        self.tris.clear();
        self.tris.reserve(submitted);
        self.dots.clear();
        self.dots.reserve(submitted);
        self.edges.clear();
        self.bands.reset(vp.height);
        let mut projected = std::mem::take(&mut self.vertices);
        set_up(self, &mut projected, positions, shader, groups, vp, kernels);
        self.vertices = projected;
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
}

impl TriangleSink for ScreenBatch {
    #[inline(always)]
    fn edges(&mut self) -> &mut Vec<Edges> {
        &mut self.edges
    }

    #[inline(always)]
    fn triangle(&mut self, tri: Triangle, span: PixelSpan) {
        self.bands.push(self.tris.len() as u32, (span.y0, span.y1));
        self.tris.push(tri);
    }

    #[inline(always)]
    fn dot(&mut self, dot: Dot) {
        self.bands
            .push(self.dots.len() as u32 | DOT_ENTRY, (dot.row(), dot.row()));
        self.dots.push(dot);
    }
}

/// Where one batch of geometry goes once set up.
pub(crate) enum BatchTarget<'t, 'f> {
    /// Kept in a screen batch, binned by bands, to be drawn band by band
    /// (the bands in parallel).
    Binned(&'t mut ScreenBatch),
    /// Drawn at once into a whole frame drawn on one thread (see
    /// [`DrawnAtOnce`]), a screen batch lending its buffers.
    AtOnce {
        /// The batch whose buffers the set-up uses.
        scratch: &'t mut ScreenBatch,
        /// The frame, already cleared.
        frame: &'t mut Band<'f>,
    },
}

impl BatchTarget<'_, '_> {
    /// Sets up every triangle of `groups` over `verts` into the target.
    /// Returns how many triangles were kept or drawn.
    pub fn build(
        self,
        verts: &[ClipVertex],
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
        kernels: Kernels,
    ) -> usize {
        let verts = ClipVertexList(verts);
        self.build_shaded(verts, verts, groups, vp, kernels)
    }

    /// [`BatchTarget::build`] with the vertices of `positions` coloured by
    /// `shader` (see [`ScreenBatch::rebuild_shaded`]).
    pub fn build_shaded<P: ClipSource, S: VertexShader>(
        self,
        positions: P,
        shader: S,
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
        kernels: Kernels,
    ) -> usize {
        match self {
            BatchTarget::Binned(batch) => {
                batch.rebuild_shaded(positions, shader, groups, vp, kernels);
                batch.len()
            }
            BatchTarget::AtOnce { scratch, frame } => {
                // The batch lends its buffers and is left empty.
                scratch.tris.clear();
                scratch.dots.clear();
                scratch.bands.reset(vp.height);
                let mut sink = DrawnAtOnce::new(frame, &mut scratch.edges);
                let projected = &mut scratch.vertices;
                set_up(&mut sink, projected, positions, shader, groups, vp, kernels);
                sink.drawn()
            }
        }
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
