use std::time::Duration;

use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb as ObAabb;
use obvhs::bvh2::builder::build_bvh2;

use super::binned_bvh::{build_binned, ploc_degenerates};
use super::ray::usable_max_t;
use super::triangle::{PACKET, TriPacket};
use super::wide_bvh::{LeafItems, WideBvh, WideRay};
use super::{Aabb, GeomError, Hit, HitTarget, MeshId, Ray, TriMesh};

/// Build preset: obvhs's very slow preset (PLOC, then reinsertion over
/// every node, before and after collapsing) with leaves of at most 4
/// triangles (one [`TriPacket`]). Against the medium preset it builds a
/// 100k-triangle mesh in about 0.29 s instead of 0.08 s, and an incoherent
/// ray then visits 10.3 nodes and 1.6 packets instead of 11.0 and 1.8 (6 %
/// fewer instructions, 10–15 % less time; measured). Its collapse traversal
/// cost (3) packs the leaves fullest; lower costs gave more, emptier packets
/// and no faster casts, and higher ones the same tree (measured).
const LEAF_BUILD: BvhBuildParams = BvhBuildParams {
    max_prims_per_leaf: PACKET as u32,
    ..BvhBuildParams::very_slow_build()
};

/// A BVH over a static [`TriMesh`]: an obvhs PLOC binary BVH (very slow preset, with reinsertion),
/// or a binned SAH one on layouts where PLOC takes quadratic time (a row of
/// triangles, a fan of overlapping slivers), collapsed into a 4-wide BVH with full-precision boxes, whose leaves are
/// packets of up to four triangles tested together.
///
/// Packets are stored in the order the tree is laid out (depth first), each
/// triangle as a corner and two edges; hits name the triangle's index in the
/// source mesh.
#[derive(Clone)]
pub struct MeshBvh {
    bvh: WideBvh,
    packets: Packets,
    triangles: usize,
    bounds: Aabb,
    id: MeshId,
}

/// The leaf items of a [`MeshBvh`]: triangle packets and, per lane, the
/// source triangle index (`u32::MAX` for an unused lane). A hit's id is
/// `packet * PACKET + lane`.
#[derive(Clone)]
struct Packets {
    packets: Vec<TriPacket>,
    source: Vec<[u32; PACKET]>,
}

impl Packets {
    /// Appends the triangles of the source indices `slots` (`corners` by
    /// source index) as packets, and returns their range `(first, count)`
    /// (one empty packet for no triangles, so that a leaf is never empty).
    fn push_leaf(&mut self, slots: &[u32], corners: &[[Vec3A; 3]]) -> (u32, u32) {
        let first = self.packets.len() as u32;
        let chunks: Vec<&[u32]> = if slots.is_empty() {
            vec![&[]]
        } else {
            slots.chunks(PACKET).collect()
        };
        for chunk in chunks {
            let triangles: Vec<[Vec3A; 3]> = chunk
                .iter()
                .map(|&k| {
                    let [a, b, c] = corners[k as usize];
                    [a, b - a, c - a]
                })
                .collect();
            self.packets.push(TriPacket::new(&triangles));
            let mut source = [u32::MAX; PACKET];
            source[..chunk.len()].copy_from_slice(chunk);
            self.source.push(source);
        }
        (first, self.packets.len() as u32 - first)
    }
}

impl LeafItems for Packets {
    #[inline(always)]
    fn nearest(&self, item: u32, ray: &WideRay, t_max: f32) -> (f32, u32) {
        let (t, lane) = self.packets[item as usize].closest(&ray.origin, &ray.dir, t_max);
        (t, item * PACKET as u32 + lane as u32)
    }

    #[inline(always)]
    fn address(&self, item: u32) -> *const u8 {
        self.packets.as_ptr().wrapping_add(item as usize).cast()
    }
}

impl std::fmt::Debug for MeshBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MeshBvh")
            .field("id", &self.id)
            .field("triangles", &self.triangles)
            .field("bounds", &self.bounds)
            .finish()
    }
}

impl MeshBvh {
    /// Builds the BVH after checking the mesh (non-empty, finite, indices in range).
    /// Hits carry `MeshId(0)` until [`MeshBvh::with_id`] says otherwise.
    pub fn build(mesh: &TriMesh) -> Result<MeshBvh, GeomError> {
        mesh.validate()?;
        let corners: Vec<[Vec3A; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| Vec3A::from(mesh.positions[v as usize])))
            .collect();
        let bounds = Aabb::from_points(&mesh.positions);
        // Boxes padded so that a ray lying exactly in a box face (an axis-aligned
        // ray on a shared edge or on the mesh's outer face) is never rejected.
        let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
        let pad = Vec3A::splat(1e-5 * scale.max(1e-3));
        let boxes: Vec<ObAabb> = corners
            .iter()
            .map(|&[a, b, c]| ObAabb::new(a.min(b).min(c) - pad, a.max(b).max(c) + pad))
            .collect();
        // PLOC stalls on rows of equal triangles and on fans of overlapping
        // slivers (quadratic time); those layouts get a binned SAH build.
        let bvh2 = if ploc_degenerates(&boxes) {
            build_binned(&boxes, PACKET)
        } else {
            build_bvh2(&boxes, LEAF_BUILD, &mut Duration::default())
        };
        let mut packets = Packets {
            packets: Vec::with_capacity(corners.len() / 2),
            source: Vec::with_capacity(corners.len() / 2),
        };
        let bvh = WideBvh::from_bvh2(&bvh2, |first, count| {
            let slots = &bvh2.primitive_indices[first as usize..(first + count) as usize];
            packets.push_leaf(slots, &corners)
        });
        Ok(MeshBvh {
            bvh,
            packets,
            triangles: corners.len(),
            bounds,
            id: MeshId(0),
        })
    }

    /// The same BVH, reporting hits as mesh `id`.
    pub fn with_id(mut self, id: MeshId) -> MeshBvh {
        self.id = id;
        self
    }

    /// The id hits carry.
    pub fn id(&self) -> MeshId {
        self.id
    }

    /// Bounding box of the mesh.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// The closest hit of `ray` within `max_t` (triangles are two-sided).
    pub fn cast(&self, ray: &Ray, max_t: f32) -> Option<Hit> {
        if !usable_max_t(max_t) {
            return None;
        }
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        let found = self.bvh.traverse::<false>(o, d, max_t, &self.packets)?;
        Some(self.hit(ray, found))
    }

    /// True when `ray` meets the mesh within `max_t`.
    pub fn any_hit(&self, ray: &Ray, max_t: f32) -> bool {
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        usable_max_t(max_t)
            && self
                .bvh
                .traverse::<true>(o, d, max_t, &self.packets)
                .is_some()
    }

    /// [`MeshBvh::cast`] for many rays at once: `hits` is cleared and then
    /// holds the answer for `rays[k]` at index `k`: what `cast` gives (the
    /// same distance bit for bit; where two triangles are hit at exactly that
    /// distance, as on a shared edge, it may name the other one).
    ///
    /// Faster than one `cast` after another for rays that go to unrelated
    /// places: several rays are walked down the tree interleaved, each
    /// prefetching what it reads next, so their cache misses overlap.
    ///
    /// ```
    /// use engine::geom::{MeshBvh, Ray, TriMesh};
    /// use engine::glam::Vec3;
    /// let quad = TriMesh::new(
    ///     vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )
    /// .unwrap();
    /// let bvh = MeshBvh::build(&quad).unwrap();
    /// let rays = [Ray::down(0.5, 1.0, 0.5).unwrap(), Ray::down(5.0, 1.0, 0.5).unwrap()];
    /// let mut hits = Vec::new();
    /// bvh.cast_many(&rays, f32::INFINITY, &mut hits);
    /// assert_eq!(hits[0].map(|h| h.distance), Some(1.0));
    /// assert!(hits[1].is_none());
    /// ```
    pub fn cast_many(&self, rays: &[Ray], max_t: f32, hits: &mut Vec<Option<Hit>>) {
        hits.clear();
        hits.resize(rays.len(), None);
        if !usable_max_t(max_t) {
            return;
        }
        self.bvh
            .traverse_many::<false>(rays, max_t, &self.packets, |k, found| {
                hits[k] = found.map(|found| self.hit(&rays[k], found));
            });
    }

    /// [`MeshBvh::any_hit`] for many rays at once, interleaved like
    /// [`MeshBvh::cast_many`]: `hit` is cleared and then holds the answer for
    /// `rays[k]` at index `k`.
    pub fn any_hit_many(&self, rays: &[Ray], max_t: f32, hit: &mut Vec<bool>) {
        hit.clear();
        hit.resize(rays.len(), false);
        if !usable_max_t(max_t) {
            return;
        }
        self.bvh
            .traverse_many::<true>(rays, max_t, &self.packets, |k, found| {
                hit[k] = found.is_some();
            });
    }

    /// The hit record of `ray` at `(t, packet * PACKET + lane)`.
    fn hit(&self, ray: &Ray, (t, id): (f32, u32)) -> Hit {
        let (packet, lane) = (id as usize / PACKET, id as usize % PACKET);
        let [_, e1, e2] = self.packets.packets[packet].triangle(lane);
        Hit {
            point: ray.at(t),
            normal: Vec3::from(e1.cross(e2)).normalize_or(Vec3::Y),
            distance: t,
            target: HitTarget::Mesh {
                mesh: self.id,
                triangle: self.packets.source[packet][lane],
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::ray_triangle;
    use crate::rng::SplitMix64;

    /// A wavy `n` x `n` terrain of unit cells: shared edges on integer
    /// coordinates, where exactly vertical rays test the lost-hit case.
    fn terrain(n: u32) -> TriMesh {
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i as f32, j as f32)))
            .map(|(x, z)| Vec3::new(x, (0.7 * x).sin() * (0.4 * z).cos(), z))
            .collect();
        let at = |i: u32, j: u32| j * (n + 1) + i;
        let triangles = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .flat_map(|(i, j)| {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                [[a, b, c], [a, c, d]]
            })
            .collect();
        TriMesh::new(positions, triangles).unwrap()
    }

    /// The closest hit over every triangle: `(t, triangle)`.
    fn brute(mesh: &TriMesh, ray: &Ray, max_t: f32) -> Option<(f32, u32)> {
        let (o, d) = (Vec3A::from(ray.origin()), Vec3A::from(ray.dir()));
        let mut best: Option<(f32, u32)> = None;
        for (k, t) in mesh.triangles.iter().enumerate() {
            let corners = t.map(|v| Vec3A::from(mesh.positions[v as usize]));
            if let Some(t) = ray_triangle(o, d, corners, max_t)
                && best.is_none_or(|b| t < b.0)
            {
                best = Some((t, k as u32));
            }
        }
        best
    }

    #[test]
    fn one_by_one_and_batched_casts_match_brute_force() {
        let mesh = terrain(24);
        let bvh = MeshBvh::build(&mesh).unwrap();
        let mut rng = SplitMix64::new(11);
        let mut rays: Vec<Ray> = (0..400)
            .map(|_| {
                let o = Vec3::new(
                    rng.range(-4.0, 28.0),
                    rng.range(-2.0, 4.0),
                    rng.range(-4.0, 28.0),
                );
                let to = Vec3::new(rng.range(0.0, 24.0), 0.0, rng.range(0.0, 24.0));
                Ray::new(o, to - o).unwrap()
            })
            .collect();
        // Vertical rays on shared edges and corners, and axis-aligned ones.
        for k in 0..60 {
            let (x, z) = ((k % 24) as f32, (k / 3) as f32 * 0.5);
            rays.push(Ray::down(x, 3.0, z).unwrap());
            rays.push(Ray::new(Vec3::new(-1.0, 0.0, z), Vec3::X).unwrap());
        }
        let max_t = 40.0;
        let mut many = Vec::new();
        bvh.cast_many(&rays, max_t, &mut many);
        let mut any_many = Vec::new();
        bvh.any_hit_many(&rays, max_t, &mut any_many);
        let mut hits = 0;
        for (k, ray) in rays.iter().enumerate() {
            let want = brute(&mesh, ray, max_t);
            let got = bvh.cast(ray, max_t);
            let distance = |h: Option<Hit>| h.map(|h| h.distance.to_bits());
            assert_eq!(
                distance(many[k]),
                distance(got),
                "ray {k}: batched and single differ"
            );
            assert_eq!(got.is_some(), want.is_some(), "ray {k} {ray:?}");
            assert_eq!(bvh.any_hit(ray, max_t), want.is_some(), "ray {k}");
            assert_eq!(any_many[k], want.is_some(), "ray {k}");
            for h in [got, many[k]].into_iter().flatten() {
                let Some((t, tri)) = want else {
                    panic!("ray {k}: a hit where brute force finds none")
                };
                hits += 1;
                assert_eq!(h.distance, t, "ray {k}: the same arithmetic, the same bits");
                let HitTarget::Mesh { triangle, .. } = h.target else {
                    panic!("ray {k}: not a mesh hit")
                };
                let tie = ray_triangle(
                    ray.origin().into(),
                    ray.dir().into(),
                    mesh.triangles[triangle as usize].map(|v| mesh.positions[v as usize].into()),
                    max_t,
                );
                assert!(
                    triangle == tri || tie == Some(t),
                    "ray {k}: triangle {triangle} vs {tri}"
                );
            }
        }
        assert!(hits > rays.len(), "only {hits} hits of two casts each");
        // Refused limits give nothing, in one piece.
        bvh.cast_many(&rays, f32::NAN, &mut many);
        assert!(many.len() == rays.len() && many.iter().all(Option::is_none));
        bvh.any_hit_many(&rays[..5], -1.0, &mut any_many);
        assert_eq!(any_many, [false; 5]);
    }
}
