//! Glue from a [`TerrainSpec`] to the library's terrain generators.
//!
//! The shape comes from `softwalk_systems::terrain::generate` (flat, slope,
//! dunes, noise) or from `engine::asset::load_heightmap`; a base slope is
//! added per sample; then heights are shifted so the lowest sample is at 0 and
//! clamped to `[0, max_height]`. The grid's origin is `(0, 0)`, so the terrain
//! spans `x` in `[0, size_x]`, `z` in `[0, size_z]`. A heightmap PNG is
//! stretched over the whole terrain: pixel `(0, 0)` at `x = 0, z = 0`,
//! columns along +X, rows along +Z, bilinear in between.

use std::path::Path;

use engine::asset::{AssetError, load_heightmap};
use engine::geom::HeightGrid;
use glam::Vec2;
use softwalk_systems::terrain::generate::{self, DuneParams, GridSpec, NoiseParams};
use softwalk_systems::terrain::{Heightfield, MaterialTable, TerrainError};

use super::terrain::generator_error;
use super::{SceneError, TerrainShape, TerrainSpec};

/// Field the heightmap path is read from, named in file errors.
const HEIGHTMAP_FIELD: &str = "terrain.shape.path";

impl TerrainShape {
    /// The shape's heights on `spec`, from the matching generator. A heightmap
    /// is not generated: this returns flat ground for it (see [`TerrainSpec::build_height_grid`]).
    pub(crate) fn generate(&self, spec: GridSpec) -> Result<HeightGrid, TerrainError> {
        match *self {
            TerrainShape::Flat | TerrainShape::Heightmap { .. } => generate::flat(spec, 0.0),
            TerrainShape::Slope {
                angle_deg,
                direction_deg,
            } => {
                let (s, c) = direction_deg.to_radians().sin_cos();
                let uphill = Vec2::new(c, s) * angle_deg.signum();
                generate::slope(spec, 0.0, angle_deg.abs(), uphill)
            }
            TerrainShape::Dunes {
                amplitude,
                wavelength,
                stoss_fraction,
                sinuosity,
                seed,
            } => generate::dunes(
                spec,
                DuneParams {
                    base: 0.0,
                    amplitude,
                    wavelength,
                    stoss_fraction,
                    sinuosity,
                    seed,
                },
            ),
            TerrainShape::Noise {
                amplitude,
                feature_size,
                octaves,
                gain,
                seed,
            } => generate::noise(
                spec,
                NoiseParams {
                    base: 0.0,
                    amplitude,
                    feature_size,
                    octaves,
                    gain,
                    seed,
                },
            ),
        }
    }
}

impl TerrainSpec {
    /// Where the samples lie: origin `(0, 0)`, [`TerrainSpec::cell_size`] apart,
    /// [`TerrainSpec::grid_samples`] of them.
    pub fn grid_spec(&self) -> GridSpec {
        let (nx, nz) = self.grid_samples();
        GridSpec {
            origin: Vec2::ZERO,
            cell: self.cell_size(),
            nx,
            nz,
        }
    }

    /// Builds the height grid; a heightmap path resolves against `base_dir`.
    pub fn build_height_grid(&self, base_dir: &Path) -> Result<HeightGrid, SceneError> {
        let spec = self.grid_spec();
        let mut grid = match &self.shape {
            TerrainShape::Heightmap { path, height_scale } => {
                self.stretch_heightmap(&base_dir.join(path), *height_scale, spec)?
            }
            shape => shape
                .generate(spec)
                .map_err(|e| generator_error("terrain.shape", e))?,
        };
        if let Some(base) = self.base_slope {
            let centre = spec.center();
            for j in 0..grid.nz() {
                for i in 0..grid.nx() {
                    let p = grid.sample_position(i, j);
                    let h = p.y + base.height_at(p.x, p.z, [centre.x, centre.y]);
                    grid.set_height(i, j, h);
                }
            }
        }
        let lowest = grid.heights().iter().copied().fold(f32::INFINITY, f32::min);
        let max_height = self.max_height;
        for h in grid.heights_mut() {
            *h = (*h - lowest).clamp(0.0, max_height);
        }
        Ok(grid)
    }

    /// The PNG at `path` (pixels 1 m apart as loaded), resampled bilinearly onto `spec`
    /// so that it covers the whole terrain.
    fn stretch_heightmap(
        &self,
        path: &Path,
        height_scale: f32,
        spec: GridSpec,
    ) -> Result<HeightGrid, SceneError> {
        let image = load_heightmap(path, 1.0, height_scale).map_err(|e| match e {
            AssetError::Missing { path } => SceneError::MissingFile {
                field: HEIGHTMAP_FIELD.into(),
                path,
            },
            other => SceneError::BadFile {
                field: HEIGHTMAP_FIELD.into(),
                path: path.to_path_buf(),
                reason: other.to_string(),
            },
        })?;
        let pixels = image.extent();
        let (sx, sz) = (pixels.x / self.size_x, pixels.y / self.size_z);
        HeightGrid::from_fn(spec.origin, spec.cell, spec.nx, spec.nz, |x, z| {
            image.height_bilinear(x * sx, z * sz).unwrap_or(0.0)
        })
        .map_err(|e| SceneError::invalid("terrain.resolution", e.to_string()))
    }

    /// The terrain as a [`Heightfield`]: heights from [`TerrainSpec::build_height_grid`],
    /// materials from `table` painted by `material` and `regions` (later regions win).
    pub fn build_heightfield(
        &self,
        base_dir: &Path,
        table: MaterialTable,
    ) -> Result<Heightfield, SceneError> {
        let id = |field: String, name: &str| {
            table
                .id(name)
                .map_err(|e| SceneError::invalid(field, e.to_string()))
        };
        let fill = id("terrain.material".into(), &self.material)?;
        let regions = self
            .regions
            .iter()
            .enumerate()
            .map(|(k, r)| {
                Ok((
                    r,
                    id(format!("terrain.regions[{k}].material"), &r.material)?,
                ))
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        let grid = self.build_height_grid(base_dir)?;
        let terrain_error = |e: TerrainError| SceneError::invalid("terrain", e.to_string());
        let mut field = Heightfield::from_grid(grid, table, fill).map_err(terrain_error)?;
        if !regions.is_empty() {
            field
                .paint_fn(|x, z| {
                    regions
                        .iter()
                        .rev()
                        .find(|(r, _)| r.contains(x, z))
                        .map_or(fill, |(_, id)| *id)
                })
                .map_err(terrain_error)?;
        }
        Ok(field)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, Slope};

    fn terrain(shape: TerrainShape) -> TerrainSpec {
        TerrainSpec {
            size_x: 4.0,
            size_z: 2.0,
            resolution: 41,
            max_height: 10.0,
            material: "sand".into(),
            shape,
            base_slope: None,
            regions: Vec::new(),
        }
    }

    #[test]
    fn flat_and_slope() {
        let g = terrain(TerrainShape::Flat)
            .build_height_grid(Path::new(""))
            .unwrap();
        assert_eq!((g.nx(), g.nz()), (41, 21));
        assert!(g.heights().iter().all(|h| *h == 0.0));
        let slope = terrain(TerrainShape::Slope {
            angle_deg: 45.0,
            direction_deg: 0.0,
        });
        let g = slope.build_height_grid(Path::new("")).unwrap();
        assert!(g.height(0, 5).abs() < 1e-5);
        assert!((g.height(40, 5) - 4.0).abs() < 1e-4);
        assert!((g.height(20, 0) - g.height(20, 20)).abs() < 1e-5);
        let down = terrain(TerrainShape::Slope {
            angle_deg: -45.0,
            direction_deg: 0.0,
        });
        let g = down.build_height_grid(Path::new("")).unwrap();
        assert!((g.height(0, 5) - 4.0).abs() < 1e-4);
        assert!(g.height(40, 5).abs() < 1e-5);
    }

    #[test]
    fn dunes_on_a_base_slope_stay_in_range_and_builds_repeat() {
        let mut t = terrain(TerrainShape::Dunes {
            amplitude: 0.3,
            wavelength: 1.0,
            stoss_fraction: 0.7,
            sinuosity: 0.0,
            seed: 1,
        });
        t.base_slope = Some(Slope {
            angle_deg: 5.0,
            direction_deg: 90.0,
        });
        let a = t.build_height_grid(Path::new("")).unwrap();
        let b = t.build_height_grid(Path::new("")).unwrap();
        assert_eq!(a.heights(), b.heights());
        let max = a.heights().iter().copied().fold(0.0, f32::max);
        assert!(max <= 0.3 + 5f32.to_radians().tan() * 2.0 + 1e-4);
        assert!(max > 0.25);
    }

    #[test]
    fn heightmap_png_is_stretched_over_the_terrain() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("h.png");
        let pixels: Vec<u16> = vec![0, 65535, 0, 65535, 0, 65535];
        image::ImageBuffer::<image::Luma<u16>, _>::from_raw(2, 3, pixels)
            .unwrap()
            .save(&png)
            .unwrap();
        let t = terrain(TerrainShape::Heightmap {
            path: "h.png".into(),
            height_scale: 2.0,
        });
        let g = t.build_height_grid(dir.path()).unwrap();
        assert_eq!(g.height(0, 0), 0.0);
        assert!((g.height(40, 0) - 2.0).abs() < 1e-5);
        assert!((g.height(20, 10) - 1.0).abs() < 1e-4);

        std::fs::write(&png, b"not a png").unwrap();
        let e = t.build_height_grid(dir.path()).unwrap_err();
        assert_eq!(e.field(), Some("terrain.shape.path"));
        assert!(e.to_string().contains("cannot use"), "{e}");
        std::fs::remove_file(&png).unwrap();
        let e = t.build_height_grid(dir.path()).unwrap_err();
        assert!(matches!(e, SceneError::MissingFile { .. }), "{e}");
    }

    #[test]
    fn regions_paint_the_material_map() {
        let mut t = terrain(TerrainShape::Flat);
        t.regions = vec![crate::scene::MaterialRegion {
            material: "snow".into(),
            x: Some([2.0, 4.0]),
            z: None,
        }];
        let field = t
            .build_heightfield(Path::new(""), MaterialTable::with_presets())
            .unwrap();
        assert_eq!(field.material_at(1.0, 1.0).unwrap().name, "sand");
        assert_eq!(field.material_at(3.0, 1.0).unwrap().name, "snow");
        t.material = "lava".into();
        let e = t
            .build_heightfield(Path::new(""), MaterialTable::with_presets())
            .unwrap_err();
        assert_eq!(e.field(), Some("terrain.material"));
    }

    #[test]
    fn every_builtin_terrain_builds_within_its_max_height() {
        for name in ["default", "mixed", "sand-down"] {
            let scene = Scene::builtin(name).unwrap();
            let g = scene.terrain.build_height_grid(&scene.base_dir).unwrap();
            let max = g.heights().iter().copied().fold(0.0, f32::max);
            assert!(
                max > 0.0 && max <= scene.terrain.max_height,
                "{name}: {max}"
            );
        }
    }
}
