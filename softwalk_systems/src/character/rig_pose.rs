//! [`RigPose`]: the loaded rig posed by the walking character. The simulated
//! biped stays the driver (gait, balance tilt, foot keys, foot IK, platforms);
//! each of its poses is retargeted onto the rig here.

use engine::anim::{BoneRole, LegChain};
use glam::{Affine3A, Mat3, Mat4, Quat, Vec3};

use super::body::{CharacterBody, outer};
use super::character_rig::{CharacterRig, frame_rotation};
use super::ik::{lift_to_reach, solve_two_bone};
use super::pose::Pose;
use super::skeleton::Joint;
use crate::foot::{FootPhase, FootState};

/// Outward lean of the arms from the driver's, radians: the rig's arms hang
/// clear of its hips, which are wider than the driver's capsules.
const ARM_ABDUCTION: f32 = 0.12;

/// The rig's joints in the world: each joint's position and its rotation
/// from the rest pose, and the uniform scale from rest size to the driver's.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RigPose {
    /// World position of each joint.
    pub positions: Vec<Vec3>,
    /// World rotation of each joint relative to its rest orientation.
    pub rotations: Vec<Quat>,
    /// Rest size to world size.
    pub scale: f32,
    /// Each joint's stretch in rest space, applied before its rotation: the
    /// identity but for the feet (and what hangs from them), stretched from
    /// heel to toe to the driver's foot length so both soles roll about the
    /// same heel and toe.
    pub stretch: Vec<Mat3>,
}

/// One leg of the rig with the driver's knee and the foot's index (left 0).
struct RigLeg<'a> {
    chain: &'a LegChain,
    knee: Joint,
    side: usize,
}

/// Where the rig's legs must go, computed from the driver.
struct LegTargets {
    knee: Vec3,
    ankle: Vec3,
    foot: Quat,
    stretch: Mat3,
}

impl RigPose {
    /// The rig posed after the driver: scaled so its hips stand as high as
    /// the driver's; the pelvis placed between the driver's hips and turned by
    /// the driver's hip axis and trunk (so the spine follows the proxy tilt);
    /// each leg solved by two-bone IK so its sole lies on the driver's sole (the
    /// foot turned with it and stretched to its length) with the knee towards
    /// the driver's; the arms along
    /// the driver's arm segments. Every other joint keeps its rest transform
    /// relative to its parent, so bones keep their twist.
    pub fn drive(
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
    ) -> RigPose {
        let mut out = RigPose::default();
        out.drive_in_place(rig, body, pose, feet);
        out
    }

    /// [`RigPose::drive`] into this pose, reusing its buffers (no allocation
    /// once they have the rig's size).
    pub fn drive_in_place(
        &mut self,
        rig: &CharacterRig,
        body: &CharacterBody,
        pose: &Pose,
        feet: &[FootState; 2],
    ) {
        let rest = rig.rest_positions();
        let n = rest.len();
        self.scale = body.hip_height / rig.hip_height();
        reset(&mut self.positions, n, Vec3::ZERO);
        reset(&mut self.rotations, n, Quat::IDENTITY);
        reset(&mut self.stretch, n, Mat3::IDENTITY);
        let scale = self.scale;
        let chains = rig.chains();
        let pelvis_turn = pelvis_rotation(rig, pose);
        let hip_mid = 0.5 * (rest[chains.left.hip] + rest[chains.right.hip]);
        let pelvis_at =
            pose.joint(Joint::Pelvis) - pelvis_turn * ((hip_mid - rest[chains.pelvis]) * scale);
        let legs = [
            RigLeg {
                chain: &chains.left,
                knee: Joint::KneeLeft,
                side: 0,
            },
            RigLeg {
                chain: &chains.right,
                knee: Joint::KneeRight,
                side: 1,
            },
        ];
        let mut leg_targets: [Option<LegTargets>; 2] = [None, None];
        let mut aims = arm_aims(rig, pose);
        let skeleton = rig.model().skeleton.joints();
        for j in 0..n {
            // The pelvis and the joints above it move with the pelvis.
            if rig.model().skeleton.is_ancestor(j, chains.pelvis) {
                self.rotations[j] = pelvis_turn;
                self.positions[j] =
                    pelvis_at + pelvis_turn * ((rest[j] - rest[chains.pelvis]) * scale);
                continue;
            }
            let parent = skeleton[j].parent;
            let (parent_at, parent_turn, parent_stretch, parent_rest) = match parent {
                Some(p) => (
                    self.positions[p],
                    self.rotations[p],
                    self.stretch[p],
                    rest[p],
                ),
                None => (rest[j] * scale, Quat::IDENTITY, Mat3::IDENTITY, rest[j]),
            };
            self.positions[j] =
                parent_at + parent_turn * (parent_stretch * (rest[j] - parent_rest) * scale);
            self.rotations[j] = parent_turn;
            self.stretch[j] = parent_stretch;
            for leg in &legs {
                let (chain, side) = (leg.chain, leg.side);
                if j == chain.hip {
                    let hip_at = self.positions[j];
                    let targets = leg_targets_for(rig, body, pose, &feet[side], leg, hip_at);
                    aims.set(chain.hip, targets.knee - hip_at);
                    aims.set(chain.knee, targets.ankle - targets.knee);
                    leg_targets[side] = Some(targets);
                } else if j == chain.ankle
                    && let Some(targets) = &leg_targets[side]
                {
                    self.rotations[j] = targets.foot;
                    self.stretch[j] = targets.stretch;
                }
            }
            if let Some(aim) = aims.get(j) {
                let child = child_of(rig, j);
                if let Some(child) = child {
                    let from = parent_turn * (rest[child] - rest[j]);
                    if let (Some(from), Some(to)) = (from.try_normalize(), aim.try_normalize()) {
                        self.rotations[j] =
                            (Quat::from_rotation_arc(from, to) * parent_turn).normalize();
                    }
                }
            }
        }
    }

    /// Each joint's world matrix: its rest global matrix moved by the pose.
    pub fn globals(&self, rig: &CharacterRig, out: &mut Vec<Mat4>) {
        out.clear();
        let rest = rig.rest_positions();
        out.extend(rig.rest_globals().iter().enumerate().map(|(j, g)| {
            Mat4::from_translation(self.positions[j])
                * Mat4::from_quat(self.rotations[j])
                * Mat4::from_mat3(self.stretch[j] * self.scale)
                * Mat4::from_translation(-rest[j])
                * *g
        }));
    }

    /// Each joint's skinning matrix (world matrix times inverse bind matrix).
    pub fn skin_matrices(
        &self,
        rig: &CharacterRig,
        globals: &mut Vec<Mat4>,
        out: &mut Vec<Affine3A>,
    ) {
        self.globals(rig, globals);
        engine::anim::skin_matrices(&rig.model().skeleton, globals, out);
    }
}

/// Clears `buffer` and fills it with `n` copies of `value`, keeping its capacity.
fn reset<T: Copy>(buffer: &mut Vec<T>, n: usize, value: T) {
    buffer.clear();
    buffer.resize(n, value);
}

/// Where the driver points the rig's limb bones: joint and direction, at
/// most two per limb (eight in all); a later entry for a joint overrides an
/// earlier one.
#[derive(Default)]
struct LimbAims {
    entries: [(usize, Vec3); 8],
    len: usize,
}

impl LimbAims {
    /// Aims `joint` along `direction`.
    fn set(&mut self, joint: usize, direction: Vec3) {
        self.entries[self.len] = (joint, direction);
        self.len += 1;
    }

    /// The direction `joint` is aimed along, if it is.
    fn get(&self, joint: usize) -> Option<Vec3> {
        self.entries[..self.len]
            .iter()
            .rev()
            .find(|(j, _)| *j == joint)
            .map(|&(_, direction)| direction)
    }
}

/// The rig's upper and lower arms aimed along the driver's arm segments,
/// leaning out by [`ARM_ABDUCTION`].
fn arm_aims(rig: &CharacterRig, pose: &Pose) -> LimbAims {
    let mut aims = LimbAims::default();
    for (k, arm) in rig.arms().iter().enumerate() {
        let Some(arm) = arm else { continue };
        let (shoulder, elbow, wrist, side) = match k {
            0 => (
                Joint::ShoulderLeft,
                Joint::ElbowLeft,
                Joint::WristLeft,
                -1.0,
            ),
            _ => (
                Joint::ShoulderRight,
                Joint::ElbowRight,
                Joint::WristRight,
                1.0,
            ),
        };
        let out_lean = Quat::from_axis_angle(pose.forward, -side * ARM_ABDUCTION);
        aims.set(
            arm.shoulder,
            out_lean * (pose.joint(elbow) - pose.joint(shoulder)),
        );
        aims.set(
            arm.elbow,
            out_lean * (pose.joint(wrist) - pose.joint(elbow)),
        );
    }
    aims
}

/// The joint a limb bone points at: the mapped joint of its role's child.
fn child_of(rig: &CharacterRig, joint: usize) -> Option<usize> {
    let map = rig.bone_map();
    let role = map.pairs().iter().find(|&&(_, j)| j == joint)?.0;
    map.joint(BoneRole::child(role)?)
}

/// The pelvis's turn from rest: the rest facing frame onto the driver's hip
/// axis (right) and trunk (up).
fn pelvis_rotation(rig: &CharacterRig, pose: &Pose) -> Quat {
    let right = (pose.joint(Joint::HipRight) - pose.joint(Joint::HipLeft))
        .try_normalize()
        .unwrap_or(pose.right);
    let trunk = pose.joint(Joint::Neck) - pose.joint(Joint::Pelvis);
    let up = (trunk - right * trunk.dot(right))
        .try_normalize()
        .unwrap_or(Vec3::Y);
    let forward = up.cross(right);
    frame_rotation(rig.rest_frame(), Mat3::from_cols(right, up, forward))
}

/// One leg's targets: the foot turned with the driver's sole and stretched
/// to its length, its ankle where the rig's sole centre lands on the
/// driver's, then the knee from two-bone IK from the rig's hip towards the
/// driver's knee.
fn leg_targets_for(
    rig: &CharacterRig,
    body: &CharacterBody,
    pose: &Pose,
    foot: &FootState,
    rig_leg: &RigLeg<'_>,
    hip_at: Vec3,
) -> LegTargets {
    let (leg, side) = (rig_leg.chain, rig_leg.side);
    let scale = body.hip_height / rig.hip_height();
    let rest = rig.rest_positions();
    let sole = foot.sole;
    let along = (sole.toe - sole.heel)
        .try_normalize()
        .unwrap_or(pose.forward);
    let right = (pose.right - along * pose.right.dot(along))
        .try_normalize()
        .unwrap_or_else(|| along.any_orthonormal_vector());
    let normal = right.cross(along);
    let turn = frame_rotation(rig.rest_frame(), Mat3::from_cols(right, normal, along));
    let forward = rig.rest_frame().z_axis;
    let length = rig.sole_lengths()[side] * scale;
    let factor = if length > 0.0 {
        sole.heel.distance(sole.toe) / length
    } else {
        1.0
    };
    let stretch = Mat3::IDENTITY + outer(forward, forward) * (factor - 1.0);
    let ankle =
        sole.center() + turn * (stretch * (rest[leg.ankle] - rig.sole_centres()[side]) * scale);
    let thigh = rest[leg.hip].distance(rest[leg.knee]) * scale;
    let shin = rest[leg.knee].distance(rest[leg.ankle]) * scale;
    let pole = pose.joint(rig_leg.knee) + pose.forward * body.thigh;
    // A planted foot out of the rig leg's reach is lifted, not dragged.
    let ankle = match foot.phase {
        FootPhase::Stance if ankle.distance(hip_at) > thigh + shin => {
            lift_to_reach(hip_at, ankle, thigh + shin).unwrap_or(ankle)
        }
        _ => ankle,
    };
    let solved = solve_two_bone(hip_at, ankle, pole, thigh, shin);
    LegTargets {
        knee: solved.mid,
        ankle: solved.end,
        foot: turn,
        stretch,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{
        Character, CharacterDesc, ClipScratch, ClipWalk, WalkPath, step_character,
    };
    use crate::ground::FlatGround;
    use engine::anim::bvh::load_bvh;
    use engine::anim::{BoneMap, WalkCycle};

    /// A walker of `desc` `steps` steps into a straight walk.
    fn walker(desc: CharacterDesc, steps: usize) -> Character {
        let ground = FlatGround(0.0);
        let path = WalkPath::straight(Vec3::ZERO, Vec3::X, 8.0).unwrap();
        let mut c = Character::new(desc, &path, &ground).unwrap();
        for _ in 0..steps {
            step_character(&mut c, &path, &ground, 1.0 / 60.0);
        }
        c
    }

    #[test]
    fn a_reused_pose_is_driven_as_a_fresh_one() {
        let rig = CharacterRig::human().unwrap();
        let (child, adult) = (
            walker(CharacterDesc::child(), 50),
            walker(CharacterDesc::adult(), 80),
        );
        let mut reused = RigPose::default();
        reused.drive_in_place(&rig, &child.body, &child.pose, &child.feet);
        reused.drive_in_place(&rig, &adult.body, &adult.pose, &adult.feet);
        let fresh = RigPose::drive(&rig, &adult.body, &adult.pose, &adult.feet);
        assert_eq!(reused, fresh);
        assert_ne!(
            fresh,
            RigPose::drive(&rig, &child.body, &child.pose, &child.feet)
        );
    }

    #[test]
    fn a_reused_clip_scratch_plays_as_a_fresh_one() {
        let rig = CharacterRig::human().unwrap();
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/clips/walk.bvh");
        let bvh = load_bvh(std::path::Path::new(path)).unwrap();
        let map = BoneMap::detect(&bvh.skeleton);
        let cycle = WalkCycle::analyse(&bvh.clip, &bvh.skeleton, &map).unwrap();
        let clip = ClipWalk::new(&bvh.skeleton, &map, &bvh.clip, cycle, &rig).unwrap();
        let c = walker(CharacterDesc::adult(), 70);
        let mut scratch = ClipScratch::default();
        let mut played = RigPose::drive(&rig, &c.body, &c.pose, &c.feet);
        clip.play_upper_body(&rig, &mut played, 0.3, 1.0, &mut scratch);
        played.drive_in_place(&rig, &c.body, &c.pose, &c.feet);
        clip.play_upper_body(&rig, &mut played, c.gait.phase, c.gait.roll, &mut scratch);
        assert_eq!(played, clip.drive(&rig, &c.body, &c.pose, &c.feet, &c.gait));
    }
}
