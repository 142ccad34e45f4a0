//! [`DirtyRects`]: a list of grid rectangles, merged only where they overlap
//! or touch, so two feet far apart stay two small rectangles.

use engine::geom::GridRect;

/// A set of grid rectangles that changed. Adding a rectangle merges it with
/// every listed rectangle it overlaps or touches (shares an edge or a corner
/// with) into their bounding box, repeatedly, so the listed rectangles never
/// overlap or touch each other. Rectangles far apart stay separate.
///
/// The order is deterministic: the order of addition, a merged rectangle
/// taking the place at the end of the list.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DirtyRects {
    rects: Vec<GridRect>,
}

/// True when `a` and `b` overlap or touch (their closures meet).
fn meet(a: &GridRect, b: &GridRect) -> bool {
    a.i0 <= b.i1 && b.i0 <= a.i1 && a.j0 <= b.j1 && b.j0 <= a.j1
}

impl DirtyRects {
    /// No rectangle.
    pub const fn new() -> Self {
        DirtyRects { rects: Vec::new() }
    }

    /// Adds `rect` (ignored when empty), merging it with what it meets.
    pub fn add(&mut self, rect: GridRect) {
        if rect.is_empty() {
            return;
        }
        let mut merged = rect;
        while let Some(k) = self.rects.iter().position(|r| meet(r, &merged)) {
            merged = merged.union(&self.rects.remove(k));
        }
        self.rects.push(merged);
    }

    /// Adds every rectangle of `other`.
    pub fn extend(&mut self, other: &DirtyRects) {
        for &r in &other.rects {
            self.add(r);
        }
    }

    /// The rectangles (none overlaps or touches another).
    pub fn rects(&self) -> &[GridRect] {
        &self.rects
    }

    /// Iterates the rectangles.
    pub fn iter(&self) -> impl Iterator<Item = GridRect> + '_ {
        self.rects.iter().copied()
    }

    /// True when no rectangle is listed.
    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// Number of samples covered (the rectangles do not overlap).
    pub fn area(&self) -> usize {
        self.rects.iter().map(GridRect::area).sum()
    }

    /// The bounding box of every rectangle (empty when none).
    pub fn bounds(&self) -> GridRect {
        self.rects
            .iter()
            .fold(GridRect::EMPTY, |acc, r| acc.union(r))
    }

    /// True when `rect` meets (overlaps) any listed rectangle.
    pub fn intersects(&self, rect: &GridRect) -> bool {
        self.rects.iter().any(|r| !r.intersect(rect).is_empty())
    }

    /// True when `rect` (non-empty) lies inside one listed rectangle.
    pub fn contains_rect(&self, rect: &GridRect) -> bool {
        !rect.is_empty() && self.rects.iter().any(|r| r.intersect(rect) == *rect)
    }

    /// Removes every rectangle and returns them.
    pub fn take(&mut self) -> Vec<GridRect> {
        std::mem::take(&mut self.rects)
    }

    /// Removes every rectangle, keeping the allocation.
    pub fn clear(&mut self) {
        self.rects.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_rectangles_stay_apart_and_touching_ones_merge() {
        let mut d = DirtyRects::new();
        d.add(GridRect::new(0, 0, 4, 4));
        d.add(GridRect::new(100, 100, 104, 104));
        d.add(GridRect::EMPTY);
        assert_eq!(d.rects().len(), 2);
        assert_eq!(d.area(), 32);
        // Touching along an edge: merged.
        d.add(GridRect::new(4, 0, 6, 2));
        assert_eq!(d.rects().len(), 2);
        assert!(d.contains_rect(&GridRect::new(0, 0, 6, 2)));
        // A bridge merges all three into one box.
        d.add(GridRect::new(5, 3, 101, 101));
        assert_eq!(d.rects(), &[GridRect::new(0, 0, 104, 104)]);
        assert_eq!(d.bounds(), GridRect::new(0, 0, 104, 104));
        assert_eq!(d.take().len(), 1);
        assert!(d.is_empty());
    }

    #[test]
    fn a_merged_box_absorbs_what_it_now_overlaps() {
        let mut d = DirtyRects::new();
        d.add(GridRect::new(0, 10, 2, 12));
        d.add(GridRect::new(10, 0, 12, 2));
        // Meets the second only; the merged box then covers the first too.
        d.add(GridRect::new(0, 0, 11, 11));
        assert_eq!(d.rects(), &[GridRect::new(0, 0, 12, 12)]);
        assert!(d.intersects(&GridRect::new(5, 5, 6, 6)));
        assert!(!d.intersects(&GridRect::new(20, 20, 21, 21)));
    }
}
