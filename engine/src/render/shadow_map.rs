//! Sun shadows of meshes and grass: what the sun sees of the shadow casters,
//! as the height towards the sun of the topmost caster per texel of a grid
//! across the sun's rays ([`MapFrame`]). A point is in shadow when a caster
//! stands above it towards the sun. Meshes and blades look their visibility
//! up per vertex; the terrain per pixel, where a coarse grid of the
//! casters' tops says a shadow may fall (see [`super::raster::PixelShadow`]).

use glam::{Mat4, Vec2, Vec3};

use super::camera::Camera;
use super::grass_blade::GrassBlade;
use super::shadow_fit::MapFrame;

/// How far above its own caster surface a receiver must lie to be lit, in
/// texels (the surface is only known per texel).
const BIAS_TEXELS: f32 = 1.5;
/// How far a vertex receiver is moved along its normal before its lookup,
/// in texels: a surface that casts does not shade itself where the sun
/// grazes it.
const NORMAL_OFFSET_TEXELS: f32 = 1.5;
/// Blades whose root lies farther than this (metres, per axis) outside the
/// camera's view cast no shadow: the shadows they cast fall out of view.
const BLADE_REACH: f32 = 1.5;
/// Points along a blade that cast, as fractions of the way from root to
/// tip (the lower part shades only the ground the blade stands on).
const BLADE_SAMPLES: [f32; 3] = [0.5, 0.75, 1.0];
/// Texels per side of a tile of the coarse grid of caster tops.
const TILE: usize = 8;

/// The topmost caster towards the sun per texel of a grid across the sun's rays.
#[derive(Debug, Clone)]
pub(crate) struct ShadowMap {
    /// The grid and its light coordinates.
    frame: MapFrame,
    /// Highest caster coordinate towards the sun per texel (row-major);
    /// `-inf` where nothing casts.
    top: Vec<f32>,
    /// Columns of the tile grid.
    tile_cols: usize,
    /// Highest caster per tile of [`TILE`] x [`TILE`] texels (row-major).
    tile_top: Vec<f32>,
}

impl ShadowMap {
    /// The shadow map of world-space `triangles` (of meshes) and `blades`
    /// under a sun in direction `toward_sun` (unit) over the part of the
    /// world `camera` sees, on ground no lower than `ground_low`; `None` when
    /// nothing casts there or the sun is down.
    /// Only blades near what `camera` sees cast.
    pub fn build(
        triangles: &[[Vec3; 3]],
        blades: &[GrassBlade],
        toward_sun: Vec3,
        camera: &Camera,
        ground_low: Option<f32>,
    ) -> Option<ShadowMap> {
        if toward_sun.y <= 0.0 {
            return None;
        }
        let planes = camera.frustum_planes();
        let near_view = |b: &&GrassBlade| {
            let reach = Vec3::splat(BLADE_REACH);
            camera.sees_box(&planes, b.root - reach, b.root + reach)
        };
        let blades: Vec<&GrassBlade> = blades.iter().filter(near_view).collect();
        let blade_points = blades.iter().map(|b| [b.root, b.mid, b.tip]);
        let casters = triangles.iter().copied().chain(blade_points);
        let frame = MapFrame::fit(casters, toward_sun, camera, ground_low)?;
        let mut map = ShadowMap {
            frame,
            top: vec![f32::NEG_INFINITY; frame.cols * frame.rows],
            tile_cols: 0,
            tile_top: Vec::new(),
        };
        for t in triangles {
            map.cast_triangle(t);
        }
        for b in &blades {
            map.cast_blade(b);
        }
        map.gather_tiles();
        Some(map)
    }

    /// World point to light coordinates: texel column, row and height
    /// towards the sun.
    pub fn to_light(&self) -> Mat4 {
        self.frame.to_light
    }

    /// Light coordinates of `p`.
    #[inline]
    fn locate(&self, p: Vec3) -> Vec3 {
        self.frame.to_light.transform_point3(p)
    }

    /// Raises the texel under map point `p` (texel coordinates, height) to
    /// its height; points off the map raise nothing.
    #[inline]
    fn raise_at(&mut self, p: Vec3) {
        if p.x >= 0.0 && p.y >= 0.0 {
            self.raise(p.x as usize, p.y as usize, p.z);
        }
    }

    /// Raises texel `(i, j)` to height `h`.
    #[inline]
    fn raise(&mut self, i: usize, j: usize, h: f32) {
        if i < self.frame.cols && j < self.frame.rows {
            let t = &mut self.top[j * self.frame.cols + i];
            *t = t.max(h);
        }
    }

    /// Raises the texels whose centres a world triangle covers to its height
    /// there. A triangle thinner than a texel in the map (seen almost
    /// edge-on by the sun, as along a round caster's outline) raises every
    /// texel it touches instead, to at most its highest corner's height, so
    /// that it leaves no gaps.
    fn cast_triangle(&mut self, t: &[Vec3; 3]) {
        let [a, b, c] = t.map(|p| self.locate(p));
        let (a2, b2, c2) = (a.truncate(), b.truncate(), c.truncate());
        let area = (b2 - a2).perp_dot(c2 - a2);
        if area.abs() < 1e-12 {
            // Seen edge-on by the sun: its corners still cast.
            for p in [a, b, c] {
                self.raise_at(p);
            }
            return;
        }
        let lo = (a2.min(b2).min(c2) - Vec2::splat(0.5)).max(Vec2::ZERO);
        let last = Vec2::new(self.frame.cols as f32, self.frame.rows as f32) - Vec2::ONE;
        let hi = (a2.max(b2).max(c2) + Vec2::splat(0.5)).min(last);
        if !(lo.x <= hi.x && lo.y <= hi.y) {
            return;
        }
        // Barycentric weights of a and b and the height as planes over the
        // texel centres (value = gradient . p + offset). A texel touches the
        // triangle's side of an edge when its weight at the centre is at
        // least minus half the weight's change across the texel.
        let inv = 1.0 / area;
        let weight = |from: Vec2, to: Vec2| {
            let gradient = Vec2::new(from.y - to.y, to.x - from.x) * inv;
            (gradient, -gradient.dot(from))
        };
        let (ga, oa) = weight(b2, c2);
        let (gb, ob) = weight(c2, a2);
        let longest = [b2 - a2, c2 - b2, a2 - c2]
            .map(Vec2::length)
            .into_iter()
            .fold(0.0, f32::max);
        let thin = area.abs() < longest;
        // A hair of slack otherwise, so that neighbouring triangles leave
        // no gap along their shared edge.
        let reach = |g: Vec2| {
            if thin {
                -0.5 * g.abs().element_sum()
            } else {
                -1e-4
            }
        };
        let (ra, rb, rc) = (reach(ga), reach(gb), reach(ga + gb));
        let (dha, dhb) = (a.z - c.z, b.z - c.z);
        let (gh, oh) = (ga * dha + gb * dhb, oa * dha + ob * dhb + c.z);
        let highest = a.z.max(b.z).max(c.z);
        for j in lo.y as usize..=hi.y as usize {
            let y = j as f32 + 0.5;
            let row = j * self.frame.cols;
            for i in lo.x as usize..=hi.x as usize {
                let p = Vec2::new(i as f32 + 0.5, y);
                let (wa, wb) = (ga.dot(p) + oa, gb.dot(p) + ob);
                if wa >= ra && wb >= rb && 1.0 - wa - wb >= rc {
                    let t = &mut self.top[row + i];
                    *t = t.max((gh.dot(p) + oh).min(highest));
                }
            }
        }
    }

    /// Marks the texels under points along the upper half of a blade.
    fn cast_blade(&mut self, b: &GrassBlade) {
        for t in BLADE_SAMPLES {
            // The quadratic through root, mid (t = 0.5) and tip.
            let p = b.root * ((1.0 - t) * (1.0 - 2.0 * t))
                + b.mid * (4.0 * t * (1.0 - t))
                + b.tip * (t * (2.0 * t - 1.0));
            self.raise_at(self.locate(p));
        }
    }

    /// Fills the tile grid with the highest caster of each tile.
    fn gather_tiles(&mut self) {
        let cols = self.frame.cols;
        self.tile_cols = cols.div_ceil(TILE);
        let tile_rows = self.frame.rows.div_ceil(TILE);
        self.tile_top = vec![f32::NEG_INFINITY; self.tile_cols * tile_rows];
        for (j, row) in self.top.chunks_exact(cols).enumerate() {
            let tiles = &mut self.tile_top[(j / TILE) * self.tile_cols..][..self.tile_cols];
            for (tile, texels) in tiles.iter_mut().zip(row.chunks(TILE)) {
                *tile = texels.iter().copied().fold(*tile, f32::max);
            }
        }
    }

    /// How much of the sun reaches world point `p` on a surface with unit
    /// `normal` (zero for a point without a surface, such as a blade): 0 in
    /// shadow, 1 lit, in between near a shadow's edge.
    pub fn visibility(&self, p: Vec3, normal: Vec3) -> f32 {
        let offset = normal * (NORMAL_OFFSET_TEXELS * self.frame.texel);
        self.visibility_at(self.locate(p + offset))
    }

    /// How much of the sun reaches the point at light coordinates `l`: the
    /// three by three texels around it tested, weighted by a quadratic
    /// B-spline (a tent over two texels, so the edge of a shadow is a soft
    /// ramp rather than texel steps). Points off the map are lit.
    #[inline(always)]
    pub fn visibility_at(&self, l: Vec3) -> f32 {
        let (cols, rows) = (self.frame.cols, self.frame.rows);
        let inside = l.x >= 1.0 && l.y >= 1.0;
        if !(inside && l.x < (cols - 1) as f32 && l.y < (rows - 1) as f32) {
            return 1.0;
        }
        let (i, j) = (l.x as usize, l.y as usize);
        let (wx, wy) = (
            spline_weights(l.x - i as f32),
            spline_weights(l.y - j as f32),
        );
        let h = l.z + BIAS_TEXELS * self.frame.texel;
        let lit = |t: f32| f32::from(u8::from(t <= h));
        let row = |j: usize| {
            let texels = &self.top[j * cols + i - 1..][..3];
            wx[0] * lit(texels[0]) + wx[1] * lit(texels[1]) + wx[2] * lit(texels[2])
        };
        wy[0] * row(j - 1) + wy[1] * row(j) + wy[2] * row(j + 1)
    }

    /// Whether a caster may shade some point whose light coordinates lie in
    /// the box `lo..=hi` (conservative: `false` means every such point is lit).
    pub fn may_shade(&self, lo: Vec3, hi: Vec3) -> bool {
        // The texels the lookups of the box read, and one more for slack.
        let first = (lo.truncate() - Vec2::splat(2.0)).max(Vec2::ZERO);
        let last = hi.truncate() + Vec2::splat(2.0);
        let (cols, rows) = (self.frame.cols as f32, self.frame.rows as f32);
        if !(first.x < cols && first.y < rows && last.x >= 0.0 && last.y >= 0.0) {
            return false;
        }
        let last = last.min(Vec2::new(cols - 1.0, rows - 1.0));
        let h = lo.z + BIAS_TEXELS * self.frame.texel;
        let (i0, i1) = (first.x as usize / TILE, last.x as usize / TILE);
        (first.y as usize / TILE..=last.y as usize / TILE).any(|tj| {
            let row = &self.tile_top[tj * self.tile_cols..];
            row[i0..=i1].iter().any(|&top| top > h)
        })
    }

    /// Whether a caster may shade some point of the world box `min..=max`.
    pub fn may_shade_box(&self, min: Vec3, max: Vec3) -> bool {
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for k in 0..8 {
            let corner = Vec3::select(
                glam::BVec3::new(k & 1 != 0, k & 2 != 0, k & 4 != 0),
                max,
                min,
            );
            let l = self.locate(corner);
            lo = lo.min(l);
            hi = hi.max(l);
        }
        self.may_shade(lo, hi)
    }
}

/// Weights of the texels before, at and after a point `t` (0..1) of the
/// way across a texel: the quadratic B-spline (they sum to one).
#[inline]
fn spline_weights(t: f32) -> [f32; 3] {
    let s = 1.0 - t;
    [0.5 * s * s, 0.5 + t * s, 0.5 * t * t]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::test_ground::floating_square;

    #[test]
    fn a_floating_square_shades_the_ground_below_it_towards_the_sun() {
        let sun = Vec3::new(1.0, 1.0, 0.0).normalize();
        let meshes = floating_square();
        let camera = Camera::perspective(1.0, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 3.0, -4.0), Vec3::ZERO, Vec3::Y);
        let map = ShadowMap::build(&meshes, &[], sun, &camera, Some(0.0)).unwrap();
        // The shadow falls one metre away from the sun.
        let ground = |x: f32, z: f32| map.visibility(Vec3::new(x, 0.0, z), Vec3::Y);
        assert_eq!(ground(-1.0, 0.0), 0.0);
        assert_eq!(ground(0.0, 0.0), 1.0);
        assert_eq!(ground(-1.0, 2.0), 1.0);
        // The square does not shade itself, on either side.
        assert_eq!(map.visibility(Vec3::new(0.0, 1.0, 0.0), Vec3::Y), 1.0);
        assert_eq!(map.visibility(Vec3::new(0.2, 1.0, 0.1), Vec3::ZERO), 1.0);
        // The coarse tiles agree: they may shade the shadow, never the sunlit
        // ground beside it.
        let box_at = |x: f32| (Vec3::new(x - 0.1, 0.0, -0.1), Vec3::new(x + 0.1, 0.0, 0.1));
        let (lo, hi) = box_at(-1.0);
        assert!(map.may_shade_box(lo, hi));
        let (lo, hi) = box_at(1.0);
        assert!(!map.may_shade_box(lo, hi));
        // Nor a box above the square, towards the sun.
        let above = Vec3::new(0.0, 1.0, 0.0) + 0.5 * sun;
        assert!(!map.may_shade_box(above - 0.02, above + 0.02));
        assert!(ShadowMap::build(&[], &[], sun, &camera, None).is_none());
        assert!(ShadowMap::build(&meshes, &[], -sun, &camera, None).is_none());
    }
}
