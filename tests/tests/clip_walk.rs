//! A walk driven by the shipped BVH clip (`assets/clips/walk.bvh`): it meets
//! every gait goal on sand and on snow, the cadence is the clip's, the rig's
//! arms swing as the clip's do in step with the legs, and scenes refuse a
//! missing clip or one that is not a walk with errors naming the field.

use std::path::{Path, PathBuf};

use engine::anim::BoneRole;
use engine::ecs::Entity;
use engine::schedule::App;
use rayon::prelude::*;
use softwalk_app::paper::recorded_run::record_run;
use softwalk_app::scene::{Scene, SceneError};
use softwalk_systems::character::{
    CharacterBody, CharacterRig, ClipWalk, DOWNHILL_STEP_SHORTENING, Gait, GaitModifiers,
    GaitParams, Pose,
};
use softwalk_systems::sim::{Feet, run_steps};

/// The shipped clip, relative to the repository root.
const CLIP: &str = "assets/clips/walk.bvh";
/// Its cycle, seconds (`tools/make_walk_bvh.py`).
const CLIP_PERIOD_S: f32 = 1.1;
/// Length of each measured walk, seconds.
const WALK_S: f64 = 5.0;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A built-in scene whose first character walks like the shipped clip.
fn with_clip(name: &str) -> Scene {
    let mut scene = Scene::builtin(name).unwrap();
    scene.base_dir = repo_root();
    scene.characters[0].clip = Some(CLIP.to_string());
    scene
}

#[test]
fn the_clip_walk_meets_every_gait_goal_on_sand_and_snow() {
    let failures: Vec<String> = ["sand-flat", "snow-flat"]
        .par_iter()
        .flat_map(|name| {
            let scene = with_clip(name);
            let run = record_run(&scene, scene.sim.steps_for(WALK_S)).unwrap();
            let quality = run.quality(0);
            println!("{name} with the clip: {quality}");
            quality
                .failures()
                .into_iter()
                .map(|f| format!("{name}: {f}"))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Times (seconds) at which the gait's phase wraps to a new cycle.
fn cycle_starts(app: &mut App, walker: Entity, dt: f32) -> Vec<f32> {
    let steps = (WALK_S / f64::from(dt)) as usize;
    let mut starts = Vec::new();
    let mut last = app.world.get::<Gait>(walker).unwrap().phase;
    for k in 1..=steps {
        run_steps(app, 1).unwrap();
        let phase = app.world.get::<Gait>(walker).unwrap().phase;
        if phase < last - 0.5 {
            // Linear in time across the wrap.
            let before = 1.0 - last;
            let fraction = before / (before + phase);
            starts.push((k as f32 - 1.0 + fraction) * dt);
        }
        last = phase;
    }
    starts
}

/// The mean time between the last few cycle starts.
fn measured_period(starts: &[f32]) -> f32 {
    let tail = &starts[starts.len().saturating_sub(3)..];
    (tail[tail.len() - 1] - tail[0]) / (tail.len() - 1) as f32
}

#[test]
fn the_cadence_is_the_clips() {
    let scene = with_clip("sand-flat");
    let (mut app, walkers) = scene.build_sim().unwrap();
    let body = app.world.get::<CharacterBody>(walkers[0]).unwrap().clone();
    // Unmodified, a cycle lasts the clip's period whatever the body's Froude number.
    let plain = GaitParams::new(&body, &GaitModifiers::default());
    assert!(
        (plain.cycle_time() - CLIP_PERIOD_S).abs() < 0.02,
        "{plain:?}"
    );
    let leg = body.leg_reach();
    assert!((plain.stride / leg - 1.56 / 0.85).abs() < 0.05, "{plain:?}");
    // On sand the material's modifiers apply on top; the walk keeps that cadence.
    let starts = cycle_starts(&mut app, walkers[0], scene.sim.dt);
    assert!(starts.len() >= 3, "{starts:?}");
    let gait = app.world.get::<Gait>(walkers[0]).unwrap().params;
    let period = measured_period(&starts);
    assert!(
        (period - gait.cycle_time()).abs() < 0.03,
        "measured {period} s, gait {gait:?}"
    );
    // That cycle is the clip's, scaled by the sand's stride and speed
    // factors, and shortened where the body's ground reads downhill (a
    // print's rim under one of its rays tilts it by a degree or so).
    let modifiers = *app.world.get::<GaitModifiers>(walkers[0]).unwrap();
    let downhill = 1.0 + DOWNHILL_STEP_SHORTENING * (-modifiers.grade).max(0.0);
    let expected = CLIP_PERIOD_S * modifiers.step_length_scale / (modifiers.speed_scale * downhill);
    assert!(
        (gait.cycle_time() - expected).abs() < 0.02,
        "gait {gait:?}, modifiers {modifiers:?}"
    );
}

/// Forward offsets from the pelvis of the rig's left wrist and right ankle,
/// step by step, as the view poses the rig.
fn wrist_and_foot(app: &mut App, walker: Entity, steps: usize) -> Vec<(f32, f32)> {
    let rig = app.world.get::<CharacterRig>(walker).unwrap().clone();
    let clip = app.world.get::<ClipWalk>(walker).unwrap().clone();
    let map = rig.bone_map();
    let hand = map.joint(BoneRole::HandL).unwrap();
    let ankle = rig.chains().right.ankle;
    let pelvis = rig.chains().pelvis;
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        run_steps(app, 1).unwrap();
        let body = app.world.get::<CharacterBody>(walker).unwrap();
        let pose = app.world.get::<Pose>(walker).unwrap();
        let feet = app.world.get::<Feet>(walker).unwrap();
        let gait = app.world.get::<Gait>(walker).unwrap();
        let posed = clip.drive(&rig, &body, &pose, &feet.0, &gait);
        let forward = |j: usize| (posed.positions[j] - posed.positions[pelvis]).dot(pose.forward);
        out.push((forward(hand), forward(ankle)));
    }
    out
}

fn correlation(pairs: &[(f32, f32)]) -> f32 {
    let n = pairs.len() as f32;
    let (ma, mb) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for &(a, b) in pairs {
        ab += (a - ma) * (b - mb);
        aa += (a - ma) * (a - ma);
        bb += (b - mb) * (b - mb);
    }
    ab / (aa * bb).sqrt()
}

#[test]
fn the_left_wrist_swings_forward_with_the_right_foot() {
    let scene = with_clip("sand-flat");
    let (mut app, walkers) = scene.build_sim().unwrap();
    // Skip the first second (the start from standing).
    run_steps(&mut app, scene.sim.steps_for(1.0)).unwrap();
    let steps = scene.sim.steps_for(3.0) as usize;
    let series = wrist_and_foot(&mut app, walkers[0], steps);
    let r = correlation(&series);
    let swing = series.iter().map(|s| s.0).fold(f32::NEG_INFINITY, f32::max)
        - series.iter().map(|s| s.0).fold(f32::INFINITY, f32::min);
    println!("left wrist vs right ankle: correlation {r:.2}, wrist swing {swing:.3} m");
    assert!(r > 0.8, "correlation {r}");
    // The clip's shoulder swings about +-17 degrees on a ~0.6 m arm.
    assert!((0.15..0.6).contains(&swing), "wrist swing {swing} m");
}

#[test]
fn a_missing_or_non_walk_clip_is_refused_naming_the_field() {
    let mut scene = with_clip("sand-flat");
    scene.characters[0].clip = Some("assets/clips/nowhere.bvh".into());
    let e = scene.build_sim().err().unwrap();
    assert!(matches!(e, SceneError::MissingFile { .. }), "{e}");
    assert_eq!(e.field(), Some("characters[0].clip"));

    scene.characters[0].clip = Some("assets/clips/README.md".into());
    let e = scene.build_sim().err().unwrap();
    assert_eq!(e.field(), Some("characters[0].clip"), "{e}");
    assert!(e.to_string().contains("not a .bvh file"), "{e}");

    // The clip's skeleton standing still for a second.
    let dir = tempfile::tempdir().unwrap();
    let walk = std::fs::read_to_string(repo_root().join(CLIP)).unwrap();
    let hierarchy = walk.split("MOTION").next().unwrap();
    let channels = 6 + 3 * (hierarchy.matches("JOINT").count());
    let mut standing = format!("{hierarchy}MOTION\nFrames: 61\nFrame Time: 0.016667\n");
    for _ in 0..61 {
        let mut values = vec!["0".to_string(); channels];
        values[1] = "100".into();
        standing.push_str(&values.join(" "));
        standing.push('\n');
    }
    std::fs::write(dir.path().join("standing.bvh"), standing).unwrap();
    scene.base_dir = dir.path().to_path_buf();
    scene.characters[0].clip = Some("standing.bvh".into());
    let e = scene.build_sim().err().unwrap();
    assert!(matches!(e, SceneError::BadFile { .. }), "{e}");
    assert_eq!(e.field(), Some("characters[0].clip"));
    assert!(e.to_string().contains("not a walk clip"), "{e}");
}

#[test]
fn the_clip_walk_is_deterministic_and_changes_the_world() {
    let scene = with_clip("snow-flat");
    let steps = 90;
    let reference = softwalk_tests::world_hash_after(&scene, steps, false, 1);
    assert_eq!(
        softwalk_tests::world_hash_after(&scene, steps, true, 2),
        reference,
        "rendering and two threads leave the world as it is"
    );
    let mut plain = scene.clone();
    plain.characters[0].clip = None;
    assert_ne!(
        softwalk_tests::world_hash_after(&plain, steps, false, 1),
        reference,
        "the clip sets the gait"
    );
}
