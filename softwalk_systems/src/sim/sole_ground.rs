//! The ground under a sole: terrain heights under its heel, centre and toe,
//! recorded each step so sliding and burying can be measured from the metrics.

use engine::geom::HeightGrid;
use glam::Vec3;

use crate::foot::FootSole;

/// Terrain heights under one sole (heel, centre, toe), metres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SoleGround {
    /// Terrain height under the heel.
    pub heel: f32,
    /// Terrain height under the sole centre.
    pub centre: f32,
    /// Terrain height under the toe.
    pub toe: f32,
}

impl SoleGround {
    /// Samples `grid` under the heel, centre and toe of `sole`.
    pub fn under(grid: &HeightGrid, sole: &FootSole) -> SoleGround {
        SoleGround {
            heel: clamped_height(grid, sole.heel),
            centre: clamped_height(grid, sole.center()),
            toe: clamped_height(grid, sole.toe),
        }
    }

    /// The sole's own heights, as if it stood exactly on the ground (no terrain known).
    pub fn flush(sole: &FootSole) -> SoleGround {
        SoleGround {
            heel: sole.heel.y,
            centre: sole.center().y,
            toe: sole.toe.y,
        }
    }

    /// How far the lower of heel and toe sits below the ground under it,
    /// metres (negative when both are above).
    pub fn buried(&self, sole: &FootSole) -> f32 {
        (self.heel - sole.heel.y).max(self.toe - sole.toe.y)
    }
}

/// Terrain height at `p`'s `x, z`, clamped into the grid (the border height off it).
pub fn clamped_height(grid: &HeightGrid, p: Vec3) -> f32 {
    let max = grid.origin() + grid.extent();
    let x = p.x.clamp(grid.origin().x, max.x);
    let z = p.z.clamp(grid.origin().y, max.y);
    grid.height_at(x, z).unwrap_or(p.y)
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;

    #[test]
    fn heights_under_heel_centre_and_toe_and_how_deep_the_sole_sits() {
        // A ramp rising 0.1 m per metre along X.
        let grid = HeightGrid::from_fn(Vec2::ZERO, 0.1, 11, 11, |x, _| 0.1 * x).unwrap();
        let sole = FootSole {
            heel: Vec3::new(0.2, 0.0, 0.5),
            toe: Vec3::new(0.4, 0.05, 0.5),
            width: 0.1,
        };
        let g = SoleGround::under(&grid, &sole);
        assert!((g.heel - 0.02).abs() < 1e-6);
        assert!((g.centre - 0.03).abs() < 1e-6);
        assert!((g.toe - 0.04).abs() < 1e-6);
        assert!(
            (g.buried(&sole) - 0.02).abs() < 1e-6,
            "the heel is 2 cm under"
        );
        assert_eq!(SoleGround::flush(&sole).buried(&sole), 0.0);
    }

    #[test]
    fn points_off_the_grid_read_the_border() {
        let grid = HeightGrid::from_fn(Vec2::ZERO, 0.1, 11, 11, |x, _| 0.1 * x).unwrap();
        assert!((clamped_height(&grid, Vec3::new(-5.0, 9.0, 0.5)) - 0.0).abs() < 1e-6);
        assert!((clamped_height(&grid, Vec3::new(3.0, 9.0, -2.0)) - 0.1).abs() < 1e-6);
    }
}
