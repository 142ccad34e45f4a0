//! The heads-up line: frame rate, costs, ground and body figures.

/// Weight of the newest sample in the running means.
const MEAN_WEIGHT: f64 = 0.1;

/// What the heads-up line shows this frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HudFigures {
    /// Material under the pelvis (`-` off the terrain).
    pub material: String,
    /// Forward tilt of the body, degrees.
    pub tilt_deg: f32,
    /// Lean into the turn, degrees (positive left).
    pub lean_deg: f32,
    /// Pelvis speed, m/s.
    pub speed_m_s: f32,
    /// The brush's material.
    pub brush: String,
    /// Paused.
    pub paused: bool,
    /// Frames are being recorded.
    pub recording: bool,
}

/// Running means of the frame rate and costs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Hud {
    frame_s: f64,
    step_ms: f64,
    draw_ms: f64,
}

fn blend(mean: &mut f64, sample: f64) {
    *mean = if *mean == 0.0 {
        sample
    } else {
        *mean + (sample - *mean) * MEAN_WEIGHT
    };
}

impl Hud {
    /// Records one frame: its wall time and its drawing cost, seconds.
    pub fn frame(&mut self, frame_s: f64, draw_s: f64) {
        blend(&mut self.frame_s, frame_s);
        blend(&mut self.draw_ms, 1000.0 * draw_s);
    }

    /// Records the cost of one simulation step, seconds.
    pub fn step(&mut self, step_s: f64) {
        blend(&mut self.step_ms, 1000.0 * step_s);
    }

    /// Frames per second (running mean).
    pub fn fps(&self) -> f64 {
        if self.frame_s > 0.0 {
            1.0 / self.frame_s
        } else {
            0.0
        }
    }

    /// Mean drawing time of a frame, ms.
    pub fn draw_ms(&self) -> f64 {
        self.draw_ms
    }

    /// Mean time of a simulation step, ms.
    pub fn step_ms(&self) -> f64 {
        self.step_ms
    }

    /// The line: fps, ms per step and per frame, then `figures`.
    pub fn line(&self, figures: &HudFigures) -> String {
        let mut line = format!(
            "{:.0} fps | step {:.2} ms | frame {:.1} ms | {} | tilt {:+.1}° lean {:+.1}° | {:.2} m/s | brush {}",
            self.fps(),
            self.step_ms,
            self.draw_ms,
            figures.material,
            figures.tilt_deg,
            figures.lean_deg,
            figures.speed_m_s,
            figures.brush,
        );
        if figures.paused {
            line.push_str(" | PAUSED");
        }
        if figures.recording {
            line.push_str(" | REC");
        }
        line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_shows_rates_and_figures() {
        let mut hud = Hud::default();
        hud.frame(1.0 / 50.0, 0.012);
        hud.step(40.0e-6);
        let figures = HudFigures {
            material: "snow".into(),
            tilt_deg: 2.04,
            lean_deg: -4.9,
            speed_m_s: 1.3,
            brush: "mud".into(),
            paused: true,
            recording: false,
        };
        assert_eq!(
            hud.line(&figures),
            "50 fps | step 0.04 ms | frame 12.0 ms | snow | tilt +2.0° lean -4.9° | 1.30 m/s | brush mud | PAUSED"
        );
        hud.frame(1.0 / 25.0, 0.012);
        assert!(hud.fps() < 50.0 && hud.fps() > 25.0);
    }
}
