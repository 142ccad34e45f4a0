//! [`FootBins`]: the feet of one step binned into a coarse grid, so a group
//! of blades is evaluated only against the feet within reach of it.

use glam::Vec3;

/// Largest number of bins; a wider spread of feet gets larger bins.
const MAX_BINS: usize = 1 << 14;

/// Feet (by index) in a grid of square bins over their XZ bounding box,
/// stored bin by bin (a counting sort). Rebuilt each step; the buffers are
/// reused.
#[derive(Debug, Clone, Default)]
pub(crate) struct FootBins {
    origin: [f32; 2],
    cell: f32,
    nx: usize,
    nz: usize,
    /// Start of each bin's feet in `feet`, plus the end.
    start: Vec<u32>,
    /// Foot indices, bin by bin, ascending inside a bin.
    feet: Vec<u32>,
}

impl FootBins {
    /// Bins `feet` into bins at least `cell` metres wide (`cell > 0`).
    pub(crate) fn rebuild(&mut self, feet: &[Vec3], cell: f32) {
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for f in feet {
            lo = [lo[0].min(f.x), lo[1].min(f.z)];
            hi = [hi[0].max(f.x), hi[1].max(f.z)];
        }
        let finite = lo.iter().chain(&hi).all(|v| v.is_finite());
        if feet.is_empty() || !finite || !(cell.is_finite() && cell > 0.0) {
            // One bin holding every foot: correct, only not selective.
            self.origin = [0.0; 2];
            self.cell = f32::INFINITY;
            (self.nx, self.nz) = (1, 1);
            self.start.clear();
            self.start.extend([0, feet.len() as u32]);
            self.feet.clear();
            self.feet.extend(0..feet.len() as u32);
            return;
        }
        let mut cell = cell;
        let count = |c: f32| {
            (
                ((hi[0] - lo[0]) / c) as usize + 1,
                ((hi[1] - lo[1]) / c) as usize + 1,
            )
        };
        while {
            let (nx, nz) = count(cell);
            nx.saturating_mul(nz) > MAX_BINS
        } {
            cell *= 2.0;
        }
        (self.nx, self.nz) = count(cell);
        self.origin = lo;
        self.cell = cell;
        let bins = self.nx * self.nz;
        self.start.clear();
        self.start.resize(bins + 1, 0);
        for f in feet {
            let b = self.bin_of(f);
            self.start[b + 1] += 1;
        }
        for b in 0..bins {
            self.start[b + 1] += self.start[b];
        }
        self.feet.clear();
        self.feet.resize(feet.len(), 0);
        let mut fill: Vec<u32> = self.start[..bins].to_vec();
        for (k, f) in feet.iter().enumerate() {
            let b = self.bin_of(f);
            self.feet[fill[b] as usize] = k as u32;
            fill[b] += 1;
        }
    }

    fn bin_of(&self, f: &Vec3) -> usize {
        let i = (((f.x - self.origin[0]) / self.cell) as usize).min(self.nx - 1);
        let j = (((f.z - self.origin[1]) / self.cell) as usize).min(self.nz - 1);
        j * self.nx + i
    }

    /// Pushes onto `out` the indices of the feet in the bins that meet the
    /// XZ box `[lo, hi]`, in ascending order (after what `out` held).
    pub(crate) fn gather(&self, lo: [f32; 2], hi: [f32; 2], out: &mut Vec<u32>) {
        let from = out.len();
        let range = |lo: f32, hi: f32, origin: f32, n: usize| {
            let a = ((lo - origin) / self.cell).floor();
            let b = ((hi - origin) / self.cell).floor();
            if b < 0.0 || a >= n as f32 || a.is_nan() || b.is_nan() {
                return None;
            }
            Some((a.max(0.0) as usize, (b as usize).min(n - 1)))
        };
        let (Some((i0, i1)), Some((j0, j1))) = (
            range(lo[0], hi[0], self.origin[0], self.nx),
            range(lo[1], hi[1], self.origin[1], self.nz),
        ) else {
            return;
        };
        let (i0, i1, j0, j1) = if self.cell.is_infinite() {
            (0, 0, 0, 0)
        } else {
            (i0, i1, j0, j1)
        };
        for j in j0..=j1 {
            let a = self.start[j * self.nx + i0] as usize;
            let b = self.start[j * self.nx + i1 + 1] as usize;
            out.extend_from_slice(&self.feet[a..b]);
        }
        out[from..].sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_gathers_exactly_the_feet_of_the_bins_it_meets_in_order() {
        let feet: Vec<Vec3> = (0..100)
            .map(|k| Vec3::new((k % 10) as f32, 0.0, (k / 10) as f32))
            .collect();
        let mut bins = FootBins::default();
        bins.rebuild(&feet, 1.0);
        let mut out = Vec::new();
        bins.gather([2.5, 2.5], [3.5, 3.5], &mut out);
        // Bins x 2..=3, z 2..=3.
        assert_eq!(out, vec![22, 23, 32, 33]);
        out.clear();
        bins.gather([-5.0, -5.0], [-1.0, -1.0], &mut out);
        assert!(out.is_empty());
        out.clear();
        bins.gather([-5.0, -5.0], [50.0, 50.0], &mut out);
        assert_eq!(out.len(), 100);
        assert!(out.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn a_wide_spread_gets_larger_bins_and_nan_feet_one_bin() {
        let feet = vec![Vec3::ZERO, Vec3::new(1.0e6, 0.0, 1.0e6)];
        let mut bins = FootBins::default();
        bins.rebuild(&feet, 0.01);
        assert!(bins.nx * bins.nz <= MAX_BINS);
        let mut out = Vec::new();
        bins.gather([-1.0, -1.0], [1.0, 1.0], &mut out);
        assert_eq!(out, vec![0]);
        bins.rebuild(&[Vec3::NAN, Vec3::ZERO], 1.0);
        out.clear();
        bins.gather([0.0, 0.0], [0.1, 0.1], &mut out);
        assert_eq!(out, vec![0, 1]);
    }
}
