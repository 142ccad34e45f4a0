//! Rendered frames as numbered PNG files.

use std::path::{Path, PathBuf};

use engine::output::save_png;

use crate::runner::{Frame, ObserverError, RunObserver};

/// Writes every frame to `DIR/frame_NNNNNN.png` (NNNNNN = step), each file whole or not at all.
#[derive(Debug, Clone)]
pub struct FrameWriter {
    dir: PathBuf,
    written: u64,
}

impl FrameWriter {
    /// Frames go to `dir`, which must exist.
    pub fn new(dir: &Path) -> FrameWriter {
        FrameWriter {
            dir: dir.to_path_buf(),
            written: 0,
        }
    }

    /// Frames written so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    /// The file a frame of `step` goes to.
    pub fn frame_path(&self, step: u64) -> PathBuf {
        self.dir.join(format!("frame_{step:06}.png"))
    }
}

impl RunObserver for FrameWriter {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        save_png(&self.frame_path(frame.step), frame.image)?;
        self.written += 1;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = FrameWriter::new(dir.path());
        let image = image::RgbaImage::from_fn(3, 2, |x, y| {
            image::Rgba([x as u8 * 40, y as u8 * 90, 7, 255])
        });
        w.on_frame(&Frame {
            step: 7,
            t: 0.1,
            image: &image,
        })
        .unwrap();
        let back = image::open(w.frame_path(7)).unwrap().into_rgba8();
        assert_eq!(back, image);
        assert_eq!(w.written(), 1);
    }
}
