//! [`ClipWalk`]: a walk clip played by a rigged character, its upper body
//! phase-locked to the gait while the legs and pelvis stay on the driver.

use std::sync::Arc;

use engine::anim::{BoneMap, Clip, Playback, RetargetError, Skeleton, WalkCycle, retarget};
use glam::{Mat4, Quat};
use thiserror::Error;

use super::{CharacterBody, CharacterRig, Gait, Pose, RigPose};
use crate::foot::FootState;

/// Why a clip cannot drive a character.
#[derive(Debug, Error, PartialEq)]
pub enum ClipWalkError {
    /// The clip could not be moved onto the character's rig.
    #[error("cannot retarget the clip onto the rig: {0}")]
    Retarget(#[source] RetargetError),
}

/// A walk clip retargeted onto one rig, with the cycle read from it.
#[derive(Debug, Clone)]
pub struct ClipWalk {
    clip: Arc<Clip>,
    cycle: WalkCycle,
}

impl ClipWalk {
    /// The walk `clip` (animating `source`, whose bones `source_map` names,
    /// with the `cycle` [`WalkCycle::analyse`] read from it) retargeted onto
    /// `rig`.
    pub fn new(
        source: &Skeleton,
        source_map: &BoneMap,
        clip: &Clip,
        cycle: WalkCycle,
        rig: &CharacterRig,
    ) -> Result<ClipWalk, ClipWalkError> {
        let on_rig = retarget(
            source,
            source_map,
            clip,
            &rig.model().skeleton,
            rig.bone_map(),
        )
        .map_err(ClipWalkError::Retarget)?;
        Ok(ClipWalk {
            clip: Arc::new(on_rig),
            cycle,
        })
    }

    /// The rig posed by the driver ([`RigPose::drive`]), then its upper body
    /// played from the clip at the gait's phase, as much as the gait's foot
    /// roll is applied (so it settles with the feet at a stop).
    pub fn drive(
        &self,
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
        gait: &Gait,
    ) -> RigPose {
        let mut out = RigPose::drive(rig, body, pose, feet);
        self.play_upper_body(rig, &mut out, gait.phase, gait.roll);
        out
    }

    /// Re-poses everything from the first spine bone up (spine, neck, head,
    /// clavicles, arms, hands) as the clip has it at walk phase `phase` (0 =
    /// left heel strike) relative to its pelvis, on the pelvis `out` already
    /// has; `weight` in `[0, 1]` blends from `out`'s pose to the clip's.
    pub fn play_upper_body(&self, rig: &CharacterRig, out: &mut RigPose, phase: f32, weight: f32) {
        let skeleton = &rig.model().skeleton;
        let chains = rig.chains();
        let Some(&spine) = chains.spine.first() else {
            return;
        };
        let time = self.cycle.clip_time(phase, self.clip.duration());
        let mut globals: Vec<Mat4> = Vec::with_capacity(skeleton.len());
        self.clip
            .pose_at(time, Playback::Once, skeleton)
            .globals(skeleton, &mut globals);
        let rest = rig.rest_globals();
        let rest_at = rig.rest_positions();
        let rotation = |m: &Mat4| m.to_scale_rotation_translation().1;
        let turn = |j: usize| rotation(&globals[j]) * rotation(&rest[j]).inverse();
        let on_pelvis = out.rotations[chains.pelvis] * turn(chains.pelvis).inverse();
        let weight = weight.clamp(0.0, 1.0);
        for (j, joint) in skeleton.joints().iter().enumerate() {
            let Some(parent) = joint.parent else { continue };
            if !skeleton.is_ancestor(spine, j) {
                continue;
            }
            let played: Quat = (on_pelvis * turn(j)).normalize();
            out.rotations[j] = out.rotations[j].slerp(played, weight).normalize();
            out.positions[j] = out.positions[parent]
                + out.rotations[parent]
                    * (out.stretch[parent] * (rest_at[j] - rest_at[parent]) * out.scale);
        }
    }
}
