//! Smooth, seeded value noise for the `noise` terrain shape (no global state, no time seeds).

/// A lattice value in `[-1, 1]` for integer point `(i, j)` and `seed` (SplitMix64 finaliser).
fn lattice(i: i64, j: i64, seed: u32) -> f32 {
    let mut x = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ u64::from(seed).wrapping_mul(0x1656_67B1_9E37_79F9);
    x ^= x >> 30;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 31;
    (x >> 40) as f32 / (1u64 << 23) as f32 - 1.0
}

fn smoothstep(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// One octave of value noise at `(x, z)` with lattice spacing `wavelength`, in `[-1, 1]`.
fn octave(x: f32, z: f32, wavelength: f32, seed: u32) -> f32 {
    let (u, v) = (x / wavelength, z / wavelength);
    let (i, j) = (u.floor(), v.floor());
    let (fu, fv) = (smoothstep(u - i), smoothstep(v - j));
    let (i, j) = (i as i64, j as i64);
    let a = lattice(i, j, seed) + (lattice(i + 1, j, seed) - lattice(i, j, seed)) * fu;
    let b = lattice(i, j + 1, seed) + (lattice(i + 1, j + 1, seed) - lattice(i, j + 1, seed)) * fu;
    a + (b - a) * fv
}

/// Two octaves of value noise, in `[-amplitude, amplitude]`; the same inputs give the same heights.
pub(crate) fn value_noise(x: f32, z: f32, amplitude: f32, wavelength: f32, seed: u32) -> f32 {
    let coarse = octave(x, z, wavelength, seed);
    let fine = octave(x, z, wavelength * 0.5, seed.wrapping_add(0x5EED));
    amplitude * (coarse + 0.5 * fine) / 1.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounded_seeded_and_continuous() {
        let mut max = 0.0f32;
        for k in 0..2000 {
            let (x, z) = (k as f32 * 0.037, k as f32 * 0.051);
            let h = value_noise(x, z, 0.5, 2.0, 7);
            assert!(h.abs() <= 0.5 + 1e-6);
            assert_eq!(h, value_noise(x, z, 0.5, 2.0, 7));
            let near = value_noise(x + 1e-3, z, 0.5, 2.0, 7);
            assert!((h - near).abs() < 0.01, "jump at {x}, {z}");
            max = max.max(h.abs());
        }
        assert!(max > 0.1, "the noise is not flat");
        assert_ne!(
            value_noise(1.3, 2.7, 1.0, 2.0, 7),
            value_noise(1.3, 2.7, 1.0, 2.0, 8)
        );
    }
}
