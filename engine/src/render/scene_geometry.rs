//! What a frame asks of the geometry it draws (terrain, mesh instances):
//! screen batches to fill band by band, or the same triangles drawn at once;
//! and [`FrameView`], how the frame sees them.

use glam::Mat4;
use rayon::prelude::*;

use super::Camera;
use super::batch::{BatchTarget, ScreenBatch, Viewport};
use super::batch_pool::BatchPool;
use super::frame::FrameStats;
use super::kernels::Kernels;
use super::raster::Band;
use super::shading::Lighting;

/// How a frame sees its scene: the camera, the light, the viewport and the
/// machine code of the hot kernels.
#[derive(Clone, Copy)]
pub(crate) struct FrameView<'a> {
    /// The camera.
    pub camera: &'a Camera,
    /// Its world-to-clip matrix.
    pub view_proj: Mat4,
    /// Sun, sky and fog.
    pub lighting: &'a Lighting,
    /// The image's size.
    pub vp: Viewport,
    /// The machine code of the hot kernels.
    pub kernels: Kernels,
}

impl<'a> FrameView<'a> {
    /// The view of `camera` with `lighting` over viewport `vp`.
    pub fn new(camera: &'a Camera, lighting: &'a Lighting, vp: Viewport, kernels: Kernels) -> Self {
        FrameView {
            camera,
            view_proj: camera.view_proj(),
            lighting,
            vp,
            kernels,
        }
    }
}

/// Scene geometry a frame draws, in scene order, cut into pieces of one
/// batch each. Implementors say what their pieces are and how one is set up;
/// the provided methods set up all of them, binned or drawn at once.
pub(crate) trait SceneGeometry: Sync {
    /// One batch's worth of the geometry (a terrain patch at its level, a
    /// run of a mesh's triangles).
    type Piece: Sync;

    /// The pieces `view` may see, in drawing order.
    fn pieces(&self, view: &FrameView<'_>) -> Vec<Self::Piece>;

    /// Sets up `piece` into `target`. Returns how many triangles were kept
    /// or drawn, or `None` when the piece has nothing to set up (and makes
    /// no batch).
    fn build(
        &self,
        piece: &Self::Piece,
        view: &FrameView<'_>,
        target: BatchTarget<'_, '_>,
    ) -> Option<usize>;

    /// Screen batches in drawing order, one per piece, built in parallel
    /// from `pool`'s spares, to be filled band by band.
    fn batches(&self, view: &FrameView<'_>, pool: &BatchPool) -> Vec<ScreenBatch> {
        self.pieces(view)
            .par_iter()
            .filter_map(|piece| {
                let mut batch = pool.take();
                self.build(piece, view, BatchTarget::Binned(&mut batch))?;
                Some(batch)
            })
            .collect()
    }

    /// The same triangles drawn into `frame` (cleared, all of the image's
    /// rows) as they are set up, with `scratch`'s buffers. Adds to `stats`
    /// the batches and triangles [`SceneGeometry::batches`] would have made.
    fn draw_at_once(
        &self,
        view: &FrameView<'_>,
        scratch: &mut ScreenBatch,
        frame: &mut Band<'_>,
        stats: &mut FrameStats,
    ) {
        for piece in &self.pieces(view) {
            let target = BatchTarget::AtOnce {
                scratch: &mut *scratch,
                frame: &mut *frame,
            };
            if let Some(drawn) = self.build(piece, view, target) {
                stats.batches += 1;
                stats.triangles += drawn;
            }
        }
    }
}
