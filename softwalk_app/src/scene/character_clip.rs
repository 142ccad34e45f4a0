//! A character's `clip`: a BVH walk clip whose cadence, stride and duty the
//! character's gait takes, and whose upper body its rig plays.

use std::path::{Path, PathBuf};

use engine::anim::bvh::{BvhClip, load_bvh};
use engine::anim::{BoneMap, WalkCycle};
use softwalk_systems::character::{CharacterRig, ClipGait, ClipWalk};

use super::SceneError;

/// A loaded and analysed walk clip.
#[derive(Debug, Clone)]
pub struct LoadedClip {
    /// The file, resolved against the scene's folder.
    pub path: PathBuf,
    /// The clip's skeleton and motion.
    pub bvh: BvhClip,
    /// Its bones, by the preset that matches them best.
    pub map: BoneMap,
    /// Its walk cycle.
    pub cycle: WalkCycle,
    /// Its gait.
    pub gait: ClipGait,
}

/// Loads the `.bvh` a character's `clip` names (relative to `base_dir`) and
/// reads its walk cycle; `field` is the character's path (`characters[0]`).
pub fn load_clip(field: &str, clip: &str, base_dir: &Path) -> Result<LoadedClip, SceneError> {
    let field = format!("{field}.clip");
    let path = base_dir.join(clip);
    let is_bvh = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("bvh"));
    if !is_bvh {
        return Err(SceneError::invalid(
            field,
            format!("\"{clip}\" is not a .bvh file (walk clips are read from BVH)"),
        ));
    }
    if !path.is_file() {
        return Err(SceneError::MissingFile { field, path });
    }
    let bad = |reason: String| SceneError::BadFile {
        field: field.clone(),
        path: path.clone(),
        reason,
    };
    let bvh = load_bvh(&path).map_err(|e| bad(e.to_string()))?;
    let map = BoneMap::detect(&bvh.skeleton);
    let cycle = WalkCycle::analyse(&bvh.clip, &bvh.skeleton, &map)
        .map_err(|e| bad(format!("not a walk clip: {e}")))?;
    Ok(LoadedClip {
        gait: ClipGait::from_cycle(&cycle),
        cycle,
        path,
        bvh,
        map,
    })
}

impl LoadedClip {
    /// The clip retargeted onto `rig`, to play its upper body; a refusal
    /// names `field` (the `clip` of the character that plays it).
    pub fn on_rig(&self, field: &str, rig: &CharacterRig) -> Result<ClipWalk, SceneError> {
        ClipWalk::new(
            &self.bvh.skeleton,
            &self.map,
            &self.bvh.clip,
            self.cycle,
            rig,
        )
        .map_err(|e| SceneError::BadFile {
            field: field.to_string(),
            path: self.path.clone(),
            reason: e.to_string(),
        })
    }
}
