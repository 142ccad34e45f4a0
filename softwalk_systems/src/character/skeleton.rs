//! Joint and bone names of the capsule skeleton.

/// A joint of the skeleton (an index into [`super::Pose::joints`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Joint {
    /// Root: midpoint between the hips.
    Pelvis,
    /// Left hip.
    HipLeft,
    /// Right hip.
    HipRight,
    /// Left knee.
    KneeLeft,
    /// Right knee.
    KneeRight,
    /// Left ankle.
    AnkleLeft,
    /// Right ankle.
    AnkleRight,
    /// Left toe tip (at sole height plus the foot radius).
    ToeLeft,
    /// Right toe tip.
    ToeRight,
    /// Base of the neck, top of the spine, between the shoulders.
    Neck,
    /// Top of the head.
    HeadTop,
    /// Left shoulder.
    ShoulderLeft,
    /// Right shoulder.
    ShoulderRight,
    /// Left elbow.
    ElbowLeft,
    /// Right elbow.
    ElbowRight,
    /// Left wrist (end of the forearm and hand).
    WristLeft,
    /// Right wrist.
    WristRight,
}

/// Number of joints.
pub const JOINT_COUNT: usize = 17;

/// A rigid bone between two joints; the character mesh has one capsule part per bone.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bone {
    /// From the left hip to the right hip.
    Pelvis,
    /// From the pelvis to the neck.
    Spine,
    /// From the neck to the top of the head.
    Head,
    /// Left shoulder to elbow.
    UpperArmLeft,
    /// Left elbow to wrist.
    ForearmLeft,
    /// Right shoulder to elbow.
    UpperArmRight,
    /// Right elbow to wrist.
    ForearmRight,
    /// Left hip to knee.
    ThighLeft,
    /// Left knee to ankle.
    ShinLeft,
    /// Left ankle to toe.
    FootLeft,
    /// Right hip to knee.
    ThighRight,
    /// Right knee to ankle.
    ShinRight,
    /// Right ankle to toe.
    FootRight,
}

impl Bone {
    /// Every bone, in mesh-part order.
    pub const ALL: [Bone; 13] = [
        Bone::Pelvis,
        Bone::Spine,
        Bone::Head,
        Bone::UpperArmLeft,
        Bone::ForearmLeft,
        Bone::UpperArmRight,
        Bone::ForearmRight,
        Bone::ThighLeft,
        Bone::ShinLeft,
        Bone::FootLeft,
        Bone::ThighRight,
        Bone::ShinRight,
        Bone::FootRight,
    ];

    /// The bone's name (also its mesh part's name).
    pub fn name(self) -> &'static str {
        match self {
            Bone::Pelvis => "pelvis",
            Bone::Spine => "spine",
            Bone::Head => "head",
            Bone::UpperArmLeft => "upper_arm_left",
            Bone::ForearmLeft => "forearm_left",
            Bone::UpperArmRight => "upper_arm_right",
            Bone::ForearmRight => "forearm_right",
            Bone::ThighLeft => "thigh_left",
            Bone::ShinLeft => "shin_left",
            Bone::FootLeft => "foot_left",
            Bone::ThighRight => "thigh_right",
            Bone::ShinRight => "shin_right",
            Bone::FootRight => "foot_right",
        }
    }

    /// The joints the bone runs from and to.
    pub fn joints(self) -> (Joint, Joint) {
        match self {
            Bone::Pelvis => (Joint::HipLeft, Joint::HipRight),
            Bone::Spine => (Joint::Pelvis, Joint::Neck),
            Bone::Head => (Joint::Neck, Joint::HeadTop),
            Bone::UpperArmLeft => (Joint::ShoulderLeft, Joint::ElbowLeft),
            Bone::ForearmLeft => (Joint::ElbowLeft, Joint::WristLeft),
            Bone::UpperArmRight => (Joint::ShoulderRight, Joint::ElbowRight),
            Bone::ForearmRight => (Joint::ElbowRight, Joint::WristRight),
            Bone::ThighLeft => (Joint::HipLeft, Joint::KneeLeft),
            Bone::ShinLeft => (Joint::KneeLeft, Joint::AnkleLeft),
            Bone::FootLeft => (Joint::AnkleLeft, Joint::ToeLeft),
            Bone::ThighRight => (Joint::HipRight, Joint::KneeRight),
            Bone::ShinRight => (Joint::KneeRight, Joint::AnkleRight),
            Bone::FootRight => (Joint::AnkleRight, Joint::ToeRight),
        }
    }
}
