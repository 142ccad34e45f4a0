//! Bring your own character: models the way other tools export them, built
//! from the built-in human by changing one thing at a time (bone names,
//! units, up and forward axes, bind pose, extra and missing bones,
//! proportions), written as `.glb` and loaded through a scene's `model`.
//! Each either walks, with its leg chains found, its skinned soles on the
//! ground in stance and the gait goals met, or is refused with a typed error
//! naming the file and what is wrong.
//!
//! Set `KEEP_VARIANTS=DIR` to keep the written `.glb` files in `DIR` (to
//! render them with `softwalk run` or read them with `softwalk inspect`).
//! Run with `--nocapture` for the table of figures.

use std::f32::consts::FRAC_PI_2;
use std::path::{Path, PathBuf};

use engine::anim::{RigPreset, Transform};
use glam::{Quat, Vec3};
use rayon::prelude::*;
use softwalk_app::cli::Cli;
use softwalk_app::commands::execute;
use softwalk_app::scene::Scene;
use softwalk_systems::character::{CharacterRig, ModelError, ModelUnits};
use softwalk_tests::glb_writer::{Prop, RigParts};
use softwalk_tests::sole_contact::walk_soles;

/// Length of each variant's measured walk, seconds.
const WALK_S: f64 = 5.0;
/// Largest angle between a variant's detected facing and the expected one, degrees.
const FACING_TOLERANCE_DEG: f32 = 5.0;

/// One way a game programmer's character differs from the built-in human.
struct Variant {
    /// File stem and table row.
    name: &'static str,
    /// Edits the human's parts into it.
    edit: fn(&mut RigParts),
    /// What loading it must give.
    expect: Expect,
}

impl Variant {
    /// The human's parts with this variant's edit.
    fn parts(&self) -> RigParts {
        let mut parts = RigParts::human();
        (self.edit)(&mut parts);
        parts
    }
}

enum Expect {
    /// It walks: its units, the bone-name preset detected, the direction it faces in the file.
    Walks {
        units: ModelUnits,
        preset: RigPreset,
        facing: Vec3,
    },
    /// Refused: `CharacterRig::load` gives the error `typed` accepts, and a
    /// scene's error names the file and contains `words`.
    Refused {
        typed: fn(&ModelError) -> bool,
        words: &'static str,
    },
}

fn variants() -> Vec<Variant> {
    let walks = |units, preset, facing| Expect::Walks {
        units,
        preset,
        facing,
    };
    let metres = |facing| walks(ModelUnits::Metres, RigPreset::GameEngine, facing);
    vec![
        Variant {
            name: "mixamo-names",
            edit: |p| mixamo_named(p, "mixamorig:"),
            expect: walks(ModelUnits::Metres, RigPreset::Mixamo, Vec3::Z),
        },
        Variant {
            name: "mixamo-underscore-names",
            edit: |p| mixamo_named(p, "mixamorig_"),
            expect: walks(ModelUnits::Metres, RigPreset::Mixamo, Vec3::Z),
        },
        Variant {
            name: "humanik-names",
            edit: |p| mixamo_named(p, "Character1_"),
            expect: walks(ModelUnits::Metres, RigPreset::Mixamo, Vec3::Z),
        },
        Variant {
            name: "mixamo-export",
            edit: |p| {
                mixamo_named(p, "mixamorig:");
                p.turn(Quat::from_rotation_x(FRAC_PI_2));
                p.in_units(100.0);
                p.insert_root(
                    "Armature",
                    Transform {
                        rotation: Quat::from_rotation_x(-FRAC_PI_2),
                        scale: Vec3::splat(0.01),
                        ..Transform::IDENTITY
                    },
                );
            },
            expect: walks(ModelUnits::Metres, RigPreset::Mixamo, Vec3::Z),
        },
        Variant {
            name: "centimetres-armature-scale",
            edit: |p| {
                p.in_units(100.0);
                p.insert_root(
                    "Armature",
                    Transform {
                        scale: Vec3::splat(0.01),
                        ..Transform::IDENTITY
                    },
                );
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "centimetres-no-scale",
            edit: |p| {
                p.in_units(100.0);
            },
            expect: walks(ModelUnits::Centimetres, RigPreset::GameEngine, Vec3::Z),
        },
        Variant {
            name: "decimetres",
            edit: |p| {
                p.in_units(10.0);
            },
            expect: Expect::Refused {
                typed: |e| matches!(e, ModelError::Units { .. }),
                words: "units tall",
            },
        },
        Variant {
            name: "z-up-armature",
            edit: |p| {
                p.turn(Quat::from_rotation_x(FRAC_PI_2));
                p.insert_root(
                    "Armature",
                    Transform {
                        rotation: Quat::from_rotation_x(-FRAC_PI_2),
                        ..Transform::IDENTITY
                    },
                );
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "z-up-uncorrected",
            edit: |p| {
                p.turn(Quat::from_rotation_x(FRAC_PI_2));
            },
            expect: Expect::Refused {
                typed: |e| matches!(e, ModelError::LyingDown { .. }),
                words: "lies down",
            },
        },
        Variant {
            name: "facing-minus-z",
            edit: |p| {
                p.turn(Quat::from_rotation_y(std::f32::consts::PI));
            },
            expect: metres(Vec3::NEG_Z),
        },
        Variant {
            name: "facing-plus-x",
            edit: |p| {
                p.turn(Quat::from_rotation_y(FRAC_PI_2));
            },
            expect: metres(Vec3::X),
        },
        Variant {
            name: "origin-at-the-hips",
            edit: |p| {
                let hips = p.globals()[p.joint("pelvis")].w_axis.truncate();
                p.insert_root("Armature", Transform::from_translation(-hips));
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "bones-along-their-y-axis",
            edit: |p| {
                let frames: Vec<Quat> = {
                    let at: Vec<Vec3> = p.globals().iter().map(|g| g.w_axis.truncate()).collect();
                    (0..p.joints.len())
                        .map(|j| p.along_bone(j, &at, 0.3 * j as f32))
                        .collect()
                };
                p.reorient(|j, _| frames[j]);
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "tail-below-the-soles",
            edit: |p| {
                let tip = Vec3::new(0.0, -0.1, -0.35);
                let base = [
                    Vec3::new(-0.05, 0.9, -0.1),
                    Vec3::new(0.05, 0.9, -0.1),
                    Vec3::new(0.0, 0.95, -0.15),
                ];
                p.add_tetrahedron("pelvis", [base[0], base[1], base[2], tip]);
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "t-pose",
            edit: |p| {
                p.aim_bone("upperarm_l", "lowerarm_l", Vec3::X);
                p.aim_bone("upperarm_r", "lowerarm_r", Vec3::NEG_X);
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "extra-bones",
            edit: extra_bones,
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "missing-bones",
            edit: |p| {
                for bone in [
                    "ball_l",
                    "ball_r",
                    "clavicle_l",
                    "clavicle_r",
                    "spine_02",
                    "spine_03",
                ] {
                    p.remove_bone(bone);
                }
            },
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "several-meshes-and-a-prop",
            edit: several_meshes_and_a_prop,
            expect: metres(Vec3::Z),
        },
        Variant {
            name: "long-legs-short-torso",
            edit: |p| {
                let hips = p.globals()[p.joint("thigh_l")].w_axis.y;
                p.stretch_vertically(hips, 1.15, 0.8);
            },
            expect: metres(Vec3::Z),
        },
    ]
}

/// Mixamo's bone names after `namespace` (`mixamorig:`, `mixamorig_`, or
/// Maya HumanIK's `Character1_`), on every joint.
fn mixamo_named(p: &mut RigParts, namespace: &str) {
    p.rename_to_preset(RigPreset::Mixamo, "mixamorig:");
    p.rename(|n| n.replace("mixamorig:", namespace));
}

/// Twist bones on the thighs and upper arms (taking the lower half of their
/// skin), an IK bone per foot under the root (as Unreal rigs have), and a
/// weapon bone in the right hand; the human already has a root at the
/// ground and fingers.
fn extra_bones(p: &mut RigParts) {
    for side in ["l", "r"] {
        for (upper, lower) in [("thigh", "calf"), ("upperarm", "lowerarm")] {
            let (u, l) = (
                p.joint(&format!("{upper}_{side}")),
                p.joint(&format!("{lower}_{side}")),
            );
            let globals = p.globals();
            let (a, b) = (globals[u].w_axis.truncate(), globals[l].w_axis.truncate());
            let mid = 0.5 * (a + b);
            let along = b - a;
            p.add_bone(
                &format!("{upper}_{side}"),
                &format!("{upper}_twist_01_{side}"),
                0.5 * p.joints[l].rest.translation,
                move |v| (v - mid).dot(along) > 0.0,
            );
        }
        let foot = p.globals()[p.joint(&format!("foot_{side}"))]
            .w_axis
            .truncate();
        let root = p.globals()[p.joint("Root")].w_axis.truncate();
        p.add_bone("Root", &format!("ik_foot_{side}"), foot - root, |_| false);
    }
    p.add_bone("hand_r", "weapon_r", Vec3::new(-0.05, -0.05, 0.05), |_| {
        false
    });
}

/// The body in three meshes drawn with the character's skin (head, feet,
/// the rest), after a sword triangle drawn with a skin of its own (the hand).
fn several_meshes_and_a_prop(p: &mut RigParts) {
    let neck = p.globals()[p.joint("neck_01")].w_axis.y;
    let triangles: Vec<[u32; 3]> = (p.indices.chunks_exact(3))
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    p.triangle_mesh = triangles
        .iter()
        .map(|t| {
            let y = t.map(|v| p.positions[v as usize].y);
            if y.iter().all(|&y| y > neck) {
                1
            } else if y.iter().all(|&y| y < 0.15) {
                2
            } else {
                0
            }
        })
        .collect();
    let hand = p.globals()[p.joint("hand_r")].w_axis.truncate();
    p.props.push(Prop {
        joint: "hand_r".to_string(),
        triangle: [
            hand,
            hand + Vec3::new(0.0, -0.9, 0.0),
            hand + Vec3::new(0.0, -0.9, 0.05),
        ],
    });
}

/// Where a test writes the variants' files: `KEEP_VARIANTS/test` if set
/// (one folder per test, as tests run at once), else a temporary folder.
fn output_dir(test: &str) -> (PathBuf, Option<tempfile::TempDir>) {
    match std::env::var_os("KEEP_VARIANTS") {
        Some(dir) => {
            let dir = PathBuf::from(dir).join(test);
            std::fs::create_dir_all(&dir).unwrap();
            (dir, None)
        }
        None => {
            let temp = tempfile::tempdir().unwrap();
            (temp.path().to_path_buf(), Some(temp))
        }
    }
}

/// Writes a variant's `.glb` into `dir`.
fn write(variant: &Variant, dir: &Path) -> PathBuf {
    let path = dir.join(format!("{}.glb", variant.name));
    std::fs::write(&path, variant.parts().to_glb()).unwrap();
    path
}

/// The sand walk with its first character drawn as the model at `path`.
fn scene_with(path: &Path) -> Scene {
    let mut scene = Scene::builtin("sand-flat").unwrap();
    scene.characters.truncate(1);
    scene.characters[0].model = path.display().to_string();
    scene
}

#[test]
fn every_variant_walks_on_its_soles_or_is_refused_naming_the_file() {
    let (dir, _temp) = output_dir("walks");
    let variants = variants();
    let rows: Vec<(String, Vec<String>)> = variants
        .par_iter()
        .map(|v| {
            let path = write(v, &dir);
            let scene = scene_with(&path);
            let mut failures = Vec::new();
            let row = match &v.expect {
                Expect::Refused { typed, words } => {
                    match CharacterRig::load(&path, None) {
                        Err(e) if typed(&e) => {}
                        Err(e) => failures.push(format!("refused with another error: {e}")),
                        Ok(_) => failures.push("loaded".to_string()),
                    }
                    let e = scene.validate().unwrap_err().to_string();
                    if !(e.contains(words) && e.contains(&path.display().to_string())) {
                        failures.push(format!("refused without naming the file and {words:?}: {e}"));
                    }
                    format!("refused: {e}")
                }
                Expect::Walks {
                    units,
                    preset,
                    facing,
                } => {
                    let rig = CharacterRig::load(&path, None).unwrap_or_else(|e| panic!("{e}"));
                    let triangles = v.parts().indices.len() / 3;
                    if rig.model().mesh.triangle_count() != triangles {
                        failures.push(format!(
                            "{} of {triangles} triangles loaded",
                            rig.model().mesh.triangle_count()
                        ));
                    }
                    if rig.units() != *units {
                        failures.push(format!("units {} instead of {units}", rig.units()));
                    }
                    if rig.bone_map().preset != Some(*preset) {
                        failures.push(format!("preset {:?} instead of {preset:?}", rig.bone_map().preset));
                    }
                    let off = rig.rest_frame().z_axis.angle_between(*facing).to_degrees();
                    if off > FACING_TOLERANCE_DEG {
                        failures.push(format!("faces {} degrees off {facing}", off));
                    }
                    let walk = walk_soles(&scene, WALK_S);
                    let f = &walk.soles;
                    if !f.met() || f.stance_steps < 100 {
                        failures.push(format!("soles {f:?}"));
                    }
                    failures.extend(walk.quality.failures());
                    format!(
                        "loads ({}, {:?}), chains found, sole gap {:.2} cm, slide {:.2} cm over {} stance steps, gait goals {}",
                        rig.units(),
                        preset,
                        100.0 * f.gap,
                        100.0 * f.slide,
                        f.stance_steps,
                        if walk.quality.failures().is_empty() { "met" } else { "MISSED" }
                    )
                }
            };
            (format!("{}: {row}", v.name), failures.into_iter().map(|f| format!("{}: {f}", v.name)).collect())
        })
        .collect();
    let mut failures = Vec::new();
    for (row, f) in rows {
        println!("{row}");
        failures.extend(f);
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn inspect_says_the_units_the_facing_the_preset_and_what_is_optional() {
    let (dir, _temp) = output_dir("inspect");
    let all = variants();
    let inspect = |name: &str| {
        let v = all.iter().find(|v| v.name == name).unwrap();
        let path = write(v, &dir);
        let cli = Cli::parse_args(["softwalk", "inspect", path.to_str().unwrap()]).unwrap();
        let mut out = Vec::new();
        execute(cli, &mut out).unwrap();
        String::from_utf8(out).unwrap()
    };
    for (name, words) in [
        ("mixamo-names", &["bone names: Mixamo", "units metres"][..]),
        (
            "mixamo-export",
            &[
                "bone names: Mixamo",
                "root Armature: turned 90 degrees about (-1.00",
                "scaled (0.01",
            ],
        ),
        (
            "centimetres-armature-scale",
            &["root Armature: scaled (0.01", "units metres"],
        ),
        (
            "centimetres-no-scale",
            &["units centimetres", "stands 1.67 m"],
        ),
        (
            "z-up-armature",
            &["root Armature: turned 90 degrees about (-1.00", "faces +Z"],
        ),
        ("facing-plus-x", &["faces +X"]),
        ("facing-minus-z", &["faces -Z"]),
        (
            "missing-bones",
            &[
                "toe none (optional)",
                "spine: pelvis -> spine_01 -> neck_01",
            ],
        ),
        ("decimetres", &["refused as a character", "units tall"]),
        ("z-up-uncorrected", &["refused as a character", "lies down"]),
    ] {
        let out = inspect(name);
        for w in words {
            assert!(out.contains(w), "{name}: no {w:?} in\n{out}");
        }
    }
}
