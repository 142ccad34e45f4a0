//! Prepared (cached) queries: the list of matching archetypes is kept and
//! extended incrementally when new archetypes appear.

use std::marker::PhantomData;

use super::error::EcsError;
use super::query::{Access, Query, QueryFilter, prepare_archetype};
use super::query_iter::{ArchetypeCursor, QueryBorrow, QueryIter};
use super::world::World;

/// A query whose matching archetypes are cached between runs.
///
/// ```
/// use engine::ecs::{PreparedQuery, World, With};
/// struct Speed(f32);
/// struct Fast;
/// let mut world = World::new();
/// world.spawn((Speed(1.0), Fast));
/// world.spawn((Speed(2.0),));
/// let mut fast = PreparedQuery::<&mut Speed, With<Fast>>::new();
/// for speed in fast.query_mut(&mut world) {
///     speed.0 *= 10.0;
/// }
/// let total: f32 = fast.query(&world).iter().map(|s| s.0).sum();
/// assert_eq!(total, 10.0);
/// ```
pub struct PreparedQuery<Q: Query, F: QueryFilter = ()> {
    world_id: Option<u64>,
    seen: usize,
    /// Matching archetypes (index in the world) with the query's column
    /// positions in each, so a run looks nothing up.
    matching: Vec<(u32, Q::State)>,
    accesses: Vec<Access>,
    /// Whether `Q` names a component twice with a `&mut` (checked once).
    aliasing: Result<(), EcsError>,
    _marker: PhantomData<fn() -> (Q, F)>,
}

impl<Q: Query, F: QueryFilter> Default for PreparedQuery<Q, F> {
    fn default() -> Self {
        Self::new()
    }
}

impl<Q: Query, F: QueryFilter> PreparedQuery<Q, F> {
    /// An empty cache; it fills on first use.
    pub fn new() -> Self {
        let mut accesses = Vec::new();
        Q::access(&mut accesses);
        PreparedQuery {
            world_id: None,
            seen: 0,
            matching: Vec::new(),
            aliasing: World::check_aliasing(&accesses),
            accesses,
            _marker: PhantomData,
        }
    }

    /// Scans only archetypes created since the last use (all of them if the world changed).
    fn update(&mut self, world: &World) {
        if self.world_id != Some(world.id()) {
            self.world_id = Some(world.id());
            self.seen = 0;
            self.matching.clear();
        }
        let archetypes = world.archetypes();
        for (index, archetype) in archetypes.iter().enumerate().skip(self.seen) {
            if let Some(state) = prepare_archetype::<Q, F>(archetype) {
                self.matching.push((index as u32, state));
            }
        }
        self.seen = archetypes.len();
    }

    /// Borrows the components and returns the query; panics with the borrow
    /// error's message on a conflict (see [`PreparedQuery::try_query`]).
    pub fn query<'q>(&'q mut self, world: &'q World) -> QueryBorrow<'q, Q, F> {
        self.try_query(world)
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// Borrows the components and returns the query, or the borrow conflict.
    pub fn try_query<'q>(
        &'q mut self,
        world: &'q World,
    ) -> Result<QueryBorrow<'q, Q, F>, EcsError> {
        self.update(world);
        let guard = world.acquire(&self.accesses)?;
        Ok(QueryBorrow::new(
            world.archetypes(),
            ArchetypeCursor::Cached(self.matching.iter()),
            guard,
        ))
    }

    /// Iterates with exclusive access to the world (no runtime borrow checks).
    ///
    /// # Panics
    /// If `Q` names a component twice with at least one `&mut`.
    pub fn query_mut<'q>(&'q mut self, world: &'q mut World) -> QueryIter<'q, Q, F> {
        if let Err(error) = &self.aliasing {
            panic!("{error}");
        }
        self.update(world);
        // SAFETY: `&mut World` excludes every other borrow, and `Q` does not
        // alias itself (checked above).
        unsafe {
            QueryIter::new(
                world.archetypes(),
                ArchetypeCursor::Cached(self.matching.iter()),
            )
        }
    }
}
