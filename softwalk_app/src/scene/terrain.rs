//! `[terrain]`: extent, sampling, shape and material map.
//!
//! The terrain covers `x` in `[0, size_x]` and `z` in `[0, size_z]`; heights
//! lie in `[0, max_height]`. Angles and headings are in degrees, measured
//! from +X towards +Z.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use softwalk_systems::terrain::TerrainError;
use softwalk_systems::terrain::generate::{DuneParams, GridSpec, NoiseParams};

use super::SceneError;
use super::check::{count_at_most, count_in_range, in_range, interval, positive};

/// Largest accepted `terrain.resolution` (samples along the longer side).
pub const MAX_RESOLUTION: u32 = 8192;
/// Largest accepted terrain side, metres.
pub const MAX_TERRAIN_SIZE: f32 = 10_000.0;
/// Most accepted `[[terrain.regions]]` entries (painting costs one region test per sample each).
pub const MAX_REGIONS: usize = 1024;
/// Bounds of a dune wavelength or a noise feature size, metres.
pub const FEATURE_SIZE_RANGE: [f32; 2] = [0.01, MAX_TERRAIN_SIZE];
/// Largest accepted dune sinuosity, periods.
pub const MAX_SINUOSITY: f32 = 10.0;

/// The `[terrain]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainSpec {
    /// Extent along X, metres.
    pub size_x: f32,
    /// Extent along Z, metres.
    pub size_z: f32,
    /// Samples along the longer side (2 to 8192); the cell size is `longer side / (resolution - 1)`
    /// and the shorter side gets as many whole cells as fit.
    pub resolution: u32,
    /// Highest height the terrain may reach, metres; the shape must fit in `[0, max_height]`.
    pub max_height: f32,
    /// Material everywhere no region covers.
    pub material: String,
    /// The relief.
    #[serde(default)]
    pub shape: TerrainShape,
    /// A plane added under the shape (e.g. dunes on a slope).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_slope: Option<Slope>,
    /// Material regions; later regions win where they overlap.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub regions: Vec<MaterialRegion>,
}

/// A plane rising at `angle_deg` towards the heading `direction_deg`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slope {
    /// Steepness in degrees, in `[-60, 60]` (negative falls towards `direction_deg`).
    pub angle_deg: f32,
    /// Uphill heading in degrees (0 = +X, 90 = +Z).
    pub direction_deg: f32,
}

/// The relief, selected by `kind`. Each variant maps onto one generator of
/// `softwalk_systems::terrain::generate` (or `engine::asset::load_heightmap`);
/// the field names are the generator's parameter names.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum TerrainShape {
    /// Level ground.
    #[default]
    Flat,
    /// A plane (see [`Slope`]).
    Slope {
        /// Steepness in degrees, in `[-60, 60]` (negative falls towards `direction_deg`).
        angle_deg: f32,
        /// Uphill heading in degrees.
        direction_deg: f32,
    },
    /// Transverse dunes: ridges along Z repeating along X (`generate::dunes`).
    Dunes {
        /// Trough-to-crest height, metres.
        amplitude: f32,
        /// Crest spacing along X, metres.
        wavelength: f32,
        /// Fraction of a period on the gentle side, in `(0, 1)`; default 0.7.
        #[serde(default = "default_stoss_fraction")]
        stoss_fraction: f32,
        /// Crest sinuosity in periods (0 = straight crests); default 0.1.
        #[serde(default = "default_sinuosity")]
        sinuosity: f32,
        /// Seed of the sinuous crests.
        #[serde(default = "default_seed")]
        seed: u64,
    },
    /// Seeded fractal value-noise hills (`generate::noise`).
    Noise {
        /// Largest deviation from the mean height, metres.
        amplitude: f32,
        /// Size of the largest features, metres.
        feature_size: f32,
        /// Octaves, 1 to 16; default 5.
        #[serde(default = "default_octaves")]
        octaves: u32,
        /// Amplitude ratio between octaves, in `[0, 1]`; default 0.5.
        #[serde(default = "default_gain")]
        gain: f32,
        /// Noise seed.
        #[serde(default = "default_seed")]
        seed: u64,
    },
    /// A 16-bit grayscale PNG stretched over the terrain.
    Heightmap {
        /// PNG file; a relative path is resolved against the scene file's folder.
        path: PathBuf,
        /// Height in metres of pixel value 65535.
        height_scale: f32,
    },
}

fn default_stoss_fraction() -> f32 {
    DuneParams::default().stoss_fraction
}
fn default_sinuosity() -> f32 {
    DuneParams::default().sinuosity
}
fn default_octaves() -> u32 {
    NoiseParams::default().octaves
}
fn default_gain() -> f32 {
    NoiseParams::default().gain
}
fn default_seed() -> u64 {
    1
}

/// A material over a band or rectangle. An omitted axis spans the whole terrain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialRegion {
    /// Material name.
    pub material: String,
    /// `[min, max]` along X, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<[f32; 2]>,
    /// `[min, max]` along Z, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<[f32; 2]>,
}

impl MaterialRegion {
    /// True when `(x, z)` lies in the region (bounds included).
    pub fn contains(&self, x: f32, z: f32) -> bool {
        let inside = |r: Option<[f32; 2]>, v: f32| r.is_none_or(|[lo, hi]| lo <= v && v <= hi);
        inside(self.x, x) && inside(self.z, z)
    }
}

impl Slope {
    /// Height of the plane at `(x, z)` relative to the terrain centre.
    pub fn height_at(&self, x: f32, z: f32, centre: [f32; 2]) -> f32 {
        let (s, c) = self.direction_deg.to_radians().sin_cos();
        self.angle_deg.to_radians().tan() * ((x - centre[0]) * c + (z - centre[1]) * s)
    }

    /// Height difference between the plane's highest and lowest point on a `size` terrain.
    pub fn relief(&self, size: [f32; 2]) -> f32 {
        let (s, c) = self.direction_deg.to_radians().sin_cos();
        self.angle_deg.to_radians().tan().abs() * (size[0] * c.abs() + size[1] * s.abs())
    }

    fn validate(&self, field: &str) -> Result<(), SceneError> {
        in_range(&format!("{field}.angle_deg"), self.angle_deg, -60.0, 60.0)?;
        in_range(
            &format!("{field}.direction_deg"),
            self.direction_deg,
            -360.0,
            360.0,
        )?;
        Ok(())
    }
}

impl TerrainShape {
    /// The base slope of a `Slope` shape, `None` for other shapes.
    pub fn as_slope(&self) -> Option<Slope> {
        match *self {
            TerrainShape::Slope {
                angle_deg,
                direction_deg,
            } => Some(Slope {
                angle_deg,
                direction_deg,
            }),
            _ => None,
        }
    }

    /// An upper bound on the height difference the shape spans on a `size` terrain.
    pub fn relief(&self, size: [f32; 2]) -> f32 {
        match self {
            TerrainShape::Flat => 0.0,
            TerrainShape::Slope { .. } => self.as_slope().map_or(0.0, |s| s.relief(size)),
            TerrainShape::Dunes { amplitude, .. } => *amplitude,
            TerrainShape::Noise { amplitude, .. } => 2.0 * amplitude,
            TerrainShape::Heightmap { height_scale, .. } => *height_scale,
        }
    }

    fn validate(&self, field: &str) -> Result<(), SceneError> {
        match self {
            TerrainShape::Flat => Ok(()),
            TerrainShape::Slope { .. } => self.as_slope().map_or(Ok(()), |s| s.validate(field)),
            TerrainShape::Dunes { amplitude, .. } | TerrainShape::Noise { amplitude, .. } => {
                positive(&format!("{field}.amplitude"), *amplitude, 1000.0)?;
                let [lo, hi] = FEATURE_SIZE_RANGE;
                match self {
                    TerrainShape::Dunes {
                        wavelength,
                        sinuosity,
                        ..
                    } => {
                        in_range(&format!("{field}.wavelength"), *wavelength, lo, hi)?;
                        in_range(
                            &format!("{field}.sinuosity"),
                            *sinuosity,
                            0.0,
                            MAX_SINUOSITY,
                        )?;
                    }
                    TerrainShape::Noise { feature_size, .. } => {
                        in_range(&format!("{field}.feature_size"), *feature_size, lo, hi)?;
                    }
                    _ => {}
                }
                // The generator checks its own parameters; a 2 x 2 probe names the bad one.
                self.generate(GridSpec::square(1.0, 2))
                    .map(|_| ())
                    .map_err(|e| generator_error(field, e))
            }
            TerrainShape::Heightmap { height_scale, .. } => {
                positive(&format!("{field}.height_scale"), *height_scale, 10_000.0)?;
                Ok(())
            }
        }
    }
}

/// A generator's refusal as an error on `field.<parameter>`.
pub(crate) fn generator_error(field: &str, error: TerrainError) -> SceneError {
    match error {
        TerrainError::InvalidParameter { name, reason } => {
            SceneError::invalid(format!("{field}.{name}"), reason)
        }
        other => SceneError::invalid(field, other.to_string()),
    }
}

impl TerrainSpec {
    /// `[size_x, size_z]`.
    pub fn size(&self) -> [f32; 2] {
        [self.size_x, self.size_z]
    }

    /// Distance between neighbouring samples, metres.
    pub fn cell_size(&self) -> f32 {
        self.size_x.max(self.size_z) / (self.resolution.max(2) - 1) as f32
    }

    /// Samples along X and Z: `resolution` along the longer side, whole cells along the other.
    pub fn grid_samples(&self) -> (usize, usize) {
        let cell = self.cell_size();
        let along = |size: f32| ((size / cell + 1e-3).floor() as usize + 1).max(2);
        (along(self.size_x), along(self.size_z))
    }

    /// The extent `[x, z]` the sampled grid covers, metres: `size_x` and `size_z`
    /// rounded down to whole cells. Grass and paths must lie inside it: beyond
    /// it there is no ground.
    pub fn extent(&self) -> [f32; 2] {
        let (nx, nz) = self.grid_samples();
        let cell = self.cell_size();
        [(nx - 1) as f32 * cell, (nz - 1) as f32 * cell]
    }

    /// The slope the whole terrain sits on: the shape's own slope, or `base_slope`.
    pub fn slope(&self) -> Option<Slope> {
        self.shape.as_slope().or(self.base_slope)
    }

    /// The material name at `(x, z)`: the last region containing the point, else `material`.
    pub fn material_at(&self, x: f32, z: f32) -> &str {
        self.regions
            .iter()
            .rev()
            .find(|r| r.contains(x, z))
            .map_or(self.material.as_str(), |r| r.material.as_str())
    }

    /// Checks numbers and shape; material names are checked by the scene.
    pub(crate) fn validate(&self) -> Result<(), SceneError> {
        positive("terrain.size_x", self.size_x, MAX_TERRAIN_SIZE)?;
        positive("terrain.size_z", self.size_z, MAX_TERRAIN_SIZE)?;
        count_in_range("terrain.resolution", self.resolution, 2, MAX_RESOLUTION)?;
        positive("terrain.max_height", self.max_height, 10_000.0)?;
        let size = self.size();
        self.shape.validate("terrain.shape")?;
        if let Some(base) = &self.base_slope {
            if self.shape.as_slope().is_some() {
                return Err(SceneError::invalid(
                    "terrain.base_slope",
                    "a slope shape cannot have a base slope too; combine the angles into one",
                ));
            }
            base.validate("terrain.base_slope")?;
        }
        let relief = self.shape.relief(size) + self.base_slope.map_or(0.0, |s| s.relief(size));
        if relief > self.max_height {
            return Err(SceneError::invalid(
                "terrain.shape",
                format!(
                    "spans {relief:.2} m of height, more than terrain.max_height {}",
                    self.max_height
                ),
            ));
        }
        count_at_most("terrain.regions", self.regions.len(), MAX_REGIONS)?;
        for (k, region) in self.regions.iter().enumerate() {
            if let Some(x) = region.x {
                interval(&format!("terrain.regions[{k}].x"), x, 0.0, self.size_x)?;
            }
            if let Some(z) = region.z {
                interval(&format!("terrain.regions[{k}].z"), z, 0.0, self.size_z)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terrain() -> TerrainSpec {
        TerrainSpec {
            size_x: 10.0,
            size_z: 5.0,
            resolution: 11,
            max_height: 10.0,
            material: "sand".into(),
            shape: TerrainShape::Flat,
            base_slope: None,
            regions: vec![
                MaterialRegion {
                    material: "snow".into(),
                    x: Some([5.0, 10.0]),
                    z: None,
                },
                MaterialRegion {
                    material: "mud".into(),
                    x: Some([8.0, 10.0]),
                    z: Some([0.0, 1.0]),
                },
            ],
        }
    }

    #[test]
    fn grid_uses_resolution_along_the_longer_side() {
        let t = terrain();
        assert_eq!(t.cell_size(), 1.0);
        assert_eq!(t.grid_samples(), (11, 6));
    }

    #[test]
    fn later_regions_win() {
        let t = terrain();
        assert_eq!(t.material_at(1.0, 1.0), "sand");
        assert_eq!(t.material_at(6.0, 4.0), "snow");
        assert_eq!(t.material_at(9.0, 0.5), "mud");
        assert_eq!(t.material_at(9.0, 2.0), "snow");
    }

    #[test]
    fn slope_rises_towards_its_heading() {
        let s = Slope {
            angle_deg: 45.0,
            direction_deg: 0.0,
        };
        let c = [5.0, 5.0];
        assert!((s.height_at(6.0, 5.0, c) - 1.0).abs() < 1e-5);
        assert!((s.height_at(5.0, 9.0, c)).abs() < 1e-5);
        assert!((s.relief([10.0, 10.0]) - 10.0).abs() < 1e-4);
    }

    #[test]
    fn relief_above_max_height_is_refused() {
        let mut t = terrain();
        t.max_height = 1.0;
        t.shape = TerrainShape::Slope {
            angle_deg: 30.0,
            direction_deg: 0.0,
        };
        let e = t.validate().unwrap_err().to_string();
        assert!(e.starts_with("terrain.shape: spans"), "{e}");
    }
}
