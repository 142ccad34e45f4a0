//! An archetype-based entity-component-system.
//!
//! - [`World`] holds entities ([`Entity`]: index + generation) whose components
//!   are stored in archetype tables (one table per set of component types,
//!   one dense column per type), plus resources, a deferred command buffer and
//!   event queues.
//! - Queries ([`Query`]) over `&T`, `&mut T`, `Option<&T>`, `Option<&mut T>`,
//!   [`Entity`] and tuples, with [`With`]/[`Without`] filters:
//!   [`World::query`] (runtime borrow checks), [`World::query_mut`] (exclusive),
//!   [`PreparedQuery`] (cached archetypes), and parallel
//!   [`QueryBorrow::par_for_each`].
//! - Iteration order is deterministic: archetypes in creation order, then rows
//!   in order. Rows are dense: despawning or moving an entity swaps the last row
//!   of its archetype into the hole.
//! - [`CommandBuffer`] and [`World::commands`] defer structural changes;
//!   [`Events`] are double-buffered queues.

mod archetype;
mod borrow;
mod bundle;
mod column;
mod command_queue;
mod commands;
mod entity;
mod error;
mod events;
mod prepared;
mod query;
mod query_iter;
mod resources;
mod world;

pub use archetype::{Archetype, ComponentType};
pub use borrow::{Ref, RefMut};
pub use bundle::{Bundle, Component};
pub use command_queue::CommandQueue;
pub use commands::{CommandBuffer, Commands};
pub use entity::Entity;
pub use error::{BorrowConflict, BorrowTarget, CommandsError, EcsError};
pub use events::{EventReader, Events};
pub use prepared::PreparedQuery;
pub use query::{
    Access, EntityFetch, Fetch, Query, QueryFilter, ReadFetch, With, Without, WriteFetch,
};
pub use query_iter::{QueryBorrow, QueryIter};
pub use world::World;
