//! The ground under the feet that bear the body's weight, against the
//! body's own ground (the floor under the pelvis): where the two disagree
//! (one foot on the far side of a step, a foot in a deeper print) the leg
//! bearing the weight decides the pelvis height, not the lowest foot.

use glam::Vec2;

use super::gait::Gait;
use super::rays::FootRays;
use crate::ground::rise_along;

/// How much of foot `k`'s reach into the give of its ground the pelvis
/// does not lower for, metres: the give, in the share of the body's weight
/// foot `k` does not bear (see [`Gait::load_share`]). A foot bearing no
/// weight presses loose ground only as far as its leg reaches, so a foot in
/// a deeper print, or beyond the edge of a softer ground, does not hold the
/// body down while the other leg bears it; as it takes the weight it sinks
/// in with the pelvis.
pub(super) fn unloaded_give(gait: &Gait, rays: &FootRays, k: usize) -> f32 {
    (1.0 - gait.load_share(k)) * rays.support[k].landing.give
}

/// How far the floors of the planted feet, weighted by the share of the
/// weight each bears, stand above the plane of the body's ground (its
/// floor under the pelvis, tilted with its slope), metres; 0 where they
/// stand on or below it. On a steady slope both feet stand in that plane;
/// up a step, or out of a print onto firmer ground, the foot on the upper
/// side stands above it as soon as it takes the weight, before the pelvis
/// is over the step. A foot still on the foothold the walker started on
/// (see [`FootSupport::stepped`]) is no step: the pelvis was placed over it.
///
/// [`FootSupport::stepped`]: super::support::FootSupport::stepped
pub(super) fn step_up(gait: &Gait, rays: &FootRays, pelvis: Vec2) -> f32 {
    let body = &rays.body;
    let (mut rise, mut weight) = (0.0, 0.0);
    for k in 0..2 {
        let share = gait.load_share(k);
        if share <= 0.0 || !rays.support[k].stepped {
            continue;
        }
        let floor = rays.support[k].landing.floor();
        let plane = body.point.y + rise_along(body.normal, Vec2::new(floor.x, floor.z) - pelvis);
        rise += share * (floor.y - plane);
        weight += share;
    }
    if weight > 0.0 {
        (rise / weight).max(0.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::character::body::CharacterBody;
    use crate::character::support::SupportPoint;
    use crate::character::{CharacterDesc, GaitModifiers, WalkPath};
    use crate::foot::FootPhase;
    use crate::ground::FlatGround;

    /// An adult walking along +X over level ground at height 0, its left
    /// foot bearing all the weight and its right foot swinging.
    fn left_alone() -> (Gait, FootRays) {
        let body = CharacterBody::new(CharacterDesc::adult()).unwrap();
        let path = WalkPath::straight(Vec3::ZERO, Vec3::X, 5.0).unwrap();
        let mut gait = Gait::new(&body, &path, &GaitModifiers::default());
        gait.phase = 0.3;
        gait.feet[0].phase = FootPhase::Stance;
        gait.feet[1].phase = FootPhase::SwingUp;
        let rays = FootRays::new(&gait, &body, &FlatGround(0.0));
        (gait, rays)
    }

    /// Plants foot `k` of `rays` on a floor at `floor`, under ground that
    /// gives `give` there, at `x` along the walk.
    fn land(rays: &mut FootRays, k: usize, x: f32, floor: f32, give: f32) {
        rays.support[k].stepped = true;
        rays.support[k].landing = SupportPoint {
            give,
            ..SupportPoint::rigid(Vec3::new(x, floor + give, 0.0))
        };
    }

    #[test]
    fn only_a_foot_bearing_no_weight_is_spared_the_reach_into_its_give() {
        let (gait, mut rays) = left_alone();
        land(&mut rays, 0, 0.0, -0.3, 0.3);
        land(&mut rays, 1, 0.3, -0.3, 0.3);
        assert_eq!(unloaded_give(&gait, &rays, 0), 0.0, "bearing the weight");
        assert!(
            (unloaded_give(&gait, &rays, 1) - 0.3).abs() < 1e-6,
            "swinging"
        );
        land(&mut rays, 1, 0.3, 0.0, 0.0);
        assert_eq!(
            unloaded_give(&gait, &rays, 1),
            0.0,
            "rigid: nothing to spare"
        );
    }

    #[test]
    fn the_foot_bearing_the_weight_on_a_step_raises_the_stance_ground() {
        let (gait, mut rays) = left_alone();
        // Level: the stance foot on the body's ground.
        land(&mut rays, 0, 0.2, 0.0, 0.0);
        assert!(step_up(&gait, &rays, Vec2::ZERO).abs() < 1e-6);
        // On a 0.3 m step, or on sand beside deep snow under the pelvis.
        land(&mut rays, 0, 0.2, 0.3, 0.0);
        assert!((step_up(&gait, &rays, Vec2::ZERO) - 0.3).abs() < 1e-6);
        // Below the body's ground (stepping down): nothing.
        land(&mut rays, 0, 0.2, -0.3, 0.0);
        assert_eq!(step_up(&gait, &rays, Vec2::ZERO), 0.0);
        // The swinging foot's landing does not count, however high.
        land(&mut rays, 0, 0.2, 0.0, 0.0);
        land(&mut rays, 1, 0.5, 0.4, 0.0);
        assert!(step_up(&gait, &rays, Vec2::ZERO).abs() < 1e-6);
        // Where the walker started standing, on ground it has not pressed.
        land(&mut rays, 0, 0.2, 0.3, 0.0);
        rays.support[0].stepped = false;
        assert_eq!(step_up(&gait, &rays, Vec2::ZERO), 0.0);
    }

    #[test]
    fn a_foot_on_a_steady_slope_is_no_step() {
        let (gait, mut rays) = left_alone();
        let grade = 20f32.to_radians().tan();
        rays.body.point = Vec3::ZERO;
        rays.body.normal = Vec3::new(-grade, 1.0, 0.0).normalize();
        land(&mut rays, 0, 0.4, 0.4 * grade, 0.0);
        assert!(step_up(&gait, &rays, Vec2::ZERO).abs() < 1e-5);
        land(&mut rays, 0, 0.4, 0.4 * grade + 0.2, 0.0);
        assert!((step_up(&gait, &rays, Vec2::ZERO) - 0.2).abs() < 1e-5);
    }
}
