//! [`SkinnedFigure`]: a rigged character's mesh, skinned on the CPU each
//! frame from the pose the driver gives its rig, in full or, for a figure
//! seen small, as a coarse copy (about a fifth of the triangles of the
//! default human) that skins, casts shadows and draws that much faster.

use engine::anim::{SkinnedMesh, SkinnedVertices, skin};
use engine::geom::TriMesh;
use glam::{Affine3A, Mat4};

use crate::character::{CharacterBody, CharacterRig, ClipScratch, ClipWalk, Gait, Pose, RigPose};
use crate::foot::FootState;

/// How much of a figure's mesh is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Detail {
    /// Every triangle of the model.
    Full = 0,
    /// The rig's [`CharacterRig::coarse_mesh`].
    Coarse = 1,
}

/// A skinned model with its scratch buffers and the world-space meshes of
/// the last frame.
pub(super) struct SkinnedFigure {
    rig: CharacterRig,
    rig_pose: RigPose,
    clip_scratch: ClipScratch,
    globals: Vec<Mat4>,
    matrices: Vec<Affine3A>,
    skinned: SkinnedVertices,
    /// The world-space mesh of each detail (indexed by [`Detail`]), as last skinned.
    meshes: [TriMesh; 2],
    /// The detail of the last update.
    detail: Detail,
}

impl SkinnedFigure {
    /// A figure of `rig`, in its rest pose until the first update.
    pub(super) fn new(rig: CharacterRig) -> SkinnedFigure {
        let meshes = [rest_mesh(&rig.model().mesh), rest_mesh(rig.coarse_mesh())];
        SkinnedFigure {
            rig,
            rig_pose: RigPose::default(),
            clip_scratch: ClipScratch::default(),
            globals: Vec::new(),
            matrices: Vec::new(),
            skinned: SkinnedVertices::default(),
            meshes,
            detail: Detail::Full,
        }
    }

    /// Poses the rig after the driver (the upper body from the walk clip it
    /// plays, if any) and skins the mesh of `detail` into world space, in
    /// parallel over vertices (each vertex is computed alone, so the result
    /// does not depend on the thread count).
    pub(super) fn update(
        &mut self,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
        clip: Option<(&ClipWalk, &Gait)>,
        detail: Detail,
    ) {
        self.rig_pose.drive_in_place(&self.rig, body, pose, feet);
        if let Some((clip, gait)) = clip {
            let (rig, out) = (&self.rig, &mut self.rig_pose);
            clip.play_upper_body(rig, out, gait.phase, gait.roll, &mut self.clip_scratch);
        }
        (self.rig_pose).skin_matrices(&self.rig, &mut self.globals, &mut self.matrices);
        self.detail = detail;
        let source = match detail {
            Detail::Full => &self.rig.model().mesh,
            Detail::Coarse => self.rig.coarse_mesh(),
        };
        let mesh = &mut self.meshes[detail as usize];
        // The matrices cover every joint of the skeleton the mesh was checked against.
        if skin(source, &self.matrices, &mut self.skinned).is_ok() {
            std::mem::swap(&mut mesh.positions, &mut self.skinned.positions);
            std::mem::swap(&mut mesh.normals, &mut self.skinned.normals);
        }
    }

    /// The mesh as skinned by the last update, in world space.
    pub(super) fn mesh(&self) -> &TriMesh {
        &self.meshes[self.detail as usize]
    }
}

/// `source` in its bind pose, as a mesh to draw.
fn rest_mesh(source: &SkinnedMesh) -> TriMesh {
    TriMesh {
        positions: source.positions().to_vec(),
        normals: source.normals().to_vec(),
        triangles: source
            .indices()
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        parts: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::COARSE_MESH_CELL;
    use engine::geom::Aabb;

    #[test]
    fn the_coarse_human_fills_the_same_box_with_a_fifth_of_the_triangles() {
        let figure = SkinnedFigure::new(CharacterRig::human().unwrap());
        let [full, coarse] = &figure.meshes;
        assert!(coarse.triangles.len() * 4 < full.triangles.len());
        let (fine, rough) = (
            Aabb::from_points(&full.positions),
            Aabb::from_points(&coarse.positions),
        );
        let cell = (fine.max - fine.min).max_element() * COARSE_MESH_CELL;
        assert!((rough.min - fine.min).abs().max_element() < cell);
        assert!((rough.max - fine.max).abs().max_element() < cell);
        assert_eq!(figure.mesh().triangles.len(), full.triangles.len());
    }
}
