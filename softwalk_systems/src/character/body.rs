//! The body built from a description: segment lengths (Drillis–Contini/Winter
//! fractions of the height), segment masses (Dempster/Winter), the standing
//! centre of mass and the inertia tensor.

use glam::{Mat3, Vec3};

use super::desc::CharacterDesc;
use super::error::CharacterError;
use super::skeleton::{Bone, JOINT_COUNT, Joint};

/// Mass fractions (Dempster/Winter): trunk, head+neck, upper arm, forearm+hand, thigh, shank, foot.
const MASS_TRUNK: f32 = 0.497;
const MASS_HEAD: f32 = 0.081;
const MASS_UPPER_ARM: f32 = 0.028;
const MASS_FOREARM: f32 = 0.022;
const MASS_THIGH: f32 = 0.100;
const MASS_SHANK: f32 = 0.0465;
const MASS_FOOT: f32 = 0.0145;
/// Segment centre of mass from the proximal joint, as a fraction of its length.
const PROXIMAL_COM: f32 = 0.433;

/// A body's mass properties in its own frame (X right, Y up, Z forward).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMass {
    /// Height of the centre of mass above the soles, metres.
    pub com_height: f32,
    /// Inertia about the centre of mass, kg·m².
    pub inertia: Mat3,
}

/// A character's body: dimensions, masses, centre of mass and inertia.
///
/// Lengths are in metres. The body frame has X to the character's right, Y up
/// and Z forward, with the origin on the ground between the feet.
#[derive(Debug, Clone, PartialEq)]
pub struct CharacterBody {
    /// The description it was built from.
    pub desc: CharacterDesc,
    /// Height of the ankle joint above the sole.
    pub ankle_height: f32,
    /// Hip to knee.
    pub thigh: f32,
    /// Knee to ankle.
    pub shank: f32,
    /// Half the distance between the hip joints.
    pub hip_half_width: f32,
    /// Pelvis (hip centre) to neck.
    pub trunk: f32,
    /// Neck to the top of the head.
    pub head: f32,
    /// Half the distance between the shoulders.
    pub shoulder_half_width: f32,
    /// Shoulder to elbow.
    pub upper_arm: f32,
    /// Elbow to wrist (hand included).
    pub forearm: f32,
    /// Heel to toe.
    pub foot_length: f32,
    /// Width of the sole.
    pub foot_width: f32,
    /// Standing height of the hip joints above the sole.
    pub hip_height: f32,
    /// Standing height of the whole-body centre of mass above the sole.
    pub com_height: f32,
    /// Inertia tensor of the whole body about its centre of mass, in the body frame (kg·m²).
    pub inertia: Mat3,
    /// The standing pose in the body frame, one position per [`Joint`].
    pub rest_joints: [Vec3; JOINT_COUNT],
}

impl CharacterBody {
    /// Builds the body, refusing a description with a bad field.
    pub fn new(desc: CharacterDesc) -> Result<Self, CharacterError> {
        desc.validate()?;
        let h = desc.height;
        let legs = desc.leg_length_factor;
        // Ankle 0.039, shank 0.246, thigh 0.245: hip at 0.530 H. The upper body
        // (trunk 0.288 + neck and head 0.182) is rescaled to keep the height.
        let upper = (1.0 - 0.039 - 0.491 * legs) / 0.470;
        let mut body = CharacterBody {
            desc,
            ankle_height: 0.039 * h,
            thigh: 0.245 * legs * h,
            shank: 0.246 * legs * h,
            hip_half_width: 0.05 * h,
            trunk: 0.288 * upper * h,
            head: 0.182 * upper * h,
            shoulder_half_width: 0.1295 * h,
            upper_arm: 0.188 * h,
            forearm: 0.20 * h,
            foot_length: 0.152 * h,
            foot_width: 0.055 * h,
            hip_height: 0.0,
            com_height: 0.0,
            inertia: Mat3::ZERO,
            rest_joints: [Vec3::ZERO; JOINT_COUNT],
        };
        body.hip_height = body.ankle_height + body.thigh + body.shank;
        body.rest_joints = body.standing_joints();
        let (com, inertia) = body.mass_properties();
        body.com_height = com.y;
        body.inertia = inertia;
        Ok(body)
    }

    /// Thigh plus shank: the longest hip-to-ankle distance.
    pub fn leg_reach(&self) -> f32 {
        self.thigh + self.shank
    }

    /// Mass of one leg (thigh, shank and foot), kg.
    pub fn leg_mass(&self) -> f32 {
        self.bone_mass(Bone::ThighLeft)
            + self.bone_mass(Bone::ShinLeft)
            + self.bone_mass(Bone::FootLeft)
    }

    /// Length of a bone in this body.
    pub fn bone_length(&self, bone: Bone) -> f32 {
        let (a, b) = bone.joints();
        self.rest_joints[a as usize].distance(self.rest_joints[b as usize])
    }

    /// Capsule radius of a bone (fractions of the height).
    pub fn bone_radius(&self, bone: Bone) -> f32 {
        let f = match bone {
            Bone::Pelvis => 0.055,
            Bone::Spine => 0.085,
            Bone::Head => 0.06,
            Bone::UpperArmLeft | Bone::UpperArmRight => 0.028,
            Bone::ForearmLeft | Bone::ForearmRight => 0.024,
            Bone::ThighLeft | Bone::ThighRight => 0.042,
            Bone::ShinLeft | Bone::ShinRight => 0.032,
            Bone::FootLeft | Bone::FootRight => 0.02,
        };
        f * self.desc.height
    }

    /// Mass of a bone's segment in kilograms (the pelvis bone carries none: the trunk holds it).
    pub fn bone_mass(&self, bone: Bone) -> f32 {
        let f = match bone {
            Bone::Pelvis => 0.0,
            Bone::Spine => MASS_TRUNK,
            Bone::Head => MASS_HEAD,
            Bone::UpperArmLeft | Bone::UpperArmRight => MASS_UPPER_ARM,
            Bone::ForearmLeft | Bone::ForearmRight => MASS_FOREARM,
            Bone::ThighLeft | Bone::ThighRight => MASS_THIGH,
            Bone::ShinLeft | Bone::ShinRight => MASS_SHANK,
            Bone::FootLeft | Bone::FootRight => MASS_FOOT,
        };
        f * self.desc.mass
    }

    /// Position of the ankle relative to the sole's centre, in the foot frame
    /// (Y along the sole normal, Z towards the toe).
    pub fn ankle_above_sole(&self) -> Vec3 {
        Vec3::new(0.0, self.ankle_height, -0.25 * self.foot_length)
    }

    fn standing_joints(&self) -> [Vec3; JOINT_COUNT] {
        let mut j = [Vec3::ZERO; JOINT_COUNT];
        let foot_r = self.bone_radius(Bone::FootLeft);
        for (side, sign) in [(0usize, -1.0f32), (1, 1.0)] {
            let x = sign * self.hip_half_width;
            let pick = |l: Joint, r: Joint| if side == 0 { l } else { r } as usize;
            j[pick(Joint::HipLeft, Joint::HipRight)] = Vec3::new(x, self.hip_height, 0.0);
            j[pick(Joint::KneeLeft, Joint::KneeRight)] =
                Vec3::new(x, self.ankle_height + self.shank, 0.0);
            j[pick(Joint::AnkleLeft, Joint::AnkleRight)] = Vec3::new(x, self.ankle_height, 0.0);
            j[pick(Joint::ToeLeft, Joint::ToeRight)] =
                Vec3::new(x, foot_r, 0.75 * self.foot_length);
            let sx = sign * self.shoulder_half_width;
            let shoulder_y = self.hip_height + self.trunk;
            j[pick(Joint::ShoulderLeft, Joint::ShoulderRight)] = Vec3::new(sx, shoulder_y, 0.0);
            j[pick(Joint::ElbowLeft, Joint::ElbowRight)] =
                Vec3::new(sx, shoulder_y - self.upper_arm, 0.0);
            j[pick(Joint::WristLeft, Joint::WristRight)] =
                Vec3::new(sx, shoulder_y - self.upper_arm - self.forearm, 0.0);
        }
        j[Joint::Pelvis as usize] = Vec3::new(0.0, self.hip_height, 0.0);
        j[Joint::Neck as usize] = Vec3::new(0.0, self.hip_height + self.trunk, 0.0);
        j[Joint::HeadTop as usize] = Vec3::new(0.0, self.desc.height, 0.0);
        j
    }

    /// Takes the centre of mass height and inertia of `mass`, for example
    /// those of a skinned mesh (`BodyMass::of_rig`), in place of the
    /// capsules' own.
    pub fn set_mass_properties(&mut self, mass: BodyMass) {
        self.com_height = mass.com_height;
        self.inertia = mass.inertia;
    }

    /// Whole-body centre of mass and inertia about it, from the standing pose:
    /// each segment a solid cylinder (its capsule radius) plus the parallel-axis term.
    fn mass_properties(&self) -> (Vec3, Mat3) {
        let segments: Vec<(f32, Vec3, Vec3, f32)> = Bone::ALL
            .iter()
            .map(|&bone| {
                let (a, b) = bone.joints();
                let (pa, pb) = (self.rest_joints[a as usize], self.rest_joints[b as usize]);
                let frac = match bone {
                    Bone::Spine | Bone::Head => 0.5,
                    _ => PROXIMAL_COM,
                };
                (
                    self.bone_mass(bone),
                    pa + (pb - pa) * frac,
                    pb - pa,
                    self.bone_radius(bone),
                )
            })
            .collect();
        let total: f32 = segments.iter().map(|s| s.0).sum();
        let com = segments.iter().map(|s| s.1 * s.0).sum::<Vec3>() / total;
        let mut inertia = Mat3::ZERO;
        for &(m, c, axis, r) in &segments {
            let len = axis.length();
            let dir = axis / len.max(1e-6);
            let i_axial = 0.5 * m * r * r;
            let i_perp = m * (3.0 * r * r + len * len) / 12.0;
            // I = i_perp (E - d d^T) + i_axial d d^T, then the parallel-axis shift.
            let ddt = outer(dir, dir);
            let local = (Mat3::IDENTITY - ddt) * i_perp + ddt * i_axial;
            let d = c - com;
            inertia += local + (Mat3::IDENTITY * d.length_squared() - outer(d, d)) * m;
        }
        (com, inertia)
    }
}

/// The outer product `a bᵀ`.
pub(crate) fn outer(a: Vec3, b: Vec3) -> Mat3 {
    Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adult_proportions_and_com() {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        assert!((body.hip_height - 0.530 * 1.75).abs() < 1e-4);
        let ratio = body.com_height / 1.75;
        assert!((0.52..0.60).contains(&ratio), "COM at {ratio} H");
        let total: f32 = Bone::ALL.iter().map(|&b| body.bone_mass(b)).sum();
        assert!((total - 70.0).abs() < 1e-3, "masses sum to {total}");
        // The pitch inertia of a standing adult is of order 10 kg·m².
        assert!((5.0..20.0).contains(&body.inertia.x_axis.x));
    }

    #[test]
    fn longer_legs_raise_the_com_and_keep_the_height() {
        let long = CharacterBody::new(CharacterDesc::long_legged()).unwrap();
        let short = CharacterBody::new(CharacterDesc::short_legged()).unwrap();
        assert!(long.com_height > short.com_height + 0.05);
        for b in [&long, &short] {
            assert!((b.rest_joints[Joint::HeadTop as usize].y - 1.75).abs() < 1e-4);
        }
    }
}
