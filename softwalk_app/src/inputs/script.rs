//! The input file: parsing, checking and writing [`InputScript`]s.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use thiserror::Error;

/// One thing asked of the steered character.
#[derive(Debug, Clone, PartialEq)]
pub enum InputAction {
    /// Desired planar velocity (x, z), m/s, before the speed factor.
    Velocity([f32; 2]),
    /// Factor on the desired velocity (1 walks, above 1 hurries).
    Speed(f32),
    /// Paint this material on the ground ahead of the character.
    Brush(String),
    /// Rebuild the scene from its start.
    Reset,
}

/// An action and the step (0-based) it applies before.
#[derive(Debug, Clone, PartialEq)]
pub struct InputEvent {
    /// The step the action applies before.
    pub step: u64,
    /// What is asked.
    pub action: InputAction,
}

/// A recorded session: the steered character and its events in step order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InputScript {
    /// Name of the steered character (`None`: the scene's first).
    pub character: Option<String>,
    /// The events, sorted by step (stable: same-step events keep their order).
    pub events: Vec<InputEvent>,
}

/// Why an input file could not be used.
#[derive(Debug, Error)]
pub enum InputError {
    /// The file could not be read.
    #[error("cannot read input file {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The file is not valid TOML of the input format.
    #[error("{path}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The parser's message, with the line.
        message: String,
    },
    /// An event is out of range or ambiguous.
    #[error("{path}: event[{index}]: {reason}")]
    Event {
        /// The file.
        path: PathBuf,
        /// Index of the event in the file.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// An event could not be applied to the running world.
    #[error("input {what}: {reason}")]
    Apply {
        /// The event's kind (and value).
        what: String,
        /// Why it failed.
        reason: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    character: Option<String>,
    #[serde(default)]
    event: Vec<EventToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EventToml {
    step: u64,
    velocity: Option<[f32; 2]>,
    speed: Option<f32>,
    brush: Option<String>,
    reset: Option<bool>,
}

/// Largest accepted desired speed, m/s.
const MAX_SPEED_M_S: f32 = 5.0;
/// Accepted range of the speed factor.
const SPEED_FACTOR: (f32, f32) = (0.1, 3.0);

impl EventToml {
    fn action(self) -> Result<(u64, InputAction), String> {
        let mut actions = Vec::new();
        if let Some(v) = self.velocity {
            let ok = v.iter().all(|c| c.is_finite()) && v[0].hypot(v[1]) <= MAX_SPEED_M_S;
            if !ok {
                return Err(format!(
                    "velocity {v:?} must be finite and at most {MAX_SPEED_M_S} m/s"
                ));
            }
            actions.push(InputAction::Velocity(v));
        }
        if let Some(s) = self.speed {
            if !(SPEED_FACTOR.0..=SPEED_FACTOR.1).contains(&s) {
                return Err(format!(
                    "speed {s} is not in [{}, {}]",
                    SPEED_FACTOR.0, SPEED_FACTOR.1
                ));
            }
            actions.push(InputAction::Speed(s));
        }
        if let Some(m) = self.brush {
            actions.push(InputAction::Brush(m));
        }
        match self.reset {
            Some(true) => actions.push(InputAction::Reset),
            Some(false) => return Err("reset = false asks for nothing; leave it out".into()),
            None => {}
        }
        match actions.len() {
            1 => Ok((self.step, actions.remove(0))),
            0 => Err("needs one of velocity, speed, brush or reset".into()),
            _ => Err("has more than one of velocity, speed, brush and reset".into()),
        }
    }
}

impl InputScript {
    /// Reads and checks an input file.
    pub fn load(path: &Path) -> Result<Self, InputError> {
        let text = std::fs::read_to_string(path).map_err(|source| InputError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// Parses and checks input-file text; `path` names it in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let file: FileToml = toml::from_str(text).map_err(|e| InputError::Syntax {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().replace('\n', " "),
        })?;
        let mut events = Vec::with_capacity(file.event.len());
        for (index, e) in file.event.into_iter().enumerate() {
            let (step, action) = e.action().map_err(|reason| InputError::Event {
                path: path.to_path_buf(),
                index,
                reason,
            })?;
            events.push(InputEvent { step, action });
        }
        events.sort_by_key(|e| e.step);
        Ok(InputScript {
            character: file.character,
            events,
        })
    }

    /// The events that apply before `step`.
    pub fn at(&self, step: u64) -> impl Iterator<Item = &InputEvent> {
        let from = self.events.partition_point(|e| e.step < step);
        self.events[from..]
            .iter()
            .take_while(move |e| e.step == step)
    }

    /// The script as input-file TOML (what [`InputScript::parse`] reads back).
    pub fn to_toml(&self) -> String {
        let mut out = String::from("# softwalk input recording: step numbers and events\n");
        if let Some(name) = &self.character {
            out.push_str(&format!("character = {}\n", quoted(name)));
        }
        for e in &self.events {
            out.push_str(&format!("\n[[event]]\nstep = {}\n", e.step));
            out.push_str(&match &e.action {
                InputAction::Velocity([x, z]) => format!("velocity = [{x:?}, {z:?}]\n"),
                InputAction::Speed(s) => format!("speed = {s:?}\n"),
                InputAction::Brush(m) => format!("brush = {}\n", quoted(m)),
                InputAction::Reset => "reset = true\n".into(),
            });
        }
        out
    }
}

/// A TOML basic string.
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = r#"
character = "walker"
[[event]]
step = 30
brush = "snow"
[[event]]
step = 0
velocity = [0.0, 1.2]
[[event]]
step = 30
speed = 1.5
[[event]]
step = 90
reset = true
"#;

    #[test]
    fn events_are_sorted_by_step_and_round_trip() {
        let s = InputScript::parse(FILE, Path::new("in.toml")).unwrap();
        assert_eq!(s.events[0].action, InputAction::Velocity([0.0, 1.2]));
        let at30: Vec<_> = s.at(30).map(|e| e.action.clone()).collect();
        assert_eq!(
            at30,
            vec![InputAction::Brush("snow".into()), InputAction::Speed(1.5)]
        );
        assert_eq!(s.at(31).count(), 0);
        let back = InputScript::parse(&s.to_toml(), Path::new("out.toml")).unwrap();
        assert_eq!(back, s);
    }

    #[test]
    fn bad_events_name_the_file_and_event() {
        let two = "[[event]]\nstep = 1\nspeed = 1.0\nreset = true\n";
        let e = InputScript::parse(two, Path::new("in.toml")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "in.toml: event[0]: has more than one of velocity, speed, brush and reset"
        );
        let fast = "[[event]]\nstep = 1\nvelocity = [9.0, 0.0]\n";
        let e = InputScript::parse(fast, Path::new("in.toml")).unwrap_err();
        assert!(e.to_string().contains("at most 5 m/s"), "{e}");
        let unknown = "[[event]]\nstep = 1\njump = true\n";
        let e = InputScript::parse(unknown, Path::new("in.toml")).unwrap_err();
        assert!(e.to_string().starts_with("in.toml: "), "{e}");
        assert!(e.to_string().contains("line 3"), "{e}");
    }
}
