//! Text drawing with an embedded DejaVu Sans font (rasterized by `fontdue`).
//!
//! Text is laid out on whole pixels, so the same string at the same position
//! always gives the same pixels.

use std::sync::OnceLock;

/// DejaVu Sans (Bitstream Vera license, see `assets/fonts/LICENSE-DejaVu.txt`).
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The parsed font, shared by all text drawing.
fn font() -> &'static fontdue::Font {
    static FONT: OnceLock<fontdue::Font> = OnceLock::new();
    FONT.get_or_init(|| {
        fontdue::Font::from_bytes(FONT_BYTES, fontdue::FontSettings::default())
            .expect("the embedded DejaVu Sans font parses")
    })
}

/// One rasterized glyph placed relative to the top-left corner of the text.
pub(crate) struct PlacedGlyph {
    /// Left edge of the coverage bitmap, in pixels.
    pub left: i32,
    /// Top edge of the coverage bitmap, in pixels.
    pub top: i32,
    /// Bitmap width in pixels.
    pub width: usize,
    /// Bitmap height in pixels.
    pub height: usize,
    /// Row-major coverage, 0 (none) to 255 (full).
    pub coverage: Vec<u8>,
}

/// Vertical distance between two lines of text at `size_px`, in pixels.
pub fn line_height(size_px: f32) -> f32 {
    font()
        .horizontal_line_metrics(size_px)
        .map_or(size_px * 1.2, |m| m.new_line_size.ceil())
}

/// Distance from the top of a line to its baseline at `size_px`, in pixels.
fn ascent(size_px: f32) -> f32 {
    font()
        .horizontal_line_metrics(size_px)
        .map_or(size_px, |m| m.ascent.round())
}

/// Walks the glyphs of `text` (lines split at `\n`), calling `place` with each
/// glyph's pen position (left, baseline) and character; returns the width of
/// the widest line.
fn walk(size_px: f32, text: &str, mut place: impl FnMut(f32, f32, char)) -> f32 {
    let font = font();
    let mut widest = 0.0f32;
    let mut baseline = ascent(size_px);
    for line in text.split('\n') {
        let mut pen = 0.0f32;
        let mut previous = None;
        for c in line.chars() {
            if let Some(kern) = previous.and_then(|p| font.horizontal_kern(p, c, size_px)) {
                pen += kern;
            }
            place(pen, baseline, c);
            pen += font.metrics(c, size_px).advance_width;
            previous = Some(c);
        }
        widest = widest.max(pen);
        baseline += line_height(size_px);
    }
    widest.ceil()
}

/// Width in pixels of the widest line of `text` at `size_px`.
pub fn text_width(size_px: f32, text: &str) -> f32 {
    walk(size_px, text, |_, _, _| {})
}

/// Rasterizes `text` into glyph bitmaps placed relative to its top-left corner.
pub(crate) fn layout(size_px: f32, text: &str) -> (Vec<PlacedGlyph>, f32) {
    let mut glyphs = Vec::new();
    let width = walk(size_px, text, |pen, baseline, c| {
        let (metrics, coverage) = font().rasterize(c, size_px);
        if metrics.width == 0 || metrics.height == 0 {
            return;
        }
        glyphs.push(PlacedGlyph {
            left: (pen + metrics.xmin as f32).round() as i32,
            top: (baseline - metrics.ymin as f32 - metrics.height as f32).round() as i32,
            width: metrics.width,
            height: metrics.height,
            coverage,
        });
    });
    (glyphs, width)
}
