//! The short summary printed at the end of a run.

use std::fmt::Write;

use super::RunReport;

/// A few lines: steps and times, then one line per character.
pub fn text_summary(report: &RunReport) -> String {
    let mut s = String::new();
    let t = &report.timings;
    let _ = writeln!(
        s,
        "scene {}: {} steps, {:.2} s simulated, {:.2} s wall: set-up {:.3} s, then {:.3} ms/step ({} thread{})",
        report.scene,
        report.steps,
        report.duration_seconds,
        t.wall_seconds,
        t.setup_seconds,
        t.ms_per_step,
        t.threads,
        if t.threads == 1 { "" } else { "s" },
    );
    let g = &report.terrain;
    let _ = writeln!(
        s,
        "terrain: {} x {} samples, {:.4} m cells",
        g.grid_nx, g.grid_nz, g.cell_size
    );
    for c in &report.characters {
        let st = &c.stats;
        let _ = write!(
            s,
            "{}: walked {:.2} m, tilt {:.2} +- {:.2} deg, pelvis {:.3} m, max knee {:.1} deg",
            c.name,
            st.distance_walked,
            st.mean_tilt.to_degrees(),
            st.std_tilt.to_degrees(),
            st.mean_pelvis_y,
            st.max_knee_flexion.to_degrees(),
        );
        if let Some(d) = c.print_depth {
            let _ = write!(
                s,
                ", {} prints {:.3} m deep (max {:.3} m)",
                d.prints, d.mean_m, d.max_m
            );
        }
        s.push('\n');
    }
    if let Some(h) = &report.world_hash {
        let _ = writeln!(s, "world hash: {h}");
    }
    s
}
