//! The raster path: how triangles become pixels.
//!
//! 1. **Vertices.** Each piece of geometry (a terrain patch at its level of
//!    detail, a run of a mesh's triangles, the clipped grass blades) gives
//!    its vertices in clip space with a display colour, already lit and
//!    fogged ([`ClipVertex`]); the terrain also gives the part of it the sun
//!    adds, for caster shadows resolved per pixel.
//! 2. **Vertex pass.** [`TriangleBatch::build`] projects every vertex once:
//!    its 16.8 fixed-point pixel position, `1/w`, colour / w and sun part / w
//!    ([`triangle::ScreenVertex`]), its outcode ([`clip`]) and, in a batch
//!    with a sun part, its light coordinates ([`PixelShadow::light_point`]).
//! 3. **Set-up.** Each triangle outside one frustum plane is dropped; one
//!    crossing the near plane or the guard band is clipped into a fan. Then
//!    [`triangle::Triangle::set_up`] drops the culled facing, winds it clockwise, clips
//!    its pixel box to the screen and derives its three integer edge
//!    functions (top-left rule: shared edges draw each pixel once) and the
//!    planes of `1/w` and colour / w. A triangle with a sun part that a
//!    caster may shade ([`PixelShadow::may_shade`]) also gets the plane of
//!    its sun part / w.
//! 4. **Binning.** Kept triangles are listed, in submission order, in every
//!    band of [`BAND_ROWS`] rows their box touches ([`BandBins`]).
//! 5. **Fill.** The frame ([`crate::render::Renderer`]) clears each band to
//!    the sky and fills it with the batches' triangles in scene order
//!    (terrain, meshes), after the grass (so ground the grass hides fails
//!    the depth test before it is shaded). Per row, a triangle's covered run
//!    comes from its edge functions; per pixel, the nearer `1/w` wins and the
//!    colour is colour / w over `1/w`, less the sun part the shadow map says
//!    is hidden at the pixel's light coordinates (from its position and
//!    `w`) for a triangle with a sun plane.
//!
//! Batches are built in parallel and bands are filled in parallel, but every
//! pixel meets the same triangles in the same order whatever the number of
//! threads, so frames are the same, byte for byte. Grass blades have their
//! own span rasterizer ([`crate::render::grass`]) fed through the same bands.

mod band;
mod batch;
mod clip;
mod pixel_shadow;
mod triangle;
mod viewport;

pub(crate) use band::{BAND_ROWS, Band, BandBins};
pub(crate) use batch::{TriangleBatch, TriangleGroup};
pub(crate) use clip::{ClipVertex, OUT_FRUSTUM, OUT_GUARD, OUT_NEAR, outcode};
pub(crate) use pixel_shadow::PixelShadow;
pub(crate) use triangle::to_u8;
pub use viewport::CullMode;
pub(crate) use viewport::Viewport;
