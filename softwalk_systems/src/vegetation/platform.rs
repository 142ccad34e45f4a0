//! The paper's virtual platform: the ground a walker *perceives* in vegetation.
//!
//! One state machine per foot. During the upward swing the platform rises
//! progressively under the foot (uplifting it); during the downward swing it
//! holds a fixed height (the top, `height_fraction` of the vegetation height);
//! when the foot reaches it, it falls fast or vanishes (per vegetation type),
//! so the foot drops suddenly onto the real ground.

use std::collections::VecDeque;

use glam::{Vec2, Vec3Swizzles};
use serde::{Deserialize, Serialize};

use super::error::{VegetationError, check};
use super::platform_ground::PlatformTop;
use crate::foot::{FootPhase, FootState, Side};

/// How many phase changes a platform remembers (for tests and plots).
pub const PHASE_LOG_LEN: usize = 64;

/// What a platform does once the foot reaches it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum PlatformDrop {
    /// Sinks to the real ground at `speed` (m/s).
    Fall {
        /// Sinking speed, m/s.
        speed: f32,
    },
    /// Disappears at once.
    Vanish,
}

/// Parameters of the virtual platforms of one vegetation type.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlatformSettings {
    /// Top height as a fraction of the vegetation height (the paper: 1/3).
    pub height_fraction: f32,
    /// Seconds the platform takes to rise from the ground to its top.
    pub rise_time: f32,
    /// What happens when the foot reaches it.
    pub drop: PlatformDrop,
    /// Half extent of the platform in X and Z (metres).
    pub half_size: Vec2,
    /// The foot "reaches" the platform when its sole is this close above the top (metres).
    pub contact_tolerance: f32,
}

impl Default for PlatformSettings {
    fn default() -> Self {
        Self {
            height_fraction: 1.0 / 3.0,
            rise_time: 0.2,
            drop: PlatformDrop::Fall { speed: 3.0 },
            half_size: Vec2::new(0.15, 0.2),
            contact_tolerance: 0.01,
        }
    }
}

impl PlatformSettings {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), VegetationError> {
        let positive = "must be finite and > 0";
        check(
            "platform.height_fraction",
            self.height_fraction,
            "must be finite and in (0, 1]",
            |v| v > 0.0 && v <= 1.0,
        )?;
        check("platform.rise_time", self.rise_time, positive, |v| v > 0.0)?;
        if let PlatformDrop::Fall { speed } = self.drop {
            check("platform.drop.speed", speed, positive, |v| v > 0.0)?;
        }
        check("platform.half_size.x", self.half_size.x, positive, |v| {
            v > 0.0
        })?;
        check("platform.half_size.y", self.half_size.y, positive, |v| {
            v > 0.0
        })?;
        check(
            "platform.contact_tolerance",
            self.contact_tolerance,
            "must be finite and >= 0",
            |v| v >= 0.0,
        )
    }
}

/// The phases of a platform, in the paper's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum PlatformPhase {
    /// No platform (foot in stance, or no vegetation).
    Idle,
    /// Upward swing: rising progressively under the foot.
    Rising,
    /// Downward swing: held at its top height.
    Holding,
    /// The foot reached it: sinking fast to the real ground.
    Falling,
}

/// One foot's virtual platform.
#[derive(Debug, Clone, PartialEq)]
pub struct VirtualPlatform {
    side: Side,
    phase: PlatformPhase,
    /// Height of the top above the real ground (metres).
    height: f32,
    centre: Vec2,
    ground_y: f32,
    log: VecDeque<PlatformPhase>,
}

impl VirtualPlatform {
    /// An idle platform for the foot on `side`.
    pub fn new(side: Side) -> Self {
        Self {
            side,
            phase: PlatformPhase::Idle,
            height: 0.0,
            centre: Vec2::ZERO,
            ground_y: 0.0,
            log: VecDeque::from([PlatformPhase::Idle]),
        }
    }

    /// Which foot this platform serves.
    pub fn side(&self) -> Side {
        self.side
    }

    /// The current phase.
    pub fn phase(&self) -> PlatformPhase {
        self.phase
    }

    /// Height of the top above the real ground (0 when idle).
    pub fn height(&self) -> f32 {
        self.height
    }

    /// Centre of the platform's top (world X, Z), where the foot was last seen above it.
    pub fn centre(&self) -> Vec2 {
        self.centre
    }

    /// The last phases entered, oldest first (at most [`PHASE_LOG_LEN`]),
    /// starting with the initial `Idle`.
    pub fn phase_log(&self) -> impl Iterator<Item = PlatformPhase> + '_ {
        self.log.iter().copied()
    }

    /// The platform as the foot ray sees it, or `None` when there is none.
    pub fn top(&self, settings: &PlatformSettings) -> Option<PlatformTop> {
        (self.phase != PlatformPhase::Idle && self.height > 0.0).then_some(PlatformTop {
            centre: self.centre,
            half_size: settings.half_size,
            top_y: self.ground_y + self.height,
        })
    }

    /// Advances the state machine by `dt` seconds.
    ///
    /// - `foot`: this step's foot state (phase and sole);
    /// - `ground_y`: the real ground height under the foot (from the foot ray);
    /// - `vegetation_height`: sensed under the foot (`GrassPatch::height_at`), 0 outside vegetation.
    pub fn update(
        &mut self,
        foot: &FootState,
        ground_y: f32,
        vegetation_height: f32,
        dt: f32,
        settings: &PlatformSettings,
    ) {
        let max_height = (vegetation_height * settings.height_fraction).max(0.0);
        let rise_rate = max_height / settings.rise_time;
        let sole_bottom = foot.sole.heel.y.min(foot.sole.toe.y);
        let reached = foot.pressing
            || foot.phase == FootPhase::Stance
            || sole_bottom <= ground_y + self.height + settings.contact_tolerance;
        let next = match self.phase {
            PlatformPhase::Idle if max_height > 0.0 && foot.phase == FootPhase::SwingUp => {
                self.height = 0.0;
                PlatformPhase::Rising
            }
            PlatformPhase::Rising | PlatformPhase::Holding if max_height <= 0.0 => {
                self.drop(settings)
            }
            PlatformPhase::Rising if foot.phase == FootPhase::SwingDown => PlatformPhase::Holding,
            PlatformPhase::Rising if foot.phase == FootPhase::Stance => self.drop(settings),
            PlatformPhase::Holding if reached => self.drop(settings),
            phase => phase,
        };
        self.enter(next);
        match self.phase {
            PlatformPhase::Idle => self.height = 0.0,
            PlatformPhase::Rising | PlatformPhase::Holding => {
                self.height = (self.height + rise_rate * dt).min(max_height);
                self.centre = foot.sole.center().xz();
                self.ground_y = ground_y;
            }
            PlatformPhase::Falling => {
                let speed = match settings.drop {
                    PlatformDrop::Fall { speed } => speed,
                    PlatformDrop::Vanish => f32::INFINITY,
                };
                self.height = (self.height - speed * dt).min(max_height);
                if self.height <= 0.0 {
                    self.height = 0.0;
                    self.enter(PlatformPhase::Idle);
                }
            }
        }
    }

    fn drop(&mut self, settings: &PlatformSettings) -> PlatformPhase {
        match settings.drop {
            PlatformDrop::Fall { .. } => PlatformPhase::Falling,
            PlatformDrop::Vanish => {
                self.height = 0.0;
                PlatformPhase::Idle
            }
        }
    }

    fn enter(&mut self, phase: PlatformPhase) {
        if phase != self.phase {
            self.phase = phase;
            if self.log.len() == PHASE_LOG_LEN {
                self.log.pop_front();
            }
            self.log.push_back(phase);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::foot::FootSole;
    use glam::Vec3;

    fn foot(phase: FootPhase, y: f32) -> FootState {
        FootState {
            side: Side::Left,
            sole: FootSole {
                heel: Vec3::new(0.0, y, -0.1),
                toe: Vec3::new(0.0, y, 0.1),
                width: 0.1,
            },
            ankle: Vec3::new(0.0, y + 0.08, -0.05),
            velocity: Vec3::ZERO,
            phase,
            contact: phase == FootPhase::Stance,
            pressing: phase == FootPhase::Stance,
        }
    }

    #[test]
    fn vanishing_platform_goes_straight_back_to_idle() {
        let settings = PlatformSettings {
            drop: PlatformDrop::Vanish,
            ..PlatformSettings::default()
        };
        let mut p = VirtualPlatform::new(Side::Left);
        for _ in 0..5 {
            p.update(&foot(FootPhase::SwingUp, 0.3), 0.0, 0.9, 0.05, &settings);
        }
        assert_eq!(p.phase(), PlatformPhase::Rising);
        assert!((p.height() - 0.3).abs() < 1e-6, "{}", p.height());
        p.update(&foot(FootPhase::SwingDown, 0.5), 0.0, 0.9, 0.05, &settings);
        assert_eq!(p.phase(), PlatformPhase::Holding);
        p.update(
            &foot(FootPhase::SwingDown, 0.305),
            0.0,
            0.9,
            0.05,
            &settings,
        );
        assert_eq!(p.phase(), PlatformPhase::Idle);
        assert!(p.top(&settings).is_none());
        let log: Vec<_> = p.phase_log().collect();
        use PlatformPhase::*;
        assert_eq!(log, [Idle, Rising, Holding, Idle]);
    }

    #[test]
    fn no_platform_without_vegetation() {
        let settings = PlatformSettings::default();
        let mut p = VirtualPlatform::new(Side::Right);
        for phase in [FootPhase::SwingUp, FootPhase::SwingDown, FootPhase::Stance] {
            p.update(&foot(phase, 0.2), 0.0, 0.0, 0.05, &settings);
            assert_eq!(p.phase(), PlatformPhase::Idle);
            assert!(p.top(&settings).is_none());
        }
    }

    #[test]
    fn bad_platform_settings_are_named() {
        let s = PlatformSettings {
            rise_time: 0.0,
            ..PlatformSettings::default()
        };
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .contains("platform.rise_time")
        );
        let s = PlatformSettings {
            drop: PlatformDrop::Fall { speed: -1.0 },
            ..PlatformSettings::default()
        };
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .contains("platform.drop.speed")
        );
    }
}
