//! Height-grid surfaces drawn by patches with frustum culling, distance level of
//! detail (geomipmapping) and skirts against cracks between levels.
//!
//! Patches re-mesh under each rectangle given to [`TerrainRenderer::mark_dirty`]
//! (heights or colours changed; all of them when the sun moves); the vertex colours of every level live in one
//! pyramid over the whole grid, re-lit where a change's light reaches
//! ([`TerrainRenderer::update`] does both).

use std::collections::BTreeMap;

use glam::Vec3;
use rayon::prelude::*;

use super::camera::Camera;
use super::error::{RenderError, positive};
use super::frame_view::FrameView;
use super::raster::{ClipVertex, CullMode, TriangleBatch, TriangleGroup};
use super::shade_pyramid::{Shade, ShadePyramid};
use super::shading::{Lighting, Sun, encode_display};
use super::terrain_colors::TerrainColors;
use super::terrain_light::{LightReach, TerrainLight};
use super::terrain_patch::{Patch, level_steps, offsets};
use crate::geom::{GridRect, HeightGrid};

/// How a [`TerrainRenderer`] cuts, levels and shades the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TerrainStyle {
    /// Cells per patch side (a power of two, 2..=256).
    pub patch_cells: usize,
    /// Radius of the sky-view (ambient occlusion) probe, in metres.
    pub ao_radius: f32,
    /// Longest shadow, in metres.
    pub shadow_range: f32,
    /// How much a fully disturbed sample is darkened (0..1).
    pub disturbed_darkening: f32,
    /// How much the hollow's occlusion also dims the sun on a sample (0..1):
    /// its light is scaled by `1 - hollow_darkening * (1 - sky_view)`, so a
    /// print's floor and lower walls read darker than the open ground even
    /// where the sun reaches them (bright snow would otherwise clip to white).
    pub hollow_darkening: f32,
    /// A level of detail is used only while its cells stay below this many pixels.
    pub max_cell_px: f32,
    /// ... and its height error below this many pixels.
    pub max_error_px: f32,
    /// A level whose colours stray from the samples' by more than this
    /// (display units, 0..1: prints, trails) ...
    pub max_color_error: f32,
    /// ... is used only while its cells stay below this many pixels, so that
    /// trampled ground shows its trails from afar.
    pub color_detail_px: f32,
}

impl Default for TerrainStyle {
    fn default() -> Self {
        TerrainStyle {
            patch_cells: 32,
            ao_radius: 0.3,
            shadow_range: 4.0,
            disturbed_darkening: 0.25,
            hollow_darkening: 0.8,
            max_cell_px: 12.0,
            max_error_px: 1.0,
            max_color_error: 0.03,
            color_detail_px: 6.0,
        }
    }
}

impl TerrainStyle {
    fn validate(&self) -> Result<(), RenderError> {
        if !(self.patch_cells.is_power_of_two() && (2..=256).contains(&self.patch_cells)) {
            return Err(RenderError::InvalidParameter {
                name: "patch_cells",
                reason: format!("{} must be a power of two in 2..=256", self.patch_cells),
            });
        }
        positive("ao_radius", self.ao_radius)?;
        positive("shadow_range", self.shadow_range)?;
        positive("max_cell_px", self.max_cell_px)?;
        positive("max_error_px", self.max_error_px)?;
        positive("max_color_error", self.max_color_error)?;
        positive("color_detail_px", self.color_detail_px)?;
        for (name, share) in [
            ("disturbed_darkening", self.disturbed_darkening),
            ("hollow_darkening", self.hollow_darkening),
        ] {
            if !(0.0..=1.0).contains(&share) {
                return Err(RenderError::InvalidParameter {
                    name,
                    reason: format!("{share} must lie in [0, 1]"),
                });
            }
        }
        Ok(())
    }
}

/// Draws a [`HeightGrid`] by patches. Create it once, call
/// [`mark_dirty`](TerrainRenderer::mark_dirty) with what changed and
/// [`update`](TerrainRenderer::update) before rendering a frame.
#[derive(Debug, Clone)]
pub struct TerrainRenderer {
    style: TerrainStyle,
    nx: usize,
    nz: usize,
    cell: f32,
    origin: glam::Vec2,
    patches_x: usize,
    patches: Vec<Patch>,
    /// Triangles of a `cols` x `rows` vertex grid, shared by all patches.
    indices: BTreeMap<(usize, usize), Vec<[u32; 3]>>,
    light: TerrainLight,
    /// Vertex colours of every level.
    shades: ShadePyramid,
    lit_with: Option<Sun>,
    pending: Vec<GridRect>,
    /// Patches under a rectangle given to `mark_dirty` since the last update.
    needs_remesh: Vec<bool>,
    /// Patches whose colours changed.
    needs_recolor: Vec<bool>,
    remeshed_last: usize,
}

impl TerrainRenderer {
    /// A renderer for grids shaped like `grid`. Everything is dirty until the first
    /// [`update`](TerrainRenderer::update).
    pub fn new(grid: &HeightGrid, style: TerrainStyle) -> Result<TerrainRenderer, RenderError> {
        style.validate()?;
        let p = style.patch_cells;
        let (cx, cz) = (grid.nx() - 1, grid.nz() - 1);
        let (patches_x, patches_z) = (cx.div_ceil(p), cz.div_ceil(p));
        let mut patches = Vec::with_capacity(patches_x * patches_z);
        for pj in 0..patches_z {
            for pi in 0..patches_x {
                let (i0, j0) = (pi * p, pj * p);
                patches.push(Patch::new(i0, j0, p.min(cx - i0), p.min(cz - j0)));
            }
        }
        let mut indices = BTreeMap::new();
        for patch in &patches {
            for step in level_steps(p) {
                let m = offsets(patch.cells_x, step).len();
                let n = offsets(patch.cells_z, step).len();
                indices
                    .entry((m, n))
                    .or_insert_with(|| grid_triangles(m, n));
            }
        }
        let count = patches.len();
        Ok(TerrainRenderer {
            style,
            nx: grid.nx(),
            nz: grid.nz(),
            cell: grid.cell_size(),
            origin: grid.origin(),
            patches_x,
            patches,
            indices,
            light: TerrainLight::new(grid),
            shades: ShadePyramid::new(grid.nx(), grid.nz(), level_steps(p).count()),
            lit_with: None,
            pending: vec![grid.full_rect()],
            needs_remesh: vec![false; count],
            needs_recolor: vec![false; count],
            remeshed_last: 0,
        })
    }

    /// The style in use.
    pub fn style(&self) -> &TerrainStyle {
        &self.style
    }

    /// Number of patches.
    pub fn patch_count(&self) -> usize {
        self.patches.len()
    }

    /// Number of patches re-meshed by the last [`update`](TerrainRenderer::update).
    pub fn remeshed_last_update(&self) -> usize {
        self.remeshed_last
    }

    /// The lowest height of the ground as last [`update`](TerrainRenderer::update)d.
    pub fn lowest_height(&self) -> f32 {
        self.patches
            .iter()
            .map(|p| p.min_h)
            .fold(f32::INFINITY, f32::min)
    }

    /// Reports that heights (or colours) inside `rect` changed.
    pub fn mark_dirty(&mut self, rect: GridRect) {
        let rect = rect.intersect(&GridRect::new(0, 0, self.nx, self.nz));
        if !rect.is_empty() {
            self.pending.push(rect);
        }
    }

    /// True when changes are waiting for [`update`](TerrainRenderer::update).
    pub fn is_dirty(&self) -> bool {
        !self.pending.is_empty()
    }

    fn reach(&self) -> LightReach {
        let steps = |metres: f32| ((metres / self.cell).ceil() as usize).max(1);
        LightReach {
            sky: steps(self.style.ao_radius),
            shadow: steps(self.style.shadow_range),
        }
    }

    /// Recomputes light and colours in the dirty windows (plus their light's
    /// reach) and re-meshes the patches under them; everything
    /// when the sun changed. `grid` must have the shape given to
    /// [`TerrainRenderer::new`].
    pub fn update<C: TerrainColors + Sync + ?Sized>(
        &mut self,
        grid: &HeightGrid,
        colors: &C,
        lighting: &Lighting,
    ) -> Result<(), RenderError> {
        if grid.nx() != self.nx
            || grid.nz() != self.nz
            || grid.cell_size() != self.cell
            || grid.origin() != self.origin
        {
            return Err(RenderError::InvalidParameter {
                name: "grid",
                reason: format!(
                    "{} x {} samples of {} m do not match the renderer's {} x {} of {} m",
                    grid.nx(),
                    grid.nz(),
                    grid.cell_size(),
                    self.nx,
                    self.nz,
                    self.cell
                ),
            });
        }
        if self.lit_with != Some(lighting.sun) {
            self.pending = vec![grid.full_rect()];
            self.lit_with = Some(lighting.sun);
        }
        let reach = self.reach();
        let sun_dir = lighting.sun.direction;
        let pending = std::mem::take(&mut self.pending);
        let relit = self.light.relight(grid, &pending, sun_dir, reach);
        let (style, light) = (&self.style, &self.light);
        self.shades.update(&relit, |i, j| {
            sample_shade(grid, colors, lighting, light, style, i, j)
        });
        let p = self.style.patch_cells;
        for rect in &pending {
            for k in self.patches_touching(rect) {
                self.needs_remesh[k] = true;
            }
        }
        // A coarse vertex's colour reads samples up to a patch away.
        for window in &relit {
            for k in self.patches_touching(&window.expand(p, self.nx, self.nz)) {
                self.needs_recolor[k] = true;
            }
        }
        let (shades, enough) = (&self.shades, self.style.max_color_error);
        self.patches
            .par_iter_mut()
            .zip(self.needs_remesh.par_iter())
            .zip(self.needs_recolor.par_iter())
            .filter(|((_, remesh), recolor)| **remesh || **recolor)
            .for_each(|((patch, remesh), _)| {
                if *remesh {
                    patch.remesh(grid, p);
                }
                patch.measure_colors(shades, enough);
            });
        self.remeshed_last = self.needs_remesh.iter().filter(|f| **f).count();
        self.needs_remesh.iter_mut().for_each(|f| *f = false);
        self.needs_recolor.iter_mut().for_each(|f| *f = false);
        Ok(())
    }

    /// The indices of the patches holding a sample of `window` (a sample on
    /// a patch border belongs to both patches).
    fn patches_touching(&self, window: &GridRect) -> impl Iterator<Item = usize> + use<> {
        let p = self.style.patch_cells;
        let patches_x = self.patches_x;
        let pi0 = window.i0.saturating_sub(1) / p;
        let pj0 = window.j0.saturating_sub(1) / p;
        let pi1 = (window.i1.saturating_sub(1) / p).min(patches_x - 1);
        let pz = self.patches.len() / patches_x;
        let pj1 = (window.j1.saturating_sub(1) / p).min(pz - 1);
        (pj0..=pj1).flat_map(move |pj| (pi0..=pi1).map(move |pi| pj * patches_x + pi))
    }

    /// Chooses a level per patch (`None` when culled) for this camera.
    fn choose_levels(&self, camera: &Camera) -> Vec<Option<usize>> {
        let planes = camera.frustum_planes();
        let focal = camera.focal_px();
        self.patches
            .iter()
            .map(|patch| {
                if patch.levels.is_empty() {
                    return None;
                }
                let (min, max) = patch.bounds(self.origin, self.cell);
                // Skirts hang below the patch; keep them in the culling box.
                let skirt = patch.levels.last().map_or(0.0, |l| 2.0 * l.error) + self.cell;
                let min = min - Vec3::Y * skirt;
                if !camera.sees_box(&planes, min, max) {
                    return None;
                }
                let distance = (camera.eye.clamp(min, max) - camera.eye).length().max(1e-3);
                let px_per_metre = focal / distance;
                let mut chosen = 0;
                for (l, level) in patch.levels.iter().enumerate().skip(1) {
                    let step_px = self.cell * (1 << l) as f32 * px_per_metre;
                    let error_px = level.error * px_per_metre;
                    let hides_colors = level.color_error > self.style.max_color_error
                        && step_px > self.style.color_detail_px;
                    if step_px > self.style.max_cell_px
                        || error_px > self.style.max_error_px
                        || hides_colors
                    {
                        break;
                    }
                    chosen = l;
                }
                Some(chosen)
            })
            .collect()
    }

    /// The patches `camera` sees, in patch order, each with the level and
    /// the skirts it is drawn with.
    fn visible_patches(&self, camera: &Camera) -> Vec<DrawnPatch> {
        let levels = self.choose_levels(camera);
        let pz = self.patches.len() / self.patches_x;
        (0..self.patches.len())
            .filter_map(|k| {
                let level = levels[k]?;
                let (pi, pj) = (k % self.patches_x, k / self.patches_x);
                let neighbour = |di: isize, dj: isize| -> Option<Neighbour> {
                    let (ni, nj) = (pi as isize + di, pj as isize + dj);
                    if ni < 0 || nj < 0 || ni >= self.patches_x as isize || nj >= pz as isize {
                        return None;
                    }
                    let n = nj as usize * self.patches_x + ni as usize;
                    let l = levels[n]?;
                    (l != level).then(|| Neighbour {
                        level: l,
                        error: self.patches[n].levels[l].error,
                    })
                };
                // Sides: -Z (first row), +Z (last row), -X (first column), +X (last column).
                let skirts = [
                    neighbour(0, -1),
                    neighbour(0, 1),
                    neighbour(-1, 0),
                    neighbour(1, 0),
                ];
                Some(DrawnPatch {
                    index: k,
                    level,
                    skirts,
                })
            })
            .collect()
    }
}

impl TerrainRenderer {
    /// The visible patches' batches as `view` sees them, in patch order, at
    /// the level each is drawn with, with skirts where a neighbour is drawn
    /// coarser.
    pub(crate) fn batches(&self, view: &FrameView<'_>) -> Vec<TriangleBatch> {
        self.visible_patches(view.camera)
            .par_iter()
            .map(|drawn| self.batch(drawn, view))
            .collect()
    }

    /// One visible patch's batch.
    fn batch(&self, drawn: &DrawnPatch, view: &FrameView<'_>) -> TriangleBatch {
        let DrawnPatch {
            index: k,
            level,
            skirts,
        } = *drawn;
        let patch = &self.patches[k];
        let lod = &patch.levels[level];
        let (m, n) = (lod.cols.len(), lod.rows.len());
        let mut verts = Vec::with_capacity(m * n + 2 * (m + n));
        let world = |c: usize, r: usize, h: f32| {
            Vec3::new(
                self.origin.x + (patch.i0 + lod.cols[c]) as f32 * self.cell,
                h,
                self.origin.y + (patch.j0 + lod.rows[r]) as f32 * self.cell,
            )
        };
        let eye = view.camera.eye;
        let (min, max) = patch.bounds(self.origin, self.cell);
        // Casters' shadows are resolved per pixel, where one may fall.
        let shaded = view.casters_may_shade(min - Vec3::Y * lod.error, max);
        let shades = self.vertex_shades(drawn);
        let vertex = |p: Vec3, v: usize| {
            let fog = view.lighting.fog_amount((p - eye).length());
            let Shade { lit, shaded: dark } = shades[v];
            let color = view.lighting.blend_fog(lit, fog);
            let sun = if shaded {
                (lit - dark) * (1.0 - fog)
            } else {
                Vec3::ZERO
            };
            ClipVertex {
                pos: view.view_proj * p.extend(1.0),
                color,
                sun,
            }
        };
        for r in 0..n {
            for c in 0..m {
                let v = r * m + c;
                verts.push(vertex(world(c, r, lod.heights[v]), v));
            }
        }
        let mut skirt_tris = Vec::new();
        let sides: [Vec<(usize, usize)>; 4] = [
            (0..m).map(|c| (c, 0)).collect(),
            (0..m).map(|c| (c, n - 1)).collect(),
            (0..n).map(|r| (0, r)).collect(),
            (0..n).map(|r| (m - 1, r)).collect(),
        ];
        for (side, neighbour) in sides.iter().zip(skirts) {
            let Some(neighbour) = neighbour else {
                continue;
            };
            let depth = lod.error + neighbour.error + 0.25 * self.cell;
            let base = verts.len() as u32;
            for &(c, r) in side {
                let v = r * m + c;
                verts.push(vertex(world(c, r, lod.heights[v] - depth), v));
            }
            for (s, pair) in side.windows(2).enumerate() {
                let top = |(c, r): (usize, usize)| (r * m + c) as u32;
                let (a, b) = (top(pair[0]), top(pair[1]));
                let (sa, sb) = (base + s as u32, base + s as u32 + 1);
                skirt_tris.push([a, b, sb]);
                skirt_tris.push([a, sb, sa]);
            }
        }
        let surface = &self.indices[&(m, n)];
        TriangleBatch::build(
            &verts,
            &[
                TriangleGroup {
                    triangles: surface,
                    cull: CullMode::Back,
                    first_vertex: 0,
                },
                TriangleGroup {
                    triangles: &skirt_tris,
                    cull: CullMode::None,
                    first_vertex: 0,
                },
            ],
            view.pixel_shadow.as_ref(),
            view.vp,
        )
    }
}

impl TerrainRenderer {
    /// The colours of a drawn patch's vertices, row-major. A vertex on a
    /// side whose neighbour is drawn coarser takes the coarser level's
    /// colours there (the coarsest, at a corner between two such sides), so
    /// both patches show the same colours along their border.
    fn vertex_shades(&self, drawn: &DrawnPatch) -> Vec<Shade> {
        let patch = &self.patches[drawn.index];
        let lod = &patch.levels[drawn.level];
        let (m, n) = (lod.cols.len(), lod.rows.len());
        let own = self.shades.level(drawn.level);
        let coarser = drawn
            .skirts
            .map(|side| side.filter(|s| s.level > drawn.level).map(|s| s.level));
        let mut shades = Vec::with_capacity(m * n);
        for (r, &row) in lod.rows.iter().enumerate() {
            for (c, &col) in lod.cols.iter().enumerate() {
                let (i, j) = (patch.i0 + col, patch.j0 + row);
                // Sides: -Z (first row), +Z (last row), -X (first column), +X (last column).
                let on_side = [r == 0, r == n - 1, c == 0, c == m - 1];
                let border = on_side
                    .iter()
                    .zip(coarser)
                    .filter_map(|(on, level)| level.filter(|_| *on))
                    .max();
                shades.push(match border {
                    Some(level) => self.shades.level(level).between(i, j),
                    None => own.at_sample(i, j),
                });
            }
        }
        shades
    }
}

/// A visible patch as a frame draws it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DrawnPatch {
    /// Its index in the renderer's patches.
    index: usize,
    /// Its level of detail.
    level: usize,
    /// Per side (-Z, +Z, -X, +X), the neighbour drawn at another level: a
    /// skirt hangs there.
    skirts: [Option<Neighbour>; 4],
}

/// A patch's neighbour drawn at another level of detail.
#[derive(Debug, Clone, Copy)]
struct Neighbour {
    /// Its level.
    level: usize,
    /// That level's height error.
    error: f32,
}

/// The colours of sample `(i, j)`: its albedo, darkened where disturbed and
/// in hollows, lit by the sun and sky as far as the terrain lets them reach,
/// and with the sun hidden.
fn sample_shade<C: TerrainColors + ?Sized>(
    grid: &HeightGrid,
    colors: &C,
    lighting: &Lighting,
    light: &TerrainLight,
    style: &TerrainStyle,
    i: usize,
    j: usize,
) -> Shade {
    let k = grid.index(i, j);
    let sky = light.sky_view[k];
    let albedo = colors.albedo(i, j)
        * (1.0 - style.disturbed_darkening * colors.disturbance(i, j).clamp(0.0, 1.0))
        * (1.0 - style.hollow_darkening * (1.0 - sky));
    let normal = grid.sample_normal(i, j);
    Shade {
        lit: encode_display(lighting.radiance(albedo, normal, sky, light.sun_visible[k])),
        shaded: encode_display(lighting.radiance(albedo, normal, sky, 0.0)),
    }
}

/// Triangles of an `m` x `n` vertex grid (row-major), counter-clockwise seen
/// from +Y, split along the `(c, r)`-`(c + 1, r + 1)` diagonal like [`HeightGrid`].
fn grid_triangles(m: usize, n: usize) -> Vec<[u32; 3]> {
    let mut tris = Vec::with_capacity(2 * (m - 1) * (n - 1));
    for r in 0..n - 1 {
        for c in 0..m - 1 {
            let a = (r * m + c) as u32;
            let b = a + 1;
            let cc = a + m as u32;
            let d = cc + 1;
            tris.push([a, d, b]);
            tris.push([a, cc, d]);
        }
    }
    tris
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_triangles_face_up() {
        let tris = grid_triangles(3, 2);
        assert_eq!(tris.len(), 4);
        let pos = |v: u32| Vec3::new((v % 3) as f32, 0.0, (v / 3) as f32);
        for t in tris {
            let n = (pos(t[1]) - pos(t[0])).cross(pos(t[2]) - pos(t[0]));
            assert!(n.y > 0.0);
        }
    }
}
