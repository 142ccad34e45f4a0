//! A [`Ground`] adapter so the foot ray sees the virtual platforms.

use glam::{Vec2, Vec3};

use crate::ground::{Ground, GroundHit};

/// A platform's top, as the foot ray sees it: a horizontal rectangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlatformTop {
    /// Centre of the rectangle (world X, Z).
    pub centre: Vec2,
    /// Half extent in X and Z.
    pub half_size: Vec2,
    /// World height of the top.
    pub top_y: f32,
}

impl PlatformTop {
    /// True when the vertical line through `(x, z)` crosses the top.
    pub fn covers(&self, x: f32, z: f32) -> bool {
        let d = (Vec2::new(x, z) - self.centre).abs();
        d.x <= self.half_size.x && d.y <= self.half_size.y
    }
}

/// The real ground plus platforms: a ray hits a platform's top when it is over
/// it, below the ray's start and above the real ground; otherwise the real ground.
/// Platforms stand on the real ground: where the real ray finds nothing, so does this one.
///
/// ```
/// use glam::Vec2;
/// use softwalk_systems::ground::{FlatGround, Ground};
/// use softwalk_systems::vegetation::{PlatformGround, PlatformTop};
/// let top = PlatformTop { centre: Vec2::ZERO, half_size: Vec2::splat(0.1), top_y: 0.2 };
/// let ground = PlatformGround { ground: &FlatGround(0.0), platforms: &[top] };
/// assert_eq!(ground.cast_down(0.0, 0.0, 2.0).unwrap().point.y, 0.2);
/// assert_eq!(ground.cast_down(0.5, 0.0, 2.0).unwrap().point.y, 0.0);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct PlatformGround<'a, G: Ground + ?Sized> {
    /// The real ground.
    pub ground: &'a G,
    /// The platforms standing on it.
    pub platforms: &'a [PlatformTop],
}

impl<G: Ground + ?Sized> Ground for PlatformGround<'_, G> {
    fn cast_down(&self, x: f32, z: f32, from_y: f32) -> Option<GroundHit> {
        let real = self.ground.cast_down(x, z, from_y)?;
        let floor = real.point.y;
        let platform_y = self
            .platforms
            .iter()
            .filter(|p| p.covers(x, z) && p.top_y <= from_y && p.top_y > floor)
            .map(|p| p.top_y)
            .fold(None, |best: Option<f32>, y| {
                Some(best.map_or(y, |b| b.max(y)))
            });
        match platform_y {
            Some(y) => Some(GroundHit {
                point: Vec3::new(x, y, z),
                normal: Vec3::Y,
                give: 0.0,
            }),
            None => Some(real),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ground::FlatGround;

    #[test]
    fn platform_below_ground_or_above_ray_is_ignored() {
        let tops = [
            PlatformTop {
                centre: Vec2::ZERO,
                half_size: Vec2::splat(0.2),
                top_y: 0.5,
            },
            PlatformTop {
                centre: Vec2::ZERO,
                half_size: Vec2::splat(0.2),
                top_y: 2.0,
            },
        ];
        let g = PlatformGround {
            ground: &FlatGround(1.0),
            platforms: &tops,
        };
        assert_eq!(g.cast_down(0.0, 0.0, 1.5).unwrap().point.y, 1.0);
        assert_eq!(g.cast_down(0.0, 0.0, 3.0).unwrap().point.y, 2.0);
        assert!(g.cast_down(0.0, 0.0, 0.9).is_none());
    }
}
