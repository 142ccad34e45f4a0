//! Small rendered scenes checked by pixel statistics. Each scene is also written
//! to `target/render-previews/` for a human to look at.

use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Mat4, Quat, Vec2, Vec3};
use engine::render::{
    Camera, FrameScene, GrassBlade, Lighting, MeshInstance, Renderer, SampleColors, TerrainRenderer,
    TerrainStyle, UniformColor,
};
use image::RgbaImage;

const SAND: Vec3 = Vec3::new(0.62, 0.5, 0.34);

/// Writes a preview PNG (best effort: previews are for people, not for the checks).
fn preview(name: &str, image: &RgbaImage) {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/render-previews");
    if std::fs::create_dir_all(&dir).is_ok() {
        let _ = image.save(dir.join(format!("{name}.png")));
    }
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
    (0..6).map(|k| (0.35 + k as f32 * 0.32, 1.28 + if k % 2 == 0 { 0.1 } else { -0.1 })).collect()
}

fn ground(with_prints: bool) -> HeightGrid {
    let centres = prints();
    HeightGrid::from_fn(Vec2::ZERO, 0.02, 129, 129, |x, z| {
        let mut h = bumps(x, z);
        if with_prints {
            h += centres.iter().map(|&(cx, cz)| footprint(x, z, cx, cz, 0.035)).sum::<f32>();
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
    let img_with = renderer.render(&FrameScene { terrain: Some(&t_with), ..FrameScene::new() }, &cam);
    let img_without = renderer.render(&FrameScene { terrain: Some(&t_without), ..FrameScene::new() }, &cam);
    preview("footprints", &img_with);
    preview("footprints_none", &img_without);
    // Around each print's centre the ground is darker than the same spot untouched.
    for (cx, cz) in prints() {
        let p = cam.project(Vec3::new(cx, 0.0, cz)).unwrap();
        let (x, y) = (p.x as u32, p.y as u32);
        let dark = luminance(&img_with, x - 4, y - 2, x + 4, y + 3);
        let flat = luminance(&img_without, x - 4, y - 2, x + 4, y + 3);
        assert!(dark < flat - 8.0, "print at ({cx}, {cz}): {dark} vs flat {flat}");
    }
}
