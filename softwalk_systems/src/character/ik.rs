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

#[cfg(test)]
mod tests {
    use super::*;

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
}
