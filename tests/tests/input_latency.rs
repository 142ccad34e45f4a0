//! Key-to-visible latency of the live viewer (issue 24): how many steps after
//! an input the drawn frame changes. Two copies of one world run side by
//! side; one gets the input, and both are drawn from the same camera at
//! 960 × 540 after every step until their pictures differ.
//!
//! `softwalk view` reads the keys at the start of a frame, applies them
//! before that frame's steps and draws after them, so a key pressed during
//! one frame is drawn at the end of the next: the latency in frames is one
//! (waiting for the next frame to start) plus one frame per step needed,
//! with one 60 Hz step per frame at 60 fps.

use engine::ecs::Entity;
use engine::schedule::App;
use glam::Vec3;
use image::RgbaImage;
use softwalk_app::inputs::{InputAction, InputEvent, InputScript, InputSession};
use softwalk_app::scene::Scene;
use softwalk_app::view::scene_view;
use softwalk_systems::sim::WalkerMetrics;

/// The latency goal, frames.
const LATENCY_GOAL_FRAMES: u64 = 2;
/// A picture has changed when this many pixels differ visibly.
const CHANGED_PIXELS: usize = 10;
/// A pixel differs visibly when a channel moves by more than this.
const CHANNEL_STEP: i16 = 8;
/// Steps tried before giving up.
const MOST_STEPS: u64 = 30;

/// One copy of the steered world.
struct Twin<'a> {
    app: App,
    walkers: Vec<Entity>,
    session: InputSession<'a>,
}

impl<'a> Twin<'a> {
    fn new(scene: &Scene, script: &'a InputScript) -> Self {
        let (mut app, walkers) = scene.build_sim().unwrap();
        let session = InputSession::start(script, scene, &mut app, &walkers).unwrap();
        Twin {
            app,
            walkers,
            session,
        }
    }

    fn step(&mut self, scene: &Scene, step: u64) {
        let (app, walkers) = (&mut self.app, &mut self.walkers);
        self.session.before_step(step, scene, app, walkers).unwrap();
        softwalk_systems::sim::step(&mut self.app).unwrap();
    }

    fn draw(&self, scene: &Scene, eye: Vec3, target: Vec3) -> RgbaImage {
        let mut view = scene_view(scene, &self.app.world, &self.walkers, 960, 540, 1).unwrap();
        view.look_at(eye, target);
        view.render(&self.app.world, scene.sim.dt).unwrap()
    }

    fn com(&self) -> Vec3 {
        let m = self
            .app
            .world
            .get::<WalkerMetrics>(self.walkers[0])
            .unwrap();
        m.character.com
    }
}

fn changed_pixels(a: &RgbaImage, b: &RgbaImage) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| (i16::from(p[c]) - i16::from(q[c])).abs() > CHANNEL_STEP))
        .count()
}

/// Steps after `action` (applied after `warm` steps of `before`) until the
/// picture differs from the world without it, and how many pixels differ then.
fn steps_to_visible(before: Vec<InputEvent>, warm: u64, action: InputAction) -> (u64, usize) {
    // Overlays off: the walker and the ground themselves must change.
    let mut scene = Scene::builtin("sand-flat").unwrap();
    scene.render.overlays = false;
    let script = InputScript {
        character: None,
        events: before,
    };
    let mut twins = [Twin::new(&scene, &script), Twin::new(&scene, &script)];
    for step in 0..warm {
        twins.iter_mut().for_each(|t| t.step(&scene, step));
    }
    let target = twins[0].com();
    let eye = target + softwalk_app::live::DEFAULT_CAMERA_OFFSET;
    let t = &mut twins[1];
    let (app, walkers) = (&mut t.app, &mut t.walkers);
    t.session.apply(&action, &scene, app, walkers).unwrap();
    for k in 1..=MOST_STEPS {
        twins.iter_mut().for_each(|t| t.step(&scene, warm + k));
        let [a, b] = [0, 1].map(|i| twins[i].draw(&scene, eye, target));
        let changed = changed_pixels(&a, &b);
        if changed >= CHANGED_PIXELS {
            return (k, changed);
        }
    }
    panic!("{action:?} made no visible change in {MOST_STEPS} steps");
}

fn walking() -> Vec<InputEvent> {
    vec![InputEvent {
        step: 0,
        action: InputAction::Velocity([1.2, 0.0]),
    }]
}

/// Walking off along +x, then every key released at step 60.
fn stopped() -> Vec<InputEvent> {
    let mut events = walking();
    events.push(InputEvent {
        step: 60,
        action: InputAction::Velocity([0.0, 0.0]),
    });
    events
}

/// Frames from a key to its first visible change, for each case.
fn latencies(cases: Vec<(&str, Vec<InputEvent>, u64, InputAction)>) -> u64 {
    let mut worst = 0;
    for (name, before, warm, action) in cases {
        let (steps, pixels) = steps_to_visible(before, warm, action);
        let frames = 1 + steps;
        println!(
            "{name}: visible after {steps} step(s) ({pixels} pixels changed): \
             at most {frames} frames at 60 fps"
        );
        worst = worst.max(frames);
    }
    worst
}

#[test]
fn starting_turning_stepping_back_stopping_and_painting_show_within_two_frames() {
    // The walker starts facing +x; the camera stands behind its left.
    let worst = latencies(vec![
        ("W from rest", vec![], 60, InputAction::Velocity([1.2, 0.0])),
        (
            "S from rest",
            vec![],
            60,
            InputAction::Velocity([-1.2, 0.0]),
        ),
        (
            "turn while walking",
            walking(),
            120,
            InputAction::Velocity([0.0, 1.2]),
        ),
        // A stop brakes from the first step (the walker slows, its arms
        // swing less, its trunk leans back) to where it comes to rest.
        (
            "stop while walking",
            walking(),
            120,
            InputAction::Velocity([0.0, 0.0]),
        ),
        (
            "stop mid-stride",
            walking(),
            140,
            InputAction::Velocity([0.0, 0.0]),
        ),
        (
            "S while walking",
            walking(),
            120,
            InputAction::Velocity([-1.2, 0.0]),
        ),
        (
            "W after a stop",
            stopped(),
            180,
            InputAction::Velocity([1.2, 0.0]),
        ),
        ("brush", walking(), 120, InputAction::Brush("snow".into())),
    ]);
    println!("key-to-visible latency: at most {worst} frames");
    assert!(worst <= LATENCY_GOAL_FRAMES, "{worst} frames");
}
