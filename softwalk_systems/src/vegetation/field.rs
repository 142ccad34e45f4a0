//! The paper's deformation field (eq. 2): a translation that pushes points
//! down and away from a foot, with a magnitude falling linearly with distance.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// `t(p) = clamp(t_max - gamma*|p - p_f|) * (p - p_f)_down / |p - p_f|`,
/// with `v_down = (x, -|y|, z)` and the clamp to `[0, t_max]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DeformationField {
    /// Largest translation, at the foot itself (metres).
    pub t_max: f32,
    /// Fall-off of the translation per metre of distance (1/1); the field
    /// vanishes beyond `t_max / gamma`.
    pub gamma: f32,
}

impl DeformationField {
    /// Distance from the foot beyond which the field is exactly zero.
    pub fn radius(&self) -> f32 {
        self.t_max / self.gamma
    }

    /// The translation of point `p` caused by a foot at `foot`.
    ///
    /// At `p == foot` the direction is undefined in the paper; we push straight
    /// down there (the limit of `v_down / |v|` for a point right above the foot),
    /// so the result is never NaN.
    ///
    /// ```
    /// use glam::Vec3;
    /// use softwalk_systems::vegetation::DeformationField;
    /// let field = DeformationField { t_max: 0.4, gamma: 1.0 };
    /// let t = field.at(Vec3::new(0.1, 0.1, 0.0), Vec3::ZERO);
    /// assert!(t.y < 0.0 && t.x > 0.0);
    /// assert_eq!(field.at(Vec3::new(1.0, 0.0, 0.0), Vec3::ZERO), Vec3::ZERO);
    /// assert_eq!(field.at(Vec3::ZERO, Vec3::ZERO), Vec3::new(0.0, -0.4, 0.0));
    /// ```
    #[inline]
    pub fn at(&self, p: Vec3, foot: Vec3) -> Vec3 {
        self.for_offset(p - foot)
    }

    /// The field for the offset `d = p - foot`.
    #[inline]
    fn for_offset(&self, d: Vec3) -> Vec3 {
        let dist_sq = d.length_squared();
        let radius = self.radius();
        if dist_sq >= radius * radius {
            return Vec3::ZERO;
        }
        let dist = dist_sq.sqrt();
        let magnitude = (self.t_max - self.gamma * dist).clamp(0.0, self.t_max);
        if dist <= f32::EPSILON * radius {
            return Vec3::new(0.0, -magnitude, 0.0);
        }
        Vec3::new(d.x, -d.y.abs(), d.z) * (magnitude / dist)
    }

    /// The combined translation of `p` by several feet: the sum of each foot's
    /// field, its length capped at `t_max` (two feet side by side never push
    /// further than one foot standing on the point).
    #[inline]
    pub fn combined(&self, p: Vec3, feet: &[Vec3]) -> Vec3 {
        let sum: Vec3 = feet.iter().map(|&f| self.at(p, f)).sum();
        self.capped(sum)
    }

    /// [`DeformationField::combined`] at the middle and the tip of an upright
    /// blade (`root + (0, height/2, 0)` and `root + (0, height, 0)`), in one
    /// pass over the feet: feet out of horizontal reach are skipped at once.
    /// The result is bit-identical to the two `combined` calls.
    ///
    /// ```
    /// use glam::Vec3;
    /// use softwalk_systems::vegetation::DeformationField;
    /// let field = DeformationField { t_max: 0.4, gamma: 1.0 };
    /// let (root, feet) = (Vec3::new(0.1, 0.0, 0.0), [Vec3::new(0.0, 0.2, 0.0), Vec3::X]);
    /// let [mid, tip] = field.on_upright_blade(root, 0.5, &feet);
    /// assert_eq!(mid, field.combined(root + Vec3::Y * 0.25, &feet));
    /// assert_eq!(tip, field.combined(root + Vec3::Y * 0.5, &feet));
    /// ```
    #[inline]
    pub fn on_upright_blade(&self, root: Vec3, height: f32, feet: &[Vec3]) -> [Vec3; 2] {
        let radius_sq = self.radius() * self.radius();
        let (mid_y, tip_y) = (root.y + 0.5 * height, root.y + height);
        let (mut mid, mut tip) = (Vec3::ZERO, Vec3::ZERO);
        for foot in feet {
            let (dx, dz) = (root.x - foot.x, root.z - foot.z);
            let flat_sq = dx * dx + dz * dz;
            if flat_sq >= radius_sq {
                continue;
            }
            mid += self.for_offset(Vec3::new(dx, mid_y - foot.y, dz));
            tip += self.for_offset(Vec3::new(dx, tip_y - foot.y, dz));
        }
        [self.capped(mid), self.capped(tip)]
    }

    /// `v` with its length capped at `t_max`.
    #[inline]
    fn capped(&self, v: Vec3) -> Vec3 {
        let len_sq = v.length_squared();
        if len_sq > self.t_max * self.t_max {
            v * (self.t_max / len_sq.sqrt())
        } else {
            v
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIELD: DeformationField = DeformationField {
        t_max: 0.5,
        gamma: 2.0,
    };

    #[test]
    fn magnitude_falls_linearly_and_vanishes_at_radius() {
        let foot = Vec3::new(1.0, 0.0, 2.0);
        for i in 0..10 {
            let r = i as f32 * 0.025;
            let t = FIELD.at(foot + Vec3::new(r, 0.0, 0.0), foot);
            assert!((t.length() - (0.5 - 2.0 * r)).abs() < 1e-6, "r {r}: {t}");
        }
        assert_eq!(FIELD.at(foot + Vec3::new(0.25, 0.0, 0.0), foot), Vec3::ZERO);
        assert_eq!(FIELD.at(foot + Vec3::new(0.0, 0.3, 0.0), foot), Vec3::ZERO);
    }

    #[test]
    fn direction_is_away_horizontally_and_always_down() {
        let foot = Vec3::ZERO;
        for p in [Vec3::new(0.1, 0.05, -0.02), Vec3::new(-0.1, -0.05, 0.02)] {
            let t = FIELD.at(p, foot);
            assert!(t.y < 0.0, "{p} -> {t}");
            assert!(t.x * p.x > 0.0 && t.z * p.z > 0.0, "{p} -> {t}");
        }
    }

    #[test]
    fn combined_is_capped_at_t_max() {
        let p = Vec3::new(0.0, 0.01, 0.0);
        let one = FIELD.combined(p, &[Vec3::ZERO]);
        let two = FIELD.combined(p, &[Vec3::ZERO, Vec3::new(0.0, 0.0, 0.01)]);
        assert!(one.length() <= 0.5 + 1e-6);
        assert!(two.length() <= 0.5 + 1e-6);
        assert!(FIELD.combined(p, &[]).length() == 0.0);
        assert!(FIELD.at(Vec3::ZERO, Vec3::ZERO).is_finite());
    }
}
