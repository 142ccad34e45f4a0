//! Which feet moved since the previous step. A foot that stands still (a
//! planted stance foot) pushes the blades it reaches with exactly the field of
//! the previous step, so those blades need no new field: they are held on.

use glam::Vec3;

/// The feet of one step, compared with those of the previous step.
///
/// Feet are matched by their index in the list given each step (the order of
/// the characters' feet is stable); a foot is *still* when it is bitwise at the
/// same position as the foot of the same index in the previous step.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct FootMotion {
    previous: Vec<Vec3>,
    /// This step's feet that can reach the patch, in input order.
    pub(crate) feet: Vec<Vec3>,
    /// Parallel to `feet`: true if the foot moved since the previous step
    /// (or is new).
    pub(crate) moved: Vec<bool>,
    /// Previous positions of the feet that moved or left, where they could
    /// reach the patch: the blades they held are pushed differently now.
    pub(crate) departed: Vec<Vec3>,
}

impl FootMotion {
    /// Classifies `feet` against the previous step's and remembers them;
    /// `reaches(p)` says whether a foot at `p` can touch the patch at all.
    pub(crate) fn update(&mut self, feet: &[Vec3], reaches: impl Fn(Vec3) -> bool) {
        self.feet.clear();
        self.moved.clear();
        self.departed.clear();
        for (k, &p) in feet.iter().enumerate() {
            let before = self.previous.get(k).copied();
            let still = before == Some(p);
            if let Some(q) = before
                && !still
                && reaches(q)
            {
                self.departed.push(q);
            }
            if reaches(p) {
                self.feet.push(p);
                self.moved.push(!still);
            }
        }
        let left = self.previous.get(feet.len()..).unwrap_or(&[]);
        self.departed
            .extend(left.iter().copied().filter(|&q| reaches(q)));
        self.previous.clear();
        self.previous.extend_from_slice(feet);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn still_moved_new_and_departed_feet() {
        let mut motion = FootMotion::default();
        let a = Vec3::new(0.0, 0.0, 0.0);
        let b = Vec3::new(1.0, 0.0, 0.0);
        let far = Vec3::new(100.0, 0.0, 0.0);
        let reaches = |p: Vec3| p.x < 10.0;
        motion.update(&[a, b], reaches);
        assert_eq!(motion.moved, [true, true], "new feet count as moved");
        assert!(motion.departed.is_empty());
        let b2 = b + Vec3::X * 0.1;
        motion.update(&[a, b2, far], reaches);
        assert_eq!(motion.feet, [a, b2], "a foot out of reach is dropped");
        assert_eq!(motion.moved, [false, true]);
        assert_eq!(motion.departed, [b]);
        motion.update(&[a], reaches);
        assert_eq!(motion.moved, [false]);
        assert_eq!(motion.departed, [b2], "feet that left hold nothing now");
    }
}
