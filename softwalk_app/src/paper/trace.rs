//! Runs a scene headless and keeps what the claims measure: every character's
//! metrics at every step, the terrain before and after, and the world itself.

use engine::ecs::World;
use engine::geom::HeightGrid;
use engine::schedule::App;
use softwalk_systems::sim::{GroundState, WalkerMetrics};

use super::PaperError;
use crate::scene::Scene;

/// What one headless run of a scene recorded.
pub struct Trace {
    /// The simulation after the last step (for grass and terrain queries).
    pub app: App,
    /// `walkers[c][s]`: character `c`'s metrics after step `s` (scene order).
    pub walkers: Vec<Vec<WalkerMetrics>>,
    /// Terrain heights before the first step.
    pub initial: HeightGrid,
    /// Terrain heights after the last step.
    pub last: HeightGrid,
    /// The volume the terrain should have from what was carved and compacted,
    /// before the first step and after the last (`GroundState::volume`).
    pub tracked_volume: (f64, f64),
    /// Largest number of terrain cells any single step changed (its dirty window).
    pub max_dirty_cells: usize,
    /// Fixed step, seconds.
    pub dt: f32,
}

impl Trace {
    /// Index of the first step at or after `seconds`.
    pub fn step_at(&self, seconds: f32) -> usize {
        (seconds / self.dt).round() as usize
    }

    /// Character `c`'s metrics from `seconds` on, while it walks (path not finished).
    pub fn walking_from(&self, c: usize, seconds: f32) -> Vec<WalkerMetrics> {
        let from = self.step_at(seconds).min(self.walkers[c].len());
        self.walkers[c][from..]
            .iter()
            .filter(|m| m.velocity.length() > 0.05)
            .copied()
            .collect()
    }
}

/// Runs `scene` for `steps` steps, calling `each_step` with the world after every step.
pub fn trace(
    scene: &Scene,
    steps: usize,
    mut each_step: impl FnMut(&mut World),
) -> Result<Trace, PaperError> {
    let run_error = |source| PaperError::Run {
        scene: scene.name.clone(),
        source,
    };
    let (mut app, entities) = scene
        .build_sim()
        .map_err(|e| run_error(crate::runner::SimError::Setup(e)))?;
    let initial = crate::runner::terrain_grid(&app.world);
    let start_volume = app.world.resource::<GroundState>().volume();
    app.world.resource_mut::<GroundState>().clear_unseen();
    let mut walkers = vec![Vec::with_capacity(steps); entities.len()];
    let mut max_dirty_cells = 0;
    for _ in 0..steps {
        softwalk_systems::sim::step(&mut app)
            .map_err(|e| run_error(crate::runner::SimError::Step(e)))?;
        for (series, &entity) in walkers.iter_mut().zip(&entities) {
            if let Ok(m) = app.world.get::<WalkerMetrics>(entity) {
                series.push(*m);
            }
        }
        let dirty = app.world.resource_mut::<GroundState>().take_unseen();
        let cells = dirty.iter().map(|r| r.area()).sum();
        max_dirty_cells = max_dirty_cells.max(cells);
        each_step(&mut app.world);
    }
    let end_volume = app.world.resource::<GroundState>().volume();
    let last = crate::runner::terrain_grid(&app.world);
    Ok(Trace {
        app,
        walkers,
        initial,
        last,
        tracked_volume: (start_volume, end_volume),
        max_dirty_cells,
        dt: scene.sim.dt,
    })
}
