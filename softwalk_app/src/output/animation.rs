//! The run as an animation (GIF and/or APNG) and a contact sheet of evenly spaced frames.

use std::path::Path;

use engine::output::{ApngWriter, GifWriter, contact_sheet, save_png};
use image::{Rgba, RgbaImage, imageops};

use crate::runner::{Frame, ObserverError, RunObserver};

/// Largest side of an animation frame; larger frames are halved (GIFs of full
/// 960x540 frames would be large and slow to encode).
const MAX_ANIMATION_SIDE: u32 = 480;

/// Streams frames into an animated GIF and/or APNG; `finish` renames them into place.
pub struct AnimationWriter {
    gif: Option<GifWriter>,
    apng: Option<ApngWriter>,
}

impl AnimationWriter {
    /// Writers for `gif`/`apng` paths (none = not written); `delay_ms` per frame.
    pub fn create(
        gif: Option<&Path>,
        apng: Option<&Path>,
        delay_ms: u32,
    ) -> Result<Self, ObserverError> {
        Ok(AnimationWriter {
            gif: gif.map(|p| GifWriter::create(p, delay_ms)).transpose()?,
            apng: apng.map(|p| ApngWriter::create(p, delay_ms)).transpose()?,
        })
    }

    /// True when a GIF or an APNG is written (frames are shrunk only then).
    pub fn writes_any(&self) -> bool {
        self.gif.is_some() || self.apng.is_some()
    }

    /// Completes the files (before this, nothing is visible at their paths).
    pub fn finish(self) -> Result<(), ObserverError> {
        if let Some(g) = self.gif {
            g.finish()?;
        }
        if let Some(a) = self.apng {
            a.finish()?;
        }
        Ok(())
    }
}

/// `image` shrunk so that its longer side is at most `max_side`.
fn shrink(image: &RgbaImage, max_side: u32) -> RgbaImage {
    let side = image.width().max(image.height());
    if side <= max_side {
        return image.clone();
    }
    let w = (image.width() * max_side / side).max(1);
    let h = (image.height() * max_side / side).max(1);
    imageops::resize(image, w, h, imageops::FilterType::Triangle)
}

impl RunObserver for AnimationWriter {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        // Shrinking costs as much as drawing a small frame: only for an animation.
        if !self.writes_any() {
            return Ok(());
        }
        let small = shrink(frame.image, MAX_ANIMATION_SIDE);
        if let Some(g) = self.gif.as_mut() {
            g.push(&small)?;
        }
        if let Some(a) = self.apng.as_mut() {
            a.push(&small)?;
        }
        Ok(())
    }
}

/// Keeps `count` evenly spaced frames (as thumbnails) for a contact sheet.
pub struct ContactSheet {
    every: u64,
    seen: u64,
    columns: u32,
    thumbs: Vec<RgbaImage>,
}

/// Width of one contact-sheet cell, pixels.
const THUMB_WIDTH: u32 = 320;

impl ContactSheet {
    /// A sheet of `columns` columns and about `count` of the `expected_frames` frames.
    pub fn new(expected_frames: u64, count: u64, columns: u32) -> Self {
        let every = expected_frames.div_ceil(count.max(1)).max(1);
        ContactSheet {
            every,
            seen: 0,
            columns: columns.max(1),
            thumbs: Vec::new(),
        }
    }

    /// Writes the sheet (nothing when no frame was kept).
    pub fn save(&self, path: &Path) -> Result<(), ObserverError> {
        if self.thumbs.is_empty() {
            return Ok(());
        }
        let sheet = contact_sheet(
            &self.thumbs,
            self.columns,
            THUMB_WIDTH,
            Rgba([24, 24, 28, 255]),
        );
        save_png(path, &sheet)?;
        Ok(())
    }
}

impl RunObserver for ContactSheet {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        if self.seen.is_multiple_of(self.every) {
            self.thumbs.push(shrink(frame.image, THUMB_WIDTH));
        }
        self.seen += 1;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(step: u64, image: &RgbaImage) -> Frame<'_> {
        Frame {
            step,
            t: step as f64 / 60.0,
            image,
        }
    }

    /// Issue 21: 18 % of the main job went to shrinking every frame for the
    /// GIF even with the GIF and the APNG switched off.
    #[test]
    fn no_animation_means_no_work_per_frame() {
        let mut anim = AnimationWriter::create(None, None, 40).unwrap();
        assert!(!anim.writes_any());
        let image = RgbaImage::new(960, 540);
        anim.on_frame(&frame(0, &image)).unwrap();
        anim.finish().unwrap();
        let dir = tempfile::tempdir().unwrap();
        let gif = dir.path().join("a.gif");
        assert!(
            AnimationWriter::create(Some(&gif), None, 40)
                .unwrap()
                .writes_any()
        );
    }

    #[test]
    fn animations_and_sheet_are_written_whole() {
        let dir = tempfile::tempdir().unwrap();
        let (gif, apng, sheet) = (
            dir.path().join("a.gif"),
            dir.path().join("a.png"),
            dir.path().join("s.png"),
        );
        let mut anim = AnimationWriter::create(Some(&gif), Some(&apng), 40).unwrap();
        let mut contact = ContactSheet::new(12, 4, 2);
        for step in 0..12 {
            let image = RgbaImage::from_pixel(960, 540, Rgba([step as u8 * 20, 40, 90, 255]));
            anim.on_frame(&frame(step, &image)).unwrap();
            contact.on_frame(&frame(step, &image)).unwrap();
            assert!(!gif.exists(), "nothing is visible before finish");
        }
        anim.finish().unwrap();
        contact.save(&sheet).unwrap();
        let decoded = image::open(&gif).unwrap();
        assert_eq!(decoded.width(), MAX_ANIMATION_SIDE);
        assert_eq!(contact.thumbs.len(), 4);
        let sheet = image::open(&sheet).unwrap();
        assert!((2 * THUMB_WIDTH..3 * THUMB_WIDTH).contains(&sheet.width()));
    }
}
