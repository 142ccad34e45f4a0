//! A frame: everything drawn in one image, and the [`Renderer`] that draws it.

use std::sync::{Arc, Mutex};

use glam::Vec3;
use image::RgbaImage;
use rayon::prelude::*;

use super::camera::Camera;
use super::error::RenderError;
use super::frame_view::FrameView;
use super::grass::GrassLayer;
use super::grass_blade::GrassBlade;
use super::mesh::MeshInstance;
use super::raster::{BAND_ROWS, Band, TriangleBatch, Viewport, to_u8};
use super::shading::Lighting;
use super::shadow_map::ShadowMap;
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
    /// Whether meshes and blades cast sun shadows (on the ground, on each
    /// other and on themselves).
    pub shadows: bool,
}

impl<'a> FrameScene<'a> {
    /// An empty scene (sky only) with default lighting and shadows on.
    pub fn new() -> FrameScene<'a> {
        FrameScene {
            terrain: None,
            meshes: &[],
            blades: &[],
            lighting: Lighting::default(),
            shadows: true,
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
    /// Triangle batches (visible terrain patches, mesh parts; grass is one
    /// layer beside them).
    pub batches: usize,
    /// Triangles set up after culling and clipping: those covering at least
    /// one pixel centre's box (grass: blade pieces, a quad or a tip each).
    pub triangles: usize,
}

/// Draws [`FrameScene`]s into `width` x `height` RGBA images.
///
/// First the sun's shadow map of the meshes and blades; then geometry is
/// projected and set up per batch (terrain patch, mesh part, the grass
/// layer) in parallel; then the screen is cut into fixed bands of rows,
/// filled in parallel, each band drawing the grass, then the batches in
/// scene order. The image is byte-identical whatever the number of threads
/// (see `super::raster`).
#[derive(Debug, Clone)]
pub struct Renderer {
    width: u32,
    height: u32,
    pool: Option<Arc<rayon::ThreadPool>>,
    /// The depth buffer kept between frames (saves allocating and faulting in
    /// a fresh one per frame); a frame that finds it busy allocates its own.
    depth: Arc<Mutex<Vec<f32>>>,
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
        let shadows = scene
            .shadows
            .then(|| {
                let sun = scene.lighting.sun.direction;
                let casters: Vec<[Vec3; 3]> = scene
                    .meshes
                    .iter()
                    .flat_map(|m| m.sun_casters(sun))
                    .collect();
                let ground_low = scene.terrain.map(TerrainRenderer::lowest_height);
                ShadowMap::build(&casters, scene.blades, sun, camera, ground_low)
            })
            .flatten();
        let view = FrameView::new(camera, &scene.lighting, shadows.as_ref(), vp);
        let ((batches, sky_rows), grass) = rayon::join(
            || rayon::join(|| project(&view, scene), || sky_rows(&view)),
            || GrassLayer::build(scene.blades, &view),
        );
        let stats = FrameStats {
            batches: batches.len(),
            triangles: batches.iter().map(TriangleBatch::len).sum::<usize>() + grass.len(),
        };
        let w = self.width as usize;
        let band_rows = BAND_ROWS as usize;
        self.with_depth(|depth| {
            image
                .par_chunks_mut(w * 4 * band_rows)
                .zip(depth.par_chunks_mut(w * band_rows))
                .enumerate()
                // One band per job: a thread that runs out of bands steals a
                // single band, so all finish together.
                .with_max_len(1)
                .for_each(|(b, (color, depth))| {
                    let y0 = b as i32 * BAND_ROWS;
                    clear_to_sky(color, depth, &sky_rows[y0 as usize..], w);
                    let y1 = y0 + (depth.len() / w) as i32;
                    let mut band = Band {
                        color,
                        depth,
                        width: vp.width,
                        y0,
                        y1,
                    };
                    // The grass first: the ground it hides then fails the
                    // depth test before it is shaded.
                    grass.draw_band(b as i32, &mut band);
                    for batch in &batches {
                        batch.draw_band(b as i32, &mut band, view.pixel_shadow.as_ref());
                    }
                });
        });
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
}

/// All batches in drawing order: terrain patches, then meshes (grass is
/// drawn before them).
fn project(view: &FrameView<'_>, scene: &FrameScene<'_>) -> Vec<TriangleBatch> {
    let (mut batches, meshes) = rayon::join(
        || scene.terrain.map(|t| t.batches(view)).unwrap_or_default(),
        || -> Vec<Vec<TriangleBatch>> {
            scene.meshes.par_iter().map(|m| m.batches(view)).collect()
        },
    );
    batches.extend(meshes.into_iter().flatten());
    batches
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

/// Clears rows of a frame `width` pixels wide to empty depth and to the sky
/// colour of each (`sky_rows` from the first row on).
fn clear_to_sky(color: &mut [u8], depth: &mut [f32], sky_rows: &[Vec3], width: usize) {
    depth.fill(0.0);
    for (row, sky) in color.chunks_mut(width * 4).zip(sky_rows) {
        let px = [to_u8(sky.x), to_u8(sky.y), to_u8(sky.z), 255];
        for p in row.chunks_exact_mut(4) {
            p.copy_from_slice(&px);
        }
    }
}
#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use image::{Rgba, RgbaImage};

    use super::Renderer;
    use crate::render::RenderError;
    use crate::render::test_ground::ground;
    use crate::render::{Camera, CullMode, FrameScene, GrassBlade, Lighting, MeshInstance};
    use crate::rng::SplitMix64;

    #[test]
    fn a_renderer_reusing_its_images_draws_what_a_new_one_draws() {
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
            let (scene, camera) = &frames[0];
            let mut wrong = RgbaImage::new(90, 160);
            assert!(matches!(
                reused.render_into(scene, camera, &mut wrong),
                Err(RenderError::InvalidParameter { name: "image", .. })
            ));
        }
    }

    #[test]
    fn one_and_two_threads_draw_the_same_bytes() {
        let (terrain, mesh) = ground(129);
        let lighting = Lighting::default();
        // The dense mesh above the terrain, both sides drawn, lit each frame
        // (fog included); a pre-lit copy of it lower down.
        let mut lit = MeshInstance::new(
            &mesh,
            Mat4::from_translation(Vec3::Y * 0.3),
            Vec3::new(0.5, 0.6, 0.4),
        );
        lit.cull = CullMode::None;
        let baked: Vec<Vec3> = (0..mesh.positions.len())
            .map(|k| Vec3::new((k % 7) as f32 / 7.0, 0.5, (k % 5) as f32 / 5.0))
            .collect();
        let pre_lit = MeshInstance::new(&mesh, Mat4::from_translation(-Vec3::Y * 0.1), Vec3::ONE)
            .with_vertex_colors(&baked);
        let mut rng = SplitMix64::new(11);
        let blades: Vec<GrassBlade> = (0..3000)
            .map(|_| {
                let root = Vec3::new(rng.next_f32() * 4.0 - 2.0, 0.3, rng.next_f32() * 4.0 - 2.0);
                GrassBlade {
                    root,
                    mid: root + Vec3::new(0.01, 0.05, 0.0),
                    tip: root + Vec3::new(0.03, 0.1, 0.01),
                    width: 0.01,
                    color: Vec3::new(0.3, 0.6, 0.2),
                }
            })
            .collect();
        let meshes = [lit, pre_lit];
        let scene = FrameScene {
            terrain: Some(&terrain),
            meshes: &meshes,
            blades: &blades,
            lighting,
            shadows: true,
        };
        // Close enough that the near plane cuts the ground and blades.
        let camera = Camera::perspective(1.0, 320, 180, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 0.5, -2.1), Vec3::new(0.0, 0.0, 1.0), Vec3::Y);
        let render = |threads: usize| {
            Renderer::new(320, 180)
                .and_then(|r| r.with_threads(threads))
                .unwrap()
                .render_with_stats(&scene, &camera)
        };
        let (one, stats) = render(1);
        assert!(stats.triangles > 20_000, "{stats:?}");
        let sky = *one.get_pixel(160, 0);
        assert!(one.pixels().filter(|&&p| p != sky).count() > 30_000);
        let (two, two_stats) = render(2);
        assert!(two == one);
        assert_eq!(two_stats, stats);
    }
}
