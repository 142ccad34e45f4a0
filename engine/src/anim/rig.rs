use thiserror::Error;

use super::{BoneMap, BoneRole, Skeleton};

/// One leg's joints, from the hip down.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LegChain {
    /// Hip joint (the thigh bone's joint).
    pub hip: usize,
    /// Knee joint (the shin bone's joint).
    pub knee: usize,
    /// Ankle joint (the foot bone's joint).
    pub ankle: usize,
    /// Toe joint (the ball of the foot), if the rig has one.
    pub toe: Option<usize>,
}

/// The joints the paper's layers drive: both legs and the spine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RigChains {
    /// The pelvis (root of legs and spine).
    pub pelvis: usize,
    /// The spine from just above the pelvis up to the head, inclusive.
    pub spine: Vec<usize>,
    /// The left leg.
    pub left: LegChain,
    /// The right leg.
    pub right: LegChain,
}

/// Why the leg chains or the spine could not be found.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum RigError {
    /// Bones the chains need are not in the bone map.
    #[error("bone map {source_name}: missing {}", list_missing(.missing))]
    Missing {
        /// Where the names came from.
        source_name: String,
        /// Each missing role with the names that were looked for.
        missing: Vec<(BoneRole, Vec<String>)>,
    },
    /// The bone map names joints the skeleton does not have (it was made for another).
    #[error("the bone map names joint {joint}, but the skeleton has {joints}")]
    ForeignMap {
        /// The joint index.
        joint: usize,
        /// The skeleton's joint count.
        joints: usize,
    },
    /// Two bones of a chain are not parent and descendant.
    #[error("{lower} ({lower_name}) does not descend from {upper} ({upper_name})")]
    NotAChain {
        /// The upper role.
        upper: BoneRole,
        /// Its joint's name.
        upper_name: String,
        /// The lower role.
        lower: BoneRole,
        /// Its joint's name.
        lower_name: String,
    },
}

fn list_missing(missing: &[(BoneRole, Vec<String>)]) -> String {
    missing
        .iter()
        .map(|(role, names)| format!("{role} (looked for {})", names.join(", ")))
        .collect::<Vec<_>>()
        .join("; ")
}

/// Roles the chains need (toes are optional).
const REQUIRED: [BoneRole; 8] = [
    BoneRole::Pelvis,
    BoneRole::ThighL,
    BoneRole::CalfL,
    BoneRole::FootL,
    BoneRole::ThighR,
    BoneRole::CalfR,
    BoneRole::FootR,
    BoneRole::Head,
];

impl RigChains {
    /// The legs and spine of `skeleton` through `map`: every required role must
    /// be mapped (the error lists all that are not, with the names looked for),
    /// and each leg joint and the head must descend from the one above. Toes
    /// are optional; a mapped toe must descend from its foot.
    pub fn find(skeleton: &Skeleton, map: &BoneMap) -> Result<RigChains, RigError> {
        if let Some(&(_, joint)) = map.pairs().iter().find(|(_, j)| *j >= skeleton.len()) {
            return Err(RigError::ForeignMap {
                joint,
                joints: skeleton.len(),
            });
        }
        let missing: Vec<(BoneRole, Vec<String>)> = REQUIRED
            .iter()
            .filter(|&&r| map.joint(r).is_none())
            .map(|&r| (r, map.names_for(r)))
            .collect();
        if !missing.is_empty() {
            return Err(RigError::Missing {
                source_name: map
                    .preset
                    .map_or_else(|| "custom".to_string(), |p| format!("{p:?}")),
                missing,
            });
        }
        let joint = |r: BoneRole| map.joint(r).unwrap_or(0);
        use BoneRole::*;
        for pair in [
            [Pelvis, ThighL],
            [ThighL, CalfL],
            [CalfL, FootL],
            [FootL, ToeL],
            [Pelvis, ThighR],
            [ThighR, CalfR],
            [CalfR, FootR],
            [FootR, ToeR],
            [Pelvis, Head],
        ] {
            if map.joint(pair[1]).is_some() {
                check_descends(skeleton, map, pair[0], pair[1])?;
            }
        }
        let pelvis = joint(Pelvis);
        let mut spine = Vec::new();
        let mut current = Some(joint(Head));
        while let Some(j) = current.filter(|&j| j != pelvis) {
            spine.push(j);
            current = skeleton.joints().get(j).and_then(|joint| joint.parent);
        }
        spine.reverse();
        let leg = |hip, knee, ankle, toe| LegChain {
            hip: joint(hip),
            knee: joint(knee),
            ankle: joint(ankle),
            toe: map.joint(toe),
        };
        Ok(RigChains {
            pelvis,
            spine,
            left: leg(ThighL, CalfL, FootL, ToeL),
            right: leg(ThighR, CalfR, FootR, ToeR),
        })
    }

    /// A leg's length in the rest pose: hip to knee plus knee to ankle.
    pub fn leg_length(&self, skeleton: &Skeleton, leg: &LegChain) -> f32 {
        let globals = skeleton.rest_globals();
        let at = |j: usize| {
            globals
                .get(j)
                .map_or(glam::Vec3::ZERO, |m| m.w_axis.truncate())
        };
        at(leg.hip).distance(at(leg.knee)) + at(leg.knee).distance(at(leg.ankle))
    }
}

fn check_descends(
    skeleton: &Skeleton,
    map: &BoneMap,
    upper: BoneRole,
    lower: BoneRole,
) -> Result<(), RigError> {
    let (u, l) = (map.joint(upper).unwrap_or(0), map.joint(lower).unwrap_or(0));
    if u != l && skeleton.is_ancestor(u, l) {
        return Ok(());
    }
    let name = |j: usize| {
        skeleton
            .joints()
            .get(j)
            .map_or_else(String::new, |x| x.name.clone())
    };
    Err(RigError::NotAChain {
        upper,
        upper_name: name(u),
        lower,
        lower_name: name(l),
    })
}
