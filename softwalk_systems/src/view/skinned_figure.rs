//! [`SkinnedFigure`]: a rigged character's mesh, skinned on the CPU each
//! frame from the pose the driver gives its rig.

use engine::anim::{SkinnedVertices, skin};
use engine::geom::TriMesh;
use glam::{Affine3A, Mat4};

use crate::character::{CharacterBody, CharacterRig, ClipScratch, ClipWalk, Gait, Pose, RigPose};
use crate::foot::FootState;

/// A skinned model with its scratch buffers and the world-space mesh of the last frame.
pub(super) struct SkinnedFigure {
    rig: CharacterRig,
    rig_pose: RigPose,
    clip_scratch: ClipScratch,
    globals: Vec<Mat4>,
    matrices: Vec<Affine3A>,
    skinned: SkinnedVertices,
    mesh: TriMesh,
}

impl SkinnedFigure {
    /// A figure of `rig`, in its rest pose until the first update.
    pub(super) fn new(rig: CharacterRig) -> SkinnedFigure {
        let source = &rig.model().mesh;
        let mesh = TriMesh {
            positions: source.positions().to_vec(),
            normals: source.normals().to_vec(),
            triangles: source
                .indices()
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
            parts: Vec::new(),
        };
        SkinnedFigure {
            rig,
            rig_pose: RigPose::default(),
            clip_scratch: ClipScratch::default(),
            globals: Vec::new(),
            matrices: Vec::new(),
            skinned: SkinnedVertices::default(),
            mesh,
        }
    }

    /// Poses the rig after the driver (the upper body from the walk clip it
    /// plays, if any) and skins the mesh into world space, in parallel over
    /// vertices (each vertex is computed alone, so the result does not depend
    /// on the thread count).
    pub(super) fn update(
        &mut self,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
        clip: Option<(&ClipWalk, &Gait)>,
    ) {
        self.rig_pose.drive_in_place(&self.rig, body, pose, feet);
        if let Some((clip, gait)) = clip {
            let (rig, out) = (&self.rig, &mut self.rig_pose);
            clip.play_upper_body(rig, out, gait.phase, gait.roll, &mut self.clip_scratch);
        }
        (self.rig_pose).skin_matrices(&self.rig, &mut self.globals, &mut self.matrices);
        // The matrices cover every joint of the skeleton the mesh was checked against.
        if skin(&self.rig.model().mesh, &self.matrices, &mut self.skinned).is_ok() {
            std::mem::swap(&mut self.mesh.positions, &mut self.skinned.positions);
            std::mem::swap(&mut self.mesh.normals, &mut self.skinned.normals);
        }
    }

    /// The mesh as skinned by the last update, in world space.
    pub(super) fn mesh(&self) -> &TriMesh {
        &self.mesh
    }
}
