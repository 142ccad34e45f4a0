//! A tiny seeded PRNG (SplitMix64) and its finaliser, so everything random in
//! the project (grass scattering, noise terrains, level-of-detail thinning,
//! test and benchmark inputs) is fixed by a seed on every platform and thread
//! count, without a dependency.
//!
//! ```
//! use engine::rng::SplitMix64;
//!
//! let mut a = SplitMix64::new(7);
//! let mut b = SplitMix64::new(7);
//! let x = a.range(2.0, 3.0);
//! assert!((2.0..3.0).contains(&x));
//! assert_eq!(x, b.range(2.0, 3.0));
//! ```

#![forbid(unsafe_code)]

/// The golden-ratio increment SplitMix64 adds to its state per draw.
pub const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64: 64-bit state, passes BigCrush, two multiplies per draw.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator whose whole sequence is fixed by `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        mix64(self.state)
    }

    /// A uniform `f32` in `[0, 1)` (24 random mantissa bits).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// A uniform `f32` in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next_f32()
    }

    /// A uniform `f32` in `[centre * (1 - spread), centre * (1 + spread))`.
    pub fn around(&mut self, centre: f32, spread: f32) -> f32 {
        centre * self.range(1.0 - spread, 1.0 + spread)
    }
}

/// The SplitMix64 finaliser: a bijective 64-bit mix, usable as a hash of an
/// index or a lattice point.
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_sequence_and_unit_range() {
        let mut a = SplitMix64::new(7);
        let mut b = SplitMix64::new(7);
        let mut c = SplitMix64::new(8);
        let xs: Vec<f32> = (0..1000).map(|_| a.next_f32()).collect();
        let ys: Vec<f32> = (0..1000).map(|_| b.next_f32()).collect();
        let zs: Vec<f32> = (0..1000).map(|_| c.next_f32()).collect();
        assert_eq!(xs, ys);
        assert_ne!(xs, zs);
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = xs.iter().sum::<f32>() / xs.len() as f32;
        assert!((mean - 0.5).abs() < 0.05, "mean {mean}");
    }

    #[test]
    fn first_draw_is_the_finaliser_of_seed_plus_gamma() {
        assert_eq!(
            SplitMix64::new(41).next_u64(),
            mix64(41u64.wrapping_add(GOLDEN_GAMMA))
        );
    }
}
