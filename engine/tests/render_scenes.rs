//! Small rendered scenes checked by pixel statistics. Each scene is also written
//! to `target/render-previews/` for a human to look at.

mod render_support;

use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Mat4, Vec2, Vec3};
use engine::render::{
    Camera, FrameScene, GrassBlade, Lighting, MeshInstance, Renderer, SampleColors,
    TerrainRenderer, TerrainStyle, UniformColor,
};
use image::RgbaImage;
use render_support::preview;

const SAND: Vec3 = Vec3::new(0.62, 0.5, 0.34);

/// `terrain` alone, default lighting, as `renderer` draws it from `camera`.
fn terrain_only(renderer: &Renderer, terrain: &TerrainRenderer, camera: &Camera) -> RgbaImage {
    let scene = FrameScene {
        terrain: Some(terrain),
        ..FrameScene::new()
    };
    renderer.render(&scene, camera)
}

/// A footprint: an elliptical depression `depth` deep with a raised rim.
fn footprint(x: f32, z: f32, cx: f32, cz: f32, depth: f32) -> f32 {
    let (a, b) = (0.13, 0.055);
    let r = (((x - cx) / a).powi(2) + ((z - cz) / b).powi(2)).sqrt();
    if r < 1.0 {
        -depth * (1.0 - r.powi(4))
    } else {
        0.25 * depth * (-(r - 1.0) * 6.0).exp() * (r - 1.0).min(0.2) * 5.0
    }
}

/// Gentle bumps.
fn bumps(x: f32, z: f32) -> f32 {
    0.012 * (x * 7.0).sin() * (z * 5.0).cos() + 0.006 * (x * 17.0 + z * 11.0).sin()
}

/// Centres of a walk along +X: alternating left and right prints.
fn prints() -> Vec<(f32, f32)> {
    (0..6)
        .map(|k| {
            (
                0.35 + k as f32 * 0.32,
                1.28 + if k % 2 == 0 { 0.1 } else { -0.1 },
            )
        })
        .collect()
}

fn ground(with_prints: bool) -> HeightGrid {
    let centres = prints();
    HeightGrid::from_fn(Vec2::ZERO, 0.02, 129, 129, |x, z| {
        let mut h = bumps(x, z);
        if with_prints {
            h += centres
                .iter()
                .map(|&(cx, cz)| footprint(x, z, cx, cz, 0.035))
                .sum::<f32>();
        }
        h
    })
    .unwrap()
}

fn camera(width: u32, height: u32) -> Camera {
    Camera::perspective(0.9, width, height, 0.05, 60.0)
        .unwrap()
        .look_at(Vec3::new(1.0, 1.3, -0.3), Vec3::new(1.2, 0.0, 1.3), Vec3::Y)
}

fn terrain_for(grid: &HeightGrid, lighting: &Lighting) -> TerrainRenderer {
    let mut t = TerrainRenderer::new(grid, TerrainStyle::default()).unwrap();
    t.update(grid, &UniformColor(SAND), lighting).unwrap();
    t
}

fn luminance(image: &RgbaImage, x0: u32, y0: u32, x1: u32, y1: u32) -> f32 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in y0..y1 {
        for x in x0..x1 {
            let p = image.get_pixel(x, y);
            sum += 0.3 * p[0] as f32 + 0.59 * p[1] as f32 + 0.11 * p[2] as f32;
            n += 1.0;
        }
    }
    sum / n
}

#[test]
fn footprints_are_darker_than_flat_surroundings() {
    let lighting = Lighting::default();
    let cam = camera(256, 160);
    let renderer = Renderer::new(256, 160).unwrap();
    let with = ground(true);
    let without = ground(false);
    let t_with = terrain_for(&with, &lighting);
    let t_without = terrain_for(&without, &lighting);
    let img_with = terrain_only(&renderer, &t_with, &cam);
    let img_without = terrain_only(&renderer, &t_without, &cam);
    preview("footprints", &img_with);
    preview("footprints_none", &img_without);
    // Around each print's centre the ground is darker than the same spot untouched.
    for (cx, cz) in prints() {
        let p = cam.project(Vec3::new(cx, 0.0, cz)).unwrap();
        let (x, y) = (p.x as u32, p.y as u32);
        let dark = luminance(&img_with, x - 4, y - 2, x + 4, y + 3);
        let flat = luminance(&img_without, x - 4, y - 2, x + 4, y + 3);
        assert!(
            dark < flat - 8.0,
            "print at ({cx}, {cz}): {dark} vs flat {flat}"
        );
    }
}

/// A closed UV sphere of `radius` around `centre`, counter-clockwise from outside.
fn sphere(centre: Vec3, radius: f32) -> TriMesh {
    let (rings, segments) = (10u32, 16u32);
    let mut positions = Vec::new();
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let d = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            positions.push(centre + d * radius);
        }
    }
    let mut triangles = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let a = r * segments + s;
            let b = r * segments + (s + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    TriMesh::new(positions, triangles).unwrap()
}

/// Two spheres as named parts (a "body" and a "head").
fn two_part_mesh() -> TriMesh {
    let mut body = sphere(Vec3::ZERO, 0.12);
    body.parts = vec![engine::geom::MeshPart {
        name: "body".into(),
        triangles: 0..body.triangles.len(),
    }];
    let mut head = sphere(Vec3::ZERO, 0.07);
    head.parts = vec![engine::geom::MeshPart {
        name: "head".into(),
        triangles: 0..head.triangles.len(),
    }];
    body.append(&head);
    body
}

/// A deterministic patch of blades around `(cx, cz)`.
fn meadow(cx: f32, cz: f32, count: usize, grid: &HeightGrid) -> Vec<GrassBlade> {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rand = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|_| {
            let x = cx + (rand() - 0.5) * 0.6;
            let z = cz + (rand() - 0.5) * 0.6;
            let h = 0.12 + 0.1 * rand();
            let lean = Vec3::new(rand() - 0.5, 0.0, rand() - 0.5) * 0.08;
            let root = Vec3::new(x, grid.height_at(x, z).unwrap_or(0.0) - 0.01, z);
            GrassBlade {
                root,
                mid: root + Vec3::Y * (0.55 * h) + lean * 0.3,
                tip: root + Vec3::Y * h + lean,
                width: 0.008,
                color: Vec3::new(0.18, 0.42 + 0.1 * rand(), 0.1),
            }
        })
        .collect()
}

#[test]
fn mesh_parts_and_blades_draw_where_expected() {
    let lighting = Lighting::default();
    let grid = ground(true);
    let terrain = terrain_for(&grid, &lighting);
    let mesh = two_part_mesh();
    let at = Vec3::new(1.9, 0.14, 1.3);
    let parts = [
        Mat4::IDENTITY,
        Mat4::from_translation(Vec3::new(0.0, 0.17, 0.0)),
    ];
    let instance = MeshInstance::new(
        &mesh,
        Mat4::from_translation(at),
        Vec3::new(0.75, 0.2, 0.15),
    )
    .with_parts(&parts);
    let blades = meadow(0.7, 1.9, 3000, &grid);
    let cam = camera(256, 160);
    let renderer = Renderer::new(256, 160).unwrap();
    let meshes = [instance];
    let scene = FrameScene {
        terrain: Some(&terrain),
        meshes: &meshes,
        blades: &blades,
        lighting,
        shadows: true,
    };
    let (image, stats) = renderer.render_with_stats(&scene, &cam);
    preview("mesh_and_grass", &image);
    assert!(stats.triangles > 9000);
    // Body and head centres are red, in the right order on screen.
    let body = cam.project(at).unwrap();
    let head = cam.project(at + Vec3::Y * 0.17).unwrap();
    assert!(head.y < body.y - 5.0);
    for p in [body, head] {
        let px = image.get_pixel(p.x as u32, p.y as u32);
        assert!(px[0] > px[1] + 40 && px[0] > px[2] + 40, "{p}: {px:?}");
    }
    // The meadow is green where it stands.
    let m = cam.project(Vec3::new(0.7, 0.1, 1.9)).unwrap();
    let px = image.get_pixel(m.x as u32, m.y as u32);
    assert!(px[1] > px[0] && px[1] > px[2], "meadow pixel {px:?}");
}

#[test]
fn frames_are_identical_on_one_and_two_threads() {
    let lighting = Lighting::default();
    let grid = ground(true);
    let terrain = terrain_for(&grid, &lighting);
    let blades = meadow(0.7, 1.9, 2000, &grid);
    let mesh = sphere(Vec3::new(1.9, 0.12, 1.3), 0.12);
    let meshes = [MeshInstance::new(
        &mesh,
        Mat4::IDENTITY,
        Vec3::new(0.6, 0.6, 0.7),
    )];
    let scene = FrameScene {
        terrain: Some(&terrain),
        meshes: &meshes,
        blades: &blades,
        lighting,
        shadows: true,
    };
    let cam = camera(200, 120);
    let one = Renderer::new(200, 120)
        .unwrap()
        .with_threads(1)
        .unwrap()
        .render(&scene, &cam);
    let two = Renderer::new(200, 120)
        .unwrap()
        .with_threads(2)
        .unwrap()
        .render(&scene, &cam);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let ambient = pool.install(|| Renderer::new(200, 120).unwrap().render(&scene, &cam));
    assert!(one.as_raw() == two.as_raw(), "1 vs 2 threads differ");
    assert!(
        one.as_raw() == ambient.as_raw(),
        "own pool vs installed pool differ"
    );
    // And the light computed by a 2-thread update equals a 1-thread one.
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let terrain_one = single.install(|| terrain_for(&grid, &lighting));
    let scene_one = FrameScene {
        terrain: Some(&terrain_one),
        ..scene
    };
    let again = Renderer::new(200, 120).unwrap().render(&scene_one, &cam);
    assert!(
        one.as_raw() == again.as_raw(),
        "terrain update depends on threads"
    );
}

#[test]
fn only_dirty_patches_remesh_and_match_a_fresh_terrain() {
    let lighting = Lighting::default();
    let mut grid = ground(false);
    let mut terrain = terrain_for(&grid, &lighting);
    assert_eq!(terrain.remeshed_last_update(), terrain.patch_count());
    // Stamp one print and report its window.
    let (cx, cz) = (1.0, 1.3);
    let rect = grid.rect_covering(Vec2::new(cx - 0.2, cz - 0.1), Vec2::new(cx + 0.2, cz + 0.1));
    for (i, j) in rect.iter() {
        let p = grid.sample_position(i, j);
        let h = grid.height(i, j) + footprint(p.x, p.z, cx, cz, 0.035);
        grid.set_height(i, j, h);
    }
    terrain.mark_dirty(rect);
    assert!(terrain.is_dirty());
    terrain
        .update(&grid, &UniformColor(SAND), &lighting)
        .unwrap();
    assert!(!terrain.is_dirty());
    let remeshed = terrain.remeshed_last_update();
    assert!(
        remeshed >= 1 && remeshed < terrain.patch_count(),
        "{remeshed} of {}",
        terrain.patch_count()
    );
    // Nothing marked: nothing re-meshed.
    terrain
        .update(&grid, &UniformColor(SAND), &lighting)
        .unwrap();
    assert_eq!(terrain.remeshed_last_update(), 0);
    // The incremental result equals a terrain built from scratch.
    let fresh = terrain_for(&grid, &lighting);
    let cam = camera(160, 100);
    let r = Renderer::new(160, 100).unwrap();
    let a = terrain_only(&r, &terrain, &cam);
    let b = terrain_only(&r, &fresh, &cam);
    assert!(a.as_raw() == b.as_raw());
}

#[test]
fn level_of_detail_cuts_triangles_without_cracks() {
    let grid = HeightGrid::from_fn(Vec2::new(-6.4, -6.4), 0.05, 257, 257, |x, z| {
        0.3 * (x * 0.9).sin() * (z * 0.7).cos() + 0.04 * (x * 5.0 + z * 3.0).sin()
    })
    .unwrap();
    let magenta = Vec3::new(1.0, 0.0, 1.0);
    let lighting = Lighting {
        sky_zenith: magenta,
        sky_horizon: magenta,
        fog_density: 0.0,
        ..Lighting::default()
    };
    // Looking down steeply: the terrain fills the whole frame.
    let cam = Camera::perspective(0.8, 192, 128, 0.05, 100.0)
        .unwrap()
        .look_at(Vec3::new(0.0, 5.0, -1.0), Vec3::new(0.0, 0.0, 1.5), Vec3::Y);
    let r = Renderer::new(192, 128).unwrap();
    let render = |style: TerrainStyle| {
        let mut t = TerrainRenderer::new(&grid, style).unwrap();
        t.update(&grid, &UniformColor(SAND), &lighting).unwrap();
        r.render_with_stats(
            &FrameScene {
                terrain: Some(&t),
                lighting,
                ..FrameScene::new()
            },
            &cam,
        )
    };
    let full = TerrainStyle {
        max_cell_px: 1e-3,
        ..TerrainStyle::default()
    };
    let coarse = TerrainStyle {
        max_cell_px: 8.0,
        max_error_px: 4.0,
        ..TerrainStyle::default()
    };
    let (img_full, full_stats) = render(full);
    let (img_lod, lod_stats) = render(coarse);
    preview("lod_full", &img_full);
    preview("lod_coarse", &img_lod);
    assert!(
        lod_stats.triangles * 3 < full_stats.triangles,
        "{lod_stats:?} vs {full_stats:?}"
    );
    for (name, img) in [("full", &img_full), ("lod", &img_lod)] {
        let holes = img.pixels().filter(|p| p[1] < 90 && p[2] > p[1]).count();
        assert_eq!(
            holes, 0,
            "{name}: {holes} sky pixels show through the terrain"
        );
    }
}

#[test]
fn disturbed_samples_are_darker() {
    let lighting = Lighting::default();
    let grid = ground(false);
    let n = grid.nx() * grid.nz();
    let albedo = vec![SAND; n];
    let disturbed: Vec<f32> = (0..n)
        .map(|k| if k % grid.nx() < 64 { 1.0 } else { 0.0 })
        .collect();
    let colors = SampleColors {
        nx: grid.nx(),
        albedo: &albedo,
        disturbed: &disturbed,
    };
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).unwrap();
    terrain.update(&grid, &colors, &lighting).unwrap();
    let cam = Camera::perspective(0.9, 128, 128, 0.05, 60.0)
        .unwrap()
        .look_at(
            Vec3::new(1.28, 3.0, 1.27),
            Vec3::new(1.28, 0.0, 1.28),
            Vec3::Y,
        );
    let img = terrain_only(&Renderer::new(128, 128).unwrap(), &terrain, &cam);
    preview("disturbed", &img);
    let left = cam.project(Vec3::new(0.6, 0.0, 1.28)).unwrap();
    let right = cam.project(Vec3::new(1.9, 0.0, 1.28)).unwrap();
    let lum = |p: Vec2| {
        luminance(
            &img,
            p.x as u32 - 3,
            p.y as u32 - 3,
            p.x as u32 + 3,
            p.y as u32 + 3,
        )
    };
    assert!(
        lum(left) < lum(right) - 10.0,
        "{} vs {}",
        lum(left),
        lum(right)
    );
}

#[test]
fn bad_parameters_are_refused_with_their_name() {
    use engine::render::RenderError;
    let name = |e: RenderError| match e {
        RenderError::InvalidParameter { name, .. } => name,
        RenderError::ThreadPool { .. } => "pool",
    };
    assert_eq!(name(Renderer::new(0, 10).unwrap_err()), "size");
    assert_eq!(
        name(Renderer::new(8, 8).unwrap().with_threads(0).unwrap_err()),
        "threads"
    );
    let grid = ground(false);
    let bad = TerrainStyle {
        patch_cells: 24,
        ..TerrainStyle::default()
    };
    assert_eq!(
        name(TerrainRenderer::new(&grid, bad).unwrap_err()),
        "patch_cells"
    );
    let bad = TerrainStyle {
        ao_radius: f32::NAN,
        ..TerrainStyle::default()
    };
    assert_eq!(
        name(TerrainRenderer::new(&grid, bad).unwrap_err()),
        "ao_radius"
    );
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).unwrap();
    let other = HeightGrid::new(Vec2::ZERO, 0.02, 65, 65, 0.0).unwrap();
    let err = terrain
        .update(&other, &UniformColor(SAND), &Lighting::default())
        .unwrap_err();
    assert_eq!(name(err), "grid");
}
