//! The gallery: one rendered frame per scene, after a few seconds of walking,
//! and a strip of consecutive frames of a walk in snow ([`super::gallery_strip`]).

use std::path::Path;

use image::RgbaImage;

use super::gallery_strip::write_strip;
use super::opaque_png::write_png;
use super::report::GalleryImage;
use super::variants::builtin;
use super::{PaperError, PaperOptions};
use crate::output::LastFrame;
use crate::runner::{self, RunOptions};
use crate::scene::Scene;

/// Frame size of the gallery, pixels.
pub const GALLERY_SIZE: (u32, u32) = (480, 270);
/// When each frame is taken, seconds of walking.
pub const GALLERY_AT_S: f32 = 4.0;

/// The gallery's scenes: built-in scene name, caption.
pub const GALLERY: [(&str, &str); 9] = [
    ("sand-flat", "sand: medium prints, rims raised around them"),
    ("soil-flat", "soil: the shallowest prints"),
    ("mud-flat", "mud: deep, sharp-edged prints"),
    ("snow-flat", "snow: the deepest, smoothed prints"),
    (
        "grass-small",
        "small grass (0.5 m): trampled trail behind the walker",
    ),
    (
        "grass-medium",
        "medium grass (0.9 m): higher knees, wider trail",
    ),
    (
        "controller-compare",
        "balance controller on (front) and off (back), sand slope into snow",
    ),
    (
        "morphology",
        "morphologies of 1.0, 1.4 and 1.9 m side by side up a sand slope",
    ),
    ("default", "the default scene"),
];

/// The frame of `scene` after `seconds` of walking, at `width` x `height`.
pub fn render_at(
    scene: &Scene,
    seconds: f32,
    width: u32,
    height: u32,
) -> Result<RgbaImage, PaperError> {
    let mut options = RunOptions::from_scene(scene);
    let at = scene.sim.steps_for(f64::from(seconds)).max(1);
    options.steps = at + 1;
    options.render_every = u32::try_from(at).unwrap_or(u32::MAX);
    options.width = width;
    options.height = height;
    let mut last = LastFrame::default();
    runner::run(scene, &options, &mut last).map_err(|source| PaperError::Run {
        scene: scene.name.clone(),
        source,
    })?;
    Ok(last.into_image().expect("the run renders its last step"))
}

/// Renders every gallery scene into `dir/<name>.png`.
pub fn write_gallery(dir: &Path, options: &PaperOptions) -> Result<Vec<GalleryImage>, PaperError> {
    std::fs::create_dir_all(dir).map_err(|source| PaperError::Dir {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut images = Vec::new();
    for (name, caption) in GALLERY {
        let scene = builtin(name)?;
        options.say(&format!("rendering {name}"));
        let image = render_at(&scene, GALLERY_AT_S, GALLERY_SIZE.0, GALLERY_SIZE.1)?;
        write_png(&dir.join(format!("{name}.png")), image)?;
        images.push(GalleryImage {
            name: name.to_owned(),
            caption: caption.to_owned(),
        });
    }
    images.push(write_strip(dir, options)?);
    Ok(images)
}
