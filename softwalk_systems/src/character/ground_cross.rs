//! A patch of ground seen through a cross of five vertical rays: its mean
//! height, the normal of its plane and how little it gives. One ray reads
//! whatever lies under a point (a print's wall, a rim, the edge between two
//! materials); the cross reads the patch.

use glam::{Vec2, Vec3};

use crate::ground::GroundHit;

/// The ground over a patch: the mean of the heights found and the unit
/// normal of the plane through them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GroundCross {
    /// Mean of the heights found, metres.
    pub mean: f32,
    /// Unit normal of the patch's plane (up where a pair of rays missed).
    pub normal: Vec3,
    /// The least give found, metres: a sole across two grounds rests on the
    /// firmer one.
    pub give: f32,
    /// The mean give found, metres: the patch's mean floor is `mean - mean_give`.
    pub mean_give: f32,
    /// What the ray at the patch's centre found.
    pub centre: Option<GroundHit>,
}

impl GroundCross {
    /// Casts `ground` at `at` and `reach_along` ahead and behind it along
    /// the unit direction `forward`, and `reach_across` to either side;
    /// `None` when every ray misses.
    pub fn sample(
        ground: impl Fn(Vec2) -> Option<GroundHit>,
        at: Vec2,
        forward: Vec2,
        reach_along: f32,
        reach_across: f32,
    ) -> Option<GroundCross> {
        let right = Vec2::new(-forward.y, forward.x);
        let centre = ground(at);
        let surface = |h: Option<GroundHit>| h.map(|h| (h.point.y, h.give.max(0.0)));
        let found = [
            surface(centre),
            surface(ground(at + forward * reach_along)),
            surface(ground(at - forward * reach_along)),
            surface(ground(at + right * reach_across)),
            surface(ground(at - right * reach_across)),
        ];
        let samples = found.map(|s| s.map(|(height, _)| height));
        let heights: Vec<f32> = samples.iter().flatten().copied().collect();
        if heights.is_empty() {
            return None;
        }
        let gives: Vec<f32> = found.iter().flatten().map(|&(_, give)| give).collect();
        let give = gives.iter().copied().fold(f32::INFINITY, f32::min);
        let mean_give = gives.iter().sum::<f32>() / gives.len() as f32;
        let grade = |ahead: Option<f32>, behind: Option<f32>, reach: f32| match (ahead, behind) {
            (Some(a), Some(b)) if reach > 0.0 => (a - b) / (2.0 * reach),
            _ => 0.0,
        };
        let along = grade(samples[1], samples[2], reach_along);
        let across = grade(samples[3], samples[4], reach_across);
        let rise = forward * along + right * across;
        Some(GroundCross {
            mean: heights.iter().sum::<f32>() / heights.len() as f32,
            normal: Vec3::new(-rise.x, 1.0, -rise.y).normalize(),
            give,
            mean_give,
            centre,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hit at `p` of height `y` that gives `give`.
    fn hit(p: Vec2, y: f32, give: f32) -> Option<GroundHit> {
        Some(GroundHit {
            point: Vec3::new(p.x, y, p.y),
            normal: Vec3::Y,
            give,
        })
    }

    #[test]
    fn a_plane_is_read_exactly_and_a_pit_under_one_ray_is_averaged_out() {
        let height = |p: Vec2| 0.2 * p.x - 0.1 * p.y + 1.0;
        let plane = |p: Vec2| hit(p, height(p), 0.1 + 0.01 * p.x);
        let c = GroundCross::sample(plane, Vec2::new(1.0, 2.0), Vec2::Y, 0.3, 0.2).unwrap();
        assert!((c.mean - height(Vec2::new(1.0, 2.0))).abs() < 1e-5);
        assert!(
            (c.give - (0.1 + 0.01 * 0.8)).abs() < 1e-6,
            "the firmest sample"
        );
        let expected = Vec3::new(-0.2, 1.0, 0.1).normalize();
        assert!(c.normal.distance(expected) < 1e-5, "{}", c.normal);
        let pit = |p: Vec2| hit(p, if p.length() < 0.01 { -0.5 } else { 0.0 }, 0.0);
        let c = GroundCross::sample(pit, Vec2::ZERO, Vec2::X, 0.3, 0.3).unwrap();
        assert!((c.mean + 0.1).abs() < 1e-6);
        assert_eq!(c.normal, Vec3::Y);
        assert!(GroundCross::sample(|_| None, Vec2::ZERO, Vec2::X, 0.3, 0.3).is_none());
    }
}
