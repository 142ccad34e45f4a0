//! Per-vertex colours of a mesh instance (baked, or lit by the sun and the
//! sky, then fogged), four vertices at a time.
//!
//! The lanes do, per vertex, the same IEEE operations in the same order as
//! [`MeshShader::color`] (glam's `Vec3` and `Mat3` operations, scalar per
//! component, and [`Lighting::radiance`] and [`encode_display`]); the fog
//! (an `exp` per vertex) is applied per lane by [`Lighting::apply_fog`]
//! itself. So both give the same bits.

use glam::{Mat3, Mat4, Vec3, Vec4};

use super::project::{LANES, TransformedPoints, VertexShader, vec3_lanes};
use super::shading::{Lighting, encode_display};

/// The colours of a run of mesh vertices (vertex `k` of the run).
pub(crate) struct MeshShader<'a> {
    /// The run's model-space positions and their model transform (whose
    /// world positions the fog measures).
    placed: TransformedPoints<'a>,
    /// Model-space normals (vertices past the end face up).
    normals: &'a [Vec3],
    /// Baked display colours (vertices past the end are lit).
    baked: Option<&'a [Vec3]>,
    /// The matrix that takes normals to the world; `None` for an identity
    /// model, which is skipped: that changes at most the sign of a zero
    /// coordinate, which neither the normalisation nor the lighting tells
    /// apart.
    normal_matrix: Option<Mat3>,
    /// Linear RGB albedo of lit vertices.
    albedo: Vec3,
    /// Light and fog.
    lighting: Lighting,
    /// The camera position, for the fog distance.
    eye: Vec3,
}

impl<'a> MeshShader<'a> {
    /// The shader of the vertices of `placed` (whose model transform also
    /// turns the normals), with their `normals` and `baked` colours (either
    /// may be shorter than the run), lit with `albedo` under `lighting` and
    /// fogged as seen from `eye`.
    pub fn new(
        placed: TransformedPoints<'a>,
        normals: &'a [Vec3],
        baked: Option<&'a [Vec3]>,
        albedo: Vec3,
        lighting: Lighting,
        eye: Vec3,
    ) -> MeshShader<'a> {
        let model = placed.model();
        MeshShader {
            placed,
            normals,
            baked,
            normal_matrix: (model != Mat4::IDENTITY)
                .then(|| Mat3::from_mat4(model).inverse().transpose()),
            albedo,
            lighting,
            eye,
        }
    }

    /// The display colour of a sun-lit vertex with model-space normal `n`,
    /// before fog.
    fn lit(&self, n: Vec3) -> Vec3 {
        let n = match &self.normal_matrix {
            Some(m) => *m * n,
            None => n,
        };
        let n = n.normalize_or(Vec3::Y);
        let sky = 0.65 + 0.35 * n.y;
        encode_display(self.lighting.radiance(self.albedo, n, sky, 1.0))
    }

    /// [`MeshShader::lit`] of four normals given as lanes.
    #[inline(always)]
    fn lit_lanes(&self, [x, y, z]: [Vec4; 3]) -> [Vec4; 3] {
        let (x, y, z) = match &self.normal_matrix {
            None => (x, y, z),
            Some(normal_matrix) => {
                // Mat3 * Vec3: (x_axis x + y_axis y) + z_axis z.
                let row = |r: usize| {
                    let m = normal_matrix.row(r);
                    x * m.x + y * m.y + z * m.z
                };
                (row(0), row(1), row(2))
            }
        };
        // normalize_or(Y): times 1 / length when that is finite and positive.
        let rcp = Vec4::ONE / (x * x + y * y + z * z).sqrt();
        let ok = rcp.abs().cmplt(Vec4::INFINITY) & rcp.cmpgt(Vec4::ZERO);
        let x = Vec4::select(ok, x * rcp, Vec4::ZERO);
        let y = Vec4::select(ok, y * rcp, Vec4::ONE);
        let z = Vec4::select(ok, z * rcp, Vec4::ZERO);
        let sky = Vec4::splat(0.65) + y * 0.35;
        // Lighting::radiance with full sun visibility.
        let sun = &self.lighting.sun;
        let d = sun.direction;
        let lambert = (x * d.x + y * d.y + z * d.z).max(Vec4::ZERO) * 1.0;
        let channel = |albedo: f32, ambient: f32, color: f32| {
            let linear = (sky * ambient + lambert * color) * albedo;
            // encode_display: clamp to [0, 1] (max then min), square root.
            linear.max(Vec4::ZERO).min(Vec4::ONE).sqrt()
        };
        let (a, amb, c) = (self.albedo, sun.ambient, sun.color);
        [
            channel(a.x, amb.x, c.x),
            channel(a.y, amb.y, c.y),
            channel(a.z, amb.z, c.z),
        ]
    }

    /// The fog distances of vertices at the world positions `[x, y, z]`
    /// (lanes): the length of the position minus the eye.
    #[inline(always)]
    fn distances(&self, [x, y, z]: &[Vec4; 3]) -> Vec4 {
        let (dx, dy, dz) = (*x - self.eye.x, *y - self.eye.y, *z - self.eye.z);
        (dx * dx + dy * dy + dz * dz).sqrt()
    }

    /// [`Lighting::apply_fog`] of the display colours `[r, g, b]` (one vertex
    /// per lane) of vertices `4 * group ..`, with the same operations per
    /// lane: the fog amount `1 - exp(-density * max(distance - start, 0))`,
    /// then glam's `lerp` towards the horizon colour, kept only past the fog
    /// start (the caller skips a batch without fog).
    #[inline(always)]
    fn fogged(&self, [r, g, b]: [Vec4; 3], world: &[Vec4; 3]) -> [Vec4; 3] {
        let fog = &self.lighting;
        let distance = self.distances(world);
        let exponent = Vec4::splat(-fog.fog_density) * (distance - fog.fog_start).max(Vec4::ZERO);
        let e = exponent.to_array();
        let amount = Vec4::ONE - Vec4::new(e[0].exp(), e[1].exp(), e[2].exp(), e[3].exp());
        let keep = Vec4::ONE - amount;
        let horizon = fog.sky_horizon;
        let lerp = |c: Vec4, h: f32| c * keep + Vec4::splat(h) * amount;
        let fogged = [lerp(r, horizon.x), lerp(g, horizon.y), lerp(b, horizon.z)];
        let clear = distance.cmple(Vec4::splat(fog.fog_start));
        if !clear.any() {
            // Every vertex past the fog start (the common case).
            return fogged;
        }
        let [fr, fg, fb] = fogged;
        [
            Vec4::select(clear, r, fr),
            Vec4::select(clear, g, fg),
            Vec4::select(clear, b, fb),
        ]
    }
}

impl VertexShader for MeshShader<'_> {
    fn color(&self, k: usize) -> Vec3 {
        let display = match self.baked.and_then(|c| c.get(k)) {
            Some(&baked) => baked,
            None => {
                let n = self.normals.get(k).copied().unwrap_or(Vec3::Y);
                self.lit(n)
            }
        };
        // Without fog the distance is not needed.
        if self.lighting.fog_density == 0.0 {
            return display;
        }
        self.lighting
            .apply_fog(display, (self.placed.world(k) - self.eye).length())
    }

    #[inline]
    fn colors(&self, group: usize) -> [Vec3; LANES] {
        self.colors_at(group, &self.placed.world_lanes(group))
    }

    #[inline(always)]
    fn colors_at(&self, group: usize, world: &[Vec4; 3]) -> [Vec3; LANES] {
        let range = LANES * group..LANES * group + LANES;
        let baked = self.baked.map_or(0, <[Vec3]>::len);
        let fog = self.lighting.fog_density != 0.0;
        let lanes = if baked >= range.end {
            let c = &self.baked.unwrap_or_default()[range];
            if !fog {
                return [c[0], c[1], c[2], c[3]];
            }
            vec3_lanes(c)
        } else if baked <= range.start && self.normals.len() >= range.end {
            self.lit_lanes(vec3_lanes(&self.normals[range]))
        } else {
            return std::array::from_fn(|k| self.color(LANES * group + k));
        };
        // Without fog the distance is not needed.
        let [r, g, b] = if fog {
            self.fogged(lanes, world)
        } else {
            lanes
        };
        let (r, g, b) = (r.to_array(), g.to_array(), b.to_array());
        std::array::from_fn(|k| Vec3::new(r[k], g[k], b[k]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn lanes_give_the_scalar_colours() {
        let mut rng = SplitMix64::new(0x0801_f2e2_858e_fc16);
        let count = 4 * 300;
        let mut v = || rng.range(-3.0, 3.0);
        let points: Vec<Vec3> = (0..count).map(|_| Vec3::new(v(), v(), v())).collect();
        let mut normals: Vec<Vec3> = (0..count)
            .map(|_| Vec3::new(v(), v().abs(), v()).normalize_or(Vec3::Y))
            .collect();
        // Degenerate normals take the fallback.
        normals[5] = Vec3::ZERO;
        normals[6] = Vec3::splat(f32::NAN);
        normals[7] = Vec3::new(f32::INFINITY, 0.0, 0.0);
        let baked: Vec<Vec3> = (0..count / 2).map(|_| Vec3::new(v(), v(), v())).collect();
        let rotated = Mat4::from_rotation_y(0.6) * Mat4::from_translation(Vec3::X);
        for model in [Mat4::IDENTITY, rotated] {
            // Fog starting before every vertex, and among them (groups with
            // vertices on both sides of the start).
            for (fog_density, fog_start) in [(0.0, 1.0), (0.2, 1.0), (0.2, 6.0)] {
                for baked in [None, Some(&baked[..]), Some(&baked[..10])] {
                    let shader = MeshShader::new(
                        TransformedPoints::new(&points, model, Mat4::IDENTITY),
                        &normals[..count - 2],
                        baked,
                        Vec3::new(0.6, 0.5, 0.3),
                        Lighting {
                            fog_density,
                            fog_start,
                            ..Lighting::default()
                        },
                        Vec3::new(0.5, 2.0, -4.0),
                    );
                    let past_start = |k: usize| {
                        (shader.placed.world(k) - shader.eye).length() > shader.lighting.fog_start
                    };
                    let mixed = (0..count / LANES)
                        .filter(|g| (0..LANES).any(|k| !past_start(LANES * g + k)))
                        .count();
                    assert_eq!(mixed > 20, fog_start > 1.0, "{mixed} groups partly clear");
                    for group in 0..count / LANES {
                        let lanes = shader.colors(group);
                        for (k, lane) in lanes.iter().enumerate() {
                            let scalar = shader.color(LANES * group + k);
                            assert_eq!(
                                lane.to_array().map(f32::to_bits),
                                scalar.to_array().map(f32::to_bits)
                            );
                        }
                    }
                }
            }
        }
    }
}
