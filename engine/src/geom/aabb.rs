use glam::Vec3;

use super::Ray;

/// An axis-aligned bounding box. An empty box has `min > max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lowest corner.
    pub min: Vec3,
    /// Highest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box: the neutral element of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// A box from its corners.
    pub fn new(min: Vec3, max: Vec3) -> Aabb {
        Aabb { min, max }
    }

    /// The smallest box holding every point (empty for no points).
    pub fn from_points(points: &[Vec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| b.grown_to(p))
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The box grown to hold `p`.
    pub fn grown_to(&self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The box grown by `pad` on every side.
    pub fn padded(&self, pad: f32) -> Aabb {
        Aabb {
            min: self.min - Vec3::splat(pad),
            max: self.max + Vec3::splat(pad),
        }
    }

    /// True when `p` lies inside or on the boundary.
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The distances `(t_enter, t_exit)` over which the ray is inside the box,
    /// clipped to `0..=max_t`, or `None` when it misses.
    ///
    /// Boundaries count as inside, and a direction component that is exactly
    /// zero is handled without dividing (a ray lying in a face plane hits).
    pub fn ray_interval(&self, ray: &Ray, max_t: f32) -> Option<(f32, f32)> {
        let (o, d) = (ray.origin().to_array(), ray.dir().to_array());
        let (lo, hi) = (self.min.to_array(), self.max.to_array());
        let mut t0 = 0.0f32;
        let mut t1 = max_t;
        for k in 0..3 {
            let (a, b) = slab(o[k], d[k], lo[k], hi[k])?;
            t0 = t0.max(a);
            t1 = t1.min(b);
        }
        (t0 <= t1).then_some((t0, t1))
    }
}

/// The parameter interval over which `o + d * t` lies in `[lo, hi]`, or `None`.
/// A zero `d` gives the whole line when `o` is inside.
#[inline]
pub(crate) fn slab(o: f32, d: f32, lo: f32, hi: f32) -> Option<(f32, f32)> {
    if d == 0.0 {
        return (o >= lo && o <= hi).then_some((f32::NEG_INFINITY, f32::INFINITY));
    }
    let a = (lo - o) / d;
    let b = (hi - o) / d;
    Some((a.min(b), a.max(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_test_handles_faces_and_zero_directions() {
        let b = Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]);
        let down_on_face = Ray::new(Vec3::new(1.0, 5.0, 0.5), Vec3::NEG_Y).unwrap();
        assert_eq!(b.ray_interval(&down_on_face, 100.0), Some((4.0, 5.0)));
        let outside = Ray::new(Vec3::new(1.01, 5.0, 0.5), Vec3::NEG_Y).unwrap();
        assert_eq!(b.ray_interval(&outside, 100.0), None);
        assert_eq!(b.ray_interval(&down_on_face, 3.0), None);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.union(&b), b);
    }
}
