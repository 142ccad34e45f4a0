//! Query borrows and iterators: sequential and parallel walks over matching archetypes.

use std::marker::PhantomData;

use rayon::prelude::*;

use super::archetype::Archetype;
use super::borrow::BorrowFlag;
use super::query::{Fetch, Query, QueryFilter, prepare_archetype};

/// Runtime borrows held by a live query, released on drop.
pub(crate) struct BorrowGuard<'w> {
    pub(crate) held: Vec<(&'w BorrowFlag, bool)>,
}

impl Drop for BorrowGuard<'_> {
    fn drop(&mut self) {
        for (flag, mutable) in &self.held {
            flag.release(*mutable);
        }
    }
}

/// Which archetypes a query visits, with the query's state `S` for each.
pub(crate) enum ArchetypeCursor<'q, S> {
    /// Every archetype in the range, preparing each (and skipping those
    /// that do not match).
    Scan(std::ops::Range<usize>),
    /// A precomputed list of matching archetypes and their states (from a
    /// prepared query).
    Cached(std::slice::Iter<'q, (u32, S)>),
}

// Manual impl: a derive would require `S: Clone`.
impl<S> Clone for ArchetypeCursor<'_, S> {
    fn clone(&self) -> Self {
        match self {
            ArchetypeCursor::Scan(range) => ArchetypeCursor::Scan(range.clone()),
            ArchetypeCursor::Cached(list) => ArchetypeCursor::Cached(list.clone()),
        }
    }
}

/// A live query on a `&World`: holds the runtime borrows of the components it
/// accesses until dropped. Iterate with [`QueryBorrow::iter`] or
/// [`QueryBorrow::par_for_each`].
pub struct QueryBorrow<'w, Q: Query, F: QueryFilter = ()> {
    archetypes: &'w [Archetype],
    cursor: ArchetypeCursor<'w, Q::State>,
    _guard: BorrowGuard<'w>,
    _marker: PhantomData<fn() -> (Q, F)>,
}

impl<'w, Q: Query, F: QueryFilter> QueryBorrow<'w, Q, F> {
    /// `guard` must hold every borrow listed by `Q::access`.
    pub(crate) fn new(
        archetypes: &'w [Archetype],
        cursor: ArchetypeCursor<'w, Q::State>,
        guard: BorrowGuard<'w>,
    ) -> Self {
        QueryBorrow {
            archetypes,
            cursor,
            _guard: guard,
            _marker: PhantomData,
        }
    }

    /// Iterates the matching entities in archetype creation order, then row order.
    pub fn iter(&mut self) -> QueryIter<'_, Q, F> {
        // SAFETY: `self` holds the borrows of `Q` and is mutably borrowed for
        // the iterator's lifetime, so no second iterator can alias its items.
        unsafe { QueryIter::new(self.archetypes, self.cursor.clone()) }
    }

    /// Calls `f` on every matching entity, in parallel batches of `batch_size` rows
    /// (at least 1) on the rayon pool. Batches never span archetypes. The
    /// result does not depend on the thread count as long as `f` only writes
    /// through its item.
    pub fn par_for_each(&mut self, batch_size: usize, f: impl Fn(Q::Item<'_>) + Send + Sync) {
        self.iter().par_for_each(batch_size, f);
    }
}

impl<'a, 'w, Q: Query, F: QueryFilter> IntoIterator for &'a mut QueryBorrow<'w, Q, F> {
    type Item = Q::Item<'a>;
    type IntoIter = QueryIter<'a, Q, F>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// Iterator over a query's items: archetypes in creation order, rows in order.
pub struct QueryIter<'q, Q: Query, F: QueryFilter = ()> {
    archetypes: &'q [Archetype],
    cursor: ArchetypeCursor<'q, Q::State>,
    current: Option<Q::Fetch<'q>>,
    remaining: usize,
    _filter: PhantomData<fn() -> F>,
}

impl<'q, Q: Query, F: QueryFilter> QueryIter<'q, Q, F> {
    /// # Safety
    /// The caller holds the borrows listed by `Q::access` (or `&mut World`)
    /// for `'q`, and no other live iterator or reference aliases what `Q` writes.
    pub(crate) unsafe fn new(
        archetypes: &'q [Archetype],
        cursor: ArchetypeCursor<'q, Q::State>,
    ) -> Self {
        QueryIter {
            archetypes,
            cursor,
            current: None,
            remaining: 0,
            _filter: PhantomData,
        }
    }

    /// A fetch over `archetype` (with the query's `state` for it) and its row count.
    #[inline]
    fn fetch(archetype: &'q Archetype, state: Q::State) -> (usize, Q::Fetch<'q>) {
        // SAFETY: `state` was prepared for this archetype (by the cursor's
        // scan, or by the prepared query for this world), and the borrows
        // are held for `'q` by the contract of `QueryIter::new`.
        (archetype.len(), unsafe { Q::fetch(archetype, state) })
    }

    /// The next matching archetype: its row count and a fetch over it.
    /// Empty archetypes are not skipped: they yield no rows.
    #[inline]
    fn next_archetype(&mut self) -> Option<(usize, Q::Fetch<'q>)> {
        let archetypes = self.archetypes;
        let (archetype, state) = match &mut self.cursor {
            ArchetypeCursor::Scan(range) => range.find_map(|index| {
                let archetype = &archetypes[index];
                prepare_archetype::<Q, F>(archetype).map(|state| (archetype, state))
            })?,
            ArchetypeCursor::Cached(list) => {
                let &(index, state) = list.next()?;
                (&archetypes[index as usize], state)
            }
        };
        Some(Self::fetch(archetype, state))
    }

    /// Calls `f` on every remaining item, in parallel batches of `batch_size` rows
    /// (at least 1) on the rayon pool. Batches never span archetypes.
    pub fn par_for_each(mut self, batch_size: usize, f: impl Fn(Q::Item<'q>) + Send + Sync) {
        let batch_size = batch_size.max(1);
        let mut batches: Vec<(Q::Fetch<'q>, usize)> = Vec::new();
        let mut split = |mut fetch: Q::Fetch<'q>, mut rows: usize| {
            while rows > batch_size {
                let (head, tail) = fetch.split_at(batch_size);
                batches.push((head, batch_size));
                fetch = tail;
                rows -= batch_size;
            }
            if rows > 0 {
                batches.push((fetch, rows));
            }
        };
        if let Some(fetch) = self.current.take() {
            split(fetch, self.remaining);
        }
        while let Some((rows, fetch)) = self.next_archetype() {
            split(fetch, rows);
        }
        batches
            .into_par_iter()
            .for_each(|(fetch, rows)| fetch.fold_rows(rows, (), |(), item| f(item)));
    }
}

impl<'q, Q: Query, F: QueryFilter> Iterator for QueryIter<'q, Q, F> {
    type Item = Q::Item<'q>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.remaining > 0 {
                self.remaining -= 1;
                return self.current.as_mut().map(Fetch::next_item);
            }
            let (rows, fetch) = self.next_archetype()?;
            self.current = Some(fetch);
            self.remaining = rows;
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.remaining, None)
    }

    fn fold<B, G>(mut self, init: B, mut g: G) -> B
    where
        G: FnMut(B, Self::Item) -> B,
    {
        let mut acc = init;
        if let Some(fetch) = self.current.take() {
            acc = fetch.fold_rows(self.remaining, acc, &mut g);
        }
        let archetypes = self.archetypes;
        let mut visit = |acc, archetype, state| {
            let (rows, fetch) = Self::fetch(archetype, state);
            fetch.fold_rows(rows, acc, &mut g)
        };
        // One loop per cursor kind, so the walk does not re-dispatch per archetype.
        match self.cursor {
            ArchetypeCursor::Cached(list) => list.fold(acc, |acc, &(index, state)| {
                visit(acc, &archetypes[index as usize], state)
            }),
            ArchetypeCursor::Scan(range) => range.fold(acc, |acc, index| {
                let archetype = &archetypes[index];
                match prepare_archetype::<Q, F>(archetype) {
                    Some(state) => visit(acc, archetype, state),
                    None => acc,
                }
            }),
        }
    }
}
