//! `softwalk view`: the live simulation in a window, steered with the keyboard.
//!
//! The simulation runs at its fixed step ([`FixedStepClock`]); each display
//! frame draws the latest state with a [`WorldView`]. Every input is applied
//! between steps and recorded with the number of the step it precedes, so
//! `softwalk run --inputs` replays a session to the same world.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use engine::ecs::Entity;
use engine::schedule::App;
use glam::{Vec2, Vec3};
use image::{Rgba, RgbaImage};
use minifb::{Key, KeyRepeat, MouseButton, MouseMode, Window, WindowOptions};
use softwalk_systems::character::{Gait, RigidProxy};
use softwalk_systems::sim::{GroundState, WalkerMetrics};
use softwalk_systems::view::{OverlayLayers, WorldView};

use super::scene_and_options;
use crate::cli::{CliError, ViewArgs};
use crate::inputs::{InputAction, InputEvent, InputScript, InputSession};
use crate::live::{
    DEFAULT_CAMERA_OFFSET, FixedStepClock, Held, Hud, HudFigures, OrbitCamera, RUN_FACTOR,
    desired_velocity, next_brush,
};
use crate::runner::SimError;
use crate::scene::{CameraMode, Scene};
use crate::view::scene_view;

/// Size of the heads-up text, pixels.
const HUD_TEXT_PX: f32 = 15.0;

/// Opens the window and runs the live simulation until it is closed (Esc),
/// the step limit or `--screenshot-after` is reached; writes `--record`.
pub fn view(args: &ViewArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (scene, options) = scene_and_options(&args.scene)?;
    let script = match &args.inputs {
        Some(path) => InputScript::load(path)?,
        None => InputScript::default(),
    };
    let mut window = open_window(args)?;
    let asked = args.scene.steps.is_some() || args.scene.seconds.is_some();
    let limit = [asked.then_some(options.steps), args.screenshot_after]
        .into_iter()
        .flatten()
        .min();
    let mut live = Live::start(&scene, &script, args, options.threads)?;
    let started = Instant::now();
    while window.is_open() && !window.is_key_down(Key::Escape) {
        if limit.is_some_and(|n| live.step >= n) {
            break;
        }
        live.frame(&mut window, limit)?;
    }
    if let Some(n) = args.screenshot_after
        && live.step >= n
    {
        live.orbit.snap(live.com());
        let image = live.draw()?;
        engine::output::save_png(&args.screenshot, &image).map_err(output)?;
    }
    if let Some(path) = &args.record {
        let text = live.recording(&script).to_toml();
        engine::io::write_bytes_atomic(path, text.as_bytes())?;
    }
    let seconds = started.elapsed().as_secs_f64();
    let line = format!(
        "viewer: {} frames in {seconds:.1} s ({:.1} fps; drawing {:.1} ms a frame), {} steps ({:.3} ms each), {} steps dropped behind real time\nworld hash: {:016x}\n",
        live.frames,
        live.frames as f64 / seconds.max(1.0e-9),
        live.hud.draw_ms(),
        live.step,
        live.hud.step_ms(),
        live.clock.dropped,
        softwalk_systems::sim::world_hash(&live.app.world)
    );
    out.write_all(line.as_bytes()).map_err(CliError::Stdout)
}

/// A window of `--width` × `--height`, or a one-line reason why not.
fn open_window(args: &ViewArgs) -> Result<Window, CliError> {
    if std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        return Err(CliError::NoWindow {
            reason: "no X display (DISPLAY is not set)".into(),
        });
    }
    let opts = WindowOptions::default();
    let (w, h) = (args.width as usize, args.height as usize);
    Window::new("softwalk view", w, h, opts).map_err(|e| CliError::NoWindow {
        reason: e.to_string().replace('\n', " "),
    })
}

fn output(e: engine::output::OutputError) -> CliError {
    CliError::Output(Box::new(e))
}

fn sim_error(e: SimError) -> CliError {
    CliError::Sim(e)
}

/// The running session: the world, its view, the camera and what was asked.
struct Live<'a> {
    scene: &'a Scene,
    app: App,
    walkers: Vec<Entity>,
    session: InputSession<'a>,
    view: WorldView,
    orbit: OrbitCamera,
    clock: FixedStepClock,
    hud: Hud,
    step: u64,
    frames: u64,
    live_events: Vec<InputEvent>,
    velocity: Vec2,
    running: bool,
    brush: Option<&'static str>,
    paused: bool,
    overlays: bool,
    layers: OverlayLayers,
    frame_dir: Option<PathBuf>,
    shots: u32,
    mouse: Option<(f32, f32)>,
    args: &'a ViewArgs,
    last_frame: Instant,
    threads: usize,
    /// The window's pixels (0RGB), kept between frames.
    screen: Vec<u32>,
}

impl<'a> Live<'a> {
    fn start(
        scene: &'a Scene,
        script: &'a InputScript,
        args: &'a ViewArgs,
        threads: usize,
    ) -> Result<Self, CliError> {
        let (mut app, walkers) = scene.build_sim().map_err(CliError::Scene)?;
        let session = InputSession::start(script, scene, &mut app, &walkers)?;
        let view = scene_view(
            scene,
            &app.world,
            &walkers,
            args.width,
            args.height,
            threads,
        )
        .map_err(|e| sim_error(SimError::View(e)))?;
        let offset = match scene.camera.mode {
            CameraMode::Follow { offset, .. } => Vec3::from(offset),
            CameraMode::Fixed { .. } => DEFAULT_CAMERA_OFFSET,
        };
        let mut live = Live {
            scene,
            app,
            walkers,
            session,
            view,
            orbit: OrbitCamera::from_offset(Vec3::ZERO, offset),
            clock: FixedStepClock::new(f64::from(scene.sim.dt)),
            hud: Hud::default(),
            step: 0,
            frames: 0,
            live_events: Vec::new(),
            velocity: Vec2::ZERO,
            running: false,
            brush: None,
            paused: false,
            overlays: scene.render.overlays,
            layers: OverlayLayers::ALL,
            frame_dir: None,
            shots: 0,
            mouse: None,
            args,
            last_frame: Instant::now(),
            threads,
            screen: Vec::new(),
        };
        live.orbit.snap(live.com());
        Ok(live)
    }

    /// The steered character's entity.
    fn walker(&self) -> Entity {
        self.walkers[self.session.walker()]
    }

    /// The steered character's centre of mass.
    fn com(&self) -> Vec3 {
        let world = &self.app.world;
        world
            .get::<WalkerMetrics>(self.walker())
            .map_or(Vec3::ZERO, |m| m.character.com)
    }

    /// One display frame: input, the steps due, drawing.
    fn frame(&mut self, window: &mut Window, limit: Option<u64>) -> Result<(), CliError> {
        let now = Instant::now();
        let elapsed = now - self.last_frame;
        self.last_frame = now;
        self.keys(window)?;
        self.steer(window)?;
        self.mouse(window);
        let due = if self.paused {
            self.clock.hold();
            0
        } else {
            self.clock.advance(elapsed)
        };
        let room = limit.map_or(u64::MAX, |n| n.saturating_sub(self.step));
        self.advance(u64::from(due).min(room))?;
        self.orbit.follow(self.com(), elapsed.as_secs_f32());
        let drawing = Instant::now();
        let mut image = self.draw()?;
        self.hud
            .frame(elapsed.as_secs_f64(), drawing.elapsed().as_secs_f64());
        let line = self.hud.line(&self.figures());
        engine::canvas::draw_text(&mut image, 6.0, 4.0, HUD_TEXT_PX, Rgba([255; 4]), &line);
        self.save_frame(&image)?;
        self.screen.clear();
        self.screen.extend(
            image
                .pixels()
                .map(|p| (u32::from(p[0]) << 16) | (u32::from(p[1]) << 8) | u32::from(p[2])),
        );
        let (w, h) = (image.width() as usize, image.height() as usize);
        window
            .update_with_buffer(&self.screen, w, h)
            .map_err(|e| CliError::NoWindow {
                reason: e.to_string(),
            })?;
        self.frames += 1;
        Ok(())
    }

    /// Runs `n` steps, each after its scripted inputs.
    fn advance(&mut self, n: u64) -> Result<(), CliError> {
        for _ in 0..n {
            let reset = self
                .session
                .before_step(self.step, self.scene, &mut self.app, &mut self.walkers)
                .map_err(|e| sim_error(SimError::Inputs(Box::new(e))))?;
            if reset {
                self.rebuild_view()?;
            }
            let t = Instant::now();
            softwalk_systems::sim::step(&mut self.app).map_err(|e| sim_error(SimError::Step(e)))?;
            self.hud.step(t.elapsed().as_secs_f64());
            self.step += 1;
        }
        Ok(())
    }

    /// Draws the world from the orbit camera.
    fn draw(&mut self) -> Result<RgbaImage, CliError> {
        self.view.look_at(self.orbit.eye(), self.orbit.target);
        self.view.set_overlays(self.overlays);
        self.view.set_overlay_layers(self.layers);
        let dt = self.scene.sim.dt;
        self.view
            .render(&self.app.world, dt)
            .map_err(|e| sim_error(SimError::View(e)))
    }

    /// A new view after a reset (the world's terrain is new).
    fn rebuild_view(&mut self) -> Result<(), CliError> {
        let (w, h) = (self.args.width, self.args.height);
        self.view = scene_view(
            self.scene,
            &self.app.world,
            &self.walkers,
            w,
            h,
            self.threads,
        )
        .map_err(|e| sim_error(SimError::View(e)))?;
        self.orbit.snap(self.com());
        Ok(())
    }

    /// Applies and records a live input before the next step.
    fn act(&mut self, action: InputAction) -> Result<(), CliError> {
        let reset = self
            .session
            .apply(&action, self.scene, &mut self.app, &mut self.walkers)
            .map_err(|e| sim_error(SimError::Inputs(Box::new(e))))?;
        if reset {
            self.velocity = Vec2::ZERO;
            self.running = false;
            self.rebuild_view()?;
        }
        self.live_events.push(InputEvent {
            step: self.step,
            action,
        });
        Ok(())
    }

    /// The one-shot keys: pause, single step, reset, overlays (all, or one
    /// layer with 1 to 5), brush, screenshot, frame recording.
    fn keys(&mut self, window: &Window) -> Result<(), CliError> {
        for key in window.get_keys_pressed(KeyRepeat::No) {
            match key {
                Key::Space => self.paused = !self.paused,
                Key::N if self.paused => self.advance(1)?,
                Key::R => self.act(InputAction::Reset)?,
                Key::O => self.overlays = !self.overlays,
                Key::Key1 => self.toggle_layer(0),
                Key::Key2 => self.toggle_layer(1),
                Key::Key3 => self.toggle_layer(2),
                Key::Key4 => self.toggle_layer(3),
                Key::Key5 => self.toggle_layer(4),
                Key::B => {
                    let brush = next_brush(self.brush);
                    self.brush = Some(brush);
                    self.act(InputAction::Brush(brush.to_string()))?;
                }
                Key::P => self.screenshot()?,
                Key::F => self.toggle_frames()?,
                _ => {}
            }
        }
        Ok(())
    }

    /// Switches one overlay layer (see [`OverlayLayers::toggle`]) and shows
    /// the overlays.
    fn toggle_layer(&mut self, index: usize) {
        self.layers.toggle(index);
        self.overlays = true;
    }

    /// WASD or arrows and Shift to the desired velocity; records changes.
    fn steer(&mut self, window: &Window) -> Result<(), CliError> {
        let down = |a: Key, b: Key| window.is_key_down(a) || window.is_key_down(b);
        let held = Held {
            forward: down(Key::W, Key::Up),
            back: down(Key::S, Key::Down),
            left: down(Key::A, Key::Left),
            right: down(Key::D, Key::Right),
        };
        let running = down(Key::LeftShift, Key::RightShift);
        if running != self.running {
            self.running = running;
            let factor = if running { RUN_FACTOR } else { 1.0 };
            self.act(InputAction::Speed(factor))?;
        }
        let velocity = desired_velocity(held, self.orbit.yaw);
        if velocity != self.velocity {
            self.velocity = velocity;
            self.act(InputAction::Velocity(velocity.to_array()))?;
        }
        Ok(())
    }

    /// Left drag orbits, the wheel zooms.
    fn mouse(&mut self, window: &Window) {
        let at = window.get_mouse_pos(MouseMode::Pass);
        if window.get_mouse_down(MouseButton::Left)
            && let (Some((x0, y0)), Some((x, y))) = (self.mouse, at)
        {
            self.orbit.drag(x - x0, y - y0);
        }
        self.mouse = at;
        if let Some((_, dy)) = window.get_scroll_wheel() {
            self.orbit.zoom(dy.signum());
        }
    }

    /// What the heads-up line shows about the steered character.
    fn figures(&self) -> HudFigures {
        let world = &self.app.world;
        let walker = self.walker();
        let (tilt, lean) = world
            .get::<RigidProxy>(walker)
            .map_or((0.0, 0.0), |p| (p.tilt, p.lean));
        let (at, speed) = world.get::<Gait>(walker).map_or((Vec2::ZERO, 0.0), |g| {
            (g.pelvis.position, g.velocity.length())
        });
        let material = world
            .get_resource::<GroundState>()
            .and_then(|g| g.terrain().material_at(at.x, at.y).map(|m| m.name.clone()))
            .unwrap_or_else(|| "-".into());
        HudFigures {
            material,
            tilt_deg: tilt.to_degrees(),
            lean_deg: lean.to_degrees(),
            speed_m_s: speed,
            brush: self.brush.unwrap_or("-").to_string(),
            paused: self.paused,
            recording: self.frame_dir.is_some(),
        }
    }

    /// Saves the next frame as a numbered screenshot beside `--screenshot`.
    fn screenshot(&mut self) -> Result<(), CliError> {
        self.shots += 1;
        let path = numbered(&self.args.screenshot, self.shots);
        let image = self.draw()?;
        engine::output::save_png(&path, &image).map_err(output)?;
        eprintln!("screenshot: {}", path.display());
        Ok(())
    }

    /// Starts or stops recording frames to `--frames`.
    fn toggle_frames(&mut self) -> Result<(), CliError> {
        if self.frame_dir.take().is_none() {
            let dir = crate::out_dir::prepare_output_dir(&self.args.frames)?;
            self.frame_dir = Some(dir);
        }
        Ok(())
    }

    /// Writes `image` to the frame folder while recording.
    fn save_frame(&self, image: &RgbaImage) -> Result<(), CliError> {
        if let Some(dir) = &self.frame_dir {
            let path = dir.join(format!("frame_{:06}.png", self.frames));
            engine::output::save_png(&path, image).map_err(output)?;
        }
        Ok(())
    }

    /// The session as an input file: the live inputs, then the script's,
    /// in step order (the order they were applied in).
    fn recording(&self, script: &InputScript) -> InputScript {
        let mut events = self.live_events.clone();
        events.extend(script.events.iter().cloned());
        events.sort_by_key(|e| e.step);
        let name = &self.scene.characters[self.session.walker()].name;
        InputScript {
            character: Some(name.clone()),
            events,
        }
    }
}

/// `path` with `-N` before its extension.
fn numbered(path: &Path, n: u32) -> PathBuf {
    let stem = path.file_stem().map_or_else(
        || "softwalk-view".into(),
        |s| s.to_string_lossy().into_owned(),
    );
    let ext = path
        .extension()
        .map_or_else(|| "png".into(), |e| e.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}-{n}.{ext}"))
}
