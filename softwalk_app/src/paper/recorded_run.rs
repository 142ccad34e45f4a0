//! A headless run of a scene through [`crate::runner::run`] (the same path as
//! `softwalk run --no-render`) that keeps every character's metrics per step.

use softwalk_systems::sim::WalkerMetrics;

use super::gait_figures::GaitFigures;
use super::gait_quality::GaitQuality;
use crate::runner::{
    self, ObserverError, RunObserver, RunOptions, RunSummary, SimError, StepRecord,
};
use crate::scene::Scene;

/// What a headless run recorded.
#[derive(Debug, Clone)]
pub struct RecordedRun {
    /// `walkers[c][s]`: character `c`'s metrics after step `s` (scene order).
    pub walkers: Vec<Vec<WalkerMetrics>>,
    /// The run's summary (print depths per character).
    pub summary: RunSummary,
    /// Fixed step, seconds.
    pub dt: f32,
}

impl RecordedRun {
    /// The gait-quality figures of character `c`.
    pub fn quality(&self, c: usize) -> GaitQuality {
        GaitQuality::measure(&self.walkers[c], self.dt)
    }

    /// The rate/resolution comparison figures of character `c`.
    pub fn figures(&self, c: usize) -> GaitFigures {
        let depth = self.summary.print_depth.get(c).copied().unwrap_or_default();
        GaitFigures::measure(&self.walkers[c], self.dt, &depth)
    }
}

/// Keeps every step record's walker metrics, per character.
#[derive(Debug, Default)]
struct SeriesCollector(Vec<Vec<WalkerMetrics>>);

impl RunObserver for SeriesCollector {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        if record.character >= self.0.len() {
            self.0.resize(record.character + 1, Vec::new());
        }
        self.0[record.character].push(record.walker);
        Ok(())
    }
}

/// Runs `scene` headless (no frames, one thread) for `steps` steps at its own `dt`.
pub fn record_run(scene: &Scene, steps: u64) -> Result<RecordedRun, SimError> {
    record_run_with_inputs(scene, steps, None)
}

/// [`record_run`] with recorded `inputs` steering a character, and the
/// final world hash in the summary.
pub fn record_run_with_inputs(
    scene: &Scene,
    steps: u64,
    inputs: Option<&crate::inputs::InputScript>,
) -> Result<RecordedRun, SimError> {
    let mut options = RunOptions::from_scene(scene);
    options.steps = steps;
    options.render = false;
    options.hash = inputs.is_some();
    let mut series = SeriesCollector::default();
    let summary = runner::run_with_inputs(scene, &options, inputs, &mut series)?;
    let mut walkers = series.0;
    walkers.resize(scene.characters.len(), Vec::new());
    Ok(RecordedRun {
        walkers,
        summary,
        dt: scene.sim.dt,
    })
}
