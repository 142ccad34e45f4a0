//! The columns of `metrics.csv`: one list of (name, how to write the cell), so
//! the header and the rows are produced from the same place and cannot drift apart.

use std::fmt::Write as _;

use softwalk_systems::character::CharacterMetrics;
use softwalk_systems::sim::WalkerMetrics;

use crate::runner::StepRecord;

/// What one row's cells are read from.
pub struct MetricRow<'a> {
    /// The character's name.
    pub name: &'a str,
    /// The step record.
    pub record: &'a StepRecord,
}

impl MetricRow<'_> {
    fn w(&self) -> &WalkerMetrics {
        &self.record.walker
    }

    fn m(&self) -> &CharacterMetrics {
        &self.record.walker.character
    }
}

/// One column of `metrics.csv`: its header name and how its cell is written.
pub struct MetricColumn {
    /// Header name.
    pub name: &'static str,
    /// Appends the cell of a row (no separator).
    pub write: fn(&MetricRow<'_>, &mut String),
}

/// A value that can be one CSV cell.
trait Cell {
    fn put(&self, out: &mut String);
}

impl Cell for f32 {
    fn put(&self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

impl Cell for f64 {
    fn put(&self, out: &mut String) {
        let _ = write!(out, "{self}");
    }
}

/// Flags are written as 0 or 1.
impl Cell for bool {
    fn put(&self, out: &mut String) {
        out.push(if *self { '1' } else { '0' });
    }
}

/// A missing value is an empty cell.
impl Cell for Option<f32> {
    fn put(&self, out: &mut String) {
        if let Some(v) = self {
            v.put(out);
        }
    }
}

impl Cell for &str {
    fn put(&self, out: &mut String) {
        out.push_str(self);
    }
}

macro_rules! column {
    ($name:literal, |$row:ident| $value:expr) => {
        MetricColumn {
            name: $name,
            write: |$row: &MetricRow<'_>, out: &mut String| Cell::put(&$value, out),
        }
    };
}

/// Every column of `metrics.csv`, in file order. SI units, angles in radians;
/// `l`/`r` (or `_l`/`_r`) name the left and right foot or knee.
pub const METRIC_COLUMNS: &[MetricColumn] = &[
    column!("t", |r| r.record.t),
    column!("character", |r| r.name),
    column!("com_x", |r| r.m().com.x),
    column!("com_y", |r| r.m().com.y),
    column!("com_z", |r| r.m().com.z),
    column!("tilt", |r| r.m().tilt),
    column!("tilt_rate", |r| r.m().tilt_rate),
    column!("torque", |r| r.m().torque),
    column!("pelvis_y", |r| r.m().pelvis_y),
    column!("lfoot_x", |r| r.m().feet[0].x),
    column!("lfoot_y", |r| r.m().feet[0].y),
    column!("lfoot_z", |r| r.m().feet[0].z),
    column!("rfoot_x", |r| r.m().feet[1].x),
    column!("rfoot_y", |r| r.m().feet[1].y),
    column!("rfoot_z", |r| r.m().feet[1].z),
    column!("lcontact", |r| r.m().contact[0]),
    column!("rcontact", |r| r.m().contact[1]),
    column!("lplanted", |r| r.m().planted[0]),
    column!("rplanted", |r| r.m().planted[1]),
    column!("ltarget_y", |r| r.m().ik_target_y[0]),
    column!("rtarget_y", |r| r.m().ik_target_y[1]),
    column!("lplatform_y", |r| r.w().platform_y[0]),
    column!("rplatform_y", |r| r.w().platform_y[1]),
    column!("knee_l", |r| r.m().knee_flexion[0]),
    column!("knee_r", |r| r.m().knee_flexion[1]),
    column!("grass_height", |r| r.w().grass_height),
    column!("terrain_volume", |r| r.record.terrain_volume),
    column!("lground_y", |r| r.w().sole_ground[0].centre),
    column!("rground_y", |r| r.w().sole_ground[1].centre),
    column!("lsole_below", |r| r.w().sole_ground[0]
        .buried(&r.m().soles[0])),
    column!("rsole_below", |r| r.w().sole_ground[1]
        .buried(&r.m().soles[1])),
    column!("lheel_x", |r| r.m().soles[0].heel.x),
    column!("lheel_y", |r| r.m().soles[0].heel.y),
    column!("lheel_z", |r| r.m().soles[0].heel.z),
    column!("ltoe_x", |r| r.m().soles[0].toe.x),
    column!("ltoe_y", |r| r.m().soles[0].toe.y),
    column!("ltoe_z", |r| r.m().soles[0].toe.z),
    column!("rheel_x", |r| r.m().soles[1].heel.x),
    column!("rheel_y", |r| r.m().soles[1].heel.y),
    column!("rheel_z", |r| r.m().soles[1].heel.z),
    column!("rtoe_x", |r| r.m().soles[1].toe.x),
    column!("rtoe_y", |r| r.m().soles[1].toe.y),
    column!("rtoe_z", |r| r.m().soles[1].toe.z),
];

/// The header line of `metrics.csv` (without the newline).
pub fn metrics_header() -> String {
    let names: Vec<&str> = METRIC_COLUMNS.iter().map(|c| c.name).collect();
    names.join(",")
}

/// One data line of `metrics.csv` (without the newline), one cell per column.
pub fn metrics_line(row: &MetricRow<'_>) -> String {
    let mut line = String::new();
    for (k, column) in METRIC_COLUMNS.iter().enumerate() {
        if k > 0 {
            line.push(',');
        }
        (column.write)(row, &mut line);
    }
    line
}

/// Position of the column named `name`, if there is one.
pub fn metric_column(name: &str) -> Option<usize> {
    METRIC_COLUMNS.iter().position(|c| c.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_cover_the_sole_columns() {
        for (k, c) in METRIC_COLUMNS.iter().enumerate() {
            assert!(
                METRIC_COLUMNS[..k].iter().all(|o| o.name != c.name),
                "{} twice",
                c.name
            );
        }
        for side in ["l", "r"] {
            for part in [
                "ground_y",
                "sole_below",
                "heel_x",
                "heel_y",
                "heel_z",
                "toe_x",
                "toe_y",
                "toe_z",
            ] {
                assert!(
                    metric_column(&format!("{side}{part}")).is_some(),
                    "{side}{part}"
                );
            }
        }
    }
}
