//! Rendered frames as numbered PNG files.

use std::path::{Path, PathBuf};

use engine::io::write_bytes_atomic;
use image::ImageEncoder;
use image::codecs::png::PngEncoder;

use crate::sim::{Frame, ObserverError, RunObserver};

/// Writes every frame to `DIR/frame_NNNNNN.png` (NNNNNN = step).
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

    /// Encodes and writes one frame.
    pub fn write(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        let expected = frame.width as usize * frame.height as usize * 4;
        if frame.rgba.len() != expected {
            return Err(format!(
                "frame of step {} has {} bytes, expected {expected} for {} x {} RGBA",
                frame.step,
                frame.rgba.len(),
                frame.width,
                frame.height
            )
            .into());
        }
        let mut png = Vec::new();
        PngEncoder::new(&mut png).write_image(
            frame.rgba,
            frame.width,
            frame.height,
            image::ExtendedColorType::Rgba8,
        )?;
        write_bytes_atomic(&self.frame_path(frame.step), &png)?;
        self.written += 1;
        Ok(())
    }
}

impl RunObserver for FrameWriter {
    fn on_frame(&mut self, frame: &Frame<'_>) -> Result<(), ObserverError> {
        self.write(frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_and_bad_sizes_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = FrameWriter::new(dir.path());
        let rgba: Vec<u8> = (0..4 * 3 * 2).map(|k| k as u8 * 10).collect();
        let frame = Frame {
            step: 7,
            t: 0.1,
            width: 3,
            height: 2,
            rgba: &rgba,
        };
        w.write(&frame).unwrap();
        let img = image::open(w.frame_path(7)).unwrap().into_rgba8();
        assert_eq!(img.as_raw(), &rgba);
        let short = Frame {
            rgba: &rgba[1..],
            ..frame
        };
        assert!(
            w.write(&short)
                .unwrap_err()
                .to_string()
                .contains("expected 24")
        );
        assert_eq!(w.written(), 1);
    }
}
