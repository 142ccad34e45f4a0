//! Procedural terrain shapes: flat, constant slope, dunes and seeded fBm.
//!
//! Each generator validates its parameters (naming the bad one) and the grid
//! size before any allocation, then returns an [`engine::geom::HeightGrid`]
//! to hand to [`super::Heightfield::from_grid`].

use engine::geom::{HeightGrid, MAX_GRID_SAMPLES};
use glam::Vec2;

use super::error::{TerrainError, check_at_least, check_finite};
use super::noise::{fbm, value_noise};

/// Where the samples of a terrain lie: `nx` x `nz` samples `cell` metres apart from `origin` (XZ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// World XZ of sample (0, 0).
    pub origin: Vec2,
    /// Sample spacing, metres.
    pub cell: f32,
    /// Samples along X.
    pub nx: usize,
    /// Samples along Z.
    pub nz: usize,
}

impl GridSpec {
    /// A square of `size` metres with `samples` samples per side, from the origin.
    pub fn square(size: f32, samples: usize) -> Self {
        GridSpec {
            origin: Vec2::ZERO,
            cell: size / samples.saturating_sub(1).max(1) as f32,
            nx: samples,
            nz: samples,
        }
    }

    /// The paper's setting: 10 x 10 m with 512² samples.
    pub fn paper() -> Self {
        Self::square(10.0, 512)
    }

    /// World XZ of the grid centre.
    pub fn center(&self) -> Vec2 {
        self.origin
            + Vec2::new((self.nx.max(1) - 1) as f32, (self.nz.max(1) - 1) as f32)
                * (0.5 * self.cell)
    }

    /// Refuses a bad cell size or origin, fewer than 2 samples a side, or more
    /// than [`MAX_GRID_SAMPLES`] samples; nothing is allocated.
    pub fn validate(&self) -> Result<(), TerrainError> {
        if !(self.cell.is_finite() && self.cell > 0.0) {
            return Err(TerrainError::InvalidParameter {
                name: "cell",
                reason: format!("{} must be finite and > 0", self.cell),
            });
        }
        check_finite("origin.x", self.origin.x)?;
        check_finite("origin.y", self.origin.y)?;
        if self.nx < 2 || self.nz < 2 {
            return Err(TerrainError::InvalidParameter {
                name: "resolution",
                reason: format!("{} x {}: need at least 2 x 2 samples", self.nx, self.nz),
            });
        }
        if self
            .nx
            .checked_mul(self.nz)
            .is_none_or(|n| n > MAX_GRID_SAMPLES)
        {
            return Err(TerrainError::InvalidParameter {
                name: "resolution",
                reason: format!(
                    "{} x {} samples exceed the limit of {MAX_GRID_SAMPLES}",
                    self.nx, self.nz
                ),
            });
        }
        Ok(())
    }

    fn build(&self, f: impl FnMut(f32, f32) -> f32) -> Result<HeightGrid, TerrainError> {
        self.validate()?;
        Ok(HeightGrid::from_fn(
            self.origin,
            self.cell,
            self.nx,
            self.nz,
            f,
        )?)
    }
}

/// A flat terrain at `height`.
pub fn flat(spec: GridSpec, height: f32) -> Result<HeightGrid, TerrainError> {
    check_finite("height", height)?;
    spec.build(|_, _| height)
}

/// A plane rising at `angle_deg` (in [0, 89]) towards `uphill` (XZ, any length
/// > 0), with height `base` at the grid centre.
pub fn slope(
    spec: GridSpec,
    base: f32,
    angle_deg: f32,
    uphill: Vec2,
) -> Result<HeightGrid, TerrainError> {
    check_finite("base", base)?;
    if !(angle_deg.is_finite() && (0.0..=89.0).contains(&angle_deg)) {
        return Err(TerrainError::InvalidParameter {
            name: "angle_deg",
            reason: format!("{angle_deg} is not in [0, 89]"),
        });
    }
    let dir = uphill
        .try_normalize()
        .ok_or(TerrainError::InvalidParameter {
            name: "uphill",
            reason: format!("{uphill} is not a finite non-zero direction"),
        })?;
    let grade = angle_deg.to_radians().tan();
    let c = spec.center();
    spec.build(|x, z| base + grade * (Vec2::new(x, z) - c).dot(dir))
}

/// Transverse dunes: ridges along Z repeating every `wavelength` metres along X.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DuneParams {
    /// Height of the troughs, metres.
    pub base: f32,
    /// Trough-to-crest height, metres (>= 0).
    pub amplitude: f32,
    /// Crest spacing along X, metres (> 0).
    pub wavelength: f32,
    /// Fraction of a period on the gentle (stoss) side, in (0, 1); the rest is the steep lee face.
    pub stoss_fraction: f32,
    /// Crest sinuosity in periods (0 = straight crests).
    pub sinuosity: f32,
    /// Noise seed for the sinuous crests.
    pub seed: u64,
}

impl Default for DuneParams {
    fn default() -> Self {
        DuneParams {
            base: 0.0,
            amplitude: 1.0,
            wavelength: 5.0,
            stoss_fraction: 0.7,
            sinuosity: 0.1,
            seed: 1,
        }
    }
}

/// Asymmetric dune profile over one period `p` in [0, 1): a smooth rise over
/// `stoss`, then a faster fall; 0 in troughs, 1 at the crest.
fn dune_profile(p: f32, stoss: f32) -> f32 {
    use std::f32::consts::PI;
    if p < stoss {
        0.5 - 0.5 * (PI * p / stoss).cos()
    } else {
        0.5 + 0.5 * (PI * (p - stoss) / (1.0 - stoss)).cos()
    }
}

/// A field of transverse dunes.
pub fn dunes(spec: GridSpec, params: DuneParams) -> Result<HeightGrid, TerrainError> {
    check_finite("base", params.base)?;
    check_at_least("amplitude", params.amplitude, 0.0)?;
    if !(params.wavelength.is_finite() && params.wavelength > 0.0) {
        return Err(TerrainError::InvalidParameter {
            name: "wavelength",
            reason: format!("{} must be finite and > 0", params.wavelength),
        });
    }
    if !(params.stoss_fraction > 0.0 && params.stoss_fraction < 1.0) {
        return Err(TerrainError::InvalidParameter {
            name: "stoss_fraction",
            reason: format!("{} is not in (0, 1)", params.stoss_fraction),
        });
    }
    check_at_least("sinuosity", params.sinuosity, 0.0)?;
    let p = params;
    spec.build(|x, z| {
        let shift = p.sinuosity * value_noise(0.0, z / p.wavelength, p.seed);
        let phase = (x / p.wavelength + shift).rem_euclid(1.0);
        p.base + p.amplitude * dune_profile(phase, p.stoss_fraction)
    })
}

/// Seeded fractal value noise (fBm) hills.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseParams {
    /// Mean height, metres.
    pub base: f32,
    /// Largest deviation from `base`, metres (>= 0).
    pub amplitude: f32,
    /// Size of the largest features, metres (> 0).
    pub feature_size: f32,
    /// Octaves, 1 to 16.
    pub octaves: u32,
    /// Amplitude ratio between octaves, in [0, 1].
    pub gain: f32,
    /// Noise seed.
    pub seed: u64,
}

impl Default for NoiseParams {
    fn default() -> Self {
        NoiseParams {
            base: 1.0,
            amplitude: 0.5,
            feature_size: 4.0,
            octaves: 5,
            gain: 0.5,
            seed: 1,
        }
    }
}

/// Rolling hills of seeded fBm: `base + amplitude * fbm(x / feature_size, z / feature_size)`.
pub fn noise(spec: GridSpec, params: NoiseParams) -> Result<HeightGrid, TerrainError> {
    check_finite("base", params.base)?;
    check_at_least("amplitude", params.amplitude, 0.0)?;
    if !(params.feature_size.is_finite() && params.feature_size > 0.0) {
        return Err(TerrainError::InvalidParameter {
            name: "feature_size",
            reason: format!("{} must be finite and > 0", params.feature_size),
        });
    }
    if !(1..=16).contains(&params.octaves) {
        return Err(TerrainError::InvalidParameter {
            name: "octaves",
            reason: format!("{} is not in 1..=16", params.octaves),
        });
    }
    if !(params.gain.is_finite() && (0.0..=1.0).contains(&params.gain)) {
        return Err(TerrainError::InvalidParameter {
            name: "gain",
            reason: format!("{} is not in [0, 1]", params.gain),
        });
    }
    let p = params;
    spec.build(|x, z| {
        p.base
            + p.amplitude
                * fbm(
                    x / p.feature_size,
                    z / p.feature_size,
                    p.octaves,
                    p.gain,
                    p.seed,
                )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> GridSpec {
        GridSpec::square(4.0, 65)
    }

    #[test]
    fn slope_has_the_asked_angle_and_direction() {
        let g = slope(small(), 1.0, 25.0, Vec2::new(0.0, 2.0)).unwrap();
        let rise = g.height(10, 40) - g.height(10, 20);
        let run = 20.0 * g.cell_size();
        assert!((rise / run - 25f32.to_radians().tan()).abs() < 1e-4);
        assert_eq!(g.height(3, 30), g.height(50, 30));
        assert!((g.height(32, 32) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn dunes_have_steep_lee_and_gentle_stoss() {
        let p = DuneParams {
            sinuosity: 0.0,
            amplitude: 0.5,
            wavelength: 2.0,
            ..DuneParams::default()
        };
        let g = dunes(small(), p).unwrap();
        let (lo, hi) = g.min_max_in(&g.full_rect());
        assert!(lo >= -1e-6 && hi <= 0.5 + 1e-6 && hi - lo > 0.45);
        let max_rise = (0..64)
            .map(|i| g.height(i + 1, 5) - g.height(i, 5))
            .fold(0f32, f32::max);
        let max_fall = (0..64)
            .map(|i| g.height(i, 5) - g.height(i + 1, 5))
            .fold(0f32, f32::max);
        assert!(max_fall > 1.5 * max_rise, "fall {max_fall} rise {max_rise}");
    }

    #[test]
    fn noise_is_seeded_and_bounded() {
        let p = NoiseParams::default();
        let a = noise(small(), p).unwrap();
        assert_eq!(a, noise(small(), p).unwrap());
        assert_ne!(a, noise(small(), NoiseParams { seed: 2, ..p }).unwrap());
        let (lo, hi) = a.min_max_in(&a.full_rect());
        assert!(lo >= 0.5 && hi <= 1.5 && hi > lo);
    }

    #[test]
    fn bad_parameters_are_named_before_allocating() {
        let name = |r: Result<HeightGrid, TerrainError>| match r {
            Err(TerrainError::InvalidParameter { name, .. }) => name,
            other => panic!("expected an invalid parameter, got {other:?}"),
        };
        assert_eq!(name(flat(small(), f32::NAN)), "height");
        assert_eq!(name(slope(small(), 0.0, 95.0, Vec2::X)), "angle_deg");
        assert_eq!(name(slope(small(), 0.0, 10.0, Vec2::ZERO)), "uphill");
        let bad = DuneParams {
            amplitude: -1.0,
            ..DuneParams::default()
        };
        assert_eq!(name(dunes(small(), bad)), "amplitude");
        let bad = NoiseParams {
            octaves: 40,
            ..NoiseParams::default()
        };
        assert_eq!(name(noise(small(), bad)), "octaves");
        assert_eq!(
            name(flat(GridSpec::square(10.0, 100_000), 0.0)),
            "resolution"
        );
        let spec = GridSpec {
            cell: -1.0,
            ..small()
        };
        assert_eq!(name(flat(spec, 0.0)), "cell");
    }
}
