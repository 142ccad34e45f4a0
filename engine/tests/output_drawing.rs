//! Overlays, text and plots land on the expected pixels and keep frames opaque.

use engine::canvas::{LinePlot, Overlay, PixelRect, Series, draw_text, text_width};
use engine::glam::{Vec2, Vec3};
use image::{Rgba, RgbaImage};

const WHITE: Rgba<u8> = Rgba([255, 255, 255, 255]);
const RED: Rgba<u8> = Rgba([255, 0, 0, 255]);
const BLUE: Rgba<u8> = Rgba([0, 0, 255, 255]);

fn blank(w: u32, h: u32) -> RgbaImage {
    RgbaImage::from_pixel(w, h, WHITE)
}

fn is_opaque(img: &RgbaImage) -> bool {
    img.pixels().all(|p| p[3] == 255)
}

fn count(img: &RgbaImage, pred: impl Fn(&Rgba<u8>) -> bool) -> usize {
    img.pixels().filter(|p| pred(p)).count()
}

/// Looks down the -Z axis: world x, y map to pixels (x * 10, 100 - y * 10);
/// points behind the camera (z > 0) cannot be projected.
fn project(p: Vec3) -> Option<Vec2> {
    (p.z <= 0.0).then(|| Vec2::new(p.x * 10.0, 100.0 - p.y * 10.0))
}

#[test]
fn line_covers_its_pixels_and_nothing_far_away() {
    let mut img = blank(40, 20);
    Overlay::new(&mut img).line(Vec2::new(5.0, 10.0), Vec2::new(35.0, 10.0), RED, 2.0);
    for x in 6..34 {
        assert_eq!(img.get_pixel(x, 9), &RED);
        assert_eq!(img.get_pixel(x, 10), &RED);
        assert_eq!(img.get_pixel(x, 12), &WHITE);
        assert_eq!(img.get_pixel(x, 7), &WHITE);
    }
    assert_eq!(img.get_pixel(38, 10), &WHITE);
    assert!(is_opaque(&img));
}

#[test]
fn arrow_head_is_wider_than_its_shaft() {
    let mut img = blank(60, 30);
    Overlay::new(&mut img).arrow(Vec2::new(5.0, 15.0), Vec2::new(55.0, 15.0), BLUE, 2.0);
    let column_ink = |x: u32| (0..30).filter(|&y| img.get_pixel(x, y)[0] < 128).count();
    assert!(column_ink(20) <= 3, "shaft is thin");
    assert!(column_ink(47) >= 6, "head is wide");
    assert_eq!(img.get_pixel(57, 15), &WHITE, "nothing beyond the tip");
    assert!(is_opaque(&img));
}

#[test]
fn circles_outline_and_fill() {
    let mut img = blank(50, 50);
    {
        let mut overlay = Overlay::new(&mut img);
        overlay.circle(Vec2::new(25.0, 25.0), 15.0, RED, 2.0);
        overlay.fill_circle(Vec2::new(25.0, 25.0), 4.0, BLUE);
        overlay.point(Vec2::new(5.5, 5.5), BLUE, 3.0);
    }
    assert_eq!(img.get_pixel(25, 25), &BLUE);
    assert_eq!(img.get_pixel(25, 17), &WHITE, "ring interior");
    assert_eq!(img.get_pixel(40, 25), &RED, "on the ring (right)");
    assert_eq!(img.get_pixel(25, 9), &RED, "on the ring (top)");
    assert_eq!(img.get_pixel(5, 5), &BLUE);
    assert!(is_opaque(&img));
}

#[test]
fn world_helpers_project_and_skip_unprojectable_ends() {
    let mut img = blank(100, 100);
    {
        let mut overlay = Overlay::new(&mut img);
        overlay.world_line(
            &project,
            Vec3::new(1.0, 5.0, 0.0),
            Vec3::new(9.0, 5.0, 0.0),
            RED,
            2.0,
        );
        overlay.world_line(
            &project,
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::new(9.0, 2.0, 1.0),
            RED,
            2.0,
        );
        overlay.world_circle(&project, Vec3::new(5.0, 8.0, 0.0), 6.0, BLUE, 1.5);
        overlay.world_arrow(
            &project,
            Vec3::new(5.0, 8.0, 1.0),
            Vec3::new(9.0, 8.0, 0.0),
            BLUE,
            2.0,
        );
    }
    assert_eq!(img.get_pixel(50, 50), &RED, "projected line");
    for x in 15..85 {
        assert_eq!(
            img.get_pixel(x, 80),
            &WHITE,
            "segment with an unprojectable end is skipped"
        );
    }
    assert!(
        img.get_pixel(56, 20)[2] == 255 && img.get_pixel(56, 20)[0] < 128,
        "circle"
    );
    assert_eq!(
        img.get_pixel(80, 20),
        &WHITE,
        "arrow from behind the camera is skipped"
    );
}

#[test]
fn world_polyline_breaks_at_unprojectable_points() {
    let mut img = blank(100, 100);
    let points = [
        Vec3::new(1.0, 5.0, 0.0),
        Vec3::new(4.0, 5.0, 0.0),
        Vec3::new(5.0, 5.0, 2.0),
        Vec3::new(6.0, 5.0, 0.0),
        Vec3::new(9.0, 5.0, 0.0),
    ];
    Overlay::new(&mut img).world_polyline(&project, &points, RED, 2.0);
    assert_eq!(img.get_pixel(25, 50), &RED);
    assert_eq!(img.get_pixel(75, 50), &RED);
    assert_eq!(
        img.get_pixel(50, 50),
        &WHITE,
        "the gap around the unprojectable point"
    );
}

#[test]
fn translucent_frames_survive_the_premultiplied_round_trip() {
    let original = RgbaImage::from_fn(16, 16, |x, y| {
        Rgba([(x * 16) as u8, (y * 16) as u8, 90, (x * 16 + y) as u8])
    });
    let mut img = original.clone();
    Overlay::new(&mut img).line(Vec2::new(0.0, 8.0), Vec2::new(4.0, 8.0), RED, 1.0);
    for (x, y, p) in original.enumerate_pixels() {
        if x > 6 && p[3] > 64 {
            for c in 0..4 {
                let d = (i32::from(p[c]) - i32::from(img.get_pixel(x, y)[c])).abs();
                assert!(
                    d <= 2,
                    "pixel {x},{y}: {p:?} became {:?}",
                    img.get_pixel(x, y)
                );
            }
        }
    }
}

#[test]
fn text_is_drawn_where_asked_and_deterministically() {
    let mut a = blank(120, 40);
    let width = draw_text(&mut a, 10.0, 8.0, 16.0, Rgba([0, 0, 0, 255]), "Soft Walks");
    assert_eq!(width, text_width(16.0, "Soft Walks"));
    assert!(width > 60.0 && width < 110.0, "{width}");
    let inked: Vec<(u32, u32)> = a
        .enumerate_pixels()
        .filter(|(_, _, p)| p[0] < 128)
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(inked.len() > 60);
    assert!(
        inked
            .iter()
            .all(|&(x, y)| (10..=10 + width as u32).contains(&x) && (8..28).contains(&y))
    );
    let mut b = blank(120, 40);
    draw_text(&mut b, 10.0, 8.0, 16.0, Rgba([0, 0, 0, 255]), "Soft Walks");
    assert_eq!(a, b);
    assert!(is_opaque(&a));
    assert_eq!(text_width(16.0, ""), 0.0);
    assert!(text_width(12.0, "ab\nabcdef") == text_width(12.0, "abcdef"));
}

fn plot(series: Vec<Series>) -> LinePlot {
    LinePlot {
        title: "Pelvis height".into(),
        x_label: "time (s)".into(),
        y_label: "height (m)".into(),
        series,
    }
}

fn series(name: &str, points: Vec<(f32, f32)>, color: Rgba<u8>) -> Series {
    Series {
        name: name.into(),
        points,
        color,
    }
}

#[test]
fn plot_draws_axes_and_curves() {
    let ramp = (0..=40)
        .map(|i| (i as f32 * 0.25, i as f32 * 0.1))
        .collect();
    let img = plot(vec![series("ramp", ramp, RED)]).render(320, 200);
    assert!(is_opaque(&img));
    let red = |p: &Rgba<u8>| p[0] > 200 && p[1] < 60 && p[2] < 60;
    assert!(count(&img, red) > 200, "the curve is drawn");
    // The y axis: a dark vertical run in some column of the left third.
    let axis_column =
        (0..107).find(|&x| (40..150).filter(|&y| img.get_pixel(x, y)[0] < 90).count() > 100);
    assert!(axis_column.is_some(), "the y axis is drawn");
    // The x axis: a dark horizontal run in some row of the lower third.
    let axis_row =
        (133..200).find(|&y| (100..300).filter(|&x| img.get_pixel(x, y)[0] < 90).count() > 180);
    assert!(axis_row.is_some(), "the x axis is drawn");
    // The ramp rises: red pixels on the left sit lower than on the right.
    let mean_red_row = |xs: std::ops::Range<u32>| {
        let rows: Vec<u32> = xs
            .flat_map(|x| (0..200).map(move |y| (x, y)))
            .filter(|&(x, y)| red(img.get_pixel(x, y)))
            .map(|(_, y)| y)
            .collect();
        rows.iter().sum::<u32>() as f32 / rows.len() as f32
    };
    assert!(mean_red_row(80..100) > mean_red_row(240..260) + 30.0);
}

#[test]
fn plot_edge_cases_render_without_panicking() {
    let cases = vec![
        vec![],
        vec![series("empty", vec![], RED)],
        vec![series("one", vec![(2.0, 3.0)], RED)],
        vec![series(
            "flat",
            vec![(0.0, 5.0), (1.0, 5.0), (2.0, 5.0)],
            RED,
        )],
        vec![series("zero", vec![(0.0, 0.0), (1.0, 0.0)], RED)],
        vec![series(
            "nan",
            vec![
                (0.0, 1.0),
                (f32::NAN, 2.0),
                (2.0, f32::NAN),
                (3.0, 2.0),
                (4.0, f32::INFINITY),
            ],
            RED,
        )],
        vec![
            series("all nan", vec![(f32::NAN, f32::NAN)], RED),
            series("", vec![(0.0, 1e9), (1.0, -1e9)], BLUE),
        ],
        vec![series("tiny", vec![(0.0, 1e-7), (1.0, 2e-7)], BLUE)],
    ];
    for (i, s) in cases.into_iter().enumerate() {
        let p = plot(s);
        for (w, h) in [(320, 200), (40, 30), (3, 3), (1, 1), (0, 0)] {
            let img = p.render(w, h);
            assert_eq!(img.dimensions(), (w, h), "case {i}");
            assert!(is_opaque(&img));
        }
    }
    let single = plot(vec![series("one", vec![(2.0, 3.0)], RED)]).render(200, 120);
    assert!(
        count(&single, |p| p[0] > 200 && p[1] < 60) > 3,
        "a lone point is drawn as a dot"
    );
}

#[test]
fn plot_onto_a_frame_stays_inside_its_rectangle() {
    let mut frame = RgbaImage::from_pixel(200, 150, Rgba([10, 20, 30, 255]));
    let rect = PixelRect {
        x: 100,
        y: 80,
        width: 90,
        height: 60,
    };
    plot(vec![series("s", vec![(0.0, 0.0), (1.0, 1.0)], RED)]).draw_onto(&mut frame, rect);
    for (x, y, p) in frame.enumerate_pixels() {
        let inside = (100..190).contains(&x) && (80..140).contains(&y);
        if !inside {
            assert_eq!(
                p,
                &Rgba([10, 20, 30, 255]),
                "pixel {x},{y} outside the rectangle"
            );
        }
    }
    assert_eq!(frame.get_pixel(101, 81), &WHITE);
    // A rectangle hanging over the edge is clipped to the frame.
    let rect = PixelRect {
        x: 150,
        y: 120,
        width: 400,
        height: 400,
    };
    plot(vec![]).draw_onto(&mut frame, rect);
    assert!(is_opaque(&frame));
}

#[test]
fn label_draws_text_on_its_box() {
    let mut img = RgbaImage::from_pixel(100, 40, Rgba([30, 30, 30, 255]));
    let size = Overlay::new(&mut img).label(
        Vec2::new(4.0, 4.0),
        12.0,
        Rgba([0, 0, 0, 255]),
        WHITE,
        "CoM 1.2",
    );
    assert_eq!(size.x, text_width(12.0, "CoM 1.2") + 6.0);
    assert_eq!(img.get_pixel(5, 5), &WHITE, "box corner");
    assert_eq!(
        img.get_pixel(4 + size.x as u32 + 1, 5),
        &Rgba([30, 30, 30, 255]),
        "outside the box"
    );
    let dark_inside = (10..(size.x as u32)).flat_map(|x| (8..(size.y as u32)).map(move |y| (x, y)));
    assert!(
        dark_inside
            .filter(|&(x, y)| img.get_pixel(x, y)[0] < 60)
            .count()
            > 20,
        "text on the box"
    );
}
