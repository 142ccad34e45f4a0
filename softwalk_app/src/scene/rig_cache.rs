//! [`RigCache`]: the models and walk clips a scene's characters are drawn
//! and walk with, each loaded once and shared by the scene's validation and
//! its build, so a crowd of one model loads it once.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use softwalk_systems::character::{CharacterRig, ClipWalk};

use super::character_clip::{LoadedClip, load_clip};
use super::character_model::load_character_rig;
use super::{CharacterSpec, SceneError};

/// What one character is drawn and walks with.
#[derive(Debug, Clone)]
pub struct CharacterAssets {
    /// The rig it is drawn as (`None` for the mannequin).
    pub rig: Option<CharacterRig>,
    /// Its walk clip, loaded and analysed (`None` without a `clip`).
    pub clip: Option<Arc<LoadedClip>>,
    /// The clip retargeted onto the rig, when it has both.
    pub walk: Option<ClipWalk>,
}

/// The rigs, clips and retargeted clips loaded so far, shared by the clones
/// of a scene. Only what loaded is kept, so an error is made afresh for the
/// character that meets it and names that character's field.
#[derive(Clone, Default)]
pub struct RigCache {
    loaded: Arc<Mutex<Loaded>>,
}

/// The models a character's `model`, `bones` and folder name.
#[derive(Clone, PartialEq)]
struct RigKey {
    model: String,
    bones: BTreeMap<String, String>,
    base_dir: PathBuf,
}

/// The loaded entries, each under what it was loaded from.
#[derive(Default)]
struct Loaded {
    rigs: Vec<(RigKey, Option<CharacterRig>)>,
    clips: Vec<(PathBuf, Arc<LoadedClip>)>,
    walks: Vec<(RigKey, PathBuf, ClipWalk)>,
}

impl RigCache {
    /// The rig, clip and retargeted clip of character `spec` (at `field`,
    /// `characters[0]`), files resolved against `base_dir`: loaded the first
    /// time they are asked for, then shared.
    pub fn character(
        &self,
        field: &str,
        spec: &CharacterSpec,
        base_dir: &Path,
    ) -> Result<CharacterAssets, SceneError> {
        let mut loaded = self.loaded.lock().unwrap_or_else(PoisonError::into_inner);
        let key = RigKey {
            model: spec.model.clone(),
            bones: spec.bones.clone(),
            base_dir: base_dir.to_path_buf(),
        };
        let rig = loaded.rig(field, &key)?;
        let Some(clip) = &spec.clip else {
            return Ok(CharacterAssets {
                rig,
                clip: None,
                walk: None,
            });
        };
        let path = base_dir.join(clip);
        let clip = loaded.clip(field, clip, &path, base_dir)?;
        let walk = match &rig {
            Some(rig) => Some(loaded.walk(field, &key, &path, rig, &clip)?),
            None => None,
        };
        Ok(CharacterAssets {
            rig,
            clip: Some(clip),
            walk,
        })
    }
}

impl Loaded {
    /// The rig of `key`, loaded on first use.
    fn rig(&mut self, field: &str, key: &RigKey) -> Result<Option<CharacterRig>, SceneError> {
        if let Some((_, rig)) = self.rigs.iter().find(|(k, _)| k == key) {
            return Ok(rig.clone());
        }
        let rig = load_character_rig(field, &key.model, &key.bones, &key.base_dir)?;
        self.rigs.push((key.clone(), rig.clone()));
        Ok(rig)
    }

    /// The walk clip `clip` (the file `path`), loaded on first use.
    fn clip(
        &mut self,
        field: &str,
        clip: &str,
        path: &Path,
        base_dir: &Path,
    ) -> Result<Arc<LoadedClip>, SceneError> {
        if let Some((_, loaded)) = self.clips.iter().find(|(p, _)| p == path) {
            return Ok(loaded.clone());
        }
        let loaded = Arc::new(load_clip(field, clip, base_dir)?);
        self.clips.push((path.to_path_buf(), loaded.clone()));
        Ok(loaded)
    }

    /// The clip of `path` retargeted onto the rig of `key`, on first use.
    fn walk(
        &mut self,
        field: &str,
        key: &RigKey,
        path: &Path,
        rig: &CharacterRig,
        clip: &LoadedClip,
    ) -> Result<ClipWalk, SceneError> {
        let known = (self.walks.iter()).find(|(k, p, _)| k == key && p == path);
        if let Some((_, _, walk)) = known {
            return Ok(walk.clone());
        }
        let walk = clip.on_rig(&format!("{field}.clip"), rig)?;
        self.walks
            .push((key.clone(), path.to_path_buf(), walk.clone()));
        Ok(walk)
    }
}

impl PartialEq for RigCache {
    /// Always equal: a cache holds nothing of a scene's content.
    fn eq(&self, _: &RigCache) -> bool {
        true
    }
}

impl std::fmt::Debug for RigCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let loaded = self.loaded.lock().unwrap_or_else(PoisonError::into_inner);
        f.debug_struct("RigCache")
            .field("rigs", &loaded.rigs.len())
            .field("clips", &loaded.clips.len())
            .field("walks", &loaded.walks.len())
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn characters_of_one_model_and_clip_share_one_load() {
        let mut scene = Scene::builtin("sand-flat").unwrap();
        scene.base_dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut spec = scene.characters[0].clone();
        spec.clip = Some("assets/clips/walk.bvh".to_string());
        let cache = RigCache::default();
        let a = cache
            .character("characters[0]", &spec, &scene.base_dir)
            .unwrap();
        let b = cache
            .character("characters[1]", &spec, &scene.base_dir)
            .unwrap();
        assert!(Arc::ptr_eq(
            a.clip.as_ref().unwrap(),
            b.clip.as_ref().unwrap()
        ));
        assert!(a.walk.is_some() && b.walk.is_some());
        assert_eq!(
            format!("{cache:?}"),
            "RigCache { rigs: 1, clips: 1, walks: 1 }"
        );
    }

    #[test]
    fn an_error_names_the_character_that_meets_it() {
        let scene = Scene::builtin("sand-flat").unwrap();
        let mut spec = scene.characters[0].clone();
        spec.clip = Some("missing.bvh".to_string());
        let cache = RigCache::default();
        for field in ["characters[0]", "characters[3]"] {
            let e = cache.character(field, &spec, Path::new("")).unwrap_err();
            assert_eq!(e.field(), Some(format!("{field}.clip").as_str()), "{e}");
        }
    }
}
