//! A grid of thumbnails of many frames in one image.

use image::imageops::{self, FilterType};
use image::{Rgba, RgbaImage};

/// Lays `frames` out in a grid of `columns` columns, each frame scaled to
/// `thumb_width` pixels wide (keeping the first frame's aspect ratio), with a
/// `gap` of 4 pixels of `background` between and around the thumbnails.
///
/// Frames are placed row by row in order. No frames, zero columns or a zero
/// thumbnail width give a 1x1 image of `background`.
///
/// ```
/// use engine::output::contact_sheet;
/// use image::{Rgba, RgbaImage};
/// let frames = vec![RgbaImage::new(40, 20); 5];
/// let sheet = contact_sheet(&frames, 3, 20, Rgba([0, 0, 0, 255]));
/// assert_eq!(sheet.dimensions(), (3 * 20 + 4 * 4, 2 * 10 + 3 * 4));
/// ```
pub fn contact_sheet(
    frames: &[RgbaImage],
    columns: u32,
    thumb_width: u32,
    background: Rgba<u8>,
) -> RgbaImage {
    const GAP: u32 = 4;
    let Some(first) = frames.first() else {
        return RgbaImage::from_pixel(1, 1, background);
    };
    if columns == 0 || thumb_width == 0 || first.width() == 0 {
        return RgbaImage::from_pixel(1, 1, background);
    }
    let thumb_height = ((u64::from(thumb_width) * u64::from(first.height())
        + u64::from(first.width()) / 2)
        / u64::from(first.width()))
    .max(1) as u32;
    let columns = columns.min(frames.len() as u32);
    let rows = (frames.len() as u32).div_ceil(columns);
    let mut sheet = RgbaImage::from_pixel(
        columns * (thumb_width + GAP) + GAP,
        rows * (thumb_height + GAP) + GAP,
        background,
    );
    for (i, frame) in frames.iter().enumerate() {
        let (col, row) = (i as u32 % columns, i as u32 / columns);
        let thumb = if frame.dimensions() == (thumb_width, thumb_height) {
            frame.clone()
        } else {
            imageops::resize(frame, thumb_width, thumb_height, FilterType::Triangle)
        };
        imageops::replace(
            &mut sheet,
            &thumb,
            i64::from(GAP + col * (thumb_width + GAP)),
            i64::from(GAP + row * (thumb_height + GAP)),
        );
    }
    sheet
}
