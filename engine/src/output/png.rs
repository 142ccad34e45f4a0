//! PNG output: 8-bit RGBA frames and 16-bit grayscale height maps.

use std::io::{self, Write};
use std::path::Path;

use image::RgbaImage;

use super::OutputError;
use crate::io::write_atomic;

/// Encodes 8-bit RGBA pixels as a PNG into `out`, with fast compression.
fn encode_rgba8(out: &mut dyn Write, width: u32, height: u32, rgba: &[u8]) -> io::Result<()> {
    encode_with(
        out,
        width,
        height,
        png::ColorType::Rgba,
        png::BitDepth::Eight,
        rgba,
    )
}

/// Encodes raw samples as a PNG with the given colour type and depth.
fn encode_with(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> io::Result<()> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().map_err(io::Error::other)?;
    writer.write_image_data(data).map_err(io::Error::other)?;
    writer.finish().map_err(io::Error::other)
}

/// Encodes `image` as PNG bytes in memory (fast compression).
pub fn encode_png(image: &RgbaImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    encode_rgba8(&mut bytes, image.width(), image.height(), image.as_raw())
        .expect("encoding a valid RGBA image into memory cannot fail");
    bytes
}

/// Saves `image` as an 8-bit RGBA PNG with fast compression, atomically:
/// the file is written whole or not at all.
///
/// ```no_run
/// let frame = image::RgbaImage::new(64, 32);
/// engine::output::save_png(std::path::Path::new("frame.png"), &frame)?;
/// # Ok::<(), engine::output::OutputError>(())
/// ```
pub fn save_png(path: &Path, image: &RgbaImage) -> Result<(), OutputError> {
    check_size(path, image.width(), image.height())?;
    write_atomic(path, |w| {
        encode_rgba8(w, image.width(), image.height(), image.as_raw())
    })?;
    Ok(())
}

/// Saves `width * height` 16-bit samples (row-major) as a grayscale PNG, atomically.
pub fn save_png_gray16(
    path: &Path,
    width: u32,
    height: u32,
    samples: &[u16],
) -> Result<(), OutputError> {
    check_size(path, width, height)?;
    let expected = width as usize * height as usize;
    if samples.len() != expected {
        return Err(OutputError::InvalidParameter {
            path: path.to_path_buf(),
            parameter: "samples",
            reason: format!(
                "{} samples given for a {width}x{height} image ({expected} expected)",
                samples.len()
            ),
        });
    }
    let big_endian: Vec<u8> = samples.iter().flat_map(|s| s.to_be_bytes()).collect();
    write_atomic(path, |w| {
        encode_with(
            w,
            width,
            height,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &big_endian,
        )
    })?;
    Ok(())
}

/// Rejects images with a zero dimension, which PNG cannot store.
pub(super) fn check_size(path: &Path, width: u32, height: u32) -> Result<(), OutputError> {
    if width == 0 || height == 0 {
        return Err(OutputError::InvalidParameter {
            path: path.to_path_buf(),
            parameter: "size",
            reason: format!("{width}x{height} has no pixels"),
        });
    }
    Ok(())
}
