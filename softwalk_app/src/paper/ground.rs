//! The loose-ground claims (paper §3.2, §4): print depth and sharpness per
//! material, volume conservation and compaction, the angle of repose, print
//! asymmetry on a slope, locality, and the ground's effect on the gait.

use engine::geom::HeightGrid;
use glam::{Vec2, Vec3Swizzles};
use softwalk_systems::character::CharacterDesc;
use softwalk_systems::terrain::TerrainMaterial;

use super::measure::{changed_cells, lift_offs, print_depth, rim_split, sharpness, steepest_slope};
use super::report::{Check, Claim};
use super::stats::{mean, median};
use super::trace::{Trace, trace};
use super::variants::{RIGID, builtin, checked, walker, with_material, with_slope};
use super::{PaperError, PaperOptions};
use crate::scene::{PathSpec, Scene};

/// The materials in the paper's order of print depth (shallowest first).
const DEPTH_ORDER: [&str; 4] = ["soil", "sand", "mud", "snow"];
/// The start transient skipped before measuring the gait, seconds.
const SETTLE_S: f32 = 1.0;
/// Volumes are compared relative to a 1 m thick slab over the terrain, as the
/// tests compare them relative to a 1 m thick patch.
const SLAB_TOLERANCE: f64 = 1e-6;
/// Half the window searched around a print for steep slopes, metres.
const STANDING_REACH: f32 = 0.4;
/// Distance from a footfall beyond which no cell may change, metres.
const LOCALITY_RADIUS: f32 = 0.5;

/// The print centres of character `c` inside the terrain (away from its edge).
fn prints(t: &Trace, c: usize) -> Vec<Vec2> {
    let m = t.walkers[c].iter().map(|m| &m.character);
    lift_offs(m).into_iter().map(|p| p.xz()).collect()
}

fn slab_volume(grid: &HeightGrid) -> f64 {
    let e = grid.extent();
    f64::from(e.x) * f64::from(e.y)
}

fn preset(name: &str) -> TerrainMaterial {
    TerrainMaterial::presets()
        .into_iter()
        .find(|m| m.name == name)
        .expect("the depth order names presets")
}

/// One material's walk on flat ground and what it left.
struct MaterialWalk {
    name: &'static str,
    trace: Trace,
    prints: Vec<Vec2>,
}

impl MaterialWalk {
    fn depth(&self) -> f32 {
        mean(
            self.prints
                .iter()
                .filter_map(|&c| print_depth(&self.trace.initial, &self.trace.last, c)),
        )
    }

    /// The median print's sharpness: a print left nearly flat (a foot that
    /// barely pressed) has a tiny depth, and its ratio says nothing of the walls.
    fn sharpness(&self) -> f32 {
        median(
            self.prints
                .iter()
                .filter_map(|&c| sharpness(&self.trace.initial, &self.trace.last, c)),
        )
    }

    /// Steepest slope around the prints after settling, m/m. Prints next to
    /// where the feet still stand at the end are left out: a planted foot holds
    /// its print's walls until it lifts (they settle on release).
    fn steepest(&self) -> f32 {
        let g = &self.trace.last;
        let standing: Vec<Vec2> = self.trace.walkers[0]
            .last()
            .map(|m| m.character.feet.iter().map(|f| f.xz()).collect())
            .unwrap_or_default();
        self.prints
            .iter()
            .filter(|&&c| {
                standing
                    .iter()
                    .all(|f| f.distance(c) > 2.0 * STANDING_REACH)
            })
            .map(|&c| {
                steepest_slope(
                    g,
                    g.rect_covering(
                        c - Vec2::splat(STANDING_REACH),
                        c + Vec2::splat(STANDING_REACH),
                    ),
                )
            })
            .fold(0.0, f32::max)
    }

    /// Grid volume lost and volume compacted (from the carving reports), m³.
    fn loss_and_compacted(&self) -> (f64, f64) {
        let t = &self.trace;
        (
            t.initial.volume() - t.last.volume(),
            t.tracked_volume.0 - t.tracked_volume.1,
        )
    }
}

fn walk_material(name: &'static str, options: &PaperOptions) -> Result<MaterialWalk, PaperError> {
    let scene = builtin(&format!("{name}-flat"))?;
    options.say(&format!("walking {}", scene.name));
    let trace = trace(&scene, scene.steps() as usize, |_| {})?;
    let prints = prints(&trace, 0);
    Ok(MaterialWalk {
        name,
        trace,
        prints,
    })
}

/// Print depth, sharpness, volume and repose from the four flat material walks,
/// plus the compression-free sand walk, asymmetry, locality and the two-way effect.
pub fn ground_claims(options: &PaperOptions) -> Result<Vec<Claim>, PaperError> {
    let walks = DEPTH_ORDER
        .iter()
        .map(|name| walk_material(name, options))
        .collect::<Result<Vec<_>, _>>()?;
    let mut claims = vec![
        depth_claim(&walks),
        volume_claim(&walks, options)?,
        repose_claim(&walks),
    ];
    claims.push(asymmetry_claim(options)?);
    claims.push(locality_claim(&walks[1])?);
    claims.push(two_way_claim(&walks[3], options)?);
    Ok(claims)
}

fn depth_claim(walks: &[MaterialWalk]) -> Claim {
    let depths: Vec<f32> = walks.iter().map(MaterialWalk::depth).collect();
    let sharp: Vec<f32> = walks.iter().map(MaterialWalk::sharpness).collect();
    let listing = |values: &[f32], unit: &str, scale: f32| {
        let parts: Vec<String> = walks
            .iter()
            .zip(values)
            .map(|(w, v)| format!("{} {:.1} {unit}", w.name, v * scale))
            .collect();
        parts.join(", ")
    };
    Claim {
        title: "Print depth per material".into(),
        statement: "Table 1 and Fig. 3: soil prints are shallowest, then sand, mud, snow; mud prints \
                    are sharp-edged, snow prints are smoothed."
            .into(),
        method: "Built-in scenes `soil-flat`, `sand-flat`, `mud-flat`, `snow-flat` (10 × 10 m, 512², adult, 6 s); \
                 depth = untouched height minus the lowest height near each lift-off; sharpness = steepest \
                 wall slope across the print over its depth."
            .into(),
        checks: vec![
            Check::new(
                "mean print depth",
                listing(&depths, "mm", 1000.0),
                "soil < sand < mud < snow",
                depths.windows(2).all(|w| w[0] < w[1]),
            ),
            Check::new(
                "sharpness (wall slope / depth)",
                listing(&sharp, "/m", 1.0),
                "mud > snow",
                sharp[2] > sharp[3],
            ),
        ],
    }
}

/// Sand whose carved volume all goes to the rim (c_t = 0).
pub fn loose_sand_scene() -> Result<Scene, PaperError> {
    let mut scene = builtin("sand-flat")?;
    scene.name = "paper-sand-uncompressed".into();
    scene.description = "Sand with compression 0: every carved cell goes to the rim".into();
    let mut sand = preset("sand");
    sand.compression = 0.0;
    scene.materials.push(sand);
    checked(scene)
}

fn volume_claim(walks: &[MaterialWalk], options: &PaperOptions) -> Result<Claim, PaperError> {
    let scene = loose_sand_scene()?;
    options.say(&format!("walking {}", scene.name));
    let loose = trace(&scene, scene.steps() as usize, |_| {})?;
    let slab = slab_volume(&loose.initial);
    let change = loose.last.volume() - loose.initial.volume();
    let carved_scale: f64 = loose
        .initial
        .heights()
        .iter()
        .zip(loose.last.heights())
        .map(|(a, b)| f64::from((a - b).max(0.0)))
        .sum::<f64>()
        * f64::from(loose.initial.cell_size()).powi(2);
    let mut checks = vec![Check::new(
        "c_t = 0: volume change",
        format!("{change:.2e} m³ (cells lowered: {carved_scale:.2e} m³)"),
        "|change| < 1e-6 × a 1 m slab, something carved",
        change.abs() < SLAB_TOLERANCE * slab && carved_scale > 1e-4,
    )];
    for w in walks {
        let (loss, compacted) = w.loss_and_compacted();
        checks.push(Check::new(
            format!("{}: volume lost vs compacted", w.name),
            format!("{loss:.4e} vs {compacted:.4e} m³"),
            "equal within 1e-6 × a 1 m slab, > 0",
            (loss - compacted).abs() < SLAB_TOLERANCE * slab && compacted > 0.0,
        ));
    }
    Ok(Claim {
        title: "Volume: conserved without compression, compacted part lost".into(),
        statement:
            "c_t is the compacted fraction of the displaced volume; the rest is raised on the rim."
                .into(),
        method:
            "Scene `paper-sand-uncompressed` (sand with c_t = 0) and the four flat material walks; \
                 grid volume before and after vs the compacted volume the carving reported."
                .into(),
        checks,
    })
}

fn repose_claim(walks: &[MaterialWalk]) -> Claim {
    let checks = walks
        .iter()
        .map(|w| {
            let m = preset(w.name);
            let worst = w.steepest();
            Check::new(
                format!("{}: steepest slope near the prints", w.name),
                format!("{:.1}°", worst.atan().to_degrees()),
                format!("≤ repose {}° (+0.01 m/m)", m.repose_deg),
                worst <= m.repose_slope() + 0.01,
            )
        })
        .collect();
    Claim {
        title: "No slope steeper than the angle of repose after settling".into(),
        statement:
            "Beyond the paper (Sumner 1999): material steeper than its angle of repose slides down."
                .into(),
        method:
            "The four flat material walks; steepest 8-neighbour slope within 0.4 m of each print the feet have left (a planted foot holds its walls until it lifts)."
                .into(),
        checks,
    }
}

/// A sand plane rising `angle_deg` towards +X, walked across (along +Z).
pub fn across_slope_scene(angle_deg: f32) -> Result<Scene, PaperError> {
    let mut scene = with_slope(builtin("sand-flat")?, angle_deg);
    scene.name = format!("paper-sand-across-{angle_deg:.0}");
    scene.description = format!("Walk across a {angle_deg}° sand slope");
    let path = PathSpec::Straight {
        start: [5.0, 1.5],
        heading_deg: 90.0,
        length: 7.0,
    };
    scene.characters = vec![walker("walker", CharacterDesc::adult(), true, path)];
    checked(scene)
}

fn asymmetry_claim(options: &PaperOptions) -> Result<Claim, PaperError> {
    let mut ratios = Vec::new();
    for angle in [0.0, 25.0] {
        let scene = across_slope_scene(angle)?;
        options.say(&format!("walking {}", scene.name));
        let t = trace(&scene, scene.steps() as usize, |_| {})?;
        let (down, up) = prints(&t, 0).iter().fold((0.0, 0.0), |(d, u), &c| {
            let (down, up) = rim_split(&t.last, &t.initial, c, Vec2::X);
            (d + down, u + up)
        });
        ratios.push(down / f32::max(up, 1e-9));
    }
    Ok(Claim {
        title: "Prints on a slope slump downhill".into(),
        statement: "On sloped sand the displaced material ends up downhill of the print.".into(),
        method: "Scenes `paper-sand-across-0` and `paper-sand-across-25` (adult walking across the slope); \
                 raised volume within 0.3 m of each print, summed over the prints (left and right \
                 feet mirror each other), downhill side over uphill side."
            .into(),
        checks: vec![
            Check::new("flat: downhill/uphill rim", format!("{:.2}", ratios[0]), "in [0.8, 1.25)", (0.8..1.25).contains(&ratios[0])),
            Check::new("25°: downhill/uphill rim", format!("{:.2}", ratios[1]), "> 3", ratios[1] > 3.0),
        ],
    })
}

fn locality_claim(sand: &MaterialWalk) -> Result<Claim, PaperError> {
    let t = &sand.trace;
    let footfalls: Vec<Vec2> = t.walkers[0]
        .iter()
        .flat_map(|m| {
            (0..2)
                .filter(|&k| m.character.contact[k])
                .map(move |k| m.character.feet[k].xz())
        })
        .collect();
    let (changed, far) = changed_cells(&t.initial, &t.last, &footfalls, LOCALITY_RADIUS);
    let cells = t.initial.nx() * t.initial.nz();
    let share = t.max_dirty_cells as f64 / cells as f64;
    Ok(Claim {
        title: "Deformation is local".into(),
        statement:
            "Only a window around the foot is touched: work scales with what the feet touch.".into(),
        method:
            "The `sand-flat` walk: cells changed over the run, those farther than 0.5 m from every \
                 planted foot position, and the largest single-step dirty window."
                .into(),
        checks: vec![
            Check::new(
                "cells changed / beyond 0.5 m of a footfall",
                format!("{changed} / {far}"),
                "some changed, none beyond",
                changed > 0 && far == 0,
            ),
            Check::new(
                "largest dirty window of one step",
                format!(
                    "{} cells ({:.3} % of {cells})",
                    t.max_dirty_cells,
                    100.0 * share
                ),
                "< 1 % of the terrain",
                share < 0.01,
            ),
        ],
    })
}

fn two_way_claim(snow: &MaterialWalk, options: &PaperOptions) -> Result<Claim, PaperError> {
    let mut scene = with_material(builtin("snow-flat")?, RIGID);
    scene.name = "paper-rigid-flat".into();
    scene.description = "The snow walk on ground that does not deform".into();
    let scene = checked(with_slope(scene, 0.0))?;
    options.say(&format!("walking {}", scene.name));
    let rigid = trace(&scene, scene.steps() as usize, |_| {})?;
    let gait = |t: &Trace| {
        let m = t.walking_from(0, SETTLE_S);
        let pelvis = mean(m.iter().map(|s| s.character.pelvis_y));
        let knee = mean(
            m.iter()
                .map(|s| s.character.knee_flexion[0].max(s.character.knee_flexion[1])),
        );
        (pelvis, knee)
    };
    let (snow_pelvis, snow_knee) = gait(&snow.trace);
    let (rigid_pelvis, rigid_knee) = gait(&rigid);
    Ok(Claim {
        title: "Two-way coupling: deep snow changes the gait".into(),
        statement: "The ray sees the deformed ground: the pelvis drops and the knees bend more in deep prints.".into(),
        method: format!(
            "`snow-flat` vs `paper-rigid-flat` (same walk, undeformable ground); means after {SETTLE_S} s while walking; \
             flat ground at height 0; knee = the more bent knee each step."
        ),
        checks: vec![
            Check::new(
                "pelvis height, snow vs rigid",
                format!("{snow_pelvis:.3} m vs {rigid_pelvis:.3} m"),
                "snow lower by > 0.02 m",
                snow_pelvis < rigid_pelvis - 0.02,
            ),
            Check::new(
                "knee flexion, snow vs rigid",
                format!("{:.1}° vs {:.1}°", snow_knee.to_degrees(), rigid_knee.to_degrees()),
                "snow larger",
                snow_knee > rigid_knee,
            ),
        ],
    })
}
