//! Streaming animated GIF output.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use image::RgbaImage;

use super::OutputError;
use super::frame_size::FrameSize;
use crate::io::AtomicFile;

/// How a GIF frame's colours are reduced to 256.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GifPalette {
    /// One fixed 6x7x6 colour cube for all frames with 4x4 ordered dithering:
    /// fast (a table look-up per pixel), deterministic, and flicker-free
    /// between frames.
    FixedDithered,
    /// A per-frame palette found by NeuQuant. `speed` runs from 1 (best, slowest)
    /// to 30 (fastest); 10 is a good compromise.
    Adaptive {
        /// NeuQuant sampling speed, 1..=30.
        speed: i32,
    },
}

impl Default for GifPalette {
    /// The fast fixed palette.
    fn default() -> Self {
        Self::FixedDithered
    }
}

/// Levels per channel of the fixed colour cube (6 * 7 * 6 = 252 colours).
const LEVELS: [u32; 3] = [6, 7, 6];

/// 4x4 Bayer matrix, values 0..16.
const BAYER4: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

/// Per-channel look-up tables: for each Bayer cell and byte value, the
/// channel's contribution to the palette index.
struct DitherTables {
    /// `[channel][bayer cell][value]`.
    contribution: Box<[[[u8; 256]; 16]; 3]>,
    /// The palette as `[r, g, b, ...]`.
    palette: Vec<u8>,
}

impl DitherTables {
    fn new() -> Self {
        let strides = [LEVELS[1] * LEVELS[2], LEVELS[2], 1];
        let mut contribution = Box::new([[[0u8; 256]; 16]; 3]);
        for (channel, table) in contribution.iter_mut().enumerate() {
            let steps = LEVELS[channel] - 1;
            for (cell, row) in table.iter_mut().enumerate() {
                for (value, out) in row.iter_mut().enumerate() {
                    // level = floor(value * steps / 255 + (cell + 0.5) / 16), in integers.
                    let level =
                        (value as u32 * steps * 32 + (2 * cell as u32 + 1) * 255) / (255 * 32);
                    *out = (level.min(steps) * strides[channel]) as u8;
                }
            }
        }
        let mut palette = Vec::with_capacity(256 * 3);
        for r in 0..LEVELS[0] {
            for g in 0..LEVELS[1] {
                for b in 0..LEVELS[2] {
                    for (level, n) in [(r, LEVELS[0]), (g, LEVELS[1]), (b, LEVELS[2])] {
                        palette.push(((level * 255 + (n - 1) / 2) / (n - 1)) as u8);
                    }
                }
            }
        }
        Self {
            contribution,
            palette,
        }
    }

    /// Maps an RGBA frame to palette indices with ordered dithering.
    fn index(&self, image: &RgbaImage) -> Vec<u8> {
        let width = image.width() as usize;
        let [tr, tg, tb] = &*self.contribution;
        image
            .as_raw()
            .chunks_exact(4)
            .enumerate()
            .map(|(i, px)| {
                let cell = BAYER4[(i / width) & 3][(i % width) & 3] as usize;
                tr[cell][px[0] as usize] + tg[cell][px[1] as usize] + tb[cell][px[2] as usize]
            })
            .collect()
    }
}

/// The colour reduction in use, with its precomputed state.
enum Quantizer {
    Fixed(DitherTables),
    Adaptive { speed: i32 },
}

/// Writes an animated GIF frame by frame, looping forever.
///
/// The file appears only when [`GifWriter::finish`] succeeds; a writer dropped
/// before that leaves nothing behind.
///
/// ```no_run
/// use engine::output::GifWriter;
/// let mut gif = GifWriter::create(std::path::Path::new("walk.gif"), 40)?;
/// for _ in 0..3 {
///     gif.push(&image::RgbaImage::new(64, 48))?;
/// }
/// gif.finish()?;
/// # Ok::<(), engine::output::OutputError>(())
/// ```
pub struct GifWriter {
    // Declared before `temp` so that it is dropped (and stops writing) first.
    encoder: Option<gif::Encoder<BufWriter<File>>>,
    temp: AtomicFile,
    delay_cs: u16,
    quantizer: Quantizer,
    size: FrameSize,
    frames: usize,
}

impl GifWriter {
    /// Starts a GIF at `path` with `delay_ms` between frames and the fast
    /// fixed palette ([`GifPalette::FixedDithered`]).
    pub fn create(path: &Path, delay_ms: u32) -> Result<Self, OutputError> {
        Self::create_with(path, delay_ms, GifPalette::default())
    }

    /// Starts a GIF at `path` with `delay_ms` between frames and the given
    /// palette strategy. GIF delays are stored in hundredths of a second, so
    /// `delay_ms` is rounded to 10 ms and must lie in 10..=655350.
    pub fn create_with(
        path: &Path,
        delay_ms: u32,
        palette: GifPalette,
    ) -> Result<Self, OutputError> {
        let invalid = |parameter, reason: String| OutputError::InvalidParameter {
            path: path.to_path_buf(),
            parameter,
            reason,
        };
        if !(10..=655_350).contains(&delay_ms) {
            return Err(invalid(
                "delay_ms",
                format!("{delay_ms} ms is outside 10..=655350 (GIF stores 1/100 s)"),
            ));
        }
        if let GifPalette::Adaptive { speed } = palette
            && !(1..=30).contains(&speed)
        {
            return Err(invalid(
                "speed",
                format!("NeuQuant speed {speed} is outside 1..=30"),
            ));
        }
        let quantizer = match palette {
            GifPalette::FixedDithered => Quantizer::Fixed(DitherTables::new()),
            GifPalette::Adaptive { speed } => Quantizer::Adaptive { speed },
        };
        Ok(Self {
            encoder: None,
            temp: AtomicFile::create(path)?,
            delay_cs: ((delay_ms + 5) / 10) as u16,
            quantizer,
            size: FrameSize::default(),
            frames: 0,
        })
    }

    /// Number of frames pushed so far.
    pub fn frame_count(&self) -> usize {
        self.frames
    }

    /// Appends a frame. All frames must have the size of the first, at most
    /// 65535 pixels on a side.
    pub fn push(&mut self, frame: &RgbaImage) -> Result<(), OutputError> {
        let (width, height) = (frame.width(), frame.height());
        let (w16, h16) = self.check_frame(width, height)?;
        let mut gif_frame = match &self.quantizer {
            Quantizer::Fixed(tables) => {
                gif::Frame::from_indexed_pixels(w16, h16, tables.index(frame), None)
            }
            Quantizer::Adaptive { speed } => {
                let mut rgba = frame.as_raw().clone();
                gif::Frame::from_rgba_speed(w16, h16, &mut rgba, *speed)
            }
        };
        gif_frame.delay = self.delay_cs;
        if self.encoder.is_none() {
            let global = match &self.quantizer {
                Quantizer::Fixed(tables) => &tables.palette[..],
                Quantizer::Adaptive { .. } => &[][..],
            };
            let writer = BufWriter::with_capacity(1 << 16, self.temp.try_clone_file()?);
            let mut encoder =
                gif::Encoder::new(writer, w16, h16, global).map_err(|e| self.encode_error(e))?;
            encoder
                .set_repeat(gif::Repeat::Infinite)
                .map_err(|e| self.encode_error(e))?;
            self.encoder = Some(encoder);
        }
        let encoder = self.encoder.as_mut().expect("created above");
        let result = encoder.write_frame(&gif_frame);
        result.map_err(|e| self.encode_error(e))?;
        self.frames += 1;
        Ok(())
    }

    /// Writes the trailer and moves the finished file into place.
    pub fn finish(mut self) -> Result<(), OutputError> {
        let Some(encoder) = self.encoder.take() else {
            return Err(OutputError::NoFrames {
                path: self.temp.target().to_path_buf(),
            });
        };
        let writer = encoder.into_inner().map_err(|e| self.encode_error(e))?;
        writer
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|mut file| file.flush())
            .map_err(|e| self.temp.io_error(e))?;
        let Self { temp, .. } = self;
        Ok(temp.commit()?)
    }

    /// Checks a frame's size against the first frame and the format's limits.
    fn check_frame(&mut self, width: u32, height: u32) -> Result<(u16, u16), OutputError> {
        self.size
            .check(self.temp.target(), self.frames, width, height)?;
        match (u16::try_from(width), u16::try_from(height)) {
            (Ok(w), Ok(h)) => Ok((w, h)),
            _ => Err(OutputError::InvalidParameter {
                path: self.temp.target().to_path_buf(),
                parameter: "frame size",
                reason: format!("{width}x{height} exceeds GIF's 65535 pixel limit"),
            }),
        }
    }

    fn encode_error(&self, e: gif::EncodingError) -> OutputError {
        match e {
            gif::EncodingError::Io(source) => self.temp.io_error(source).into(),
            other => OutputError::Encode {
                path: self.temp.target().to_path_buf(),
                message: other.to_string(),
            },
        }
    }
}
