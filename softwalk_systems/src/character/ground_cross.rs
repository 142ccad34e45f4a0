//! A patch of ground seen through a cross of vertical rays: its mean
//! height, the normal of its plane, and where a sole laid on it comes to
//! rest. One ray reads whatever lies under a point (a print's wall, a rim,
//! the edge between two materials); the cross reads the patch.

use glam::{Vec2, Vec3};

use crate::ground::GroundHit;

/// The ground over a patch: the mean of the heights found, the unit normal
/// of the plane it lies in, and the heights at the patch's centre where a
/// sole with that normal first touches the ground and where it stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GroundCross {
    /// Mean of the heights found, metres.
    pub mean: f32,
    /// Unit normal of the patch's plane (up where a pair of rays missed):
    /// along and across, the gentler of the slopes of its surfaces and of its
    /// floors (surface less give), level where they disagree. A sole pressed
    /// into the patch ends between the two. Across a deep print's edge in
    /// loose snow the surfaces slope by the print's depth but the floors (the
    /// firm ground under the layer) are level; across the edge between two
    /// grounds of different give the floors slope but the surface is level.
    /// Neither is a slope a sole rests on or a body walks up.
    pub normal: Vec3,
    /// Height at the centre of a plane with [`Self::normal`] lowered onto the
    /// patch until it touches the highest surface found, metres: where a
    /// sole landing half over a hole first meets the hole's edge.
    pub rest_top: f32,
    /// Height at the centre of the same plane pressed down until it meets
    /// the highest floor (surface less give) found, metres: a sole across
    /// two grounds, or across a print's edge, stops on the firmer floor.
    pub rest_floor: f32,
    /// The median floor (surface less give) of the centre and the four
    /// ends, metres: the height a planted foot would sink to on the patch.
    /// Each ray's own floor, so a ray in a print (its surface pressed down,
    /// its give used up) reads the same floor as one on fresh ground beside
    /// it; a median, so that one ray on a rim or on another ground beside
    /// the walker's line (the edge of a snowfield beside a path on sand)
    /// does not move it. On a plane it is the centre's floor.
    pub typical_floor: f32,
    /// What the ray at the patch's centre found.
    pub centre: Option<GroundHit>,
}

/// Where the rays between the centre and the two ends of a cross under a
/// sole are cast, as fractions of the reach along: close enough that a
/// print's rim (a ring about 3 cm wide) cannot pass between two of them.
pub(crate) const SOLE_RAYS: &[f32] = &[0.25, 0.5, 0.75];

/// One ray of the cross: its offset from the centre and what it found.
#[derive(Debug, Clone, Copy)]
struct Sample {
    offset: Vec2,
    height: f32,
    give: f32,
}

impl Sample {
    /// The firm floor under the sample: its surface less its give.
    fn floor(&self) -> f32 {
        self.height - self.give
    }
}

impl GroundCross {
    /// Casts `ground` at `at`, at `reach_along` ahead and behind it along
    /// the unit direction `forward` (and at the fractions `between` of that
    /// reach, ahead and behind: [`SOLE_RAYS`] under a sole, so that where it
    /// rests sees every rim under it), and at `reach_across` to either side;
    /// `None` when every ray misses. The mean and the slope are read from
    /// the centre and the four ends.
    pub fn sample(
        ground: impl Fn(Vec2) -> Option<GroundHit>,
        at: Vec2,
        forward: Vec2,
        [reach_along, reach_across]: [f32; 2],
        between: &[f32],
    ) -> Option<GroundCross> {
        let right = Vec2::new(-forward.y, forward.x);
        let centre = ground(at);
        let cast = |offset: Vec2| {
            let hit = if offset == Vec2::ZERO {
                centre
            } else {
                ground(at + offset)
            };
            hit.map(|h| Sample {
                offset,
                height: h.point.y,
                give: h.give.max(0.0),
            })
        };
        // The centre and the four ends: the mean, the floor and the slope.
        let ends = [
            Vec2::ZERO,
            forward * reach_along,
            -forward * reach_along,
            right * reach_across,
            -right * reach_across,
        ]
        .map(cast);
        let mut floors = [0.0f32; 5];
        let mut count = 0;
        for s in ends.iter().flatten() {
            floors[count] = s.floor();
            count += 1;
        }
        if count == 0 {
            return None;
        }
        let mean = ends.iter().flatten().map(|s| s.height).sum::<f32>() / count as f32;
        let floors = &mut floors[..count];
        floors.sort_by(f32::total_cmp);
        let typical_floor = floors[count / 2];
        let reach = [reach_along, reach_across];
        let surface_grades = grades(&ends, |s| s.height, reach);
        let floor_grades = grades(&ends, Sample::floor, reach);
        let [along, across] = [0, 1].map(|i| gentler(surface_grades[i], floor_grades[i]));
        let rise = forward * along + right * across;
        // The plane through the centre (or the mean) with the patch's slope;
        // each sample's surface and floor above it say how far the plane must
        // rise to rest on the patch and to stop on it.
        let base = centre.map_or(mean, |c| c.point.y);
        let between = between
            .iter()
            .flat_map(|f| [forward * (f * reach_along), -forward * (f * reach_along)])
            .filter_map(cast);
        let (top, floor) = ends.iter().flatten().copied().chain(between).fold(
            (f32::NEG_INFINITY, f32::NEG_INFINITY),
            |(top, floor), s| {
                let plane = base + rise.dot(s.offset);
                (top.max(s.height - plane), floor.max(s.floor() - plane))
            },
        );
        Some(GroundCross {
            mean,
            normal: Vec3::new(-rise.x, 1.0, -rise.y).normalize(),
            rest_top: base + top,
            rest_floor: base + floor,
            typical_floor,
            centre,
        })
    }
}

/// The grades along and across of the `height`s of the four ends of a
/// cross (ahead, behind, right, left, at `reach` along and across); 0 where
/// one of a line's two ends missed.
fn grades(
    ends: &[Option<Sample>; 5],
    height: impl Fn(&Sample) -> f32,
    [reach_along, reach_across]: [f32; 2],
) -> [f32; 2] {
    let grade = |ahead: usize, behind: usize, reach: f32| match (&ends[ahead], &ends[behind]) {
        (Some(a), Some(b)) if reach > 0.0 => (height(a) - height(b)) / (2.0 * reach),
        _ => 0.0,
    };
    [grade(1, 2, reach_along), grade(3, 4, reach_across)]
}

/// The gentler of two grades of the same line: the one nearer level when
/// they rise the same way, level when they do not.
fn gentler(a: f32, b: f32) -> f32 {
    if a * b <= 0.0 {
        0.0
    } else if a.abs() <= b.abs() {
        a
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hit at `p` of height `y` that gives `give`.
    fn hit(p: Vec2, y: f32, give: f32) -> Option<GroundHit> {
        Some(GroundHit {
            point: Vec3::new(p.x, y, p.y),
            normal: Vec3::Y,
            give,
        })
    }

    #[test]
    fn a_plane_is_read_exactly_and_a_pit_under_one_ray_is_averaged_out() {
        let height = |p: Vec2| 0.2 * p.x - 0.1 * p.y + 1.0;
        let plane = |p: Vec2| hit(p, height(p), 0.1);
        let c = GroundCross::sample(plane, Vec2::new(1.0, 2.0), Vec2::Y, [0.3, 0.2], &[]).unwrap();
        assert!((c.mean - height(Vec2::new(1.0, 2.0))).abs() < 1e-5);
        let centre = height(Vec2::new(1.0, 2.0));
        assert!(
            (c.rest_top - centre).abs() < 1e-5,
            "a plane rests on itself"
        );
        assert!((c.rest_floor - (centre - 0.1)).abs() < 1e-5, "on its floor");
        let expected = Vec3::new(-0.2, 1.0, 0.1).normalize();
        assert!(c.normal.distance(expected) < 1e-5, "{}", c.normal);
        let pit = |p: Vec2| hit(p, if p.length() < 0.01 { -0.5 } else { 0.0 }, 0.0);
        let c = GroundCross::sample(pit, Vec2::ZERO, Vec2::X, [0.3, 0.3], &[]).unwrap();
        assert!((c.mean + 0.1).abs() < 1e-6);
        assert_eq!(c.normal, Vec3::Y);
        assert_eq!(
            (c.rest_top, c.rest_floor),
            (0.0, 0.0),
            "a sole bridges the pit"
        );
        assert!(GroundCross::sample(|_| None, Vec2::ZERO, Vec2::X, [0.3, 0.3], &[]).is_none());
    }

    #[test]
    fn the_floor_is_each_rays_own_floor_so_a_print_under_one_ray_does_not_lower_it() {
        // Loose snow over a firm floor at -0.3: fresh surface at 0 giving
        // 0.3, and an old print ahead of the centre pressed to the floor
        // (giving nothing); the floor is -0.3 wherever the print is.
        let snow = |p: Vec2| {
            if (p.x - 0.3).abs() < 0.05 {
                hit(p, -0.3, 0.0)
            } else {
                hit(p, 0.0, 0.3)
            }
        };
        let c = GroundCross::sample(snow, Vec2::ZERO, Vec2::X, [0.3, 0.3], &[]).unwrap();
        assert!((c.typical_floor + 0.3).abs() < 1e-6, "{}", c.typical_floor);
        assert!(
            c.mean < -0.05,
            "the mean surface is in the print: {}",
            c.mean
        );
        // A rim under one ray (raised 4 cm, giving its print depth) and a
        // firmer ground under another beside the line do not move it either.
        let mixed = |p: Vec2| match (p.x > 0.2, p.y > 0.2) {
            (true, _) => hit(p, 0.04, 0.3),
            (_, true) => hit(p, 0.0, 0.05),
            _ => hit(p, 0.0, 0.3),
        };
        let c = GroundCross::sample(mixed, Vec2::ZERO, Vec2::X, [0.3, 0.3], &[]).unwrap();
        assert!((c.typical_floor + 0.3).abs() < 1e-6, "{}", c.typical_floor);
    }

    /// An old print ahead of x = -0.1, its surface at `print[0]` giving
    /// `print[1]`, and fresh ground behind it at 0 giving `fresh`.
    fn print_edge(print: [f32; 2], fresh: f32) -> impl Fn(Vec2) -> Option<GroundHit> {
        move |p| {
            if p.x > -0.1 {
                hit(p, print[0], print[1])
            } else {
                hit(p, 0.0, fresh)
            }
        }
    }

    #[test]
    fn a_sole_over_a_print_edge_lands_on_the_edge_and_stops_on_every_floor() {
        // An old print 5 cm deep (pressed firm, giving 1 cm) ahead of x = -0.1,
        // loose sand giving 4 cm behind it; the sole centre is over the print.
        // The surface falls 5 cm over the cross, the floors 2 cm.
        let c = GroundCross::sample(
            print_edge([-0.05, 0.01], 0.04),
            Vec2::ZERO,
            Vec2::X,
            [0.13, 0.05],
            &[],
        )
        .unwrap();
        let tilt = 0.02 / 0.26;
        let expected = Vec3::new(tilt, 1.0, 0.0).normalize();
        assert!(c.normal.distance(expected) < 1e-5, "{}", c.normal);
        // The sole tilts with the floors and its heel meets the sand at 0.
        let heel_rise = 0.13 * tilt;
        assert!((c.rest_top + heel_rise).abs() < 1e-6, "{}", c.rest_top);
        // Pressed down, it stops with its heel on the sand's floor and its
        // toe on the print's, neither through the sand's edge nor above
        // either floor.
        assert!((c.rest_floor + heel_rise - (-0.04)).abs() < 1e-6);
        assert!((c.rest_floor - heel_rise - (-0.06)).abs() < 1e-6);
    }

    #[test]
    fn neither_a_deep_print_nor_the_edge_of_a_softer_ground_tilts_the_patch() {
        // Snow 0.3 m deep over a firm floor: a print ahead of x = -0.1 pressed
        // to the floor (its surface 0.3 m down, giving nothing), fresh snow
        // behind. A sole there comes to rest level on the floor, not on the
        // print's wall.
        let print = print_edge([-0.3, 0.0], 0.3);
        let c = GroundCross::sample(print, Vec2::ZERO, Vec2::X, [0.13, 0.05], SOLE_RAYS).unwrap();
        assert_eq!(c.normal, Vec3::Y);
        assert_eq!((c.rest_top, c.rest_floor), (0.0, -0.3));
        // Level sand beside level snow: the floors differ, the ground is level.
        let edge = |p: Vec2| hit(p, 0.0, if p.y > 0.0 { 0.3 } else { 0.02 });
        let c = GroundCross::sample(edge, Vec2::ZERO, Vec2::X, [0.13, 0.13], &[]).unwrap();
        assert_eq!(c.normal, Vec3::Y);
        assert_eq!(gentler(0.2, 0.1), 0.1);
        assert_eq!(gentler(-0.2, -0.3), -0.2);
        assert_eq!(gentler(0.2, -0.1), 0.0);
    }

    #[test]
    fn a_sole_sees_a_narrow_rim_between_the_ends_of_its_cross() {
        // A rim 3 cm wide and 4 cm high, halfway between the centre and the heel.
        let rim = |p: Vec2| {
            hit(
                p,
                if (p.x + 0.065).abs() < 0.015 {
                    0.04
                } else {
                    0.0
                },
                0.05,
            )
        };
        let five = GroundCross::sample(rim, Vec2::ZERO, Vec2::X, [0.13, 0.05], &[]).unwrap();
        assert_eq!(five.rest_top, 0.0, "five rays miss it");
        let sole = GroundCross::sample(rim, Vec2::ZERO, Vec2::X, [0.13, 0.05], SOLE_RAYS).unwrap();
        assert_eq!(sole.rest_top, 0.04);
        assert!((sole.rest_floor - (0.04 - 0.05)).abs() < 1e-6);
        assert_eq!((sole.mean, sole.normal), (five.mean, five.normal));
    }
}
