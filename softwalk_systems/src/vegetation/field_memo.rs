//! A blade's field remembered from one step to the next: a blade that only
//! feet standing still reach gets exactly the same field again.

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
    /// the blade's recovering bend.
    #[inline]
    pub(crate) fn takes_over(&self, state: &BladeState, now: f64, omega: f32) -> bool {
        (state.active && self.bend == state.held) || self.size >= state.bend_size_at(now, omega)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

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
        assert!(
            FieldMemo::new(held).takes_over(&state, 1.5, omega),
            "held on"
        );
        let weak = FieldMemo::new(held.scaled(0.5));
        assert!(
            !weak.takes_over(&state, 1.01, omega),
            "weaker than the fresh bend"
        );
        assert!(
            weak.takes_over(&state, 3.0, omega),
            "stronger than the recovered bend"
        );
        let idle = BladeState::default();
        assert!(weak.takes_over(&idle, 0.0, omega));
        assert!(!FieldMemo::default().takes_over(&state, 1.01, omega));
    }
}
