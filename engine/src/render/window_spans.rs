//! The samples a set of grid windows covers, row by row, each sample once
//! however the windows overlap.

use rayon::prelude::*;

use crate::geom::GridRect;

/// Windows of a grid, sorted by first column so that the columns they cover
/// in a row come out as merged spans without allocating per row.
#[derive(Debug)]
pub(crate) struct WindowSpans {
    /// The non-empty windows, by first column.
    windows: Vec<GridRect>,
    /// The smallest rectangle holding them all.
    bounds: GridRect,
}

impl WindowSpans {
    /// The spans of `windows` (empty ones are dropped).
    pub fn new(windows: impl IntoIterator<Item = GridRect>) -> WindowSpans {
        let mut windows: Vec<GridRect> = windows.into_iter().filter(|w| !w.is_empty()).collect();
        windows.sort_unstable_by_key(|w| w.i0);
        let bounds = windows.iter().fold(GridRect::EMPTY, |all, w| all.union(w));
        WindowSpans { windows, bounds }
    }

    /// The columns of row `j` that the windows cover, as sorted spans
    /// `[i0, i1)` that neither overlap nor touch.
    pub fn row(&self, j: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        let mut covering = self
            .windows
            .iter()
            .filter(move |w| j >= w.j0 && j < w.j1)
            .peekable();
        std::iter::from_fn(move || {
            let first = covering.next()?;
            let (i0, mut i1) = (first.i0, first.i1);
            while let Some(next) = covering.next_if(|w| w.i0 <= i1) {
                i1 = i1.max(next.i1);
            }
            Some((i0, i1))
        })
    }

    /// Sets each element of `buf` (rows of `width`) that the windows cover
    /// to `value(column, row)`, rows in parallel.
    pub fn par_fill<T: Send>(
        &self,
        buf: &mut [T],
        width: usize,
        value: impl Fn(usize, usize) -> T + Sync,
    ) {
        let rows = self.bounds;
        let j1 = rows.j1.min(buf.len() / width.max(1));
        if rows.is_empty() || rows.j0 >= j1 {
            return;
        }
        // Only the rows the windows span go to the pool, so a small window
        // is still split across threads.
        buf[rows.j0 * width..j1 * width]
            .par_chunks_mut(width)
            .enumerate()
            .for_each(|(dj, row)| {
                let j = rows.j0 + dj;
                for (i0, i1) in self.row(j) {
                    let i1 = i1.min(width);
                    for (i, out) in (i0.min(i1)..i1).zip(&mut row[i0.min(i1)..i1]) {
                        *out = value(i, j);
                    }
                }
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_windows_give_each_column_of_a_row_once() {
        let spans = WindowSpans::new([
            GridRect::new(5, 0, 9, 4),
            GridRect::new(0, 2, 3, 6),
            GridRect::new(2, 3, 6, 5),
            GridRect::new(12, 3, 14, 8),
            GridRect::new(20, 1, 20, 9),
        ]);
        let row = |j| spans.row(j).collect::<Vec<_>>();
        assert_eq!(row(0), vec![(5, 9)]);
        assert_eq!(row(3), vec![(0, 9), (12, 14)]);
        assert_eq!(row(5), vec![(0, 3), (12, 14)]);
        assert_eq!(row(8), vec![]);
        assert_eq!(spans.bounds, GridRect::new(0, 0, 14, 8));
        assert!(WindowSpans::new([]).bounds.is_empty());
    }
}
