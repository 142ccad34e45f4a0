//! Where a sun shadow map lies: a grid across the sun's rays over the casters
//! whose shadows the camera may see (the view frustum's footprint between the
//! ground and the highest caster), its texel taken from a fixed ladder of
//! sizes and its corner snapped to whole texels, so that shadows stay put
//! while the camera follows a walker.

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::camera::Camera;

/// Finest texel width, in metres.
const MIN_TEXEL: f32 = 0.015;
/// Least ratio of a texel's height (along the rows) to its width: the sine
/// of an elevation of about 12 degrees (a lower sun stretches texels on
/// the ground rather than multiplying rows).
const MIN_SQUASH: f32 = 0.2;
/// Most texels per side.
const MAX_SIDE: usize = 1024;
/// Texels kept around the casters on each side: a lookup beside a caster
/// reads its neighbours.
const MARGIN: f32 = 2.0;
/// Texel sizes per doubling: the ladder of sizes the texel is rounded up to.
const TEXEL_STEPS_PER_OCTAVE: f32 = 4.0;

/// The grid of a shadow map: light coordinates and size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MapFrame {
    /// World point to light coordinates: texel column and row (continuous,
    /// texel `(i, j)` spans `[i, i + 1) x [j, j + 1)`) and height towards
    /// the sun, in metres.
    pub to_light: Mat4,
    /// Texel width (along the columns), in metres; rows are shorter, by
    /// the sine of the sun's elevation.
    pub texel: f32,
    /// Columns.
    pub cols: usize,
    /// Rows.
    pub rows: usize,
}

impl MapFrame {
    /// The grid for casters made of triangles `casters` (a blade gives
    /// three points along it) under a sun in direction `toward_sun` (unit,
    /// above the horizon), covering only the casters whose shadows may fall
    /// inside `camera`'s view onto ground no lower than `ground_low` (the
    /// casters' lowest point when `None`). `None` when there are no casters
    /// or no such shadow.
    pub fn fit(
        casters: impl Iterator<Item = [Vec3; 3]> + Clone,
        toward_sun: Vec3,
        camera: &Camera,
        ground_low: Option<f32>,
    ) -> Option<MapFrame> {
        let right = toward_sun.cross(Vec3::Y).try_normalize().unwrap_or(Vec3::X);
        let up = right.cross(toward_sun);
        let across = |p: Vec3| Vec2::new(p.dot(right), p.dot(up));
        let (mut y_lo, mut y_hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for p in casters.clone().flatten() {
            y_lo = y_lo.min(p.y);
            y_hi = y_hi.max(p.y);
        }
        let y_lo = ground_low.map_or(y_lo, |g| g.min(y_lo));
        let seen = view_footprint(camera, y_lo, y_hi, across)?;
        let mut covered = Bounds::EMPTY;
        for caster in casters {
            let mut own = Bounds::EMPTY;
            caster.into_iter().for_each(|p| own.add(across(p)));
            if let Some(part) = own.intersect(&seen) {
                covered.add(part.lo);
                covered.add(part.hi);
            }
        }
        let covered = covered.non_empty()?;
        // Rows are shorter than columns are wide, so that a texel covers a
        // square of level ground: a row across the rays stretches over
        // `1 / sin(elevation)` of ground.
        let squash = toward_sun.y.max(MIN_SQUASH);
        let extent = covered.hi - covered.lo;
        let needed = extent.x.max(extent.y / squash) / MAX_SIDE as f32;
        let texel = ladder_texel(needed.max(MIN_TEXEL));
        let size = Vec2::new(texel, texel * squash);
        // Whole texels from the light-space origin, a margin of MARGIN.
        let margin = Vec2::splat(MARGIN);
        let corner = (covered.lo / size).floor() - margin;
        let span =
            ((covered.hi / size).ceil() + margin - corner).min(Vec2::splat((MAX_SIDE + 5) as f32));
        let to_light = Mat4::from_cols(
            (right / size.x).extend(-corner.x),
            (up / size.y).extend(-corner.y),
            toward_sun.extend(0.0),
            Vec4::W,
        )
        .transpose();
        Some(MapFrame {
            to_light,
            texel,
            cols: span.x as usize,
            rows: span.y as usize,
        })
    }
}

/// The smallest size of the ladder `MIN_TEXEL * 2^(k / TEXEL_STEPS_PER_OCTAVE)`
/// at least `needed` (which is at least `MIN_TEXEL`).
fn ladder_texel(needed: f32) -> f32 {
    let steps = (TEXEL_STEPS_PER_OCTAVE * (needed / MIN_TEXEL).log2()).ceil();
    let texel = MIN_TEXEL * (steps / TEXEL_STEPS_PER_OCTAVE).exp2();
    // Rounding may leave the rung a hair short.
    texel.max(needed)
}

/// A 2D axis-aligned box; empty while `lo > hi`.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    lo: Vec2,
    hi: Vec2,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        lo: Vec2::INFINITY,
        hi: Vec2::NEG_INFINITY,
    };

    fn add(&mut self, p: Vec2) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    /// The common part of two boxes, `None` when they do not meet (or one
    /// holds a NaN).
    fn intersect(&self, other: &Bounds) -> Option<Bounds> {
        Bounds {
            lo: self.lo.max(other.lo),
            hi: self.hi.min(other.hi),
        }
        .non_empty()
    }

    /// The bounds, unless they are empty (or not numbers).
    fn non_empty(self) -> Option<Bounds> {
        (self.lo.x <= self.hi.x && self.lo.y <= self.hi.y).then_some(self)
    }
}

/// The bounds, seen through `across`, of the part of `camera`'s frustum
/// between heights `y_lo` and `y_hi`: its corners inside that slab and the
/// points where its edges cross the slab's planes. `None` when the frustum
/// misses the slab.
fn view_footprint(
    camera: &Camera,
    y_lo: f32,
    y_hi: f32,
    across: impl Fn(Vec3) -> Vec2,
) -> Option<Bounds> {
    let to_world = camera.clip_to_world();
    let corner = |sx: f32, sy: f32, w: f32| to_world.transform_point3(Vec3::new(sx * w, sy * w, w));
    let ring =
        |w: f32| [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| corner(x, y, w));
    let (near, far) = (ring(camera.near), ring(camera.far));
    let mut seen = Bounds::EMPTY;
    for p in near.iter().chain(&far) {
        if (y_lo..=y_hi).contains(&p.y) {
            seen.add(across(*p));
        }
    }
    let edges = (0..4).flat_map(|k| {
        let next = (k + 1) % 4;
        [
            (near[k], near[next]),
            (far[k], far[next]),
            (near[k], far[k]),
        ]
    });
    for (a, b) in edges {
        for y in [y_lo, y_hi] {
            if (a.y - y) * (b.y - y) < 0.0 {
                seen.add(across(a.lerp(b, (y - a.y) / (b.y - a.y))));
            }
        }
    }
    seen.non_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::perspective(1.0, 64, 48, 0.05, 50.0)
            .unwrap()
            .look_at(Vec3::new(0.0, 3.0, -4.0), Vec3::ZERO, Vec3::Y)
    }

    #[test]
    fn texels_climb_a_fixed_ladder() {
        assert_eq!(ladder_texel(MIN_TEXEL), MIN_TEXEL);
        let t = ladder_texel(0.03);
        assert!((0.03..0.03 * 1.19).contains(&t), "{t}");
        // Nearby needs share a rung, so small changes of the view keep it.
        assert_eq!(ladder_texel(0.0301), ladder_texel(0.0302));
    }

    #[test]
    fn the_map_covers_only_casters_whose_shadows_the_camera_may_see() {
        let sun = Vec3::new(0.0, 1.0, 1.0).normalize();
        // A post in view and one 300 m to the side.
        let post = |x: f32| {
            [[
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x, 2.0, 0.0),
                Vec3::new(x, 1.0, 0.0),
            ]]
        };
        let near = MapFrame::fit(post(0.0).into_iter(), sun, &camera(), Some(0.0)).unwrap();
        let both = post(0.0).into_iter().chain(post(300.0));
        let fitted = MapFrame::fit(both, sun, &camera(), Some(0.0)).unwrap();
        assert_eq!(fitted, near);
        assert_eq!(fitted.texel, MIN_TEXEL);
        let top = Vec3::new(0.0, 2.0, 0.0);
        let a = near.to_light.transform_point3(top);
        assert!(a.x >= 0.0 && a.x < near.cols as f32 && a.y >= 0.0 && a.y < near.rows as f32);
        assert!((a.z - top.dot(sun)).abs() < 1e-6);
        // A second post a little aside moves the map's corner by whole
        // texels only: the first post keeps its place within its texel.
        let wider = post(0.0).into_iter().chain(post(0.137));
        let moved = MapFrame::fit(wider, sun, &camera(), Some(0.0)).unwrap();
        let b = moved.to_light.transform_point3(top);
        assert_ne!(a.x, b.x);
        let shift = a - b;
        assert!(
            (shift - shift.round()).abs().max_element() < 1e-3,
            "{shift}"
        );
        // Posts wholly behind the camera cast nothing it sees.
        let behind = post(0.0).map(|t| t.map(|p| p - Vec3::Z * 30.0));
        assert_eq!(
            MapFrame::fit(behind.into_iter(), Vec3::Y, &camera(), Some(0.0)),
            None
        );
        assert_eq!(
            MapFrame::fit(std::iter::empty(), sun, &camera(), None),
            None
        );
    }
}
