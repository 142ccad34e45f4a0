//! Perceptual per-pixel comparison in the manner of pixelmatch: a YIQ colour
//! delta with a threshold, and anti-aliased edge pixels forgiven (Vyšniauskas
//! 2009).

use image::{Rgba, RgbaImage};

/// The largest YIQ delta between two colours (black and white).
const MAX_YIQ_DELTA: f32 = 35215.0;

/// Colour of a pixel that differs in the diff image.
const DIFF_COLOR: Rgba<u8> = Rgba([230, 20, 20, 255]);
/// Colour of a forgiven anti-aliasing pixel in the diff image.
const AA_COLOR: Rgba<u8> = Rgba([250, 210, 0, 255]);

/// The result of comparing two images of the same size.
#[derive(Debug, Clone)]
pub(crate) struct Comparison {
    /// Pixels whose delta exceeds the threshold and that are not anti-aliasing.
    pub diff_pixels: usize,
    /// Pixels over the threshold forgiven as anti-aliasing.
    pub aa_pixels: usize,
    /// The largest delta found, on the threshold's 0..=1 scale.
    pub max_delta: f32,
    /// Faded grey copy of the expected image with differences in red and
    /// forgiven anti-aliasing in yellow.
    pub diff_image: RgbaImage,
}

/// Composites a straight-alpha pixel over white, as pixelmatch does.
fn over_white(p: &Rgba<u8>) -> [f32; 3] {
    let a = f32::from(p[3]) / 255.0;
    [0, 1, 2].map(|c| 255.0 + (f32::from(p[c]) - 255.0) * a)
}

fn luma(c: [f32; 3]) -> f32 {
    c[0] * 0.298_895_3 + c[1] * 0.586_622_5 + c[2] * 0.114_482_23
}

/// Squared YIQ distance between two pixels, negative when `b` is brighter.
fn yiq_delta(a: &Rgba<u8>, b: &Rgba<u8>) -> f32 {
    let (ca, cb) = (over_white(a), over_white(b));
    let y = luma(ca) - luma(cb);
    let i = (ca[0] - cb[0]) * 0.595_977_99
        - (ca[1] - cb[1]) * 0.274_176_1
        - (ca[2] - cb[2]) * 0.321_801_9;
    let q = (ca[0] - cb[0]) * 0.211_470_17 - (ca[1] - cb[1]) * 0.522_617_1
        + (ca[2] - cb[2]) * 0.311_146_94;
    let delta = 0.5053 * y * y + 0.299 * i * i + 0.1957 * q * q;
    if y > 0.0 { -delta } else { delta }
}

/// Brightness difference `a - b`.
fn luma_delta(a: &Rgba<u8>, b: &Rgba<u8>) -> f32 {
    luma(over_white(a)) - luma(over_white(b))
}

/// The 3x3 neighbourhood of `(x, y)` clipped to the image, without the centre,
/// and whether the pixel lies on the image border.
fn neighbours(img: &RgbaImage, x: u32, y: u32) -> (impl Iterator<Item = (u32, u32)>, bool) {
    let (w, h) = img.dimensions();
    let (x0, x1) = (x.saturating_sub(1), (x + 1).min(w - 1));
    let (y0, y1) = (y.saturating_sub(1), (y + 1).min(h - 1));
    let on_border = x == x0 || x == x1 || y == y0 || y == y1;
    let iter = (y0..=y1)
        .flat_map(move |ny| (x0..=x1).map(move |nx| (nx, ny)))
        .filter(move |&(nx, ny)| (nx, ny) != (x, y));
    (iter, on_border)
}

/// Whether more than two neighbours of `(x, y)` in `img` equal it exactly.
fn has_many_siblings(img: &RgbaImage, x: u32, y: u32) -> bool {
    let centre = img.get_pixel(x, y);
    let (around, on_border) = neighbours(img, x, y);
    let same = around
        .filter(|&(nx, ny)| img.get_pixel(nx, ny) == centre)
        .count();
    same + usize::from(on_border) > 2
}

/// Whether `(x, y)` of `img` looks like an anti-aliased edge pixel: its
/// neighbours include both darker and brighter ones, at most two equal it,
/// and the darkest or the brightest neighbour has many identical siblings in
/// both `img` and `other`.
fn is_antialiased(img: &RgbaImage, other: &RgbaImage, x: u32, y: u32) -> bool {
    let centre = img.get_pixel(x, y);
    let (around, on_border) = neighbours(img, x, y);
    let mut equal = usize::from(on_border);
    let (mut darkest, mut brightest) = ((0.0f32, (x, y)), (0.0f32, (x, y)));
    for (nx, ny) in around {
        let delta = luma_delta(centre, img.get_pixel(nx, ny));
        if delta == 0.0 {
            equal += 1;
            if equal > 2 {
                return false;
            }
        } else if delta < darkest.0 {
            darkest = (delta, (nx, ny));
        } else if delta > brightest.0 {
            brightest = (delta, (nx, ny));
        }
    }
    if darkest.0 == 0.0 || brightest.0 == 0.0 {
        return false;
    }
    let siblings_in_both =
        |(px, py): (u32, u32)| has_many_siblings(img, px, py) && has_many_siblings(other, px, py);
    siblings_in_both(darkest.1) || siblings_in_both(brightest.1)
}

/// Compares two images of equal size with a `threshold` in 0..=1 on the YIQ
/// delta (0.1 is pixelmatch's default).
pub(crate) fn compare(expected: &RgbaImage, actual: &RgbaImage, threshold: f32) -> Comparison {
    debug_assert_eq!(expected.dimensions(), actual.dimensions());
    let max_delta_allowed = MAX_YIQ_DELTA * threshold * threshold;
    let mut diff_image = RgbaImage::new(expected.width(), expected.height());
    let (mut diff_pixels, mut aa_pixels, mut max_delta) = (0, 0, 0.0f32);
    for (x, y, e) in expected.enumerate_pixels() {
        let a = actual.get_pixel(x, y);
        let delta = if e == a { 0.0 } else { yiq_delta(e, a).abs() };
        max_delta = max_delta.max(delta);
        let marker = if delta <= max_delta_allowed {
            let faded = (255.0 + (luma(over_white(e)) - 255.0) * 0.1) as u8;
            Rgba([faded, faded, faded, 255])
        } else if is_antialiased(expected, actual, x, y) || is_antialiased(actual, expected, x, y) {
            aa_pixels += 1;
            AA_COLOR
        } else {
            diff_pixels += 1;
            DIFF_COLOR
        };
        diff_image.put_pixel(x, y, marker);
    }
    Comparison {
        diff_pixels,
        aa_pixels,
        max_delta: (max_delta / MAX_YIQ_DELTA).sqrt(),
        diff_image,
    }
}
