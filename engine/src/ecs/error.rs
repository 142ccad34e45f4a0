//! Errors of the ECS.

use std::fmt;

use super::Entity;

/// What kind of storage a borrow conflict is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BorrowTarget {
    /// A component type (all its columns).
    Component,
    /// A resource.
    Resource,
}

impl fmt::Display for BorrowTarget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BorrowTarget::Component => "component",
            BorrowTarget::Resource => "resource",
        })
    }
}

/// Why a runtime borrow was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BorrowConflict {
    /// Someone holds a mutable borrow.
    AlreadyMutable,
    /// Someone holds a shared borrow, so a mutable one is refused.
    AlreadyShared,
    /// One query names the type twice, at least once as `&mut`.
    AliasedInQuery,
}

impl fmt::Display for BorrowConflict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BorrowConflict::AlreadyMutable => "is already borrowed mutably",
            BorrowConflict::AlreadyShared => {
                "is already borrowed (shared), so it cannot be borrowed mutably"
            }
            BorrowConflict::AliasedInQuery => "appears twice in one query with `&mut` access",
        })
    }
}

/// An ECS operation that could not be done.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EcsError {
    /// The entity was despawned (or never existed in this world).
    #[error("entity {0:?} does not exist (despawned or never spawned)")]
    NoSuchEntity(Entity),
    /// The entity lacks the component.
    #[error("entity {entity:?} has no component `{type_name}`")]
    MissingComponent {
        /// The entity.
        entity: Entity,
        /// The component's type name.
        type_name: &'static str,
    },
    /// A runtime borrow check failed.
    #[error("{target} `{type_name}` {conflict}")]
    Borrow {
        /// Component or resource.
        target: BorrowTarget,
        /// The borrowed type's name.
        type_name: &'static str,
        /// Why the borrow was refused.
        conflict: BorrowConflict,
    },
    /// The resource was never inserted (or was removed).
    #[error("resource `{type_name}` does not exist in the world")]
    MissingResource {
        /// The resource's type name.
        type_name: &'static str,
    },
    /// A bundle names one component type twice.
    #[error("bundle contains component `{type_name}` more than once")]
    DuplicateComponent {
        /// The repeated component's type name.
        type_name: &'static str,
    },
}

/// Deferred commands that failed when applied. Every command is still
/// attempted; this lists the failures in recording order.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{} deferred command(s) failed: {}", failures.len(), list(failures))]
pub struct CommandsError {
    /// `(index of the command in recording order, error)`.
    pub failures: Vec<(usize, EcsError)>,
}

fn list(failures: &[(usize, EcsError)]) -> String {
    failures
        .iter()
        .map(|(index, error)| format!("#{index}: {error}"))
        .collect::<Vec<_>>()
        .join("; ")
}
