//! The `World`: entities, their components in archetype tables, and resources.

use std::any::TypeId;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

use super::archetype::{Archetype, ArchetypeColumn, ComponentType, Edge};
use super::borrow::{BorrowFlag, Ref, RefMut, SharedCell};
use super::bundle::{Bundle, Component};
use super::command_queue::CommandQueue;
use super::entity::{Entities, Entity, Location};
use super::error::{BorrowConflict, BorrowTarget, CommandsError, EcsError};
use super::events::Events;
use super::query::{Access, Query, QueryFilter};
use super::query_iter::{ArchetypeCursor, BorrowGuard, QueryBorrow, QueryIter};
use super::resources::Resources;

/// Advances one event type's queue.
type EventUpdater = fn(&World);

static NEXT_WORLD_ID: AtomicU64 = AtomicU64::new(0);

/// Entities with components, plus resources (singletons), a deferred command
/// buffer and event queues.
///
/// Components live in archetype tables: one table per distinct set of
/// component types, one dense column per type. Queries walk archetypes in
/// creation order and rows in order, so iteration order is deterministic.
///
/// Borrows of component types and resources through `&World` are checked at
/// run time; a conflict is refused with an error naming the type.
///
/// ```
/// use engine::ecs::{Entity, World, Without};
///
/// #[derive(Debug, PartialEq)]
/// struct Position(f32);
/// struct Velocity(f32);
/// struct Frozen;
///
/// let mut world = World::new();
/// let a = world.spawn((Position(0.0), Velocity(1.0)));
/// let b = world.spawn((Position(5.0), Velocity(1.0), Frozen));
///
/// for (pos, vel) in world.query_mut::<(&mut Position, &Velocity)>() {
///     pos.0 += vel.0;
/// }
/// let moving: Vec<Entity> = world
///     .query_filtered::<Entity, Without<Frozen>>()
///     .iter()
///     .collect();
/// assert_eq!(moving, vec![a]);
/// assert_eq!(*world.get::<Position>(b).unwrap(), Position(6.0));
///
/// world.despawn(a).unwrap();
/// assert!(world.get::<Position>(a).is_err());
/// ```
pub struct World {
    id: u64,
    entities: Entities,
    archetypes: Vec<Archetype>,
    component_ids: HashMap<TypeId, usize>,
    component_flags: Vec<BorrowFlag>,
    pub(crate) resources: Resources,
    commands: std::sync::Mutex<CommandQueue<World>>,
    event_updaters: Vec<(TypeId, EventUpdater)>,
}

impl Default for World {
    fn default() -> Self {
        Self::new()
    }
}

/// Index of the archetype with no components.
const EMPTY_ARCHETYPE: u32 = 0;

impl World {
    /// An empty world.
    pub fn new() -> Self {
        World {
            id: NEXT_WORLD_ID.fetch_add(1, Ordering::Relaxed),
            entities: Entities::default(),
            archetypes: vec![Archetype::new(Vec::new())],
            component_ids: HashMap::new(),
            component_flags: Vec::new(),
            resources: Resources::default(),
            commands: std::sync::Mutex::new(CommandQueue::new()),
            event_updaters: Vec::new(),
        }
    }

    /// A process-unique id of this world (used by prepared queries to detect a world swap).
    pub fn id(&self) -> u64 {
        self.id
    }

    /// The archetype tables, in creation order.
    pub fn archetypes(&self) -> &[Archetype] {
        &self.archetypes
    }

    // ---------------------------------------------------------------- entities

    /// Creates an entity with the components of `bundle` (a tuple of 1 to 12 components).
    ///
    /// # Panics
    /// If the bundle names a component type twice.
    pub fn spawn<B: Bundle>(&mut self, bundle: B) -> Entity {
        let target = self
            .bundle_target::<B>(EMPTY_ARCHETYPE)
            .unwrap_or_else(|e| panic!("{e}"));
        self.spawn_in(target, bundle)
    }

    /// Spawns one entity per bundle, in order, and returns their ids.
    ///
    /// # Panics
    /// If the bundle type names a component type twice.
    pub fn spawn_batch<B: Bundle, I: IntoIterator<Item = B>>(&mut self, bundles: I) -> Vec<Entity> {
        let target = self
            .bundle_target::<B>(EMPTY_ARCHETYPE)
            .unwrap_or_else(|e| panic!("{e}"));
        let bundles = bundles.into_iter();
        let (lower, _) = bundles.size_hint();
        self.archetypes[target as usize].reserve(lower);
        self.entities.reserve(lower);
        let mut spawned = Vec::with_capacity(lower);
        let entities = &mut self.entities;
        B::push_batch(bundles, &mut self.archetypes[target as usize], |row| {
            let entity = entities.alloc(Location {
                archetype: target,
                row,
            });
            spawned.push(entity);
            entity
        });
        spawned
    }

    fn spawn_in<B: Bundle>(&mut self, target: u32, bundle: B) -> Entity {
        let archetype = &mut self.archetypes[target as usize];
        let row = archetype.len() as u32;
        let entity = self.entities.alloc(Location {
            archetype: target,
            row,
        });
        bundle.push_into(archetype);
        archetype.entities.push(entity);
        entity
    }

    /// Adds the components of `bundle` to `entity`; components it already has are replaced.
    pub fn insert<B: Bundle>(&mut self, entity: Entity, bundle: B) -> Result<(), EcsError> {
        let location = self.location(entity)?;
        let edge = self.add_edge::<B>(location.archetype)?;
        let (target, row) = (edge.target, location.row as usize);
        if target == location.archetype {
            bundle.overwrite(&mut self.archetypes[target as usize], row);
            return Ok(());
        }
        let replaced: Vec<TypeId> = if edge.overlaps {
            B::component_types().iter().map(|t| t.type_id).collect()
        } else {
            Vec::new()
        };
        self.move_entity(location, target, |type_id| replaced.contains(&type_id));
        bundle.push_into(&mut self.archetypes[target as usize]);
        Ok(())
    }

    /// Adds (or replaces) one component.
    pub fn insert_one<T: Component>(
        &mut self,
        entity: Entity,
        component: T,
    ) -> Result<(), EcsError> {
        self.insert(entity, (component,))
    }

    /// Removes the components of bundle `B` from `entity` and returns them.
    /// Fails without change if the entity lacks any of them.
    pub fn remove<B: Bundle>(&mut self, entity: Entity) -> Result<B, EcsError> {
        let location = self.location(entity)?;
        let target = self.remove_target::<B>(entity, location.archetype)?;
        let removed = B::take_from(
            &mut self.archetypes[location.archetype as usize],
            location.row as usize,
        );
        // The bundle's columns (absent from the target) are already taken; the rest move.
        self.move_entity(location, target, |_| false);
        Ok(removed)
    }

    /// Removes one component and returns it.
    pub fn remove_one<T: Component>(&mut self, entity: Entity) -> Result<T, EcsError> {
        self.remove::<(T,)>(entity).map(|(component,)| component)
    }

    /// Destroys the entity and drops its components. Its id is never valid again.
    pub fn despawn(&mut self, entity: Entity) -> Result<(), EcsError> {
        let location = self
            .entities
            .free(entity)
            .ok_or(EcsError::NoSuchEntity(entity))?;
        let archetype = &mut self.archetypes[location.archetype as usize];
        if let Some(moved) = archetype.swap_remove_drop(location.row as usize) {
            self.entities.set_location(moved, location);
        }
        Ok(())
    }

    /// Whether the entity is alive.
    pub fn contains(&self, entity: Entity) -> bool {
        self.entities.get(entity).is_some()
    }

    /// Whether the entity is alive and has component `T`.
    pub fn has<T: Component>(&self, entity: Entity) -> bool {
        self.entities
            .get(entity)
            .is_some_and(|l| self.archetypes[l.archetype as usize].has(TypeId::of::<T>()))
    }

    /// Number of live entities.
    pub fn len(&self) -> usize {
        self.entities.len()
    }

    /// Whether there are no live entities.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Live entities in ascending index order.
    pub fn entities(&self) -> impl Iterator<Item = Entity> + '_ {
        self.entities.iter()
    }

    fn location(&self, entity: Entity) -> Result<Location, EcsError> {
        self.entities
            .get(entity)
            .ok_or(EcsError::NoSuchEntity(entity))
    }

    // -------------------------------------------------------- component access

    /// A shared borrow of `entity`'s component `T` (runtime-checked).
    pub fn get<T: Component>(&self, entity: Entity) -> Result<Ref<'_, T>, EcsError> {
        let (archetype, row, flag) = self.component_slot::<T>(entity, false)?;
        // SAFETY: the shared borrow of `T` is held and released by the `Ref`.
        let column = unsafe { archetype.column_slice::<T>() };
        Ok(Ref::new(&column.expect("column checked")[row], flag))
    }

    /// A mutable borrow of `entity`'s component `T` (runtime-checked).
    pub fn get_mut<T: Component>(&self, entity: Entity) -> Result<RefMut<'_, T>, EcsError> {
        let (archetype, row, flag) = self.component_slot::<T>(entity, true)?;
        // SAFETY: the unique borrow of `T` is held and released by the `RefMut`.
        let column = unsafe { archetype.column_slice_mut::<T>() };
        Ok(RefMut::new(&mut column.expect("column checked")[row], flag))
    }

    /// Finds the entity's row and acquires the borrow of `T`.
    fn component_slot<T: Component>(
        &self,
        entity: Entity,
        mutable: bool,
    ) -> Result<(&Archetype, usize, &BorrowFlag), EcsError> {
        let location = self.location(entity)?;
        let archetype = &self.archetypes[location.archetype as usize];
        let column =
            archetype
                .column_index(TypeId::of::<T>())
                .ok_or(EcsError::MissingComponent {
                    entity,
                    type_name: std::any::type_name::<T>(),
                })?;
        let flag = &self.component_flags[archetype.columns[column].component_id];
        flag.try_acquire(mutable)
            .map_err(|conflict| EcsError::Borrow {
                target: BorrowTarget::Component,
                type_name: std::any::type_name::<T>(),
                conflict,
            })?;
        Ok((archetype, location.row as usize, flag))
    }

    // ----------------------------------------------------------------- queries

    /// A query over `&World` with runtime borrow checks per component type.
    ///
    /// # Panics
    /// On a borrow conflict, with a message naming the type (see [`World::try_query`]).
    pub fn query<Q: Query>(&self) -> QueryBorrow<'_, Q> {
        self.query_filtered::<Q, ()>()
    }

    /// Like [`World::query`], returning the borrow conflict as an error.
    pub fn try_query<Q: Query>(&self) -> Result<QueryBorrow<'_, Q>, EcsError> {
        self.try_query_filtered::<Q, ()>()
    }

    /// A query restricted by filter `F` ([`super::With`], [`super::Without`] or a tuple of them).
    ///
    /// # Panics
    /// On a borrow conflict, with a message naming the type.
    pub fn query_filtered<Q: Query, F: QueryFilter>(&self) -> QueryBorrow<'_, Q, F> {
        self.try_query_filtered()
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// Like [`World::query_filtered`], returning the borrow conflict as an error.
    pub fn try_query_filtered<Q: Query, F: QueryFilter>(
        &self,
    ) -> Result<QueryBorrow<'_, Q, F>, EcsError> {
        let mut accesses = Vec::new();
        Q::access(&mut accesses);
        let guard = self.acquire(&accesses)?;
        Ok(QueryBorrow::new(
            &self.archetypes,
            ArchetypeCursor::Scan(0..self.archetypes.len()),
            guard,
        ))
    }

    /// Iterates with exclusive access (no runtime borrow checks).
    ///
    /// # Panics
    /// If `Q` names a component twice with at least one `&mut`.
    pub fn query_mut<Q: Query>(&mut self) -> QueryIter<'_, Q> {
        self.query_filtered_mut::<Q, ()>()
    }

    /// [`World::query_mut`] with a filter.
    ///
    /// # Panics
    /// If `Q` names a component twice with at least one `&mut`.
    pub fn query_filtered_mut<Q: Query, F: QueryFilter>(&mut self) -> QueryIter<'_, Q, F> {
        let mut accesses = Vec::new();
        Q::access(&mut accesses);
        Self::check_aliasing(&accesses).unwrap_or_else(|error| panic!("{error}"));
        // SAFETY: `&mut self` excludes every other borrow, and `Q` does not alias itself.
        unsafe {
            QueryIter::new(
                &self.archetypes,
                ArchetypeCursor::Scan(0..self.archetypes.len()),
            )
        }
    }

    /// Refuses a query that names one type twice with at least one `&mut`.
    pub(crate) fn check_aliasing(accesses: &[Access]) -> Result<(), EcsError> {
        for (i, a) in accesses.iter().enumerate() {
            for b in &accesses[i + 1..] {
                if a.type_id == b.type_id && (a.mutable || b.mutable) {
                    return Err(EcsError::Borrow {
                        target: BorrowTarget::Component,
                        type_name: a.type_name,
                        conflict: BorrowConflict::AliasedInQuery,
                    });
                }
            }
        }
        Ok(())
    }

    /// Acquires the borrows of a query; on a conflict releases what it took.
    pub(crate) fn acquire(&self, accesses: &[Access]) -> Result<BorrowGuard<'_>, EcsError> {
        Self::check_aliasing(accesses)?;
        let mut guard = BorrowGuard {
            held: Vec::with_capacity(accesses.len()),
        };
        for access in accesses {
            // A type never stored has no column anywhere: nothing to borrow.
            let Some(&id) = self.component_ids.get(&access.type_id) else {
                continue;
            };
            let flag = &self.component_flags[id];
            flag.try_acquire(access.mutable)
                .map_err(|conflict| EcsError::Borrow {
                    target: BorrowTarget::Component,
                    type_name: access.type_name,
                    conflict,
                })?;
            guard.held.push((flag, access.mutable));
        }
        Ok(guard)
    }

    // ------------------------------------------------------ archetype moves

    /// The archetype reached from `source` by adding bundle `B` (cached edge).
    fn bundle_target<B: Bundle>(&mut self, source: u32) -> Result<u32, EcsError> {
        self.add_edge::<B>(source).map(|edge| edge.target)
    }

    /// The cached transition from `source` by adding bundle `B`.
    fn add_edge<B: Bundle>(&mut self, source: u32) -> Result<Edge, EcsError> {
        let bundle = TypeId::of::<B>();
        if let Some(edge) = self.archetypes[source as usize]
            .add_edges
            .iter()
            .find(|e| e.bundle == bundle)
        {
            return Ok(*edge);
        }
        let added = unique_types::<B>()?;
        let source_archetype = &self.archetypes[source as usize];
        let overlaps = added.iter().any(|t| source_archetype.has(t.type_id));
        let mut types: Vec<ComponentType> = source_archetype.columns.iter().map(|c| c.ty).collect();
        types.extend(added.iter().filter(|t| !source_archetype.has(t.type_id)));
        let target = self.archetype_with(types);
        let edge = Edge {
            bundle,
            target,
            overlaps,
        };
        self.archetypes[source as usize].add_edges.push(edge);
        Ok(edge)
    }

    /// The archetype reached from `source` by removing bundle `B` (cached
    /// edge). An edge exists only once `source` was checked to hold every
    /// type of `B`, so the check runs once per archetype and bundle.
    fn remove_target<B: Bundle>(&mut self, entity: Entity, source: u32) -> Result<u32, EcsError> {
        let bundle = TypeId::of::<B>();
        let source_archetype = &self.archetypes[source as usize];
        if let Some(edge) = source_archetype
            .remove_edges
            .iter()
            .find(|e| e.bundle == bundle)
        {
            return Ok(edge.target);
        }
        let removed = unique_types::<B>()?;
        if let Some(missing) = removed.iter().find(|t| !source_archetype.has(t.type_id)) {
            return Err(EcsError::MissingComponent {
                entity,
                type_name: missing.type_name,
            });
        }
        let types: Vec<ComponentType> = source_archetype
            .columns
            .iter()
            .map(|c| c.ty)
            .filter(|t| !removed.iter().any(|r| r.type_id == t.type_id))
            .collect();
        let target = self.archetype_with(types);
        self.archetypes[source as usize].remove_edges.push(Edge {
            bundle,
            target,
            overlaps: false,
        });
        Ok(target)
    }

    /// The archetype with exactly these types, created if needed.
    fn archetype_with(&mut self, mut types: Vec<ComponentType>) -> u32 {
        types.sort_by_key(|t| t.type_id);
        let found = self
            .archetypes
            .iter()
            .position(|a| a.type_ids().eq(types.iter().map(|t| t.type_id)));
        if let Some(index) = found {
            return index as u32;
        }
        let columns = types
            .into_iter()
            .map(|ty| ArchetypeColumn {
                component_id: self.component_id(ty.type_id),
                data: SharedCell::new((ty.new_column)()),
                ty,
            })
            .collect();
        self.archetypes.push(Archetype::new(columns));
        (self.archetypes.len() - 1) as u32
    }

    fn component_id(&mut self, type_id: TypeId) -> usize {
        let next = self.component_flags.len();
        let id = *self.component_ids.entry(type_id).or_insert(next);
        if id == next {
            self.component_flags.push(BorrowFlag::new());
        }
        id
    }

    /// Moves an entity's row from its archetype to `target`. Columns the
    /// target lacks must already have been swap-removed by the caller (a
    /// removed bundle); of the others, those for which `drop_it` holds are
    /// dropped (replaced by an inserted bundle) and the rest move. The caller
    /// then pushes any target columns still short of a row.
    fn move_entity(&mut self, from: Location, target: u32, drop_it: impl Fn(TypeId) -> bool) {
        let row = from.row as usize;
        let [source, destination] = self
            .archetypes
            .get_disjoint_mut([from.archetype as usize, target as usize])
            .expect("source and target archetypes differ");
        for column in &mut source.columns {
            let Some(index) = destination.column_index(column.ty.type_id) else {
                continue;
            };
            let data = column.data.get_exclusive();
            if drop_it(column.ty.type_id) {
                data.swap_remove_drop(row);
            } else {
                data.swap_remove_into(row, &mut **destination.columns[index].data.get_exclusive());
            }
        }
        self.finish_move(from, target);
    }

    /// Moves the entity id between the archetypes' entity lists and fixes locations.
    fn finish_move(&mut self, from: Location, target: u32) {
        let source = &mut self.archetypes[from.archetype as usize];
        let entity = source.entities[from.row as usize];
        if let Some(moved) = source.swap_remove_entity(from.row as usize) {
            self.entities.set_location(moved, from);
        }
        let destination = &mut self.archetypes[target as usize];
        let row = destination.entities.len() as u32;
        destination.entities.push(entity);
        self.entities.set_location(
            entity,
            Location {
                archetype: target,
                row,
            },
        );
    }

    // --------------------------------------------------------------- resources

    /// Inserts (or replaces) resource `R`; returns the previous value.
    pub fn insert_resource<R: Component>(&mut self, resource: R) -> Option<R> {
        self.resources.insert(resource)
    }

    /// A shared borrow of resource `R`.
    ///
    /// # Panics
    /// If `R` is missing or mutably borrowed, with a message naming `R`.
    pub fn resource<R: Component>(&self) -> Ref<'_, R> {
        self.try_resource()
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// A mutable borrow of resource `R`.
    ///
    /// # Panics
    /// If `R` is missing or already borrowed, with a message naming `R`.
    pub fn resource_mut<R: Component>(&self) -> RefMut<'_, R> {
        self.try_resource_mut()
            .unwrap_or_else(|error| panic!("{error}"))
    }

    /// A shared borrow of resource `R`, or why not.
    pub fn try_resource<R: Component>(&self) -> Result<Ref<'_, R>, EcsError> {
        self.resources.borrow()
    }

    /// A mutable borrow of resource `R`, or why not.
    pub fn try_resource_mut<R: Component>(&self) -> Result<RefMut<'_, R>, EcsError> {
        self.resources.borrow_mut()
    }

    /// Resource `R` if present.
    ///
    /// # Panics
    /// If `R` is mutably borrowed.
    pub fn get_resource<R: Component>(&self) -> Option<Ref<'_, R>> {
        self.contains_resource::<R>().then(|| self.resource())
    }

    /// Resource `R` mutably if present.
    ///
    /// # Panics
    /// If `R` is already borrowed.
    pub fn get_resource_mut<R: Component>(&self) -> Option<RefMut<'_, R>> {
        self.contains_resource::<R>().then(|| self.resource_mut())
    }

    /// Removes resource `R` and returns it.
    pub fn remove_resource<R: Component>(&mut self) -> Option<R> {
        self.resources.remove()
    }

    /// Whether resource `R` is present.
    pub fn contains_resource<R: Component>(&self) -> bool {
        self.resources.contains::<R>()
    }

    // ---------------------------------------------------------------- commands

    /// The queue behind [`World::commands`].
    pub(super) fn command_queue(&self) -> &std::sync::Mutex<CommandQueue<World>> {
        &self.commands
    }

    /// Applies and clears the world's deferred commands, in recording order.
    /// Every command is attempted; failures are returned together.
    pub fn apply_commands(&mut self) -> Result<(), CommandsError> {
        let mut buffer = std::mem::take(
            self.commands
                .get_mut()
                .unwrap_or_else(std::sync::PoisonError::into_inner),
        );
        buffer.run_on(self)
    }

    // ------------------------------------------------------------------ events

    /// Registers event type `T`: inserts an empty [`Events<T>`] resource and
    /// lets [`World::update_events`] advance it.
    pub fn add_event<T: Component>(&mut self) {
        if !self.contains_resource::<Events<T>>() {
            self.insert_resource(Events::<T>::new());
        }
        if !self
            .event_updaters
            .iter()
            .any(|(id, _)| *id == TypeId::of::<T>())
        {
            self.event_updaters
                .push((TypeId::of::<T>(), update_events_of::<T>));
        }
    }

    /// Sends an event (registering its type on first use).
    pub fn send_event<T: Component>(&mut self, event: T) {
        self.add_event::<T>();
        self.resource_mut::<Events<T>>().send(event);
    }

    /// Advances every registered event queue by one update (see [`Events::update`]).
    /// [`crate::schedule::App`] calls this once per step, before the systems run.
    pub fn update_events(&mut self) {
        for (_, update) in &self.event_updaters {
            update(self);
        }
    }
}

/// The bundle's component types, refusing a type named twice.
fn unique_types<B: Bundle>() -> Result<Vec<ComponentType>, EcsError> {
    let types = B::component_types();
    for (i, a) in types.iter().enumerate() {
        if types[i + 1..].iter().any(|b| b.type_id == a.type_id) {
            return Err(EcsError::DuplicateComponent {
                type_name: a.type_name,
            });
        }
    }
    Ok(types)
}

fn update_events_of<T: Component>(world: &World) {
    if let Some(mut events) = world.get_resource_mut::<Events<T>>() {
        events.update();
    }
}
