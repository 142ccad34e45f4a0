/// A half-open rectangle of grid sample indices: `i0..i1` along X, `j0..j1` along Z.
///
/// Used for dirty windows: what a foot touched this step, what a BVH refit or a
/// render patch must redo.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GridRect {
    /// First column (inclusive).
    pub i0: usize,
    /// First row (inclusive).
    pub j0: usize,
    /// Last column (exclusive).
    pub i1: usize,
    /// Last row (exclusive).
    pub j1: usize,
}

impl GridRect {
    /// The empty rectangle.
    pub const EMPTY: GridRect = GridRect {
        i0: 0,
        j0: 0,
        i1: 0,
        j1: 0,
    };

    /// A rectangle from its corners (half-open).
    pub fn new(i0: usize, j0: usize, i1: usize, j1: usize) -> Self {
        GridRect { i0, j0, i1, j1 }
    }

    /// True when the rectangle holds no sample.
    pub fn is_empty(&self) -> bool {
        self.i0 >= self.i1 || self.j0 >= self.j1
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.i1.saturating_sub(self.i0)
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.j1.saturating_sub(self.j0)
    }

    /// Number of samples inside.
    pub fn area(&self) -> usize {
        self.width() * self.height()
    }

    /// The smallest rectangle holding both (an empty side is ignored).
    pub fn union(&self, other: &GridRect) -> GridRect {
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        GridRect {
            i0: self.i0.min(other.i0),
            j0: self.j0.min(other.j0),
            i1: self.i1.max(other.i1),
            j1: self.j1.max(other.j1),
        }
    }

    /// The overlap of both (possibly empty).
    pub fn intersect(&self, other: &GridRect) -> GridRect {
        let r = GridRect {
            i0: self.i0.max(other.i0),
            j0: self.j0.max(other.j0),
            i1: self.i1.min(other.i1),
            j1: self.j1.min(other.j1),
        };
        if r.is_empty() { GridRect::EMPTY } else { r }
    }

    /// Grown by `margin` samples on every side, clipped to a `nx` x `nz` grid.
    pub fn expand(&self, margin: usize, nx: usize, nz: usize) -> GridRect {
        if self.is_empty() {
            return GridRect::EMPTY;
        }
        GridRect {
            i0: self.i0.saturating_sub(margin),
            j0: self.j0.saturating_sub(margin),
            i1: (self.i1 + margin).min(nx),
            j1: (self.j1 + margin).min(nz),
        }
    }

    /// True when sample `(i, j)` lies inside.
    pub fn contains(&self, i: usize, j: usize) -> bool {
        i >= self.i0 && i < self.i1 && j >= self.j0 && j < self.j1
    }

    /// Iterates the `(i, j)` samples inside, row by row.
    pub fn iter(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let (i0, i1) = (self.i0, self.i1);
        (self.j0..self.j1).flat_map(move |j| (i0..i1).map(move |i| (i, j)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_intersect_expand() {
        let a = GridRect::new(2, 2, 5, 5);
        let b = GridRect::new(4, 0, 8, 3);
        assert_eq!(a.union(&b), GridRect::new(2, 0, 8, 5));
        assert_eq!(a.intersect(&b), GridRect::new(4, 2, 5, 3));
        assert!(a.intersect(&GridRect::new(6, 6, 7, 7)).is_empty());
        assert_eq!(a.expand(3, 6, 100), GridRect::new(0, 0, 6, 8));
        assert_eq!(GridRect::EMPTY.union(&a), a);
        assert_eq!(a.iter().count(), a.area());
    }
}
