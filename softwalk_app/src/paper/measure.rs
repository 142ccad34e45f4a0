//! Measurements on recorded walks and terrains: stance drift and gap, print
//! depth and sharpness, slopes, rim asymmetry. Pure functions of their inputs.

use engine::geom::{GridRect, HeightGrid};
use glam::{Vec2, Vec3, Vec3Swizzles};
use softwalk_systems::character::CharacterMetrics;

/// A sole point counts as touching the ground within this height, metres.
pub const TOUCHING: f32 = 0.005;

/// Largest horizontal drift of a sole point (heel or toe) while it touches the
/// ground during one stance, and the largest gap between a planted sole's
/// lowest point and the ground under it, metres. The foot rolls (heel strike,
/// heel rise), so the part that touches changes; each touching part must stay put.
/// `ground` must be the surface the feet stood on (rigid ground, or the heights before carving).
pub fn stance_errors<'a>(
    metrics: impl IntoIterator<Item = &'a CharacterMetrics>,
    ground: &HeightGrid,
) -> (f32, f32) {
    let (mut drift, mut gap) = (0.0f32, 0.0f32);
    let height = |p: Vec3| ground.height_at(p.x, p.z).unwrap_or(p.y);
    let mut anchors: [[Option<Vec3>; 2]; 2] = [[None; 2]; 2];
    for m in metrics {
        for (k, foot_anchors) in anchors.iter_mut().enumerate() {
            if !m.contact[k] {
                *foot_anchors = [None; 2];
                continue;
            }
            let lowest = m.feet[k];
            gap = gap.max((lowest.y - height(lowest)).abs());
            for (anchor, p) in foot_anchors
                .iter_mut()
                .zip([m.soles[k].heel, m.soles[k].toe])
            {
                if (p.y - height(p)).abs() > TOUCHING {
                    continue;
                }
                let a = *anchor.get_or_insert(p);
                drift = drift.max((p.xz() - a.xz()).length());
            }
        }
    }
    (drift, gap)
}

/// Where the feet lifted off: the centres of the prints a walk left.
pub fn lift_offs<'a>(metrics: impl IntoIterator<Item = &'a CharacterMetrics>) -> Vec<Vec3> {
    let mut detector = LiftOffs::default();
    for m in metrics {
        detector.observe(m);
    }
    detector.prints
}

/// Streaming form of [`lift_offs`]: feed one step's metrics at a time.
#[derive(Debug, Clone, Default)]
pub struct LiftOffs {
    /// Lowest sole point of each planted foot when it was planted.
    landed: [Option<Vec3>; 2],
    /// The print centres found so far, in the order the feet lifted.
    pub prints: Vec<Vec3>,
}

impl LiftOffs {
    /// Records the prints of the feet that lifted off in this step (left
    /// their stance): midway between the lowest sole point when the foot was
    /// planted (its heel) and when it lifted (its toe), the print's middle.
    pub fn observe(&mut self, m: &CharacterMetrics) {
        for k in 0..2 {
            match (self.landed[k], m.planted[k]) {
                (None, true) => self.landed[k] = Some(m.feet[k]),
                (Some(heel), false) => {
                    self.prints.push(0.5 * (heel + m.feet[k]));
                    self.landed[k] = None;
                }
                _ => {}
            }
        }
    }
}

/// Half extents of the window searched for a print's floor (along X, along Z), metres.
const PRINT_WINDOW: Vec2 = Vec2::new(0.08, 0.05);

/// Depth of the print at `c`, measured against the surface each sample had
/// before: the largest drop of a sample near `c` (0 where nothing was
/// carved, on a slope as on flat ground). `before` and `after` are the same
/// grid at two moments.
pub fn print_depth(before: &HeightGrid, after: &HeightGrid, c: Vec2) -> Option<f32> {
    let rect = after.rect_covering(c - PRINT_WINDOW, c + PRINT_WINDOW);
    if rect.is_empty() || before.nx() != after.nx() || before.nz() != after.nz() {
        return None;
    }
    let drop = rect
        .iter()
        .map(|(i, j)| before.height(i, j) - after.height(i, j))
        .fold(0.0f32, f32::max);
    Some(drop)
}

/// Sharpness of a print walked along +X: the steepest wall slope across it
/// (along Z, within 0.2 m) divided by its depth, 1/m: how abruptly the floor meets the surface.
pub fn sharpness(before: &HeightGrid, after: &HeightGrid, c: Vec2) -> Option<f32> {
    let depth = print_depth(before, after, c)?;
    if depth <= 0.0 {
        return None;
    }
    let half_cell = 0.5 * after.cell_size();
    let rect = after.rect_covering(c - Vec2::new(half_cell, 0.2), c + Vec2::new(half_cell, 0.2));
    let i = after.to_grid(c.x, c.y).round().x as usize;
    let steepest = (rect.j0..rect.j1.saturating_sub(1))
        .map(|j| (after.height(i, j + 1) - after.height(i, j)).abs() / after.cell_size())
        .fold(0.0, f32::max);
    Some(steepest / depth)
}

/// Steepest 8-neighbour slope (m/m) between two samples inside `rect`.
pub fn steepest_slope(grid: &HeightGrid, rect: GridRect) -> f32 {
    let c = grid.cell_size();
    let mut worst = 0.0f32;
    for (i, j) in rect.iter() {
        for (di, dj) in [(1isize, 0isize), (0, 1), (1, 1), (-1, 1)] {
            let (ib, jb) = (i as isize + di, j as isize + dj);
            if ib < rect.i0 as isize || ib >= rect.i1 as isize || jb >= rect.j1 as isize {
                continue;
            }
            let d = c * ((di * di + dj * dj) as f32).sqrt();
            worst =
                worst.max((grid.height(i, j) - grid.height(ib as usize, jb as usize)).abs() / d);
        }
    }
    worst
}

/// Raised (rim) volume within 0.3 m of the print at `c`, split into the side
/// behind `c` along `axis` and the side ahead of it, from the rise over the
/// untouched terrain (m per cell).
pub fn rim_split(after: &HeightGrid, untouched: &HeightGrid, c: Vec2, axis: Vec2) -> (f32, f32) {
    let rect = after.rect_covering(c - Vec2::splat(0.3), c + Vec2::splat(0.3));
    let (mut behind, mut ahead) = (0.0, 0.0);
    for (i, j) in rect.iter() {
        let d = (after.height(i, j) - untouched.height(i, j)).max(0.0);
        if (after.sample_position(i, j).xz() - c).dot(axis) < 0.0 {
            behind += d;
        } else {
            ahead += d;
        }
    }
    (behind, ahead)
}

/// Cells whose height differs between `a` and `b` (same grid layout): how many,
/// and how many lie farther than `radius` from every point of `near`.
pub fn changed_cells(a: &HeightGrid, b: &HeightGrid, near: &[Vec2], radius: f32) -> (usize, usize) {
    let (mut changed, mut far) = (0, 0);
    for j in 0..a.nz() {
        for i in 0..a.nx() {
            if a.height(i, j) == b.height(i, j) {
                continue;
            }
            changed += 1;
            let p = a.sample_position(i, j).xz();
            if near.iter().all(|q| q.distance_squared(p) > radius * radius) {
                far += 1;
            }
        }
    }
    (changed, far)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_and_slope_of_a_square_pit() {
        let before = HeightGrid::from_fn(Vec2::ZERO, 0.02, 51, 51, |_, _| 1.0).unwrap();
        let after = HeightGrid::from_fn(Vec2::ZERO, 0.02, 51, 51, |x, z| {
            if (x - 0.5).abs() < 0.05 && (z - 0.5).abs() < 0.05 {
                0.98
            } else {
                1.0
            }
        })
        .unwrap();
        let c = Vec2::splat(0.5);
        assert!((print_depth(&before, &after, c).unwrap() - 0.02).abs() < 1e-6);
        assert!(
            (steepest_slope(&after, after.rect_covering(Vec2::ZERO, Vec2::ONE)) - 1.0).abs() < 1e-4
        );
        let (changed, far) = changed_cells(&before, &after, &[c], 0.1);
        assert!(changed > 0);
        assert_eq!(far, 0);
        assert_eq!(
            changed_cells(&before, &after, &[Vec2::ZERO], 0.1).1,
            changed
        );
    }
}
