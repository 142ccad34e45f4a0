//! Plots of the main metric series, one PNG per quantity.

use std::path::Path;

use engine::render::{LinePlot, Series, save_png};
use image::Rgba;

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

/// One plotted quantity: file name, title, y label, and how to read it from a
/// record (one value per curve; `labels` names the curves).
struct Quantity {
    file: &'static str,
    title: &'static str,
    y_label: &'static str,
    labels: &'static [&'static str],
    read: fn(&StepRecord) -> Vec<f32>,
}

const QUANTITIES: [Quantity; 5] = [
    Quantity {
        file: "tilt.png",
        title: "Forward tilt of the proxy",
        y_label: "degrees",
        labels: &[""],
        read: |r| vec![r.walker.character.tilt.to_degrees()],
    },
    Quantity {
        file: "torque.png",
        title: "Balance torque (eq. 1)",
        y_label: "N m",
        labels: &[""],
        read: |r| vec![r.walker.character.torque],
    },
    Quantity {
        file: "pelvis.png",
        title: "Pelvis height",
        y_label: "m",
        labels: &[""],
        read: |r| vec![r.walker.character.pelvis_y],
    },
    Quantity {
        file: "knees.png",
        title: "Knee flexion",
        y_label: "degrees",
        labels: &[" left", " right"],
        read: |r| {
            r.walker
                .character
                .knee_flexion
                .map(f32::to_degrees)
                .to_vec()
        },
    },
    Quantity {
        file: "feet.png",
        title: "Foot height",
        y_label: "m",
        labels: &[" left", " right"],
        read: |r| r.walker.character.feet.map(|f| f.y).to_vec(),
    },
];

/// Collects every record and writes the plots at the end.
pub struct PlotCollector {
    names: Vec<String>,
    records: Vec<StepRecord>,
}

impl PlotCollector {
    /// A collector for characters named `names` (scene order).
    pub fn new(names: Vec<String>) -> Self {
        PlotCollector {
            names,
            records: Vec::new(),
        }
    }

    /// Writes `DIR/<quantity>.png` for every quantity; returns the files written.
    pub fn save(&self, dir: &Path) -> Result<Vec<String>, ObserverError> {
        let mut written = Vec::new();
        for q in &QUANTITIES {
            let mut series = Vec::new();
            for (c, name) in self.names.iter().enumerate() {
                for (k, label) in q.labels.iter().enumerate() {
                    let points = self
                        .records
                        .iter()
                        .filter(|r| r.character == c)
                        .map(|r| (r.t as f32, (q.read)(r)[k]))
                        .collect();
                    let color = COLORS[(c * q.labels.len() + k) % COLORS.len()];
                    series.push(Series {
                        name: format!("{name}{label}"),
                        points,
                        color,
                    });
                }
            }
            let plot = LinePlot {
                title: q.title.into(),
                x_label: "time (s)".into(),
                y_label: q.y_label.into(),
                series,
            };
            save_png(&dir.join(q.file), &plot.render(720, 360))?;
            written.push(q.file.to_string());
        }
        Ok(written)
    }
}

impl RunObserver for PlotCollector {
    fn on_step(&mut self, record: &StepRecord) -> Result<(), ObserverError> {
        self.records.push(*record);
        Ok(())
    }
}
