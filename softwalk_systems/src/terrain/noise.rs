//! Seeded value noise and fBm, hashed with the SplitMix64 finaliser
//! ([`engine::rng::mix64`]).
//!
//! Everything is integer hashing plus `f32` arithmetic, so the same seed gives
//! the same terrain on every run and every thread count.

use engine::rng::{GOLDEN_GAMMA, mix64};

/// A value in `[-1, 1)` for lattice point `(i, j)` and `seed`.
fn lattice(i: i64, j: i64, seed: u64) -> f32 {
    let h = mix64(seed ^ mix64((i as u64).wrapping_mul(GOLDEN_GAMMA) ^ (j as u64).rotate_left(32)));
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
