//! `metrics.csv`: one row per step per character, streamed through the `csv`
//! crate into the file's `.metrics.csv.partial` beside the target, which is
//! renamed over the target only when the run finishes. Nothing is kept in
//! memory but the writer's buffer, however long the run.

use std::io;
use std::path::{Path, PathBuf};

use engine::io::{AtomicFile, WriteError};

use super::metrics_row::{MetricsRow, metrics_columns};
use crate::runner::{ObserverError, RunObserver, StepRecord};

/// Streams metric rows; [`MetricsCsv::finish`] makes the file appear.
/// Dropped without `finish`, it removes its partial file and the target is untouched.
pub struct MetricsCsv {
    path: PathBuf,
    writer: csv::Writer<AtomicFile>,
    names: Vec<String>,
    rows: u64,
}

impl MetricsCsv {
    /// Starts `path` (written at [`MetricsCsv::finish`]) with its header;
    /// `names` are the character names by index.
    pub fn create(path: &Path, names: Vec<String>) -> Result<MetricsCsv, WriteError> {
        let file = AtomicFile::create(path)?;
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(file);
        writer
            .write_record(metrics_columns())
            .map_err(|e| csv_error(path, e))?;
        Ok(MetricsCsv {
            path: path.to_path_buf(),
            writer,
            names,
            rows: 0,
        })
    }

    /// Rows written so far (header excluded).
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Appends one row.
    pub fn write_record(&mut self, r: &StepRecord) -> Result<(), WriteError> {
        let fallback;
        let name = match self.names.get(r.character) {
            Some(name) => name.as_str(),
            None => {
                fallback = r.character.to_string();
                fallback.as_str()
            }
        };
        self.writer
            .serialize(MetricsRow::new(name, r))
            .map_err(|e| csv_error(&self.path, e))?;
        self.rows += 1;
        Ok(())
    }

    /// Flushes, syncs and renames the partial file over the target; returns the row count.
    pub fn finish(self) -> Result<u64, WriteError> {
        let Self {
            path, writer, rows, ..
        } = self;
        let file = writer.into_inner().map_err(|e| WriteError {
            path,
            source: e.into_error(),
        })?;
        file.commit()?;
        Ok(rows)
    }
}

/// A `csv` error while writing `path`, as a [`WriteError`] naming the file.
fn csv_error(path: &Path, e: csv::Error) -> WriteError {
    let message = e.to_string();
    let source = match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        _ => io::Error::other(message),
    };
    WriteError {
        path: path.to_path_buf(),
        source,
    }
}

impl RunObserver for MetricsCsv {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        Ok(self.write_record(record)?)
    }
}

#[cfg(test)]
mod tests {
    use std::fs;

    use glam::Vec3;
    use softwalk_systems::character::CharacterMetrics;
    use softwalk_systems::foot::FootSole;
    use softwalk_systems::sim::{SoleGround, WalkerMetrics};

    use super::*;
    use crate::output::metrics_header;
    use crate::runner::test_records;

    fn record(step: u64, character: usize) -> StepRecord {
        let standing = test_records::standing();
        StepRecord {
            step,
            t: (step + 1) as f64 * 0.5,
            character,
            walker: WalkerMetrics {
                character: CharacterMetrics {
                    com: Vec3::new(1.0, 0.9, 2.0),
                    tilt: 0.1,
                    tilt_rate: -0.2,
                    torque: 3.0,
                    pelvis_y: 0.95,
                    feet: [Vec3::new(1.0, 0.0, 1.9), Vec3::new(1.2, 0.1, 2.1)],
                    contact: [true, false],
                    pressing: [true, false],
                    planted: [true, false],
                    ik_target_y: [0.0, 0.05],
                    knee_flexion: [0.2, 0.6],
                    soles: [
                        standing.character.soles[0],
                        FootSole {
                            toe: Vec3::new(0.1, 0.01, 0.15),
                            ..standing.character.soles[1]
                        },
                    ],
                    ..standing.character
                },
                platform_y: [None, Some(0.3)],
                grass_height: 0.0,
                sole_ground: [
                    SoleGround {
                        centre: -0.01,
                        ..SoleGround::default()
                    },
                    SoleGround {
                        centre: 0.02,
                        ..SoleGround::default()
                    },
                ],
                ..standing
            },
            terrain_volume: 12.5,
        }
    }

    #[test]
    fn rows_appear_only_after_finish() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("metrics.csv");
        let mut csv = MetricsCsv::create(&path, vec!["a".into(), "b".into()]).unwrap();
        for step in 0..3 {
            for c in 0..2 {
                csv.write_record(&record(step, c)).unwrap();
            }
        }
        assert!(!path.exists());
        assert_eq!(csv.finish().unwrap(), 6);
        let text = fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], metrics_header());
        assert_eq!(lines.len(), 7);
        assert_eq!(
            lines[1],
            "0.5,a,1,0.9,2,0.1,-0.2,3,0.95,1,0,1.9,1.2,0.1,2.1,1,0,1,0,1,0,0,0.05,,0.3,0.2,0.6,0,12.5,\
             -0.01,0.02,0,-0.001998402,-0.1,0,-0.1,-0.1,0,0.15,0.1,0,-0.1,0.1,0.01,0.15"
        );
        let columns = metrics_header().split(',').count();
        assert!(lines.iter().all(|l| l.split(',').count() == columns));
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn dropped_writer_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("metrics.csv");
        fs::write(&path, "old").unwrap();
        let mut csv = MetricsCsv::create(&path, vec!["a".into()]).unwrap();
        csv.write_record(&record(0, 0)).unwrap();
        drop(csv);
        assert_eq!(fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
