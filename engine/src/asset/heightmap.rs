use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use glam::Vec2;

use super::AssetError;
use crate::geom::{HeightGrid, MAX_GRID_SAMPLES};
use crate::io::write_atomic;

/// What [`save_heightmap_png16`] wrote: enough to turn the 16-bit values back
/// into heights with [`load_heightmap_restored`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightmapInfo {
    /// Image width (samples along X).
    pub width: u32,
    /// Image height (samples along Z).
    pub height: u32,
    /// The height stored as 0.
    pub min: f32,
    /// The height stored as 65535.
    pub max: f32,
    /// Sample spacing of the grid, in metres.
    pub cell: f32,
    /// World XZ position of sample `(0, 0)`.
    pub origin: Vec2,
}

impl HeightmapInfo {
    /// Metres per full 16-bit range (`max - min`).
    pub fn height_scale(&self) -> f32 {
        self.max - self.min
    }

    /// The height a stored 16-bit value stands for.
    pub fn height_of(&self, value: u16) -> f32 {
        self.min + value as f32 / 65535.0 * self.height_scale()
    }
}

/// Loads an 8- or 16-bit grayscale PNG as a height grid: pixel `(x, y)` becomes
/// sample `(i, j)`, `cell` metres apart from origin zero, with height
/// `value / max_value * height_scale` (so white is `height_scale`).
///
/// The image size is checked against [`MAX_GRID_SAMPLES`] from the header,
/// before any pixel is decoded.
pub fn load_heightmap(path: &Path, cell: f32, height_scale: f32) -> Result<HeightGrid, AssetError> {
    if !height_scale.is_finite() {
        return Err(geometry_error(
            path,
            "height_scale",
            format!("{height_scale} is not finite"),
        ));
    }
    let (w, h, values) = read_gray_png(path)?;
    let heights = values.into_iter().map(|v| v * height_scale).collect();
    make_grid(path, Vec2::ZERO, cell, w, h, heights)
}

/// Loads a PNG written by [`save_heightmap_png16`] back into heights, using the
/// recorded range, cell size and origin (to within `height_scale / 65535`).
pub fn load_heightmap_restored(
    path: &Path,
    info: &HeightmapInfo,
) -> Result<HeightGrid, AssetError> {
    if !(info.min.is_finite() && info.max.is_finite()) {
        return Err(geometry_error(
            path,
            "info",
            format!("height range {}..{} is not finite", info.min, info.max),
        ));
    }
    let (w, h, values) = read_gray_png(path)?;
    if (w, h) != (info.width as usize, info.height as usize) {
        return Err(geometry_error(
            path,
            "info",
            format!(
                "image is {w} x {h}, info says {} x {}",
                info.width, info.height
            ),
        ));
    }
    let heights = values
        .into_iter()
        .map(|v| info.min + v * info.height_scale())
        .collect();
    make_grid(path, info.origin, info.cell, w, h, heights)
}

/// Writes `grid` as a 16-bit grayscale PNG, normalised to the grid's
/// min..max (a flat grid is all zeros), atomically; returns what is needed to
/// recover the heights.
pub fn save_heightmap_png16(grid: &HeightGrid, path: &Path) -> Result<HeightmapInfo, AssetError> {
    let (lo, hi) = grid.min_max_in(&grid.full_rect());
    let range = hi - lo;
    let mut bytes = Vec::with_capacity(grid.heights().len() * 2);
    for &h in grid.heights() {
        let v = if range > 0.0 {
            ((h - lo) / range * 65535.0).round().clamp(0.0, 65535.0) as u16
        } else {
            0
        };
        bytes.extend_from_slice(&v.to_be_bytes());
    }
    let info = HeightmapInfo {
        width: grid.nx() as u32,
        height: grid.nz() as u32,
        min: lo,
        max: hi,
        cell: grid.cell_size(),
        origin: grid.origin(),
    };
    write_atomic(path, |w| {
        let mut encoder = png::Encoder::new(&mut *w, info.width, info.height);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Sixteen);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(&bytes)
            .map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    })?;
    Ok(info)
}

/// Decodes a grayscale PNG into values in `0..=1`, row-major.
fn read_gray_png(path: &Path) -> Result<(usize, usize, Vec<f32>), AssetError> {
    let file = File::open(path).map_err(|source| AssetError::reading(path, source))?;
    let corrupt = |e: png::DecodingError| AssetError::CorruptPng {
        path: path.to_path_buf(),
        reason: e.to_string(),
    };
    let mut decoder = png::Decoder::new_with_limits(
        BufReader::new(file),
        png::Limits {
            bytes: MAX_GRID_SAMPLES * 2 + (1 << 20),
        },
    );
    decoder.set_transformations(png::Transformations::IDENTITY);
    let mut reader = decoder.read_info().map_err(corrupt)?;
    let (width, height, color, depth) = {
        let info = reader.info();
        (info.width, info.height, info.color_type, info.bit_depth)
    };
    let samples = (width as u64) * (height as u64);
    if samples > MAX_GRID_SAMPLES as u64 {
        return Err(AssetError::GridTooLarge {
            path: path.to_path_buf(),
            width,
            height,
            limit: MAX_GRID_SAMPLES,
        });
    }
    if color != png::ColorType::Grayscale {
        return Err(AssetError::NotGrayscale {
            path: path.to_path_buf(),
            found: format!("{color:?}"),
        });
    }
    let max_value = match depth {
        png::BitDepth::Eight => 255.0,
        png::BitDepth::Sixteen => 65535.0,
        other => {
            return Err(AssetError::UnsupportedBitDepth {
                path: path.to_path_buf(),
                depth: other as u8,
            });
        }
    };
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| AssetError::GridTooLarge {
            path: path.to_path_buf(),
            width,
            height,
            limit: MAX_GRID_SAMPLES,
        })?;
    let mut buf = vec![0u8; size];
    let frame = reader.next_frame(&mut buf).map_err(corrupt)?;
    let (w, h) = (width as usize, height as usize);
    let mut values = Vec::with_capacity(w * h);
    for row in buf.chunks_exact(frame.line_size).take(h) {
        if max_value > 255.0 {
            values.extend(
                row[..2 * w]
                    .chunks_exact(2)
                    .map(|b| u16::from_be_bytes([b[0], b[1]]) as f32 / max_value),
            );
        } else {
            values.extend(row[..w].iter().map(|&b| b as f32 / max_value));
        }
    }
    Ok((w, h, values))
}

fn make_grid(
    path: &Path,
    origin: Vec2,
    cell: f32,
    w: usize,
    h: usize,
    heights: Vec<f32>,
) -> Result<HeightGrid, AssetError> {
    HeightGrid::from_heights(origin, cell, w, h, heights).map_err(|source| AssetError::Geometry {
        path: path.to_path_buf(),
        source,
    })
}

fn geometry_error(path: &Path, name: &'static str, reason: String) -> AssetError {
    AssetError::Geometry {
        path: path.to_path_buf(),
        source: crate::geom::GeomError::InvalidParameter { name, reason },
    }
}
