//! Turns a [`TerrainSpec`] into an [`engine::geom::HeightGrid`].
//!
//! Heights are the shape plus the base slope, shifted so the lowest sample is
//! at 0 and clamped to `[0, max_height]`. The grid's origin is `(0, 0)`.
//! A heightmap PNG is stretched over the whole terrain: pixel `(0, 0)` at
//! `x = 0, z = 0`, columns along +X, rows along +Z, bilinear in between.

use std::path::Path;

use engine::geom::HeightGrid;
use glam::Vec2;

use super::value_noise::value_noise;
use super::{SceneError, TerrainShape, TerrainSpec};

/// A 16-bit grayscale image, values scaled to `[0, 1]`.
struct Heightmap {
    width: usize,
    height: usize,
    values: Vec<f32>,
}

impl Heightmap {
    fn load(path: &Path) -> Result<Heightmap, SceneError> {
        let bad = |reason: String| SceneError::BadFile {
            field: "terrain.shape.path".into(),
            path: path.to_path_buf(),
            reason,
        };
        let image = image::open(path)
            .map_err(|e| bad(e.to_string()))?
            .into_luma16();
        let (width, height) = (image.width() as usize, image.height() as usize);
        if width < 2 || height < 2 {
            return Err(bad(format!(
                "{width} x {height} pixels; need at least 2 x 2"
            )));
        }
        let values = image
            .as_raw()
            .iter()
            .map(|v| f32::from(*v) / 65535.0)
            .collect();
        Ok(Heightmap {
            width,
            height,
            values,
        })
    }

    /// Bilinear value at fractional pixel coordinates (clamped to the image).
    fn sample(&self, u: f32, v: f32) -> f32 {
        let u = u.clamp(0.0, (self.width - 1) as f32);
        let v = v.clamp(0.0, (self.height - 1) as f32);
        let (i, j) = (
            (u as usize).min(self.width - 2),
            (v as usize).min(self.height - 2),
        );
        let (fu, fv) = (u - i as f32, v - j as f32);
        let at = |i: usize, j: usize| self.values[j * self.width + i];
        let a = at(i, j) + (at(i + 1, j) - at(i, j)) * fu;
        let b = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * fu;
        a + (b - a) * fv
    }
}

impl TerrainSpec {
    /// Builds the height grid; a heightmap path resolves against `base_dir`.
    pub fn build_height_grid(&self, base_dir: &Path) -> Result<HeightGrid, SceneError> {
        let heightmap = match &self.shape {
            TerrainShape::Heightmap { path, .. } => Some(Heightmap::load(&base_dir.join(path))?),
            _ => None,
        };
        let centre = [self.size_x * 0.5, self.size_z * 0.5];
        let base = self.base_slope;
        let shape_height = |x: f32, z: f32| -> f32 {
            let shape = match &self.shape {
                TerrainShape::Flat => 0.0,
                TerrainShape::Slope { .. } => self
                    .shape
                    .as_slope()
                    .map_or(0.0, |s| s.height_at(x, z, centre)),
                TerrainShape::Dunes {
                    amplitude,
                    wavelength,
                    direction_deg,
                } => {
                    let (s, c) = direction_deg.to_radians().sin_cos();
                    let along = x * c + z * s;
                    amplitude * (std::f32::consts::TAU * along / wavelength).sin()
                }
                TerrainShape::Noise {
                    amplitude,
                    wavelength,
                    seed,
                } => value_noise(x, z, *amplitude, *wavelength, *seed),
                TerrainShape::Heightmap { height_scale, .. } => {
                    heightmap.as_ref().map_or(0.0, |m| {
                        let u = x / self.size_x * (m.width - 1) as f32;
                        let v = z / self.size_z * (m.height - 1) as f32;
                        m.sample(u, v) * height_scale
                    })
                }
            };
            shape + base.map_or(0.0, |b| b.height_at(x, z, centre))
        };
        let (nx, nz) = self.grid_samples();
        let grid_error =
            |e: engine::geom::GeomError| SceneError::invalid("terrain.resolution", e.to_string());
        let mut grid = HeightGrid::from_fn(Vec2::ZERO, self.cell_size(), nx, nz, shape_height)
            .map_err(grid_error)?;
        let lowest = grid.heights().iter().copied().fold(f32::INFINITY, f32::min);
        let max_height = self.max_height;
        for h in grid.heights_mut() {
            *h = (*h - lowest).clamp(0.0, max_height);
        }
        Ok(grid)
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
    }

    #[test]
    fn dunes_on_a_base_slope_stay_in_range_and_builds_repeat() {
        let mut t = terrain(TerrainShape::Dunes {
            amplitude: 0.3,
            wavelength: 1.0,
            direction_deg: 0.0,
        });
        t.base_slope = Some(Slope {
            angle_deg: 5.0,
            direction_deg: 90.0,
        });
        let a = t.build_height_grid(Path::new("")).unwrap();
        let b = t.build_height_grid(Path::new("")).unwrap();
        assert_eq!(a.heights(), b.heights());
        let max = a.heights().iter().copied().fold(0.0, f32::max);
        assert!(max <= 0.6 + 5f32.to_radians().tan() * 2.0 + 1e-4);
        assert!(max > 0.5);
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
