//! Gallery images as opaque PNG files.

use std::path::Path;

use image::RgbaImage;

use super::PaperError;

/// Writes `image` as an opaque PNG at `path`, whole or not at all.
pub fn write_png(path: &Path, image: RgbaImage) -> Result<(), PaperError> {
    let mut bytes = Vec::new();
    image::DynamicImage::ImageRgba8(image)
        .to_rgb8()
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|e| PaperError::Encode {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
    engine::io::write_bytes_atomic(path, &bytes)?;
    Ok(())
}
