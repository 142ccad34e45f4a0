//! One estimate of the memory a run needs, made from the scene and the run
//! options before anything is allocated, and the budget it is checked against.
//!
//! The estimate is a sum of named items (terrain grid, grass blades, frames,
//! contact sheet, ...), each a count from the scene times a cost per element
//! measured on release builds (peak resident set size of short runs; see
//! `NOTES-issue22b.md`) and rounded up. It is meant to refuse runs that cannot
//! fit, not to predict the peak to the megabyte.

use std::fmt;

use thiserror::Error;

use crate::runner::RunOptions;
use crate::scene::{MAX_STEPS, Scene, png_size};

/// The default memory budget, bytes (8 GiB); `--max-memory` changes it.
pub const DEFAULT_MAX_MEMORY: u64 = 8 << 30;

/// The process before the scene: code, thread stacks, the allocator, bytes.
const PROCESS_BYTES: u64 = 32 << 20;
/// Terrain heights, initial heights, materials and carving state per grid sample, bytes (measured ~7).
const TERRAIN_BYTES_PER_SAMPLE: u64 = 16;
/// The renderer's terrain mesh, normals and lighting per grid sample, bytes (measured ~60).
const TERRAIN_RENDER_BYTES_PER_SAMPLE: u64 = 72;
/// One grass blade: its description, state columns, bends and the scattering copies, bytes (measured ~190).
const BLADE_BYTES: u64 = 224;
/// One grass blade's drawing data, bytes (measured ~64).
const BLADE_RENDER_BYTES: u64 = 80;
/// One character: body, gait, rays, path, bytes.
const CHARACTER_BYTES: u64 = 1 << 20;
/// What the plots keep per character whatever the run's length, bytes: 7
/// curves of at most 2048 buckets (1024 after each merge) of about 64 bytes.
const PLOT_BYTES_PER_CHARACTER: u64 = 7 * 2048 * 64;
/// A prop mesh per byte of its OBJ file: positions, normals, triangles, its
/// BVH and a drawing copy, bytes (an OBJ line of ~25 bytes becomes ~100).
const PROP_BYTES_PER_OBJ_BYTE: u64 = 8;
/// A built-in prop mesh (a few hundred triangles), bytes.
const BUILTIN_PROP_BYTES: u64 = 256 << 10;
/// Colour, depth and work buffers of one frame per pixel, bytes (measured ~9).
const FRAME_BYTES_PER_PIXEL: u64 = 16;
/// A decoded heightmap per pixel: the gray values and the heights, bytes.
const HEIGHTMAP_BYTES_PER_PIXEL: u64 = 12;
/// Width of a contact-sheet thumbnail, pixels (`output::ContactSheet`).
const THUMB_WIDTH: u64 = 320;
/// Gap between contact-sheet thumbnails, pixels (`engine::output::contact_sheet`).
const SHEET_GAP: u64 = 4;
/// Thumbnails a contact sheet keeps, about (`output::ContactSheet`).
const SHEET_THUMBS: u64 = 12;

/// One named part of the estimate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MemoryItem {
    /// What the memory is for (`grass blades (3 patches)`).
    pub name: String,
    /// Bytes.
    pub bytes: u64,
}

/// The memory a run is estimated to need, item by item.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// The items, in a fixed order; items of zero bytes are left out.
    pub items: Vec<MemoryItem>,
}

/// A run asks for more than it may.
#[derive(Debug, Error)]
pub enum BudgetError {
    /// The memory estimate is above the budget.
    #[error(
        "the run needs about {} of memory, more than the budget of {} \
         (largest item: {largest} with {}); shrink the scene or raise --max-memory",
        Bytes(*estimate), Bytes(*budget), Bytes(*largest_bytes)
    )]
    Memory {
        /// Estimated bytes.
        estimate: u64,
        /// The budget, bytes.
        budget: u64,
        /// The largest item's name.
        largest: String,
        /// The largest item's bytes.
        largest_bytes: u64,
    },
    /// The step count is above [`MAX_STEPS`], whichever setting asked for it.
    #[error("{setting} asks for {steps} steps, more than the maximum {max}")]
    Steps {
        /// What set the count: `--seconds 1000000`, `sim.duration`, ...
        setting: String,
        /// Steps asked for.
        steps: u64,
        /// The maximum, [`MAX_STEPS`].
        max: u64,
    },
}

/// A byte count printed in binary units (`1.5 GiB`).
#[derive(Debug, Clone, Copy)]
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
        let mut value = self.0 as f64;
        let mut unit = 0;
        while value >= 1024.0 && unit + 1 < UNITS.len() {
            value /= 1024.0;
            unit += 1;
        }
        if unit == 0 {
            write!(f, "{} B", self.0)
        } else {
            write!(f, "{value:.1} {}", UNITS[unit])
        }
    }
}

/// Refuses more than [`MAX_STEPS`] steps; `source` names what set the count.
pub fn check_steps(steps: u64, source: &str) -> Result<(), BudgetError> {
    if steps > MAX_STEPS {
        return Err(BudgetError::Steps {
            setting: source.to_owned(),
            steps,
            max: MAX_STEPS,
        });
    }
    Ok(())
}

/// Parses a byte size: a number with an optional unit `K`, `M`, `G`, `T`
/// (binary, optionally followed by `B` or `iB`), e.g. `8G`, `512MiB`, `1000000`.
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let value: f64 = number
        .parse()
        .map_err(|_| format!("\"{text}\" is not a size such as 8G or 512M"))?;
    let unit = unit.trim().to_ascii_uppercase();
    let unit = unit.trim_end_matches("IB").trim_end_matches('B');
    let scale: u64 = match unit {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        "T" => 1 << 40,
        _ => return Err(format!("\"{text}\": unknown unit; use K, M, G or T")),
    };
    let bytes = value * scale as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes <= u64::MAX as f64) {
        return Err(format!("\"{text}\" is not a positive size"));
    }
    Ok(bytes as u64)
}

impl MemoryEstimate {
    /// The estimate for running `scene` with `options` (steps, rendering, frame size).
    pub fn of(scene: &Scene, options: &RunOptions) -> MemoryEstimate {
        let mut items = vec![MemoryItem {
            name: "process".into(),
            bytes: PROCESS_BYTES,
        }];
        let mut push = |name: String, bytes: u64| {
            if bytes > 0 {
                items.push(MemoryItem { name, bytes });
            }
        };
        let (nx, nz) = scene.terrain.grid_samples();
        let samples = (nx as u64).saturating_mul(nz as u64);
        push(
            format!("terrain grid ({nx} x {nz} samples)"),
            samples.saturating_mul(TERRAIN_BYTES_PER_SAMPLE),
        );
        if let Some((w, h)) = scene.heightmap_path().and_then(|p| png_size(&p)) {
            let px = u64::from(w) * u64::from(h);
            push(
                format!("heightmap ({px} pixels)"),
                px.saturating_mul(HEIGHTMAP_BYTES_PER_PIXEL),
            );
        }
        let blades: f64 = scene.grass.iter().map(|g| g.blade_count()).sum();
        let blades = blades.min(u64::MAX as f64 / 1024.0) as u64;
        let blade_bytes = BLADE_BYTES
            + if options.render {
                BLADE_RENDER_BYTES
            } else {
                0
            };
        push(
            format!(
                "grass blades ({blades} over {} patch(es))",
                scene.grass.len()
            ),
            blades.saturating_mul(blade_bytes),
        );
        let prop_bytes = (scene.props.iter())
            .map(|p| match p.mesh_path(&scene.base_dir) {
                Some(path) => std::fs::metadata(path)
                    .map_or(0, |m| m.len())
                    .saturating_mul(PROP_BYTES_PER_OBJ_BYTE),
                None => BUILTIN_PROP_BYTES,
            })
            .fold(0u64, u64::saturating_add);
        push(format!("props ({})", scene.props.len()), prop_bytes);
        let characters = scene.characters.len() as u64;
        push(
            format!("characters ({characters})"),
            characters.saturating_mul(CHARACTER_BYTES),
        );
        push(
            format!("plot series ({characters} character(s))"),
            characters.saturating_mul(PLOT_BYTES_PER_CHARACTER),
        );
        if options.render {
            push(
                "terrain mesh for rendering".into(),
                samples.saturating_mul(TERRAIN_RENDER_BYTES_PER_SAMPLE),
            );
            let pixels = u64::from(options.width) * u64::from(options.height);
            push(
                format!("frame buffers ({} x {})", options.width, options.height),
                pixels.saturating_mul(FRAME_BYTES_PER_PIXEL),
            );
            if scene.render.contact_sheet_columns > 0 {
                push(
                    "contact sheet".into(),
                    contact_sheet_bytes(options, scene.render.contact_sheet_columns),
                );
            }
        }
        MemoryEstimate { items }
    }

    /// Total bytes.
    pub fn total(&self) -> u64 {
        self.items
            .iter()
            .fold(0u64, |t, i| t.saturating_add(i.bytes))
    }

    /// The item with the most bytes.
    pub fn largest(&self) -> Option<&MemoryItem> {
        self.items.iter().max_by_key(|i| i.bytes)
    }

    /// Refuses a total above `budget` bytes, naming the estimate and the largest item.
    pub fn check(&self, budget: u64) -> Result<(), BudgetError> {
        let estimate = self.total();
        if estimate <= budget {
            return Ok(());
        }
        let (largest, largest_bytes) = self
            .largest()
            .map_or((String::new(), 0), |i| (i.name.clone(), i.bytes));
        Err(BudgetError::Memory {
            estimate,
            budget,
            largest,
            largest_bytes,
        })
    }
}

/// Bytes of a contact sheet: the kept thumbnails (frames shrunk to a longer
/// side of 320 pixels), the sheet of 320-pixel-wide cells, and one cell being resized.
fn contact_sheet_bytes(options: &RunOptions, columns: u32) -> u64 {
    let (w, h) = (u64::from(options.width), u64::from(options.height));
    let frames = options
        .steps
        .div_ceil(u64::from(options.render_every.max(1)));
    let every = frames.div_ceil(SHEET_THUMBS).max(1);
    let thumbs = frames.div_ceil(every);
    if thumbs == 0 || w == 0 || h == 0 {
        return 0;
    }
    let side = w.max(h);
    let (tw, th) = if side <= THUMB_WIDTH {
        (w, h)
    } else {
        (
            (w * THUMB_WIDTH / side).max(1),
            (h * THUMB_WIDTH / side).max(1),
        )
    };
    let cell_h = ((THUMB_WIDTH * th + tw / 2) / tw).max(1);
    let columns = u64::from(columns).min(thumbs).max(1);
    let rows = thumbs.div_ceil(columns);
    let sheet_px = (columns * (THUMB_WIDTH + SHEET_GAP) + SHEET_GAP)
        .saturating_mul(rows.saturating_mul(cell_h + SHEET_GAP) + SHEET_GAP);
    let kept_px = thumbs * tw * th;
    let cell_px = THUMB_WIDTH * cell_h;
    4 * (sheet_px.saturating_add(kept_px).saturating_add(cell_px))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_binary_units() {
        assert_eq!(parse_bytes("8G"), Ok(8 << 30));
        assert_eq!(parse_bytes("512MiB"), Ok(512 << 20));
        assert_eq!(parse_bytes("1.5 GB"), Ok(3 << 29));
        assert_eq!(parse_bytes("1000"), Ok(1000));
        assert!(parse_bytes("-1G").is_err());
        assert!(parse_bytes("8X").is_err());
        assert!(parse_bytes("0").is_err());
        assert_eq!(Bytes(3 << 29).to_string(), "1.5 GiB");
    }

    #[test]
    fn a_tall_contact_sheet_is_counted() {
        let scene = Scene::builtin("sand-flat").unwrap();
        let mut options = RunOptions::from_scene(&scene);
        options.width = 16;
        options.height = 8192;
        options.steps = 24;
        // 12 thumbnails of 1 x 320 shown as 320 x 102400 cells in one column: ~400 Mpx.
        let bytes = contact_sheet_bytes(&options, 1);
        assert!((1_500 << 20..2_000 << 20).contains(&bytes), "{bytes}");
    }

    #[test]
    fn the_largest_item_is_named() {
        let mut scene = Scene::builtin("sand-flat").unwrap();
        scene.terrain.resolution = 8192;
        let options = RunOptions::from_scene(&scene);
        let estimate = MemoryEstimate::of(&scene, &options);
        let largest = estimate.largest().unwrap();
        assert_eq!(largest.name, "terrain mesh for rendering");
        let e = estimate.check(1 << 30).unwrap_err().to_string();
        assert!(e.contains("terrain mesh for rendering"), "{e}");
        estimate.check(DEFAULT_MAX_MEMORY).unwrap();
    }
}
