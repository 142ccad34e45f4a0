//! The `raster` group of the peers harness: one 512² terrain mesh (522,242
//! triangles, per-vertex colours) seen by one camera at 1280 x 720, drawn by our
//! renderer and by `euc` (a scalar Rust software rasterizer).
//!
//! Rows (both renderers do the same shading work inside the timed region):
//! - `terrain_mesh_522k_tris`: both draw every triangle of the same mesh and
//!   light it each frame with the same formula (sun, sky, display encoding,
//!   fog): ours as a [`MeshInstance`] (per vertex, only for vertices of
//!   triangles that reach the screen), `euc` in its vertex shader (which it
//!   calls once per index: it has no vertex cache).
//! - `terrain_mesh_522k_tris_prelit`: the same mesh with the same colours
//!   computed once before timing, no fog: ours through
//!   [`MeshInstance::with_vertex_colors`], `euc` reading them in its vertex shader.
//! - `terrain_patches_lod`: ours draws the same grid through [`TerrainRenderer`]
//!   (patch culling and level of detail; lit when the grid changes, fog per
//!   frame); `euc` is the pre-lit full mesh of the row above.
//!
//! `euc` (0.5 has no threading) draws on one thread, so `ours_ns` is ours on
//! a one-thread pool (where it draws each triangle as it sets it up): the
//! like-for-like figure. `ours_2_threads_ns` is ours on
//! two threads, for reference. Each draws into buffers it keeps from frame to
//! frame (ours through [`Renderer::render_into`]). The workloads are timed
//! interleaved ([`crate::time_interleaved_ns`]), so that all see the machine
//! in the same state.

use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Mat4, Vec2, Vec3};
use engine::render::{
    Camera, CullMode, FrameScene, Lighting, MeshInstance, Renderer, TerrainRenderer, TerrainStyle,
    UniformColor, encode_display,
};
use euc::{Pipeline, buffer::Buffer2d, rasterizer};
use image::RgbaImage;

use crate::{Row, time_interleaved_ns};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;
const SAND: Vec3 = Vec3::new(0.62, 0.5, 0.34);

/// The shared 10 x 10 m, 512² terrain.
fn grid() -> HeightGrid {
    HeightGrid::from_fn(Vec2::new(-5.0, -5.0), 10.0 / 511.0, 512, 512, |x, z| {
        0.25 * (x * 0.6).sin() * (z * 0.45).cos() + 0.01 * (x * 9.0 + z * 7.0).sin()
    })
    .expect("valid grid")
}

/// The grid as one triangle mesh (same triangulation as the grid).
fn grid_mesh(grid: &HeightGrid) -> TriMesh {
    let (nx, nz) = (grid.nx(), grid.nz());
    let positions = (0..nz)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .map(|(i, j)| grid.sample_position(i, j))
        .collect();
    let mut triangles = Vec::with_capacity(2 * (nx - 1) * (nz - 1));
    for j in 0..nz - 1 {
        for i in 0..nx - 1 {
            let a = (j * nx + i) as u32;
            let (b, c) = (a + 1, a + nx as u32);
            triangles.push([a, c + 1, b]);
            triangles.push([a, c, c + 1]);
        }
    }
    TriMesh::new(positions, triangles).expect("valid mesh")
}

/// The shared camera: outside the terrain, looking across it (all of it in front).
fn camera() -> Camera {
    Camera::perspective(0.9, WIDTH, HEIGHT, 0.05, 200.0)
        .expect("camera")
        .look_at(Vec3::new(0.0, 3.0, -8.0), Vec3::new(0.0, 0.0, 0.0), Vec3::Y)
}

/// Where `euc`'s vertex shader gets its colours.
enum EucColors<'a> {
    /// Lit in the shader like our mesh vertices: normal, sky term, sun, display
    /// encoding and fog.
    Lit {
        normals: &'a [Vec3],
        lighting: Lighting,
        eye: Vec3,
    },
    /// Read from a table computed before timing.
    Baked(&'a [Vec3]),
}

/// `euc` pipeline: indexed positions through our view-projection, Gouraud colours.
struct EucTerrain<'a> {
    view_proj: Mat4,
    positions: &'a [Vec3],
    colors: EucColors<'a>,
}

impl Pipeline for EucTerrain<'_> {
    type Vertex = u32;
    type VsOut = (f32, f32, f32);
    type Pixel = u32;

    fn vert(&self, v: &u32) -> ([f32; 4], Self::VsOut) {
        let k = *v as usize;
        let p = self.positions[k];
        let clip = self.view_proj * p.extend(1.0);
        let c = match &self.colors {
            EucColors::Lit {
                normals,
                lighting,
                eye,
            } => {
                let n = normals[k];
                lighting.apply_fog(lit(lighting, n), (p - *eye).length())
            }
            EucColors::Baked(colors) => colors[k],
        };
        (clip.to_array(), (c.x, c.y, c.z))
    }

    fn frag(&self, c: &Self::VsOut) -> u32 {
        let b = |v: f32| (v.clamp(0.0, 1.0) * 255.0) as u32;
        0xff00_0000 | (b(c.0) << 16) | (b(c.1) << 8) | b(c.2)
    }
}

/// The display colour of a sand vertex with normal `n`, as our mesh path
/// lights it (before fog).
fn lit(lighting: &Lighting, n: Vec3) -> Vec3 {
    let sky = 0.65 + 0.35 * n.y;
    encode_display(lighting.radiance(SAND, n, sky, 1.0))
}

/// `euc` set up to draw `mesh` with `colors` into its own buffers.
struct EucFrame<'a> {
    indices: Vec<u32>,
    pipeline: EucTerrain<'a>,
    color: Buffer2d<u32>,
    depth: Buffer2d<f32>,
}

impl<'a> EucFrame<'a> {
    fn new(mesh: &'a TriMesh, cam: &Camera, colors: EucColors<'a>) -> EucFrame<'a> {
        EucFrame {
            indices: mesh.triangles.iter().flatten().copied().collect(),
            pipeline: EucTerrain {
                view_proj: cam.view_proj(),
                positions: &mesh.positions,
                colors,
            },
            color: Buffer2d::new([WIDTH as usize, HEIGHT as usize], 0u32),
            depth: Buffer2d::new([WIDTH as usize, HEIGHT as usize], 1.0f32),
        }
    }

    /// Clears the buffers and draws the mesh (the timed work).
    fn draw(&mut self) {
        euc::Target::clear(&mut self.color, 0);
        euc::Target::clear(&mut self.depth, 1.0);
        self.pipeline
            .draw::<rasterizer::Triangles<_, rasterizer::BackfaceCullingDisabled>, _>(
                &self.indices,
                &mut self.color,
                Some(&mut self.depth),
            );
    }

    /// Pixels the last frame covered.
    fn covered(&self) -> usize {
        self.color.as_ref().iter().filter(|&&p| p != 0).count()
    }
}

/// Ours drawing `scene` into its own image, frame after frame (as `euc`
/// draws into its own buffers).
fn ours<'a>(
    renderer: &'a Renderer,
    scene: &'a FrameScene<'a>,
    cam: &'a Camera,
) -> impl FnMut() + 'a {
    let mut image = RgbaImage::new(WIDTH, HEIGHT);
    move || {
        renderer
            .render_into(scene, cam, &mut image)
            .expect("an image of the renderer's size");
        std::hint::black_box(&image);
    }
}

/// Time per timed workload (ours on one thread, ours on two, `euc`): their
/// frames are interleaved, so all see the machine in the same state.
const BUDGET_PER_WORKLOAD_MS: u64 = 3000;

/// Runs the group and returns one row per workload.
pub fn run() -> Vec<Row> {
    let grid = grid();
    let mesh = grid_mesh(&grid);
    let cam = camera();
    let lighting = Lighting::default();
    let threads = [1, 2].map(|n| {
        Renderer::new(WIDTH, HEIGHT)
            .and_then(|r| r.with_threads(n))
            .expect("renderer")
    });
    let [one_thread, two_threads] = &threads;

    // Lit each frame by both.
    let mut euc_lit = EucFrame::new(
        &mesh,
        &cam,
        EucColors::Lit {
            normals: &mesh.normals,
            lighting,
            eye: cam.eye,
        },
    );
    let mut instance = MeshInstance::new(&mesh, Mat4::IDENTITY, SAND);
    instance.cull = CullMode::None;
    let lit_meshes = [instance];
    // euc casts no shadows: neither does ours here.
    let lit_scene = FrameScene {
        meshes: &lit_meshes,
        lighting,
        shadows: false,
        ..FrameScene::new()
    };
    let [ours_lit, ours_lit_2, euc_lit_ns] = time_interleaved_ns(
        3 * BUDGET_PER_WORKLOAD_MS,
        [
            &mut ours(one_thread, &lit_scene, &cam),
            &mut ours(two_threads, &lit_scene, &cam),
            &mut || euc_lit.draw(),
        ],
    );
    let euc_covered = euc_lit.covered();

    // Pre-lit by both: the same colours, computed once; no fog. Ours also
    // draws the same grid through the terrain renderer (patch culling and
    // level of detail; lit when the grid changes, fog per frame).
    let unfogged = Lighting {
        fog_density: 0.0,
        ..lighting
    };
    let baked: Vec<Vec3> = mesh.normals.iter().map(|&n| lit(&lighting, n)).collect();
    let mut euc_baked = EucFrame::new(&mesh, &cam, EucColors::Baked(&baked));
    let baked_meshes = [instance.with_vertex_colors(&baked)];
    let prelit = FrameScene {
        meshes: &baked_meshes,
        lighting: unfogged,
        shadows: false,
        ..FrameScene::new()
    };
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).expect("style");
    terrain
        .update(&grid, &UniformColor(SAND), &lighting)
        .expect("grid");
    let terrain_scene = FrameScene {
        terrain: Some(&terrain),
        lighting,
        ..FrameScene::new()
    };
    let [
        ours_baked,
        ours_baked_2,
        euc_baked_ns,
        ours_terrain,
        ours_terrain_2,
    ] = time_interleaved_ns(
        5 * BUDGET_PER_WORKLOAD_MS,
        [
            &mut ours(one_thread, &prelit, &cam),
            &mut ours(two_threads, &prelit, &cam),
            &mut || euc_baked.draw(),
            &mut ours(one_thread, &terrain_scene, &cam),
            &mut ours(two_threads, &terrain_scene, &cam),
        ],
    );
    let (_, stats) = one_thread.render_with_stats(&terrain_scene, &cam);
    eprintln!(
        "raster: euc covered {euc_covered} px; terrain patches set up {} triangles",
        stats.triangles
    );

    let row = |name: &str, [one, two]: [f64; 2], euc_ns: f64| {
        Row::new(
            name,
            vec![
                ("ours_ns", Some(one)),
                ("ours_2_threads_ns", Some(two)),
                ("euc_ns", Some(euc_ns)),
            ],
        )
    };
    vec![
        row("terrain_mesh_522k_tris", [ours_lit, ours_lit_2], euc_lit_ns),
        row(
            "terrain_mesh_522k_tris_prelit",
            [ours_baked, ours_baked_2],
            euc_baked_ns,
        ),
        row(
            "terrain_patches_lod",
            [ours_terrain, ours_terrain_2],
            euc_baked_ns,
        ),
    ]
}
