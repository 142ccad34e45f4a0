//! Image and animation files: round trips, atomic writes, typed errors.

use std::fs;
use std::io::BufReader;
use std::path::Path;

use engine::output::{
    ApngWriter, GifPalette, GifWriter, OutputError, contact_sheet, save_png, save_png_gray16,
};
use image::codecs::gif::GifDecoder;
use image::codecs::png::PngDecoder;
use image::{AnimationDecoder, Rgba, RgbaImage};

/// A gradient with deterministic noise, like a rendered frame.
fn frame(width: u32, height: u32, seed: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let noise = (x.wrapping_mul(73_856_093)
            ^ y.wrapping_mul(19_349_663)
            ^ seed.wrapping_mul(83_492_791))
            % 17;
        Rgba([
            (x * 255 / width) as u8,
            (y * 255 / height) as u8,
            (seed * 40 + noise) as u8,
            255,
        ])
    })
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn png_round_trip_gives_identical_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frame.png");
    let img = frame(97, 41, 1);
    save_png(&path, &img).unwrap();
    assert_eq!(image::open(&path).unwrap().into_rgba8(), img);
    assert_eq!(files_in(dir.path()), ["frame.png"]);
}

#[test]
fn gray16_round_trip_keeps_all_sixteen_bits() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("height.png");
    let samples: Vec<u16> = (0..12 * 7).map(|i| (i * 781) as u16).collect();
    save_png_gray16(&path, 12, 7, &samples).unwrap();
    let decoded = image::open(&path).unwrap().into_luma16();
    assert_eq!(decoded.dimensions(), (12, 7));
    assert_eq!(decoded.into_raw(), samples);
}

#[test]
fn bad_sizes_are_typed_errors_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.png");
    let err = save_png_gray16(&path, 4, 4, &[0; 15]).unwrap_err();
    assert!(
        matches!(
            err,
            OutputError::InvalidParameter {
                parameter: "samples",
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("h.png"));
    let err = save_png(&path, &RgbaImage::new(0, 5)).unwrap_err();
    assert!(
        matches!(
            err,
            OutputError::InvalidParameter {
                parameter: "size",
                ..
            }
        ),
        "{err}"
    );
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn failed_overwrite_leaves_the_old_file_intact() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frame.png");
    let old = frame(8, 8, 2);
    save_png(&path, &old).unwrap();
    assert!(save_png(&path, &RgbaImage::new(0, 0)).is_err());
    assert_eq!(image::open(&path).unwrap().into_rgba8(), old);
    // A directory in the way: the rename fails, and no temporary file remains.
    fs::create_dir(dir.path().join("busy.png")).unwrap();
    fs::write(dir.path().join("busy.png").join("keep"), b"x").unwrap();
    assert!(save_png(&dir.path().join("busy.png"), &old).is_err());
    assert_eq!(files_in(dir.path()), ["busy.png", "frame.png"]);
}

#[test]
fn unwritable_directory_is_a_typed_error_naming_the_file() {
    let missing = Path::new("/nonexistent-softwalk-dir/out.png");
    let err = save_png(missing, &frame(4, 4, 0)).unwrap_err();
    assert!(matches!(err, OutputError::Write(_)));
    assert!(
        err.to_string().contains("nonexistent-softwalk-dir/out.png"),
        "{err}"
    );
    let err = GifWriter::create(&missing.with_extension("gif"), 40)
        .err()
        .unwrap();
    assert!(
        matches!(err, OutputError::Write(_)) && err.to_string().contains("out.gif"),
        "{err}"
    );
    let err = ApngWriter::create(missing, 40).err().unwrap();
    assert!(err.to_string().contains("out.png"), "{err}");
}

fn decode_gif(path: &Path) -> Vec<RgbaImage> {
    let decoder = GifDecoder::new(BufReader::new(fs::File::open(path).unwrap())).unwrap();
    decoder
        .into_frames()
        .map(|f| f.unwrap().into_buffer())
        .collect()
}

#[test]
fn gif_decodes_with_frame_count_size_and_palette_colours() {
    let dir = tempfile::tempdir().unwrap();
    for (name, palette) in [
        ("fixed.gif", GifPalette::FixedDithered),
        ("adaptive.gif", GifPalette::Adaptive { speed: 10 }),
    ] {
        let path = dir.path().join(name);
        let mut gif = GifWriter::create_with(&path, 40, palette).unwrap();
        let colours = [
            Rgba([255, 0, 0, 255]),
            Rgba([0, 0, 255, 255]),
            Rgba([255, 255, 255, 255]),
        ];
        for c in colours {
            gif.push(&RgbaImage::from_pixel(40, 30, c)).unwrap();
        }
        assert_eq!(gif.frame_count(), 3);
        gif.finish().unwrap();
        let frames = decode_gif(&path);
        assert_eq!(frames.len(), 3, "{name}");
        for (f, c) in frames.iter().zip(colours) {
            assert_eq!(f.dimensions(), (40, 30));
            assert_eq!(f.get_pixel(20, 15), &c, "{name}");
        }
    }
}

#[test]
fn gif_dithers_gradients_to_nearby_colours() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("g.gif");
    let img = frame(64, 48, 3);
    let mut gif = GifWriter::create(&path, 100).unwrap();
    gif.push(&img).unwrap();
    gif.finish().unwrap();
    let decoded = &decode_gif(&path)[0];
    // Ordered dithering keeps each pixel within one palette step (51) per channel.
    for (a, b) in img.pixels().zip(decoded.pixels()) {
        for c in 0..3 {
            assert!(
                (i32::from(a[c]) - i32::from(b[c])).abs() <= 51,
                "{a:?} vs {b:?}"
            );
        }
    }
}

#[test]
fn apng_decodes_losslessly_with_the_frame_count() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.png");
    let frames: Vec<RgbaImage> = (0..4).map(|i| frame(33, 21, i)).collect();
    let mut apng = ApngWriter::create(&path, 50).unwrap();
    for f in &frames {
        apng.push(f).unwrap();
    }
    apng.finish().unwrap();
    let decoder = PngDecoder::new(BufReader::new(fs::File::open(&path).unwrap())).unwrap();
    assert!(decoder.is_apng().unwrap());
    let decoded: Vec<RgbaImage> = decoder
        .apng()
        .unwrap()
        .into_frames()
        .map(|f| f.unwrap().into_buffer())
        .collect();
    assert_eq!(decoded, frames);
    assert_eq!(files_in(dir.path()), ["walk.png"]);
}

#[test]
fn animations_dropped_or_empty_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    {
        let mut gif = GifWriter::create(&dir.path().join("a.gif"), 40).unwrap();
        gif.push(&frame(8, 8, 0)).unwrap();
        let mut apng = ApngWriter::create(&dir.path().join("a.png"), 40).unwrap();
        apng.push(&frame(8, 8, 0)).unwrap();
    }
    assert!(files_in(dir.path()).is_empty());
    let err = GifWriter::create(&dir.path().join("b.gif"), 40)
        .unwrap()
        .finish()
        .unwrap_err();
    assert!(matches!(err, OutputError::NoFrames { .. }), "{err}");
    let err = ApngWriter::create(&dir.path().join("b.png"), 40)
        .unwrap()
        .finish()
        .unwrap_err();
    assert!(matches!(err, OutputError::NoFrames { .. }), "{err}");
    assert!(files_in(dir.path()).is_empty());
}

#[test]
fn frames_of_another_size_and_bad_delays_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let mut gif = GifWriter::create(&dir.path().join("a.gif"), 40).unwrap();
    gif.push(&frame(8, 8, 0)).unwrap();
    let err = gif.push(&frame(9, 8, 0)).unwrap_err();
    assert!(
        matches!(
            err,
            OutputError::FrameSize {
                index: 1,
                found_width: 9,
                ..
            }
        ),
        "{err}"
    );
    let mut apng = ApngWriter::create(&dir.path().join("a.png"), 40).unwrap();
    apng.push(&frame(8, 8, 0)).unwrap();
    assert!(matches!(
        apng.push(&frame(8, 3, 0)),
        Err(OutputError::FrameSize { .. })
    ));
    let err = GifWriter::create(&dir.path().join("c.gif"), 5)
        .err()
        .unwrap();
    assert!(matches!(
        err,
        OutputError::InvalidParameter {
            parameter: "delay_ms",
            ..
        }
    ));
    let err = GifWriter::create_with(
        &dir.path().join("c.gif"),
        40,
        GifPalette::Adaptive { speed: 31 },
    );
    assert!(matches!(
        err.err().unwrap(),
        OutputError::InvalidParameter {
            parameter: "speed",
            ..
        }
    ));
    assert!(matches!(
        ApngWriter::create(&dir.path().join("c.png"), 70_000)
            .err()
            .unwrap(),
        OutputError::InvalidParameter { .. }
    ));
}

#[test]
fn contact_sheet_places_thumbnails_row_by_row() {
    let colours: Vec<Rgba<u8>> = (0..5u8)
        .map(|i| Rgba([i * 50, 255 - i * 50, 100, 255]))
        .collect();
    let frames: Vec<RgbaImage> = colours
        .iter()
        .map(|&c| RgbaImage::from_pixel(80, 40, c))
        .collect();
    let background = Rgba([0, 0, 0, 255]);
    let sheet = contact_sheet(&frames, 3, 40, background);
    // 3 columns of 40 px and 2 rows of 20 px, with 4 px gaps around.
    assert_eq!(sheet.dimensions(), (3 * 40 + 4 * 4, 2 * 20 + 3 * 4));
    for (i, c) in colours.iter().enumerate() {
        let (col, row) = (i as u32 % 3, i as u32 / 3);
        assert_eq!(
            sheet.get_pixel(4 + col * 44 + 20, 4 + row * 24 + 10),
            c,
            "frame {i}"
        );
    }
    assert_eq!(sheet.get_pixel(2, 2), &background);
    assert_eq!(
        sheet.get_pixel(4 + 2 * 44 + 20, 4 + 24 + 10),
        &background,
        "empty sixth cell"
    );
    assert_eq!(contact_sheet(&[], 3, 40, background).dimensions(), (1, 1));
}
