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
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
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
