//! A frame: everything drawn in one image, and the [`Renderer`] that draws it.

use std::sync::{Arc, Mutex};

use glam::Vec3;
use image::RgbaImage;
use multiversion::multiversion;
use rayon::prelude::*;

use super::Camera;
use super::batch::{BAND_ROWS, ScreenBatch, Viewport};
use super::batch_pool::BatchPool;
use super::error::RenderError;
use super::grass::{GrassBlade, GrassLayer};
use super::kernels::{Kernels, run_baseline};
use super::mesh::MeshInstance;
use super::raster::{Band, to_u8};
use super::scene_geometry::{FrameView, SceneGeometry};
use super::shading::Lighting;
use super::terrain::TerrainRenderer;

/// Everything drawn in one frame.
#[derive(Debug, Clone, Copy)]
pub struct FrameScene<'a> {
    /// The ground, already [`TerrainRenderer::update`]d.
    pub terrain: Option<&'a TerrainRenderer>,
    /// Meshes (characters, props).
    pub meshes: &'a [MeshInstance<'a>],
    /// Grass blades.
    pub blades: &'a [GrassBlade],
    /// Sun, sky and fog.
    pub lighting: Lighting,
}

impl<'a> FrameScene<'a> {
    /// An empty scene (sky only) with default lighting.
    pub fn new() -> FrameScene<'a> {
        FrameScene {
            terrain: None,
            meshes: &[],
            blades: &[],
            lighting: Lighting::default(),
        }
    }
}

impl Default for FrameScene<'_> {
    fn default() -> Self {
        FrameScene::new()
    }
}

/// What one frame sent to the rasterizer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameStats {
    /// Screen batches (visible terrain patches, mesh parts; grass is one layer
    /// beside them).
    pub batches: usize,
    /// Triangles set up after culling and clipping: those covering at least one
    /// pixel centre (grass: blade pieces, a quad or a tip each).
    pub triangles: usize,
}

/// Draws [`FrameScene`]s into `width` x `height` RGBA images.
///
/// Geometry is projected per batch (terrain patch, mesh part, group of blades)
/// in parallel; then the screen is cut into fixed bands of rows, rasterized in
/// parallel, each band drawing the batches in scene order. On a one-thread
/// pool, terrain and mesh triangles are instead drawn as they are set up,
/// with nothing kept to draw later. The image is bit-identical whatever the
/// number of threads.
///
/// A renderer keeps its per-frame buffers (the depth buffer and the screen
/// batches, with their projected vertices, set-up triangles and band lists)
/// from frame to frame: render many frames with one renderer. Clones share
/// them.
#[derive(Debug, Clone)]
pub struct Renderer {
    width: u32,
    height: u32,
    pool: Option<Arc<rayon::ThreadPool>>,
    /// The depth buffer kept between frames (saves allocating and faulting in
    /// a fresh one per frame); a frame that finds it busy allocates its own.
    depth: Arc<Mutex<Vec<f32>>>,
    /// The screen batches kept between frames, for the same reason.
    batches: Arc<BatchPool>,
    /// The machine code of the hot kernels.
    kernels: Kernels,
}

impl Renderer {
    /// A renderer using the ambient rayon pool.
    pub fn new(width: u32, height: u32) -> Result<Renderer, RenderError> {
        let pixels = (width as u64) * (height as u64);
        if width == 0 || height == 0 || width > 16384 || height > 16384 {
            return Err(RenderError::InvalidParameter {
                name: "size",
                reason: format!("{width} x {height} ({pixels} pixels) must be 1..=16384 per side"),
            });
        }
        Ok(Renderer {
            width,
            height,
            pool: None,
            depth: Arc::default(),
            batches: Arc::default(),
            kernels: Kernels::default(),
        })
    }

    /// The same renderer with its own pool of `threads` threads.
    pub fn with_threads(mut self, threads: usize) -> Result<Renderer, RenderError> {
        if threads == 0 {
            return Err(RenderError::InvalidParameter {
                name: "threads",
                reason: "at least one thread is needed".into(),
            });
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| RenderError::ThreadPool {
                threads,
                reason: e.to_string(),
            })?;
        self.pool = Some(Arc::new(pool));
        Ok(self)
    }

    /// The same renderer running its hot kernels with `kernels`.
    #[cfg(test)]
    pub(crate) fn with_kernels(mut self, kernels: Kernels) -> Renderer {
        self.kernels = kernels;
        self
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Renders one frame. The camera's viewport should match the renderer's size
    /// (its aspect ratio is used for the projection).
    pub fn render(&self, scene: &FrameScene<'_>, camera: &Camera) -> RgbaImage {
        self.render_with_stats(scene, camera).0
    }

    /// Renders one frame and says how much geometry reached the rasterizer.
    pub fn render_with_stats(
        &self,
        scene: &FrameScene<'_>,
        camera: &Camera,
    ) -> (RgbaImage, FrameStats) {
        let mut image = RgbaImage::new(self.width, self.height);
        let stats = self.draw(scene, camera, &mut image);
        (image, stats)
    }

    /// Renders one frame into `image`, which must have the renderer's size,
    /// overwriting every pixel: a loop drawing frame after frame into one
    /// image allocates no image per frame. Says how much geometry reached
    /// the rasterizer.
    ///
    /// ```
    /// use engine::glam::Vec3;
    /// use engine::render::{Camera, FrameScene, RenderError, Renderer};
    /// use image::RgbaImage;
    ///
    /// let renderer = Renderer::new(64, 48).unwrap();
    /// let camera = Camera::perspective(1.0, 64, 48, 0.05, 100.0)
    ///     .unwrap()
    ///     .look_at(Vec3::new(0.0, 1.0, -3.0), Vec3::ZERO, Vec3::Y);
    /// let mut image = RgbaImage::new(64, 48);
    /// for _ in 0..3 {
    ///     renderer.render_into(&FrameScene::new(), &camera, &mut image).unwrap();
    /// }
    /// assert_eq!(image, renderer.render(&FrameScene::new(), &camera));
    /// let mut wrong = RgbaImage::new(48, 64);
    /// let refused = renderer.render_into(&FrameScene::new(), &camera, &mut wrong);
    /// assert!(matches!(refused, Err(RenderError::InvalidParameter { name: "image", .. })));
    /// ```
    pub fn render_into(
        &self,
        scene: &FrameScene<'_>,
        camera: &Camera,
        image: &mut RgbaImage,
    ) -> Result<FrameStats, RenderError> {
        if image.dimensions() != (self.width, self.height) {
            let (w, h) = image.dimensions();
            return Err(RenderError::InvalidParameter {
                name: "image",
                reason: format!(
                    "a {w} x {h} image for a {} x {} renderer",
                    self.width, self.height
                ),
            });
        }
        Ok(self.draw(scene, camera, image))
    }

    /// Draws a frame into `image` (of the renderer's size), on the
    /// renderer's pool if it has one.
    fn draw(&self, scene: &FrameScene<'_>, camera: &Camera, image: &mut RgbaImage) -> FrameStats {
        match &self.pool {
            Some(pool) => pool.install(|| self.render_here(scene, camera, image)),
            None => self.render_here(scene, camera, image),
        }
    }

    fn render_here(
        &self,
        scene: &FrameScene<'_>,
        camera: &Camera,
        image: &mut RgbaImage,
    ) -> FrameStats {
        let vp = Viewport {
            width: self.width as i32,
            height: self.height as i32,
        };
        let view = FrameView::new(camera, &scene.lighting, vp, self.kernels);
        if rayon::current_num_threads() == 1 {
            return self.render_at_once(&view, scene, image);
        }
        // Terrain and meshes project while the grass layer builds (its blade
        // sort and binning are serial), and the sky rows beside them: one
        // barrier instead of three before the bands.
        let ((batches, sky_rows), grass) = rayon::join(
            || rayon::join(|| self.project(&view, scene), || sky_rows(&view)),
            // Grass: its own pass per band, after terrain and meshes.
            || grass_layer(&view, scene),
        );
        let stats = FrameStats {
            batches: batches.len(),
            triangles: batches.iter().map(ScreenBatch::len).sum::<usize>() + grass.len(),
        };
        let w = self.width as usize;
        let band_rows = BAND_ROWS as usize;
        self.with_depth(|depth| {
            // Every band clears its own rows (colour and depth), while they
            // are in cache.
            image
                .par_chunks_mut(w * 4 * band_rows)
                .zip(depth.par_chunks_mut(w * band_rows))
                .enumerate()
                // One band per job: a thread that runs out of bands steals a
                // single band, not half of a run of them, so both finish
                // together.
                .with_max_len(1)
                .for_each(|(b, (color, depth))| {
                    let band = BandJob {
                        index: b as i32,
                        color,
                        depth,
                        sky_rows: Some(&sky_rows),
                    };
                    self.fill_band(band, &batches, &grass, vp);
                });
        });
        self.batches.give_back(batches);
        stats
    }

    /// [`Renderer::render_here`] on one thread: the frame is cleared, then
    /// terrain and meshes are drawn as they are set up ([`DrawnAtOnce`]),
    /// then the grass band by band. No band would run in parallel with
    /// another, so nothing is kept to draw later; every pixel meets the same
    /// triangles in the same order, so the image is the same.
    ///
    /// [`DrawnAtOnce`]: super::at_once::DrawnAtOnce
    fn render_at_once(
        &self,
        view: &FrameView<'_>,
        scene: &FrameScene<'_>,
        image: &mut RgbaImage,
    ) -> FrameStats {
        let vp = view.vp;
        let sky_rows = sky_rows(view);
        let grass = grass_layer(view, scene);
        let mut scratch = self.batches.take();
        let mut stats = FrameStats {
            batches: 0,
            triangles: grass.len(),
        };
        let w = self.width as usize;
        self.with_depth(|depth| {
            clear_to_sky(image, depth, &sky_rows, w);
            let mut frame = Band {
                color: image,
                depth,
                width: vp.width,
                y0: 0,
                y1: vp.height,
            };
            if let Some(terrain) = scene.terrain {
                terrain.draw_at_once(view, &mut scratch, &mut frame, &mut stats);
            }
            for mesh in scene.meshes {
                mesh.draw_at_once(view, &mut scratch, &mut frame, &mut stats);
            }
            let band_rows = BAND_ROWS as usize;
            let bands = image
                .chunks_mut(w * 4 * band_rows)
                .zip(depth.chunks_mut(w * band_rows));
            for (b, (color, depth)) in bands.enumerate() {
                let band = BandJob {
                    index: b as i32,
                    color,
                    depth,
                    sky_rows: None,
                };
                self.fill_band(band, &[], &grass, vp);
            }
        });
        self.batches.give_back(vec![scratch]);
        stats
    }

    /// Runs `draw` with the frame's depth buffer (the kept one, unless
    /// another frame holds it), sized for the frame, its contents stale.
    fn with_depth<R>(&self, draw: impl FnOnce(&mut [f32]) -> R) -> R {
        let mut cached = self.depth.try_lock().ok();
        let mut own = Vec::new();
        let depth = cached.as_deref_mut().unwrap_or(&mut own);
        depth.resize(self.width as usize * self.height as usize, 0.0);
        draw(depth)
    }

    /// Fills a band ([`fill_band`]) in the renderer's machine code.
    fn fill_band(
        &self,
        band: BandJob<'_>,
        batches: &[ScreenBatch],
        grass: &GrassLayer,
        vp: Viewport,
    ) {
        match self.kernels {
            Kernels::Dispatched => fill_band_dispatched(band, batches, grass, vp),
            Kernels::Baseline => run_baseline(|| fill_band(band, batches, grass, vp)),
        }
    }

    /// All screen batches in drawing order: terrain, meshes (grass is drawn after them).
    fn project(&self, view: &FrameView<'_>, scene: &FrameScene<'_>) -> Vec<ScreenBatch> {
        let (mut batches, meshes) = rayon::join(
            || match scene.terrain {
                Some(t) => t.batches(view, &self.batches),
                None => Vec::new(),
            },
            || -> Vec<Vec<ScreenBatch>> {
                scene
                    .meshes
                    .par_iter()
                    .map(|m| m.batches(view, &self.batches))
                    .collect()
            },
        );
        batches.extend(meshes.into_iter().flatten());
        batches
    }
}

/// Sky colour per row, from the view direction through the row's centre.
fn sky_rows(view: &FrameView<'_>) -> Vec<Vec3> {
    let inv = view.view_proj.inverse();
    let height = view.vp.height;
    (0..height)
        .map(|y| {
            let ndc_y = 1.0 - 2.0 * (y as f32 + 0.5) / height as f32;
            let far = inv.project_point3(Vec3::new(0.0, ndc_y, 1.0));
            let dir = (far - view.camera.eye).normalize_or_zero();
            view.lighting.sky(dir.y)
        })
        .collect()
}

/// The scene's blades as seen by `view`, binned by bands.
fn grass_layer(view: &FrameView<'_>, scene: &FrameScene<'_>) -> GrassLayer {
    GrassLayer::build(
        scene.blades,
        view.camera,
        view.lighting,
        view.vp,
        view.kernels,
    )
}

/// One band's share of the frame buffers.
struct BandJob<'a> {
    /// Band index (rows `index * BAND_ROWS ..`).
    index: i32,
    /// The band's RGBA8 rows.
    color: &'a mut [u8],
    /// The band's depth rows.
    depth: &'a mut [f32],
    /// The sky colour of every row of the frame, to clear the band to
    /// first; `None` when it is cleared already.
    sky_rows: Option<&'a [Vec3]>,
}

/// [`fill_band`] in the best machine code for the CPU (see [`Kernels`]).
#[multiversion(targets("x86_64+avx2"))]
fn fill_band_dispatched(
    job: BandJob<'_>,
    batches: &[ScreenBatch],
    grass: &GrassLayer,
    vp: Viewport,
) {
    fill_band(job, batches, grass, vp);
}

/// Clears a band to the sky and empty depth (unless it is cleared already),
/// then draws the batches and the grass touching it, in scene order.
#[inline(always)]
fn fill_band(job: BandJob<'_>, batches: &[ScreenBatch], grass: &GrassLayer, vp: Viewport) {
    let BandJob {
        index,
        color,
        depth,
        sky_rows,
    } = job;
    let w = vp.width as usize;
    let y0 = index * BAND_ROWS;
    let y1 = y0 + (depth.len() / w) as i32;
    if let Some(sky_rows) = sky_rows {
        clear_to_sky(color, depth, &sky_rows[y0 as usize..], w);
    }
    let mut band = Band {
        color,
        depth,
        width: vp.width,
        y0,
        y1,
    };
    for batch in batches {
        batch.draw_band(index, &mut band);
    }
    grass.draw_band(index, &mut band);
}

/// Clears rows of a frame `width` pixels wide to empty depth and to the sky
/// colour of each (`sky_rows` from the first row on).
fn clear_to_sky(color: &mut [u8], depth: &mut [f32], sky_rows: &[Vec3], width: usize) {
    depth.fill(0.0);
    for (row, sky) in color.chunks_mut(width * 4).zip(sky_rows) {
        let px = [to_u8(sky.x), to_u8(sky.y), to_u8(sky.z), 255];
        fill_row(row, px);
    }
}

/// Fills an RGBA8 row with one pixel value: the first pixel, then doubling
/// copies (a few `memcpy`s per row instead of one 4-byte store per pixel).
fn fill_row(row: &mut [u8], px: [u8; 4]) {
    let Some(first) = row.get_mut(..4) else {
        return;
    };
    first.copy_from_slice(&px);
    let mut filled = 4;
    while filled < row.len() {
        let n = filled.min(row.len() - filled);
        row.copy_within(..n, filled);
        filled += n;
    }
}

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use image::{Rgba, RgbaImage};

    use super::{Renderer, fill_row};
    use crate::render::RenderError;
    use crate::render::test_ground::ground;
    use crate::render::{Camera, CullMode, FrameScene, Lighting, MeshInstance};

    #[test]
    fn a_renderer_reusing_its_batches_and_images_draws_what_a_new_one_draws() {
        let (terrain, mesh) = ground(97);
        let lighting = Lighting::default();
        let mut instance =
            MeshInstance::new(&mesh, Mat4::from_translation(Vec3::Y * 0.2), Vec3::ONE);
        instance.cull = CullMode::None;
        let meshes = [instance];
        // Frames of different sizes in turn: terrain and mesh from afar, the
        // mesh alone up close (more triangles per batch, some clipped).
        let both = FrameScene {
            terrain: Some(&terrain),
            meshes: &meshes,
            lighting,
            ..FrameScene::new()
        };
        let mesh_only = FrameScene {
            meshes: &meshes,
            lighting,
            ..FrameScene::new()
        };
        let camera = |eye: Vec3| {
            Camera::perspective(1.0, 160, 90, 0.05, 50.0)
                .unwrap()
                .look_at(eye, Vec3::ZERO, Vec3::Y)
        };
        let frames = [
            (&both, camera(Vec3::new(0.0, 2.5, -4.0))),
            (&mesh_only, camera(Vec3::new(0.3, 0.5, -0.6))),
        ];
        for threads in [1, 2] {
            let new = || {
                Renderer::new(160, 90)
                    .unwrap()
                    .with_threads(threads)
                    .unwrap()
            };
            let reused = new();
            // One image drawn into frame after frame, garbage at first.
            let mut into = RgbaImage::from_pixel(160, 90, Rgba([7, 99, 201, 13]));
            for _ in 0..2 {
                for (scene, camera) in &frames {
                    let (image, stats) = reused.render_with_stats(scene, camera);
                    assert!(stats.triangles > 1000, "{stats:?}");
                    let want = new().render(scene, camera);
                    assert!(image == want, "{threads} threads");
                    assert_eq!(reused.render_into(scene, camera, &mut into), Ok(stats));
                    assert!(into == want, "{threads} threads, into one image");
                }
            }
            // One thread draws at once with one scratch batch; more keep a
            // batch per patch and per mesh run.
            let kept = reused.batches.len();
            assert!(if threads == 1 { kept == 1 } else { kept > 1 }, "{kept}");
            let (scene, camera) = &frames[0];
            let mut wrong = RgbaImage::new(90, 160);
            assert!(matches!(
                reused.render_into(scene, camera, &mut wrong),
                Err(RenderError::InvalidParameter { name: "image", .. })
            ));
        }
    }

    #[test]
    fn fill_row_writes_every_pixel() {
        for pixels in [0usize, 1, 2, 3, 5, 8, 13, 1280] {
            let mut row = vec![0u8; 4 * pixels];
            fill_row(&mut row, [1, 2, 3, 255]);
            assert!(
                row.chunks_exact(4).all(|p| p == [1, 2, 3, 255]),
                "{pixels} pixels"
            );
        }
    }
}
