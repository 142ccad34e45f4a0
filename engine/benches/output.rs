//! Output speed: PNG encoding of a 1280x720 frame (goal: under the ~16 ms a
//! frame takes to render) and GIF encoding per 960x540 frame.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use engine::output::{GifPalette, GifWriter, encode_png};
use image::{Rgba, RgbaImage};

/// A frame that looks rendered: sky gradient above, shaded noisy ground below,
/// and a few flat-coloured shapes.
fn rendered_looking(width: u32, height: u32) -> RgbaImage {
    let mut state = 0x2545_f491_u32;
    RgbaImage::from_fn(width, height, |x, y| {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        let noise = (state % 9) as u8;
        let horizon = height * 2 / 5;
        if (x / 40 + y / 40) % 11 == 0 {
            Rgba([200, 60, 40, 255])
        } else if y < horizon {
            let t = y * 255 / horizon;
            Rgba([120 + (t / 3) as u8, 160 + (t / 4) as u8, 230, 255])
        } else {
            let shade = 140 + ((x * 7 + y * 3) % 60) as u8;
            Rgba([shade + noise, shade - 20 + noise, 100 + noise, 255])
        }
    })
}

/// On-CPU time of this thread in nanoseconds (Linux `schedstat`), which unlike
/// wall time does not grow when other processes share the cores.
fn thread_cpu_ns() -> Option<u64> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    stat.split_whitespace().next()?.parse().ok()
}

/// Mean on-CPU milliseconds of `f` over `calls` calls, where measurable.
fn on_cpu_ms_per_call(calls: u32, mut f: impl FnMut()) -> Option<f64> {
    let start = thread_cpu_ns()?;
    for _ in 0..calls {
        f();
    }
    Some((thread_cpu_ns()? - start) as f64 / 1e6 / f64::from(calls))
}

fn png(c: &mut Criterion) {
    let frame = rendered_looking(1280, 720);
    c.bench_function("png_encode_1280x720", |b| {
        b.iter(|| black_box(encode_png(black_box(&frame))))
    });
    if let Some(ms) = on_cpu_ms_per_call(30, || {
        black_box(encode_png(&frame));
    }) {
        eprintln!("png_encode_1280x720: {ms:.2} ms on-CPU per frame (load-independent)");
    }
}

fn gif(c: &mut Criterion) {
    let frame = rendered_looking(960, 540);
    let dir = tempfile::tempdir().expect("a temporary directory");
    for (name, palette) in [
        ("gif_frame_960x540_fixed", GifPalette::FixedDithered),
        (
            "gif_frame_960x540_neuquant10",
            GifPalette::Adaptive { speed: 10 },
        ),
        (
            "gif_frame_960x540_neuquant30",
            GifPalette::Adaptive { speed: 30 },
        ),
    ] {
        let mut writer =
            GifWriter::create_with(&dir.path().join(format!("{name}.gif")), 40, palette)
                .expect("a GIF writer");
        if let Some(ms) = on_cpu_ms_per_call(5, || writer.push(&frame).expect("a frame")) {
            eprintln!("{name}: {ms:.2} ms on-CPU per frame (load-independent)");
        }
        c.bench_function(name, |b| {
            b.iter(|| writer.push(black_box(&frame)).expect("a frame"))
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = png, gif
}
criterion_main!(benches);
