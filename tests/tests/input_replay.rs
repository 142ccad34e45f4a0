//! Recorded inputs replay headless (issue 24): a steered walk with turns, a
//! stop and a material change, one stepping back on sand and one planting
//! grass ahead, end in known worlds, the same with or without frames, and
//! their gait meets the gait-quality goals.

use std::path::Path;

use softwalk_app::inputs::InputScript;
use softwalk_app::paper::recorded_run::{RecordedRun, record_run_with_inputs};
use softwalk_app::runner::{self, RunObserver, RunOptions};
use softwalk_app::scene::Scene;

/// Steps of the recorded walk (10 s at 60 Hz).
const STEPS: u64 = 600;
/// The world the recorded walk ends in. Changes only when the simulation
/// is meant to change: update it deliberately, and say so.
const REPLAY_HASH: u64 = 0x2afb_1628_19ae_e485;
/// Steps of the recorded walk stepping back on sand (8 s at 60 Hz).
const BACK_STEPS: u64 = 480;
/// The world the walk stepping back ends in (same rule as [`REPLAY_HASH`]).
const BACK_HASH: u64 = 0x23c6_8f64_c4be_0a6a;

fn script() -> InputScript {
    load("turns_stop_snow.toml")
}

fn load(name: &str) -> InputScript {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("inputs")
        .join(name);
    InputScript::load(&path).unwrap()
}

fn scene() -> Scene {
    Scene::builtin("default").unwrap()
}

/// Replays `inputs` on `scene` for `steps` twice: the same world both
/// times, its gait meeting the gait-quality goals. Returns the run and its hash.
fn replay_twice(scene: &Scene, inputs: &InputScript, steps: u64) -> (RecordedRun, u64) {
    let run = record_run_with_inputs(scene, steps, Some(inputs)).unwrap();
    let again = record_run_with_inputs(scene, steps, Some(inputs)).unwrap();
    let hash = run.summary.world_hash.unwrap();
    println!("{}: replay hash {hash:#018x}", scene.name);
    assert_eq!(again.summary.world_hash, Some(hash), "replays differ");
    let quality = run.quality(0);
    println!("gait quality: {quality}");
    assert!(quality.passes(), "{:?}", quality.failures());
    (run, hash)
}

#[test]
fn a_recorded_walk_replays_to_a_known_world_meeting_the_gait_goals() {
    let (run, hash) = replay_twice(&scene(), &script(), STEPS);
    let walked = &run.walkers[0];
    let stopped = walked[345..380].iter().all(|m| m.velocity.length() == 0.0);
    assert!(stopped, "the walker did not stop");
    let standing = walked[345..380]
        .iter()
        .all(|m| m.character.contact == [true, true]);
    assert!(standing, "a foot in the air at rest");
    let last = walked.last().unwrap().character.com;
    assert!(
        last.z < 2.9 && last.x > 6.0,
        "the curves did not take it to -z and on along +x: {last}"
    );
    assert_eq!(hash, REPLAY_HASH, "the replayed world changed");
}

#[test]
fn a_recorded_walk_stepping_back_replays_to_a_known_world() {
    let scene = Scene::builtin("sand-flat").unwrap();
    let (run, hash) = replay_twice(&scene, &load("steps_back_sand.toml"), BACK_STEPS);
    let walked = &run.walkers[0];
    let backward = walked.iter().filter(|m| m.velocity.x < -0.2).count();
    assert!(backward > 60, "stepped back for {backward} steps only");
    assert_eq!(hash, BACK_HASH, "the replayed world changed");
}

/// Steps of the recorded walk stepping back aslant and hurried (9 s at 60 Hz).
const ASLANT_STEPS: u64 = 540;
/// The world the walk stepping back aslant ends in (same rule as [`REPLAY_HASH`]).
const ASLANT_HASH: u64 = 0x4aa7_2055_db2f_4f07;

#[test]
fn a_recorded_walk_stepping_back_aslant_and_hurried_replays_to_a_known_world() {
    let scene = Scene::builtin("sand-flat").unwrap();
    let inputs = load("steps_back_aslant_sand.toml");
    let (run, hash) = replay_twice(&scene, &inputs, ASLANT_STEPS);
    let walked = &run.walkers[0];
    let aslant = walked.iter().filter(|m| m.velocity.z < -0.1).count();
    let hurried = walked.iter().filter(|m| m.velocity.x < -0.7).count();
    assert!(aslant > 60, "stepped back aslant for {aslant} steps only");
    assert!(hurried > 30, "hurried back for {hurried} steps only");
    assert_eq!(hash, ASLANT_HASH, "the replayed world changed");
}

/// Counts frames; draws nothing else.
struct Frames(usize);

impl RunObserver for Frames {
    fn on_frame(&mut self, _: &runner::Frame<'_>) -> Result<(), runner::ObserverError> {
        self.0 += 1;
        Ok(())
    }
}

#[test]
fn replaying_with_frames_ends_in_the_same_world() {
    let stepping_back = Scene::builtin("sand-flat").unwrap();
    for (scene, inputs) in [
        (scene(), script()),
        (stepping_back, load("steps_back_sand.toml")),
    ] {
        let mut options = RunOptions::from_scene(&scene);
        options.steps = 420;
        options.hash = true;
        options.width = 96;
        options.height = 54;
        options.render_every = 10;
        let mut frames = Frames(0);
        let drawn = runner::run_with_inputs(&scene, &options, Some(&inputs), &mut frames).unwrap();
        options.render = false;
        let mut none = Frames(0);
        let headless = runner::run_with_inputs(&scene, &options, Some(&inputs), &mut none).unwrap();
        assert_eq!(frames.0, 42);
        assert_eq!(drawn.world_hash, headless.world_hash, "{}", scene.name);
    }
}

#[test]
fn unknown_brushes_and_characters_are_refused_before_the_first_step() {
    let scene = scene();
    let mut options = RunOptions::from_scene(&scene);
    options.render = false;
    for (text, expected) in [
        (
            "[[event]]\nstep = 40\nbrush = \"lava\"\n",
            "input brush \"lava\" at step 40: unknown material `lava`",
        ),
        (
            "character = \"bob\"\n",
            "input character: the scene has no character \"bob\"",
        ),
    ] {
        let inputs = InputScript::parse(text, Path::new("bad.toml")).unwrap();
        let mut frames = Frames(0);
        let e = runner::run_with_inputs(&scene, &options, Some(&inputs), &mut frames).unwrap_err();
        let line = softwalk_app::cli::error_line(&e);
        assert!(line.contains(expected), "{line}");
    }
}

#[test]
fn the_grass_brush_plants_grass_ahead_that_the_walker_walks_through() {
    let inputs = load("grass_ahead_sand.toml");
    let scene = Scene::builtin("sand-flat").unwrap();
    let (run, _) = replay_twice(&scene, &inputs, 300);
    let walked = &run.walkers[0];
    assert!(
        walked[..90].iter().all(|m| m.grass_height == 0.0),
        "grass before the brush"
    );
    let in_grass = walked[90..].iter().filter(|m| m.grass_height > 0.4).count();
    assert!(in_grass > 30, "the walker met grass in {in_grass} steps");
}
