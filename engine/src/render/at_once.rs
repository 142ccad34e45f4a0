//! Triangles drawn the moment they are set up: how a frame drawn on one
//! thread skips keeping them.

use super::raster::{Band, Dot, Edges, PixelSpan, Triangle};
use super::set_up::TriangleSink;

/// A [`TriangleSink`] that draws each triangle into a frame as soon as it is
/// set up, instead of keeping it to draw band by band later.
///
/// On one thread, keeping triangles only costs time: writing them out,
/// binning them and reading them back. Every pixel still meets the frame's
/// triangles in the order it would band by band (scene order, then
/// submission order), so the image is the same, bit for bit.
pub(crate) struct DrawnAtOnce<'t, 'f> {
    /// The frame, as one band of all its rows.
    frame: &'t mut Band<'f>,
    /// Scratch for the edge functions of big triangles.
    edges: &'t mut Vec<Edges>,
    /// Triangles drawn so far, dots included.
    drawn: usize,
}

impl<'t, 'f> DrawnAtOnce<'t, 'f> {
    /// Draws into `frame` (already cleared), with `edges` as scratch.
    pub fn new(frame: &'t mut Band<'f>, edges: &'t mut Vec<Edges>) -> DrawnAtOnce<'t, 'f> {
        edges.clear();
        DrawnAtOnce {
            frame,
            edges,
            drawn: 0,
        }
    }

    /// How many triangles (dots included) were drawn.
    pub fn drawn(&self) -> usize {
        self.drawn
    }
}

impl TriangleSink for DrawnAtOnce<'_, '_> {
    #[inline(always)]
    fn edges(&mut self) -> &mut Vec<Edges> {
        self.edges
    }

    #[inline(always)]
    fn triangle(&mut self, tri: Triangle, _span: PixelSpan) {
        tri.draw(self.edges, self.frame);
        self.drawn += 1;
    }

    #[inline(always)]
    fn dot(&mut self, dot: Dot) {
        dot.draw(self.frame);
        self.drawn += 1;
    }
}
