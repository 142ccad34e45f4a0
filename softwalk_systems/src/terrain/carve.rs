//! Carving: a stance foot in contact presses its sole into the ground and
//! pushes the displaced material that is not compacted onto the rim.

use engine::geom::GridRect;
use glam::Vec2;

use super::error::TerrainError;
use super::footprint::Footprint;
use super::heightfield::{DISTURBED_PRESSED, DISTURBED_RIM, Heightfield, TerrainParts};
use super::units::REFERENCE_CELL_M;
use crate::foot::FootSole;

/// Width of the rim ring as a fraction of the sole half-width.
pub const RIM_WIDTH_FRACTION: f32 = 0.6;
/// The rim ring is at least this wide, metres: 1.5 cells of the reference
/// grid ([`REFERENCE_CELL_M`]), about 2.9 cm.
pub const RIM_MIN_WIDTH_M: f32 = 1.5 * REFERENCE_CELL_M;
/// A sample counts as pressed (held) when the sole is at most this high above it, metres.
pub const CONTACT_TOLERANCE: f32 = 0.005;
/// How much wider than the sole a print is on every side, metres (one
/// reference cell, [`REFERENCE_CELL_M`], about 2 cm). The print's
/// anti-aliased edge is centred this far outside the sole's outline, so on
/// any grid up to twice the reference cell every sample under the sole is
/// pressed the whole way: a sole resting on the print's floor reads that
/// floor, not part of the print's wall.
pub const PRINT_MARGIN_M: f32 = REFERENCE_CELL_M;

/// Width of the rim ring around a footprint of half-width `radius`, metres:
/// [`RIM_WIDTH_FRACTION`] of it, at least [`RIM_MIN_WIDTH_M`].
pub fn rim_width(radius: f32) -> f32 {
    (RIM_WIDTH_FRACTION * radius).max(RIM_MIN_WIDTH_M)
}

/// Per-foot carving state: the surface each sample had when this contact first
/// touched it, so a foot pressed again and again stops at the print depth
/// instead of sinking forever.
#[derive(Debug, Clone, Default)]
pub struct FootPrint {
    active: bool,
    window: GridRect,
    reference: Vec<f32>,
    touched: GridRect,
    /// Grid indices of the samples with a reference height, in the order they were first pressed.
    pressed: Vec<usize>,
    rim: Vec<(usize, f32)>,
}

impl FootPrint {
    /// A foot not in contact.
    pub fn new() -> Self {
        Self::default()
    }

    /// True while the foot is in a contact (between first touch and release).
    pub fn is_active(&self) -> bool {
        self.active
    }

    /// Every sample rectangle this contact has touched so far (print and rim).
    pub fn touched(&self) -> GridRect {
        self.touched
    }

    /// The surface height sample `(i, j)` had when this contact first pressed it.
    pub fn reference_height(&self, i: usize, j: usize) -> Option<f32> {
        if !self.active || !self.window.contains(i, j) {
            return None;
        }
        let h = self.reference[self.local(i, j)];
        (!h.is_nan()).then_some(h)
    }

    #[inline]
    fn local(&self, i: usize, j: usize) -> usize {
        (j - self.window.j0) * self.window.width() + (i - self.window.i0)
    }

    /// Makes the reference window hold `rect` (grows it, keeping known references).
    fn cover(&mut self, rect: GridRect, nx: usize, nz: usize) {
        if self.active && self.window.intersect(&rect) == rect {
            return;
        }
        if !self.active {
            // A new contact: reuse the buffers of the last one.
            self.window = rect.expand(rect.width().max(rect.height()) / 2, nx, nz);
            self.reference.clear();
            self.reference.resize(self.window.area(), f32::NAN);
            self.pressed.clear();
            self.touched = GridRect::EMPTY;
            self.active = true;
            return;
        }
        let grown = self.window.union(&rect);
        let mut reference = vec![f32::NAN; grown.area()];
        for (i, j) in self.window.iter() {
            let k = (j - grown.j0) * grown.width() + (i - grown.i0);
            reference[k] = self.reference[self.local(i, j)];
        }
        self.window = grown;
        self.reference = reference;
    }

    /// Ends the contact; returns what it touched (smooth and settle it once more).
    fn release(&mut self) -> GridRect {
        if !self.active {
            return GridRect::EMPTY;
        }
        self.active = false;
        std::mem::replace(&mut self.touched, GridRect::EMPTY)
    }
}

/// One step of carving by one foot; returns the rectangle to smooth and settle.
///
/// With `contact`, each sample under the [`Footprint`] that the sole reaches
/// goes down to the sole (the foot sets the pace and the print takes the
/// sole's tilt; samples under a raised toe are left alone), a sample on the
/// print's edge at most by the material's
/// [`super::TerrainMaterial::sink_speed`] × `dt` a step; never below the
/// print depth under the surface this contact first touched, and never below
/// its firm floor ([`Heightfield::firm_floor`]: the
/// loose layer is all there is to press). The print is [`PRINT_MARGIN_M`]
/// wider than the sole on every side, and its edge is anti-aliased: a
/// sample within half a cell of it goes the share of that way its cell is
/// covered (`0.5 + (radius + margin - distance) / cell`, at most 1), so a
/// print has the same area and volume on any grid. Of the removed volume, c_t is
/// compacted and 1 - c_t is spread over the rim ring of [`rim_width`] just
/// outside the pressed samples, weighted linearly from 1 at its inner edge
/// to 0 at its outer edge. Samples off the grid, and samples a sole holds
/// this step (any sole's, see `HeldMask`), get
/// none: sand pushed out of one print cannot go under another planted foot.
/// With no rim sample left the volume counts as compacted.
///
/// This is [`press`] followed by [`deposit_rim`]. With several feet, press
/// them all first and then deposit every rim, so that no rim lands on a
/// sole pressed later in the step.
///
/// Without `contact`, a foot that was in contact is released: nothing is
/// carved and the whole touched rectangle is returned (and added to
/// [`super::StepChanges::released`]) so that smoothing and settling run once
/// more without the foot holding the walls.
///
/// A footprint partly off the grid carves what exists; fully off, nothing.
pub fn carve(
    hf: &mut Heightfield,
    print: &mut FootPrint,
    sole: &FootSole,
    contact: bool,
    dt: f32,
) -> Result<GridRect, TerrainError> {
    let pressed = press(hf, print, sole, contact, dt)?;
    Ok(deposit_rim(hf, print, pressed))
}

/// What one foot pressed this step: the rectangle it covered and the volume
/// (in heights summed over samples) its rim is owed. The default is nothing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pressed {
    rect: GridRect,
    removed: f64,
    compacted: f64,
    released: bool,
}

/// The first half of [`carve`]: presses the sole's samples (or releases a
/// foot no longer in contact) and marks them held, leaving the displaced
/// volume for [`deposit_rim`].
pub fn press(
    hf: &mut Heightfield,
    print: &mut FootPrint,
    sole: &FootSole,
    contact: bool,
    dt: f32,
) -> Result<Pressed, TerrainError> {
    if !(dt.is_finite() && dt >= 0.0) {
        return Err(TerrainError::InvalidParameter {
            name: "dt",
            reason: format!("{dt} must be finite and >= 0"),
        });
    }
    let foot = Footprint::from_sole(sole)?;
    if !contact {
        return Ok(release(hf, print));
    }
    let grid = hf.grid();
    let (origin, cell, nx, nz) = (grid.origin(), grid.cell_size(), grid.nx(), grid.nz());
    // The print's edge, [`PRINT_MARGIN_M`] outside the sole's outline, is
    // anti-aliased over one cell: a sample within half a cell of it is
    // pressed by the part of its cell the print covers, so a print has the
    // same area and volume on any grid. The rim starts where that band ends.
    let edge = foot.radius + PRINT_MARGIN_M;
    let rim_start = edge + 0.5 * cell;
    let rim_width = rim_width(foot.radius);
    let (lo, hi) = foot.bounds(PRINT_MARGIN_M + rim_width + 0.5 * cell);
    let rect = grid.rect_covering(lo, hi);
    if rect.is_empty() {
        return Ok(Pressed::default());
    }
    print.cover(rect, nx, nz);

    let mut parts = hf.parts_mut();
    let mut removed = 0.0f64;
    let mut compacted = 0.0f64;
    print.rim.clear();
    for j in rect.j0..rect.j1 {
        for i in rect.i0..rect.i1 {
            let p = origin + Vec2::new(i as f32, j as f32) * cell;
            let d = foot.axis_distance(p);
            let k = j * nx + i;
            let cover = (0.5 + (edge - d) / cell).min(1.0);
            if cover <= 0.0 {
                if d <= rim_start + rim_width {
                    print.rim.push((k, 1.0 - (d - rim_start) / rim_width));
                }
                continue;
            }
            let sole_y = foot.sole_height(p);
            if sole_y > parts.heights[k] + CONTACT_TOLERANCE {
                continue;
            }
            let local = print.local(i, j);
            if print.reference[local].is_nan() {
                print.reference[local] = parts.heights[k];
                print.pressed.push(k);
            }
            let (dh, compressed) =
                press_sample(&mut parts, k, print.reference[local], sole_y, cover, dt);
            removed += dh;
            compacted += compressed;
        }
    }
    // Everything this contact has pressed stays held until the foot lifts, not
    // only what is under the sole now: a rolling foot lifts its heel
    // mid-stance, and smoothing must not pour the rim back under it every step.
    let held_bounds = print.touched.union(&rect);
    parts.changes.held.push_group(held_bounds, &print.pressed);
    parts.held_mask.set(&print.pressed);
    Ok(Pressed {
        rect,
        removed,
        compacted,
        released: false,
    })
}

/// Releases a foot no longer in contact: nothing is pressed, and the whole
/// rectangle its contact touched is noted as released and carved, so that
/// smoothing and settling run once more without the foot holding the walls.
fn release(hf: &mut Heightfield, print: &mut FootPrint) -> Pressed {
    let released = print.release();
    let changes = hf.parts_mut().changes;
    changes.released.add(released);
    if !released.is_empty() {
        changes.carved.push(released);
    }
    Pressed {
        rect: released,
        released: true,
        ..Pressed::default()
    }
}

/// Presses sample `k`, under a sole at `sole_y` covering `cover` of its
/// cell, for `dt` seconds: a fully covered sample goes down with the sole
/// (the foot sets the pace) and stops at the print depth below `reference`
/// (its height when this contact first touched it) or at the firm floor; a
/// partly covered one sinks at the material's speed and stops that share
/// of the way. Marks the sample pressed and returns how far it went down
/// and how much of that its material compacted.
fn press_sample(
    parts: &mut TerrainParts<'_>,
    k: usize,
    reference: f32,
    sole_y: f32,
    cover: f32,
    dt: f32,
) -> (f64, f64) {
    let h = parts.heights[k];
    let material = parts.material(k);
    let firm = parts.floor(k);
    let full = (reference - material.print_depth()).max(firm);
    let floor = (reference - cover * (reference - full))
        .max(sole_y)
        .max(firm);
    let new_h = if cover >= 1.0 {
        floor
    } else {
        (h - material.sink_speed() * dt).max(floor)
    };
    parts.disturbed[k] = DISTURBED_PRESSED;
    if new_h < h {
        parts.heights[k] = new_h;
        let dh = (h - new_h) as f64;
        (dh, material.compression as f64 * dh)
    } else {
        (0.0, 0.0)
    }
}

/// The second half of [`carve`]: spreads what `pressed` displaced and did
/// not compact over the print's rim ring, skipping samples any sole holds;
/// returns the rectangle to smooth and settle.
pub fn deposit_rim(hf: &mut Heightfield, print: &mut FootPrint, pressed: Pressed) -> GridRect {
    let Pressed {
        rect,
        removed,
        mut compacted,
        released,
    } = pressed;
    if released {
        return rect;
    }
    if removed == 0.0 {
        return GridRect::EMPTY;
    }
    let cell = hf.grid().cell_size();
    let parts = hf.parts_mut();
    let free = |&&(k, _): &&(usize, f32)| !parts.held_mask.contains(k);
    let weight_sum: f64 = print.rim.iter().filter(free).map(|&(_, w)| w as f64).sum();
    let mut to_rim = removed - compacted;
    if weight_sum > 0.0 {
        for &(k, w) in print.rim.iter().filter(free) {
            parts.heights[k] += (to_rim * w as f64 / weight_sum) as f32;
            parts.disturbed[k] = parts.disturbed[k].max(DISTURBED_RIM);
        }
    } else {
        compacted += to_rim;
        to_rim = 0.0;
    }
    let area = (cell as f64) * (cell as f64);
    parts.changes.carved_volume += removed * area;
    parts.changes.compacted_volume += compacted * area;
    parts.changes.rim_volume += to_rim * area;
    print.touched = print.touched.union(&rect);
    parts.changes.carved.push(rect);
    hf.mark_dirty(rect);
    rect
}
