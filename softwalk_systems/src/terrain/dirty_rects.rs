//! [`DirtyRects`]: a list of grid rectangles, merged only where they overlap
//! or touch, so two feet far apart stay two small rectangles.

use engine::geom::GridRect;

/// A set of grid rectangles that changed, merged where they overlap or
/// touch (share an edge or a corner) into their bounding box, repeatedly, so
/// the merged rectangles never overlap or touch each other. Rectangles far
/// apart stay separate.
///
/// Adding is amortised `O(log n)`: a rectangle is appended, and the list is
/// merged ([`DirtyRects::merge`]) once the appended ones outnumber the merged
/// ones. Read [`DirtyRects::merged`] for the merged list;
/// [`DirtyRects::rects`] may still hold rectangles appended since the last
/// merge (overlapping ones included), which covers the same samples.
///
/// The merged order is deterministic: by first column, then first row.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DirtyRects {
    rects: Vec<GridRect>,
    /// How many rectangles the last merge left (the list's head).
    merged_len: usize,
}

/// True when `a` and `b` overlap or touch (their closures meet).
fn meet(a: &GridRect, b: &GridRect) -> bool {
    a.i0 <= b.i1 && b.i0 <= a.i1 && a.j0 <= b.j1 && b.j0 <= a.j1
}

/// Appended rectangles (beyond twice the merged ones) that trigger a merge.
const MERGE_SLACK: usize = 32;

impl DirtyRects {
    /// No rectangle.
    pub const fn new() -> Self {
        DirtyRects {
            rects: Vec::new(),
            merged_len: 0,
        }
    }

    /// Adds `rect` (ignored when empty).
    pub fn add(&mut self, rect: GridRect) {
        if rect.is_empty() {
            return;
        }
        self.rects.push(rect);
        if self.rects.len() > 2 * self.merged_len + MERGE_SLACK {
            self.merge();
        }
    }

    /// Adds every rectangle of `other`.
    pub fn extend(&mut self, other: &DirtyRects) {
        for &r in &other.rects {
            self.add(r);
        }
    }

    /// Merges the rectangles that overlap or touch, until none do: a sweep
    /// along X over the rectangles sorted by first column, repeated while
    /// a merged box meets another.
    pub fn merge(&mut self) {
        let mut out: Vec<GridRect> = Vec::with_capacity(self.rects.len());
        let mut active: Vec<usize> = Vec::new();
        loop {
            self.rects
                .sort_unstable_by_key(|r| (r.i0, r.j0, r.i1, r.j1));
            out.clear();
            active.clear();
            let mut merged_any = false;
            for &r in &self.rects {
                // Only merged rectangles reaching the current first column
                // can still meet this one or a later one.
                active.retain(|&k| out[k].i1 >= r.i0);
                match active.iter().rev().copied().find(|&k| meet(&out[k], &r)) {
                    Some(k) => {
                        out[k] = out[k].union(&r);
                        merged_any = true;
                    }
                    None => {
                        active.push(out.len());
                        out.push(r);
                    }
                }
            }
            std::mem::swap(&mut self.rects, &mut out);
            if !merged_any {
                break;
            }
        }
        self.merged_len = self.rects.len();
    }

    /// The merged rectangles (none overlaps or touches another).
    pub fn merged(&mut self) -> &[GridRect] {
        if self.merged_len != self.rects.len() {
            self.merge();
        }
        &self.rects
    }

    /// The rectangles, possibly with some appended since the last merge
    /// (they cover the same samples as [`DirtyRects::merged`]).
    pub fn rects(&self) -> &[GridRect] {
        &self.rects
    }

    /// Iterates [`DirtyRects::rects`].
    pub fn iter(&self) -> impl Iterator<Item = GridRect> + '_ {
        self.rects.iter().copied()
    }

    /// True when no rectangle is listed.
    pub fn is_empty(&self) -> bool {
        self.rects.is_empty()
    }

    /// Number of samples covered (merges first, so none counts twice).
    pub fn area(&mut self) -> usize {
        self.merged().iter().map(GridRect::area).sum()
    }

    /// The bounding box of every rectangle (empty when none).
    pub fn bounds(&self) -> GridRect {
        self.rects
            .iter()
            .fold(GridRect::EMPTY, |acc, r| acc.union(r))
    }

    /// True when `rect` overlaps any rectangle.
    pub fn intersects(&self, rect: &GridRect) -> bool {
        self.rects.iter().any(|r| !r.intersect(rect).is_empty())
    }

    /// True when `rect` (non-empty) lies inside one rectangle.
    pub fn contains_rect(&self, rect: &GridRect) -> bool {
        !rect.is_empty() && self.rects.iter().any(|r| r.intersect(rect) == *rect)
    }

    /// Removes every rectangle and returns them merged.
    pub fn take(&mut self) -> Vec<GridRect> {
        self.merged();
        self.merged_len = 0;
        std::mem::take(&mut self.rects)
    }

    /// Removes every rectangle, keeping the allocation.
    pub fn clear(&mut self) {
        self.rects.clear();
        self.merged_len = 0;
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
        assert_eq!(d.merged().len(), 2);
        assert_eq!(d.area(), 32);
        // Touching along an edge: merged.
        d.add(GridRect::new(4, 0, 6, 2));
        assert_eq!(d.merged().len(), 2);
        assert!(d.contains_rect(&GridRect::new(0, 0, 6, 2)));
        // A bridge merges all three into one box.
        d.add(GridRect::new(5, 3, 101, 101));
        assert_eq!(d.merged(), &[GridRect::new(0, 0, 104, 104)]);
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
        assert_eq!(d.merged(), &[GridRect::new(0, 0, 12, 12)]);
        assert!(d.intersects(&GridRect::new(5, 5, 6, 6)));
        assert!(!d.intersects(&GridRect::new(20, 20, 21, 21)));
    }

    #[test]
    fn many_scattered_rectangles_merge_into_a_disjoint_cover() {
        // A pseudo-random scatter: the merged list covers every sample of
        // every rectangle added, and no two merged rectangles meet.
        let mut d = DirtyRects::new();
        let mut added = Vec::new();
        let mut seed = 12345u64;
        for _ in 0..500 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (i, j) = ((seed >> 20) as usize % 2000, (seed >> 40) as usize % 2000);
            let r = GridRect::new(i, j, i + 8, j + 5);
            added.push(r);
            d.add(r);
        }
        let merged = d.merged().to_vec();
        for (k, a) in merged.iter().enumerate() {
            assert!(merged[k + 1..].iter().all(|b| !meet(a, b)));
        }
        for r in &added {
            assert!(merged.iter().any(|m| m.intersect(r) == *r));
        }
    }
}
