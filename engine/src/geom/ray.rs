use glam::Vec3;

use super::GeomError;

/// A half-line with a finite origin and a unit direction.
///
/// Built only through [`Ray::new`], which refuses NaN, infinite or zero input,
/// so every query can trust that the ray is well formed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    origin: Vec3,
    dir: Vec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (normalised here).
    ///
    /// ```
    /// use engine::geom::Ray;
    /// use engine::glam::Vec3;
    /// let r = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, -3.0, 0.0)).unwrap();
    /// assert_eq!(r.dir(), Vec3::NEG_Y);
    /// assert!(Ray::new(Vec3::ZERO, Vec3::ZERO).is_err());
    /// ```
    pub fn new(origin: Vec3, dir: Vec3) -> Result<Ray, GeomError> {
        if !origin.is_finite() {
            return Err(GeomError::InvalidParameter {
                name: "origin",
                reason: format!("{origin} is not finite"),
            });
        }
        if !dir.is_finite() {
            return Err(GeomError::InvalidParameter {
                name: "dir",
                reason: format!("{dir} is not finite"),
            });
        }
        // Scale by the largest component first, so that a tiny direction does
        // not underflow to zero length.
        let largest = dir.abs().max_element();
        match (largest > 0.0)
            .then(|| (dir / largest).try_normalize())
            .flatten()
        {
            Some(dir) => Ok(Ray { origin, dir }),
            None => Err(GeomError::InvalidParameter {
                name: "dir",
                reason: format!("{dir} has no usable length"),
            }),
        }
    }

    /// A ray pointing straight down (-Y) from `(x, from_y, z)`.
    pub fn down(x: f32, from_y: f32, z: f32) -> Result<Ray, GeomError> {
        Ray::new(Vec3::new(x, from_y, z), Vec3::NEG_Y)
    }

    /// The start point.
    #[inline]
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The unit direction.
    #[inline]
    pub fn dir(&self) -> Vec3 {
        self.dir
    }

    /// The point at distance `t` along the ray.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Identifies a mesh added to a [`crate::geom::RayScene`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MeshId(pub u32);

/// What a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HitTarget {
    /// Cell `(i, j)` of a height grid (the cell spanning samples `i..=i+1`, `j..=j+1`).
    Grid {
        /// Cell column.
        i: usize,
        /// Cell row.
        j: usize,
    },
    /// Triangle `triangle` of mesh `mesh` (an index into its `TriMesh::triangles`).
    Mesh {
        /// The mesh.
        mesh: MeshId,
        /// The triangle index inside that mesh.
        triangle: u32,
    },
}

/// The closest intersection of a ray with a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// World position of the hit.
    pub point: Vec3,
    /// Unit geometric normal of the surface hit: up-facing for height grids,
    /// the counter-clockwise front side for mesh triangles.
    pub normal: Vec3,
    /// Distance from the ray origin (the ray direction is unit length).
    pub distance: f32,
    /// The grid cell or mesh triangle hit.
    pub target: HitTarget,
}

/// True for a distance limit a query can honour: zero, positive or infinite (not NaN).
#[inline]
pub(crate) fn usable_max_t(max_t: f32) -> bool {
    max_t >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_non_finite_and_zero_input() {
        let ok = Vec3::new(1.0, 2.0, 3.0);
        for bad in [
            Vec3::NAN,
            Vec3::INFINITY,
            Vec3::new(0.0, f32::NEG_INFINITY, 0.0),
        ] {
            assert!(matches!(
                Ray::new(bad, ok),
                Err(GeomError::InvalidParameter { name: "origin", .. })
            ));
            assert!(matches!(
                Ray::new(ok, bad),
                Err(GeomError::InvalidParameter { name: "dir", .. })
            ));
        }
        assert!(Ray::new(ok, Vec3::ZERO).is_err());
        // A tiny but usable direction is normalised, not refused.
        assert_eq!(
            Ray::new(ok, Vec3::new(0.0, 1e-30, 0.0)).unwrap().dir(),
            Vec3::Y
        );
        let r = Ray::new(ok, Vec3::new(0.0, 0.0, -2.0)).unwrap();
        assert_eq!(r.at(1.5), Vec3::new(1.0, 2.0, 1.5));
        assert!(!usable_max_t(f32::NAN) && !usable_max_t(-1.0) && usable_max_t(f32::INFINITY));
    }
}
