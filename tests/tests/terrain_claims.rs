//! The paper's terrain claims (§3.2, §4) as measurable checks, driven by
//! synthetic planted feet: footholds along a line, each planted 0.3 s at
//! 60 Hz, running carve -> smooth -> settle every step.

use glam::Vec2;
use softwalk_app::paper::measure::{rim_split, steepest_slope};
use softwalk_app::paper::stats::mean;
use softwalk_systems::terrain::generate::{self, GridSpec};
use softwalk_systems::terrain::*;
use softwalk_tests::steepest_wall_across;

const DT: f32 = 1.0 / 60.0;
/// 0.3 s of stance at 60 Hz.
const STANCE_STEPS: usize = 18;
/// The paper's sample spacing: 10 m over 512 samples.
const PAPER_CELL: f32 = 10.0 / 511.0;
const BASE: f32 = 1.0;

/// A 4 x 2 m patch at the paper's resolution, flat at `BASE`, all `material`.
fn flat_patch(material: TerrainMaterial) -> Heightfield {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: PAPER_CELL,
        nx: 205,
        nz: 103,
    };
    let mut table = MaterialTable::new();
    let id = table.add(material).unwrap();
    Heightfield::from_grid(generate::flat(spec, BASE).unwrap(), table, id).unwrap()
}

/// Footholds along +X at z = 1 +- 0.09 (left/right), 0.6 m apart.
fn footholds() -> Vec<Vec2> {
    (0..5)
        .map(|k| Vec2::new(0.8 + 0.6 * k as f32, if k % 2 == 0 { 0.91 } else { 1.09 }))
        .collect()
}

/// Walks the footholds heading along `heading`; returns the summed reports.
fn walk_along(hf: &mut Heightfield, holds: &[Vec2], heading: Vec2) -> FootholdReport {
    let mut print = FootPrint::new();
    let mut total = FootholdReport::default();
    for &c in holds {
        let r = plant_foothold(
            hf,
            &mut print,
            c,
            heading,
            FootSize::default(),
            STANCE_STEPS,
            DT,
        )
        .unwrap();
        total.rect = total.rect.union(&r.rect);
        total.carved_volume += r.carved_volume;
        total.compacted_volume += r.compacted_volume;
        total.rim_volume += r.rim_volume;
    }
    total
}

/// Walks the footholds along +X.
fn walk(hf: &mut Heightfield, holds: &[Vec2]) -> FootholdReport {
    walk_along(hf, holds, Vec2::X)
}

/// Depth below the untouched surface at a foothold's centre.
fn print_depth(hf: &Heightfield, c: Vec2) -> f32 {
    BASE - hf
        .lowest_in(c - Vec2::new(0.08, 0.03), c + Vec2::new(0.08, 0.03))
        .unwrap()
}

/// Sharpness of a print: steepest wall slope across it (perpendicular to the
/// walk) divided by its depth, in 1/m: how abruptly the floor meets the surface.
fn sharpness(hf: &Heightfield, c: Vec2) -> f32 {
    steepest_wall_across(hf.grid(), c) / print_depth(hf, c)
}

#[test]
fn claim1_print_depth_order_soil_sand_mud_snow_and_mud_sharper_than_snow() {
    let holds = footholds();
    let mut depth = Vec::new();
    let mut sharp = Vec::new();
    for m in TerrainMaterial::presets() {
        let mut hf = flat_patch(m.clone());
        walk(&mut hf, &holds);
        let d = mean(holds.iter().map(|&c| print_depth(&hf, c)));
        let s = mean(holds.iter().map(|&c| sharpness(&hf, c)));
        println!(
            "{}: depth {d:.4} m (nominal {:.3}), sharpness {s:.1} /m",
            m.name,
            m.print_depth()
        );
        depth.push((m.name.clone(), d));
        sharp.push(s);
    }
    let [sand, soil, mud, snow] = [&depth[0], &depth[1], &depth[2], &depth[3]];
    assert!(
        soil.1 < sand.1,
        "soil {soil:?} not shallower than sand {sand:?}"
    );
    assert!(
        sand.1 < mud.1,
        "sand {sand:?} not shallower than mud {mud:?}"
    );
    assert!(
        mud.1 < snow.1,
        "mud {mud:?} not shallower than snow {snow:?}"
    );
    assert!(
        sharp[2] > sharp[3],
        "mud sharpness {} <= snow {}",
        sharp[2],
        sharp[3]
    );
}

#[test]
fn claim2_volume_is_conserved_without_compression_and_loses_the_compacted_part() {
    let mut loose = TerrainMaterial::dry_sand();
    loose.compression = 0.0;
    let mut hf = flat_patch(loose);
    let before = hf.grid().volume();
    let report = walk(&mut hf, &footholds());
    let after = hf.grid().volume();
    println!(
        "c = 0: carved {:.3e} m3, relative change {:.2e}",
        report.carved_volume,
        (after - before) / before
    );
    assert!(report.carved_volume > 1e-3);
    assert!(((after - before) / before).abs() < 1e-6);
    assert_eq!(report.compacted_volume, 0.0);

    for m in TerrainMaterial::presets() {
        let c = m.compression as f64;
        let mut hf = flat_patch(m.clone());
        let before = hf.grid().volume();
        let report = walk(&mut hf, &footholds());
        let loss = before - hf.grid().volume();
        println!(
            "{}: carved {:.4e}, compacted {:.4e}, loss {:.4e}",
            m.name, report.carved_volume, report.compacted_volume, loss
        );
        assert!(
            (report.compacted_volume - c * report.carved_volume).abs()
                < 1e-9 * report.carved_volume
        );
        assert!(
            (loss - report.compacted_volume).abs() < 1e-6 * before,
            "{}: loss {loss} vs compacted {}",
            m.name,
            report.compacted_volume
        );
        assert!(
            (report.rim_volume - (1.0 - c) * report.carved_volume).abs()
                < 1e-9 * report.carved_volume
        );
    }
}

#[test]
fn claim3_no_slope_in_the_dirty_window_exceeds_the_angle_of_repose() {
    for m in TerrainMaterial::presets() {
        let mut hf = flat_patch(m.clone());
        let report = walk(&mut hf, &footholds());
        let worst = steepest_slope(hf.grid(), report.rect);
        println!(
            "{}: steepest {:.1} deg, repose {} deg",
            m.name,
            worst.atan().to_degrees(),
            m.repose_deg
        );
        assert!(
            worst <= m.repose_slope() + 0.01,
            "{}: slope {worst}",
            m.name
        );
    }
}

#[test]
fn claim3_a_print_on_a_25_degree_sand_slope_slumps_downhill() {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: PAPER_CELL,
        nx: 103,
        nz: 205,
    };
    // Walking straight up the slope (+Z), left and right feet.
    let holds: Vec<Vec2> = (0..3)
        .map(|k| Vec2::new(if k % 2 == 0 { 0.91 } else { 1.09 }, 1.0 + 0.6 * k as f32))
        .collect();
    let mut ratios = Vec::new();
    for angle in [0.0, 25.0] {
        let grid = generate::slope(spec, 2.0, angle, Vec2::Y).unwrap();
        let untouched = grid.clone();
        let mut table = MaterialTable::new();
        let sand = table.add(TerrainMaterial::dry_sand()).unwrap();
        let mut hf = Heightfield::from_grid(grid, table, sand).unwrap();
        let report = walk_along(&mut hf, &holds, Vec2::Y);
        let ratio = mean(holds.iter().map(|&c| {
            let (down, up) = rim_split(hf.grid(), &untouched, c, Vec2::Y);
            down / up.max(1e-9)
        }));
        let worst = steepest_slope(hf.grid(), report.rect);
        println!(
            "{angle} deg: downhill/uphill rim volume {ratio:.2}, steepest {:.1} deg",
            worst.atan().to_degrees()
        );
        assert!(worst <= TerrainMaterial::dry_sand().repose_slope() + 0.01);
        ratios.push(ratio);
    }
    assert!(
        (0.8..1.25).contains(&ratios[0]),
        "flat print rim not symmetric: {}",
        ratios[0]
    );
    // Where the grid's samples fall moves this ratio by about ±5 % (2.9 to
    // 3.2 for the same prints with the grid shifted by a quarter cell), so
    // the claim asks for a clear majority downhill, not a figure at the edge
    // of that spread.
    assert!(
        ratios[1] > 2.5,
        "slope print rim not pushed downhill: {}",
        ratios[1]
    );
}

#[test]
fn claim5_one_step_changes_only_the_print_its_rim_and_the_stage_margin() {
    let mut hf = flat_patch(TerrainMaterial::dry_sand());
    let mut print = FootPrint::new();
    let center = Vec2::new(1.5, 1.0);
    let size = FootSize::default();
    let mut changed_total = 0;
    for step in 0..=STANCE_STEPS {
        let contact = step < STANCE_STEPS;
        hf.begin_step();
        let sole = press_into(&hf, sole_on_ground(&hf, center, Vec2::X, size).unwrap(), DT);
        let touched = print.touched();
        let before = hf.grid().clone();
        step_foot(&mut hf, &mut print, &sole, contact, DT).unwrap();
        let foot = Footprint::from_sole(&sole).unwrap();
        let rim = rim_width(foot.radius);
        let (lo, hi) = foot.bounds(rim);
        let reach = if contact {
            hf.grid().rect_covering(lo, hi)
        } else {
            touched
        };
        let bound = stage_window(&hf, reach);
        let (nx, nz) = (before.nx(), before.nz());
        for j in 0..nz {
            for i in 0..nx {
                if before.height(i, j) != hf.grid().height(i, j) {
                    changed_total += 1;
                    assert!(
                        bound.contains(i, j),
                        "step {step}: ({i}, {j}) changed outside {bound:?}"
                    );
                }
            }
        }
        assert!(
            bound.area() < 45 * 35,
            "bound {bound:?} too large for one foot"
        );
    }
    assert!(changed_total > 0);
}
