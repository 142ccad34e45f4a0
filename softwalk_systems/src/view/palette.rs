//! Display colours of the ground materials (linear RGB).

use crate::terrain::Heightfield;
use glam::Vec3;

/// Albedo of a material by name: the paper's four grounds have fixed colours;
/// any other (user) material gets a stable colour derived from its name.
pub fn material_albedo(name: &str) -> Vec3 {
    match name {
        "sand" => Vec3::new(0.72, 0.58, 0.36),
        "soil" => Vec3::new(0.36, 0.26, 0.17),
        "mud" => Vec3::new(0.26, 0.19, 0.13),
        "snow" => Vec3::new(0.80, 0.83, 0.88),
        other => {
            let h = other.bytes().fold(0x811c_9dc5u32, |h, b| {
                (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
            });
            let c = |shift: u32| 0.25 + 0.5 * ((h >> shift) & 0xff) as f32 / 255.0;
            Vec3::new(c(0), c(8), c(16))
        }
    }
}

/// Per-sample display colours of a terrain: the albedo of each sample's
/// material, and how trodden each sample is (0..1, from the disturbed mask).
/// Hand both to `engine::render::SampleColors`.
#[derive(Debug, Clone, PartialEq)]
pub struct TerrainPaint {
    /// Albedo per sample, row-major.
    pub albedo: Vec<Vec3>,
    /// Disturbance per sample in 0..1, row-major.
    pub disturbed: Vec<f32>,
}

impl TerrainPaint {
    /// The colours of every sample of `hf`.
    pub fn of(hf: &Heightfield) -> Self {
        let palette = palette(hf);
        TerrainPaint {
            albedo: hf
                .material_map()
                .iter()
                .map(|&id| palette[usize::from(id)])
                .collect(),
            disturbed: hf.disturbed().iter().map(|&d| disturbance(d)).collect(),
        }
    }

    /// Re-reads the material and disturbance of the samples in `rects`
    /// (after the ground changed there, or was repainted).
    pub fn refresh(&mut self, hf: &Heightfield, rects: &[engine::geom::GridRect]) {
        let (nx, marks) = (hf.grid().nx(), hf.disturbed());
        let palette = palette(hf);
        let map = hf.material_map();
        for (i, j) in rects.iter().flat_map(|rect| rect.iter()) {
            let k = j * nx + i;
            self.disturbed[k] = disturbance(marks[k]);
            if let Some(&albedo) = palette.get(usize::from(map[k])) {
                self.albedo[k] = albedo;
            }
        }
    }
}

/// A trodden mark (0..255) as a darkening amount (0..1).
fn disturbance(mark: u8) -> f32 {
    f32::from(mark) / 255.0
}

/// The albedo of each material of `hf`'s table, by material id.
fn palette(hf: &Heightfield) -> Vec<Vec3> {
    hf.table()
        .materials()
        .iter()
        .map(|m| material_albedo(&m.name))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snow_is_brightest_and_user_colours_are_stable() {
        assert!(material_albedo("snow").min_element() > material_albedo("sand").max_element());
        assert_eq!(material_albedo("wet-sand"), material_albedo("wet-sand"));
        assert!(material_albedo("wet-sand").cmple(Vec3::ONE).all());
    }
}
