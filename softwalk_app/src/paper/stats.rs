//! Summary statistics of measured series, shared by the paper report and the
//! integration tests so both compute a claim's figure the same way.

/// Mean of a series (0 for an empty one), accumulated in `f64`.
pub fn mean(xs: impl IntoIterator<Item = f32>) -> f32 {
    let (sum, n) = xs
        .into_iter()
        .fold((0.0f64, 0usize), |(s, n), x| (s + f64::from(x), n + 1));
    (sum / n.max(1) as f64) as f32
}

/// Median of a series (0 for an empty one): the middle value, or the mean
/// of the two middle ones. One outlier cannot move it.
pub fn median(xs: impl IntoIterator<Item = f32>) -> f32 {
    let mut v: Vec<f32> = xs.into_iter().collect();
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f32::total_cmp);
    let mid = v.len() / 2;
    if v.len() % 2 == 1 {
        v[mid]
    } else {
        0.5 * (v[mid - 1] + v[mid])
    }
}

/// Population standard deviation of a series.
pub fn std_dev(xs: &[f32]) -> f32 {
    let m = mean(xs.iter().copied());
    mean(xs.iter().map(|x| (x - m) * (x - m))).sqrt()
}

/// Largest minus smallest value (0 for an empty series).
pub fn peak_to_peak(xs: &[f32]) -> f32 {
    if xs.is_empty() {
        return 0.0;
    }
    let max = xs.iter().copied().fold(f32::MIN, f32::max);
    let min = xs.iter().copied().fold(f32::MAX, f32::min);
    max - min
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_outlier_does_not_move_the_median() {
        assert_eq!(median([3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median([4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median([20.0, 21.0, 1.0e6, 19.0, 22.0]), 21.0);
        assert_eq!(median([]), 0.0);
    }

    #[test]
    fn statistics_of_a_small_series() {
        let xs = [1.0, 3.0, 5.0, 7.0];
        assert_eq!(mean(xs), 4.0);
        assert!((std_dev(&xs) - 5.0f32.sqrt()).abs() < 1e-6);
        assert_eq!(peak_to_peak(&xs), 6.0);
        assert_eq!(mean([]), 0.0);
        assert_eq!(peak_to_peak(&[]), 0.0);
    }
}
