//! Terrain edge cases, bad input and determinism.

use glam::{Vec2, Vec3};
use softwalk_systems::foot::FootSole;
use softwalk_systems::terrain::generate::{self, GridSpec, NoiseParams};
use softwalk_systems::terrain::*;

const DT: f32 = 1.0 / 60.0;
const CELL: f32 = 10.0 / 511.0;

fn patch(material: TerrainMaterial, nx: usize, nz: usize) -> Heightfield {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: CELL,
        nx,
        nz,
    };
    let mut table = MaterialTable::new();
    let id = table.add(material).unwrap();
    Heightfield::from_grid(generate::flat(spec, 1.0).unwrap(), table, id).unwrap()
}

fn loose_sand() -> TerrainMaterial {
    TerrainMaterial {
        compression: 0.0,
        ..TerrainMaterial::dry_sand()
    }
}

fn plant(hf: &mut Heightfield, center: Vec2, heading: Vec2, steps: usize) -> FootholdReport {
    let mut print = FootPrint::new();
    plant_foothold(
        hf,
        &mut print,
        center,
        heading,
        FootSize::default(),
        steps,
        DT,
    )
    .unwrap()
}

#[test]
fn a_foot_fully_off_the_grid_does_nothing() {
    let mut hf = patch(TerrainMaterial::mud(), 60, 60);
    let before = hf.grid().clone();
    for c in [
        Vec2::new(-1.0, 0.5),
        Vec2::new(5.0, 5.0),
        Vec2::new(0.5, -0.4),
    ] {
        let report = plant(&mut hf, c, Vec2::X, 18);
        assert!(report.rect.is_empty());
    }
    assert_eq!(hf.grid(), &before);
    assert!(hf.dirty().is_empty());
}

#[test]
fn a_foot_half_off_any_edge_or_corner_carves_what_exists_and_conserves_volume() {
    let size = 60;
    let far = (size - 1) as f32 * CELL;
    let spots = [
        Vec2::new(0.0, 0.6),
        Vec2::new(far, 0.6),
        Vec2::new(0.6, 0.0),
        Vec2::new(0.6, far),
        Vec2::new(0.0, 0.0),
        Vec2::new(far, far),
        Vec2::new(far + 0.1, 0.6),
    ];
    for (k, &c) in spots.iter().enumerate() {
        let heading = if k % 2 == 0 {
            Vec2::X
        } else {
            Vec2::new(0.6, 0.8)
        };
        let mut hf = patch(loose_sand(), size, size);
        let before = hf.grid().volume();
        let report = plant(&mut hf, c, heading, 18);
        assert!(report.carved_volume > 0.0, "spot {c}: nothing carved");
        let rel = (hf.grid().volume() - before) / before;
        assert!(rel.abs() < 1e-6, "spot {c}: volume changed by {rel:e}");
        assert!(hf.grid().heights().iter().all(|h| h.is_finite()));
    }
}

#[test]
fn a_grid_smaller_than_the_foot_counts_the_unplaceable_rim_as_compacted() {
    let mut hf = patch(loose_sand(), 2, 2);
    let before = hf.grid().volume();
    let report = plant(&mut hf, Vec2::splat(0.5 * CELL), Vec2::X, 18);
    assert!(report.carved_volume > 0.0);
    assert_eq!(report.compacted_volume, report.carved_volume);
    let loss = before - hf.grid().volume();
    assert!((loss - report.compacted_volume).abs() < 1e-9);
}

#[test]
fn a_planted_foot_stops_at_the_print_depth() {
    for m in TerrainMaterial::presets() {
        // Or at firm ground, where the loose layer is thinner (mud).
        let depth = m.print_depth().min(m.layer);
        let mut hf = patch(m.clone(), 40, 40);
        let mut print = FootPrint::new();
        let c = Vec2::splat(20.0 * CELL);
        // Ten seconds of the ray -> carve -> lower foot feedback.
        for _ in 0..600 {
            hf.begin_step();
            let sole = sole_on_ground(&hf, c, Vec2::X, FootSize::default()).unwrap();
            let sole = press_into(&hf, sole, DT);
            step_foot(&mut hf, &mut print, &sole, true, DT).unwrap();
        }
        let lowest = hf.grid().min_max_in(&hf.grid().full_rect()).0;
        assert!(
            (1.0 - lowest - depth).abs() < 1e-4,
            "{}: sank {}",
            m.name,
            1.0 - lowest
        );
        assert!(print.reference_height(20, 20).is_some());
    }
}

#[test]
fn a_raised_toe_leaves_the_ground_under_it() {
    let mut hf = patch(TerrainMaterial::snow(), 60, 40);
    let mut print = FootPrint::new();
    let sole = FootSole {
        heel: Vec3::new(0.3, 0.7, 0.4),
        toe: Vec3::new(0.56, 1.08, 0.4),
        width: 0.1,
    };
    for _ in 0..10 {
        hf.begin_step();
        carve(&mut hf, &mut print, &sole, true, DT).unwrap();
    }
    let g = hf.grid();
    let heel = g.height_at(0.33, 0.4).unwrap();
    let toe = g.height_at(0.53, 0.4).unwrap();
    assert!(heel < 0.9, "heel not pressed: {heel}");
    assert_eq!(toe, 1.0, "raised toe pressed the ground");
}

#[test]
fn a_rolling_foot_grows_its_reference_window() {
    let mut hf = patch(TerrainMaterial::mud(), 80, 80);
    let mut print = FootPrint::new();
    let heel = Vec2::splat(0.75);
    for k in 0..30 {
        hf.begin_step();
        let a = k as f32 * 0.1;
        let toe = heel + Vec2::new(a.cos(), a.sin()) * 0.26;
        let sole = FootSole {
            heel: Vec3::new(heel.x, 0.8, heel.y),
            toe: Vec3::new(toe.x, 0.8, toe.y),
            width: 0.1,
        };
        step_foot(&mut hf, &mut print, &sole, true, DT).unwrap();
    }
    let lowest = hf.grid().min_max_in(&hf.grid().full_rect()).0;
    assert!(lowest >= 1.0 - TerrainMaterial::mud().print_depth() - 1e-5);
    assert!(lowest < 0.9);
}

#[test]
fn materials_side_by_side_print_to_their_own_depth() {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: CELL,
        nx: 80,
        nz: 40,
    };
    let table = MaterialTable::with_presets();
    let (soil, snow) = (table.id("soil").unwrap(), table.id("snow").unwrap());
    let mut hf = Heightfield::from_grid(generate::flat(spec, 1.0).unwrap(), table, soil).unwrap();
    hf.paint_bands_x(&[soil, snow]).unwrap();
    // A foot straddling the border at x = 0.78 m.
    plant(&mut hf, Vec2::new(0.78, 0.4), Vec2::X, 18);
    let soil_floor = hf
        .lowest_in(Vec2::new(0.66, 0.38), Vec2::new(0.72, 0.42))
        .unwrap();
    let snow_floor = hf
        .lowest_in(Vec2::new(0.84, 0.38), Vec2::new(0.9, 0.42))
        .unwrap();
    assert!(1.0 - soil_floor <= TerrainMaterial::soil().print_depth() + 1e-5);
    assert!(
        1.0 - snow_floor > 0.2,
        "snow side only {}",
        1.0 - snow_floor
    );
}

#[test]
fn settling_leaves_natural_over_steep_slopes_alone() {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: CELL,
        nx: 60,
        nz: 120,
    };
    let grid = generate::slope(spec, 2.0, 40.0, Vec2::Y).unwrap();
    let untouched = grid.clone();
    let mut hf =
        Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap();
    let full = hf.grid().full_rect();
    assert!(settle(&mut hf, full).is_empty());
    assert_eq!(hf.grid(), &untouched);
    // A print on the 40 degree slope slumps, but only inside its stage windows.
    let report = plant(&mut hf, Vec2::new(0.58, 1.16), Vec2::Y, 18);
    let changed: Vec<(usize, usize)> = hf
        .grid()
        .full_rect()
        .iter()
        .filter(|&(i, j)| hf.grid().height(i, j) != untouched.height(i, j))
        .collect();
    assert!(!changed.is_empty());
    assert!(changed.iter().all(|&(i, j)| report.rect.contains(i, j)));
    assert!(
        report.rect.height() < 60,
        "slump crept along the slope: {:?}",
        report.rect
    );
}

#[test]
fn bad_carving_input_is_a_named_error() {
    let mut hf = patch(TerrainMaterial::soil(), 20, 20);
    let mut print = FootPrint::new();
    let good = FootSole {
        heel: Vec3::new(0.1, 1.0, 0.2),
        toe: Vec3::new(0.3, 1.0, 0.2),
        width: 0.1,
    };
    fn name<T: std::fmt::Debug>(r: Result<T, TerrainError>) -> &'static str {
        match r {
            Err(TerrainError::InvalidParameter { name, .. }) => name,
            other => panic!("expected an invalid parameter, got {other:?}"),
        }
    }
    assert_eq!(
        name(carve(&mut hf, &mut print, &good, true, f32::NAN)),
        "dt"
    );
    assert_eq!(name(carve(&mut hf, &mut print, &good, true, -0.1)), "dt");
    let nan = FootSole {
        heel: Vec3::NAN,
        ..good
    };
    assert_eq!(name(carve(&mut hf, &mut print, &nan, true, DT)), "sole");
    let flat = FootSole { width: 0.0, ..good };
    assert_eq!(
        name(carve(&mut hf, &mut print, &flat, true, DT)),
        "sole.width"
    );
    assert_eq!(
        name(sole_on_ground(
            &hf,
            Vec2::ONE,
            Vec2::ZERO,
            FootSize::default()
        )),
        "heading"
    );
    assert_eq!(
        name(sole_on_ground(&hf, Vec2::NAN, Vec2::X, FootSize::default())),
        "center"
    );
    assert!(matches!(
        MaterialTable::with_presets().id("lava"),
        Err(TerrainError::UnknownMaterial { .. })
    ));
}

/// A walk over fBm hills with all four materials in bands.
fn noisy_walk() -> Heightfield {
    let spec = GridSpec {
        origin: Vec2::ZERO,
        cell: CELL,
        nx: 160,
        nz: 60,
    };
    let grid = generate::noise(
        spec,
        NoiseParams {
            amplitude: 0.2,
            feature_size: 1.0,
            ..NoiseParams::default()
        },
    )
    .unwrap();
    let mut hf =
        Heightfield::from_grid(grid, MaterialTable::with_presets(), MaterialId(0)).unwrap();
    hf.paint_bands_x(&[MaterialId(0), MaterialId(1), MaterialId(2), MaterialId(3)])
        .unwrap();
    let mut print = FootPrint::new();
    for k in 0..5 {
        let c = Vec2::new(0.3 + 0.55 * k as f32, if k % 2 == 0 { 0.5 } else { 0.68 });
        plant_foothold(
            &mut hf,
            &mut print,
            c,
            Vec2::new(1.0, 0.1),
            FootSize::default(),
            18,
            DT,
        )
        .unwrap();
    }
    hf
}

#[test]
fn the_same_walk_gives_bit_identical_terrain_on_any_thread() {
    let bits = |hf: &Heightfield| -> Vec<u32> {
        hf.grid().heights().iter().map(|h| h.to_bits()).collect()
    };
    let a = noisy_walk();
    let b = std::thread::spawn(noisy_walk).join().unwrap();
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a.disturbed(), b.disturbed());
    assert!(a.disturbed().contains(&DISTURBED_PRESSED));
}
