//! Heightmap PNG import and export: 8- and 16-bit, round trips, every bad input.

use std::path::Path;

use engine::asset::{AssetError, load_heightmap, load_heightmap_restored, save_heightmap_png16};
use engine::geom::{HeightGrid, MAX_GRID_SAMPLES};
use engine::glam::Vec2;

/// Encodes a PNG with the given header and raw (already packed) pixel bytes.
fn png_bytes(
    w: u32,
    h: u32,
    color: png::ColorType,
    depth: png::BitDepth,
    pixels: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        let mut writer = enc.write_header().unwrap();
        writer.write_image_data(pixels).unwrap();
        writer.finish().unwrap();
    }
    out
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn eight_bit_grayscale_loads_with_the_height_scale() {
    let dir = tempfile::tempdir().unwrap();
    let pixels: Vec<u8> = (0..12).map(|k| (k * 20) as u8).collect();
    let p = write(
        dir.path(),
        "h8.png",
        &png_bytes(
            4,
            3,
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &pixels,
        ),
    );
    let g = load_heightmap(&p, 0.5, 2.0).unwrap();
    assert_eq!((g.nx(), g.nz()), (4, 3));
    assert_eq!(g.cell_size(), 0.5);
    for j in 0..3 {
        for i in 0..4 {
            let want = pixels[j * 4 + i] as f32 / 255.0 * 2.0;
            assert!((g.height(i, j) - want).abs() < 1e-6);
        }
    }
}

#[test]
fn sixteen_bit_round_trip_recovers_the_heights() {
    let grid = HeightGrid::from_fn(Vec2::new(-1.0, 3.0), 0.05, 37, 23, |x, z| {
        (3.0 * x).sin() * 0.4 - 0.2 * z
    })
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("terrain.png");
    let info = save_heightmap_png16(&grid, &p).unwrap();
    let (lo, hi) = grid.min_max_in(&grid.full_rect());
    assert_eq!(
        (info.min, info.max, info.width, info.height),
        (lo, hi, 37, 23)
    );
    let back = load_heightmap_restored(&p, &info).unwrap();
    assert_eq!(
        (back.origin(), back.cell_size()),
        (grid.origin(), grid.cell_size())
    );
    let step = info.height_scale() / 65535.0;
    for (a, b) in back.heights().iter().zip(grid.heights()) {
        assert!((a - b).abs() <= step, "{a} vs {b}");
    }
    // Plain loading gives the normalised heights times the chosen scale.
    let plain = load_heightmap(&p, 0.05, 10.0).unwrap();
    for (a, b) in plain.heights().iter().zip(grid.heights()) {
        let want = (b - lo) / (hi - lo) * 10.0;
        assert!((a - want).abs() <= 10.0 / 65535.0 + 1e-5);
    }
    // A flat grid is stored as zeros and comes back flat.
    let flat = HeightGrid::new(Vec2::ZERO, 1.0, 3, 3, 0.7).unwrap();
    let info = save_heightmap_png16(&flat, &p).unwrap();
    assert_eq!(load_heightmap_restored(&p, &info).unwrap(), flat);
}

#[test]
fn bad_heightmaps_give_typed_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();

    let e = load_heightmap(&d.join("missing.png"), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::Missing { .. }), "{e}");
    assert!(e.to_string().contains("missing.png"));

    let rgb = png_bytes(2, 2, png::ColorType::Rgb, png::BitDepth::Eight, &[0; 12]);
    let e = load_heightmap(&write(d, "rgb.png", &rgb), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::NotGrayscale { .. }), "{e}");
    let ga = png_bytes(
        2,
        2,
        png::ColorType::GrayscaleAlpha,
        png::BitDepth::Eight,
        &[0; 8],
    );
    let e = load_heightmap(&write(d, "ga.png", &ga), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::NotGrayscale { .. }), "{e}");

    let four = png_bytes(
        4,
        2,
        png::ColorType::Grayscale,
        png::BitDepth::Four,
        &[0x12, 0x34, 0x56, 0x78],
    );
    let e = load_heightmap(&write(d, "four.png", &four), 1.0, 1.0).unwrap_err();
    assert!(
        matches!(e, AssetError::UnsupportedBitDepth { depth: 4, .. }),
        "{e}"
    );

    let good = png_bytes(
        64,
        64,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &[7; 64 * 64 * 2],
    );
    for cut in [good.len() - 20, good.len() / 2, 30, 5] {
        let e = load_heightmap(&write(d, "cut.png", &good[..cut]), 1.0, 1.0).unwrap_err();
        assert!(
            matches!(e, AssetError::CorruptPng { .. }),
            "cut at {cut}: {e}"
        );
    }
    let e = load_heightmap(&write(d, "text.png", b"not a png at all"), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::CorruptPng { .. }), "{e}");

    // A header claiming a huge image is refused before any pixel is decoded:
    // the file holds a header and a stub of pixel data, which is never read.
    let side = (MAX_GRID_SAMPLES as f64).sqrt() as u32 + 1;
    let mut huge = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut huge, side, side);
        enc.set_color(png::ColorType::Grayscale);
        let mut writer = enc.write_header().unwrap();
        writer.write_chunk(png::chunk::IDAT, &[0x78, 0x9c]).unwrap();
        drop(writer);
    }
    let e = load_heightmap(&write(d, "huge.png", &huge), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::GridTooLarge { .. }), "{e}");

    let thin = png_bytes(
        1,
        5,
        png::ColorType::Grayscale,
        png::BitDepth::Eight,
        &[1; 5],
    );
    let e = load_heightmap(&write(d, "thin.png", &thin), 1.0, 1.0).unwrap_err();
    assert!(matches!(e, AssetError::Geometry { .. }), "{e}");

    let ok = write(
        d,
        "ok.png",
        &png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &[1; 4],
        ),
    );
    let e = load_heightmap(&ok, f32::NAN, 1.0).unwrap_err();
    assert!(e.to_string().contains("cell"), "{e}");
    let e = load_heightmap(&ok, 1.0, f32::INFINITY).unwrap_err();
    assert!(e.to_string().contains("height_scale"), "{e}");
}

#[test]
fn a_failed_export_writes_nothing() {
    let grid = HeightGrid::new(Vec2::ZERO, 1.0, 3, 3, 0.0).unwrap();
    let e = save_heightmap_png16(&grid, Path::new("/nonexistent-dir/h.png")).unwrap_err();
    assert!(matches!(e, AssetError::Write(_)), "{e}");
}
