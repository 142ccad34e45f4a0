//! `[render]`: frame size, cadence and outputs.

use serde::{Deserialize, Serialize};

use super::SceneError;
use super::check::count_in_range;

/// Largest accepted frame side, pixels.
pub const MAX_FRAME_SIDE: u32 = 8192;
/// Frame delays a GIF can store, milliseconds (`engine::output::GifWriter`
/// stores hundredths of a second in 16 bits).
pub const GIF_DELAY_MS: [u32; 2] = [10, 655_350];
/// Frame delays an APNG can store, milliseconds (`engine::output::ApngWriter`).
pub const APNG_DELAY_MS: [u32; 2] = [0, 65_535];

/// Time between two rendered frames, milliseconds, as the animation writers get it.
pub fn frame_delay_ms(dt: f64, every: u32) -> u64 {
    (dt * f64::from(every) * 1000.0).round() as u64
}

/// The `[render]` table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSettings {
    /// Frame width, pixels, in `[16, 8192]`.
    pub width: u32,
    /// Frame height, pixels, in `[16, 8192]`.
    pub height: u32,
    /// Render every k-th step, k in `[1, 100000]`.
    pub every: u32,
    /// Draw metric overlays (plots, labels) on frames.
    #[serde(default)]
    pub overlays: bool,
    /// Write an animated GIF of the frames.
    #[serde(default)]
    pub gif: bool,
    /// Write an animated PNG of the frames.
    #[serde(default)]
    pub apng: bool,
    /// Columns of the contact sheet of frames; 0 = no contact sheet.
    #[serde(default)]
    pub contact_sheet_columns: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 960,
            height: 540,
            every: 2,
            overlays: true,
            gif: false,
            apng: false,
            contact_sheet_columns: 0,
        }
    }
}

impl RenderSettings {
    pub(crate) fn validate(&self) -> Result<(), SceneError> {
        count_in_range("render.width", self.width, 16, MAX_FRAME_SIDE)?;
        count_in_range("render.height", self.height, 16, MAX_FRAME_SIDE)?;
        count_in_range("render.every", self.every, 1, 100_000)?;
        count_in_range(
            "render.contact_sheet_columns",
            self.contact_sheet_columns,
            0,
            64,
        )?;
        Ok(())
    }

    /// Checks that an animation the scene asks for can store the time between
    /// frames, `dt * every`; the error names `render.every`.
    pub(crate) fn validate_delay(&self, dt: f32) -> Result<(), SceneError> {
        let delay = frame_delay_ms(f64::from(dt), self.every);
        let formats = [
            (self.gif, "GIF", GIF_DELAY_MS),
            (self.apng, "APNG", APNG_DELAY_MS),
        ];
        for (on, format, [lo, hi]) in formats {
            if on && !(u64::from(lo)..=u64::from(hi)).contains(&delay) {
                return Err(SceneError::invalid(
                    "render.every",
                    format!(
                        "{} steps of sim.dt {dt} s are {delay} ms between frames; \
                         a {format} stores {lo} to {hi} ms (set render.every so that \
                         every * dt lies in that range, or turn render.{} off)",
                        self.every,
                        format.to_lowercase()
                    ),
                ));
            }
        }
        Ok(())
    }
}
