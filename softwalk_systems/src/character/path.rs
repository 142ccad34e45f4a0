//! The path a character walks: straight runs, circular arcs and turns on
//! the spot, optionally looped, walked facing forward or backward.

use glam::{Vec2, Vec3};

use super::error::CharacterError;

/// One piece of a [`WalkPath`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PathSegment {
    /// A straight run of this length (m).
    Straight {
        /// Length in metres (> 0).
        length: f32,
    },
    /// A circular arc; positive `angle` turns left (seen from above), negative right.
    Arc {
        /// Radius in metres (> 0).
        radius: f32,
        /// Turn angle in radians (non-zero).
        angle: f32,
    },
    /// A turn on the spot: the heading turns by `angle` (positive left)
    /// while the position stays; the walk steps around it, one metre of
    /// distance for every `1 / reach` radians turned.
    Pivot {
        /// Distance walked per radian turned, metres (> 0): sets how far
        /// each step turns.
        reach: f32,
        /// Turn angle in radians (non-zero).
        angle: f32,
    },
}

impl PathSegment {
    fn length(&self) -> f32 {
        match *self {
            PathSegment::Straight { length } => length,
            PathSegment::Arc { radius, angle } => radius * angle.abs(),
            PathSegment::Pivot { reach, angle } => reach * angle.abs(),
        }
    }

    fn is_valid(&self) -> bool {
        match *self {
            PathSegment::Straight { length } => length.is_finite() && length > 0.0,
            PathSegment::Arc {
                radius: size,
                angle,
            }
            | PathSegment::Pivot { reach: size, angle } => {
                size.is_finite() && size > 0.0 && angle.is_finite() && angle != 0.0
            }
        }
    }
}

/// A point on the path: position on the XZ plane and unit heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// Position (x, z).
    pub position: Vec2,
    /// Unit facing direction (x, z): the walking direction, or (on a path
    /// walked backward) turned away from it.
    pub heading: Vec2,
    /// Unit direction of travel (x, z): the heading, except on a path
    /// walked backward.
    pub travel: Vec2,
}

impl PathPoint {
    /// The heading as a horizontal 3D vector.
    pub fn heading3(&self) -> Vec3 {
        Vec3::new(self.heading.x, 0.0, self.heading.y)
    }

    /// The character's right, horizontal: heading × up.
    pub fn right3(&self) -> Vec3 {
        self.heading3().cross(Vec3::Y)
    }
}

/// A walk path on the ground plane, parametrised by distance walked.
///
/// Distances are counted from the path's `origin` (0 unless set with
/// [`WalkPath::with_origin`]), so a path generated mid-walk can continue the
/// distance its walker has already covered. Before its start the path extends straight backwards; after its end it
/// stays at the end point, unless `looped`, when the distance wraps around
/// (a looped path should end where it starts, heading the same way).
///
/// A path [walked backward](WalkPath::walked_backward) is laid out from its
/// start along the opposite of the facing direction; its points face against
/// the direction of travel. One [stepped back](WalkPath::stepped_back) aslant
/// is laid out along a travel direction up to [`MAX_BACKWARD_ASLANT`] off
/// straight behind, and its points face that much turned from the opposite
/// of the travel, so the walker keeps facing where it faced.
#[derive(Debug, Clone, PartialEq)]
pub struct WalkPath {
    segments: Vec<PathSegment>,
    starts: Vec<PathPoint>,
    start_distance: Vec<f32>,
    length: f32,
    looped: bool,
    origin: f32,
    backward: bool,
    /// On a path walked backward: the facing's turn from the opposite of
    /// the travel, as `(cos, sin)` of the angle (positive left); `None`
    /// for straight behind.
    aslant: Option<Vec2>,
}

/// The largest angle between the travel of a path stepped back and straight
/// behind the walker, radians (35°): further aslant, a foot lifting off
/// drags its sole sideways through the wall of its own print on loose ground.
pub const MAX_BACKWARD_ASLANT: f32 = 0.61;
/// A travel within this of straight behind (radians) is straight behind.
const STRAIGHT_BEHIND: f32 = 1.0e-6;

impl WalkPath {
    /// A path from `start` (its y is ignored) heading along `direction` (horizontal part used).
    pub fn new(
        start: Vec3,
        direction: Vec3,
        segments: Vec<PathSegment>,
        looped: bool,
    ) -> Result<Self, CharacterError> {
        let bad = |field, reason: String| Err(CharacterError::InvalidPath { field, reason });
        if !start.is_finite() {
            return bad("start", format!("{start} is not finite"));
        }
        let Some(heading) = Vec2::new(direction.x, direction.z).try_normalize() else {
            return bad(
                "direction",
                format!("{direction} has no finite horizontal part"),
            );
        };
        if segments.is_empty() {
            return bad("segments", "a path needs at least one segment".into());
        }
        let mut here = PathPoint {
            position: Vec2::new(start.x, start.z),
            heading,
            travel: heading,
        };
        let mut starts = Vec::with_capacity(segments.len());
        let mut start_distance = Vec::with_capacity(segments.len());
        let mut length = 0.0;
        for seg in &segments {
            if !seg.is_valid() {
                return bad("segments", format!("{seg:?} needs finite positive sizes"));
            }
            starts.push(here);
            start_distance.push(length);
            here = advance(here, seg, seg.length());
            length += seg.length();
        }
        Ok(WalkPath {
            segments,
            starts,
            start_distance,
            length,
            looped,
            origin: 0.0,
            backward: false,
            aslant: None,
        })
    }

    /// A path from `start` (y ignored) walked backward by a walker facing
    /// `facing` (horizontal part used): `segments` are laid out towards
    /// `-facing`, and every point faces against the direction of travel.
    pub fn walked_backward(
        start: Vec3,
        facing: Vec3,
        segments: Vec<PathSegment>,
    ) -> Result<Self, CharacterError> {
        let mut path = Self::new(start, -facing, segments, false)?;
        path.backward = true;
        Ok(path)
    }

    /// A path from `start` (y ignored) stepped back by a walker facing
    /// `facing` towards `travel` (horizontal parts used): `segments` are laid
    /// out along `travel` turned to within [`MAX_BACKWARD_ASLANT`] of
    /// `-facing`, and every point keeps the walker's facing relative to its
    /// travel. Straight behind it is [`WalkPath::walked_backward`].
    pub fn stepped_back(
        start: Vec3,
        facing: Vec3,
        travel: Vec3,
        segments: Vec<PathSegment>,
    ) -> Result<Self, CharacterError> {
        let flat = |v: Vec3| Vec2::new(v.x, v.z).try_normalize();
        let (Some(face), Some(go)) = (flat(facing), flat(travel)) else {
            return Self::walked_backward(start, facing, segments);
        };
        let behind = -face;
        let left = Vec2::new(behind.y, -behind.x);
        let angle = turn_angle(behind, go);
        if angle.abs() < STRAIGHT_BEHIND {
            return Self::walked_backward(start, facing, segments);
        }
        let angle = angle.clamp(-MAX_BACKWARD_ASLANT, MAX_BACKWARD_ASLANT);
        let (s, c) = angle.sin_cos();
        let along = behind * c + left * s;
        let mut path = Self::new(start, Vec3::new(along.x, 0.0, along.y), segments, false)?;
        path.backward = true;
        path.aslant = Some(Vec2::new(c, -s));
        Ok(path)
    }

    /// True when the walker faces against the direction of travel.
    pub fn is_backward(&self) -> bool {
        self.backward
    }

    /// This path with its start at distance `origin` (a finite number): a
    /// walker that has covered `origin` metres stands at its start.
    pub fn with_origin(mut self, origin: f32) -> Self {
        if origin.is_finite() {
            self.origin = origin;
        }
        self
    }

    /// The distance at the path's start, metres.
    pub fn origin(&self) -> f32 {
        self.origin
    }

    /// The distance at the path's end: its origin plus its length, metres.
    pub fn end_distance(&self) -> f32 {
        self.origin + self.length
    }

    /// A straight path of `length` metres from `start` along `direction`.
    pub fn straight(start: Vec3, direction: Vec3, length: f32) -> Result<Self, CharacterError> {
        Self::new(
            start,
            direction,
            vec![PathSegment::Straight { length }],
            false,
        )
    }

    /// A looped circle of `radius` through `start`, heading along `direction`, turning left.
    pub fn circle(start: Vec3, direction: Vec3, radius: f32) -> Result<Self, CharacterError> {
        let arc = PathSegment::Arc {
            radius,
            angle: std::f32::consts::TAU,
        };
        Self::new(start, direction, vec![arc], true)
    }

    /// Total length in metres (from the origin to the end).
    pub fn length(&self) -> f32 {
        self.length
    }

    /// Whether the distance wraps around at the end.
    pub fn is_looped(&self) -> bool {
        self.looped
    }

    /// True when `distance` has reached the end of a path that does not loop.
    pub fn is_finished(&self, distance: f32) -> bool {
        !self.looped && distance >= self.end_distance()
    }

    /// Position and facing after walking `distance` metres.
    pub fn point_at(&self, distance: f32) -> PathPoint {
        let p = self.travel_point_at(distance);
        if !self.backward {
            return p;
        }
        let heading = match self.aslant {
            None => -p.heading,
            Some(turn) => turn_by(-p.heading, turn),
        };
        PathPoint {
            position: p.position,
            heading,
            travel: p.heading,
        }
    }

    /// Position and direction of travel after walking `distance` metres.
    fn travel_point_at(&self, distance: f32) -> PathPoint {
        let distance = distance - self.origin;
        let s = if self.looped {
            distance.rem_euclid(self.length)
        } else {
            distance.min(self.length)
        };
        if s < 0.0 {
            let p = self.starts[0];
            return PathPoint {
                position: p.position + p.heading * s,
                ..p
            };
        }
        let k = self.start_distance.partition_point(|&d| d <= s).max(1) - 1;
        advance(
            self.starts[k],
            &self.segments[k],
            s - self.start_distance[k],
        )
    }
}

/// Walks `along` metres on `seg` from `from`.
fn advance(from: PathPoint, seg: &PathSegment, along: f32) -> PathPoint {
    match *seg {
        PathSegment::Straight { .. } => PathPoint {
            position: from.position + from.heading * along,
            ..from
        },
        PathSegment::Arc { radius, angle } => {
            // Left of heading (x, z) seen from above with Y up is (z, -x).
            let left = Vec2::new(from.heading.y, -from.heading.x) * angle.signum();
            let turn = along / radius;
            let (s, c) = turn.sin_cos();
            let heading = (from.heading * c + left * s).normalize();
            PathPoint {
                position: from.position + (from.heading * s + left * (1.0 - c)) * radius,
                heading,
                travel: heading,
            }
        }
        PathSegment::Pivot { reach, angle } => {
            let turn = along / reach * angle.signum();
            let left = Vec2::new(from.heading.y, -from.heading.x);
            let (s, c) = turn.sin_cos();
            let heading = (from.heading * c + left * s).normalize();
            PathPoint {
                position: from.position,
                heading,
                travel: heading,
            }
        }
    }
}

/// The signed angle from `heading` to `direction`, radians, positive to the left.
pub fn turn_angle(heading: Vec2, direction: Vec2) -> f32 {
    let left = Vec2::new(heading.y, -heading.x);
    direction.dot(left).atan2(direction.dot(heading))
}

/// `v` (x, z) turned by the angle whose `(cos, sin)` is `turn`, positive left.
fn turn_by(v: Vec2, turn: Vec2) -> Vec2 {
    let left = Vec2::new(v.y, -v.x);
    v * turn.x + left * turn.y
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_path_clamps_and_extends_backwards() {
        let p = WalkPath::straight(Vec3::ZERO, Vec3::Z, 4.0).unwrap();
        assert_eq!(p.point_at(2.0).position, Vec2::new(0.0, 2.0));
        assert_eq!(p.point_at(9.0).position, Vec2::new(0.0, 4.0));
        assert_eq!(p.point_at(-1.0).position, Vec2::new(0.0, -1.0));
        assert!(p.is_finished(4.0) && !p.is_finished(3.9));
    }

    #[test]
    fn left_arc_turns_towards_the_left() {
        // Facing +Z with Y up, the character's left is +X.
        let quarter = PathSegment::Arc {
            radius: 2.0,
            angle: std::f32::consts::FRAC_PI_2,
        };
        let p = WalkPath::new(Vec3::ZERO, Vec3::Z, vec![quarter], false).unwrap();
        let end = p.point_at(p.length());
        assert!((end.position - Vec2::new(2.0, 2.0)).length() < 1e-4);
        assert!((end.heading - Vec2::X).length() < 1e-4);
        assert!((p.point_at(0.0).right3() - Vec3::NEG_X).length() < 1e-6);
    }

    #[test]
    fn pivot_turns_in_place_and_origin_shifts_distances() {
        let half = PathSegment::Pivot {
            reach: 0.5,
            angle: std::f32::consts::PI,
        };
        let p = WalkPath::new(Vec3::ZERO, Vec3::Z, vec![half], false)
            .unwrap()
            .with_origin(10.0);
        assert_eq!(p.end_distance(), 10.0 + 0.5 * std::f32::consts::PI);
        let mid = p.point_at(10.0 + 0.25 * std::f32::consts::PI);
        assert_eq!(mid.position, Vec2::ZERO);
        assert!((mid.heading - Vec2::X).length() < 1e-5, "{:?}", mid.heading);
        assert!((p.point_at(20.0).heading - Vec2::NEG_Y).length() < 1e-5);
        assert!(!p.is_finished(11.0) && p.is_finished(12.0));
    }

    #[test]
    fn a_path_walked_backward_moves_against_its_facing() {
        let run = PathSegment::Straight { length: 2.0 };
        let p = WalkPath::walked_backward(Vec3::ZERO, Vec3::Z, vec![run]).unwrap();
        assert!(p.is_backward());
        let end = p.point_at(1.5);
        assert_eq!(end.position, Vec2::new(0.0, -1.5));
        assert_eq!(end.heading, Vec2::Y);
        assert!(
            !WalkPath::straight(Vec3::ZERO, Vec3::Z, 1.0)
                .unwrap()
                .is_backward()
        );
    }

    #[test]
    fn a_path_stepped_back_aslant_keeps_the_facing_within_its_bound() {
        let run = || vec![PathSegment::Straight { length: 2.0 }];
        let behind = Vec3::new(0.0, 0.0, -1.0);
        let straight = WalkPath::stepped_back(Vec3::ZERO, Vec3::Z, behind, run()).unwrap();
        let plain = WalkPath::walked_backward(Vec3::ZERO, Vec3::Z, run()).unwrap();
        assert_eq!(straight, plain, "straight behind is walked backward");
        // 30° off straight behind, to the walker's left (+x).
        let (sin, cos) = 30f32.to_radians().sin_cos();
        let aslant = Vec3::new(sin, 0.0, -cos);
        let p = WalkPath::stepped_back(Vec3::ZERO, Vec3::Z, aslant, run()).unwrap();
        let end = p.point_at(1.0);
        assert!((end.position - Vec2::new(sin, -cos)).length() < 1e-6);
        assert!((end.heading - Vec2::Y).length() < 1e-6, "{end:?}");
        assert!((end.travel - Vec2::new(sin, -cos)).length() < 1e-6);
        // Straight to the side: stepped back at the bound.
        let p = WalkPath::stepped_back(Vec3::ZERO, Vec3::Z, Vec3::NEG_X, run()).unwrap();
        let (sin, cos) = MAX_BACKWARD_ASLANT.sin_cos();
        let end = p.point_at(1.0);
        assert!((end.position - Vec2::new(-sin, -cos)).length() < 1e-6);
        assert!((end.heading - Vec2::Y).length() < 1e-6);
    }

    #[test]
    fn circle_loops_back_to_its_start() {
        let p = WalkPath::circle(Vec3::new(1.0, 0.0, 0.0), Vec3::Z, 3.0).unwrap();
        let a = p.point_at(0.5);
        let b = p.point_at(0.5 + p.length());
        assert!((a.position - b.position).length() < 1e-3);
    }

    #[test]
    fn bad_paths_are_refused_by_field() {
        let e = WalkPath::straight(Vec3::ZERO, Vec3::Y, 1.0).unwrap_err();
        assert!(matches!(
            e,
            CharacterError::InvalidPath {
                field: "direction",
                ..
            }
        ));
        let e = WalkPath::straight(Vec3::ZERO, Vec3::Z, f32::NAN).unwrap_err();
        assert!(matches!(
            e,
            CharacterError::InvalidPath {
                field: "segments",
                ..
            }
        ));
    }
}
