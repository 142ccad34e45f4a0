//! Sun shadows on the ground, checked against geometry: a box standing on
//! flat ground under a known sun darkens exactly the ground the box hides
//! from the sun (from the box's foot on), the shadow's edge is a straight
//! line where the geometry puts it (no stair-steps), and the lit ground
//! around it is untouched (no acne).

mod render_support;

use engine::geom::{HeightGrid, TriMesh};
use engine::glam::{Mat4, Vec2, Vec3, Vec4};
use engine::render::{
    Camera, FrameScene, Lighting, MeshInstance, Renderer, Sun, TerrainRenderer, TerrainStyle,
    UniformColor,
};
use image::RgbaImage;
use render_support::preview;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;
/// Half the box's side, in metres.
const HALF: f32 = 0.2;
/// The box's height, in metres.
const TALL: f32 = 0.8;
/// The sun's elevation: the shadow reaches `TALL / tan(ELEVATION)` past the box.
const ELEVATION: f32 = 0.7;
/// The box's turn about the vertical, in radians: its shadow's outline
/// runs slanted across the shadow map's texels.
const TURN: f32 = 0.5;
/// Ground points this close to the shadow's outline (metres) are not
/// checked: the outline is a shadow texel soft.
const MARGIN: f32 = 0.03;

/// An axis-aligned box, faces wound counter-clockwise seen from outside.
fn cuboid(min: Vec3, max: Vec3) -> TriMesh {
    let corner = |k: u32| {
        Vec3::new(
            if k & 1 != 0 { max.x } else { min.x },
            if k & 2 != 0 { max.y } else { min.y },
            if k & 4 != 0 { max.z } else { min.z },
        )
    };
    let quads = [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ];
    let triangles = quads
        .iter()
        .flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]])
        .collect();
    let mut mesh = TriMesh::new((0..8).map(corner).collect(), triangles).unwrap();
    mesh.compute_normals();
    mesh
}

/// The sun from -X: the shadow runs along +X.
fn lighting() -> Lighting {
    let sun = Sun::from_angles(
        std::f32::consts::PI,
        ELEVATION,
        Vec3::splat(1.1),
        Vec3::splat(0.4),
    );
    Lighting {
        sun,
        fog_density: 0.0,
        ..Lighting::default()
    }
}

/// Looking obliquely at the shadow, so its edges run slanted across the image.
fn camera() -> Camera {
    Camera::perspective(1.0, WIDTH, HEIGHT, 0.05, 30.0)
        .unwrap()
        .look_at(
            Vec3::new(-0.5, 1.3, -1.3),
            Vec3::new(0.5, 0.0, 0.1),
            Vec3::Y,
        )
}

/// Flat ground under [`lighting`], drawn as a terrain.
fn flat_ground() -> TerrainRenderer {
    let grid = HeightGrid::new(Vec2::splat(-2.0), 0.02, 201, 201, 0.0).unwrap();
    let mut terrain = TerrainRenderer::new(&grid, TerrainStyle::default()).unwrap();
    terrain
        .update(
            &grid,
            &UniformColor(Vec3::new(0.6, 0.55, 0.45)),
            &lighting(),
        )
        .unwrap();
    terrain
}

/// The box's colour.
const BOX_COLOUR: Vec3 = Vec3::new(0.3, 0.4, 0.8);

/// The box: `HALF` either side of its axis, `TALL` high, standing on y = 0.
fn box_mesh() -> TriMesh {
    cuboid(Vec3::new(-HALF, 0.0, -HALF), Vec3::new(HALF, TALL, HALF))
}

/// `meshes` on `terrain` in the test's light, seen from the test's camera,
/// with or without caster shadows.
fn draw(terrain: &TerrainRenderer, meshes: &[MeshInstance<'_>], shadows: bool) -> RgbaImage {
    let scene = FrameScene {
        terrain: Some(terrain),
        meshes,
        lighting: lighting(),
        shadows,
        ..FrameScene::new()
    };
    Renderer::new(WIDTH, HEIGHT)
        .unwrap()
        .render(&scene, &camera())
}

/// The frame with and without caster shadows.
fn render() -> (RgbaImage, RgbaImage) {
    let terrain = flat_ground();
    let mesh = box_mesh();
    let meshes = [MeshInstance::new(
        &mesh,
        Mat4::from_rotation_y(TURN),
        BOX_COLOUR,
    )];
    let frames = (
        draw(&terrain, &meshes, true),
        draw(&terrain, &meshes, false),
    );
    preview("sun_shadow_box", &frames.0);
    frames
}

/// Where the shadow of the box's foot corner `corner` (0..4) falls when
/// raised by `t` of the box's height.
fn shadow_of_corner(corner: usize, t: f32) -> Vec3 {
    let (x, z) = [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)][corner];
    let foot = Mat4::from_rotation_y(TURN).transform_point3(Vec3::new(x, 0.0, z));
    let sun = lighting().sun.direction;
    let away = Vec3::new(-sun.x, 0.0, -sun.z) * (TALL / sun.y);
    foot + away * t
}

/// Whether the segment from `from` along `dir` (lengths `0..=reach` of
/// `dir`) meets the box.
fn meets_box(from: Vec3, dir: Vec3, reach: f32) -> bool {
    let turn = Mat4::from_rotation_y(-TURN);
    let (from, dir) = (turn.transform_point3(from), turn.transform_vector3(dir));
    let (lo, hi) = (Vec3::new(-HALF, 0.0, -HALF), Vec3::new(HALF, TALL, HALF));
    let (a, b) = ((lo - from) / dir, (hi - from) / dir);
    let enter = a.min(b).max_element().max(1e-4);
    let leave = a.max(b).min_element().min(reach);
    enter <= leave
}

/// Whether the box hides ground point `g` from the sun.
fn in_shadow(g: Vec3) -> bool {
    meets_box(g, lighting().sun.direction, f32::INFINITY)
}

/// The ground points around `g` within `MARGIN` all agree: `Some(true)`
/// deep in the shadow, `Some(false)` well out of it.
fn clearly_in_shadow(g: Vec3) -> Option<bool> {
    let around = (0..16).map(|k| {
        let a = k as f32 * std::f32::consts::TAU / 16.0;
        g + Vec3::new(a.cos(), 0.0, a.sin()) * MARGIN
    });
    let first = in_shadow(g);
    around.map(in_shadow).all(|s| s == first).then_some(first)
}

/// Where the ray from the eye through pixel `(x, y)`'s centre meets the
/// ground, unless the box is in the way.
fn ground_seen(camera: &Camera, x: u32, y: u32) -> Option<Vec3> {
    let ndc = Vec2::new(
        2.0 * (x as f32 + 0.5) / WIDTH as f32 - 1.0,
        1.0 - 2.0 * (y as f32 + 0.5) / HEIGHT as f32,
    );
    let to_world = camera.clip_to_world();
    let dir = (to_world * Vec4::new(ndc.x, ndc.y, 1.0, 0.0)).truncate();
    let t = -camera.eye.y / dir.y;
    (t > 0.0 && !meets_box(camera.eye, dir, t)).then(|| camera.eye + dir * t)
}

fn green(image: &RgbaImage, x: u32, y: u32) -> f32 {
    f32::from(image.get_pixel(x, y)[1])
}

#[test]
fn the_shadow_covers_what_the_box_hides_from_the_sun_and_nothing_else() {
    let (shadowed, bare) = render();
    let camera = camera();
    let (mut inside, mut outside, mut acne) = (0, 0, 0);
    let mut dark = Vec::new();
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let Some(g) = ground_seen(&camera, x, y) else {
                continue;
            };
            match clearly_in_shadow(g) {
                Some(false) => {
                    outside += 1;
                    acne += usize::from(shadowed.get_pixel(x, y) != bare.get_pixel(x, y));
                }
                Some(true) => {
                    inside += 1;
                    dark.push(green(&bare, x, y) - green(&shadowed, x, y));
                }
                None => {}
            }
        }
    }
    assert!(
        inside > 1500 && outside > 30_000,
        "{inside} in, {outside} out"
    );
    assert_eq!(acne, 0, "lit ground pixels changed by the shadow pass");
    // Every ground pixel in the shadow loses the sun (the same share of it
    // on flat ground), also at the box's foot.
    let least = dark.iter().copied().fold(f32::INFINITY, f32::min);
    let most = dark.iter().copied().fold(0.0, f32::max);
    assert!(
        least > 40.0 && most - least <= 2.0,
        "darkened by {least}..{most}"
    );
}

#[test]
fn the_shadow_edge_is_a_straight_line_where_geometry_puts_it() {
    let (shadowed, bare) = render();
    let camera = camera();
    // A side of the shadow's outline: the shadow of the box's upright edge
    // at a foot corner, from a little past the box to a little before the
    // shadow's end. The corner nearest the camera whose shadow is on the
    // outline (the sun grazes its two faces from one side).
    let corner = (0..4)
        .filter(|&c| {
            let beside = |t: f32| shadow_of_corner(c, 0.5) + Vec3::new(0.0, 0.0, t);
            in_shadow(beside(0.02)) != in_shadow(beside(-0.02))
        })
        .min_by(|&a, &b| {
            let d = |c| (shadow_of_corner(c, 0.5) - camera.eye).length();
            d(a).total_cmp(&d(b))
        })
        .expect("a corner's shadow runs along the outline");
    let ends = [0.15, 0.85].map(|t| {
        camera
            .project(shadow_of_corner(corner, t))
            .expect("the edge is in view")
    });
    let (left, right) = if ends[0].x < ends[1].x {
        (ends[0], ends[1])
    } else {
        (ends[1], ends[0])
    };
    assert!(right.x - left.x > 45.0, "the edge spans {left} to {right}");
    let dark_level = {
        let middle = (shadow_of_corner(0, 0.5) + shadow_of_corner(2, 0.5)) * 0.5;
        let centre = camera.project(middle).unwrap();
        green(&shadowed, centre.x as u32, centre.y as u32)
    };
    // Per column, the edge's row from the shadowed share of a window of
    // rows across it.
    const WINDOW: i32 = 10;
    let mut offsets = Vec::new();
    for x in left.x.ceil() as u32..right.x.floor() as u32 {
        let t = (x as f32 + 0.5 - left.x) / (right.x - left.x);
        let geometry = left.y + (right.y - left.y) * t;
        let y0 = geometry as i32 - WINDOW;
        let shares: Vec<f32> = (y0..y0 + 2 * WINDOW)
            .map(|y| {
                let lit = green(&bare, x, y as u32);
                ((lit - green(&shadowed, x, y as u32)) / (lit - dark_level)).clamp(0.0, 1.0)
            })
            .collect();
        let share: f32 = shares.iter().sum();
        let (above, below) = shares.split_at(WINDOW as usize);
        let edge = if above.iter().sum::<f32>() > below.iter().sum::<f32>() {
            y0 as f32 + share
        } else {
            (y0 + 2 * WINDOW) as f32 - share
        };
        offsets.push(edge - geometry);
    }
    let n = offsets.len() as f32;
    let mean = offsets.iter().sum::<f32>() / n;
    assert!(
        mean.abs() < 0.75,
        "the edge lies {mean} px off its geometry"
    );
    // Straight: no column strays from the fitted line, and the edge does
    // not zigzag (stair-steps of texels or of terrain vertices would).
    let (sx, sxx) =
        (0..offsets.len()).fold((0.0, 0.0), |(s, ss), k| (s + k as f32, ss + (k * k) as f32));
    let sxy: f32 = offsets.iter().enumerate().map(|(k, o)| k as f32 * o).sum();
    let slope = (n * sxy - sx * offsets.iter().sum::<f32>()) / (n * sxx - sx * sx);
    let fitted = |k: usize| mean + slope * (k as f32 - sx / n);
    let worst = (0..offsets.len())
        .map(|k| (offsets[k] - fitted(k)).abs())
        .fold(0.0, f32::max);
    let turns = offsets
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < -0.01)
        .count();
    println!("edge: mean {mean:.3} px, worst {worst:.3} px, {turns} turns over {n} columns");
    assert!(
        worst < 0.6,
        "the edge strays {worst} px from a straight line"
    );
    assert!(
        turns as f32 <= 0.2 * n,
        "the edge turns {turns} times over {n} columns"
    );
}

#[test]
fn ground_in_the_shadow_of_two_casters_is_no_darker_than_in_one() {
    let terrain = flat_ground();
    let mesh = box_mesh();
    // Two boxes side by side across the sun: their shadows overlap in a band.
    let boxes = [Vec3::ZERO, Vec3::new(0.2, 0.0, 0.25)]
        .map(|at| MeshInstance::new(&mesh, Mat4::from_translation(at), BOX_COLOUR));
    let draw_on_ground =
        |meshes: &[MeshInstance<'_>], shadows: bool| draw(&terrain, meshes, shadows);
    let ground = draw_on_ground(&[], false);
    let unshadowed = draw_on_ground(&boxes, false);
    let (one, other, both) = (
        draw_on_ground(&boxes[..1], true),
        draw_on_ground(&boxes[1..], true),
        draw_on_ground(&boxes, true),
    );
    // The deepest shadow of one caster, the deepest of both, and where
    // both shade the same ground.
    let (mut deepest_one, mut deepest_both, mut overlap) = (0.0f32, 0.0f32, 0);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            // Only ground that neither box hides from the eye.
            if unshadowed.get_pixel(x, y) != ground.get_pixel(x, y) {
                continue;
            }
            let lit = green(&ground, x, y);
            let shade = |image: &RgbaImage| lit - green(image, x, y);
            let (a, b) = (shade(&one), shade(&other));
            deepest_one = deepest_one.max(a).max(b);
            deepest_both = deepest_both.max(shade(&both));
            overlap += usize::from(a > 40.0 && b > 40.0);
        }
    }
    assert!(overlap > 200, "the shadows overlap on {overlap} pixels");
    assert!(deepest_one > 40.0, "one caster darkens by {deepest_one}");
    assert!(
        deepest_both <= deepest_one + 1.0,
        "two casters darken by {deepest_both}, one by {deepest_one}"
    );
}
