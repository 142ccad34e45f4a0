//! Terrain parameters are in metres and seconds, and loose ground is a layer
//! over firm ground: the same synthetic planted foot gives the same print at
//! any grid resolution (256, 512, 1024 samples over 10 m) and step rate (30,
//! 60, 120 Hz), and however often a foot presses the same spot, nothing goes
//! below the initial surface minus the material's layer.

use glam::{Vec2, Vec3};
use softwalk_systems::foot::FootSole;
use softwalk_systems::terrain::generate::{self, GridSpec};
use softwalk_systems::terrain::*;
use softwalk_tests::steepest_wall_across;

const BASE: f32 = 1.0;
/// Contact time of a planted foot, seconds.
const STANCE_S: f32 = 0.3;
/// Where the foot is planted, on a 2 x 2 m patch.
const CENTER: Vec2 = Vec2::new(1.0, 1.0);
/// Sample counts over 10 m.
const RESOLUTIONS: [usize; 3] = [256, 512, 1024];
/// Step rates, Hz.
const RATES: [f32; 3] = [30.0, 60.0, 120.0];

/// A 2 x 2 m flat patch of `material` with the spacing of `samples` samples
/// over 10 m.
fn patch(material: &TerrainMaterial, samples: usize) -> Heightfield {
    let cell = 10.0 / (samples - 1) as f32;
    let n = (2.0 / cell).ceil() as usize + 1;
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell,
        nx: n,
        nz: n,
    };
    let mut table = MaterialTable::new();
    let id = table.add(material.clone()).unwrap();
    Heightfield::from_grid(generate::flat(spec, BASE).unwrap(), table, id).unwrap()
}

/// Plants the default foot at [`CENTER`] for [`STANCE_S`] at `rate`, then
/// lets the print settle.
fn plant(hf: &mut Heightfield, rate: f32) -> FootholdReport {
    plant_at(hf, CENTER, rate)
}

/// Plants the default foot at `center` for [`STANCE_S`] at `rate`, then
/// lets the print settle.
fn plant_at(hf: &mut Heightfield, center: Vec2, rate: f32) -> FootholdReport {
    let steps = (STANCE_S * rate).round() as usize;
    let mut print = FootPrint::new();
    let size = FootSize::default();
    plant_foothold(hf, &mut print, center, Vec2::X, size, steps, 1.0 / rate).unwrap()
}

/// What a print looks like: its depth below the initial surface, the volume
/// raised above the initial surface over the volume below it, and the
/// sharpness of its walls (steepest slope across it over its depth, 1/m).
#[derive(Debug, Clone, Copy)]
struct Print {
    depth: f32,
    rim_fraction: f64,
    sharpness: f32,
}

fn measure(hf: &Heightfield) -> Print {
    measure_at(hf, CENTER)
}

/// [`measure`] for a print centred at `center`.
fn measure_at(hf: &Heightfield, center: Vec2) -> Print {
    let g = hf.grid();
    let lowest = hf
        .lowest_in(
            center - Vec2::new(0.08, 0.03),
            center + Vec2::new(0.08, 0.03),
        )
        .unwrap();
    let depth = BASE - lowest;
    let rect = g.rect_covering(center - Vec2::splat(0.35), center + Vec2::splat(0.35));
    let (mut above, mut below) = (0.0f64, 0.0f64);
    for (i, j) in rect.iter() {
        let d = f64::from(g.height(i, j) - hf.initial().height(i, j));
        if d > 0.0 {
            above += d;
        } else {
            below -= d;
        }
    }
    let steepest = steepest_wall_across(g, center);
    Print {
        depth,
        rim_fraction: above / below,
        sharpness: steepest / depth,
    }
}

/// The print a fresh patch of `material` gets at `samples` and `rate`,
/// averaged over four placements a quarter of a cell apart across the walk:
/// a print's lowest sample depends on where the samples fall under its V
/// or flat bottom, by up to half a cell's slope, which is not what differs
/// between resolutions.
fn print_of(material: &TerrainMaterial, samples: usize, rate: f32) -> Print {
    let cell = 10.0 / (samples - 1) as f32;
    let prints: Vec<Print> = (0..4)
        .map(|k| {
            let center = CENTER + Vec2::new(0.0, 0.25 * k as f32 * cell);
            let mut hf = patch(material, samples);
            plant_at(&mut hf, center, rate);
            measure_at(&hf, center)
        })
        .collect();
    let p = Print {
        depth: prints.iter().map(|p| p.depth).sum::<f32>() / 4.0,
        rim_fraction: prints.iter().map(|p| p.rim_fraction).sum::<f64>() / 4.0,
        sharpness: prints.iter().map(|p| p.sharpness).sum::<f32>() / 4.0,
    };
    println!(
        "{:5} {samples:5} samples {rate:4} Hz: depth {:.4} m, rim fraction {:.3}, sharpness {:.1} /m",
        material.name, p.depth, p.rim_fraction, p.sharpness
    );
    p
}

/// Checks that every print of `prints` matches `prints[1]` (the paper's
/// 512 samples, or 60 Hz) within 10 % in depth and within 0.06 in rim
/// fraction (a fraction of the displaced volume: an absolute tolerance; on
/// 256 samples over 10 m a 10 cm sole is 2.5 cells wide, and diffusion
/// mixes less of the rim into a print whose wall is one cell).
fn assert_alike(material: &TerrainMaterial, what: &str, prints: &[Print]) {
    let reference = prints[1];
    for p in prints {
        assert!(
            (p.depth - reference.depth).abs() <= 0.1 * reference.depth,
            "{} across {what}: depth {} vs {}",
            material.name,
            p.depth,
            reference.depth
        );
        assert!(
            (p.rim_fraction - reference.rim_fraction).abs() <= 0.06,
            "{} across {what}: rim fraction {} vs {}",
            material.name,
            p.rim_fraction,
            reference.rim_fraction
        );
    }
}

#[test]
fn a_print_is_the_same_at_256_512_and_1024_samples_over_10_m() {
    for m in TerrainMaterial::presets() {
        let prints: Vec<Print> = RESOLUTIONS.iter().map(|&n| print_of(&m, n, 60.0)).collect();
        assert_alike(&m, "resolutions", &prints);
    }
}

#[test]
fn a_print_is_the_same_at_30_60_and_120_hz() {
    for m in TerrainMaterial::presets() {
        let prints: Vec<Print> = RATES.iter().map(|&r| print_of(&m, 512, r)).collect();
        assert_alike(&m, "step rates", &prints);
    }
}

#[test]
fn the_depth_order_and_mud_sharper_than_snow_hold_at_every_resolution() {
    for n in RESOLUTIONS {
        let [sand, soil, mud, snow] = TerrainMaterial::presets().map(|m| print_of(&m, n, 60.0));
        assert!(soil.depth < sand.depth, "{n}: soil {soil:?} sand {sand:?}");
        assert!(sand.depth < mud.depth, "{n}: sand {sand:?} mud {mud:?}");
        assert!(mud.depth < snow.depth, "{n}: mud {mud:?} snow {snow:?}");
        assert!(
            mud.sharpness > snow.sharpness,
            "{n}: mud {mud:?} snow {snow:?}"
        );
    }
}

/// True when no sample of `hf` is below its firm floor.
fn above_the_floor(hf: &Heightfield) -> bool {
    let heights = hf.grid().heights();
    (0..heights.len()).all(|k| heights[k] >= hf.firm_floor(k) - 1e-6)
}

#[test]
fn repeated_plants_stop_at_the_floor() {
    for m in TerrainMaterial::presets() {
        let mut hf = patch(&m, 512);
        for _ in 0..200 {
            plant(&mut hf, 60.0);
            // Carving, smoothing and settling never went below the floor.
            assert!(above_the_floor(&hf), "{}", m.name);
        }
        let p = measure(&hf);
        println!(
            "{}: after 200 plants depth {:.4} m (layer {}, print depth {})",
            m.name,
            p.depth,
            m.layer,
            m.print_depth()
        );
        assert!(p.depth <= m.layer + 1e-5, "{}: {p:?}", m.name);
        assert!(p.depth > 0.5 * m.layer.min(m.print_depth()), "{}", m.name);
    }
}

#[test]
fn give_is_the_print_depth_on_fresh_ground_and_nothing_on_the_floor() {
    for m in TerrainMaterial::presets() {
        let mut hf = patch(&m, 512);
        let fresh = hf.give_at(CENTER.x, CENTER.y).unwrap();
        assert!(
            (fresh - m.print_depth().min(m.layer)).abs() < 1e-6,
            "{}: {fresh}",
            m.name
        );
        // Press (no release) until the sole stops sinking: every preset's
        // layer is at most its print depth, so the print reaches the floor.
        let mut print = FootPrint::new();
        for _ in 0..30 {
            hf.begin_step();
            let sole = sole_on_ground(&hf, CENTER, Vec2::X, FootSize::default()).unwrap();
            let sole = press_into(&hf, sole, 1.0 / 60.0);
            step_foot(&mut hf, &mut print, &sole, true, 1.0 / 60.0).unwrap();
        }
        assert_eq!(hf.give_at(CENTER.x, CENTER.y), Some(0.0), "{}", m.name);
        assert!(hf.give_at(-1.0, 0.0).is_none());
        assert_eq!(hf.initial().height_at(CENTER.x, CENTER.y), Some(BASE));
    }
}

#[test]
fn the_carved_volume_is_the_same_at_every_resolution_and_rate() {
    // The print's edge is anti-aliased, so the volume a sole presses out is
    // its area times the depth on any grid (within 5 %), and at any rate.
    for m in TerrainMaterial::presets() {
        let volume = |samples: usize, rate: f32| {
            let mut hf = patch(&m, samples);
            plant(&mut hf, rate).carved_volume
        };
        let reference = volume(512, 60.0);
        for (samples, rate) in [(256, 60.0), (1024, 60.0), (512, 30.0), (512, 120.0)] {
            let v = volume(samples, rate);
            println!(
                "{} {samples} samples {rate} Hz: carved {v:.4e} m3 (512, 60 Hz: {reference:.4e})",
                m.name
            );
            assert!(
                (v - reference).abs() <= 0.05 * reference,
                "{} at {samples} samples, {rate} Hz: {v} vs {reference}",
                m.name
            );
        }
    }
}

#[test]
fn a_sole_on_its_prints_floor_reads_that_floor_under_heel_centre_and_toe() {
    // A flat sole held at the snow's firm floor presses its print down to
    // it; the surface read under the sole (at the centres of its rounded
    // heel and toe and at its centre) is that floor, not the print's wall,
    // wherever the samples fall under the sole: for an adult's and a
    // child's foot on grids of the reference cell or finer, and within a
    // centimetre for an adult's foot on cells twice as large (a child's
    // foot, 5.5 cm wide, is then barely wider than one cell).
    let snow = TerrainMaterial::snow();
    let floor = BASE - snow.layer;
    let (adult, child) = ((0.26, 0.10), (0.152, 0.055));
    let cases = [
        (512, adult, 0.001),
        (512, child, 0.001),
        (1024, adult, 0.001),
        (1024, child, 0.001),
        (256, adult, 0.012),
    ];
    for (samples, (length, width), tolerance) in cases {
        for shift in [0.0, 0.3, 0.5, 0.8] {
            let mut hf = patch(&snow, samples);
            let cell = hf.grid().cell_size();
            let c = CENTER + Vec2::new(shift, 0.7 * shift) * cell;
            let half = Vec3::X * (0.5 * length);
            let at = Vec3::new(c.x, floor, c.y);
            let sole = FootSole {
                heel: at - half,
                toe: at + half,
                width,
            };
            let mut print = FootPrint::new();
            hf.begin_step();
            carve(&mut hf, &mut print, &sole, true, 1.0 / 60.0).unwrap();
            let inset = Vec3::X * (0.5 * width);
            for p in [sole.heel + inset, at, sole.toe - inset] {
                let read = hf.grid().height_at(p.x, p.z).unwrap();
                assert!(
                    read - floor <= tolerance,
                    "{samples} samples, foot {length} x {width}, shift {shift}: \
                     {read} over the floor {floor} at {p}"
                );
            }
        }
    }
}
