//! Closed-form recovery of a bent blade: a critically damped spring.
//!
//! `x(t) = (x0 + (v0 + w x0) t) e^{-w t}`. Blades are released at rest
//! (`v0 = 0`, the foot holds them until it leaves), so the remaining fraction of
//! the bend is `(1 + w t) e^{-w t}`. Evaluated from the release time, the result
//! does not depend on the step size.

/// Remaining fraction of the bend `(1 + w t) e^{-w t}` below which a blade is
/// treated as settled (snapped to its resting offset).
pub const SETTLED_FRACTION: f32 = 1e-5;

/// `w t` at which `(1 + w t) e^{-w t}` falls to 5 %.
pub const WT_FOR_5_PERCENT: f32 = 4.743_865;

/// `w t` at which `(1 + w t) e^{-w t}` falls to [`SETTLED_FRACTION`].
pub const WT_SETTLED: f32 = 14.236_628;

/// Fraction of the initial bend left after `elapsed` seconds with natural
/// angular frequency `omega` (rad/s); exactly 0 once settled.
#[inline]
pub fn remaining_fraction(omega: f32, elapsed: f32) -> f32 {
    let wt = omega * elapsed.max(0.0);
    if wt >= WT_SETTLED {
        return 0.0;
    }
    (1.0 + wt) * (-wt).exp()
}

/// Seconds until a blade with `omega` is within 5 % of its resting shape.
pub fn time_to_5_percent(omega: f32) -> f32 {
    WT_FOR_5_PERCENT / omega
}

/// Seconds until a blade with `omega` is settled (see [`SETTLED_FRACTION`]).
pub fn time_to_settle(omega: f32) -> f32 {
    WT_SETTLED / omega
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fraction(wt: f64) -> f64 {
        (1.0 + wt) * (-wt).exp()
    }

    #[test]
    fn constants_match_the_closed_form() {
        assert!((fraction(WT_FOR_5_PERCENT as f64) - 0.05).abs() < 1e-6);
        assert!((fraction(WT_SETTLED as f64) - SETTLED_FRACTION as f64).abs() < 1e-9);
    }

    #[test]
    fn decays_monotonically_from_one_to_zero() {
        assert_eq!(remaining_fraction(3.0, 0.0), 1.0);
        let mut last = 1.0;
        for i in 1..200 {
            let f = remaining_fraction(3.0, i as f32 * 0.03);
            assert!(f <= last, "step {i}");
            last = f;
        }
        assert_eq!(remaining_fraction(3.0, time_to_settle(3.0) + 0.01), 0.0);
        assert!((remaining_fraction(2.0, time_to_5_percent(2.0)) - 0.05).abs() < 1e-5);
    }
}
