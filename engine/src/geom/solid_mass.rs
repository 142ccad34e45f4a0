//! Volume, centroid and inertia of the solid a closed triangle mesh bounds.
//!
//! Each triangle and a reference point inside the mesh span a tetrahedron;
//! its signed volume, first and second moments have closed forms, and their
//! sums over the surface are the solid's (the divergence theorem). Taking
//! the vertices' mean as the reference keeps the terms small, so a small
//! hole in the surface costs little accuracy.

use glam::{DMat3, DVec3, Mat3, Vec3};

/// The mass properties of a solid of unit density, from its surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidMass {
    /// Volume, m³ (also the mass at unit density).
    pub volume: f32,
    /// Centre of the volume.
    pub centroid: Vec3,
    /// Inertia tensor about the centroid at unit density, kg·m² per kg/m³;
    /// multiply by a density for a body's inertia.
    pub inertia: Mat3,
    /// How far the surface is from closed: the relative change of the volume
    /// when it is measured from a point half the bounding box away instead.
    /// 0 for a closed surface; a surface with holes (an open neck, a missing
    /// face) gives a volume that depends on that point.
    pub leak: f32,
}

impl SolidMass {
    /// The solid bounded by triangles `indices` (three per triangle) over
    /// `positions`, wound either way consistently. `None` when the surface
    /// encloses no volume (empty, flat or inconsistently wound) or an index
    /// is out of range.
    ///
    /// ```
    /// use engine::geom::SolidMass;
    /// use glam::Vec3;
    /// // A tetrahedron with corners at the origin and on the three axes.
    /// let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    /// let tris = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
    /// let m = SolidMass::of_surface(&p, &tris).unwrap();
    /// assert!((m.volume - 1.0 / 6.0).abs() < 1e-6);
    /// assert!((m.centroid - Vec3::splat(0.25)).length() < 1e-6);
    /// ```
    pub fn of_surface(positions: &[Vec3], indices: &[u32]) -> Option<SolidMass> {
        if positions.is_empty() || indices.iter().any(|&i| i as usize >= positions.len()) {
            return None;
        }
        let reference =
            positions.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / positions.len() as f64;
        let (lo, hi) = positions.iter().fold(
            (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
            |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())),
        );
        let shift = (hi - lo) * 0.5;
        let mut volume = 0.0;
        let mut shifted_volume = 0.0;
        let mut first = DVec3::ZERO;
        let mut second = DMat3::ZERO;
        for tri in indices.chunks_exact(3) {
            let [a, b, c] =
                [tri[0], tri[1], tri[2]].map(|i| positions[i as usize].as_dvec3() - reference);
            let v = a.dot(b.cross(c)) / 6.0;
            let sum = a + b + c;
            volume += v;
            shifted_volume += (a - shift).dot((b - shift).cross(c - shift)) / 6.0;
            first += sum * (v / 4.0);
            // ∫ x xᵀ over the tetrahedron (0, a, b, c) = v/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ).
            second += (outer(a, a) + outer(b, b) + outer(c, c) + outer(sum, sum)) * (v / 20.0);
        }
        if !(volume.is_finite() && volume.abs() > f64::EPSILON) {
            return None;
        }
        // Inward winding gives every moment the opposite sign.
        let sign = volume.signum();
        let (volume, first, second) = (volume * sign, first * sign, second * sign);
        let centre = first / volume;
        let about_centre = second - outer(centre, centre) * volume;
        let trace = about_centre.x_axis.x + about_centre.y_axis.y + about_centre.z_axis.z;
        let inertia = DMat3::IDENTITY * trace - about_centre;
        Some(SolidMass {
            volume: volume as f32,
            centroid: (reference + centre).as_vec3(),
            inertia: inertia.as_mat3(),
            leak: ((shifted_volume * sign - volume) / volume).abs() as f32,
        })
    }
}

/// The outer product `a bᵀ`.
fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned box from `lo` to `hi`, its triangles wound outwards.
    fn cuboid(lo: Vec3, hi: Vec3) -> (Vec<Vec3>, Vec<u32>) {
        let p: Vec<Vec3> = (0..8)
            .map(|k| {
                Vec3::new(
                    if k & 1 == 0 { lo.x } else { hi.x },
                    if k & 2 == 0 { lo.y } else { hi.y },
                    if k & 4 == 0 { lo.z } else { hi.z },
                )
            })
            .collect();
        let quads = [
            [0, 2, 3, 1], // -z
            [4, 5, 7, 6], // +z
            [0, 1, 5, 4], // -y
            [2, 6, 7, 3], // +y
            [0, 4, 6, 2], // -x
            [1, 3, 7, 5], // +x
        ];
        let tris = quads
            .iter()
            .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
            .collect();
        (p, tris)
    }

    #[test]
    fn a_box_has_its_textbook_volume_centre_and_inertia() {
        let (lo, hi) = (Vec3::new(1.0, -2.0, 0.5), Vec3::new(1.4, 0.0, 1.5));
        let (p, tris) = cuboid(lo, hi);
        let m = SolidMass::of_surface(&p, &tris).unwrap();
        let size = hi - lo;
        let volume = size.x * size.y * size.z;
        assert!((m.volume - volume).abs() < 1e-5, "{}", m.volume);
        assert!((m.centroid - (lo + hi) * 0.5).length() < 1e-5);
        let expect = Vec3::new(
            size.y * size.y + size.z * size.z,
            size.x * size.x + size.z * size.z,
            size.x * size.x + size.y * size.y,
        ) * (volume / 12.0);
        let diag = Vec3::new(m.inertia.x_axis.x, m.inertia.y_axis.y, m.inertia.z_axis.z);
        assert!((diag - expect).length() < 1e-5, "{diag} vs {expect}");
        assert!(m.inertia.x_axis.y.abs() < 1e-6 && m.inertia.x_axis.z.abs() < 1e-6);
        assert!(m.inertia.y_axis.z.abs() < 1e-6);
    }

    #[test]
    fn inward_winding_gives_the_same_solid() {
        let (p, tris) = cuboid(Vec3::ZERO, Vec3::new(2.0, 1.0, 3.0));
        let flipped: Vec<u32> = tris.chunks(3).flat_map(|t| [t[0], t[2], t[1]]).collect();
        let out = SolidMass::of_surface(&p, &tris).unwrap();
        let inward = SolidMass::of_surface(&p, &flipped).unwrap();
        assert!((out.volume - inward.volume).abs() < 1e-6);
        assert!((out.inertia - inward.inertia).abs_diff_eq(Mat3::ZERO, 1e-6));
    }

    #[test]
    fn two_solids_add_up() {
        let (mut p, mut tris) = cuboid(Vec3::ZERO, Vec3::ONE);
        let (q, more) = cuboid(Vec3::new(3.0, 0.0, 0.0), Vec3::new(4.0, 1.0, 1.0));
        tris.extend(more.iter().map(|i| i + p.len() as u32));
        p.extend(q);
        let m = SolidMass::of_surface(&p, &tris).unwrap();
        assert!((m.volume - 2.0).abs() < 1e-5);
        assert!((m.centroid - Vec3::new(2.0, 0.5, 0.5)).length() < 1e-5);
        // Each unit cube: 1/6 about its centre, plus 1 · 1.5² about y and z.
        assert!((m.inertia.y_axis.y - (2.0 / 6.0 + 2.0 * 2.25)).abs() < 1e-4);
        assert!((m.inertia.x_axis.x - 2.0 / 6.0).abs() < 1e-5);
    }

    #[test]
    fn a_closed_surface_does_not_leak_and_an_open_one_does() {
        let (p, tris) = cuboid(Vec3::new(0.3, 0.0, -0.2), Vec3::new(0.7, 1.8, 0.2));
        assert!(SolidMass::of_surface(&p, &tris).unwrap().leak < 1e-6);
        let open = SolidMass::of_surface(&p, &tris[6..]).unwrap();
        assert!(open.leak > 0.1, "{}", open.leak);
    }

    #[test]
    fn a_surface_that_encloses_nothing_is_refused() {
        let flat = [Vec3::ZERO, Vec3::X, Vec3::Y];
        assert!(SolidMass::of_surface(&flat, &[0, 1, 2]).is_none());
        assert!(SolidMass::of_surface(&[], &[]).is_none());
        assert!(SolidMass::of_surface(&flat, &[0, 1, 7]).is_none());
    }
}
