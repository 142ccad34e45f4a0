//! [`ClipWalk`]: a walk clip played by a rigged character, its upper body
//! phase-locked to the gait while the legs and pelvis stay on the driver.

use std::sync::Arc;

use engine::anim::{BoneMap, Clip, Playback, RetargetError, Skeleton, WalkCycle, retarget};
use glam::{Mat4, Quat};
use thiserror::Error;

use super::clip_scratch::ClipScratch;
use super::{CharacterBody, CharacterRig, Gait, Pose, RigPose};
use crate::foot::FootState;

/// Why a clip cannot drive a character.
#[derive(Debug, Error, PartialEq)]
pub enum ClipWalkError {
    /// The clip could not be moved onto the character's rig.
    #[error("cannot retarget the clip onto the rig: {0}")]
    Retarget(#[source] RetargetError),
}

/// A walk clip retargeted onto one rig, with the cycle read from it and
/// what of the rig it plays: the upper body's joints and their rest turns.
#[derive(Debug, Clone)]
pub struct ClipWalk {
    clip: Arc<Clip>,
    cycle: WalkCycle,
    /// The inverse of each joint's rest rotation (world).
    rest_turns: Vec<Quat>,
    /// The joints from the first spine bone up, each with its parent, in
    /// skeleton order (parents first).
    upper_body: Vec<(usize, usize)>,
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
        let skeleton = &rig.model().skeleton;
        let rest_turns = (rig.rest_globals().iter())
            .map(|m| rotation(m).inverse())
            .collect();
        let upper_body = match rig.chains().spine.first() {
            Some(&spine) => (skeleton.joints().iter().enumerate())
                .filter(|&(j, _)| skeleton.is_ancestor(spine, j))
                .filter_map(|(j, joint)| Some((j, joint.parent?)))
                .collect(),
            None => Vec::new(),
        };
        Ok(ClipWalk {
            clip: Arc::new(on_rig),
            cycle,
            rest_turns,
            upper_body,
        })
    }

    /// The rig posed by the driver ([`RigPose::drive`]), then its upper body
    /// played from the clip at the gait's phase, as much as the gait's foot
    /// roll is applied (so it settles with the feet at a stop). It allocates
    /// a pose and a scratch; per frame, keep both and call
    /// [`RigPose::drive_in_place`] and [`ClipWalk::play_upper_body`], as the
    /// view does.
    pub fn drive(
        &self,
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
        gait: &Gait,
    ) -> RigPose {
        let mut out = RigPose::drive(rig, body, pose, feet);
        let mut scratch = ClipScratch::default();
        self.play_upper_body(rig, &mut out, gait.phase, gait.roll, &mut scratch);
        out
    }

    /// Re-poses everything from the first spine bone up (spine, neck, head,
    /// clavicles, arms, hands) as the clip has it at walk phase `phase` (0 =
    /// left heel strike) relative to its pelvis, on the pelvis `out` already
    /// has; `weight` in `[0, 1]` blends from `out`'s pose to the clip's.
    /// `rig` is the rig the clip was made for (another skeleton is left as
    /// `out` has it); `scratch` holds the clip's pose between calls.
    pub fn play_upper_body(
        &self,
        rig: &CharacterRig,
        out: &mut RigPose,
        phase: f32,
        weight: f32,
        scratch: &mut ClipScratch,
    ) {
        let skeleton = &rig.model().skeleton;
        let n = skeleton.len();
        if self.upper_body.is_empty() || self.rest_turns.len() != n || out.rotations.len() != n {
            return;
        }
        let chains = rig.chains();
        let time = self.cycle.clip_time(phase, self.clip.duration());
        // The rest pose under the clip's channels, as `Clip::pose_at` has it.
        let locals = &mut scratch.pose.locals;
        locals.clear();
        locals.extend(skeleton.joints().iter().map(|joint| joint.rest));
        self.clip
            .sample(time, Playback::Once, skeleton, &mut scratch.pose);
        scratch.pose.globals(skeleton, &mut scratch.globals);
        let globals = &scratch.globals;
        let rest_at = rig.rest_positions();
        let turn = |j: usize| rotation(&globals[j]) * self.rest_turns[j];
        let on_pelvis = out.rotations[chains.pelvis] * turn(chains.pelvis).inverse();
        let weight = weight.clamp(0.0, 1.0);
        for &(j, parent) in &self.upper_body {
            let played: Quat = (on_pelvis * turn(j)).normalize();
            out.rotations[j] = out.rotations[j].slerp(played, weight).normalize();
            out.positions[j] = out.positions[parent]
                + out.rotations[parent]
                    * (out.stretch[parent] * (rest_at[j] - rest_at[parent]) * out.scale);
        }
    }
}

/// The rotation part of a joint's global matrix.
fn rotation(m: &Mat4) -> Quat {
    m.to_scale_rotation_translation().1
}
