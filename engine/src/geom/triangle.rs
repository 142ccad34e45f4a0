use glam::Vec3A;

/// Barycentric slack on triangle edges: a ray through a shared edge is caught
/// by at least one of the two triangles, despite rounding.
const EDGE_SLACK: f32 = 1e-6;

/// Two-sided ray/triangle intersection (Möller–Trumbore).
///
/// Returns the distance `t` in `0..=max_t` (in units of `dir`), or `None`.
/// Edges and corners count as inside (with a tiny slack), so watertight
/// neighbours never let a ray slip between them.
#[inline]
pub fn ray_triangle(origin: Vec3A, dir: Vec3A, [a, b, c]: [Vec3A; 3], max_t: f32) -> Option<f32> {
    ray_triangle_edges(origin, dir, [a, b - a, c - a], max_t)
}

/// [`ray_triangle`] for a triangle given as its first corner and the edges
/// to the other two (`[a, b - a, c - a]`), so a BVH can store them prepared.
/// Bit-identical to [`ray_triangle`] on the same triangle.
#[inline]
pub(crate) fn ray_triangle_edges(
    origin: Vec3A,
    dir: Vec3A,
    [a, e1, e2]: [Vec3A; 3],
    max_t: f32,
) -> Option<f32> {
    let p = dir.cross(e2);
    let det = e1.dot(p);
    // Rejects a zero, infinite or NaN determinant (NaN fails both comparisons).
    let size = det.abs();
    if !(size > 0.0 && size < f32::INFINITY) {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t >= 0.0 && t <= max_t).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_inside_and_on_edges_misses_outside() {
        let tri = [Vec3A::ZERO, Vec3A::X, Vec3A::Z];
        let down = Vec3A::NEG_Y;
        assert_eq!(
            ray_triangle(Vec3A::new(0.2, 1.0, 0.2), down, tri, 9.0),
            Some(1.0)
        );
        assert_eq!(
            ray_triangle(Vec3A::new(0.5, 1.0, 0.5), down, tri, 9.0),
            Some(1.0)
        );
        assert_eq!(
            ray_triangle(Vec3A::new(0.0, 1.0, 0.0), down, tri, 9.0),
            Some(1.0)
        );
        assert_eq!(
            ray_triangle(Vec3A::new(0.6, 1.0, 0.6), down, tri, 9.0),
            None
        );
        assert_eq!(
            ray_triangle(Vec3A::new(0.2, 1.0, 0.2), down, tri, 0.5),
            None
        );
        assert_eq!(
            ray_triangle(Vec3A::new(0.2, -1.0, 0.2), -down, tri, 9.0),
            Some(1.0)
        );
    }
}
