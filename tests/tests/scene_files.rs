//! Scene files: every built-in scene validates and round-trips; each kind of bad
//! input gives a clear error that names the field.

use std::fs;
use std::path::Path;

use softwalk_app::scene::{Scene, SceneError, TerrainShape, builtin_scenes};

/// A small valid scene; tests edit one line of it at a time.
const BASE: &str = r#"
name = "probe"

[terrain]
size_x = 10.0
size_z = 10.0
resolution = 64
max_height = 10.0
material = "sand"

[sim]
duration = 1.0
dt = 0.02

[[characters]]
name = "a"
body = { height = 1.75, mass = 70.0 }
path = { kind = "straight", start = [1.0, 5.0], heading_deg = 0.0, length = 5.0 }

[[characters]]
name = "b"
controller = false
path = { kind = "straight", start = [1.0, 7.0], heading_deg = 0.0, length = 5.0 }

[characters.body]
height = 1.0
mass = 20.0
froude = 0.2
alpha = 30.0
"#;

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, Path::new(""))
}

/// Parses `BASE` with `from` replaced by `to` and returns the error text
/// without the line it is on (see `validation_errors_name_their_line`).
fn error_with(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "BASE lacks {from:?}");
    parse(&BASE.replacen(from, to, 1))
        .expect_err("the edited scene should be refused")
        .innermost()
        .to_string()
}

#[test]
fn base_scene_is_valid() {
    let scene = parse(BASE).unwrap();
    assert_eq!(scene.characters.len(), 2);
    assert_eq!(scene.characters[1].body.alpha, 30.0);
    assert_eq!(scene.characters[1].body.froude, 0.2);
    assert_eq!(
        scene.characters[0].body.beta, 6.0,
        "beta defaults to the paper's 6"
    );
    assert!(
        scene.characters[0].controller,
        "the controller is on by default"
    );
    assert!(!scene.characters[1].controller);
    assert_eq!(scene.steps(), 50);
}

#[test]
fn every_builtin_scene_validates_and_round_trips() {
    let all = builtin_scenes();
    assert!(all.len() >= 18);
    for b in &all {
        let scene = Scene::builtin(&b.name).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        assert_eq!(scene.name, b.name);
        assert!(
            !scene.description.is_empty(),
            "{} has no description",
            b.name
        );
        let text = scene.to_toml_string().unwrap();
        let again = parse(&text).unwrap_or_else(|e| panic!("{} dump: {e}\n{text}", b.name));
        assert_eq!(scene, again, "{} does not round-trip", b.name);
    }
}

#[test]
fn builtin_scenes_cover_the_papers_settings() {
    let names: Vec<String> = builtin_scenes().into_iter().map(|b| b.name).collect();
    for material in ["sand", "soil", "mud", "snow"] {
        for kind in ["flat", "up", "down"] {
            let name = format!("{material}-{kind}");
            assert!(names.contains(&name), "missing {name}");
            let s = Scene::builtin(&name).unwrap();
            assert_eq!(s.terrain.material, material);
            assert_eq!((s.terrain.size_x, s.terrain.size_z), (10.0, 10.0));
            assert_eq!(s.terrain.resolution, 512);
            assert_eq!(s.terrain.max_height, 10.0);
            let body = s.characters[0].body;
            assert_eq!((body.alpha, body.beta), (30.0, 6.0));
            let slope = s.terrain.slope().map_or(0.0, |p| p.angle_deg);
            let expected = match kind {
                "flat" => 0.0,
                "up" => 10.0,
                _ => -10.0,
            };
            assert_eq!(slope, expected, "{name}");
        }
    }
    let grass = |n: &str| Scene::builtin(n).unwrap().grass[0].settings().height;
    assert_eq!(grass("grass-small"), 0.5);
    assert_eq!(grass("grass-medium"), 0.9);
    let heights: Vec<f32> = Scene::builtin("morphology")
        .unwrap()
        .characters
        .iter()
        .map(|c| c.body.height)
        .collect();
    assert_eq!(heights, [1.0, 1.4, 1.9]);
    let compare = Scene::builtin("controller-compare").unwrap();
    let controllers: Vec<bool> = compare.characters.iter().map(|c| c.controller).collect();
    assert_eq!(controllers, [true, false]);

    let default = Scene::builtin("default").unwrap();
    assert_eq!(default.steps(), 600, "10 s at 60 Hz");
    assert_eq!(
        (
            default.render.width,
            default.render.height,
            default.render.every
        ),
        (960, 540, 2)
    );
    let [start, end] = default.characters[0].path.polyline()[..] else {
        panic!("the default path is one straight line");
    };
    let along = |f: f32| {
        let x = start[0] + f * (end[0] - start[0]);
        let z = start[1] + f * (end[1] - start[1]);
        default.terrain.material_at(x, z)
    };
    assert_eq!(
        [along(0.05), along(0.5), along(0.95)],
        ["sand", "snow", "soil"]
    );
    let grass = &default.grass[0];
    assert!(
        grass.x[0] < end[0] && end[0] <= grass.x[1],
        "ends in the grass"
    );
    assert!(
        default.terrain.slope().unwrap().angle_deg > 0.0,
        "walks uphill"
    );
    let mixed = Scene::builtin("mixed").unwrap();
    let used: std::collections::BTreeSet<&str> = mixed
        .terrain
        .regions
        .iter()
        .map(|r| r.material.as_str())
        .collect();
    assert!(used.len() >= 3);
}

#[test]
fn missing_field_is_named_with_its_line() {
    let e = error_with("size_x = 10.0\n", "");
    assert!(
        e.starts_with("terrain.size_x: missing field `size_x`"),
        "{e}"
    );
    assert!(e.contains("line "), "{e}");
}

#[test]
fn wrong_type_names_the_field_and_line() {
    let e = error_with("resolution = 64", "resolution = \"fine\"");
    assert!(e.starts_with("terrain.resolution: "), "{e}");
    assert!(e.contains("line 7"), "{e}");
}

#[test]
fn unknown_fields_are_refused() {
    let e = error_with("max_height = 10.0", "max_height = 10.0\nroughness = 3.0");
    assert!(
        e.starts_with("terrain.roughness: unknown field `roughness`"),
        "{e}"
    );
    let e = error_with("name = \"b\"\n", "name = \"b\"\ngamma = 1.0\n");
    assert!(e.starts_with("characters[1].gamma: unknown field"), "{e}");
    let e = error_with("alpha = 30.0", "alpha = 30.0\nleg_factor = 0.5");
    assert!(
        e.starts_with("characters[1].body.leg_factor: unknown field"),
        "{e}"
    );
}

#[test]
fn out_of_range_numbers_are_refused() {
    assert_eq!(
        error_with("resolution = 64", "resolution = 100000"),
        "terrain.resolution: 100000 exceeds the maximum 8192; allowed [2, 8192]"
    );
    assert_eq!(
        error_with("dt = 0.02", "dt = 0.0"),
        "sim.dt: 0 must be > 0; allowed (0, 1]"
    );
    assert_eq!(
        error_with("height = 1.0\n", "height = 7.0\n"),
        "characters[1].body.height: 7 is not a finite number in [0.5, 2.5]"
    );
    assert_eq!(
        error_with("froude = 0.2", "froude = 3.0"),
        "characters[1].body.froude: 3 is not a finite number in [0.02, 0.5]"
    );
    let e = error_with(
        "length = 5.0 }\n\n[[characters]]",
        "length = 50.0 }\n\n[[characters]]",
    );
    assert!(
        e.starts_with("characters[0].path.length: point [51, 5] lies off"),
        "{e}"
    );
}

#[test]
fn dt_outside_1_240_to_1_20_is_refused_naming_sim_dt() {
    for dt in ["0.004", "0.0001", "0.051", "0.1", "1.0"] {
        let e = error_with("dt = 0.02", &format!("dt = {dt}"));
        assert!(
            e.starts_with(&format!(
                "sim.dt: {} s is outside [1/240, 1/20] s",
                dt.trim_end_matches(".0")
            )),
            "{dt}: {e}"
        );
    }
    for dt in [
        "0.004166667",
        "0.0041666668",
        "0.008333334",
        "0.016666668",
        "0.033333335",
        "0.05",
    ] {
        let text = BASE.replacen("dt = 0.02", &format!("dt = {dt}"), 1);
        assert!(parse(&text).is_ok(), "dt = {dt} should be accepted");
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fast.toml");
    fs::write(&path, BASE.replacen("dt = 0.02", "dt = 0.2", 1)).unwrap();
    let e = Scene::load(&path).unwrap_err();
    assert_eq!(e.field(), Some("sim.dt"));
    let text = e.to_string();
    assert!(
        text.contains("fast.toml") && text.contains("sim.dt: 0.2 s is outside"),
        "{text}"
    );
}

#[test]
fn nan_is_refused() {
    assert_eq!(
        error_with("alpha = 30.0", "alpha = nan"),
        "characters[1].body.alpha: NaN is not a finite number in [0, 10000]"
    );
    assert_eq!(
        error_with("size_z = 10.0", "size_z = inf"),
        "terrain.size_z: inf is not allowed (must be finite)"
    );
}

#[test]
fn unknown_material_lists_the_known_ones() {
    let e = error_with(
        "material = \"sand\"",
        "material = \"sand\"\n[[terrain.regions]]\nmaterial = \"quicksand\"\nx = [1.0, 2.0]",
    );
    assert_eq!(
        e,
        "terrain.regions[0].material: unknown material \"quicksand\" (known: sand, soil, mud, snow)"
    );
}

/// `BASE` on a user material `ash`, the `[[materials]]` entry given as TOML keys.
fn with_ash(keys: &str) -> String {
    BASE.replacen(
        "material = \"sand\"",
        &format!("material = \"ash\"\n\n[[materials]]\nname = \"ash\"\n{keys}"),
        1,
    )
}

const ASH: &str = "depth = 1.0\ncompression = 0.3\nsmoothness = 2.0\nrepose_deg = 38.0\ngait = { speed_scale = 0.9, step_length_scale = 0.95, extra_clearance = 0.0 }";

#[test]
fn user_materials_are_data_and_usable() {
    let scene = parse(&with_ash(ASH)).unwrap();
    let ash = scene.material_at(3.0, 3.0).unwrap();
    assert_eq!(ash.depth, 1.0);
    assert!(
        (ash.print_depth() - 0.1).abs() < 1e-6,
        "d_t 1 is a 0.1 m print"
    );
    assert_eq!(ash.gait.speed_scale, 0.9);
    assert!(scene.material_names().contains(&"ash".to_owned()));
    let table = scene.material_table().unwrap();
    assert_eq!(table.by_name("ash").unwrap(), &ash);
    let no_gait = ASH.split("\ngait").next().unwrap();
    let scene = parse(&with_ash(no_gait)).unwrap();
    assert_eq!(
        scene.material("ash").unwrap().gait,
        softwalk_systems::terrain::GaitResponse::NEUTRAL
    );
}

#[test]
fn bad_user_materials_name_the_field() {
    let bad = |from: &str, to: &str| {
        parse(&with_ash(&ASH.replacen(from, to, 1)))
            .expect_err("the material should be refused")
            .innermost()
            .to_string()
    };
    assert_eq!(
        bad("compression = 0.3", "compression = 1.5"),
        "materials[0].compression: 1.5 is not in [0, 1]"
    );
    assert_eq!(
        bad("repose_deg = 38.0", "repose_deg = nan"),
        "materials[0].repose_deg: NaN is not in (0, 90]"
    );
    assert_eq!(
        bad("speed_scale = 0.9", "speed_scale = 0.0"),
        "materials[0].gait.speed_scale: 0 is not in (0, 2]"
    );
    let e = bad("depth = 1.0", "depth = 1.0\nhardness = 2.0");
    assert!(
        e.starts_with("materials[0].hardness: unknown field `hardness`"),
        "{e}"
    );
    let e = bad("smoothness = 2.0\n", "");
    assert!(
        e.starts_with("materials[0].smoothness: missing field `smoothness`"),
        "{e}"
    );
}

#[test]
fn bad_grass_names_the_field() {
    let grass = |keys: &str| {
        let text = BASE.replacen(
            "[[characters]]",
            &format!("[[grass]]\nx = [2.0, 4.0]\nz = [2.0, 4.0]\n{keys}\n\n[[characters]]"),
            1,
        );
        parse(&text)
    };
    let scene = grass("preset = \"medium\"\ngamma = 1.5").unwrap();
    assert_eq!(scene.grass[0].settings().height, 0.9);
    assert_eq!(scene.grass[0].settings().field.gamma, 1.5);
    let e = grass("t_max = nan").unwrap_err().to_string();
    assert!(e.starts_with("grass[0].t_max: NaN is not allowed"), "{e}");
    let e = grass("preset = \"tall\"").unwrap_err().to_string();
    assert!(
        e.starts_with("grass[0].preset: unknown variant `tall`"),
        "{e}"
    );
    let e = grass("density = 1e9").unwrap_err().to_string();
    assert!(e.starts_with("grass[0].density: "), "{e}");
    let e = grass("blades = 3").unwrap_err().to_string();
    assert!(e.starts_with("grass[0].blades: unknown field"), "{e}");
}

#[test]
fn bad_waypoint_paths_name_the_point() {
    let e = error_with(
        "path = { kind = \"straight\", start = [1.0, 5.0], heading_deg = 0.0, length = 5.0 }",
        "path = { kind = \"waypoints\", points = [[1.0, 5.0], [4.0, 5.0], [1.0, 5.1]] }",
    );
    assert!(
        e.starts_with("characters[0].path.points[1]: turns by"),
        "{e}"
    );
    let e = error_with(
        "path = { kind = \"straight\", start = [1.0, 5.0], heading_deg = 0.0, length = 5.0 }",
        "path = { kind = \"waypoints\", points = [[1.0, 5.0]] }",
    );
    assert!(
        e.starts_with("characters[0].path.points: 1 point(s)"),
        "{e}"
    );
}

#[test]
fn missing_heightmap_file_is_named_and_paths_resolve_against_the_scene_folder() {
    let dir = tempfile::tempdir().unwrap();
    let shape = "material = \"sand\"\n\n[terrain.shape]\nkind = \"heightmap\"\npath = \"x.png\"\nheight_scale = 2.0";
    let text = BASE.replacen("material = \"sand\"", shape, 1);
    let scene_path = dir.path().join("scene.toml");
    fs::write(&scene_path, &text).unwrap();

    let e = Scene::load(&scene_path).unwrap_err();
    assert_eq!(e.field(), Some("terrain.shape.path"));
    assert!(matches!(e.innermost(), SceneError::MissingFile { .. }));
    let msg = e.to_string();
    assert!(msg.contains("scene.toml"), "{msg}");
    assert!(msg.contains("terrain.shape.path: file \""), "{msg}");
    assert!(msg.ends_with("x.png\" does not exist (line 13)"), "{msg}");

    // A file that is not a PNG, or a PNG too small to make a grid, is refused by validation.
    let png = dir.path().join("x.png");
    fs::write(&png, b"not a png").unwrap();
    let e = Scene::load(&scene_path).unwrap_err();
    assert!(e.to_string().contains("not a PNG file"), "{e}");
    let gray = |w: u32, h: u32| {
        image::ImageBuffer::<image::Luma<u16>, _>::from_raw(w, h, vec![0u16; (w * h) as usize])
            .unwrap()
            .save(&png)
            .unwrap();
    };
    gray(1, 1);
    let e = Scene::load(&scene_path).unwrap_err();
    assert_eq!(e.field(), Some("terrain.shape.path"));
    assert!(
        e.to_string().contains("1 x 1 pixels; at least 2 x 2"),
        "{e}"
    );
    gray(2, 2);
    let scene = Scene::load(&scene_path).unwrap();
    assert_eq!(scene.heightmap_path().unwrap(), dir.path().join("x.png"));
    assert!(matches!(
        scene.terrain.shape,
        TerrainShape::Heightmap { .. }
    ));
}

#[test]
fn unreadable_scene_file_names_the_file() {
    let e = Scene::load(Path::new("no/such/scene.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Read { .. }));
    assert!(e.to_string().contains("no/such/scene.toml"), "{e}");
}

#[test]
fn inconsistent_fields_are_refused() {
    let e = error_with("name = \"b\"", "name = \"a\"");
    assert_eq!(e, "characters[1].name: character \"a\" is defined twice");
    let e = error_with(
        "[sim]",
        "[camera]\nfov_deg = 50.0\nmode = { kind = \"follow\", character = \"zed\", offset = [1.0, 1.0, 1.0] }\n\n[sim]",
    );
    assert!(
        e.starts_with("camera.mode.character: no character named \"zed\""),
        "{e}"
    );
    let e = error_with(
        "max_height = 10.0",
        "max_height = 1.0\nshape = { kind = \"slope\", angle_deg = 30.0, direction_deg = 0.0 }",
    );
    assert!(e.starts_with("terrain.shape: spans"), "{e}");
}

/// A built-in scene's TOML with `edit` applied.
fn edited_builtin(name: &str, edit: impl Fn(&str) -> String) -> String {
    edit(&Scene::builtin(name).unwrap().to_toml_string().unwrap())
}

#[test]
fn a_missing_top_level_table_is_named_not_the_first_key() {
    let text = edited_builtin("sand-flat", |t| {
        let mut skip = false;
        t.lines()
            .filter(|l| {
                if l.starts_with('[') {
                    skip = l.starts_with("[terrain");
                }
                !skip
            })
            .map(|l| format!("{l}\n"))
            .collect()
    });
    let err = Scene::from_toml_str(&text, Path::new("")).unwrap_err();
    assert_eq!(err.field(), Some("terrain"), "{err}");
}

#[test]
fn a_bad_value_in_a_tagged_table_names_its_key() {
    let text = edited_builtin("sand-flat", |t| {
        let mut in_path = false;
        t.lines()
            .map(|l| {
                if l.starts_with('[') {
                    in_path = l == "[characters.path]";
                }
                if in_path && l.starts_with("start = ") {
                    "start = 1.0\n".to_owned()
                } else {
                    format!("{l}\n")
                }
            })
            .collect()
    });
    let err = Scene::from_toml_str(&text, Path::new("")).unwrap_err();
    assert_eq!(err.field(), Some("characters[0].path.start"), "{err}");
}

#[test]
fn a_huge_dotted_key_is_not_echoed_whole() {
    let text = format!("name = \"x\"\n{}b = 1\n", "a.".repeat(100_000));
    let err = Scene::from_toml_str(&text, Path::new("")).unwrap_err();
    assert!(
        err.to_string().len() < 1000,
        "{} bytes",
        err.to_string().len()
    );
}

#[test]
fn a_scene_path_that_is_not_a_regular_file_is_refused_without_reading() {
    let dir = tempfile::tempdir().unwrap();
    let err = Scene::load(dir.path()).unwrap_err();
    assert!(matches!(err, SceneError::NotAFile { .. }), "{err}");
    #[cfg(unix)]
    {
        let fifo = dir.path().join("scene.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let err = Scene::load(&fifo).unwrap_err();
            assert!(matches!(err, SceneError::NotAFile { .. }), "{err}");
        }
    }
}
