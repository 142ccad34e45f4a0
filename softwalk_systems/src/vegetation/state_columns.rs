//! The blades' states split by how often a deformation step touches them.
//!
//! Every push reads and writes a few fields of its blade (tread clock and
//! count, flags, the floor that decides most pushes); only a push whose field
//! takes the blade over, a new tread or a retirement touches the bends. The
//! two parts live in separate columns, so the common push touches one 16-byte
//! entry instead of the whole state. [`BladeState`] is the assembled view.

use super::blade::{Bend, BladeState};
use super::field_memo::BendSizes;

/// The part of a blade's state that every push reads and writes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PushState {
    /// Time of the latest push, or a negative value if never pushed.
    pub(crate) last_push: f64,
    /// [`BendSizes::floor`] of the blade's bends: a field below it loses to the
    /// recovering bend at any time. NaN until a push needs it (computed
    /// lazily: a blade whose bend changes each step rarely needs it).
    pub(crate) floor: f32,
    /// Number of separate treads so far.
    pub(crate) treads: u16,
    /// True once the blade broke.
    pub(crate) broken: bool,
    /// True while the blade is recovering.
    pub(crate) active: bool,
}

impl Default for PushState {
    fn default() -> Self {
        let state = BladeState::default();
        Self {
            last_push: state.last_push,
            floor: BendSizes::default().floor,
            treads: state.treads,
            broken: state.broken,
            active: state.active,
        }
    }
}

impl PushState {
    /// Records a push at `now`; true if it starts a new tread (the previous
    /// push is more than `tread_gap` seconds ago, or there was none).
    #[inline]
    pub(crate) fn count_tread(&mut self, now: f64, tread_gap: f32) -> bool {
        let new_tread = self.last_push < 0.0 || now - self.last_push > tread_gap as f64;
        if new_tread {
            self.treads = self.treads.saturating_add(1);
        }
        self.last_push = now;
        new_tread
    }
}

/// The bends of a blade's state and their sizes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct BendRecord {
    /// Bend at `anchor_time`.
    pub(crate) held: Bend,
    /// Permanent bend: zero for a healthy blade.
    pub(crate) rest: Bend,
    /// Time (patch clock) when `held` was set.
    pub(crate) anchor_time: f64,
    /// `held.size()`.
    pub(crate) held_size: f32,
    /// `rest.size()`.
    pub(crate) rest_size: f32,
}

/// Per-blade states in two columns: [`PushState`] and [`BendRecord`].
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct StateColumns {
    /// What every push touches.
    pub(crate) push: Vec<PushState>,
    /// What only pushes that change the bend, new treads and retirements touch.
    pub(crate) bends: Vec<BendRecord>,
}

impl StateColumns {
    /// `count` upright, never pushed blades.
    pub(crate) fn new(count: usize) -> Self {
        Self {
            push: vec![PushState::default(); count],
            bends: vec![BendRecord::default(); count],
        }
    }

    /// The whole state of blade `i`.
    #[inline]
    pub(crate) fn get(&self, i: usize) -> BladeState {
        let (p, b) = (&self.push[i], &self.bends[i]);
        BladeState {
            held: b.held,
            rest: b.rest,
            anchor_time: b.anchor_time,
            last_push: p.last_push,
            treads: p.treads,
            broken: p.broken,
            active: p.active,
        }
    }

    /// The ceiling of blade `i`'s recovering bend ([`BendSizes::ceiling`]).
    #[inline]
    pub(crate) fn ceiling(&self, i: usize) -> f32 {
        let b = &self.bends[i];
        BendSizes::ceiling_of(b.held_size, b.rest_size)
    }

    /// The floor of blade `i`'s recovering bend ([`BendSizes::floor`]),
    /// computed now if not known yet.
    #[inline]
    pub(crate) fn floor(&mut self, i: usize) -> f32 {
        let floor = &mut self.push[i].floor;
        if floor.is_nan() {
            let b = &self.bends[i];
            *floor = BendSizes::floor_of(&b.held, b.held_size, &b.rest, b.rest_size);
        }
        *floor
    }

    /// Records the sizes of blade `i`'s held and resting bends (after either
    /// changed); its floor is computed when first needed.
    #[inline]
    pub(crate) fn set_sizes(&mut self, i: usize, held_size: f32, rest_size: f32) {
        let b = &mut self.bends[i];
        b.held_size = held_size;
        b.rest_size = rest_size;
        // A healthy blade recovers to upright: no floor.
        self.push[i].floor = if rest_size > 0.0 { f32::NAN } else { 0.0 };
    }

    /// Recomputes blade `i`'s sizes from its bends.
    #[inline]
    pub(crate) fn resize(&mut self, i: usize) {
        let b = &self.bends[i];
        self.set_sizes(i, b.held.size(), b.rest.size());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn parts_assemble_the_whole_state() {
        let mut columns = StateColumns::new(3);
        assert_eq!(columns.get(1), BladeState::default());
        let held = Bend {
            mid: Vec3::new(0.1, -0.2, 0.0),
            tip: Vec3::new(0.2, -0.3, 0.1),
        };
        columns.bends[1].held = held;
        columns.bends[1].rest = held.scaled(0.3);
        columns.bends[1].anchor_time = 2.5;
        columns.resize(1);
        assert!(columns.push[1].count_tread(2.5, 0.2));
        assert!(!columns.push[1].count_tread(2.6, 0.2), "same tread");
        columns.push[1].broken = true;
        columns.push[1].active = true;
        let want = BladeState {
            held,
            rest: held.scaled(0.3),
            anchor_time: 2.5,
            last_push: 2.6,
            treads: 1,
            broken: true,
            active: true,
        };
        assert_eq!(columns.get(1), want);
        let sizes = BendSizes::new(&held, &held.scaled(0.3));
        assert!(columns.push[1].floor.is_nan(), "floor not computed yet");
        assert_eq!(columns.floor(1), sizes.floor);
        assert_eq!(columns.push[1].floor, sizes.floor, "kept");
        assert_eq!(columns.ceiling(1), sizes.ceiling());
        columns.bends[1].rest = Bend::ZERO;
        columns.resize(1);
        assert_eq!(columns.push[1].floor, 0.0, "healthy: no floor");
        assert_eq!(columns.get(0), BladeState::default(), "others untouched");
    }
}
