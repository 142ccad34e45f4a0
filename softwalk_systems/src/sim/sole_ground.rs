//! The ground under a sole: its heights under the heel, centre and toe,
//! recorded each step so sliding and burying can be measured from the metrics.
//! A foot on a static mesh (a rock, a plank) stands on the mesh's top, so
//! the mesh counts as the ground where it lies just above the terrain.
//!
//! A sole is a rounded rectangle, and so is its print. Its very tips lie on
//! the print's wall, which a height grid can only draw as a slope one cell
//! wide between carved and uncarved samples, so the heel and toe are measured
//! at the centres of the sole's rounded ends (half a sole width in from the
//! tips): the last points whose ground the print fully carves.

use engine::geom::{HeightGrid, RayScene};
use glam::Vec3;

use super::ground_state::GroundState;
use crate::foot::FootSole;

/// How far above a sole point a static mesh's surface may be and still be
/// the ground under it, metres: a foot sunk into a rock is measured against
/// the rock's top, a foot under a bridge not against the bridge.
pub const MESH_GROUND_REACH: f32 = 0.3;

/// Ground heights under one sole (heel end, centre, toe end), metres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SoleGround {
    /// Ground height under the centre of the heel's rounded end.
    pub heel: f32,
    /// Ground height under the sole centre.
    pub centre: f32,
    /// Ground height under the centre of the toe's rounded end.
    pub toe: f32,
}

/// The centres of a sole's rounded heel and toe ends: half the sole width
/// in from its tips along the sole (the centre for a sole shorter than wide).
pub fn sole_ends(sole: &FootSole) -> [Vec3; 2] {
    let along = sole.toe - sole.heel;
    let inset = (0.5 * sole.width / along.length().max(f32::EPSILON)).min(0.5);
    [sole.heel + along * inset, sole.toe - along * inset]
}

impl SoleGround {
    /// Samples `grid` under the heel end, centre and toe end of `sole`.
    pub fn under(grid: &HeightGrid, sole: &FootSole) -> SoleGround {
        let [heel, toe] = sole_ends(sole);
        SoleGround {
            heel: clamped_height(grid, heel),
            centre: clamped_height(grid, sole.center()),
            toe: clamped_height(grid, toe),
        }
    }

    /// `self` raised to the static meshes of `scene` under the sole's
    /// points, where a mesh's surface lies above the terrain and at most
    /// `MESH_GROUND_REACH` above the point.
    pub fn on_meshes(self, scene: &RayScene, sole: &FootSole) -> SoleGround {
        let [heel, toe] = sole_ends(sole);
        let raised = |terrain: f32, p: Vec3| {
            scene
                .cast_down(None, p.x, p.z, p.y + MESH_GROUND_REACH)
                .map_or(terrain, |hit| terrain.max(hit.point.y))
        };
        SoleGround {
            heel: raised(self.heel, heel),
            centre: raised(self.centre, sole.center()),
            toe: raised(self.toe, toe),
        }
    }

    /// The sole's own heights, as if it stood exactly on the ground (no terrain known).
    pub fn flush(sole: &FootSole) -> SoleGround {
        let [heel, toe] = sole_ends(sole);
        SoleGround {
            heel: heel.y,
            centre: sole.center().y,
            toe: toe.y,
        }
    }

    /// How far the lower of the sole's heel and toe ends sits below the
    /// ground under it, metres (negative when both are above).
    pub fn buried(&self, sole: &FootSole) -> f32 {
        let [heel, toe] = sole_ends(sole);
        (self.heel - heel.y).max(self.toe - toe.y)
    }
}

/// The ground under each sole on `ground`: its terrain, raised to its
/// static meshes (see [`SoleGround::on_meshes`]); without a ground, the
/// soles' own heights.
pub fn under_soles(ground: Option<&GroundState>, soles: &[FootSole; 2]) -> [SoleGround; 2] {
    soles.map(|sole| match ground {
        Some(g) => SoleGround::under(g.terrain().grid(), &sole).on_meshes(g.scene(), &sole),
        None => SoleGround::flush(&sole),
    })
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
        let [heel, toe] = sole_ends(&sole);
        assert!((heel.distance(sole.heel) - 0.05).abs() < 1e-6);
        assert!((toe.distance(sole.toe) - 0.05).abs() < 1e-6);
        assert!((g.heel - 0.1 * heel.x).abs() < 1e-6);
        assert!((g.centre - 0.03).abs() < 1e-6);
        assert!((g.toe - 0.1 * toe.x).abs() < 1e-6);
        assert!(
            (g.buried(&sole) - (0.1 * heel.x - heel.y)).abs() < 1e-6,
            "the heel end is under"
        );
        assert_eq!(SoleGround::flush(&sole).buried(&sole), 0.0);
    }

    #[test]
    fn a_mesh_just_above_the_terrain_is_the_ground_under_a_sole_and_one_high_above_is_not() {
        // A horizontal plate at `top` over x in [0.3, 1], z in [0, 1].
        let plate = |top: f32| {
            let corners = [[0.3, 0.0], [1.0, 0.0], [1.0, 1.0], [0.3, 1.0]];
            let positions = corners.map(|[x, z]| Vec3::new(x, top, z)).to_vec();
            let mut scene = RayScene::new();
            let mesh = engine::geom::TriMesh::new(positions, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
            scene.add_mesh(mesh).unwrap();
            scene
        };
        // The heel end over bare ground (height 0), the toe end over the plate.
        let sole = FootSole {
            heel: Vec3::new(0.0, 0.0, 0.5),
            toe: Vec3::new(0.5, 0.0, 0.5),
            width: 0.1,
        };
        let terrain = SoleGround::flush(&sole);
        // A rock top 4 cm above the toe: the toe end is 4 cm inside it.
        let on_rock = terrain.on_meshes(&plate(0.04), &sole);
        assert_eq!(on_rock.heel, 0.0);
        assert!((on_rock.toe - 0.04).abs() < 1e-6, "{on_rock:?}");
        assert!((on_rock.buried(&sole) - 0.04).abs() < 1e-6);
        // A bridge a metre above is not the ground under the foot; a mesh
        // below the terrain does not lower it.
        assert_eq!(terrain.on_meshes(&plate(1.0), &sole), terrain);
        assert_eq!(terrain.on_meshes(&plate(-0.2), &sole), terrain);
    }

    #[test]
    fn points_off_the_grid_read_the_border() {
        let grid = HeightGrid::from_fn(Vec2::ZERO, 0.1, 11, 11, |x, _| 0.1 * x).unwrap();
        assert!((clamped_height(&grid, Vec3::new(-5.0, 9.0, 0.5)) - 0.0).abs() < 1e-6);
        assert!((clamped_height(&grid, Vec3::new(3.0, 9.0, -2.0)) - 0.1).abs() < 1e-6);
    }
}
