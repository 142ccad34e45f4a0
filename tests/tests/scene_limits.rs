//! Issue 22 regressions: every limit the run enforces is checked by validation,
//! with the field's path, its line, the value and the allowed range; numbers
//! have physical bounds; keys a scene kind does not use are refused.

use std::path::Path;
use std::time::{Duration, Instant};

use softwalk_app::scene::{GIF_DELAY_MS, MAX_REGIONS, Scene, SceneError};
use softwalk_systems::sim::run_steps;

/// A small valid scene; tests edit it. `beta` is on line 16.
const BASE: &str = r#"name = "probe"

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
body = { height = 1.75, mass = 70.0, beta = 6.0 }
path = { kind = "straight", start = [1.0, 5.0], heading_deg = 0.0, length = 5.0 }
"#;

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, Path::new(""))
}

/// `BASE` with `from` replaced by `to` must be refused; returns the error.
fn refused(text: &str) -> SceneError {
    parse(text).expect_err("the edited scene should be refused")
}

fn edit(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "BASE lacks {from:?}");
    BASE.replacen(from, to, 1)
}

#[test]
fn base_scene_is_valid_and_runs() {
    let scene = parse(BASE).unwrap();
    let (mut app, _) = scene.build_sim().unwrap();
    run_steps(&mut app, 3).unwrap();
}

#[test]
fn beta_at_or_above_the_passive_damping_is_refused_by_validation() {
    for beta in ["12.0", "50.0", "10000.0"] {
        let e = refused(&edit("beta = 6.0", &format!("beta = {beta}")));
        assert_eq!(e.field(), Some("characters[0].body.beta"), "{e}");
        assert_eq!(e.line(), Some(16), "{e}");
        let text = e.to_string();
        assert!(text.contains("allowed [0, 12)"), "{text}");
    }
    // Just below the limit validates and runs (the run used to refuse above 12).
    let scene = parse(&edit("beta = 6.0", "beta = 11.9")).unwrap();
    let (mut app, _) = scene.build_sim().unwrap();
    run_steps(&mut app, 3).unwrap();
}

#[test]
fn grass_beyond_the_sampled_grid_is_refused_and_grass_inside_it_builds() {
    // 10 m at resolution 11 is a 1 m cell; 9.99 m gets 9 whole cells: the grid stops at z = 9.
    let base =
        edit("size_z = 10.0", "size_z = 9.99").replacen("resolution = 64", "resolution = 11", 1);
    let with_grass =
        |z1: &str| format!("{base}\n[[grass]]\nx = [1.0, 3.0]\nz = [1.0, {z1}]\ndensity = 100.0\n");
    let e = refused(&with_grass("9.99"));
    assert_eq!(e.field(), Some("grass[0].z[1]"), "{e}");
    assert!(e.to_string().contains("9.99"), "{e}");
    let scene = parse(&with_grass("9.0")).unwrap();
    scene
        .build_sim()
        .expect("grass on the grid has ground under it");
}

#[test]
fn paths_beyond_the_sampled_grid_are_refused() {
    let text = edit("size_z = 10.0", "size_z = 9.99")
        .replacen("resolution = 64", "resolution = 11", 1)
        .replacen("start = [1.0, 5.0]", "start = [1.0, 9.5]", 1);
    let e = refused(&text);
    assert_eq!(e.field(), Some("characters[0].path.start"), "{e}");
}

#[test]
fn gif_frame_delays_out_of_range_name_render_every() {
    let render = |every: u32, gif: bool| {
        format!("{BASE}\n[render]\nwidth = 64\nheight = 64\nevery = {every}\ngif = {gif}\n")
    };
    // dt 0.02 * 100000 = 2000 s between frames: more than a GIF stores.
    let e = refused(&render(100_000, true));
    assert_eq!(e.field(), Some("render.every"), "{e}");
    assert!(e.to_string().contains("2000000 ms"), "{e}");
    assert!(e.line().is_some(), "{e}");
    // 1/240 s per frame is 4 ms: less than a GIF's 10 ms.
    let fast = render(1, true).replacen("dt = 0.02", "dt = 0.004166667", 1);
    let e = refused(&fast);
    assert_eq!(e.field(), Some("render.every"), "{e}");
    assert!(e.to_string().contains("sim.dt"), "{e}");
    // Without a GIF the cadence is free.
    parse(&render(100_000, false)).unwrap();
    parse(&render(1, false).replacen("dt = 0.02", "dt = 0.004166667", 1)).unwrap();
}

#[test]
fn the_gif_delay_range_is_the_writers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.gif");
    let [lo, hi] = GIF_DELAY_MS;
    for ok in [lo, hi] {
        engine::output::GifWriter::create(&path, ok).expect("in range");
    }
    for bad in [lo - 1, hi + 1] {
        assert!(engine::output::GifWriter::create(&path, bad).is_err());
    }
}

#[test]
fn too_many_regions_are_refused_quickly() {
    let mut text = BASE.to_owned();
    // 200,000 regions used to hang the set-up; a few thousand show the cap as well.
    for _ in 0..5_000 {
        text.push_str("[[terrain.regions]]\nmaterial = \"snow\"\nx = [1.0, 2.0]\n");
    }
    let start = Instant::now();
    let e = refused(&text);
    assert!(start.elapsed() < Duration::from_secs(20), "{e}");
    assert_eq!(
        e.field(),
        Some(format!("terrain.regions[{MAX_REGIONS}]").as_str())
    );
    assert!(e.to_string().contains("5000 entries"), "{e}");
}

#[test]
fn grass_numbers_have_physical_bounds() {
    let grass = |key: &str| {
        format!("{BASE}\n[[grass]]\nx = [1.0, 3.0]\nz = [1.0, 3.0]\npreset = \"medium\"\n{key}\n")
    };
    for (key, field) in [
        ("height = 1e30", "grass[0].height"),
        ("height = 1e5", "grass[0].height"),
        ("height = 3.5", "grass[0].height"),
        ("blade_width = 1e30", "grass[0].blade_width"),
        ("blade_width = 0.5", "grass[0].blade_width"),
        ("t_max = 1e9", "grass[0].t_max"),
        ("gamma = 1e9", "grass[0].gamma"),
        ("recovery_omega = 1e9", "grass[0].recovery_omega"),
        ("break_bend = 1e9", "grass[0].break_bend"),
        ("density = 1e9", "grass[0].density"),
    ] {
        let e = refused(&grass(key));
        assert_eq!(e.field(), Some(field), "{key}: {e}");
        assert!(e.to_string().contains("allowed (0, "), "{key}: {e}");
        assert!(e.line().is_some(), "{key}: {e}");
    }
    parse(&grass("height = 2.0\nblade_width = 0.01")).unwrap();
}

#[test]
fn blades_are_capped_over_all_patches() {
    // Each patch alone is under the cap (2^26 blades); together they are not.
    let mut text =
        edit("size_x = 10.0", "size_x = 1000.0").replacen("size_z = 10.0", "size_z = 1000.0", 1);
    for _ in 0..3 {
        text.push_str("\n[[grass]]\nx = [0.0, 1000.0]\nz = [0.0, 1000.0]\ndensity = 30.0\n");
    }
    let e = refused(&text);
    assert_eq!(e.field(), Some("grass[2].density"), "{e}");
    assert!(e.to_string().contains("over all patches"), "{e}");
}

#[test]
fn tagged_shapes_refuse_keys_of_other_kinds() {
    let flat = format!(
        "{BASE}\n[terrain.shape]\nkind = \"flat\"\nangle_deg = 30.0\nbogus = \"anything\"\n"
    );
    // The shape table follows [[characters]] in the text; put it under [terrain].
    let flat = flat.replacen(
        "material = \"sand\"\n",
        "material = \"sand\"\nshape = { kind = \"flat\", angle_deg = 30.0, bogus = \"anything\" }\n",
        1,
    );
    let flat = flat.split("\n[terrain.shape]").next().unwrap().to_owned();
    let e = refused(&flat);
    assert_eq!(e.field(), Some("terrain.shape.angle_deg"), "{e}");
    assert_eq!(e.line(), Some(9), "{e}");
    let only_bogus = flat.replacen("angle_deg = 30.0, ", "", 1);
    let e = refused(&only_bogus);
    assert_eq!(e.field(), Some("terrain.shape.bogus"), "{e}");
    // The same under a kind that has no such key was already refused.
    let slope = flat.replacen(
        "kind = \"flat\"",
        "kind = \"slope\", direction_deg = 0.0",
        1,
    );
    let e = refused(&slope);
    assert!(e.to_string().contains("bogus"), "{e}");
}

#[test]
fn dune_and_noise_sizes_are_bounded() {
    let shape = |s: &str| {
        edit(
            "material = \"sand\"\n",
            &format!("material = \"sand\"\n{s}\n"),
        )
    };
    let e = refused(&shape(
        "shape = { kind = \"dunes\", amplitude = 0.3, wavelength = 1e-30 }",
    ));
    assert_eq!(e.field(), Some("terrain.shape.wavelength"), "{e}");
    let e = refused(&shape(
        "shape = { kind = \"noise\", amplitude = 0.3, feature_size = 1e30 }",
    ));
    assert_eq!(e.field(), Some("terrain.shape.feature_size"), "{e}");
}

#[test]
fn camera_coordinates_are_bounded() {
    let text = format!(
        "{BASE}\n[camera]\nfov_deg = 50.0\nmode = {{ kind = \"fixed\", eye = [1e30, 1.0, 1.0], target = [0.0, 0.0, 0.0] }}\n"
    );
    let e = refused(&text);
    assert_eq!(e.field(), Some("camera.mode.eye[0]"), "{e}");
}
