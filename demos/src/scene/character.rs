//! `[[characters]]`: who walks, where and how fast.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::{finite, identifier, in_range, on_terrain, positive};

/// Standard gravity, m/s^2, used to turn a Froude number into a speed.
pub const GRAVITY: f32 = 9.81;

/// Body proportions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Morphology {
    /// Standing height, metres, in `[0.5, 2.5]` (paper: 1 to 1.9 m).
    pub height: f32,
    /// Body mass, kg, in `(0, 300]`.
    pub mass: f32,
    /// Leg length (hip to sole) as a fraction of the height, in `[0.35, 0.65]`.
    pub leg_factor: f32,
}

impl Morphology {
    /// Leg length, metres.
    pub fn leg_length(&self) -> f32 {
        self.height * self.leg_factor
    }
}

/// The route a character follows, selected by `kind`.
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
    /// A polyline through at least two points `[x, z]`.
    Waypoints {
        /// The points in walking order.
        points: Vec<[f32; 2]>,
    },
}

impl PathSpec {
    /// The path as a polyline of `[x, z]` points.
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
            PathSpec::Waypoints { points } => points.clone(),
        }
    }

    /// Total length of the path, metres.
    pub fn length(&self) -> f32 {
        self.polyline()
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum()
    }

    fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        if let PathSpec::Straight {
            heading_deg,
            length,
            ..
        } = self
        {
            in_range(&format!("{field}.heading_deg"), *heading_deg, -360.0, 360.0)?;
            positive(&format!("{field}.length"), *length, 100_000.0)?;
        }
        let points = self.polyline();
        if points.len() < 2 {
            return Err(SceneError::invalid(
                format!("{field}.points"),
                format!("{} point(s); a path needs at least 2", points.len()),
            ));
        }
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
        if self.length() <= 0.0 {
            return Err(SceneError::invalid(field, "the path has zero length"));
        }
        Ok(())
    }
}

/// Walking speed, either in m/s or as a Froude number `v^2 / (g L)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum SpeedSpec {
    /// Metres per second, in `(0, 5]`.
    Mps(f32),
    /// Froude number, in `(0, 1]` (0.25 is a comfortable walk).
    Froude(f32),
}

/// One `[[characters]]` entry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CharacterSpec {
    /// Unique name (letters, digits, `-`, `_`), used in metrics and the camera.
    pub name: String,
    /// Body proportions.
    pub morphology: Morphology,
    /// Walking speed (`speed = { mps = 1.2 }` or `speed = { froude = 0.25 }`).
    pub speed: SpeedSpec,
    /// PD gain alpha on the centre-of-mass error (paper: 30), in `[0, 1000]`.
    #[serde(default = "default_alpha")]
    pub alpha: f32,
    /// PD gain beta on the angular velocity (paper: 6), in `[0, 1000]`.
    #[serde(default = "default_beta")]
    pub beta: f32,
    /// Whether the balance controller (tilt and swing) runs.
    #[serde(default = "default_controller")]
    pub controller: bool,
    /// The route.
    pub path: PathSpec,
}

fn default_alpha() -> f32 {
    30.0
}
fn default_beta() -> f32 {
    6.0
}
fn default_controller() -> bool {
    true
}

impl CharacterSpec {
    /// Walking speed in m/s (a Froude number is converted with the leg length).
    pub fn speed_mps(&self) -> f32 {
        match self.speed {
            SpeedSpec::Mps(v) => v,
            SpeedSpec::Froude(fr) => (fr * GRAVITY * self.morphology.leg_length()).sqrt(),
        }
    }

    /// Checks the character; `field` is its path (`characters[0]`).
    pub(crate) fn validate(&self, field: &str, size: [f32; 2]) -> Result<(), SceneError> {
        identifier(&format!("{field}.name"), &self.name)?;
        let m = &self.morphology;
        in_range(&format!("{field}.morphology.height"), m.height, 0.5, 2.5)?;
        positive(&format!("{field}.morphology.mass"), m.mass, 300.0)?;
        in_range(
            &format!("{field}.morphology.leg_factor"),
            m.leg_factor,
            0.35,
            0.65,
        )?;
        match self.speed {
            SpeedSpec::Mps(v) => positive(&format!("{field}.speed.mps"), v, 5.0)?,
            SpeedSpec::Froude(fr) => positive(&format!("{field}.speed.froude"), fr, 1.0)?,
        };
        in_range(&format!("{field}.alpha"), self.alpha, 0.0, 1000.0)?;
        in_range(&format!("{field}.beta"), self.beta, 0.0, 1000.0)?;
        self.path.validate(&format!("{field}.path"), size)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn froude_speed_uses_leg_length() {
        let c = CharacterSpec {
            name: "a".into(),
            morphology: Morphology {
                height: 1.0,
                mass: 30.0,
                leg_factor: 0.49,
            },
            speed: SpeedSpec::Froude(0.25),
            alpha: 30.0,
            beta: 6.0,
            controller: true,
            path: PathSpec::Straight {
                start: [1.0, 1.0],
                heading_deg: 90.0,
                length: 3.0,
            },
        };
        assert!((c.speed_mps() - 1.096).abs() < 0.01);
        let end = c.path.polyline()[1];
        assert!((end[0] - 1.0).abs() < 1e-5 && (end[1] - 4.0).abs() < 1e-5);
        c.validate("characters[0]", [10.0, 10.0]).unwrap();
        let e = c.validate("characters[0]", [10.0, 3.0]).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("characters[0].path.length: point"),
            "{e}"
        );
    }
}
