//! A character's `model` (the built-in human, the capsule mannequin or a
//! glTF file) and its optional `[characters.bones]` table, checked and loaded.

use std::collections::BTreeMap;
use std::path::Path;

use engine::anim::{BoneMap, BoneRole, Model, RigPreset};
use softwalk_systems::character::CharacterRig;

use super::SceneError;

/// `model` value of the built-in human (the default).
pub const HUMAN_MODEL: &str = "human";
/// `model` value of the capsule mannequin (for debugging).
pub const MANNEQUIN_MODEL: &str = "mannequin";

/// The default `model`: the built-in human.
pub(crate) fn default_model() -> String {
    HUMAN_MODEL.to_string()
}

/// The key naming `role` in a `[characters.bones]` table: its game-engine
/// bone name (`pelvis`, `spine_01`, `thigh_l`, `calf_l`, `foot_l`, `ball_l`, ...).
pub fn role_key(role: BoneRole) -> &'static str {
    RigPreset::GameEngine.names(role)[0]
}

/// The role a `[characters.bones]` key names.
fn role_of(key: &str) -> Option<BoneRole> {
    BoneRole::ALL.into_iter().find(|&r| role_key(r) == key)
}

/// Loads the rig a character is drawn as: `None` for the mannequin. `field`
/// is the character's path (`characters[0]`); relative files resolve against
/// `base_dir`. The bone map is the preset that matches the model best, with
/// each `bones` entry (role key = bone name) put over it.
pub fn load_character_rig(
    field: &str,
    model: &str,
    bones: &BTreeMap<String, String>,
    base_dir: &Path,
) -> Result<Option<CharacterRig>, SceneError> {
    let model_field = format!("{field}.model");
    if model == MANNEQUIN_MODEL {
        return match bones.keys().next() {
            Some(key) => Err(SceneError::invalid(
                format!("{field}.bones.{key}"),
                "the mannequin has no bones to name: remove the table or set `model` to a file",
            )),
            None => Ok(None),
        };
    }
    if model == HUMAN_MODEL && bones.is_empty() {
        return CharacterRig::human()
            .map(Some)
            .map_err(|e| SceneError::invalid(model_field, e.to_string()));
    }
    let (model, path) = if model == HUMAN_MODEL {
        let model = CharacterRig::parse_human()
            .map_err(|e| SceneError::invalid(&model_field, e.to_string()))?;
        (model, Path::new(HUMAN_MODEL).to_path_buf())
    } else {
        let path = base_dir.join(model);
        if !path.is_file() {
            return Err(SceneError::MissingFile {
                field: model_field,
                path,
            });
        }
        let model = engine::anim::gltf::load_gltf(&path).map_err(|e| SceneError::BadFile {
            field: model_field.clone(),
            path: path.clone(),
            reason: e.to_string(),
        })?;
        (model, path)
    };
    let map = bone_map(field, &model, bones)?;
    CharacterRig::new(&path.display().to_string(), model, map)
        .map(Some)
        .map_err(|e| SceneError::BadFile {
            field: model_field,
            path,
            reason: e.to_string(),
        })
}

/// The best-matching preset's map (as it is, naming its preset, without a
/// table), with the table's entries put over it.
fn bone_map(
    field: &str,
    model: &Model,
    bones: &BTreeMap<String, String>,
) -> Result<BoneMap, SceneError> {
    let skeleton = &model.skeleton;
    let detected = BoneMap::detect(skeleton);
    if bones.is_empty() {
        return Ok(detected);
    }
    let mut names: Vec<(BoneRole, String)> = Vec::new();
    for (key, bone) in bones {
        let entry = format!("{field}.bones.{key}");
        let Some(role) = role_of(key) else {
            let known: Vec<&str> = BoneRole::ALL.into_iter().map(role_key).collect();
            return Err(SceneError::invalid(
                entry,
                format!("unknown role (known: {})", known.join(", ")),
            ));
        };
        if skeleton.find(bone).is_none() {
            return Err(SceneError::invalid(
                entry,
                format!("the model has no bone named \"{bone}\""),
            ));
        }
        names.push((role, bone.clone()));
    }
    for &(role, joint) in detected.pairs() {
        if !names.iter().any(|(r, _)| *r == role) {
            names.push((role, skeleton.joints()[joint].name.clone()));
        }
    }
    Ok(BoneMap::from_names(skeleton, &names))
}
