//! Analytic two-bone IK in position form (hip, knee, ankle with a knee pole).

use glam::Vec3;

/// The joints found by [`solve_two_bone`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoBoneSolution {
    /// The middle joint (knee).
    pub mid: Vec3,
    /// The end joint (ankle): the target when reachable, else the nearest reachable point.
    pub end: Vec3,
    /// True when the target was reachable and `end` is on it.
    pub reached: bool,
}

/// Places a chain `root -l1- mid -l2- end` so that `end` reaches `target`,
/// bending towards `pole`.
///
/// Targets closer than `|l1 - l2|` or farther than `l1 + l2` are clamped
/// along the root-target direction; `reached` is then false.
pub fn solve_two_bone(root: Vec3, target: Vec3, pole: Vec3, l1: f32, l2: f32) -> TwoBoneSolution {
    let to = target - root;
    let raw = to.length();
    let dir = to.try_normalize().unwrap_or(Vec3::NEG_Y);
    let eps = 1.0e-6 * (l1 + l2);
    let d = raw.clamp((l1 - l2).abs() + eps, l1 + l2 - eps);
    let to_pole = pole - root;
    let bend = (to_pole - dir * to_pole.dot(dir))
        .try_normalize()
        .unwrap_or_else(|| dir.any_orthonormal_vector());
    let cos_a = ((l1 * l1 + d * d - l2 * l2) / (2.0 * l1 * d)).clamp(-1.0, 1.0);
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    TwoBoneSolution {
        mid: root + (dir * cos_a + bend * sin_a) * l1,
        end: root + dir * d,
        reached: (d - raw).abs() <= 1.0e-5 * (l1 + l2),
    }
}

/// Knee flexion (0 = straight) of a chain `l1`, `l2` whose ends are
/// `distance` apart (clamped to what the chain can span), radians.
pub fn flexion_at_distance(distance: f32, l1: f32, l2: f32) -> f32 {
    let d = distance.clamp((l1 - l2).abs(), l1 + l2);
    ((d * d - l1 * l1 - l2 * l2) / (2.0 * l1 * l2))
        .clamp(-1.0, 1.0)
        .acos()
}

/// Distance between the ends of a chain `l1`, `l2` bent by `flexion` radians.
pub fn distance_at_flexion(flexion: f32, l1: f32, l2: f32) -> f32 {
    (l1 * l1 + l2 * l2 + 2.0 * l1 * l2 * flexion.cos())
        .max(0.0)
        .sqrt()
}

/// `target` moved along the line from `root` so that the chain's flexion
/// lies in `[least, most]` radians: within a knee's range, or within what it
/// can turn in one step from its last flexion (a joint cannot turn faster
/// than its muscles, so a target that jumps is followed over a few steps
/// instead of in one).
pub fn clamp_flexion(root: Vec3, target: Vec3, least: f32, most: f32, l1: f32, l2: f32) -> Vec3 {
    let to = target - root;
    let flexion = flexion_at_distance(to.length(), l1, l2);
    let limited = flexion.clamp(least, most);
    if limited == flexion {
        return target;
    }
    let dir = to.try_normalize().unwrap_or(Vec3::NEG_Y);
    root + dir * distance_at_flexion(limited, l1, l2)
}

/// The point straight above or below `ankle` at `length` from `hip` (the
/// lower of the two, below the hip): where a planted foot out of a leg's
/// reach goes, lifted instead of pulled towards the hip so that it does not
/// slide. `None` when the ankle is further than `length` from the hip
/// horizontally.
pub fn lift_to_reach(hip: Vec3, ankle: Vec3, length: f32) -> Option<Vec3> {
    let across = glam::Vec2::new(ankle.x - hip.x, ankle.z - hip.z).length_squared();
    let below = length * length - across;
    (below >= 0.0).then(|| Vec3::new(ankle.x, hip.y - below.sqrt(), ankle.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flexion_and_distance_are_inverse() {
        for flexion in [0.0f32, 0.3, 1.2, 2.0] {
            let d = distance_at_flexion(flexion, 0.45, 0.43);
            assert!((flexion_at_distance(d, 0.45, 0.43) - flexion).abs() < 1e-3);
        }
    }

    #[test]
    fn flexion_is_clamped_along_the_line() {
        let root = Vec3::new(0.0, 1.0, 0.0);
        let target = Vec3::new(0.0, 0.4, 0.0);
        let limited = clamp_flexion(root, target, 0.0, 0.2, 0.45, 0.45);
        let s = solve_two_bone(root, limited, root + Vec3::Z, 0.45, 0.45);
        let flexion = (s.mid - root).angle_between(s.end - s.mid);
        assert!((flexion - 0.2).abs() < 1e-3, "{flexion}");
        assert!(limited.x.abs() < 1e-6 && limited.y < target.y);
        let free = clamp_flexion(root, target, 0.0, 3.5, 0.45, 0.45);
        assert_eq!(free, target);
    }

    #[test]
    fn reachable_targets_are_reached_exactly_with_bone_lengths_kept() {
        let root = Vec3::new(0.1, 0.9, -0.2);
        for target in [
            Vec3::new(0.1, 0.1, 0.1),
            Vec3::new(0.3, 0.3, 0.3),
            Vec3::new(0.1, 0.5, -0.2),
        ] {
            let s = solve_two_bone(root, target, root + Vec3::Z, 0.43, 0.43);
            assert!(s.reached);
            assert!(s.end.distance(target) < 1e-5);
            assert!((s.mid.distance(root) - 0.43).abs() < 1e-5);
            assert!((s.mid.distance(s.end) - 0.43).abs() < 1e-5);
            // The knee bends towards the pole (+Z).
            assert!(s.mid.z > (root.z + target.z) / 2.0 - 1e-6);
        }
    }

    #[test]
    fn unreachable_targets_are_clamped_along_the_direction() {
        let s = solve_two_bone(Vec3::ZERO, Vec3::new(0.0, -2.0, 0.0), Vec3::Z, 0.4, 0.4);
        assert!(!s.reached);
        assert!((s.end.length() - 0.8).abs() < 1e-4);
        assert!(s.end.x.abs() < 1e-6 && s.end.y < 0.0);
        assert!(s.mid.is_finite() && s.end.is_finite());
        let s = solve_two_bone(Vec3::ZERO, Vec3::ZERO, Vec3::Z, 0.4, 0.3);
        assert!(!s.reached && s.mid.is_finite() && s.end.is_finite());
    }

    #[test]
    fn a_foot_out_of_reach_is_lifted_straight_up_onto_the_reach() {
        let hip = Vec3::new(0.0, 1.0, 0.0);
        let ankle = Vec3::new(0.3, 0.0, 0.4);
        let lifted = lift_to_reach(hip, ankle, 0.9).unwrap();
        assert_eq!((lifted.x, lifted.z), (ankle.x, ankle.z));
        assert!((lifted.distance(hip) - 0.9).abs() < 1e-5);
        assert!(lifted.y > ankle.y && lifted.y < hip.y);
        assert!(lift_to_reach(hip, Vec3::new(1.0, 0.0, 0.0), 0.9).is_none());
    }
}
