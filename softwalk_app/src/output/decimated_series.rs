//! A time series kept in bounded memory for plotting: the lowest and the
//! highest sample of each of at most [`MAX_BUCKETS`] equal runs of samples.

/// Most buckets a series keeps; more than the pixel columns of a plot, so a
/// decimated curve draws like the full one (every column's extremes are kept).
pub(super) const MAX_BUCKETS: usize = 1024;

/// One sample: time and value.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sample {
    t: f64,
    v: f32,
}

/// A run of consecutive samples: how many, their finite extremes, and whether
/// a non-finite value (which breaks the curve) was among them.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Bucket {
    count: u64,
    /// The lowest and the highest finite sample (the earlier one on ties).
    extremes: Option<(Sample, Sample)>,
    /// The last sample's time, where a break in the curve is drawn.
    last_t: f64,
    broken: bool,
}

impl Bucket {
    fn of(t: f64, v: f32) -> Self {
        Bucket {
            count: 1,
            extremes: v.is_finite().then_some((Sample { t, v }, Sample { t, v })),
            last_t: t,
            broken: !v.is_finite(),
        }
    }

    /// This bucket followed by `next`, as one bucket.
    fn merge(self, next: Bucket) -> Bucket {
        let extremes = match (self.extremes, next.extremes) {
            (Some((lo, hi)), Some((nlo, nhi))) => Some((
                if nlo.v < lo.v { nlo } else { lo },
                if nhi.v > hi.v { nhi } else { hi },
            )),
            (a, b) => a.or(b),
        };
        Bucket {
            count: self.count + next.count,
            extremes,
            last_t: next.last_t,
            broken: self.broken || next.broken,
        }
    }
}

/// A series of `(t, value)` samples in time order, summarised in at most
/// [`MAX_BUCKETS`] buckets of equal sample counts: while there are fewer
/// samples than buckets every sample is kept as it is; then each time the
/// buckets are full, neighbours are merged pairwise and the bucket width doubles.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct DecimatedSeries {
    buckets: Vec<Bucket>,
    /// Samples per full bucket.
    width: u64,
}

impl Default for DecimatedSeries {
    fn default() -> Self {
        DecimatedSeries {
            buckets: Vec::new(),
            width: 1,
        }
    }
}

impl DecimatedSeries {
    /// Adds the sample at time `t` (not before the previous one).
    pub(super) fn push(&mut self, t: f64, v: f32) {
        let sample = Bucket::of(t, v);
        match self.buckets.last_mut() {
            Some(last) if last.count < self.width => *last = last.merge(sample),
            _ => {
                if self.buckets.len() == MAX_BUCKETS {
                    self.halve();
                }
                self.buckets.push(sample);
            }
        }
    }

    /// Merges neighbouring buckets pairwise, doubling the bucket width.
    fn halve(&mut self) {
        let merged: Vec<Bucket> = self
            .buckets
            .chunks(2)
            .map(|pair| match pair {
                [a, b] => a.merge(*b),
                [a] => *a,
                _ => unreachable!("chunks(2) yields one or two buckets"),
            })
            .collect();
        self.buckets.clear();
        self.buckets.extend(merged);
        self.width *= 2;
    }

    /// The points to draw, in time order: each bucket's lowest and highest
    /// sample (one point when they are the same sample), then a non-finite
    /// point where the bucket held a non-finite value, which breaks the curve.
    pub(super) fn points(&self) -> Vec<(f32, f32)> {
        let mut points = Vec::with_capacity(2 * self.buckets.len());
        for b in &self.buckets {
            if let Some((lo, hi)) = b.extremes {
                let (first, second) = if hi.t < lo.t { (hi, lo) } else { (lo, hi) };
                points.push((first.t as f32, first.v));
                if second != first {
                    points.push((second.t as f32, second.v));
                }
            }
            if b.broken {
                points.push((b.last_t as f32, f32::NAN));
            }
        }
        points
    }

    /// Samples pushed so far.
    #[cfg(test)]
    fn len(&self) -> u64 {
        self.buckets.iter().map(|b| b.count).sum()
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn short_series_are_kept_sample_for_sample() {
        let mut s = DecimatedSeries::default();
        let values = [1.0, f32::NAN, 3.0, 2.0];
        for (k, v) in values.iter().enumerate() {
            s.push(k as f64, *v);
        }
        let points = s.points();
        assert_eq!(points.len(), 4);
        assert_eq!(points[0], (0.0, 1.0));
        assert!(points[1].1.is_nan());
        assert_eq!(&points[2..], [(2.0, 3.0), (3.0, 2.0)]);
    }

    #[test]
    fn a_million_samples_stay_within_the_bucket_bound_and_keep_the_extremes() {
        let mut s = DecimatedSeries::default();
        for k in 0..1_000_000u64 {
            let v = if k == 777_777 {
                5.0
            } else {
                (k as f32 * 0.01).sin()
            };
            s.push(k as f64 * 0.01, v);
        }
        assert!(s.buckets.len() <= MAX_BUCKETS);
        assert!(s.buckets.capacity() <= 2 * MAX_BUCKETS);
        assert_eq!(s.len(), 1_000_000);
        let points = s.points();
        assert!(points.len() <= 2 * MAX_BUCKETS);
        let top = points.iter().map(|p| p.1).fold(f32::MIN, f32::max);
        assert_eq!(top, 5.0);
        assert!(points.windows(2).all(|w| w[0].0 <= w[1].0), "time order");
    }

    proptest! {
        #[test]
        fn extremes_and_breaks_survive_decimation(
            values in prop::collection::vec(
                prop_oneof![8 => -1.0e3f32..1.0e3, 1 => Just(f32::NAN), 1 => Just(f32::INFINITY)],
                0..5000,
            ),
        ) {
            let mut s = DecimatedSeries::default();
            for (k, v) in values.iter().enumerate() {
                s.push(k as f64, *v);
            }
            prop_assert!(s.buckets.len() <= MAX_BUCKETS);
            prop_assert_eq!(s.len(), values.len() as u64);
            let points = s.points();
            let finite = |p: &&(f32, f32)| p.1.is_finite();
            let lo = values.iter().copied().filter(|v| v.is_finite()).fold(f32::INFINITY, f32::min);
            let hi = values.iter().copied().filter(|v| v.is_finite()).fold(f32::NEG_INFINITY, f32::max);
            prop_assert_eq!(points.iter().filter(finite).map(|p| p.1).fold(f32::INFINITY, f32::min), lo);
            prop_assert_eq!(points.iter().filter(finite).map(|p| p.1).fold(f32::NEG_INFINITY, f32::max), hi);
            let any_break = values.iter().any(|v| !v.is_finite());
            prop_assert_eq!(points.iter().any(|p| !p.1.is_finite()), any_break);
        }
    }
}
