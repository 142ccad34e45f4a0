//! Built-in scenes: TOML text compiled into the program.
//!
//! Most are files under `softwalk_app/scenes/`; the per-material and grass scenes
//! are filled in from one template each, so the variants cannot drift apart.

use super::SceneError;

const DEFAULT: &str = include_str!("../../scenes/default.toml");
const MATERIAL_WALK: &str = include_str!("../../scenes/material-walk.toml");
const GRASS: &str = include_str!("../../scenes/grass.toml");
const MORPHOLOGY: &str = include_str!("../../scenes/morphology.toml");
const CONTROLLER_COMPARE: &str = include_str!("../../scenes/controller-compare.toml");
const MIXED: &str = include_str!("../../scenes/mixed.toml");
const PROPS: &str = include_str!("../../scenes/props.toml");

/// The materials that get flat, uphill and downhill scenes.
const WALK_MATERIALS: [&str; 4] = ["sand", "soil", "mud", "snow"];
/// Slope of the `-up` and `-down` scenes, degrees.
const WALK_SLOPE_DEG: f32 = 10.0;
/// Grass scenes: name, `[[grass]]` preset, label.
const GRASS_SCENES: [(&str, &str, &str); 2] = [
    ("grass-small", "small", "small (0.5 m)"),
    ("grass-medium", "medium", "medium (0.9 m)"),
];

/// A built-in scene: its name and TOML source.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltinScene {
    /// Name accepted by `softwalk run NAME`.
    pub name: String,
    /// The scene as TOML.
    pub toml: String,
}

/// Every built-in scene, in listing order.
pub fn builtin_scenes() -> Vec<BuiltinScene> {
    let fixed = |name: &str, toml: &str| BuiltinScene {
        name: name.to_owned(),
        toml: toml.to_owned(),
    };
    let mut all = vec![fixed("default", DEFAULT)];
    for material in WALK_MATERIALS {
        for (suffix, angle, words) in [
            ("flat", 0.0, "on flat ground"),
            ("up", WALK_SLOPE_DEG, "up a 10 degree slope"),
            ("down", -WALK_SLOPE_DEG, "down a 10 degree slope"),
        ] {
            let name = format!("{material}-{suffix}");
            let description = format!("Walk on {material} {words}");
            let toml = fill(
                MATERIAL_WALK,
                &[
                    ("@NAME@", &name),
                    ("@DESCRIPTION@", &description),
                    ("@MATERIAL@", material),
                    ("@SHAPE@", &shape_keys(angle)),
                ],
            );
            all.push(BuiltinScene { name, toml });
        }
    }
    for (name, preset, label) in GRASS_SCENES {
        let description = format!("Walk on soil through {label} grass");
        let toml = fill(
            GRASS,
            &[
                ("@NAME@", name),
                ("@DESCRIPTION@", &description),
                ("@PRESET@", preset),
            ],
        );
        all.push(BuiltinScene {
            name: name.to_owned(),
            toml,
        });
    }
    all.push(fixed("morphology", MORPHOLOGY));
    all.push(fixed("controller-compare", CONTROLLER_COMPARE));
    all.push(fixed("mixed", MIXED));
    all.push(fixed("props", PROPS));
    all.push(BuiltinScene {
        name: "crowd".to_owned(),
        toml: super::CrowdSpec::default().toml("crowd"),
    });
    all
}

/// The `[terrain.shape]` keys of a plane rising `angle` degrees towards +X (flat at 0).
fn shape_keys(angle: f32) -> String {
    if angle == 0.0 {
        "kind = \"flat\"".to_owned()
    } else {
        format!("kind = \"slope\"\nangle_deg = {angle:.1}\ndirection_deg = 0.0")
    }
}

fn fill(template: &str, values: &[(&str, &str)]) -> String {
    values
        .iter()
        .fold(template.to_owned(), |text, (key, value)| {
            text.replace(key, value)
        })
}

impl BuiltinScene {
    /// The built-in scene with this name, or an error listing the known names.
    pub fn find(name: &str) -> Result<BuiltinScene, SceneError> {
        let all = builtin_scenes();
        let known = all
            .iter()
            .map(|b| b.name.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        all.iter()
            .find(|b| b.name == name)
            .cloned()
            .ok_or_else(|| SceneError::UnknownBuiltin {
                name: name.to_owned(),
                known,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_templates_fully_filled() {
        let all = builtin_scenes();
        for (k, b) in all.iter().enumerate() {
            assert!(
                !b.toml.contains('@'),
                "{} has an unfilled placeholder",
                b.name
            );
            assert!(
                all[..k].iter().all(|o| o.name != b.name),
                "{} twice",
                b.name
            );
        }
        assert!(BuiltinScene::find("nope").is_err());
    }
}
