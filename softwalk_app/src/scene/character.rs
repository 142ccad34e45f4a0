//! `[[characters]]`: who walks, where, and whether the balance controller runs.
//!
//! The body is the library's [`CharacterDesc`] (`[characters.body]`); the
//! walking speed follows from its Froude number. The path is turned into a
//! [`WalkPath`] here.

use std::collections::BTreeMap;
use std::path::Path;

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};
use softwalk_systems::character::{CharacterDesc, CharacterError, PathSegment, WalkPath};

use super::SceneError;
use super::character_clip::LoadedClip;
use super::character_model::default_model;
use super::check::{finite, identifier, in_range, on_terrain, positive};
use super::rig_cache::RigCache;

/// Default radius of the rounded corners of a waypoint path, metres.
pub const DEFAULT_CORNER_RADIUS: f32 = 0.75;
/// Sharpest accepted turn at a waypoint, degrees (a U-turn cannot be rounded).
pub const MAX_TURN_DEG: f32 = 170.0;
/// Most accepted waypoints on one path.
pub const MAX_WAYPOINTS: usize = 10_000;

/// The route a character follows, selected by `kind`. Headings are in degrees
/// from +X towards +Z.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum PathSpec {
    /// A straight line.
    Straight {
        /// Start point `[x, z]`, metres.
        start: [f32; 2],
        /// Heading in degrees (0 = +X, 90 = +Z).
        heading_deg: f32,
        /// Length, metres.
        length: f32,
    },
    /// Straight runs through at least two points `[x, z]`, corners rounded by circular arcs.
    Waypoints {
        /// The points in walking order.
        points: Vec<[f32; 2]>,
        /// Radius of the corner arcs, metres, in `(0, 100]`; shrunk where the runs are short.
        #[serde(default = "default_corner_radius")]
        corner_radius: f32,
    },
}

fn default_corner_radius() -> f32 {
    DEFAULT_CORNER_RADIUS
}

impl PathSpec {
    /// The path's corner points `[x, z]` (start and end for a straight path).
    pub fn polyline(&self) -> Vec<[f32; 2]> {
        match self {
            PathSpec::Straight {
                start,
                heading_deg,
                length,
            } => {
                let (s, c) = heading_deg.to_radians().sin_cos();
                vec![*start, [start[0] + c * length, start[1] + s * length]]
            }
            PathSpec::Waypoints { points, .. } => points.clone(),
        }
    }

    /// The library path: straight runs joined by tangent arcs, starting at ground
    /// level (the path ignores heights; characters stand on the ground under it).
    pub fn walk_path(&self) -> Result<WalkPath, CharacterError> {
        let points: Vec<Vec2> = self.polyline().iter().map(|p| Vec2::from(*p)).collect();
        let radius = match self {
            PathSpec::Straight { .. } => 0.0,
            PathSpec::Waypoints { corner_radius, .. } => *corner_radius,
        };
        let runs: Vec<Vec2> = points.windows(2).map(|w| w[1] - w[0]).collect();
        // Tangent length cut from each run at each interior corner, and the corner's arc.
        let mut cut = vec![[0.0f32; 2]; runs.len()];
        let mut arcs = vec![None; runs.len()];
        for k in 1..runs.len() {
            let (a, b) = (runs[k - 1], runs[k]);
            // Positive when turning from +X towards +Z, which is a right turn for the path.
            let turn = a.perp_dot(b).atan2(a.dot(b));
            if turn.abs() < 1e-4 || radius <= 0.0 {
                continue;
            }
            let half_tan = (turn.abs() * 0.5).tan();
            let tangent = (radius * half_tan)
                .min(0.5 * a.length())
                .min(0.5 * b.length());
            cut[k - 1][1] = tangent;
            cut[k][0] = tangent;
            arcs[k] = Some(PathSegment::Arc {
                radius: tangent / half_tan,
                angle: -turn,
            });
        }
        let mut segments = Vec::with_capacity(2 * runs.len());
        for (k, run) in runs.iter().enumerate() {
            if let Some(arc) = arcs[k] {
                segments.push(arc);
            }
            let length = run.length() - cut[k][0] - cut[k][1];
            if length > 1e-4 {
                segments.push(PathSegment::Straight { length });
            }
        }
        let start = points.first().copied().unwrap_or(Vec2::ZERO);
        let heading = runs.first().copied().unwrap_or(Vec2::ZERO);
        WalkPath::new(
            Vec3::new(start.x, 0.0, start.y),
            Vec3::new(heading.x, 0.0, heading.y),
            segments,
            false,
        )
    }

    fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        match self {
            PathSpec::Straight {
                heading_deg,
                length,
                ..
            } => {
                in_range(&format!("{field}.heading_deg"), *heading_deg, -360.0, 360.0)?;
                positive(&format!("{field}.length"), *length, 100_000.0)?;
            }
            PathSpec::Waypoints {
                points,
                corner_radius,
            } => {
                positive(&format!("{field}.corner_radius"), *corner_radius, 100.0)?;
                super::check::count_at_most(
                    &format!("{field}.points"),
                    points.len(),
                    MAX_WAYPOINTS,
                )?;
                if points.len() < 2 {
                    return Err(SceneError::invalid(
                        format!("{field}.points"),
                        format!("{} point(s); a path needs at least 2", points.len()),
                    ));
                }
            }
        }
        let points = self.polyline();
        for (k, p) in points.iter().enumerate() {
            let name = match self {
                PathSpec::Straight { .. } if k == 0 => format!("{field}.start"),
                PathSpec::Straight { .. } => format!("{field}.length"),
                PathSpec::Waypoints { .. } => format!("{field}.points[{k}]"),
            };
            finite(&format!("{name}[0]"), p[0])?;
            finite(&format!("{name}[1]"), p[1])?;
            on_terrain(&name, *p, size).map_err(|_| {
                SceneError::invalid(
                    &name,
                    format!(
                        "point [{}, {}] lies off the {} x {} m terrain",
                        p[0], p[1], size[0], size[1]
                    ),
                )
            })?;
        }
        for k in 1..points.len() {
            let run = Vec2::from(points[k]) - Vec2::from(points[k - 1]);
            if run.length() < 1e-3 {
                return Err(SceneError::invalid(
                    format!("{field}.points[{k}]"),
                    "repeats the previous point",
                ));
            }
            if k + 1 < points.len() {
                let next = Vec2::from(points[k + 1]) - Vec2::from(points[k]);
                let turn = run.perp_dot(next).atan2(run.dot(next)).to_degrees();
                if turn.abs() > MAX_TURN_DEG {
                    return Err(SceneError::invalid(
                        format!("{field}.points[{k}]"),
                        format!(
                            "turns by {:.0} degrees; at most {MAX_TURN_DEG} can be rounded",
                            turn.abs()
                        ),
                    ));
                }
            }
        }
        self.walk_path()
            .map(|_| ())
            .map_err(|e| SceneError::invalid(field, e.to_string()))
    }
}

/// One `[[characters]]` entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CharacterSpec {
    /// Unique name (letters, digits, `-`, `_`), used in metrics and the camera.
    pub name: String,
    /// Whether the balance controller (tilt and swing) runs; `Balance::enabled`.
    #[serde(default = "default_controller")]
    pub controller: bool,
    /// Body and gains: `height`, `mass`, optional `leg_length_factor`, `froude`
    /// (sets the speed), `alpha`, `beta`, `proxy_mass`.
    pub body: CharacterDesc,
    /// The route.
    pub path: PathSpec,
    /// What the character is drawn as: `"human"` (the built-in body, the
    /// default), `"mannequin"` (capsules, for debugging) or a `.glb`/`.gltf`
    /// file relative to the scene file.
    #[serde(default = "default_model")]
    pub model: String,
    /// Rig bone names by role key (`thigh_l = "LeftUpLeg"`), over the names
    /// the best-matching preset finds.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub bones: BTreeMap<String, String>,
    /// A `.bvh` walk clip relative to the scene file: the character walks
    /// with its cadence, stride (scaled by leg length) and duty factor, and
    /// a rigged character plays its upper body in step with the gait.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clip: Option<String>,
}

fn default_controller() -> bool {
    true
}

impl CharacterSpec {
    /// Checks the character, its model and clip loaded through `rigs`;
    /// `field` is its path (`characters[0]`).
    pub(crate) fn validate(
        &self,
        field: &str,
        size: [f32; 2],
        base_dir: &Path,
        rigs: &RigCache,
    ) -> Result<(), SceneError> {
        identifier(&format!("{field}.name"), &self.name)?;
        self.body.validate().map_err(|e| match e {
            CharacterError::InvalidField {
                field: name,
                reason,
            } => SceneError::invalid(format!("{field}.body.{name}"), reason),
            other => SceneError::invalid(format!("{field}.body"), other.to_string()),
        })?;
        self.path.validate(&format!("{field}.path"), size)?;
        rigs.character(field, self, base_dir)?;
        Ok(())
    }

    /// The body description the simulation builds: `body`, walking with the
    /// clip's gait when there is a clip.
    pub fn desc(&self, clip: Option<&LoadedClip>) -> CharacterDesc {
        CharacterDesc {
            clip_gait: clip.map(|c| c.gait),
            ..self.body
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn walker(path: PathSpec) -> CharacterSpec {
        CharacterSpec {
            name: "a".into(),
            controller: true,
            body: CharacterDesc::adult(),
            path,
            model: default_model(),
            bones: BTreeMap::new(),
            clip: None,
        }
    }

    #[test]
    fn straight_path_heads_along_its_angle() {
        let c = walker(PathSpec::Straight {
            start: [1.0, 1.0],
            heading_deg: 90.0,
            length: 3.0,
        });
        let end = c.path.polyline()[1];
        assert!((end[0] - 1.0).abs() < 1e-5 && (end[1] - 4.0).abs() < 1e-5);
        let path = c.path.walk_path().unwrap();
        assert!((path.point_at(3.0).position - Vec2::new(1.0, 4.0)).length() < 1e-5);
        c.validate(
            "characters[0]",
            [10.0, 10.0],
            Path::new(""),
            &RigCache::default(),
        )
        .unwrap();
        let e = c
            .validate(
                "characters[0]",
                [10.0, 3.0],
                Path::new(""),
                &RigCache::default(),
            )
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("characters[0].path.length: point"),
            "{e}"
        );
    }

    #[test]
    fn waypoint_corners_are_rounded_and_the_path_ends_at_the_last_point() {
        let spec = PathSpec::Waypoints {
            points: vec![[1.0, 1.0], [6.0, 1.0], [6.0, 6.0], [2.0, 7.0]],
            corner_radius: 1.0,
        };
        let path = spec.walk_path().unwrap();
        let end = path.point_at(path.length());
        assert!(
            (end.position - Vec2::new(2.0, 7.0)).length() < 1e-3,
            "{end:?}"
        );
        // Mid-run points lie on the polyline; the first corner is cut inside.
        assert!((path.point_at(2.0).position - Vec2::new(3.0, 1.0)).length() < 1e-4);
        let corner = path.point_at(5.0 - 1.0 + 0.25 * std::f32::consts::PI);
        assert!(
            corner.position.x < 6.0 && corner.position.y > 1.0,
            "{corner:?}"
        );
        assert!(path.length() < 5.0 + 5.0 + 17f32.sqrt());
        let e = walker(PathSpec::Waypoints {
            points: vec![[1.0, 1.0], [5.0, 1.0], [1.0, 1.01]],
            corner_radius: 1.0,
        })
        .validate(
            "characters[0]",
            [10.0, 10.0],
            Path::new(""),
            &RigCache::default(),
        )
        .unwrap_err();
        assert_eq!(e.field(), Some("characters[0].path.points[1]"));
    }

    #[test]
    fn body_errors_name_the_field() {
        let mut c = walker(PathSpec::Straight {
            start: [1.0, 1.0],
            heading_deg: 0.0,
            length: 3.0,
        });
        c.body.alpha = f32::NAN;
        let e = c
            .validate(
                "characters[1]",
                [10.0, 10.0],
                Path::new(""),
                &RigCache::default(),
            )
            .unwrap_err();
        assert_eq!(e.field(), Some("characters[1].body.alpha"));
    }
}
