//! The renderable capsule man: one capsule per bone, in bone-local space.

use std::f32::consts::{FRAC_PI_2, TAU};

use engine::geom::{MeshPart, TriMesh};
use glam::Vec3;

use super::body::CharacterBody;
use super::skeleton::Bone;

/// Vertices around each capsule ring.
const RING_VERTICES: usize = 12;
/// Rings per hemisphere cap (pole excluded).
const CAP_RINGS: usize = 4;

/// A capsule along local +Y from 0 to `length` with `radius`, outward normals,
/// counter-clockwise triangles seen from outside.
pub fn capsule(radius: f32, length: f32) -> TriMesh {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    // Rows from the bottom pole to the top pole; the two equators make the cylinder.
    for (centre_y, from, to) in [(0.0, -FRAC_PI_2, 0.0), (length, 0.0, FRAC_PI_2)] {
        for i in 0..=CAP_RINGS {
            let phi = from + (to - from) * i as f32 / CAP_RINGS as f32;
            for s in 0..RING_VERTICES {
                let theta = TAU * s as f32 / RING_VERTICES as f32;
                let n = Vec3::new(phi.cos() * theta.cos(), phi.sin(), phi.cos() * theta.sin());
                positions.push(n * radius + Vec3::Y * centre_y);
                normals.push(n);
            }
        }
    }
    let rows = 2 * (CAP_RINGS + 1);
    let mut triangles = Vec::new();
    for r in 0..rows - 1 {
        for s in 0..RING_VERTICES {
            let at = |r: usize, s: usize| (r * RING_VERTICES + s % RING_VERTICES) as u32;
            let (a, b, c, d) = (at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    }
    TriMesh {
        positions,
        normals,
        triangles,
        parts: Vec::new(),
    }
}

/// The character's mesh: one capsule part per bone, named after it, in
/// [`Bone::ALL`] order, vertices in bone-local space (place each part with
/// [`super::Pose::part_transforms`]).
pub fn character_mesh(body: &CharacterBody) -> TriMesh {
    let mut mesh = TriMesh::default();
    for &bone in &Bone::ALL {
        let mut part = capsule(body.bone_radius(bone), body.bone_length(bone));
        part.parts.push(MeshPart {
            name: bone.name().to_string(),
            triangles: 0..part.triangles.len(),
        });
        mesh.append(&part);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{CharacterDesc, Pose};

    #[test]
    fn capsule_faces_point_outwards() {
        let m = capsule(0.1, 0.5);
        m.validate().unwrap();
        let centre = Vec3::new(0.0, 0.25, 0.0);
        for t in &m.triangles {
            let [a, b, c] = t.map(|v| m.positions[v as usize]);
            let n = (b - a).cross(c - a);
            if n.length() > 1e-9 {
                assert!(n.dot((a + b + c) / 3.0 - centre) > 0.0);
            }
        }
    }

    #[test]
    fn mesh_parts_follow_the_bones() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let mesh = character_mesh(&body);
        mesh.validate().unwrap();
        assert_eq!(mesh.parts.len(), Bone::ALL.len());
        assert!(mesh.part("thigh_left").is_some());
        let pose = Pose::rest(&body, Vec3::ZERO);
        let transforms = pose.part_transforms();
        assert_eq!(transforms.len(), mesh.parts.len());
        // The top of the head capsule lands a radius above the head top joint.
        let head = mesh.part("head").unwrap();
        let top = mesh.triangles[head.triangles.clone()]
            .iter()
            .flatten()
            .map(|&v| transforms[2].transform_point3(mesh.positions[v as usize]).y)
            .fold(f32::MIN, f32::max);
        let expected = 1.75 + body.bone_radius(Bone::Head);
        assert!((top - expected).abs() < 1e-3, "{top} vs {expected}");
    }
}
