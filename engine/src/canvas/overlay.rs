//! Anti-aliased 2D drawing (lines, arrows, circles, points, text) on top of
//! a frame, in pixel space or in world space through a projector.
//!
//! Drawing goes through tiny-skia directly on the frame's bytes. tiny-skia
//! works on premultiplied RGBA; opaque frames are premultiplied already, so
//! they are drawn on in place. A frame with translucent pixels is
//! premultiplied when the overlay starts and converted back when it ends.

use glam::{Vec2, Vec3};
use image::{Rgba, RgbaImage};
use tiny_skia::{
    FillRule, LineCap, LineJoin, Paint, PathBuilder, PixmapMut, PixmapPaint, PremultipliedColorU8,
    Stroke, Transform,
};

use super::text;

/// Draws onto an [`RgbaImage`] until dropped.
///
/// Pixel coordinates have their origin at the top-left corner of the image;
/// pixel `(i, j)` covers `[i, i + 1) x [j, j + 1)`, so its centre is at
/// `(i + 0.5, j + 0.5)`.
///
/// ```
/// use engine::glam::Vec2;
/// use engine::canvas::Overlay;
/// use image::{Rgba, RgbaImage};
/// let mut frame = RgbaImage::from_pixel(32, 32, Rgba([255, 255, 255, 255]));
/// {
///     let mut overlay = Overlay::new(&mut frame);
///     overlay.line(Vec2::new(0.0, 16.0), Vec2::new(32.0, 16.0), Rgba([255, 0, 0, 255]), 2.0);
/// }
/// assert_eq!(frame.get_pixel(10, 16), &Rgba([255, 0, 0, 255]));
/// ```
pub struct Overlay<'a> {
    /// `None` for an image without pixels.
    pixmap: Option<PixmapMut<'a>>,
    /// Whether the frame held translucent pixels and was premultiplied.
    premultiplied: bool,
}

/// Converts an 8-bit colour to tiny-skia's paint.
fn paint(color: Rgba<u8>) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color[0], color[1], color[2], color[3]);
    paint.anti_alias = true;
    paint
}

/// A stroke of `width` pixels with round caps and joins.
fn stroke(width: f32) -> Stroke {
    Stroke {
        width: width.max(0.0),
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..Stroke::default()
    }
}

/// Length of an arrow head for a shaft of `length` drawn `width` pixels wide.
fn arrow_head_length(length: f32, width: f32) -> f32 {
    (4.0 * width + 4.0).min(0.5 * length)
}

impl<'a> Overlay<'a> {
    /// Starts drawing on `image`. An image without pixels gets an overlay that
    /// draws nothing.
    pub fn new(image: &'a mut RgbaImage) -> Self {
        let (width, height) = image.dimensions();
        let bytes: &'a mut [u8] = image;
        let premultiplied = bytes.chunks_exact(4).any(|px| px[3] != 255);
        if premultiplied {
            for px in bytes.chunks_exact_mut(4) {
                let a = u16::from(px[3]);
                for c in &mut px[..3] {
                    *c = ((u16::from(*c) * a + 127) / 255) as u8;
                }
            }
        }
        Self {
            pixmap: PixmapMut::from_bytes(bytes, width, height),
            premultiplied,
        }
    }

    /// Strokes the path built by `build` with `color` and `width` pixels.
    fn stroke_with(&mut self, color: Rgba<u8>, width: f32, build: impl FnOnce(&mut PathBuilder)) {
        let Some(pixmap) = self.pixmap.as_mut() else {
            return;
        };
        let mut builder = PathBuilder::new();
        build(&mut builder);
        if let Some(path) = builder.finish() {
            pixmap.stroke_path(
                &path,
                &paint(color),
                &stroke(width),
                Transform::identity(),
                None,
            );
        }
    }

    /// Fills the closed path built by `build` with `color`.
    fn fill_with(&mut self, color: Rgba<u8>, build: impl FnOnce(&mut PathBuilder)) {
        let Some(pixmap) = self.pixmap.as_mut() else {
            return;
        };
        let mut builder = PathBuilder::new();
        build(&mut builder);
        if let Some(path) = builder.finish() {
            pixmap.fill_path(
                &path,
                &paint(color),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }

    /// A straight line from `a` to `b`, `width` pixels wide, with round caps.
    pub fn line(&mut self, a: Vec2, b: Vec2, color: Rgba<u8>, width: f32) {
        self.polyline(&[a, b], color, width);
    }

    /// Connected line segments through `points` (nothing for fewer than two).
    pub fn polyline(&mut self, points: &[Vec2], color: Rgba<u8>, width: f32) {
        let [first, rest @ ..] = points else {
            return;
        };
        if rest.is_empty() {
            return;
        }
        self.stroke_with(color, width, |pb| {
            pb.move_to(first.x, first.y);
            for p in rest {
                pb.line_to(p.x, p.y);
            }
        });
    }

    /// An arrow from `from` to `to` with a filled head at `to`. The head grows
    /// with the width and never takes more than half the arrow.
    pub fn arrow(&mut self, from: Vec2, to: Vec2, color: Rgba<u8>, width: f32) {
        let shaft = to - from;
        let length = shaft.length();
        if length <= f32::EPSILON {
            return;
        }
        let dir = shaft / length;
        let head = arrow_head_length(length, width);
        let base = to - dir * head;
        self.line(from, base, color, width);
        let side = dir.perp() * (0.5 * head + 0.5 * width);
        self.fill_with(color, |pb| {
            pb.move_to(to.x, to.y);
            pb.line_to(base.x + side.x, base.y + side.y);
            pb.line_to(base.x - side.x, base.y - side.y);
            pb.close();
        });
    }

    /// A circle outline of `radius` pixels around `center`, `width` pixels wide.
    pub fn circle(&mut self, center: Vec2, radius: f32, color: Rgba<u8>, width: f32) {
        if radius > 0.0 {
            self.stroke_with(color, width, |pb| {
                pb.push_circle(center.x, center.y, radius)
            });
        }
    }

    /// A filled disc of `radius` pixels around `center`.
    pub fn fill_circle(&mut self, center: Vec2, radius: f32, color: Rgba<u8>) {
        if radius > 0.0 {
            self.fill_with(color, |pb| pb.push_circle(center.x, center.y, radius));
        }
    }

    /// A point marker: a filled disc `size` pixels across.
    pub fn point(&mut self, p: Vec2, color: Rgba<u8>, size: f32) {
        self.fill_circle(p, 0.5 * size, color);
    }

    /// A filled axis-aligned rectangle with corner `min` and the given size.
    pub fn fill_rect(&mut self, min: Vec2, size: Vec2, color: Rgba<u8>) {
        if size.x > 0.0 && size.y > 0.0 {
            self.fill_with(color, |pb| {
                pb.push_rect(
                    tiny_skia::Rect::from_xywh(min.x, min.y, size.x, size.y)
                        .expect("a rectangle with positive size"),
                )
            });
        }
    }

    /// An axis-aligned rectangle outline with corner `min` and the given size.
    pub fn rect(&mut self, min: Vec2, size: Vec2, color: Rgba<u8>, width: f32) {
        let max = min + size;
        self.stroke_with(color, width, |pb| {
            pb.move_to(min.x, min.y);
            pb.line_to(max.x, min.y);
            pb.line_to(max.x, max.y);
            pb.line_to(min.x, max.y);
            pb.close();
        });
    }

    /// Text with its top-left corner at `top_left`, `size_px` high (see
    /// [`draw_text`]). Returns the width of the widest line in pixels.
    pub fn text(&mut self, top_left: Vec2, size_px: f32, color: Rgba<u8>, text: &str) -> f32 {
        let (glyphs, width) = text::layout(size_px, text);
        let Some(pixmap) = self.pixmap.as_mut() else {
            return width;
        };
        let origin = top_left.round();
        let alpha = u32::from(color[3]);
        for glyph in glyphs {
            let Some(mut bitmap) = tiny_skia::Pixmap::new(glyph.width as u32, glyph.height as u32)
            else {
                continue;
            };
            for (dst, &coverage) in bitmap.pixels_mut().iter_mut().zip(&glyph.coverage) {
                let a = ((u32::from(coverage) * alpha + 127) / 255) as u8;
                let premul = |c: u8| ((u32::from(c) * u32::from(a) + 127) / 255) as u8;
                *dst = PremultipliedColorU8::from_rgba(
                    premul(color[0]),
                    premul(color[1]),
                    premul(color[2]),
                    a,
                )
                .expect("premultiplied channels never exceed alpha");
            }
            pixmap.draw_pixmap(
                origin.x as i32 + glyph.left,
                origin.y as i32 + glyph.top,
                bitmap.as_ref(),
                &PixmapPaint::default(),
                Transform::identity(),
                None,
            );
        }
        width
    }

    /// Text on a filled box (padded by a quarter of the text size), readable
    /// on any background. Returns the box size in pixels.
    pub fn label(
        &mut self,
        top_left: Vec2,
        size_px: f32,
        color: Rgba<u8>,
        background: Rgba<u8>,
        text: &str,
    ) -> Vec2 {
        let pad = (0.25 * size_px).round();
        let lines = text.split('\n').count() as f32;
        let size = Vec2::new(
            text::text_width(size_px, text) + 2.0 * pad,
            lines * text::line_height(size_px) + 2.0 * pad,
        );
        self.fill_rect(top_left, size, background);
        self.text(top_left + Vec2::splat(pad), size_px, color, text);
        size
    }

    /// A line between two world points; skipped if either end cannot be projected.
    pub fn world_line(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        a: Vec3,
        b: Vec3,
        color: Rgba<u8>,
        width: f32,
    ) {
        if let (Some(a), Some(b)) = (project(a), project(b)) {
            self.line(a, b, color, width);
        }
    }

    /// A polyline through world points; a segment with an unprojectable end is
    /// skipped, breaking the line there.
    pub fn world_polyline(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        points: &[Vec3],
        color: Rgba<u8>,
        width: f32,
    ) {
        let projected: Vec<Option<Vec2>> = points.iter().map(|&p| project(p)).collect();
        for run in projected.split(Option::is_none) {
            let run: Vec<Vec2> = run.iter().flatten().copied().collect();
            self.polyline(&run, color, width);
        }
    }

    /// An arrow between two world points (torques, velocities, rays);
    /// skipped if either end cannot be projected.
    pub fn world_arrow(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        from: Vec3,
        to: Vec3,
        color: Rgba<u8>,
        width: f32,
    ) {
        if let (Some(a), Some(b)) = (project(from), project(to)) {
            self.arrow(a, b, color, width);
        }
    }

    /// A circle outline of `radius_px` screen pixels around a world point
    /// (centre of mass, IK targets); skipped if the point cannot be projected.
    pub fn world_circle(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        center: Vec3,
        radius_px: f32,
        color: Rgba<u8>,
        width: f32,
    ) {
        if let Some(c) = project(center) {
            self.circle(c, radius_px, color, width);
        }
    }

    /// A point marker `size_px` across at a world point; skipped if it cannot
    /// be projected.
    pub fn world_point(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        p: Vec3,
        color: Rgba<u8>,
        size_px: f32,
    ) {
        if let Some(p) = project(p) {
            self.point(p, color, size_px);
        }
    }

    /// Text whose top-left corner sits `offset_px` from a projected world point;
    /// skipped if the point cannot be projected.
    pub fn world_text(
        &mut self,
        project: &impl Fn(Vec3) -> Option<Vec2>,
        anchor: Vec3,
        offset_px: Vec2,
        size_px: f32,
        color: Rgba<u8>,
        text: &str,
    ) {
        if let Some(p) = project(anchor) {
            self.text(p + offset_px, size_px, color, text);
        }
    }
}

impl Drop for Overlay<'_> {
    /// Converts a frame that held translucent pixels back to straight alpha.
    fn drop(&mut self) {
        if let (true, Some(pixmap)) = (self.premultiplied, self.pixmap.as_mut()) {
            for px in pixmap.data_mut().chunks_exact_mut(4) {
                let a = u16::from(px[3]);
                if a != 0 && a != 255 {
                    for c in &mut px[..3] {
                        *c = ((u16::from(*c) * 255 + a / 2) / a).min(255) as u8;
                    }
                }
            }
        }
    }
}

/// Draws `text` with its top-left corner at (`x`, `y`) pixels, `size_px` high,
/// blending `color` by glyph coverage. Lines are split at `\n`. Returns the
/// width of the widest line in pixels.
///
/// ```
/// use image::{Rgba, RgbaImage};
/// let mut img = RgbaImage::from_pixel(80, 20, Rgba([255, 255, 255, 255]));
/// let width = engine::canvas::draw_text(&mut img, 2.0, 2.0, 12.0, Rgba([0, 0, 0, 255]), "step 42");
/// assert!(width > 30.0 && width < 60.0);
/// assert!(img.pixels().any(|p| p[0] < 128));
/// ```
pub fn draw_text(
    image: &mut RgbaImage,
    x: f32,
    y: f32,
    size_px: f32,
    color: Rgba<u8>,
    text: &str,
) -> f32 {
    Overlay::new(image).text(Vec2::new(x, y), size_px, color, text)
}
