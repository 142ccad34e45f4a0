//! Small line plots of time series, rendered alone or onto a frame.

use glam::Vec2;
use image::{Rgba, RgbaImage};

use super::overlay::Overlay;
use super::text::{line_height, text_width};

/// A rectangle of pixels: top-left corner and size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelRect {
    /// Left edge.
    pub x: u32,
    /// Top edge.
    pub y: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// One named curve of a [`LinePlot`].
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Name shown in the legend.
    pub name: String,
    /// `(x, y)` samples in drawing order; points with a non-finite coordinate
    /// are skipped and break the curve.
    pub points: Vec<(f32, f32)>,
    /// Curve colour.
    pub color: Rgba<u8>,
}

/// A line plot with axes, ticks, grid and legend.
///
/// ```
/// use engine::canvas::{LinePlot, Series};
/// use image::Rgba;
/// let plot = LinePlot {
///     title: "pelvis height".into(),
///     x_label: "time (s)".into(),
///     y_label: "height (m)".into(),
///     series: vec![Series {
///         name: "sand".into(),
///         points: (0..50).map(|i| (i as f32 * 0.1, (i as f32 * 0.3).sin())).collect(),
///         color: Rgba([200, 80, 20, 255]),
///     }],
/// };
/// let img = plot.render(320, 200);
/// assert_eq!(img.dimensions(), (320, 200));
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinePlot {
    /// Title above the plot.
    pub title: String,
    /// Label under the x axis.
    pub x_label: String,
    /// Label above the y axis.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
}

/// Plot background.
const BACKGROUND: Rgba<u8> = Rgba([255, 255, 255, 255]);
/// Axis lines, tick labels and titles.
const INK: Rgba<u8> = Rgba([40, 40, 48, 255]);
/// Grid lines.
const GRID: Rgba<u8> = Rgba([225, 228, 234, 255]);
/// Legend box fill.
const LEGEND_FILL: Rgba<u8> = Rgba([255, 255, 255, 220]);

/// Most ticks an axis gets, whatever it is asked for.
const MAX_TICKS: usize = 20;

/// Tick steps from 1e-4 up to below 1e6 are labelled in fixed notation
/// (`0.0025`, `120`); smaller and larger ones in scientific notation (`2.5e-7`).
const FIXED_LABELS: std::ops::Range<f64> = 1e-4..1e6;

/// How tick labels are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LabelStyle {
    /// Fixed notation with this many decimals.
    Fixed(usize),
    /// Scientific notation, with as many mantissa decimals as reach the
    /// power of ten of the tick step (this exponent).
    Scientific(i32),
}

/// An axis range with its tick positions.
///
/// Computed in `f64` from `f32` data, so neither the widest (about ±3.4e38)
/// nor the tiniest (about 1.4e-45) finite `f32` values overflow or underflow
/// the range, its step or its labels.
#[derive(Debug, Clone, PartialEq)]
struct Axis {
    min: f64,
    max: f64,
    ticks: Vec<f64>,
    style: LabelStyle,
}

impl Axis {
    /// A range covering `values` (finite ones) widened to round tick steps,
    /// with about `target_ticks` ticks (at most [`MAX_TICKS`]). No finite data
    /// give a unit range; constant data (to `f32` precision) a range padded
    /// by a tenth of the value each way, or by one around zero.
    fn covering(values: impl Iterator<Item = f32>, target_ticks: usize) -> Self {
        let (mut lo, mut hi) = values
            .filter(|v| v.is_finite())
            .map(f64::from)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        if lo > hi {
            (lo, hi) = (0.0, 1.0);
        }
        let magnitude = lo.abs().max(hi.abs());
        if hi - lo <= magnitude * f64::from(f32::EPSILON) {
            let pad = if magnitude == 0.0 {
                1.0
            } else {
                0.1 * magnitude
            };
            (lo, hi) = (lo - pad, hi + pad);
        }
        let target_ticks = target_ticks.clamp(1, MAX_TICKS);
        let step = nice_step((hi - lo) / target_ticks as f64);
        let min = (lo / step).floor() * step;
        let max = (hi / step).ceil() * step;
        let count = (((max - min) / step).round() as usize).clamp(1, 2 * MAX_TICKS);
        let ticks = (0..=count).map(|i| min + i as f64 * step).collect();
        Self {
            min,
            max,
            ticks,
            style: label_style(step),
        }
    }

    /// Position of `v` in the range, 0 at `min` and 1 at `max`.
    fn fraction(&self, v: f64) -> f32 {
        ((v - self.min) / (self.max - self.min)) as f32
    }

    /// The tick label for `v`.
    fn label(&self, v: f64) -> String {
        let v = if v.abs() < 1e-6 * (self.max - self.min) {
            0.0
        } else {
            v
        };
        match self.style {
            LabelStyle::Fixed(decimals) => format!("{v:.decimals$}"),
            LabelStyle::Scientific(_) if v == 0.0 => "0".to_owned(),
            LabelStyle::Scientific(step_exponent) => {
                let exponent = v.abs().log10().floor() as i32;
                let decimals = (exponent - step_exponent).clamp(0, 9) as usize;
                format!("{v:.decimals$e}")
            }
        }
    }
}

/// The label style for ticks `step` apart: just enough decimals to tell
/// neighbouring ticks apart.
fn label_style(step: f64) -> LabelStyle {
    let step_exponent = step.log10().floor();
    if FIXED_LABELS.contains(&step) {
        LabelStyle::Fixed((-step_exponent).max(0.0) as usize)
    } else {
        LabelStyle::Scientific(step_exponent as i32)
    }
}

/// The smallest step of the form 1, 2 or 5 times a power of ten not below
/// `raw` (a positive, finite span per tick).
fn nice_step(raw: f64) -> f64 {
    let magnitude = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw * 0.999)
        .unwrap_or(10.0 * magnitude)
}

impl LinePlot {
    /// Renders the plot alone into a new `width` x `height` image.
    pub fn render(&self, width: u32, height: u32) -> RgbaImage {
        let mut image = RgbaImage::from_pixel(width, height, BACKGROUND);
        self.draw_onto(
            &mut image,
            PixelRect {
                x: 0,
                y: 0,
                width,
                height,
            },
        );
        image
    }

    /// Draws the plot on an opaque background into `rect` of `image` (clipped
    /// to the image), for example as an inset on a rendered frame.
    pub fn draw_onto(&self, image: &mut RgbaImage, rect: PixelRect) {
        let Some(layout) = self.layout(image, rect) else {
            return;
        };
        let mut overlay = Overlay::new(image);
        let box_ = &layout.bounds;
        overlay.fill_rect(
            Vec2::new(box_.x0, box_.y0),
            Vec2::new(box_.w, box_.h),
            BACKGROUND,
        );
        if layout.right - layout.left < 4.0 || layout.bottom - layout.top < 4.0 {
            return;
        }
        layout.draw_grid(&mut overlay);
        self.draw_titles(&mut overlay, &layout);
        self.draw_curves(&mut overlay, &layout);
        self.draw_legend(
            &mut overlay,
            layout.font,
            Vec2::new(layout.right, layout.top),
        );
    }

    /// Where everything of the plot goes in `rect` of `image`: `None` when
    /// the part of `rect` on the image is too small to draw in.
    fn layout(&self, image: &RgbaImage, rect: PixelRect) -> Option<PlotLayout> {
        let x0 = rect.x.min(image.width()) as f32;
        let y0 = rect.y.min(image.height()) as f32;
        let w = (rect.width.min(image.width().saturating_sub(rect.x))) as f32;
        let h = (rect.height.min(image.height().saturating_sub(rect.y))) as f32;
        if w < 2.0 || h < 2.0 {
            return None;
        }
        let font = (h.min(w * 0.75) / 18.0).clamp(9.0, 16.0).round();
        let line = line_height(font);
        let y_ticks = ((h / (3.0 * line)) as usize).clamp(2, 8);
        let x_ticks = ((w / 90.0) as usize).clamp(2, 10);
        let xs = Axis::covering(self.finite_points().map(|p| p.0), x_ticks);
        let ys = Axis::covering(self.finite_points().map(|p| p.1), y_ticks);

        let pad = (font * 0.6).round();
        let tick_label_width = ys
            .ticks
            .iter()
            .map(|&t| text_width(font, &ys.label(t)))
            .fold(0.0, f32::max);
        let title_height = if self.title.is_empty() {
            0.0
        } else {
            line + pad * 0.5
        };
        let y_label_height = if self.y_label.is_empty() { 0.0 } else { line };
        let x_label_height = if self.x_label.is_empty() { 0.0 } else { line };
        Some(PlotLayout {
            left: x0 + pad + tick_label_width + pad * 0.7,
            right: x0 + w - pad - 0.5 * text_width(font, &xs.label(xs.max)),
            top: y0 + pad + title_height + y_label_height + 0.5 * line,
            bottom: y0 + h - pad - x_label_height - line - pad * 0.3,
            bounds: Bounds { x0, y0, w, h },
            font,
            line,
            pad,
            xs,
            ys,
        })
    }

    /// The title above the plot, the y label above its axis and the x label
    /// below the plot area.
    fn draw_titles(&self, overlay: &mut Overlay<'_>, layout: &PlotLayout) {
        let PlotLayout {
            font, line, pad, ..
        } = *layout;
        let Bounds { x0, y0, w, h } = layout.bounds;
        if !self.title.is_empty() {
            let tw = text_width(font, &self.title);
            overlay.text(
                Vec2::new(x0 + 0.5 * (w - tw), y0 + pad * 0.5),
                font,
                INK,
                &self.title,
            );
        }
        if !self.y_label.is_empty() {
            overlay.text(
                Vec2::new(x0 + pad, layout.top - 0.5 * line - line),
                font,
                INK,
                &self.y_label,
            );
        }
        if !self.x_label.is_empty() {
            let tw = text_width(font, &self.x_label);
            overlay.text(
                Vec2::new(0.5 * (layout.left + layout.right - tw), y0 + h - pad - line),
                font,
                INK,
                &self.x_label,
            );
        }
    }

    /// The curves: runs of finite points as lines; lone points as dots.
    fn draw_curves(&self, overlay: &mut Overlay<'_>, layout: &PlotLayout) {
        let curve_width = (layout.font / 6.0).clamp(1.5, 2.5);
        for series in &self.series {
            for run in series
                .points
                .split(|p| !(p.0.is_finite() && p.1.is_finite()))
            {
                let run: Vec<Vec2> = run.iter().map(|&(x, y)| layout.to_px(x, y)).collect();
                match run.as_slice() {
                    [] => {}
                    [single] => overlay.point(*single, series.color, 2.5 * curve_width),
                    _ => overlay.polyline(&run, series.color, curve_width),
                }
            }
        }
    }

    /// The legend box in the top-right corner of the plot area.
    fn draw_legend(&self, overlay: &mut Overlay<'_>, font: f32, top_right: Vec2) {
        let named: Vec<&Series> = self.series.iter().filter(|s| !s.name.is_empty()).collect();
        if named.is_empty() {
            return;
        }
        let line = line_height(font);
        let swatch = 1.6 * font;
        let pad = (0.4 * font).round();
        let name_width = named
            .iter()
            .map(|s| text_width(font, &s.name))
            .fold(0.0, f32::max);
        let size = Vec2::new(
            3.0 * pad + swatch + name_width,
            2.0 * pad + line * named.len() as f32,
        );
        let min = top_right + Vec2::new(-size.x - pad, pad);
        overlay.fill_rect(min, size, LEGEND_FILL);
        overlay.rect(min, size, GRID, 1.0);
        for (i, series) in named.iter().enumerate() {
            let row = min + Vec2::new(pad, pad + i as f32 * line);
            let mid = row.y + 0.5 * line;
            overlay.line(
                Vec2::new(row.x, mid),
                Vec2::new(row.x + swatch, mid),
                series.color,
                2.0,
            );
            overlay.text(
                Vec2::new(row.x + swatch + pad, row.y),
                font,
                INK,
                &series.name,
            );
        }
    }

    /// All points with finite coordinates, over all series.
    fn finite_points(&self) -> impl Iterator<Item = (f32, f32)> + '_ {
        self.series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|p| p.0.is_finite() && p.1.is_finite())
    }
}

/// The part of the image a plot is drawn in, pixels.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    x0: f32,
    y0: f32,
    w: f32,
    h: f32,
}

/// Where a plot's parts go: its bounds, the plot area's edges, the text
/// sizes and the two axes.
struct PlotLayout {
    bounds: Bounds,
    left: f32,
    right: f32,
    top: f32,
    bottom: f32,
    font: f32,
    line: f32,
    pad: f32,
    xs: Axis,
    ys: Axis,
}

impl PlotLayout {
    /// The pixel of data point `(x, y)`.
    fn to_px(&self, x: f32, y: f32) -> Vec2 {
        Vec2::new(
            self.left + self.xs.fraction(f64::from(x)) * (self.right - self.left),
            self.bottom - self.ys.fraction(f64::from(y)) * (self.bottom - self.top),
        )
    }

    /// The grid lines with their tick labels, and the two axes.
    fn draw_grid(&self, overlay: &mut Overlay<'_>) {
        let (font, line, pad) = (self.font, self.line, self.pad);
        let (left, right, top, bottom) = (self.left, self.right, self.top, self.bottom);
        for &t in &self.xs.ticks {
            let px = (left + self.xs.fraction(t) * (right - left)).round() + 0.5;
            overlay.line(Vec2::new(px, top), Vec2::new(px, bottom), GRID, 1.0);
            let label = self.xs.label(t);
            let lw = text_width(font, &label);
            overlay.text(
                Vec2::new(px - 0.5 * lw, bottom + pad * 0.4),
                font,
                INK,
                &label,
            );
        }
        for &t in &self.ys.ticks {
            let py = (bottom - self.ys.fraction(t) * (bottom - top)).round() + 0.5;
            overlay.line(Vec2::new(left, py), Vec2::new(right, py), GRID, 1.0);
            let label = self.ys.label(t);
            let lw = text_width(font, &label);
            overlay.text(
                Vec2::new(left - pad * 0.5 - lw, py - 0.55 * line),
                font,
                INK,
                &label,
            );
        }
        let (ax, ay) = (left.round() + 0.5, bottom.round() + 0.5);
        overlay.line(Vec2::new(ax, top), Vec2::new(ax, ay), INK, 1.0);
        overlay.line(Vec2::new(ax, ay), Vec2::new(right, ay), INK, 1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(nice_step(0.7), 1.0);
        assert_eq!(nice_step(1.3), 2.0);
        assert_eq!(nice_step(3.0), 5.0);
        assert!((nice_step(0.013) - 0.02).abs() < 1e-6);
    }

    #[test]
    fn axis_widens_to_round_ticks_and_handles_degenerate_data() {
        let axis = Axis::covering([0.3, 9.2].into_iter(), 5);
        assert_eq!((axis.min, axis.max), (0.0, 10.0));
        assert_eq!(axis.ticks.len(), 6);
        let empty = Axis::covering(std::iter::empty(), 5);
        assert_eq!((empty.min, empty.max), (0.0, 1.0));
        let constant = Axis::covering([2.0, 2.0, f32::NAN].into_iter(), 4);
        assert!(constant.min < 2.0 && constant.max > 2.0);
        assert_eq!(constant.label(2.0), "2.0");
    }

    /// Issue 22: the torque series {0, -1e-45} of `snow-flat` with
    /// `alpha = 1e-45` made the padding underflow, the step 0 and the number
    /// of decimals infinite ("Formatting argument out of range").
    #[test]
    fn subnormal_series_get_a_finite_axis_and_short_labels() {
        let axis = Axis::covering([0.0, -1.0e-45].into_iter(), 4);
        assert!(axis.min <= -1.0e-45 && axis.max >= 0.0 && axis.min < axis.max);
        for &t in &axis.ticks {
            assert!(axis.label(t).len() < 16, "{}", axis.label(t));
        }
        assert_eq!(axis.label(0.0), "0");
        let constant = Axis::covering([1.0e-45; 3].into_iter(), 4);
        assert!(constant.min < constant.max);
        let plot = LinePlot {
            series: vec![Series {
                name: "torque".into(),
                points: vec![(0.0, 0.0), (0.1, -1.0e-45), (0.2, 0.0)],
                color: INK,
            }],
            ..LinePlot::default()
        };
        assert_eq!(plot.render(720, 360).dimensions(), (720, 360));
    }

    #[test]
    fn extreme_and_non_finite_series_get_finite_axes() {
        for values in [
            vec![f32::MAX, -f32::MAX],
            vec![f32::MAX; 2],
            vec![f32::INFINITY, f32::NAN, f32::NEG_INFINITY],
            vec![f32::MIN_POSITIVE, 0.0],
            vec![1.0e30, 1.0e30 + 1.0e24],
        ] {
            let axis = Axis::covering(values.iter().copied(), 5);
            assert!(axis.min.is_finite() && axis.max.is_finite(), "{values:?}");
            assert!(axis.min < axis.max, "{values:?}");
            assert!(axis.ticks.len() <= 2 * MAX_TICKS + 1, "{values:?}");
        }
        assert_eq!(
            Axis::covering([0.0, 3.0e7].into_iter(), 3).label(1.0e7),
            "1e7"
        );
    }

    fn any_series() -> impl proptest::strategy::Strategy<Value = Vec<f32>> {
        use proptest::prelude::*;
        let special = prop::sample::select(vec![
            0.0,
            -0.0,
            1.0e-45,
            -1.0e-45,
            f32::MIN_POSITIVE,
            f32::MAX,
            -f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ]);
        let value = prop_oneof![prop::num::f32::ANY, special, -1.0e3f32..1.0e3];
        prop_oneof![
            prop::collection::vec(value.clone(), 0..40),
            (value, 1..40usize).prop_map(|(v, n)| vec![v; n]),
        ]
    }

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config::with_cases(256))]

        #[test]
        fn any_series_gets_a_finite_covering_axis_with_distinct_labels(
            values in any_series(),
            ticks in 0..30usize,
        ) {
            let axis = Axis::covering(values.iter().copied(), ticks);
            proptest::prop_assert!(axis.min.is_finite() && axis.max.is_finite());
            proptest::prop_assert!(axis.min < axis.max);
            proptest::prop_assert!((2..=2 * MAX_TICKS + 1).contains(&axis.ticks.len()));
            for v in values.iter().filter(|v| v.is_finite()) {
                let v = f64::from(*v);
                proptest::prop_assert!(axis.min <= v && v <= axis.max, "{v} outside {axis:?}");
            }
            let labels: Vec<String> = axis.ticks.iter().map(|&t| axis.label(t)).collect();
            for pair in labels.windows(2) {
                proptest::prop_assert!(pair[0] != pair[1], "{labels:?}");
            }
            proptest::prop_assert!(labels.iter().all(|l| l.len() <= 24), "{labels:?}");
        }

        #[test]
        fn any_series_renders_without_panicking(
            xs in any_series(),
            ys in any_series(),
            width in 1..200u32,
            height in 1..120u32,
        ) {
            let plot = LinePlot {
                title: "t".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                series: vec![Series {
                    name: "s".into(),
                    points: xs.into_iter().zip(ys).collect(),
                    color: INK,
                }],
            };
            proptest::prop_assert_eq!(plot.render(width, height).dimensions(), (width, height));
        }
    }
}
