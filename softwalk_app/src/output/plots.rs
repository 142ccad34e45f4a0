//! Plots of the main metric series, one PNG per quantity, drawn from series
//! kept in bounded memory however long the run.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use engine::canvas::{LinePlot, Series};
use engine::output::save_png;
use image::Rgba;

use super::decimated_series::DecimatedSeries;
use crate::runner::{ObserverError, RunObserver, StepRecord};

/// Colours of successive series.
const COLORS: [Rgba<u8>; 6] = [
    Rgba([31, 119, 180, 255]),
    Rgba([214, 39, 40, 255]),
    Rgba([44, 160, 44, 255]),
    Rgba([255, 127, 14, 255]),
    Rgba([148, 103, 189, 255]),
    Rgba([140, 86, 75, 255]),
];

/// One plotted quantity: file name, title, y label, and how to read curve `k`
/// from a record (`labels` names the curves).
struct Quantity {
    file: &'static str,
    title: &'static str,
    y_label: &'static str,
    labels: &'static [&'static str],
    read: fn(&StepRecord, usize) -> f32,
}

const QUANTITIES: [Quantity; 5] = [
    Quantity {
        file: "tilt.png",
        title: "Forward tilt of the proxy",
        y_label: "degrees",
        labels: &[""],
        read: |r, _| r.walker.character.tilt.to_degrees(),
    },
    Quantity {
        file: "torque.png",
        title: "Balance torque (eq. 1)",
        y_label: "N m",
        labels: &[""],
        read: |r, _| r.walker.character.torque,
    },
    Quantity {
        file: "pelvis.png",
        title: "Pelvis height",
        y_label: "m",
        labels: &[""],
        read: |r, _| r.walker.character.pelvis_y,
    },
    Quantity {
        file: "knees.png",
        title: "Knee flexion",
        y_label: "degrees",
        labels: &[" left", " right"],
        read: |r, k| r.walker.character.knee_flexion[k].to_degrees(),
    },
    Quantity {
        file: "feet.png",
        title: "Foot height",
        y_label: "m",
        labels: &[" left", " right"],
        read: |r, k| r.walker.character.feet[k].y,
    },
];

/// Plot width and height, pixels.
const PLOT_SIZE: (u32, u32) = (720, 360);

/// Keeps every plotted curve as a `DecimatedSeries` (bounded memory) and
/// writes the plots at the end.
pub struct PlotCollector {
    names: Vec<String>,
    /// `[character][quantity][curve]`.
    curves: Vec<Vec<Vec<DecimatedSeries>>>,
}

/// What [`PlotCollector::save`] did: the plots written, and a warning for
/// each plot it skipped.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlotsSaved {
    /// File names of the plots written.
    pub written: Vec<String>,
    /// One line per skipped plot: the file and why.
    pub skipped: Vec<String>,
}

impl PlotCollector {
    /// A collector for characters named `names` (scene order).
    pub fn new(names: Vec<String>) -> Self {
        let curves = names.iter().map(|_| Self::empty_curves()).collect();
        PlotCollector { names, curves }
    }

    fn empty_curves() -> Vec<Vec<DecimatedSeries>> {
        QUANTITIES
            .iter()
            .map(|q| vec![DecimatedSeries::default(); q.labels.len()])
            .collect()
    }

    /// The file names of the plots [`PlotCollector::save`] writes.
    pub fn files() -> impl Iterator<Item = &'static str> {
        QUANTITIES.iter().map(|q| q.file)
    }

    /// Writes `DIR/<quantity>.png` for every quantity. A plot that cannot be
    /// drawn or written is skipped with a warning in the result; it never
    /// fails the run.
    pub fn save(&self, dir: &Path) -> PlotsSaved {
        let mut saved = PlotsSaved::default();
        for (qi, q) in QUANTITIES.iter().enumerate() {
            let path = dir.join(q.file);
            let drawn = catch_unwind(AssertUnwindSafe(|| {
                self.plot(qi).render(PLOT_SIZE.0, PLOT_SIZE.1)
            }));
            let result = match drawn {
                Ok(image) => save_png(&path, &image).map_err(|e| e.to_string()),
                Err(_) => Err("drawing it panicked".to_owned()),
            };
            match result {
                Ok(()) => saved.written.push(q.file.to_string()),
                Err(why) => saved
                    .skipped
                    .push(format!("plot {} skipped: {why}", path.display())),
            }
        }
        saved
    }

    /// The plot of quantity `qi`: one curve per character and label.
    fn plot(&self, qi: usize) -> LinePlot {
        let q = &QUANTITIES[qi];
        let mut series = Vec::new();
        for (c, name) in self.names.iter().enumerate() {
            for (k, label) in q.labels.iter().enumerate() {
                series.push(Series {
                    name: format!("{name}{label}"),
                    points: self.curves[c][qi][k].points(),
                    color: COLORS[(c * q.labels.len() + k) % COLORS.len()],
                });
            }
        }
        LinePlot {
            title: q.title.into(),
            x_label: "time (s)".into(),
            y_label: q.y_label.into(),
            series,
        }
    }
}

impl RunObserver for PlotCollector {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        if record.character >= self.curves.len() {
            self.curves
                .resize_with(record.character + 1, Self::empty_curves);
            while self.names.len() < self.curves.len() {
                self.names.push(self.names.len().to_string());
            }
        }
        for (q, curves) in QUANTITIES.iter().zip(&mut self.curves[record.character]) {
            for (k, curve) in curves.iter_mut().enumerate() {
                curve.push(record.t, (q.read)(record, k));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runner::test_records;

    fn record(step: u64, torque: f32, pelvis_y: f32) -> StepRecord {
        let mut walker = test_records::standing();
        walker.character.torque = torque;
        walker.character.pelvis_y = pelvis_y;
        StepRecord {
            step,
            t: step as f64 / 60.0,
            character: 0,
            walker,
            terrain_volume: 0.0,
        }
    }

    /// Issue 22: the torque series {0, -1e-45} panicked in the axis labels;
    /// huge and non-finite values must not stop the plots either.
    #[test]
    fn degenerate_series_are_all_plotted() {
        let dir = tempfile::tempdir().unwrap();
        let mut plots = PlotCollector::new(vec!["walker".into()]);
        let values = [
            (0.0, 0.9),
            (-1.0e-45, f32::NAN),
            (f32::MAX, f32::INFINITY),
            (-f32::MAX, 1.0e-45),
        ];
        for (step, (torque, pelvis)) in values.into_iter().enumerate() {
            plots.on_step(&record(step as u64, torque, pelvis)).unwrap();
        }
        let saved = plots.save(dir.path());
        assert_eq!(saved.skipped, Vec::<String>::new());
        assert_eq!(saved.written.len(), QUANTITIES.len());
    }

    #[test]
    fn a_plot_that_cannot_be_written_is_skipped_with_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        fs_folder(&dir.path().join("torque.png"));
        let mut plots = PlotCollector::new(vec!["walker".into()]);
        plots.on_step(&record(0, 1.0, 0.9)).unwrap();
        let saved = plots.save(dir.path());
        assert_eq!(saved.written.len(), QUANTITIES.len() - 1);
        assert_eq!(saved.skipped.len(), 1);
        assert!(
            saved.skipped[0].contains("torque.png"),
            "{:?}",
            saved.skipped
        );
    }

    fn fs_folder(path: &Path) {
        std::fs::create_dir(path).unwrap();
    }
}
