//! Stops the other tests do not contain, held to the gait goals over the
//! whole stop (closing step included) and to both feet flat within
//! [`FLAT_AFTER_GOAL_S`] of the key: in snow, in 0.9 m grass, up and down a
//! 15° slope, in the middle of a turn, at Froude 0.35, with a 1.0 m and a
//! 1.9 m walker, and stopping twice within a second.

use std::path::Path;

use rayon::prelude::*;
use softwalk_app::inputs::InputScript;
use softwalk_app::paper::recorded_run::record_run_with_inputs;
use softwalk_app::paper::variants::{builtin, checked, with_material, with_slope};
use softwalk_app::scene::Scene;
use softwalk_systems::character::{CharacterBody, CharacterDesc, GaitModifiers, GaitParams};
use softwalk_tests::stop_figures::{
    FLAT_AFTER_GOAL_S, SLIDE_GOAL_M, StopFigures, sole_samples, worst_slide,
};
use softwalk_tests::walker_body;

/// The step before which the (last) stop key is pressed, unless a probe says otherwise.
const STOP_AT: usize = 150;
/// Steps recorded after the last stop key: the stop and more than a second at rest.
const AFTER_STOP: usize = 180;

/// One stop to probe.
struct Probe {
    name: &'static str,
    scene: Scene,
    /// Events (`step`, wished velocity as a multiple of the walker's own
    /// speed, x and z); the last one stops.
    events: Vec<(usize, [f32; 2])>,
}

impl Probe {
    /// A walk along +x on `scene` at the walker's own speed, stopped at [`STOP_AT`].
    fn straight(name: &'static str, scene: Scene) -> Probe {
        Probe {
            name,
            scene,
            events: vec![(0, [1.0, 0.0]), (STOP_AT, [0.0, 0.0])],
        }
    }

    /// The step of the last key, which stops.
    fn key(&self) -> usize {
        self.events.last().map_or(0, |e| e.0)
    }

    /// The input script steering the scene's first character.
    fn inputs(&self) -> InputScript {
        let c = &self.scene.characters[0];
        let body = CharacterBody::new(c.body).unwrap();
        let speed = GaitParams::new(&body, &GaitModifiers::default()).speed;
        let mut text = format!("character = \"{}\"\n", c.name);
        for (step, [x, z]) in &self.events {
            text += &format!(
                "[[event]]\nstep = {step}\nvelocity = [{}, {}]\n",
                x * speed,
                z * speed
            );
        }
        InputScript::parse(&text, Path::new(self.name)).unwrap()
    }
}

/// `scene` with its first walker's body replaced by `body`.
fn with_body(mut scene: Scene, body: CharacterDesc) -> Scene {
    scene.characters[0].body = body;
    checked(scene).unwrap()
}

fn sand() -> Scene {
    builtin("sand-flat").unwrap()
}

/// Every probe.
fn probes() -> Vec<Probe> {
    let mid_turn = Probe {
        name: "mid-turn",
        scene: sand(),
        events: vec![(0, [1.0, 0.0]), (120, [0.7, -0.7]), (140, [0.0, 0.0])],
    };
    let twice = Probe {
        name: "stop, go, stop within 1 s",
        scene: sand(),
        events: vec![
            (0, [1.0, 0.0]),
            (STOP_AT, [0.0, 0.0]),
            (STOP_AT + 25, [1.0, 0.0]),
            (STOP_AT + 55, [0.0, 0.0]),
        ],
    };
    vec![
        Probe::straight("snow", with_material(sand(), "snow")),
        Probe::straight("0.9 m grass", builtin("grass-medium").unwrap()),
        Probe::straight("sand up 15°", checked(with_slope(sand(), 15.0)).unwrap()),
        Probe::straight("sand down 15°", checked(with_slope(sand(), -15.0)).unwrap()),
        mid_turn,
        Probe::straight("Froude 0.35", with_body(sand(), walker_body(1.75, 0.35))),
        Probe::straight("1.0 m walker", with_body(sand(), walker_body(1.0, 0.15))),
        Probe::straight("1.9 m walker", with_body(sand(), walker_body(1.9, 0.15))),
        twice,
    ]
}

#[test]
fn every_probed_stop_closes_flat_and_meets_the_gait_goals() {
    let results: Vec<(String, StopFigures, Vec<String>)> = probes()
        .par_iter()
        .map(|p| {
            let steps = (p.key() + AFTER_STOP) as u64;
            let run = record_run_with_inputs(&p.scene, steps, Some(&p.inputs())).unwrap();
            let stop = StopFigures::measure(&run.walkers[0], run.dt, p.key());
            let mut failures = stop.failures();
            let whole = run.quality(0);
            failures.extend(whole.failures());
            let line = format!("{}: {stop}\n    whole walk: {whole}", p.name);
            (line, stop, failures)
        })
        .collect();
    let mut failed = Vec::new();
    for (line, _, failures) in &results {
        println!("{line}");
        if !failures.is_empty() {
            failed.push(format!("{}: {failures:?}", line.lines().next().unwrap()));
        }
    }
    let slowest = results
        .iter()
        .filter_map(|(_, s, _)| s.flat_after_s)
        .fold(0.0f32, f32::max);
    println!("slowest to both feet flat: {slowest:.2} s (goal ≤ {FLAT_AFTER_GOAL_S} s)");
    assert!(failed.is_empty(), "{failed:#?}");
}

#[test]
fn a_standing_walker_keeps_both_feet_planted_when_the_ground_is_repainted() {
    // Snow painted under the closing step, then mud once at rest: slower
    // materials, whose walk has another stance fraction.
    let text = format!(
        "character = \"walker\"\n\
         [[event]]\nstep = 0\nvelocity = [1.2, 0.0]\n\
         [[event]]\nstep = {STOP_AT}\nvelocity = [0.0, 0.0]\n\
         [[event]]\nstep = 190\nbrush = \"snow\"\n\
         [[event]]\nstep = 240\nbrush = \"mud\"\n"
    );
    let inputs = InputScript::parse(&text, Path::new("repaint.toml")).unwrap();
    let run = record_run_with_inputs(&sand(), 330, Some(&inputs)).unwrap();
    let walked = &run.walkers[0];
    let at_rest = |m: &softwalk_systems::sim::WalkerMetrics| {
        m.velocity.length() == 0.0 && m.character.contact == [true, true]
    };
    let rest = (STOP_AT..walked.len())
        .find(|&s| at_rest(&walked[s]))
        .unwrap();
    let lifted: Vec<usize> = (rest..walked.len())
        .filter(|&s| walked[s].character.contact != [true, true])
        .collect();
    let slide = worst_slide(&sole_samples(&walked[rest..]));
    println!(
        "repainted under a standing walker: at rest from step {rest}, a foot off the ground \
         in {} steps, slide {:.2} cm",
        lifted.len(),
        100.0 * slide
    );
    assert!(rest < 240, "not at rest before the mud: {rest}");
    assert!(lifted.is_empty(), "a foot lifted at steps {lifted:?}");
    assert!(slide <= SLIDE_GOAL_M, "slide {slide} m");
}
