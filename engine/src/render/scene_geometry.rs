//! What a frame asks of the geometry it draws (terrain, mesh instances):
//! screen batches to fill band by band, or the same triangles drawn at once.

use glam::Mat4;

use super::Camera;
use super::batch::{ScreenBatch, Viewport};
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

/// Scene geometry a frame draws, in scene order.
pub(crate) trait SceneGeometry {
    /// Screen batches in drawing order, built in parallel from `pool`'s
    /// spares, to be filled band by band.
    fn batches(&self, view: &FrameView<'_>, pool: &BatchPool) -> Vec<ScreenBatch>;

    /// The same triangles drawn into `frame` (cleared, all of the image's
    /// rows) as they are set up, with `scratch`'s buffers. Returns how many
    /// batches and triangles [`SceneGeometry::batches`] would have made.
    fn draw_at_once(
        &self,
        view: &FrameView<'_>,
        scratch: &mut ScreenBatch,
        frame: &mut Band<'_>,
    ) -> FrameStats;
}
