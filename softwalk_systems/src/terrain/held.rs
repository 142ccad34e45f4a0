//! [`HeldSamples`]: the samples the soles hold this step, grouped by print,
//! so a window looks only at the prints it meets; and [`HeldMask`], the same
//! samples as one bit per grid sample, so a rim can ask whether a sample is
//! under a sole in constant time.

use std::ops::Range;

use engine::geom::GridRect;

/// Samples held by soles this step (row-major grid indices), in groups: one
/// per foot in contact, with the rectangle that bounds the group.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct HeldSamples {
    samples: Vec<usize>,
    groups: Vec<(GridRect, Range<usize>)>,
}

impl HeldSamples {
    /// Adds one foot's held `samples`, all inside `bounds`.
    pub fn push_group(&mut self, bounds: GridRect, samples: &[usize]) {
        if samples.is_empty() {
            return;
        }
        let start = self.samples.len();
        self.samples.extend_from_slice(samples);
        self.groups.push((bounds, start..self.samples.len()));
    }

    /// Every held sample, group after group.
    pub fn all(&self) -> &[usize] {
        &self.samples
    }

    /// The held samples of the groups whose bounds meet `rect` (samples of
    /// those groups outside `rect` included).
    pub fn near(&self, rect: GridRect) -> impl Iterator<Item = usize> + '_ {
        self.groups
            .iter()
            .filter(move |(b, _)| !b.intersect(&rect).is_empty())
            .flat_map(|(_, r)| self.samples[r.clone()].iter().copied())
    }

    /// Removes every group, keeping the buffers.
    pub fn clear(&mut self) {
        self.samples.clear();
        self.groups.clear();
    }

    /// True when no sample is held.
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }
}

/// One bit per grid sample: set while a sole holds the sample this step.
/// Setting and clearing cost as much as the samples held, never the grid.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct HeldMask {
    words: Vec<u64>,
}

impl HeldMask {
    /// A mask of `samples` bits, none set.
    pub fn new(samples: usize) -> Self {
        HeldMask {
            words: vec![0; samples.div_ceil(64)],
        }
    }

    /// Sets the bits of `samples`.
    pub fn set(&mut self, samples: &[usize]) {
        for &k in samples {
            self.words[k / 64] |= 1 << (k % 64);
        }
    }

    /// Clears the bits of `samples`.
    pub fn clear(&mut self, samples: &[usize]) {
        for &k in samples {
            self.words[k / 64] &= !(1 << (k % 64));
        }
    }

    /// True when sample `k` is held.
    #[inline]
    pub fn contains(&self, k: usize) -> bool {
        self.words[k / 64] & (1 << (k % 64)) != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mask_holds_what_was_set_until_it_is_cleared() {
        let mut mask = HeldMask::new(130);
        mask.set(&[0, 63, 64, 129]);
        assert!([0, 63, 64, 129].iter().all(|&k| mask.contains(k)));
        assert!(!mask.contains(1) && !mask.contains(128));
        mask.clear(&[63, 129]);
        assert!(mask.contains(0) && mask.contains(64));
        assert!(!mask.contains(63) && !mask.contains(129));
    }

    #[test]
    fn a_window_sees_only_the_groups_it_meets() {
        let mut h = HeldSamples::default();
        h.push_group(GridRect::new(0, 0, 2, 2), &[0, 1]);
        h.push_group(GridRect::new(50, 50, 52, 52), &[7]);
        h.push_group(GridRect::new(9, 9, 10, 10), &[]);
        assert_eq!(h.all(), &[0, 1, 7]);
        let near: Vec<usize> = h.near(GridRect::new(1, 1, 5, 5)).collect();
        assert_eq!(near, vec![0, 1]);
        assert_eq!(h.near(GridRect::new(20, 20, 30, 30)).count(), 0);
    }
}
