use std::fmt;

use super::Skeleton;

/// What a bone does in a humanoid rig, whatever the rig calls it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BoneRole {
    /// The pelvis (hips): the root of the legs and the spine.
    Pelvis,
    /// The lowest spine bone.
    Spine1,
    /// The middle spine bone.
    Spine2,
    /// The upper spine bone (chest).
    Spine3,
    /// The neck.
    Neck,
    /// The head.
    Head,
    /// Left hip joint (thigh bone).
    ThighL,
    /// Left knee (shin bone).
    CalfL,
    /// Left ankle (foot bone).
    FootL,
    /// Left toe joint (ball of the foot).
    ToeL,
    /// Right hip joint (thigh bone).
    ThighR,
    /// Right knee (shin bone).
    CalfR,
    /// Right ankle (foot bone).
    FootR,
    /// Right toe joint (ball of the foot).
    ToeR,
    /// Left clavicle.
    ClavicleL,
    /// Left shoulder (upper arm bone).
    UpperArmL,
    /// Left elbow (forearm bone).
    LowerArmL,
    /// Left wrist (hand bone).
    HandL,
    /// Right clavicle.
    ClavicleR,
    /// Right shoulder (upper arm bone).
    UpperArmR,
    /// Right elbow (forearm bone).
    LowerArmR,
    /// Right wrist (hand bone).
    HandR,
}

impl BoneRole {
    /// Every role, pelvis first.
    pub const ALL: [BoneRole; 22] = [
        BoneRole::Pelvis,
        BoneRole::Spine1,
        BoneRole::Spine2,
        BoneRole::Spine3,
        BoneRole::Neck,
        BoneRole::Head,
        BoneRole::ThighL,
        BoneRole::CalfL,
        BoneRole::FootL,
        BoneRole::ToeL,
        BoneRole::ThighR,
        BoneRole::CalfR,
        BoneRole::FootR,
        BoneRole::ToeR,
        BoneRole::ClavicleL,
        BoneRole::UpperArmL,
        BoneRole::LowerArmL,
        BoneRole::HandL,
        BoneRole::ClavicleR,
        BoneRole::UpperArmR,
        BoneRole::LowerArmR,
        BoneRole::HandR,
    ];

    /// The next role down a limb or up the spine, whose joint this bone points
    /// at (e.g. the calf for the thigh); `None` at the end of a chain.
    pub fn child(self) -> Option<BoneRole> {
        use BoneRole::*;
        Some(match self {
            ThighL => CalfL,
            CalfL => FootL,
            FootL => ToeL,
            ThighR => CalfR,
            CalfR => FootR,
            FootR => ToeR,
            ClavicleL => UpperArmL,
            UpperArmL => LowerArmL,
            LowerArmL => HandL,
            ClavicleR => UpperArmR,
            UpperArmR => LowerArmR,
            LowerArmR => HandR,
            _ => return None,
        })
    }
}

impl fmt::Display for BoneRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

/// The naming conventions the presets know.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RigPreset {
    /// Unreal / "game engine" names (`pelvis`, `thigh_l`, `calf_l`, `foot_l`, `ball_l`),
    /// as the MakeHuman game-engine rig and the default human use.
    GameEngine,
    /// Mixamo names (`mixamorig:Hips`, `mixamorig:LeftUpLeg`, ...); any namespace
    /// before `:` matches, and so does a prefix ending in `_` before a name
    /// without underscores (`mixamorig_LeftUpLeg`, `Character1_LeftUpLeg`).
    Mixamo,
    /// CMU / common BVH names (`Hips`, `LeftUpLeg`, `LeftLeg`, `LeftFoot`, `LeftToeBase`).
    Bvh,
}

impl RigPreset {
    /// Every preset.
    pub const ALL: [RigPreset; 3] = [RigPreset::GameEngine, RigPreset::Mixamo, RigPreset::Bvh];

    /// The candidate names of a role in this convention, most likely first.
    pub fn names(self, role: BoneRole) -> &'static [&'static str] {
        match self {
            RigPreset::GameEngine => game_engine_names(role),
            RigPreset::Mixamo => mixamo_names(role),
            RigPreset::Bvh => bvh_names(role),
        }
    }
}

fn game_engine_names(role: BoneRole) -> &'static [&'static str] {
    use BoneRole::*;
    match role {
        Pelvis => &["pelvis"],
        Spine1 => &["spine_01"],
        Spine2 => &["spine_02"],
        Spine3 => &["spine_03"],
        Neck => &["neck_01"],
        Head => &["head"],
        ThighL => &["thigh_l"],
        CalfL => &["calf_l"],
        FootL => &["foot_l"],
        ToeL => &["ball_l"],
        ThighR => &["thigh_r"],
        CalfR => &["calf_r"],
        FootR => &["foot_r"],
        ToeR => &["ball_r"],
        ClavicleL => &["clavicle_l"],
        UpperArmL => &["upperarm_l"],
        LowerArmL => &["lowerarm_l"],
        HandL => &["hand_l"],
        ClavicleR => &["clavicle_r"],
        UpperArmR => &["upperarm_r"],
        LowerArmR => &["lowerarm_r"],
        HandR => &["hand_r"],
    }
}

fn mixamo_names(role: BoneRole) -> &'static [&'static str] {
    use BoneRole::*;
    match role {
        Pelvis => &["mixamorig:Hips"],
        Spine1 => &["mixamorig:Spine"],
        Spine2 => &["mixamorig:Spine1"],
        Spine3 => &["mixamorig:Spine2"],
        Neck => &["mixamorig:Neck"],
        Head => &["mixamorig:Head"],
        ThighL => &["mixamorig:LeftUpLeg"],
        CalfL => &["mixamorig:LeftLeg"],
        FootL => &["mixamorig:LeftFoot"],
        ToeL => &["mixamorig:LeftToeBase"],
        ThighR => &["mixamorig:RightUpLeg"],
        CalfR => &["mixamorig:RightLeg"],
        FootR => &["mixamorig:RightFoot"],
        ToeR => &["mixamorig:RightToeBase"],
        ClavicleL => &["mixamorig:LeftShoulder"],
        UpperArmL => &["mixamorig:LeftArm"],
        LowerArmL => &["mixamorig:LeftForeArm"],
        HandL => &["mixamorig:LeftHand"],
        ClavicleR => &["mixamorig:RightShoulder"],
        UpperArmR => &["mixamorig:RightArm"],
        LowerArmR => &["mixamorig:RightForeArm"],
        HandR => &["mixamorig:RightHand"],
    }
}

fn bvh_names(role: BoneRole) -> &'static [&'static str] {
    use BoneRole::*;
    match role {
        Pelvis => &["Hips", "hip", "Hip", "pelvis"],
        Spine1 => &["LowerBack", "Spine", "abdomen"],
        Spine2 => &["Spine", "Spine1", "chest"],
        Spine3 => &["Spine1", "Spine2", "chest2"],
        Neck => &["Neck", "neck"],
        Head => &["Head", "head"],
        ThighL => &["LeftUpLeg", "LeftHip", "lThigh"],
        CalfL => &["LeftLeg", "LeftKnee", "lShin"],
        FootL => &["LeftFoot", "LeftAnkle", "lFoot"],
        ToeL => &["LeftToeBase", "LeftToe", "LeftToes"],
        ThighR => &["RightUpLeg", "RightHip", "rThigh"],
        CalfR => &["RightLeg", "RightKnee", "rShin"],
        FootR => &["RightFoot", "RightAnkle", "rFoot"],
        ToeR => &["RightToeBase", "RightToe", "RightToes"],
        ClavicleL => &["LeftShoulder", "LeftCollar", "lCollar"],
        UpperArmL => &["LeftArm", "LeftUpArm", "lShldr"],
        LowerArmL => &["LeftForeArm", "LeftLowArm", "lForeArm"],
        HandL => &["LeftHand", "lHand"],
        ClavicleR => &["RightShoulder", "RightCollar", "rCollar"],
        UpperArmR => &["RightArm", "RightUpArm", "rShldr"],
        LowerArmR => &["RightForeArm", "RightLowArm", "rForeArm"],
        HandR => &["RightHand", "rHand"],
    }
}

/// Which joint of one skeleton plays each role.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BoneMap {
    /// The preset whose names it uses; `None` for a custom map.
    pub preset: Option<RigPreset>,
    joints: Vec<(BoneRole, usize)>,
}

impl BoneMap {
    /// The joints of `skeleton` that `preset`'s names match. Each role takes its
    /// first candidate found that no earlier role took; a name matches exactly,
    /// or ignoring case and any `namespace:` prefix.
    pub fn from_preset(skeleton: &Skeleton, preset: RigPreset) -> BoneMap {
        let mut joints: Vec<(BoneRole, usize)> = Vec::new();
        for role in BoneRole::ALL {
            let found = preset.names(role).iter().find_map(|name| {
                find_joint(skeleton, name).filter(|j| joints.iter().all(|(_, t)| t != j))
            });
            if let Some(joint) = found {
                joints.push((role, joint));
            }
        }
        BoneMap {
            preset: Some(preset),
            joints,
        }
    }

    /// The joints of `skeleton` named in `names` (role, bone name), e.g. from a
    /// scene's `[character.bones]` table; names not in the skeleton are left out.
    pub fn from_names(skeleton: &Skeleton, names: &[(BoneRole, String)]) -> BoneMap {
        let joints = names
            .iter()
            .filter_map(|(role, name)| Some((*role, find_joint(skeleton, name)?)))
            .collect();
        BoneMap {
            preset: None,
            joints,
        }
    }

    /// The preset that maps the most roles of `skeleton`; on a tie, the one
    /// with more exact name matches (so `LeftUpLeg` is BVH, `mixamorig:LeftUpLeg`
    /// Mixamo), then the first.
    pub fn detect(skeleton: &Skeleton) -> BoneMap {
        let score = |map: &BoneMap| (map.len(), map.exact_matches(skeleton));
        RigPreset::ALL
            .iter()
            .map(|&p| BoneMap::from_preset(skeleton, p))
            .fold(None, |best: Option<BoneMap>, map| match best {
                Some(b) if score(&b) >= score(&map) => Some(b),
                _ => Some(map),
            })
            .unwrap_or(BoneMap {
                preset: None,
                joints: Vec::new(),
            })
    }

    /// How many mapped joints carry one of the preset's names exactly.
    fn exact_matches(&self, skeleton: &Skeleton) -> usize {
        let Some(preset) = self.preset else {
            return self.len();
        };
        self.joints
            .iter()
            .filter(|&&(role, joint)| {
                skeleton
                    .joints()
                    .get(joint)
                    .is_some_and(|j| preset.names(role).contains(&j.name.as_str()))
            })
            .count()
    }

    /// The names looked for for `role`: the preset's candidates (none for a custom map).
    pub fn names_for(&self, role: BoneRole) -> Vec<String> {
        self.preset.map_or_else(Vec::new, |p| {
            p.names(role).iter().map(|s| s.to_string()).collect()
        })
    }

    /// The joint playing `role`, if any.
    pub fn joint(&self, role: BoneRole) -> Option<usize> {
        self.joints
            .iter()
            .find(|(r, _)| *r == role)
            .map(|&(_, joint)| joint)
    }

    /// Every (role, joint) pair, in role order.
    pub fn pairs(&self) -> &[(BoneRole, usize)] {
        &self.joints
    }

    /// How many roles are mapped.
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// Whether no role is mapped.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }
}

/// The joint named `name`: exactly, else ignoring case and namespaces (`a:b` ~ `b`),
/// else, for a name without underscores (`LeftUpLeg`), after a prefix ending in
/// the first underscore (`mixamorig_LeftUpLeg`, Maya HumanIK's `Character1_LeftUpLeg`).
fn find_joint(skeleton: &Skeleton, name: &str) -> Option<usize> {
    let wanted = bare(name);
    let joints = skeleton.joints();
    skeleton
        .find(name)
        .or_else(|| (joints.iter()).position(|j| bare(&j.name).eq_ignore_ascii_case(wanted)))
        .or_else(|| {
            if wanted.contains('_') {
                return None;
            }
            joints.iter().position(|j| {
                bare(&j.name)
                    .split_once('_')
                    .is_some_and(|(_, rest)| rest.eq_ignore_ascii_case(wanted))
            })
        })
}

fn bare(name: &str) -> &str {
    name.rsplit(':').next().unwrap_or(name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::{Joint, Transform};
    use glam::Mat4;

    fn skeleton(names: &[&str]) -> Skeleton {
        let joints = (names.iter().enumerate())
            .map(|(k, name)| Joint {
                name: name.to_string(),
                parent: k.checked_sub(1),
                rest: Transform::IDENTITY,
                inverse_bind: Mat4::IDENTITY,
            })
            .collect();
        Skeleton::new(joints).unwrap()
    }

    #[test]
    fn names_match_through_namespaces_and_underscore_prefixes_only_when_unambiguous() {
        let s = skeleton(&[
            "Armature:Character1_Hips",
            "mixamorig_LeftUpLeg",
            "ik_foot_l",
            "LeftLeg",
        ]);
        assert_eq!(find_joint(&s, "Hips"), Some(0));
        assert_eq!(find_joint(&s, "LeftUpLeg"), Some(1));
        // An exact name wins over a prefixed one.
        assert_eq!(find_joint(&s, "LeftLeg"), Some(3));
        // Names with underscores match only whole: `ik_foot_l` is not `foot_l`.
        assert_eq!(find_joint(&s, "foot_l"), None);
    }
}
