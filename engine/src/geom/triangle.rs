use std::ops::{Add, Div, Mul, Sub};

use glam::{Vec3A, Vec4};

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
/// Bit-identical to [`ray_triangle`] on the same triangle, and to lane `k` of
/// [`TriPacket::nearest`] on a packet holding it in lane `k`.
#[inline]
pub(crate) fn ray_triangle_edges(
    origin: Vec3A,
    dir: Vec3A,
    [a, e1, e2]: [Vec3A; 3],
    max_t: f32,
) -> Option<f32> {
    let (dir, e1, e2): (Xyz<f32>, Xyz<f32>, Xyz<f32>) = (dir.into(), e1.into(), e2.into());
    let p = dir.cross(e2);
    let det = e1.dot(p);
    // Rejects a zero, infinite or NaN determinant (NaN fails both comparisons).
    let size = det.abs();
    if !(size > 0.0 && size < f32::INFINITY) {
        return None;
    }
    let inv = 1.0 / det;
    let s = Xyz::<f32>::from(origin) - a.into();
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

/// Number types the Möller–Trumbore arithmetic runs on: `f32` for one
/// triangle, [`Vec4`] for four at once (one per lane, IEEE operations lane by
/// lane, never fused), so both give the same bits.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
}

impl Lanes for f32 {}
impl Lanes for Vec4 {}

/// A 3D vector of [`Lanes`], component by component: the cross and dot
/// products are written out once, in one operation order, for every lane type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Xyz<T> {
    pub(crate) x: T,
    pub(crate) y: T,
    pub(crate) z: T,
}

impl<T: Lanes> Xyz<T> {
    #[inline(always)]
    fn cross(self, r: Xyz<T>) -> Xyz<T> {
        Xyz {
            x: self.y * r.z - r.y * self.z,
            y: self.z * r.x - r.z * self.x,
            z: self.x * r.y - r.x * self.y,
        }
    }

    #[inline(always)]
    fn dot(self, r: Xyz<T>) -> T {
        self.x * r.x + self.y * r.y + self.z * r.z
    }
}

impl<T: Lanes> Sub for Xyz<T> {
    type Output = Xyz<T>;
    #[inline(always)]
    fn sub(self, r: Xyz<T>) -> Xyz<T> {
        Xyz {
            x: self.x - r.x,
            y: self.y - r.y,
            z: self.z - r.z,
        }
    }
}

impl From<Vec3A> for Xyz<f32> {
    #[inline(always)]
    fn from(v: Vec3A) -> Xyz<f32> {
        Xyz {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

impl From<Vec3A> for Xyz<Vec4> {
    /// Each component splatted over the four lanes.
    #[inline(always)]
    fn from(v: Vec3A) -> Xyz<Vec4> {
        Xyz {
            x: Vec4::splat(v.x),
            y: Vec4::splat(v.y),
            z: Vec4::splat(v.z),
        }
    }
}

impl Xyz<Vec4> {
    /// Lane `k` as a vector.
    #[inline]
    fn lane(&self, k: usize) -> Vec3A {
        Vec3A::new(self.x[k], self.y[k], self.z[k])
    }
}

/// Lanes per [`TriPacket`].
pub(crate) const PACKET: usize = 4;

/// Up to four triangles in structure-of-arrays form (lane `k` is triangle
/// `k`), each as its first corner and two edges, intersected with one ray at
/// once by 4-lane vector arithmetic. Unused lanes hold a degenerate triangle,
/// which no ray hits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriPacket {
    a: Xyz<Vec4>,
    e1: Xyz<Vec4>,
    e2: Xyz<Vec4>,
}

impl TriPacket {
    /// A packet of `triangles` (at most [`PACKET`]), each as `[a, b - a, c - a]`.
    pub(crate) fn new(triangles: &[[Vec3A; 3]]) -> TriPacket {
        debug_assert!(triangles.len() <= PACKET);
        let mut lanes = [[Vec3A::ZERO; 3]; PACKET];
        lanes[..triangles.len()].copy_from_slice(triangles);
        let column = |c: usize| Xyz {
            x: Vec4::from_array(lanes.map(|t| t[c].x)),
            y: Vec4::from_array(lanes.map(|t| t[c].y)),
            z: Vec4::from_array(lanes.map(|t| t[c].z)),
        };
        TriPacket {
            a: column(0),
            e1: column(1),
            e2: column(2),
        }
    }

    /// Triangle `lane` as `[a, b - a, c - a]`.
    pub(crate) fn triangle(&self, lane: usize) -> [Vec3A; 3] {
        [self.a.lane(lane), self.e1.lane(lane), self.e2.lane(lane)]
    }

    /// The nearest of the four triangles hit by the ray within `max_t`, as
    /// `(t, lane)` (the lowest lane among equally near ones). The ray's origin
    /// and direction come splatted over the lanes. Each lane gives exactly
    /// [`ray_triangle_edges`]'s answer for its triangle. (The traversal uses
    /// [`TriPacket::closest`]; this is its answer as an option, for tests.)
    #[cfg(test)]
    pub(crate) fn nearest(
        &self,
        origin: &Xyz<Vec4>,
        dir: &Xyz<Vec4>,
        max_t: f32,
    ) -> Option<(f32, usize)> {
        let (t, lane) = self.closest(origin, dir, max_t);
        (!t.is_nan()).then_some((t, lane))
    }

    /// The nearest hit lane, like `TriPacket::nearest`, without a branch: `t` is NaN when no lane is hit
    /// (and `lane` is then [`PACKET`]), so that a caller keeping the better
    /// of two answers can select rather than branch on an unpredictable hit.
    #[inline(always)]
    pub(crate) fn closest(&self, origin: &Xyz<Vec4>, dir: &Xyz<Vec4>, max_t: f32) -> (f32, usize) {
        let p = dir.cross(self.e2);
        let det = self.e1.dot(p);
        let size = det.abs();
        let inv = Vec4::ONE / det;
        let s = *origin - self.a;
        let u = s.dot(p) * inv;
        let q = s.cross(self.e1);
        let v = dir.dot(q) * inv;
        let t = self.e2.dot(q) * inv;
        let slack = Vec4::splat(EDGE_SLACK);
        let hit = size.cmpgt(Vec4::ZERO)
            & size.cmplt(Vec4::INFINITY)
            & u.cmpge(-slack)
            & u.cmple(Vec4::ONE + slack)
            & !v.cmplt(-slack)
            & !(u + v).cmpgt(Vec4::ONE + slack)
            & t.cmpge(Vec4::ZERO)
            & t.cmple(Vec4::splat(max_t));
        // The nearest hit lane (the lowest among equally near ones).
        let hit_t = Vec4::select(hit, t, Vec4::INFINITY);
        let nearest = hit_t.min_element();
        let lanes = (hit & hit_t.cmpeq(Vec4::splat(nearest))).bitmask();
        let lane = (lanes | 1 << PACKET).trailing_zeros();
        // No hit: `nearest` is infinite, and setting its quiet-NaN bit (the
        // lane is PACKET exactly then) makes it NaN.
        let missed = (lane >> PACKET.trailing_zeros()) * QUIET_NAN_BIT;
        (f32::from_bits(nearest.to_bits() | missed), lane as usize)
    }
}

/// The bit that makes an infinite `f32` a quiet NaN.
const QUIET_NAN_BIT: u32 = 1 << 22;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

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

    #[test]
    fn packet_lanes_match_the_scalar_test_bit_for_bit() {
        let mut rng = SplitMix64::new(7);
        let point = |rng: &mut SplitMix64| {
            Vec3A::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        };
        let (mut hits, mut rays) = (0, 0);
        for round in 0..3000 {
            // Random triangles, plus an edge-on one, a degenerate one and a
            // triangle sharing an edge with the first (rays through it).
            let count = 1 + round % PACKET;
            let mut tris: Vec<[Vec3A; 3]> = (0..count)
                .map(|_| {
                    let a = point(&mut rng);
                    [a, point(&mut rng) - a, point(&mut rng) - a]
                })
                .collect();
            if round % 5 == 0 {
                tris[0] = [Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0];
            }
            let packet = TriPacket::new(&tris);
            for k in 0..4 {
                let o = point(&mut rng) * 3.0;
                let d = match k {
                    0 => point(&mut rng),
                    1 => Vec3A::NEG_Y,
                    // Towards the shared corner or edge midpoint of lane 0.
                    2 => tris[0][0] - o,
                    _ => tris[0][0] + 0.5 * tris[0][1] - o,
                };
                let max_t = if k == 3 { 2.5 } else { f32::INFINITY };
                let scalar: Vec<Option<f32>> = tris
                    .iter()
                    .map(|&t| ray_triangle_edges(o, d, t, max_t))
                    .collect();
                let want = scalar
                    .iter()
                    .enumerate()
                    .filter_map(|(lane, t)| t.map(|t| (t, lane)))
                    .fold(None, |b: Option<(f32, usize)>, (t, lane)| {
                        if b.is_none_or(|(bt, _)| t < bt) {
                            Some((t, lane))
                        } else {
                            b
                        }
                    });
                let got = packet.nearest(&Xyz::from(o), &Xyz::from(d), max_t);
                assert_eq!(
                    got.map(|(t, lane)| (t.to_bits(), lane)),
                    want.map(|(t, lane)| (t.to_bits(), lane)),
                    "round {round}, ray {k}"
                );
                // Each lane alone, too (a packet of one).
                for (lane, &t) in scalar.iter().enumerate() {
                    let alone = TriPacket::new(&tris[lane..=lane]);
                    let got = alone.nearest(&Xyz::from(o), &Xyz::from(d), max_t);
                    assert_eq!(got.map(|(t, _)| t.to_bits()), t.map(f32::to_bits));
                    assert_eq!(packet.triangle(lane), tris[lane]);
                }
                rays += 1;
                hits += usize::from(want.is_some());
            }
        }
        assert!(hits > rays / 10, "only {hits} of {rays} rays hit");
    }
}
