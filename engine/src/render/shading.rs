//! Lighting parameters and the shading formulas shared by terrain, meshes and grass.
//!
//! Shading is done in linear RGB and encoded for display with gamma 2 (a square
//! root), per vertex; the rasterizer interpolates display values (except the
//! terrain's sun part under caster shadows, taken off per pixel: see
//! `raster::PixelShadow`).

use glam::Vec3;

/// The sun: a directional light plus the sky's ambient light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Unit vector pointing towards the sun.
    pub direction: Vec3,
    /// Direct light colour (linear RGB).
    pub color: Vec3,
    /// Ambient sky light colour (linear RGB), scaled by sky visibility.
    pub ambient: Vec3,
}

impl Sun {
    /// A sun at `azimuth` radians (0 = from +X, pi/2 = from +Z) and `elevation`
    /// radians above the horizon.
    pub fn from_angles(azimuth: f32, elevation: f32, color: Vec3, ambient: Vec3) -> Sun {
        let (sa, ca) = azimuth.sin_cos();
        let (se, ce) = elevation.sin_cos();
        Sun {
            direction: Vec3::new(ca * ce, se, sa * ce),
            color,
            ambient,
        }
    }

    /// Elevation of the sun above the horizon in radians.
    pub fn elevation(&self) -> f32 {
        self.direction.y.clamp(-1.0, 1.0).asin()
    }
}

impl Default for Sun {
    /// A low afternoon sun (28 degrees) from +Z and a little -X: across the default
    /// walking direction +X, so that footprints cast readable shadows, and facing a
    /// camera placed on the -Z side, so that the shaded walls of prints face it.
    fn default() -> Self {
        Sun::from_angles(
            2.0,
            28f32.to_radians(),
            Vec3::new(1.0, 0.93, 0.82) * 1.15,
            Vec3::new(0.42, 0.48, 0.6),
        )
    }
}

/// Everything about light and atmosphere for one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting {
    /// The sun (and ambient light).
    pub sun: Sun,
    /// Sky colour straight up (display-encoded RGB).
    pub sky_zenith: Vec3,
    /// Sky colour at the horizon, also the fog colour (display-encoded RGB).
    pub sky_horizon: Vec3,
    /// Exponential fog density per metre (0 = no fog).
    pub fog_density: f32,
    /// Distance from the eye below which there is no fog, in metres.
    pub fog_start: f32,
}

impl Default for Lighting {
    fn default() -> Self {
        Lighting {
            sun: Sun::default(),
            sky_zenith: Vec3::new(0.42, 0.6, 0.86),
            sky_horizon: Vec3::new(0.8, 0.86, 0.92),
            fog_density: 0.02,
            fog_start: 4.0,
        }
    }
}

impl Lighting {
    /// Fraction of fog at `distance` metres from the eye, in `[0, 1)`.
    #[inline]
    pub fn fog_amount(&self, distance: f32) -> f32 {
        let d = (distance - self.fog_start).max(0.0);
        1.0 - (-self.fog_density * d).exp()
    }

    /// A display colour seen through the fog at `distance`.
    #[inline]
    pub fn apply_fog(&self, display: Vec3, distance: f32) -> Vec3 {
        if distance <= self.fog_start || self.fog_density == 0.0 {
            return display;
        }
        self.blend_fog(display, self.fog_amount(distance))
    }

    /// A display colour seen through fog amount `fog` (from
    /// [`Lighting::fog_amount`]).
    #[inline]
    pub fn blend_fog(&self, display: Vec3, fog: f32) -> Vec3 {
        if fog == 0.0 {
            return display;
        }
        display.lerp(self.sky_horizon, fog)
    }

    /// The sky colour for a view direction with vertical component `up` (-1..1).
    #[inline]
    pub fn sky(&self, up: f32) -> Vec3 {
        let t = up.clamp(0.0, 1.0).sqrt();
        self.sky_horizon.lerp(self.sky_zenith, t)
    }

    /// Linear radiance of a surface with `albedo` and unit `normal`, given its sky
    /// visibility `sky_view` (0..1) and sun visibility `sun_visible` (0..1).
    #[inline]
    pub fn radiance(&self, albedo: Vec3, normal: Vec3, sky_view: f32, sun_visible: f32) -> Vec3 {
        let lambert = normal.dot(self.sun.direction).max(0.0);
        albedo * (self.sun.ambient * sky_view + self.sun.color * (lambert * sun_visible))
    }
}

/// Linear RGB to display values (gamma 2), clamped to `[0, 1]`.
#[inline]
pub fn encode_display(linear: Vec3) -> Vec3 {
    linear.clamp(Vec3::ZERO, Vec3::ONE).map(f32::sqrt)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_sun_is_low_and_across_the_walk() {
        let sun = Sun::default();
        assert!((sun.direction.length() - 1.0).abs() < 1e-5);
        let elevation = sun.elevation().to_degrees();
        assert!((20.0..35.0).contains(&elevation));
        // Horizontal part mostly across +X.
        assert!(sun.direction.z.abs() > 2.0 * sun.direction.x.abs());
    }

    #[test]
    fn fog_grows_with_distance_and_shadow_darkens() {
        let l = Lighting::default();
        assert_eq!(l.fog_amount(1.0), 0.0);
        assert!(l.fog_amount(50.0) > l.fog_amount(10.0));
        let lit = l.radiance(Vec3::ONE, l.sun.direction, 1.0, 1.0);
        let shade = l.radiance(Vec3::ONE, l.sun.direction, 1.0, 0.0);
        assert!(lit.x > shade.x);
        assert_eq!(
            encode_display(Vec3::new(0.25, 2.0, -1.0)),
            Vec3::new(0.5, 1.0, 0.0)
        );
    }
}
