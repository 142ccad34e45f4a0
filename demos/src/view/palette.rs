//! Display colours of the ground materials (linear RGB).

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
