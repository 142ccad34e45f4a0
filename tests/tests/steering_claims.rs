//! Steering and the lateral balance axis (issue 24): a character whose path
//! comes from a desired velocity starts, stops, curves tightly, turns on
//! the spot and steps backward without sliding a planted foot, and leans
//! into turns by `atan(v² / (g r))` while staying upright on straight paths.

use std::path::Path;

use glam::{Vec2, Vec3};
use softwalk_app::inputs::InputScript;
use softwalk_app::paper::gait_quality::GaitQuality;
use softwalk_app::paper::recorded_run::{RecordedRun, record_run_with_inputs};
use softwalk_app::scene::Scene;
use softwalk_systems::character::{
    Character, CharacterBody, CharacterDesc, GaitModifiers, GaitParams, Joint, MAX_BACKWARD_ASLANT,
    Steering, SteeringSettings, WalkPath, brake_modifiers, step_character,
};
use softwalk_systems::ground::FlatGround;
use softwalk_systems::sim::WalkerMetrics;
use softwalk_tests::stop_figures::{
    SLIDE_GOAL_M, SoleSample, StopFigures, sole_samples, worst_slide,
};

const DT: f32 = 1.0 / 60.0;

/// A steered adult standing at the origin facing +Z on flat ground.
struct Steered {
    character: Character,
    steering: Steering,
    path: WalkPath,
    ground: FlatGround,
}

impl Steered {
    fn new() -> Self {
        let ground = FlatGround(0.0);
        let path = WalkPath::straight(Vec3::ZERO, Vec3::Z, 1.0).unwrap();
        let character = Character::new(CharacterDesc::adult(), &path, &ground).unwrap();
        Steered {
            character,
            steering: Steering::new(),
            path,
            ground,
        }
    }

    /// Steps `seconds` wanting `velocity`; returns each step's heel and toe
    /// positions with whether each foot was in contact.
    fn walk(&mut self, velocity: Vec2, seconds: f32) -> Vec<SoleSample> {
        self.steering.set_desired_velocity(velocity).unwrap();
        let steps = (seconds / DT).round() as usize;
        (0..steps)
            .map(|_| {
                let c = &mut self.character;
                let (steering, path) = (&mut self.steering, &mut self.path);
                let base = GaitModifiers::default();
                c.modifiers = brake_modifiers(steering, &c.gait, &c.body, path, base, DT);
                step_character(c, &self.path, &self.ground, DT);
                let m = &c.metrics;
                [0, 1].map(|k| (m.contact[k], [m.soles[k].heel, m.soles[k].toe]))
            })
            .collect()
    }
}

#[test]
fn turning_on_the_spot_keeps_planted_feet_still() {
    // A wish 110° round (past `pivot_start`, short of stepping back), and
    // one straight behind faster than `backward_max_speed`, turn on the spot
    // before walking off.
    let fastest_back = SteeringSettings::default().backward_max_speed;
    for (degrees, speed) in [(110f32, 1.2), (180.0, fastest_back + 0.3)] {
        let mut s = Steered::new();
        let (sin, cos) = degrees.to_radians().sin_cos();
        let samples = s.walk(Vec2::new(sin, cos) * speed, 3.0);
        let slide = worst_slide(&samples);
        let heading = s.character.gait.pelvis.heading;
        let travelled = s.character.gait.pelvis.position.length();
        println!(
            "turn on the spot by {degrees}° at {speed} m/s: slide {:.2} cm, heading {heading:?}, \
             pelvis moved {travelled:.2} m",
            slide * 100.0
        );
        assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
        assert!(
            (heading - Vec2::new(sin, cos)).length() < 0.1,
            "did not turn round: {heading:?}"
        );
    }
}

#[test]
fn tight_curves_start_and_stop_keep_planted_feet_still() {
    let mut s = Steered::new();
    let mut samples = s.walk(Vec2::new(0.0, 1.0), 2.0);
    let started = s.character.gait.pelvis.position.y;
    samples.extend(s.walk(Vec2::new(1.0, 0.0), 2.0));
    samples.extend(s.walk(Vec2::new(0.0, -1.0), 2.5));
    samples.extend(s.walk(Vec2::ZERO, 2.0));
    let slide = worst_slide(&samples);
    let gait = &s.character.gait;
    println!(
        "curves and stop: slide {:.2} cm, stopped {}, heading {:?}",
        slide * 100.0,
        gait.stopped,
        gait.pelvis.heading
    );
    assert!(started > 1.0, "did not start: {started}");
    assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
    assert!(gait.stopped && gait.double_support(), "did not stop");
    let before = gait.pelvis.position;
    s.walk(Vec2::ZERO, 1.0);
    assert_eq!(s.character.gait.pelvis.position, before, "drifts at rest");
    s.walk(Vec2::new(0.0, -1.0), 1.0);
    let moved = (s.character.gait.pelvis.position - before).length();
    assert!(moved > 0.5, "did not start again: {moved} m");
}

/// Steps of the backward walk on sand (8 s at 60 Hz).
const BACK_STEPS: u64 = 480;
/// The step at which the wish behind starts: the walker stops (its last
/// step closing at the walk's cadence), then steps back until step 280.
const WISH_BEHIND: usize = 120;
/// The step by which stepping back has ended.
const STEPPED_BACK: usize = 300;

/// A recorded walk on sand-flat from `tests/inputs/<name>`, `steps` long:
/// the run, each step's soles against the ground under them, and whether
/// the toes always stayed ahead of the heels along +x (facing forward).
fn recorded_on_sand(name: &str, steps: u64) -> (RecordedRun, Vec<SoleSample>, bool) {
    let scene = Scene::builtin("sand-flat").unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("inputs")
        .join(name);
    let inputs = InputScript::load(&file).unwrap();
    let run = record_run_with_inputs(&scene, steps, Some(&inputs)).unwrap();
    let walked = &run.walkers[0];
    let samples = sole_samples(walked);
    let facing_forward = walked
        .iter()
        .all(|m| m.character.soles.iter().all(|s| s.toe.x > s.heel.x));
    (run, samples, facing_forward)
}

/// Feet landing over `walked` (a foot in contact that was not the step before).
fn landings(walked: &[WalkerMetrics]) -> usize {
    (1..walked.len())
        .flat_map(|s| [0, 1].map(|k| (s, k)))
        .filter(|&(s, k)| walked[s].character.contact[k] && !walked[s - 1].character.contact[k])
        .count()
}

#[test]
fn a_slow_wish_behind_steps_back_on_sand_facing_forward() {
    let (run, samples, facing_forward) = recorded_on_sand("steps_back_sand.toml", BACK_STEPS);
    let walked = &run.walkers[0];
    let first_back = (WISH_BEHIND..STEPPED_BACK)
        .find(|&s| walked[s].velocity.x < 0.0)
        .expect("never stepped back");
    let back = &walked[first_back..STEPPED_BACK];
    let landings = landings(back);
    let moved = back[back.len() - 1].character.com - back[0].character.com;
    let slide = worst_slide(&samples);
    let whole = run.quality(0);
    let stepping_back = GaitQuality::measure(back, run.dt);
    println!(
        "steps back on sand: {landings} steps, moved {:.2} m along x, slide {:.2} cm\n\
         gait quality stepping back: {stepping_back}\nwhole walk: {whole}",
        moved.x,
        slide * 100.0
    );
    assert!((3..=4).contains(&landings), "{landings} steps back");
    assert!(moved.x < -0.8 && moved.z.abs() < 0.05, "moved {moved}");
    assert!(facing_forward, "the feet turned round");
    assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
    assert!(stepping_back.passes(), "{:?}", stepping_back.failures());
    assert!(whole.passes(), "{:?}", whole.failures());
}

/// Steps of the walk stepping back aslant and hurried (9 s at 60 Hz).
const ASLANT_STEPS: u64 = 540;
/// Its steps stepping back aslant (S with A from step 120, after a stop).
const ASLANT: std::ops::Range<usize> = 180..280;
/// Its steps stepping back hurried (Shift with S from step 340).
const HURRIED: std::ops::Range<usize> = 360..460;

#[test]
fn back_with_a_side_key_steps_back_aslant_and_shift_hurries_in_short_steps() {
    let (run, samples, facing_forward) =
        recorded_on_sand("steps_back_aslant_sand.toml", ASLANT_STEPS);
    let walked = &run.walkers[0];
    let moved = |range: std::ops::Range<usize>| {
        walked[range.end].character.com - walked[range.start].character.com
    };
    let (aslant, hurried) = (moved(ASLANT), moved(HURRIED));
    let seconds = |range: std::ops::Range<usize>| range.len() as f32 * run.dt;
    let (slow, fast) = (
        Vec2::new(aslant.x, aslant.z).length() / seconds(ASLANT),
        -hurried.x / seconds(HURRIED),
    );
    let stride = |range: std::ops::Range<usize>| {
        2.0 * moved(range.clone()).x.abs() / landings(&walked[range]).max(1) as f32
    };
    let hurried_steps = landings(&walked[HURRIED]);
    let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
    let forward = GaitParams::new(&body, &GaitModifiers::default()).stride;
    let stride = stride(HURRIED);
    let slide = worst_slide(&samples);
    let whole = run.quality(0);
    let off_behind = aslant.z.atan2(-aslant.x).to_degrees();
    let most = MAX_BACKWARD_ASLANT.to_degrees();
    println!(
        "aslant: moved ({:.2}, {:.2}) m ({off_behind:.1}° off behind) at {slow:.2} m/s; hurried: {:.2} m at {fast:.2} m/s, \
         {hurried_steps} steps (stride {stride:.2} m, forward {forward:.2} m); slide {:.2} cm\n\
         whole walk: {whole}",
        aslant.x,
        aslant.z,
        hurried.x,
        slide * 100.0
    );
    assert!(aslant.x < -0.3, "did not step back: {aslant}");
    assert!(
        (-most - 5.0..=-most + 5.0).contains(&off_behind),
        "{off_behind}° off straight behind, not aslant to the left: {aslant}"
    );
    assert!(
        fast > 1.3 * slow,
        "Shift did not hurry: {fast} against {slow} m/s"
    );
    let top = SteeringSettings::default().backward_top_speed;
    assert!(fast <= top + 0.05, "faster than the top speed: {fast} m/s");
    assert!(stride < 0.85 * forward, "long steps back: {stride} m");
    assert!(facing_forward, "the feet turned round");
    assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
    assert!(whole.passes(), "{:?}", whole.failures());
}

/// Steps of the walk that stops on sand (5 s at 60 Hz).
const STOP_STEPS: u64 = 300;
/// The step before which every key is released.
const STOP_AT: usize = 150;
/// The slowest the walker moves before it rests, m/s (the braking floor).
const LAST_SPEED_M_S: f32 = 0.3;
/// Feet at rest no further apart than this along the walk have closed
/// side by side, metres (a foot is about 0.26 m long).
const CLOSED_FEET_M: f32 = 0.1;

#[test]
fn a_stop_brakes_at_once_leans_back_and_closes_the_feet_side_by_side() {
    let (run, samples, _) = recorded_on_sand("stop_sand.toml", STOP_STEPS);
    let walked = &run.walkers[0];
    let speed: Vec<f32> = walked.iter().map(|m| m.velocity.length()).collect();
    let rest = STOP_AT + speed[STOP_AT..].iter().position(|&v| v == 0.0).unwrap();
    let profile: Vec<String> = (STOP_AT - 1..=rest)
        .step_by(3)
        .map(|s| format!("{:.2}", speed[s]))
        .collect();
    let tilt = |s: usize| walked[s].character.tilt.to_degrees();
    let walking_tilt = (STOP_AT - 60..STOP_AT).map(tilt).sum::<f32>() / 60.0;
    let braking_tilt = (STOP_AT..rest).map(tilt).fold(f32::INFINITY, f32::min);
    let travelled = walked[rest].character.com.x - walked[STOP_AT - 1].character.com.x;
    let seconds = (rest + 1 - STOP_AT) as f32 * run.dt;
    let at_rest = &walked[STOP_STEPS as usize - 1].character;
    let feet = at_rest
        .soles
        .map(|f| 0.5 * (f.heel.x + f.toe.x) - at_rest.com.x);
    let slide = worst_slide(&samples);
    let whole = run.quality(0);
    let stop = StopFigures::measure(walked, run.dt, STOP_AT);
    println!(
        "stop on sand: pelvis speed every 3 steps from the key (m/s) {}\n\
         rests after {seconds:.2} s and {travelled:.2} m; tilt {walking_tilt:.2}° walking, \
         {braking_tilt:.2}° at most braking; sole centres {:.2} m and {:.2} m from the COM along x; \
         slide {:.2} cm\nthe stop: {stop}\nwhole walk: {whole}",
        profile.join(" "),
        feet[0],
        feet[1],
        slide * 100.0
    );
    assert!(stop.failures().is_empty(), "{:?}", stop.failures());
    assert!(
        (feet[0] - feet[1]).abs() <= CLOSED_FEET_M,
        "the last step did not close beside the other foot: {feet:?}"
    );
    assert!(speed[STOP_AT] < speed[STOP_AT - 1], "did not slow at once");
    let slowing = speed[STOP_AT - 1..=rest]
        .windows(2)
        .all(|w| w[1] <= w[0] + 1e-4);
    assert!(slowing, "sped up while stopping: {profile:?}");
    assert!(
        speed[rest - 1] <= LAST_SPEED_M_S,
        "halted from {} m/s",
        speed[rest - 1]
    );
    assert!((0.3..=1.2).contains(&seconds), "stopped in {seconds} s");
    assert!(
        braking_tilt < walking_tilt - 2.0,
        "no lean back: {braking_tilt}°"
    );
    assert!(
        feet[0].min(feet[1]) < 0.05 && feet[0].max(feet[1]) > -0.05,
        "the COM rests outside its feet: {feet:?}"
    );
    assert_eq!(at_rest.contact, [true, true], "a foot in the air at rest");
    assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
    assert!(whole.passes(), "{:?}", whole.failures());
}

/// Mean lean of the trunk towards the character's left over the last
/// `settled` seconds of `seconds` walking `path`, at `speed` m/s, in radians:
/// from the pose (pelvis to neck) and from the proxy, and the largest
/// lean from the pose over that time.
fn mean_lean(path: &WalkPath, speed: f32, seconds: f32, settled: f32) -> (f32, f32, f32) {
    let ground = FlatGround(0.0);
    let mut c = Character::new(CharacterDesc::adult(), path, &ground).unwrap();
    let natural = GaitParams::new(&c.body, &GaitModifiers::default()).speed;
    c.modifiers.speed_scale = speed / natural;
    let steps = (seconds / DT).round() as usize;
    let from = steps - (settled / DT).round() as usize;
    let (mut pose_sum, mut proxy_sum, mut largest) = (0.0, 0.0, 0.0f32);
    for step in 0..steps {
        step_character(&mut c, path, &ground, DT);
        if step >= from {
            let j = &c.pose.joints;
            let trunk = j[Joint::Neck as usize] - j[Joint::Pelvis as usize];
            let lean = (-trunk.dot(c.pose.right)).atan2(trunk.y);
            pose_sum += lean;
            largest = largest.max(lean.abs());
            proxy_sum += c.proxy.lean;
        }
    }
    let n = (steps - from) as f32;
    (pose_sum / n, proxy_sum / n, largest)
}

#[test]
fn the_body_leans_into_turns_by_v_squared_over_g_r() {
    let (speed, radius) = (1.3f32, 2.0f32);
    let expected = (speed * speed / (9.81 * radius)).atan();
    for (dir, sign) in [(Vec3::Z, 1.0f32), (Vec3::NEG_Z, -1.0)] {
        // A looped circle turns left; heading -Z from (0,0,0) with the
        // circle mirrored gives the right turn.
        let path = if sign > 0.0 {
            WalkPath::circle(Vec3::ZERO, dir, radius).unwrap()
        } else {
            let arc = softwalk_systems::character::PathSegment::Arc {
                radius,
                angle: -std::f32::consts::TAU,
            };
            WalkPath::new(Vec3::ZERO, dir, vec![arc], true).unwrap()
        };
        let (pose, proxy, _) = mean_lean(&path, speed, 8.0, 4.0);
        println!(
            "turn {}: lean from the pose {:.2}°, proxy {:.2}°, atan(v²/gr) {:.2}°",
            if sign > 0.0 { "left" } else { "right" },
            pose.to_degrees(),
            proxy.to_degrees(),
            (sign * expected).to_degrees()
        );
        for lean in [pose, proxy] {
            assert!(lean * sign > 0.0, "leans out of the turn: {lean}");
            assert!(
                (lean * sign - expected).abs() <= 0.3 * expected,
                "lean {lean} rad against {expected} rad"
            );
        }
    }
    let straight = WalkPath::straight(Vec3::ZERO, Vec3::Z, 20.0).unwrap();
    let (_, proxy, largest) = mean_lean(&straight, speed, 6.0, 5.5);
    println!(
        "straight: largest lean {:.3}° (pose), mean {:.3}° (proxy)",
        largest.to_degrees(),
        proxy.to_degrees()
    );
    assert!(largest.to_degrees() <= 0.5 && proxy.abs().to_degrees() <= 0.5);
}
