//! Deferred structural changes: a command buffer applied later in recording order.

use std::sync::{Mutex, MutexGuard, PoisonError};

use super::bundle::{Bundle, Component};
use super::command_queue::CommandQueue;
use super::entity::Entity;
use super::error::EcsError;
use super::world::World;

/// Recorded structural changes to a world (spawn, insert, remove, despawn,
/// or any closure), applied by [`CommandQueue::run_on`] in the order they
/// were recorded.
///
/// ```
/// use engine::ecs::{CommandBuffer, World};
/// struct Health(u32);
/// let mut world = World::new();
/// let e = world.spawn((Health(3),));
/// let mut commands = CommandBuffer::new();
/// for (entity, health) in world.query::<(engine::ecs::Entity, &Health)>().iter() {
///     if health.0 > 0 {
///         commands.despawn(entity);
///     }
/// }
/// commands.spawn((Health(10),));
/// commands.run_on(&mut world).unwrap();
/// assert!(!world.contains(e));
/// assert_eq!(world.len(), 1);
/// ```
pub type CommandBuffer = CommandQueue<World>;

impl CommandQueue<World> {
    /// Records spawning an entity with `bundle`.
    pub fn spawn<B: Bundle>(&mut self, bundle: B) {
        self.push(move |world| {
            world.spawn(bundle);
            Ok(())
        });
    }

    /// Records adding (or replacing) the components of `bundle` on `entity`.
    pub fn insert<B: Bundle>(&mut self, entity: Entity, bundle: B) {
        self.push(move |world| world.insert(entity, bundle));
    }

    /// Records adding (or replacing) one component.
    pub fn insert_one<T: Component>(&mut self, entity: Entity, component: T) {
        self.insert(entity, (component,));
    }

    /// Records removing the components of bundle `B` (they are dropped).
    pub fn remove<B: Bundle>(&mut self, entity: Entity) {
        self.push(move |world| world.remove::<B>(entity).map(drop));
    }

    /// Records despawning `entity`.
    pub fn despawn(&mut self, entity: Entity) {
        self.push(move |world| world.despawn(entity));
    }
}

impl World {
    /// The world's own deferred command buffer, usable through `&World`
    /// (e.g. while a query is live). The schedule applies it after each system;
    /// call [`World::apply_commands`] to apply it yourself.
    pub fn commands(&self) -> Commands<'_> {
        Commands {
            buffer: self.command_queue(),
        }
    }
}

/// A handle to the world's own deferred buffer, usable through `&World`.
/// Each call locks the buffer briefly. Commands recorded from parallel code
/// are ordered by lock acquisition, which is not deterministic: record from
/// sequential code when order matters.
#[derive(Clone, Copy)]
pub struct Commands<'w> {
    buffer: &'w Mutex<CommandBuffer>,
}

impl<'w> Commands<'w> {
    fn lock(&self) -> MutexGuard<'w, CommandBuffer> {
        self.buffer.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// See [`CommandBuffer::spawn`].
    pub fn spawn<B: Bundle>(&self, bundle: B) {
        self.lock().spawn(bundle);
    }

    /// See [`CommandBuffer::insert`].
    pub fn insert<B: Bundle>(&self, entity: Entity, bundle: B) {
        self.lock().insert(entity, bundle);
    }

    /// See [`CommandBuffer::insert_one`].
    pub fn insert_one<T: Component>(&self, entity: Entity, component: T) {
        self.lock().insert_one(entity, component);
    }

    /// See [`CommandBuffer::remove`].
    pub fn remove<B: Bundle>(&self, entity: Entity) {
        self.lock().remove::<B>(entity);
    }

    /// See [`CommandBuffer::despawn`].
    pub fn despawn(&self, entity: Entity) {
        self.lock().despawn(entity);
    }

    /// See [`CommandBuffer::push`].
    pub fn push(&self, command: impl FnOnce(&mut World) -> Result<(), EcsError> + Send + 'static) {
        self.lock().push(command);
    }

    /// Number of commands waiting.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether no command is waiting.
    pub fn is_empty(&self) -> bool {
        self.lock().is_empty()
    }
}
