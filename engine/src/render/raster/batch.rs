//! A batch: the one vertex pass and triangle set-up of a piece of geometry
//! (a terrain patch, a run of a mesh), its triangles binned by bands.

use glam::Vec3;

use super::band::{Band, BandBins};
use super::clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, clip_triangle, outcode};
use super::pixel_shadow::PixelShadow;
use super::triangle::{Plane, ScreenVertex, Triangle};
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

/// A vertex after the vertex pass: on the screen, its outcode, and where
/// it lies in the sun shadow map's light coordinates (zero without one).
struct ProjectedVertex {
    screen: ScreenVertex,
    outcode: u8,
    light: Vec3,
}

/// Screen-space triangles ready to fill, binned by the bands of rows they touch.
#[derive(Debug, Default)]
pub(crate) struct TriangleBatch {
    /// The set-up triangles, in submission order.
    triangles: Vec<Triangle>,
    /// Sun part / w planes of the triangles that resolve shadows per pixel.
    sun_planes: Vec<Plane<Vec3>>,
    /// Indices into `triangles` per band.
    bins: BandBins,
}

impl TriangleBatch {
    /// Projects `verts` (the vertex pass) and sets up every triangle of
    /// `groups`, in order: triangles outside one frustum plane are dropped,
    /// those crossing the near plane or the guard band clipped first.
    /// Triangles with a sun part that a caster of `shadow` may shade keep
    /// their sun plane, to be shaded per pixel.
    pub fn build(
        verts: &[ClipVertex],
        groups: &[TriangleGroup<'_>],
        shadow: Option<&PixelShadow<'_>>,
        vp: Viewport,
    ) -> TriangleBatch {
        // Only a batch with a sun part needs its vertices in light coordinates.
        let light = shadow.filter(|_| verts.iter().any(|v| v.sun != Vec3::ZERO));
        let projected: Vec<ProjectedVertex> = verts
            .iter()
            .map(|v| ProjectedVertex {
                screen: ScreenVertex::project(v, vp),
                outcode: outcode(v.pos),
                light: light.map_or(Vec3::ZERO, |s| s.light_point(v.pos)),
            })
            .collect();
        let mut batch = TriangleBatch {
            triangles: Vec::new(),
            sun_planes: Vec::new(),
            bins: BandBins::new(vp.height),
        };
        let mut polygon = Vec::with_capacity(9);
        for group in groups {
            for tri in group.triangles {
                let tri = tri.map(|k| k - group.first_vertex);
                let [a, b, c] = tri.map(|k| &projected[k as usize]);
                if a.outcode & b.outcode & c.outcode & OUT_FRUSTUM != 0 {
                    continue;
                }
                let corners = tri.map(|k| &verts[k as usize]);
                let shaded = light.is_some_and(|s| {
                    corners.iter().any(|v| v.sun != Vec3::ZERO)
                        && s.may_shade([a.light, b.light, c.light])
                });
                if (a.outcode | b.outcode | c.outcode) & (OUT_NEAR | OUT_GUARD) == 0 {
                    let screen = [&a.screen, &b.screen, &c.screen];
                    batch.set_up(screen, group.cull, shaded, vp);
                    continue;
                }
                clip_triangle(corners.map(|v| *v), &mut polygon);
                let fan: Vec<ScreenVertex> = polygon
                    .iter()
                    .map(|v| ScreenVertex::project(v, vp))
                    .collect();
                for k in 1..fan.len().saturating_sub(1) {
                    let v = [&fan[0], &fan[k], &fan[k + 1]];
                    batch.set_up(v, group.cull, shaded, vp);
                }
            }
        }
        batch
    }

    /// Sets up a triangle (with its sun plane when `with_sun`) and keeps
    /// it, binned by the bands it touches.
    fn set_up(&mut self, v: [&ScreenVertex; 3], cull: CullMode, with_sun: bool, vp: Viewport) {
        let set_up = if with_sun {
            Triangle::set_up_with_sun(v, cull, vp).map(|(mut t, sun)| {
                t.sun_plane = Some(self.sun_planes.len() as u32);
                self.sun_planes.push(sun);
                t
            })
        } else {
            Triangle::set_up(v, cull, vp)
        };
        if let Some(t) = set_up {
            self.bins.push(self.triangles.len() as u32, t.rows());
            self.triangles.push(t);
        }
    }

    /// Number of set-up triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Fills the band (band index `band`) with the triangles touching it, in
    /// submission order; triangles with a sun plane are shaded per pixel by
    /// `shadow` (the one the batch was built with).
    pub fn draw_band(&self, band: i32, target: &mut Band<'_>, shadow: Option<&PixelShadow<'_>>) {
        for &k in self.bins.band(band) {
            let t = &self.triangles[k as usize];
            match (t.sun_plane, shadow) {
                (Some(sun), Some(shadow)) => {
                    t.draw_with_shadow(target, &self.sun_planes[sun as usize], shadow);
                }
                _ => t.draw(target),
            }
        }
    }
}
