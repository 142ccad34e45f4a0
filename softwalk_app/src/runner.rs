//! The interface between the command line and the simulation.
//!
//! The command line calls [`run`] with a validated [`Scene`], the resolved
//! [`RunOptions`] and a [`RunObserver`] that receives one [`StepRecord`] per
//! character per step, the rendered [`Frame`]s and the end of every step.
//! [`run`] returns a [`RunSummary`].
//!
//! [`run`] builds the world from the scene (`Scene::build_sim`), steps the
//! pipeline of `softwalk_systems::sim`, and draws frames with a
//! [`softwalk_systems::view::WorldView`].

use engine::ecs::{Entity, World};
use engine::geom::HeightGrid;
use engine::schedule::App;
use glam::Vec3Swizzles;
use image::RgbaImage;
use serde::Serialize;
use softwalk_systems::sim::{GroundState, SystemTimings, WalkerMetrics, world_hash};
use softwalk_systems::terrain::Heightfield;
use std::time::Instant;
use thiserror::Error;

use crate::inputs::{InputScript, InputSession, SessionError};
use crate::paper::measure::{LiftOffs, print_depth};
use crate::scene::{Scene, SceneError};
use softwalk_systems::view::ViewError;

use crate::view::scene_view;

/// An error raised by an observer (an output writer); it stops the run.
pub type ObserverError = Box<dyn std::error::Error + Send + Sync>;

/// How to run a scene; resolved from the scene and the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// Number of fixed steps to simulate.
    pub steps: u64,
    /// Fixed time step, seconds.
    pub dt: f64,
    /// Whether to render frames at all.
    pub render: bool,
    /// Frame width, pixels.
    pub width: u32,
    /// Frame height, pixels.
    pub height: u32,
    /// Render every k-th step (k >= 1).
    pub render_every: u32,
    /// Worker threads of the pool the run executes in.
    pub threads: usize,
    /// Whether to compute a hash of the final world ([`RunSummary::world_hash`]).
    pub hash: bool,
}

impl RunOptions {
    /// The scene's own settings: its step count, dt and frame size, rendering on, one thread, no hash.
    pub fn from_scene(scene: &Scene) -> RunOptions {
        RunOptions {
            steps: scene.steps(),
            dt: scene.sim.dt as f64,
            render: true,
            width: scene.render.width,
            height: scene.render.height,
            render_every: scene.render.every,
            threads: 1,
            hash: false,
        }
    }

    /// Simulated time at the end of step `step` (0-based), seconds.
    pub fn time_after(&self, step: u64) -> f64 {
        (step + 1) as f64 * self.dt
    }

    /// True when step `step` (0-based) is rendered.
    pub fn renders_step(&self, step: u64) -> bool {
        self.render && step.is_multiple_of(u64::from(self.render_every.max(1)))
    }
}

/// One metrics row: the state of one character at the end of one step.
/// SI units, angles in radians; index 0 of each pair is the left foot or knee.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRecord {
    /// Step index, from 0.
    pub step: u64,
    /// Simulated time at the end of the step, seconds.
    pub t: f64,
    /// Index of the character in `Scene::characters`.
    pub character: usize,
    /// What the character recorded this step: its own metrics (COM, tilt,
    /// torque, pelvis, feet, contacts, IK targets, knees) plus the platforms
    /// and the grass height under it.
    pub walker: WalkerMetrics,
    /// Volume of the terrain above height 0, cubic metres (shows mass conservation).
    pub terrain_volume: f64,
}

/// A rendered frame.
#[derive(Debug, Clone, Copy)]
pub struct Frame<'a> {
    /// Step the frame shows, from 0.
    pub step: u64,
    /// Simulated time of the frame, seconds.
    pub t: f64,
    /// The pixels (opaque RGBA).
    pub image: &'a RgbaImage,
}

/// Which terrain a [`RunObserver::on_terrain`] call shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TerrainMoment {
    /// Before the first step.
    Initial,
    /// After the last step.
    Final,
}

/// Receives what a run produces, in order: for each step, its records (one per
/// character, in scene order), then its frame if rendered, then the end of the step.
/// Every method defaults to doing nothing. An error stops the run.
pub trait RunObserver: Send {
    /// One character's state at the end of a step.
    fn on_step(&mut self, _record: &StepRecord) -> Result<(), ObserverError> {
        Ok(())
    }

    /// A rendered frame.
    fn on_frame(&mut self, _frame: &Frame<'_>) -> Result<(), ObserverError> {
        Ok(())
    }

    /// The terrain heights before the first step and after the last.
    fn on_terrain(
        &mut self,
        _moment: TerrainMoment,
        _grid: &HeightGrid,
    ) -> Result<(), ObserverError> {
        Ok(())
    }

    /// Step `step` (0-based) is complete; simulated time is now `t` seconds.
    fn on_step_end(&mut self, _step: u64, _t: f64) -> Result<(), ObserverError> {
        Ok(())
    }
}

/// An observer that ignores everything.
impl RunObserver for () {}

/// Sends everything to several observers, in order.
pub struct Observers<'a>(pub Vec<&'a mut dyn RunObserver>);

impl RunObserver for Observers<'_> {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        self.0.iter_mut().try_for_each(|o| o.on_step(record))
    }

    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        self.0.iter_mut().try_for_each(|o| o.on_frame(frame))
    }

    fn on_terrain(
        &mut self,
        moment: TerrainMoment,
        grid: &HeightGrid,
    ) -> Result<(), ObserverError> {
        self.0
            .iter_mut()
            .try_for_each(|o| o.on_terrain(moment, grid))
    }

    fn on_step_end(&mut self, step: u64, t: f64) -> Result<(), ObserverError> {
        self.0.iter_mut().try_for_each(|o| o.on_step_end(step, t))
    }
}

/// Depth statistics of the prints one character left.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct DepthStats {
    /// Number of footprints.
    pub prints: u32,
    /// Mean print depth, metres.
    pub mean_m: f32,
    /// Deepest print, metres.
    pub max_m: f32,
}

/// Time spent in one named system over a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemTiming {
    /// System name (e.g. `carve`).
    pub name: String,
    /// Mean time per step, nanoseconds.
    pub mean_ns: f64,
}

/// What a run reports when it ends.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunSummary {
    /// Steps simulated.
    pub steps: u64,
    /// Simulated time, seconds.
    pub sim_seconds: f64,
    /// Hash of the final world, when [`RunOptions::hash`] asked for it and the simulation computes one.
    pub world_hash: Option<u64>,
    /// Wall-clock time of building the world and the renderer, seconds.
    pub setup_seconds: f64,
    /// Wall-clock time of the steps (simulation, rendering, observers), seconds.
    pub stepping_seconds: f64,
    /// Print depths per character (scene order); empty when not measured.
    pub print_depth: Vec<DepthStats>,
    /// Per-system costs, in schedule order; empty when not measured.
    pub timings: Vec<SystemTiming>,
}

/// The simulation failed.
#[derive(Debug, Error)]
pub enum SimError {
    /// An observer (output writer) failed.
    #[error("writing the run's output failed")]
    Observer(#[source] ObserverError),
    /// The scene could not be turned into a world.
    #[error("cannot set up the scene")]
    Setup(#[source] SceneError),
    /// A step of the simulation failed.
    #[error("the simulation failed")]
    Step(#[source] softwalk_systems::sim::SimError),
    /// A frame could not be drawn.
    #[error("rendering failed")]
    View(#[source] ViewError),
    /// The recorded inputs could not be applied.
    #[error("replaying the inputs failed")]
    Inputs(#[source] Box<SessionError>),
}

/// Runs `scene` for `options.steps` fixed steps, reporting to `observer`:
/// every step's records (one per character, scene order), a frame every
/// `render_every` steps when rendering, the terrain before and after, and the
/// end of each step. Rendering reads the world and never changes it, so a run
/// with frames and one without end in the same world (same hash).
pub fn run(
    scene: &Scene,
    options: &RunOptions,
    observer: &mut dyn RunObserver,
) -> Result<RunSummary, SimError> {
    run_with_inputs(scene, options, None, observer)
}

/// [`run`], with `inputs` (when given) steering one character: each step's
/// events are applied before it, so a recorded session replays to the same
/// world and frames.
pub fn run_with_inputs(
    scene: &Scene,
    options: &RunOptions,
    inputs: Option<&InputScript>,
    observer: &mut dyn RunObserver,
) -> Result<RunSummary, SimError> {
    let setup = Instant::now();
    let (mut app, mut walkers) = scene.build_sim().map_err(SimError::Setup)?;
    let mut session = match inputs {
        Some(script) => Some(
            InputSession::start(script, scene, &mut app, &walkers)
                .map_err(|e| SimError::Inputs(Box::new(e.into())))?,
        ),
        None => None,
    };
    with_terrain(&app.world, |t| {
        observer.on_terrain(TerrainMoment::Initial, t.initial())
    })
    .map_err(SimError::Observer)?;
    let new_view = |app: &App, walkers: &[Entity]| {
        scene_view(
            scene,
            &app.world,
            walkers,
            options.width,
            options.height,
            options.threads,
        )
        .map_err(SimError::View)
    };
    let mut view = match options.render {
        true => Some(new_view(&app, &walkers)?),
        false => None,
    };
    let mut prints = PrintTracker::new(walkers.len());
    let mut last_frame_t = 0.0;
    let setup_seconds = setup.elapsed().as_secs_f64();
    let stepping = Instant::now();
    for step in 0..options.steps {
        if let Some(session) = session.as_mut()
            && session
                .before_step(step, scene, &mut app, &mut walkers)
                .map_err(|e| SimError::Inputs(Box::new(e)))?
            && let Some(view) = view.as_mut()
        {
            *view = new_view(&app, &walkers)?;
        }
        softwalk_systems::sim::step(&mut app).map_err(SimError::Step)?;
        let t = options.time_after(step);
        report_step(&app.world, &walkers, &mut prints, observer, step, t)?;
        if let Some(view) = view.as_mut()
            && options.renders_step(step)
        {
            let image = view
                .render(&app.world, (t - last_frame_t) as f32)
                .map_err(SimError::View)?;
            last_frame_t = t;
            observer
                .on_frame(&Frame {
                    step,
                    t,
                    image: &image,
                })
                .map_err(SimError::Observer)?;
        }
        observer.on_step_end(step, t).map_err(SimError::Observer)?;
    }
    let stepping_seconds = stepping.elapsed().as_secs_f64();
    let print_depth = with_terrain(&app.world, |t| {
        observer.on_terrain(TerrainMoment::Final, t.grid())?;
        Ok(prints.depths(t.initial(), t.grid()))
    })
    .map_err(SimError::Observer)?;
    Ok(RunSummary {
        steps: options.steps,
        sim_seconds: options.steps as f64 * options.dt,
        world_hash: options.hash.then(|| world_hash(&app.world)),
        setup_seconds,
        stepping_seconds,
        print_depth,
        timings: system_timings(&app.world),
    })
}

/// Reports each walker's metrics after `step` (ending at `t` seconds) to
/// `observer`, in scene order, and follows their prints.
fn report_step(
    world: &World,
    walkers: &[Entity],
    prints: &mut PrintTracker,
    observer: &mut dyn RunObserver,
    step: u64,
    t: f64,
) -> Result<(), SimError> {
    let volume = world.resource::<GroundState>().volume();
    for (character, &entity) in walkers.iter().enumerate() {
        let Ok(m) = world.get::<WalkerMetrics>(entity) else {
            continue;
        };
        prints.observe(character, &m);
        observer
            .on_step(&StepRecord {
                step,
                t,
                character,
                walker: *m,
                terrain_volume: volume,
            })
            .map_err(SimError::Observer)?;
    }
    Ok(())
}

/// The mean cost of each system so far, in schedule order; empty when the
/// world does not measure them.
fn system_timings(world: &World) -> Vec<SystemTiming> {
    world
        .get_resource::<SystemTimings>()
        .map(|t| {
            t.means()
                .into_iter()
                .map(|(name, mean_ns)| SystemTiming {
                    name: name.to_string(),
                    mean_ns,
                })
                .collect()
        })
        .unwrap_or_default()
}

/// Runs `f` with the terrain of a world built by [`Scene::build_sim`].
fn with_terrain<T>(world: &World, f: impl FnOnce(&Heightfield) -> T) -> T {
    let ground = world
        .get_resource::<GroundState>()
        .expect("build_sim always adds a terrain");
    f(ground.terrain())
}

/// A copy of the terrain's heights.
pub fn terrain_grid(world: &World) -> HeightGrid {
    with_terrain(world, |t| t.grid().clone())
}

/// Where each character's feet lifted off (the prints they left), to measure print depths at the end.
struct PrintTracker(Vec<LiftOffs>);

impl PrintTracker {
    fn new(characters: usize) -> Self {
        PrintTracker(vec![LiftOffs::default(); characters])
    }

    fn observe(&mut self, character: usize, m: &WalkerMetrics) {
        self.0[character].observe(&m.character);
    }

    /// Depth of each print: the height there before the run minus the lowest height near it after.
    fn depths(&self, before: &HeightGrid, after: &HeightGrid) -> Vec<DepthStats> {
        self.0
            .iter()
            .map(|feet| {
                let depths: Vec<f32> = feet
                    .prints
                    .iter()
                    .filter_map(|p| print_depth(before, after, p.xz()))
                    .collect();
                DepthStats {
                    prints: depths.len() as u32,
                    mean_m: if depths.is_empty() {
                        0.0
                    } else {
                        depths.iter().sum::<f32>() / depths.len() as f32
                    },
                    max_m: depths.iter().copied().fold(0.0, f32::max),
                }
            })
            .collect()
    }
}

/// Records for the output writers' tests.
#[cfg(test)]
pub(crate) mod test_records {
    use glam::Vec3;
    use softwalk_systems::character::CharacterMetrics;
    use softwalk_systems::foot::FootSole;
    use softwalk_systems::sim::{SoleGround, WalkerMetrics};

    /// A character standing at the origin on flat bare ground; tests adjust
    /// the fields they check with struct update syntax.
    pub(crate) fn standing() -> WalkerMetrics {
        let sole = |x: f32| FootSole {
            heel: Vec3::new(x, 0.0, -0.1),
            toe: Vec3::new(x, 0.0, 0.15),
            width: 0.1,
        };
        WalkerMetrics {
            character: CharacterMetrics {
                com: Vec3::new(0.0, 0.9, 0.0),
                tilt: 0.0,
                tilt_rate: 0.0,
                torque: 0.0,
                pelvis_y: 0.95,
                feet: [Vec3::new(-0.1, 0.0, 0.0), Vec3::new(0.1, 0.0, 0.0)],
                soles: [sole(-0.1), sole(0.1)],
                contact: [true; 2],
                pressing: [true; 2],
                planted: [true; 2],
                ik_target_y: [0.0; 2],
                knee_flexion: [0.0; 2],
                ground_slope: 0.0,
            },
            platform_y: [None; 2],
            grass_height: 0.0,
            ground_y: 0.0,
            velocity: Vec3::ZERO,
            sole_ground: [SoleGround::default(); 2],
            path_distance: 0.0,
            path_finished: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stand_in_advances_time_and_reports_every_step() {
        struct Steps(Vec<(u64, f64)>);
        impl RunObserver for Steps {
            fn on_step_end(&mut self, step: u64, t: f64) -> Result<(), ObserverError> {
                self.0.push((step, t));
                Ok(())
            }
        }
        let scene = Scene::builtin("sand-flat").unwrap();
        let mut options = RunOptions::from_scene(&scene);
        options.steps = 3;
        options.dt = 0.5;
        let mut seen = Steps(Vec::new());
        let summary = run(&scene, &options, &mut seen).unwrap();
        assert_eq!(seen.0, [(0, 0.5), (1, 1.0), (2, 1.5)]);
        assert_eq!((summary.steps, summary.sim_seconds), (3, 1.5));
    }

    #[test]
    fn observer_errors_stop_the_run() {
        struct Fails;
        impl RunObserver for Fails {
            fn on_step_end(&mut self, _: u64, _: f64) -> Result<(), ObserverError> {
                Err("disk full".into())
            }
        }
        let scene = Scene::builtin("sand-flat").unwrap();
        let e = run(&scene, &RunOptions::from_scene(&scene), &mut Fails).unwrap_err();
        assert!(matches!(e, SimError::Observer(_)));
    }

    #[test]
    fn render_cadence_follows_every() {
        let scene = Scene::builtin("sand-flat").unwrap();
        let mut options = RunOptions::from_scene(&scene);
        options.render_every = 3;
        let rendered: Vec<u64> = (0..7).filter(|s| options.renders_step(*s)).collect();
        assert_eq!(rendered, [0, 3, 6]);
        options.render = false;
        assert!(!options.renders_step(0));
    }
}
