//! One row of `metrics.csv` as a `#[derive(Serialize)]` struct: the header is
//! the struct's field names and the cells its values, so the two cannot drift
//! apart.

use std::fmt::{self, Display, Write as _};
use std::sync::OnceLock;

use serde::{Serialize, Serializer};

use crate::runner::StepRecord;

/// A number written as Rust's `Display` writes it (`0`, `0.95`, `-0.001998402`,
/// `NaN`): the shortest text that reads back to the same value, never in
/// scientific notation.
#[derive(Debug, Clone, Copy, Default)]
struct Num<T>(T);

impl<T: Display> Serialize for Num<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        // Formatted on the stack: a run writes tens of cells per step.
        let mut text = CellText::default();
        match write!(text, "{}", self.0) {
            Ok(()) => serializer.serialize_str(text.as_str()),
            Err(_) => serializer.collect_str(&self.0),
        }
    }
}

/// Bytes of [`CellText`]: room for any `f32` (the longest, the smallest
/// subnormal, takes 47) and for `f64`s of ordinary sizes.
const CELL_BYTES: usize = 64;

/// A cell's text, formatted without allocating; formatting fails when the
/// text does not fit.
struct CellText {
    bytes: [u8; CELL_BYTES],
    len: usize,
}

impl Default for CellText {
    fn default() -> Self {
        CellText {
            bytes: [0; CELL_BYTES],
            len: 0,
        }
    }
}

impl CellText {
    fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..self.len]).expect("only whole strs are written")
    }
}

impl fmt::Write for CellText {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        let room = self.bytes.get_mut(self.len..end).ok_or(fmt::Error)?;
        room.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// A flag written as `0` or `1`.
#[derive(Debug, Clone, Copy, Default)]
struct Flag(bool);

impl Serialize for Flag {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(u8::from(self.0))
    }
}

/// One row of `metrics.csv`: the state of one character at the end of one step.
/// SI units, angles in radians; `l`/`r` (or `_l`/`_r`) name the left and right
/// foot or knee; a missing value (no platform) is an empty cell.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub(super) struct MetricsRow<'a> {
    t: Num<f64>,
    character: &'a str,
    com_x: Num<f32>,
    com_y: Num<f32>,
    com_z: Num<f32>,
    tilt: Num<f32>,
    tilt_rate: Num<f32>,
    torque: Num<f32>,
    pelvis_y: Num<f32>,
    lfoot_x: Num<f32>,
    lfoot_y: Num<f32>,
    lfoot_z: Num<f32>,
    rfoot_x: Num<f32>,
    rfoot_y: Num<f32>,
    rfoot_z: Num<f32>,
    lcontact: Flag,
    rcontact: Flag,
    lplanted: Flag,
    rplanted: Flag,
    lpressing: Flag,
    rpressing: Flag,
    ltarget_y: Num<f32>,
    rtarget_y: Num<f32>,
    lplatform_y: Option<Num<f32>>,
    rplatform_y: Option<Num<f32>>,
    knee_l: Num<f32>,
    knee_r: Num<f32>,
    grass_height: Num<f32>,
    terrain_volume: Num<f64>,
    lground_y: Num<f32>,
    rground_y: Num<f32>,
    lsole_below: Num<f32>,
    rsole_below: Num<f32>,
    lheel_x: Num<f32>,
    lheel_y: Num<f32>,
    lheel_z: Num<f32>,
    ltoe_x: Num<f32>,
    ltoe_y: Num<f32>,
    ltoe_z: Num<f32>,
    rheel_x: Num<f32>,
    rheel_y: Num<f32>,
    rheel_z: Num<f32>,
    rtoe_x: Num<f32>,
    rtoe_y: Num<f32>,
    rtoe_z: Num<f32>,
}

impl<'a> MetricsRow<'a> {
    /// The row of `record` for the character named `name`.
    pub(super) fn new(name: &'a str, record: &StepRecord) -> Self {
        let w = &record.walker;
        let m = &w.character;
        let [lfoot, rfoot] = m.feet;
        let [lsole, rsole] = &m.soles;
        let [lground, rground] = &w.sole_ground;
        MetricsRow {
            t: Num(record.t),
            character: name,
            com_x: Num(m.com.x),
            com_y: Num(m.com.y),
            com_z: Num(m.com.z),
            tilt: Num(m.tilt),
            tilt_rate: Num(m.tilt_rate),
            torque: Num(m.torque),
            pelvis_y: Num(m.pelvis_y),
            lfoot_x: Num(lfoot.x),
            lfoot_y: Num(lfoot.y),
            lfoot_z: Num(lfoot.z),
            rfoot_x: Num(rfoot.x),
            rfoot_y: Num(rfoot.y),
            rfoot_z: Num(rfoot.z),
            lcontact: Flag(m.contact[0]),
            rcontact: Flag(m.contact[1]),
            lplanted: Flag(m.planted[0]),
            rplanted: Flag(m.planted[1]),
            lpressing: Flag(m.pressing[0]),
            rpressing: Flag(m.pressing[1]),
            ltarget_y: Num(m.ik_target_y[0]),
            rtarget_y: Num(m.ik_target_y[1]),
            lplatform_y: w.platform_y[0].map(Num),
            rplatform_y: w.platform_y[1].map(Num),
            knee_l: Num(m.knee_flexion[0]),
            knee_r: Num(m.knee_flexion[1]),
            grass_height: Num(w.grass_height),
            terrain_volume: Num(record.terrain_volume),
            lground_y: Num(lground.centre),
            rground_y: Num(rground.centre),
            lsole_below: Num(lground.buried(lsole)),
            rsole_below: Num(rground.buried(rsole)),
            lheel_x: Num(lsole.heel.x),
            lheel_y: Num(lsole.heel.y),
            lheel_z: Num(lsole.heel.z),
            ltoe_x: Num(lsole.toe.x),
            ltoe_y: Num(lsole.toe.y),
            ltoe_z: Num(lsole.toe.z),
            rheel_x: Num(rsole.heel.x),
            rheel_y: Num(rsole.heel.y),
            rheel_z: Num(rsole.heel.z),
            rtoe_x: Num(rsole.toe.x),
            rtoe_y: Num(rsole.toe.y),
            rtoe_z: Num(rsole.toe.z),
        }
    }
}

/// The column names of `metrics.csv`, in file order: the field names of
/// [`MetricsRow`], as the `csv` crate writes them in a header.
pub(super) fn metrics_columns() -> &'static [String] {
    static COLUMNS: OnceLock<Vec<String>> = OnceLock::new();
    COLUMNS.get_or_init(|| {
        let mut writer = csv::Writer::from_writer(Vec::new());
        writer
            .serialize(MetricsRow::default())
            .expect("a row serializes into memory");
        let bytes = writer.into_inner().expect("writing to memory cannot fail");
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(bytes.as_slice());
        let header = reader
            .records()
            .next()
            .expect("the header comes first")
            .expect("the header is valid CSV");
        header.iter().map(str::to_owned).collect()
    })
}

/// The header line of `metrics.csv` (without the newline).
pub fn metrics_header() -> String {
    metrics_columns().join(",")
}

/// Position of the column named `name`, if there is one.
pub fn metric_column(name: &str) -> Option<usize> {
    metrics_columns().iter().position(|c| c == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_read_as_display_writes_them_short_or_long() {
        let cell = |v: f64| {
            let mut w = csv::Writer::from_writer(Vec::new());
            w.serialize([Num(v)]).unwrap();
            String::from_utf8(w.into_inner().unwrap()).unwrap()
        };
        for v in [0.0, -0.001998402, 12.5, f64::MAX, 5e-324, f64::NAN] {
            assert_eq!(cell(v), format!("{v}\n"));
        }
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize([Num(1.0e-45f32)]).unwrap();
        assert_eq!(
            String::from_utf8(w.into_inner().unwrap()).unwrap(),
            format!("{}\n", 1.0e-45f32)
        );
    }

    #[test]
    fn names_are_unique_and_cover_the_sole_columns() {
        let columns = metrics_columns();
        assert_eq!(columns.len(), 45);
        assert_eq!(columns[0], "t");
        for (k, c) in columns.iter().enumerate() {
            assert!(!columns[..k].contains(c), "{c} twice");
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
