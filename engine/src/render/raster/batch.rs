//! A batch: the one vertex pass and triangle set-up of a piece of geometry
//! (a terrain patch, a run of a mesh), its triangles binned by bands.

use super::band::{Band, BandBins};
use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle, outcode};
use super::triangle::{ScreenVertex, Triangle};
use super::viewport::{CullMode, Viewport};

/// A run of triangles sharing one cull mode, indexing a vertex slice.
pub(crate) struct TriangleGroup<'a> {
    /// Triangles as three vertex indices.
    pub triangles: &'a [[u32; 3]],
    /// Facing to drop.
    pub cull: CullMode,
    /// The index the triangles give the vertex slice's first vertex
    /// (subtracted from every index as it is read).
    pub first_vertex: u32,
}

/// Screen-space triangles ready to fill, binned by the bands of rows they touch.
#[derive(Debug, Default)]
pub(crate) struct TriangleBatch {
    /// The set-up triangles, in submission order.
    triangles: Vec<Triangle>,
    /// Indices into `triangles` per band.
    bins: BandBins,
}

impl TriangleBatch {
    /// Projects `verts` (the vertex pass) and sets up every triangle of
    /// `groups`, in order: triangles outside one frustum plane are dropped,
    /// those crossing the near plane or the guard band clipped first.
    pub fn build(
        verts: &[ClipVertex],
        groups: &[TriangleGroup<'_>],
        vp: Viewport,
    ) -> TriangleBatch {
        let projected: Vec<(ScreenVertex, u8)> = verts
            .iter()
            .map(|v| (ScreenVertex::project(v, vp), outcode(v.pos)))
            .collect();
        let mut batch = TriangleBatch {
            triangles: Vec::new(),
            bins: BandBins::new(vp.height),
        };
        let mut polygon = Vec::with_capacity(9);
        for group in groups {
            for tri in group.triangles {
                let tri = tri.map(|k| k - group.first_vertex);
                let [a, b, c] = tri.map(|k| &projected[k as usize]);
                if a.1 & b.1 & c.1 & OUT_FRUSTUM != 0 {
                    continue;
                }
                if (a.1 | b.1 | c.1) & (OUT_NEAR | OUT_GUARD) == 0 {
                    batch.push(Triangle::set_up([&a.0, &b.0, &c.0], group.cull, vp));
                    continue;
                }
                clip_triangle(tri.map(|k| verts[k as usize]), &mut polygon);
                let fan: Vec<ScreenVertex> = polygon
                    .iter()
                    .map(|v| ScreenVertex::project(v, vp))
                    .collect();
                for k in 1..fan.len().saturating_sub(1) {
                    let v = [&fan[0], &fan[k], &fan[k + 1]];
                    batch.push(Triangle::set_up(v, group.cull, vp));
                }
            }
        }
        batch
    }

    /// Keeps a set-up triangle, binned by the bands it touches.
    fn push(&mut self, triangle: Option<Triangle>) {
        if let Some(t) = triangle {
            self.bins.push(self.triangles.len() as u32, t.rows());
            self.triangles.push(t);
        }
    }

    /// Number of set-up triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Fills the band (band index `band`) with the triangles touching it, in
    /// submission order.
    pub fn draw_band(&self, band: i32, target: &mut Band<'_>) {
        for &t in self.bins.band(band) {
            self.triangles[t as usize].draw(target);
        }
    }
}
