//! Streaming animated PNG (APNG) output through the `png` crate.

use std::fs::File;
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::Path;

use image::RgbaImage;

use super::OutputError;
use super::frame_size::FrameSize;
use crate::io::AtomicFile;

/// Frame count announced in the header until the real count is known; the
/// `acTL` chunk is patched with the real count in [`ApngWriter::finish`].
const PLACEHOLDER_FRAMES: u32 = u32::MAX;

/// Length of the PNG signature that precedes the first chunk.
const SIGNATURE_LEN: u64 = 8;

/// Writes an animated PNG frame by frame, lossless, looping forever.
///
/// The frame count need not be known in advance: the header announces a
/// placeholder that `finish()` patches. The file appears only when
/// [`ApngWriter::finish`] succeeds; a writer dropped before that leaves
/// nothing behind.
///
/// ```no_run
/// use engine::output::ApngWriter;
/// let mut apng = ApngWriter::create(std::path::Path::new("walk.png"), 40)?;
/// apng.push(&image::RgbaImage::new(64, 48))?;
/// apng.finish()?;
/// # Ok::<(), engine::output::OutputError>(())
/// ```
pub struct ApngWriter {
    // Declared before `temp` so that it is dropped (and stops writing) first.
    writer: Option<png::Writer<BufWriter<File>>>,
    temp: AtomicFile,
    delay_ms: u16,
    size: FrameSize,
    frames: u32,
}

impl ApngWriter {
    /// Starts an APNG at `path` with `delay_ms` (0..=65535) between frames.
    pub fn create(path: &Path, delay_ms: u32) -> Result<Self, OutputError> {
        let delay_ms = u16::try_from(delay_ms).map_err(|_| OutputError::InvalidParameter {
            path: path.to_path_buf(),
            parameter: "delay_ms",
            reason: format!("{delay_ms} ms exceeds APNG's 65535 ms limit"),
        })?;
        Ok(Self {
            writer: None,
            temp: AtomicFile::create(path)?,
            delay_ms,
            size: FrameSize::default(),
            frames: 0,
        })
    }

    /// Number of frames pushed so far.
    pub fn frame_count(&self) -> usize {
        self.frames as usize
    }

    /// Appends a frame; all frames must have the size of the first.
    pub fn push(&mut self, frame: &RgbaImage) -> Result<(), OutputError> {
        let (width, height) = (frame.width(), frame.height());
        self.size
            .check(self.temp.target(), self.frames as usize, width, height)?;
        if self.writer.is_none() {
            self.writer = Some(self.start(width, height)?);
        }
        let writer = self.writer.as_mut().expect("started above");
        let result = writer.write_image_data(frame.as_raw());
        result.map_err(|e| self.encode_error(e))?;
        self.frames += 1;
        Ok(())
    }

    /// Writes the end of the stream, patches the frame count and moves the
    /// finished file into place.
    pub fn finish(mut self) -> Result<(), OutputError> {
        let Some(writer) = self.writer.take() else {
            return Err(OutputError::NoFrames {
                path: self.temp.target().to_path_buf(),
            });
        };
        writer.finish().map_err(|e| self.encode_error(e))?;
        let frames = self.frames;
        patch_frame_count(self.temp.file_mut(), frames).map_err(|e| self.temp.io_error(e))?;
        let Self { temp, .. } = self;
        Ok(temp.commit()?)
    }

    /// Writes the PNG header with an animation control chunk.
    fn start(&self, width: u32, height: u32) -> Result<png::Writer<BufWriter<File>>, OutputError> {
        let writer = BufWriter::with_capacity(1 << 16, self.temp.try_clone_file()?);
        let mut encoder = png::Encoder::new(writer, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        encoder.validate_sequence(false);
        encoder
            .set_animated(PLACEHOLDER_FRAMES, 0)
            .and_then(|()| encoder.set_frame_delay(self.delay_ms, 1000))
            .map_err(|e| self.encode_error(e))?;
        encoder.write_header().map_err(|e| self.encode_error(e))
    }

    fn encode_error(&self, e: png::EncodingError) -> OutputError {
        match e {
            png::EncodingError::IoError(source) => self.temp.io_error(source).into(),
            other => OutputError::Encode {
                path: self.temp.target().to_path_buf(),
                message: other.to_string(),
            },
        }
    }
}

/// Finds the `acTL` chunk of the PNG in `file` and rewrites its frame count
/// (and CRC) to `frames`.
fn patch_frame_count(file: &mut File, frames: u32) -> std::io::Result<()> {
    let mut offset = SIGNATURE_LEN;
    loop {
        let mut head = [0u8; 8];
        file.seek(SeekFrom::Start(offset))?;
        file.read_exact(&mut head)?;
        let len = u32::from_be_bytes([head[0], head[1], head[2], head[3]]);
        match &head[4..8] {
            b"acTL" => {
                let mut chunk = [0u8; 12];
                chunk[..4].copy_from_slice(b"acTL");
                file.read_exact(&mut chunk[4..])?;
                chunk[4..8].copy_from_slice(&frames.to_be_bytes());
                file.seek(SeekFrom::Start(offset + 8))?;
                file.write_all(&chunk[4..])?;
                return file.write_all(&crc32fast::hash(&chunk).to_be_bytes());
            }
            b"IDAT" | b"IEND" => {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    "no acTL chunk before the image data",
                ));
            }
            _ => offset += 12 + u64::from(len),
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn crc32fast_matches_the_png_iend_chunk() {
        // Every PNG ends with IEND and the CRC AE 42 60 82.
        assert_eq!(crc32fast::hash(b"IEND"), 0xAE42_6082);
    }
}
