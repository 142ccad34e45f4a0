//! Deterministic randomness: a SplitMix64 generator and seeded value noise / fBm.
//!
//! Everything is integer hashing plus `f32` arithmetic, so the same seed gives
//! the same terrain on every run and every thread count.

/// The SplitMix64 pseudo-random generator (small, fast, seedable).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix64(self.state)
    }

    /// A uniform value in `[0, 1)`.
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// A uniform value in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next_f32()
    }
}

/// The SplitMix64 finaliser: a bijective 64-bit mix.
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A value in `[-1, 1)` for lattice point `(i, j)` and `seed`.
fn lattice(i: i64, j: i64, seed: u64) -> f32 {
    let h = mix64(
        seed ^ mix64((i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (j as u64).rotate_left(32)),
    );
    (h >> 40) as f32 / (1u64 << 23) as f32 - 1.0
}

/// Seeded value noise at `(x, y)` (lattice spacing 1), smooth (smoothstep blend), in `[-1, 1]`.
pub fn value_noise(x: f32, y: f32, seed: u64) -> f32 {
    let (fx, fy) = (x.floor(), y.floor());
    let (i, j) = (fx as i64, fy as i64);
    let smooth = |t: f32| t * t * (3.0 - 2.0 * t);
    let (tx, ty) = (smooth(x - fx), smooth(y - fy));
    let a = lattice(i, j, seed) + (lattice(i + 1, j, seed) - lattice(i, j, seed)) * tx;
    let b = lattice(i, j + 1, seed) + (lattice(i + 1, j + 1, seed) - lattice(i, j + 1, seed)) * tx;
    a + (b - a) * ty
}

/// Fractal sum of `octaves` value-noise layers (frequency x2, amplitude x`gain`
/// per octave), normalised to `[-1, 1]`.
pub fn fbm(x: f32, y: f32, octaves: u32, gain: f32, seed: u64) -> f32 {
    let (mut sum, mut norm, mut amp, mut freq) = (0.0, 0.0, 1.0, 1.0);
    for o in 0..octaves {
        sum += amp * value_noise(x * freq, y * freq, seed.wrapping_add(o as u64));
        norm += amp;
        amp *= gain;
        freq *= 2.0;
    }
    if norm > 0.0 { sum / norm } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generator_is_deterministic_and_uniform_enough() {
        let mut a = SplitMix64::new(7);
        let mut b = SplitMix64::new(7);
        let xs: Vec<f32> = (0..1000).map(|_| a.next_f32()).collect();
        assert!(
            xs.iter()
                .all(|&x| x == b.next_f32() && (0.0..1.0).contains(&x))
        );
        let mean = xs.iter().sum::<f32>() / 1000.0;
        assert!((mean - 0.5).abs() < 0.05, "mean {mean}");
        assert_ne!(SplitMix64::new(8).next_u64(), SplitMix64::new(7).next_u64());
    }

    #[test]
    fn noise_is_bounded_continuous_and_seeded() {
        for k in 0..500 {
            let (x, y) = (k as f32 * 0.37 - 50.0, k as f32 * 0.11 - 20.0);
            let v = fbm(x, y, 5, 0.5, 3);
            assert!((-1.0..=1.0).contains(&v));
            assert!((value_noise(x, y, 3) - value_noise(x + 1e-3, y, 3)).abs() < 0.01);
        }
        assert_ne!(value_noise(0.5, 0.5, 1), value_noise(0.5, 0.5, 2));
        assert_eq!(fbm(1.3, 2.7, 4, 0.5, 9), fbm(1.3, 2.7, 4, 0.5, 9));
    }
}
