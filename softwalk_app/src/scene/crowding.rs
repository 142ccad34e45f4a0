//! Limits and warnings for scenes with many walkers: a cap on the number of
//! characters (checked before anything is built) and spawn points that overlap.

use super::{CharacterSpec, SceneError};

/// Most characters a scene may hold: each costs a few kilobytes of state
/// plus its share of every per-step buffer, and beyond this the build would
/// allocate far more than a run can use.
pub const MAX_CHARACTERS: usize = 20_000;

/// Spawn points closer than this (metres) overlap: the walkers start inside
/// each other (they are not pushed apart; a warning, not an error).
pub const SPAWN_CLEARANCE_M: f32 = 0.3;

/// Refuses more than [`MAX_CHARACTERS`] characters, naming the field.
pub(crate) fn check_count(characters: &[CharacterSpec]) -> Result<(), SceneError> {
    if characters.len() > MAX_CHARACTERS {
        return Err(SceneError::invalid(
            "characters",
            format!(
                "{} characters exceed the limit {MAX_CHARACTERS}",
                characters.len()
            ),
        ));
    }
    Ok(())
}

/// One warning per pair of characters whose spawn points are closer than
/// [`SPAWN_CLEARANCE_M`], in scene order (a sweep along X, so thousands of
/// walkers are checked quickly).
pub(crate) fn overlapping_spawns(characters: &[CharacterSpec]) -> Vec<String> {
    let mut starts: Vec<(usize, [f32; 2])> = characters
        .iter()
        .enumerate()
        .filter_map(|(k, c)| c.path.polyline().first().map(|&p| (k, p)))
        .filter(|(_, p)| p.iter().all(|v| v.is_finite()))
        .collect();
    starts.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.0.cmp(&b.0)));
    let mut pairs = Vec::new();
    for (n, &(a, pa)) in starts.iter().enumerate() {
        for &(b, pb) in &starts[n + 1..] {
            if pb[0] - pa[0] >= SPAWN_CLEARANCE_M {
                break;
            }
            let d = ((pb[0] - pa[0]).powi(2) + (pb[1] - pa[1]).powi(2)).sqrt();
            if d < SPAWN_CLEARANCE_M {
                pairs.push((a.min(b), a.max(b), d));
            }
        }
    }
    pairs.sort_by_key(|p| (p.0, p.1));
    pairs
        .into_iter()
        .map(|(a, b, d)| {
            format!(
                "characters[{a}] ({}) and characters[{b}] ({}) start {d:.2} m apart (less than {SPAWN_CLEARANCE_M} m): they overlap",
                characters[a].name, characters[b].name
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::scene::{CrowdSpec, Scene, SceneError};

    use super::*;

    #[test]
    fn too_many_walkers_are_refused_naming_the_field() {
        let spec = CrowdSpec {
            walkers: MAX_CHARACTERS + 1,
            resolution: 65,
            grass_fraction: 0.0,
            ..CrowdSpec::default()
        };
        let err = Scene::from_toml_str(&spec.toml("huge"), Path::new("")).unwrap_err();
        match err.innermost() {
            SceneError::Invalid { field, .. } => assert_eq!(field, "characters"),
            other => panic!("unexpected error {other}"),
        }
    }

    #[test]
    fn overlapping_spawn_points_are_warnings_and_the_world_builds() {
        let mut scene = Scene::builtin("morphology").unwrap();
        scene.terrain.resolution = 65;
        let mut twin = scene.characters[0].clone();
        twin.name = "twin".into();
        scene.characters.push(twin);
        scene.validate().unwrap();
        let warnings = scene.warnings();
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].contains("characters[0]") && warnings[0].contains("characters[3]"));
        let (mut app, walkers) = scene.build_sim().unwrap();
        assert_eq!(walkers.len(), 4);
        softwalk_systems::sim::run_steps(&mut app, 5).unwrap();
        assert!(Scene::builtin("crowd").unwrap().warnings().is_empty());
    }
}
