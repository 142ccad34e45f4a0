//! What a foot's vertical ray sees: the interface between the character and
//! whatever lies under it (deformed terrain, meshes, virtual platforms).

use glam::Vec3;

/// A point on the ground found by a vertical ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundHit {
    /// The hit point (world).
    pub point: Vec3,
    /// Unit surface normal at the hit.
    pub normal: Vec3,
    /// How far a planted foot presses this surface into the ground, metres:
    /// the print loose ground will take here (0 on rigid ground).
    pub give: f32,
}

/// Anything a foot can stand on, queried with vertical rays.
pub trait Ground {
    /// Casts a ray straight down from `(x, from_y, z)`; the first surface below,
    /// or `None` when there is nothing (off the terrain).
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit>;
}

impl Ground for engine::geom::HeightGrid {
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit> {
        let y = self.height_at(x, z)?;
        if y > from_y {
            return None;
        }
        Some(GroundHit {
            point: Vec3::new(x, y, z),
            normal: self.normal_at(x, z)?,
            give: 0.0,
        })
    }
}

/// How fast ground of unit `normal` rises when crossed along `direction`
/// (x, z): rise per unit of `direction`'s length (a grade for a unit
/// direction, a rate in m/s for a velocity); the normal's tilt is capped so
/// a near-vertical normal gives a large but finite value.
pub fn rise_along(normal: Vec3, direction: glam::Vec2) -> f32 {
    -(normal.x * direction.x + normal.z * direction.y) / normal.y.max(0.1)
}

/// Flat ground at a fixed height (handy in tests).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatGround(pub f32);

impl Ground for FlatGround {
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit> {
        (self.0 <= from_y).then_some(GroundHit {
            point: Vec3::new(x, self.0, z),
            normal: Vec3::Y,
            give: 0.0,
        })
    }
}
