//! The gallery's strip: consecutive frames of a walk in snow, rendered every
//! step with the camera close on the legs, side by side in one image, so a
//! pelvis pop or a knee flicker between two steps shows.

use image::RgbaImage;

use super::opaque_png::write_png;
use super::recorded_run::record_run;
use super::report::GalleryImage;
use super::variants::builtin;
use super::{PaperError, PaperOptions};
use crate::runner::{self, Frame, ObserverError, RunObserver, RunOptions};
use crate::scene::{CameraMode, Scene};

/// The strip's scene.
pub const STRIP_SCENE: &str = "snow-flat";
/// The strip's file name stem (`gallery/<name>.png`).
pub const STRIP_NAME: &str = "snow-strip";
/// Frames in the strip.
pub const STRIP_FRAMES: usize = 8;
/// Size of each frame, pixels.
pub const STRIP_FRAME_SIZE: (u32, u32) = (200, 150);
/// Simulated time of the strip's first frame, seconds.
pub const STRIP_AT_S: f32 = 3.0;
/// Height of the camera's aim above the ground under the pelvis (about the knees), metres.
const AIM_HEIGHT: f32 = 0.4;
/// Eye position relative to the aim (beside the walk, slightly ahead), metres.
const EYE_OFFSET: [f32; 3] = [0.25, 0.2, 1.9];

/// Keeps the frames of steps `from..from + count`.
struct StripFrames {
    from: u64,
    count: usize,
    frames: Vec<RgbaImage>,
}

impl RunObserver for StripFrames {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        if frame.step >= self.from && self.frames.len() < self.count {
            self.frames.push(frame.image.clone());
        }
        Ok(())
    }
}

/// `frames` consecutive frames of `scene` from `at_s` seconds, each rendered
/// one step after the previous, `width` x `height` each, side by side. The
/// camera stands still beside the walker's legs where they are at `at_s`.
pub fn render_strip(
    scene: &Scene,
    at_s: f32,
    frames: usize,
    width: u32,
    height: u32,
) -> Result<RgbaImage, PaperError> {
    let run_error = |source| PaperError::Run {
        scene: scene.name.clone(),
        source,
    };
    let from = scene.sim.steps_for(f64::from(at_s));
    let mut close = scene.clone();
    close.camera.mode = legs_camera(scene, from)?;
    close.render.overlays = false;
    let mut options = RunOptions::from_scene(&close);
    options.steps = from + frames as u64;
    options.render_every = 1;
    options.width = width;
    options.height = height;
    let mut strip = StripFrames {
        from,
        count: frames,
        frames: Vec::with_capacity(frames),
    };
    runner::run(&close, &options, &mut strip).map_err(run_error)?;
    Ok(side_by_side(&strip.frames, width, height))
}

/// A fixed camera aimed at the first character's knees after `steps` steps.
fn legs_camera(scene: &Scene, steps: u64) -> Result<CameraMode, PaperError> {
    let run = record_run(scene, steps.max(1)).map_err(|source| PaperError::Run {
        scene: scene.name.clone(),
        source,
    })?;
    let last = run.walkers.first().and_then(|w| w.last());
    let (com, ground) = last.map_or((glam::Vec3::ZERO, 0.0), |m| (m.character.com, m.ground_y));
    let target = glam::Vec3::new(com.x, ground + AIM_HEIGHT, com.z);
    let eye = target + glam::Vec3::from(EYE_OFFSET);
    Ok(CameraMode::Fixed {
        eye: eye.to_array(),
        target: target.to_array(),
    })
}

/// The frames left to right in one image (`width` x `height` each).
fn side_by_side(frames: &[RgbaImage], width: u32, height: u32) -> RgbaImage {
    let mut strip = RgbaImage::new(width * frames.len().max(1) as u32, height);
    for (k, frame) in frames.iter().enumerate() {
        image::imageops::replace(&mut strip, frame, i64::from(width) * k as i64, 0);
    }
    strip
}

/// Renders the snow strip into `dir/snow-strip.png`.
pub fn write_strip(
    dir: &std::path::Path,
    options: &PaperOptions,
) -> Result<GalleryImage, PaperError> {
    let scene = builtin(STRIP_SCENE)?;
    options.say(&format!("rendering the {STRIP_SCENE} strip"));
    let (w, h) = STRIP_FRAME_SIZE;
    let image = render_strip(&scene, STRIP_AT_S, STRIP_FRAMES, w, h)?;
    write_png(&dir.join(format!("{STRIP_NAME}.png")), image)?;
    Ok(GalleryImage {
        name: STRIP_NAME.to_owned(),
        caption: format!(
            "{STRIP_FRAMES} consecutive steps (1/60 s apart) of a walk in snow from {STRIP_AT_S} s, \
             camera on the legs: the pelvis and knees should move smoothly from frame to frame"
        ),
    })
}
