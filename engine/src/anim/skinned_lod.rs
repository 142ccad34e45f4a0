//! A coarse copy of a [`SkinnedMesh`] for figures seen from afar, by vertex
//! clustering: the bind-pose vertices are binned into cubes of one size, and
//! each cube's vertices become the one nearest their mean. A vertex is only
//! merged with vertices that follow the same main joint, so an arm never
//! welds to the torso it swings past, and the coarse mesh skins like the
//! fine one.

use std::collections::{HashMap, HashSet};

use glam::{IVec3, Vec3};

use super::{AnimError, SkinnedMesh};

impl SkinnedMesh {
    /// This mesh with its vertices clustered into cubes of side `cell`
    /// (metres, in the bind pose): each cluster keeps the position, normal,
    /// joints and weights of its member nearest the members' mean, and
    /// triangles whose corners fall into fewer than three clusters (or that
    /// repeat another) are dropped. Refused for a `cell` that is not a
    /// positive finite number.
    pub fn clustered(&self, cell: f32) -> Result<SkinnedMesh, AnimError> {
        if !(cell.is_finite() && cell > 0.0) {
            return Err(AnimError::ClusterSize { cell });
        }
        let (cluster_of, count) = self.clusters(cell);
        let representatives = self.representatives(&cluster_of, count);
        let triangles = remapped_triangles(self.indices(), &cluster_of);
        let pick = |v: usize| representatives[v] as usize;
        let n = representatives.len();
        SkinnedMesh::new(
            (0..n).map(|c| self.positions()[pick(c)]).collect(),
            (0..n).map(|c| self.normals()[pick(c)]).collect(),
            triangles,
            (0..n).map(|c| self.joints()[pick(c)]).collect(),
            (0..n).map(|c| self.weights()[pick(c)]).collect(),
            self.joint_count(),
        )
    }

    /// The cluster of each vertex, and how many clusters there are:
    /// clusters are numbered in the order of their first vertex, so the
    /// result does not depend on hashing.
    fn clusters(&self, cell: f32) -> (Vec<u32>, usize) {
        let mut ids: HashMap<(u16, IVec3), u32> = HashMap::new();
        let cluster_of = self
            .positions()
            .iter()
            .enumerate()
            .map(|(v, p)| {
                let key = (self.main_joint(v), (*p / cell).floor().as_ivec3());
                let next = ids.len() as u32;
                *ids.entry(key).or_insert(next)
            })
            .collect();
        (cluster_of, ids.len())
    }

    /// The joint vertex `v` follows most (the first of equal weights).
    fn main_joint(&self, v: usize) -> u16 {
        let (weights, joints) = (self.weights()[v], self.joints()[v]);
        let heaviest = (1..4).fold(
            0,
            |best, k| if weights[k] > weights[best] { k } else { best },
        );
        joints[heaviest]
    }

    /// Per cluster (of `n`), the member vertex nearest the members' mean
    /// (the first of equally near ones).
    fn representatives(&self, cluster_of: &[u32], n: usize) -> Vec<u32> {
        let mut sums = vec![(Vec3::ZERO, 0u32); n];
        for (p, &c) in self.positions().iter().zip(cluster_of) {
            let sum = &mut sums[c as usize];
            *sum = (sum.0 + *p, sum.1 + 1);
        }
        let means: Vec<Vec3> = sums.iter().map(|(s, k)| *s / *k as f32).collect();
        let mut best = vec![(u32::MAX, f32::INFINITY); n];
        for (v, (p, &c)) in self.positions().iter().zip(cluster_of).enumerate() {
            let d = p.distance_squared(means[c as usize]);
            let slot = &mut best[c as usize];
            if d < slot.1 {
                *slot = (v as u32, d);
            }
        }
        best.into_iter().map(|(v, _)| v).collect()
    }
}

/// The triangles of `indices` over clusters, without those that collapse
/// (two corners in one cluster) or repeat an earlier one.
fn remapped_triangles(indices: &[u32], cluster_of: &[u32]) -> Vec<u32> {
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|v| cluster_of[v as usize]);
        if a == b || b == c || a == c {
            continue;
        }
        let mut key = [a, b, c];
        key.sort_unstable();
        if seen.insert(key) {
            out.extend([a, b, c]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` quads along x, 1 cm apart, bound half to joint 0 and
    /// half to joint 1.
    fn strip(n: usize) -> SkinnedMesh {
        let mut positions = Vec::new();
        for i in 0..=n {
            positions.push(Vec3::new(i as f32 * 0.01, 0.0, 0.0));
            positions.push(Vec3::new(i as f32 * 0.01, 0.01, 0.0));
        }
        let mut indices = Vec::new();
        for i in 0..n as u32 {
            let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
            indices.extend([a, c, b, b, c, d]);
        }
        let count = positions.len();
        let joints = (0..count)
            .map(|v| [u16::from(v >= count / 2), 0, 0, 0])
            .collect();
        SkinnedMesh::new(
            positions,
            vec![Vec3::Z; count],
            indices,
            joints,
            vec![[1.0, 0.0, 0.0, 0.0]; count],
            2,
        )
        .unwrap()
    }

    #[test]
    fn clustering_merges_nearby_vertices_of_one_joint_only() {
        let fine = strip(40);
        let coarse = fine.clustered(0.05).unwrap();
        assert!(coarse.vertex_count() < fine.vertex_count() / 3);
        assert!(coarse.triangle_count() > 0 && coarse.triangle_count() < fine.triangle_count());
        // Every kept vertex is one of the fine mesh's, with its own skinning.
        for (p, j) in coarse.positions().iter().zip(coarse.joints()) {
            let v = fine.positions().iter().position(|q| q == p).unwrap();
            assert_eq!(fine.joints()[v], *j);
        }
        // The two joints' halves stay apart: the cube that holds the
        // boundary gives one vertex per joint.
        let on = |joint: u16| coarse.joints().iter().filter(|j| j[0] == joint).count();
        assert!(on(0) > 0 && on(1) > 0);
    }

    #[test]
    fn a_cell_smaller_than_the_spacing_keeps_the_mesh() {
        let fine = strip(10);
        let same = fine.clustered(0.001).unwrap();
        assert_eq!(same.vertex_count(), fine.vertex_count());
        assert_eq!(same.indices(), fine.indices());
        assert!(fine.clustered(0.0).is_err());
        assert!(fine.clustered(f32::NAN).is_err());
    }
}
