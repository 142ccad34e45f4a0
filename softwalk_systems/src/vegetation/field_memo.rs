//! A blade's field remembered from one step to the next: a blade that only
//! feet standing still reach gets exactly the same field again.

use glam::Vec3;

use super::blade::{Bend, BladeState};

/// The field of one step's feet on a blade.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct FieldMemo {
    /// The bend the field pushes the blade to.
    pub(crate) bend: Bend,
    /// `bend.size()`.
    pub(crate) size: f32,
}

impl FieldMemo {
    /// A freshly computed field (the scalar reference of the batched field).
    #[cfg(test)]
    pub(crate) fn new(bend: Bend) -> Self {
        Self {
            bend,
            size: bend.size(),
        }
    }

    /// True if this field takes the blade over at `now` (re-anchors it): it is
    /// the field already holding the blade, or at least as large (by size) as
    /// the blade's recovering bend, which recovers with `omega()` (rad/s).
    /// `ceiling` and `floor()` ([`BendSizes`]) bound the recovering bend's
    /// size at all times: a field outside the bounds is decided without
    /// evaluating the recovery (with the same answer); the floor is asked
    /// for only when the field is below the ceiling.
    #[inline]
    pub(crate) fn takes_over(
        &self,
        state: &BladeState,
        ceiling: f32,
        floor: impl FnOnce() -> f32,
        now: f64,
        omega: impl FnOnce() -> f32,
    ) -> bool {
        if state.active && self.bend == state.held || self.size >= ceiling {
            return true;
        }
        self.size >= floor() && self.size >= state.bend_size_at(now, omega())
    }
}

/// Sizes (`|mid| + |tip|`) of a blade's held and resting bends, kept beside
/// its state, and a floor under the size of its recovering bend.
///
/// The recovering bend is `rest + (held - rest) k` with `k` in `[0, 1]`: each
/// of its points lies on the segment from the resting to the held point, so
/// its size is at most the larger of the two sizes (the ceiling) and at least
/// the summed distances from the origin to the two segments (the floor).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct BendSizes {
    /// Size of `BladeState::held`.
    pub(crate) held: f32,
    /// Size of `BladeState::rest`.
    pub(crate) rest: f32,
    /// Never above the size of the blade's bend at any time from its anchor.
    pub(crate) floor: f32,
}

impl BendSizes {
    /// Relative margin of the bounds over the rounding of the recovering
    /// bend (a few units in the last place, far below this).
    const MARGIN: f32 = 1.0 / 16384.0;

    #[cfg(test)]
    /// The sizes of `held` and `rest` and the floor between them.
    pub(crate) fn new(held: &Bend, rest: &Bend) -> Self {
        Self::with_sizes(held, held.size(), rest, rest.size())
    }

    #[cfg(test)]
    /// [`BendSizes::new`] with the sizes of `held` and `rest` already known.
    #[inline]
    pub(crate) fn with_sizes(held: &Bend, held_size: f32, rest: &Bend, rest_size: f32) -> Self {
        Self {
            held: held_size,
            rest: rest_size,
            floor: Self::floor_of(held, held_size, rest, rest_size),
        }
    }

    /// The floor of the bends `held` and `rest` of sizes `held_size` and
    /// `rest_size`.
    #[inline]
    pub(crate) fn floor_of(held: &Bend, held_size: f32, rest: &Bend, rest_size: f32) -> f32 {
        // A healthy blade recovers to upright: no floor.
        let exact = if rest_size > 0.0 {
            segment_distance(rest.mid, held.mid) + segment_distance(rest.tip, held.tip)
        } else {
            0.0
        };
        (exact - (held_size + rest_size) * Self::MARGIN).max(0.0)
    }

    #[cfg(test)]
    /// Never below the size of the blade's bend at any time from its anchor.
    #[inline]
    pub(crate) fn ceiling(&self) -> f32 {
        Self::ceiling_of(self.held, self.rest)
    }

    /// The ceiling of bends of sizes `held_size` and `rest_size`.
    #[inline]
    pub(crate) fn ceiling_of(held_size: f32, rest_size: f32) -> f32 {
        held_size.max(rest_size) * (1.0 + Self::MARGIN)
    }
}

/// Distance from the origin to the segment from `a` to `b`.
fn segment_distance(a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let len_sq = ab.length_squared();
    let t = if len_sq > 0.0 {
        (-a.dot(ab) / len_sq).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_on_or_stronger_fields_take_over() {
        let held = Bend {
            mid: Vec3::new(0.1, -0.2, 0.0),
            tip: Vec3::new(0.2, -0.3, 0.05),
        };
        let state = BladeState {
            held,
            anchor_time: 1.0,
            active: true,
            ..BladeState::default()
        };
        let omega = 2.5;
        let sizes = BendSizes::new(&held, &Bend::ZERO);
        assert_eq!(sizes.floor, 0.0, "a healthy blade recovers to upright");
        let takes_over = |m: FieldMemo, s: &BladeState, now: f64| {
            m.takes_over(s, sizes.ceiling(), || sizes.floor, now, || omega)
        };
        assert!(takes_over(FieldMemo::new(held), &state, 1.5), "held on");
        let weak = FieldMemo::new(held.scaled(0.5));
        assert!(
            !takes_over(weak, &state, 1.01),
            "weaker than the fresh bend"
        );
        assert!(
            takes_over(weak, &state, 3.0),
            "stronger than the recovered bend"
        );
        let idle = BladeState::default();
        assert!(takes_over(weak, &idle, 0.0));
        assert!(!takes_over(FieldMemo::default(), &state, 1.01));
        let stronger = FieldMemo::new(held.scaled(1.5));
        assert!(takes_over(stronger, &state, 1.0), "above the ceiling");
    }

    /// The recovering bend's size stays between the floor and the ceiling,
    /// healthy or broken, at any time after the anchor.
    #[test]
    fn size_bounds_hold_the_recovering_bend() {
        let held = Bend {
            mid: Vec3::new(0.13, -0.21, 0.02),
            tip: Vec3::new(0.27, -0.33, 0.05),
        };
        let rest = Bend {
            mid: Vec3::new(-0.05, -0.1, 0.2),
            tip: Vec3::new(0.1, -0.4, 0.1),
        };
        for (rest, broken) in [(Bend::ZERO, false), (rest, true), (held.scaled(0.7), true)] {
            let state = BladeState {
                held,
                rest,
                anchor_time: 2.0,
                active: true,
                broken,
                ..BladeState::default()
            };
            let sizes = BendSizes::new(&held, &rest);
            assert!(sizes.floor > 0.0 || !broken, "{sizes:?}");
            for k in 0..2000 {
                let now = 2.0 + k as f64 * 1e-4 * (1.0 + k as f64);
                let size = state.bend_size_at(now, 3.0);
                assert!(size <= sizes.ceiling(), "{size} at {now}");
                assert!(size >= sizes.floor, "{size} at {now}");
            }
            let settled = BladeState {
                active: false,
                ..state
            };
            assert!(settled.bend_size_at(9.0, 3.0) >= sizes.floor);
        }
    }
}
