//! Sun shadows of meshes and grass: what the sun sees of the shadow casters,
//! as the height towards the sun of the topmost caster per texel of a grid
//! across the sun's rays. A point is in shadow when a caster stands above
//! it towards the sun; receivers (terrain, mesh and blade vertices) look
//! their visibility up once per vertex.

use glam::{Vec2, Vec3};

use super::camera::Camera;
use super::grass_blade::GrassBlade;

/// Finest texel, in metres.
const MIN_TEXEL: f32 = 0.02;
/// Most texels per side.
const MAX_SIDE: usize = 1024;
/// How far above its own caster surface a receiver must lie to be lit, in
/// texels (the surface is only known per texel).
const BIAS_TEXELS: f32 = 2.0;
/// Blades whose root lies farther than this (metres, per axis) outside the
/// camera's view cast no shadow: the shadows they cast fall out of view.
const BLADE_REACH: f32 = 1.5;
/// Points along a blade that cast, as fractions of the way from root to
/// tip (the lower part shades only the ground the blade stands on).
const BLADE_SAMPLES: [f32; 3] = [0.5, 0.75, 1.0];

/// The topmost caster towards the sun per texel of a grid across the sun's rays.
#[derive(Debug, Clone)]
pub(crate) struct ShadowMap {
    /// Across the rays, along the map's columns.
    right: Vec3,
    /// Across the rays, along the map's rows.
    up: Vec3,
    /// Towards the sun.
    toward_sun: Vec3,
    /// Light-space coordinates of the corner of texel (0, 0).
    origin: Vec2,
    /// Texel side, in metres.
    texel: f32,
    /// Columns and rows.
    side: usize,
    /// Highest caster coordinate towards the sun per texel (row-major);
    /// `-inf` where nothing casts.
    top: Vec<f32>,
}

impl ShadowMap {
    /// The shadow map of world-space `triangles` (of meshes) and `blades`
    /// under a sun in direction `toward_sun` (unit); `None` when nothing
    /// casts or the sun is down.
    /// Only blades near what `camera` sees cast.
    pub fn build(
        triangles: &[[Vec3; 3]],
        blades: &[GrassBlade],
        toward_sun: Vec3,
        camera: &Camera,
    ) -> Option<ShadowMap> {
        if toward_sun.y <= 0.0 || (triangles.is_empty() && blades.is_empty()) {
            return None;
        }
        let planes = camera.frustum_planes();
        let near_view = |b: &&GrassBlade| {
            let reach = Vec3::splat(BLADE_REACH);
            camera.sees_box(&planes, b.root - reach, b.root + reach)
        };
        let blades: Vec<&GrassBlade> = blades.iter().filter(near_view).collect();
        let right = toward_sun.cross(Vec3::Y).try_normalize().unwrap_or(Vec3::X);
        let up = right.cross(toward_sun);
        let across = |p: Vec3| Vec2::new(p.dot(right), p.dot(up));
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        let points = triangles.iter().flatten();
        for p in points.chain(blades.iter().flat_map(|b| [&b.root, &b.mid, &b.tip])) {
            let q = across(*p);
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if !(lo.x <= hi.x && lo.y <= hi.y) {
            return None;
        }
        let extent = (hi - lo).max_element() + 4.0 * MIN_TEXEL;
        let texel = (extent / MAX_SIDE as f32).max(MIN_TEXEL);
        let side = ((extent / texel).ceil() as usize + 2).min(MAX_SIDE + 2);
        let mut map = ShadowMap {
            right,
            up,
            toward_sun,
            origin: lo - Vec2::splat(texel),
            texel,
            side,
            top: vec![f32::NEG_INFINITY; side * side],
        };
        for t in triangles {
            map.cast_triangle(t);
        }
        for b in &blades {
            map.cast_blade(b);
        }
        Some(map)
    }

    /// Map coordinates (in texels) and height towards the sun of `p`.
    #[inline]
    fn locate(&self, p: Vec3) -> (Vec2, f32) {
        let q = Vec2::new(p.dot(self.right), p.dot(self.up));
        ((q - self.origin) / self.texel, p.dot(self.toward_sun))
    }

    /// Raises texel `(i, j)` to height `h`.
    #[inline]
    fn raise(&mut self, i: usize, j: usize, h: f32) {
        if i < self.side && j < self.side {
            let t = &mut self.top[j * self.side + i];
            *t = t.max(h);
        }
    }

    /// Marks the texels whose centres a world triangle covers.
    fn cast_triangle(&mut self, t: &[Vec3; 3]) {
        let [(a, ha), (b, hb), (c, hc)] = t.map(|p| self.locate(p));
        let area = (b - a).perp_dot(c - a);
        if area.abs() < 1e-12 {
            // Seen edge-on by the sun: its edges still cast.
            for (p, h) in [(a, ha), (b, hb), (c, hc)] {
                self.raise(p.x as usize, p.y as usize, h);
            }
            return;
        }
        let lo = a.min(b).min(c).max(Vec2::ZERO);
        let hi = a.max(b).max(c).min(Vec2::splat(self.side as f32 - 1.0));
        for j in lo.y as usize..=hi.y.max(0.0) as usize {
            for i in lo.x as usize..=hi.x.max(0.0) as usize {
                let p = Vec2::new(i as f32 + 0.5, j as f32 + 0.5);
                let wa = (c - b).perp_dot(p - b) / area;
                let wb = (a - c).perp_dot(p - c) / area;
                let wc = 1.0 - wa - wb;
                // A little slack so that neighbouring triangles leave no gap.
                if wa >= -0.05 && wb >= -0.05 && wc >= -0.05 {
                    self.raise(i, j, wa * ha + wb * hb + wc * hc);
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
            let (q, h) = self.locate(p);
            if q.x >= 0.0 && q.y >= 0.0 {
                self.raise(q.x as usize, q.y as usize, h);
            }
        }
    }

    /// How much of the sun reaches `p` past the casters: 0 in shadow, 1 lit,
    /// in between near a shadow's edge (four texels, bilinearly weighted).
    pub fn visibility(&self, p: Vec3) -> f32 {
        let (q, h) = self.locate(p);
        let q = q - Vec2::splat(0.5);
        let limit = (self.side - 1) as f32;
        if !(q.x >= 0.0 && q.y >= 0.0 && q.x < limit && q.y < limit) {
            return 1.0;
        }
        let (i, j) = (q.x as usize, q.y as usize);
        let (fx, fy) = (q.x - i as f32, q.y - j as f32);
        let bias = BIAS_TEXELS * self.texel;
        let lit = |i: usize, j: usize| f32::from(u8::from(self.top[j * self.side + i] <= h + bias));
        let row = |j: usize| lit(i, j) + (lit(i + 1, j) - lit(i, j)) * fx;
        row(j) + (row(j + 1) - row(j)) * fy
    }
}

#[cfg(test)]
mod tests {
    use glam::Mat4;

    use super::*;
    use crate::geom::TriMesh;
    use crate::render::mesh::MeshInstance;

    #[test]
    fn a_floating_square_shades_the_ground_below_it_towards_the_sun() {
        let square = TriMesh::new(
            vec![
                Vec3::new(-0.5, 1.0, -0.5),
                Vec3::new(0.5, 1.0, -0.5),
                Vec3::new(0.5, 1.0, 0.5),
                Vec3::new(-0.5, 1.0, 0.5),
            ],
            vec![[0, 2, 1], [0, 3, 2]],
        )
        .unwrap();
        let sun = Vec3::new(1.0, 1.0, 0.0).normalize();
        let mesh = MeshInstance::new(&square, Mat4::IDENTITY, Vec3::ONE);
        let meshes: Vec<[Vec3; 3]> = mesh.world_triangles().collect();
        let camera = Camera::perspective(1.0, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 3.0, -4.0), Vec3::ZERO, Vec3::Y);
        let map = ShadowMap::build(&meshes, &[], sun, &camera).unwrap();
        // The shadow falls one metre away from the sun.
        assert_eq!(map.visibility(Vec3::new(-1.0, 0.0, 0.0)), 0.0);
        assert_eq!(map.visibility(Vec3::new(0.0, 0.0, 0.0)), 1.0);
        assert_eq!(map.visibility(Vec3::new(-1.0, 0.0, 2.0)), 1.0);
        // The square does not shade itself.
        assert_eq!(map.visibility(Vec3::new(0.0, 1.0, 0.0)), 1.0);
        assert!(ShadowMap::build(&[], &[], sun, &camera).is_none());
        assert!(ShadowMap::build(&meshes, &[], -sun, &camera).is_none());
    }
}
