//! The final pose: world positions of every joint, and one world transform per
//! mesh part.

use glam::{Mat4, Vec3};

use super::body::CharacterBody;
use super::skeleton::{Bone, JOINT_COUNT, Joint};

/// World positions of the skeleton's joints, and the character's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    /// One world position per [`Joint`] (index with `joint as usize`).
    pub joints: [Vec3; JOINT_COUNT],
    /// The character's horizontal forward direction.
    pub forward: Vec3,
    /// The character's right (forward × up).
    pub right: Vec3,
}

impl Pose {
    /// The standing pose of a body facing +Z with its feet around `at`.
    pub fn rest(body: &CharacterBody, at: Vec3) -> Self {
        Pose {
            // The body frame has X to the right; facing +Z with Y up, right is -X.
            joints: body.rest_joints.map(|j| at + Vec3::new(-j.x, j.y, j.z)),
            forward: Vec3::Z,
            right: Vec3::NEG_X,
        }
    }

    /// Position of one joint.
    pub fn joint(&self, joint: Joint) -> Vec3 {
        self.joints[joint as usize]
    }

    /// World transform of a bone's mesh part: its local +Y runs from the
    /// bone's first joint to its second, local X leans towards the character's
    /// right (forward for the pelvis bone, which runs along the right).
    pub fn bone_transform(&self, bone: Bone) -> Mat4 {
        let (a, b) = bone.joints();
        let (pa, pb) = (self.joint(a), self.joint(b));
        let y = (pb - pa).try_normalize().unwrap_or(Vec3::Y);
        let reference = if bone == Bone::Pelvis {
            self.forward
        } else {
            self.right
        };
        let x = (reference - y * reference.dot(y))
            .try_normalize()
            .unwrap_or_else(|| y.any_orthonormal_vector());
        let z = x.cross(y);
        Mat4::from_cols(x.extend(0.0), y.extend(0.0), z.extend(0.0), pa.extend(1.0))
    }

    /// One world transform per mesh part, in [`Bone::ALL`] order (the order of
    /// [`super::character_mesh`]'s parts).
    pub fn part_transforms(&self) -> Vec<Mat4> {
        let mut out = Vec::with_capacity(Bone::ALL.len());
        self.write_part_transforms(&mut out);
        out
    }

    /// [`Pose::part_transforms`] into `out` (cleared first, its capacity kept).
    pub fn write_part_transforms(&self, out: &mut Vec<Mat4>) {
        out.clear();
        out.extend(Bone::ALL.iter().map(|&b| self.bone_transform(b)));
    }

    /// Whole-body centre of mass of this pose (segment masses at their centres).
    pub fn center_of_mass(&self, body: &CharacterBody) -> Vec3 {
        let mut sum = Vec3::ZERO;
        let mut mass = 0.0;
        for &bone in &Bone::ALL {
            let (a, b) = bone.joints();
            let m = body.bone_mass(bone);
            sum += (self.joint(a) + self.joint(b)) * (0.5 * m);
            mass += m;
        }
        sum / mass
    }

    /// Knee flexion of each leg (left first), radians: 0 when straight.
    pub fn knee_flexion(&self) -> [f32; 2] {
        [
            (Joint::HipLeft, Joint::KneeLeft, Joint::AnkleLeft),
            (Joint::HipRight, Joint::KneeRight, Joint::AnkleRight),
        ]
        .map(|(h, k, a)| {
            let thigh = self.joint(k) - self.joint(h);
            let shin = self.joint(a) - self.joint(k);
            thigh.angle_between(shin)
        })
    }
}
