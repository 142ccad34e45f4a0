//! Entity ids and their allocator.

use std::fmt;
use std::num::NonZeroU32;

/// A handle to an entity: a slot index plus a generation.
///
/// When an entity is despawned its slot's generation is bumped, so an old id
/// never refers to the entity that later reuses the slot. A slot whose
/// generation would overflow is retired, never reused.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Entity {
    index: u32,
    generation: NonZeroU32,
}

impl Entity {
    /// The id as one `u64`: generation in the high 32 bits, index in the low 32 bits.
    pub fn to_bits(self) -> u64 {
        (u64::from(self.generation.get()) << 32) | u64::from(self.index)
    }

    /// The id encoded by [`Entity::to_bits`]; `None` when the generation part is zero
    /// (no entity ever has generation zero).
    pub fn from_bits(bits: u64) -> Option<Entity> {
        let generation = NonZeroU32::new((bits >> 32) as u32)?;
        Some(Entity {
            index: bits as u32,
            generation,
        })
    }

    /// The slot index (dense, reused after despawn).
    pub fn index(self) -> u32 {
        self.index
    }

    /// The generation of the slot when this id was handed out (starts at 1).
    pub fn generation(self) -> u32 {
        self.generation.get()
    }
}

impl fmt::Debug for Entity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}v{}", self.index, self.generation)
    }
}

impl fmt::Display for Entity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

/// Where an entity's components live: archetype and row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Location {
    pub archetype: u32,
    pub row: u32,
}

#[derive(Clone, Copy, Debug)]
struct Slot {
    generation: NonZeroU32,
    location: Option<Location>,
}

/// Allocates entity ids. Freed slots are reused last-in first-out, which is
/// deterministic.
#[derive(Default)]
pub(crate) struct Entities {
    slots: Vec<Slot>,
    free: Vec<u32>,
    alive: usize,
}

impl Entities {
    /// A fresh id whose location must be set with [`Entities::set_location`] right away.
    pub fn alloc(&mut self, location: Location) -> Entity {
        self.alive += 1;
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.location = Some(location);
            return Entity {
                index,
                generation: slot.generation,
            };
        }
        let index = u32::try_from(self.slots.len()).expect("more than u32::MAX entities");
        let generation = NonZeroU32::MIN;
        self.slots.push(Slot {
            generation,
            location: Some(location),
        });
        Entity { index, generation }
    }

    /// Makes room for `additional` more ids without reallocating.
    pub fn reserve(&mut self, additional: usize) {
        self.slots
            .reserve(additional.saturating_sub(self.free.len()));
    }

    /// Frees a live id and returns where it was; `None` if it is not alive.
    pub fn free(&mut self, entity: Entity) -> Option<Location> {
        let slot = self.slots.get_mut(entity.index as usize)?;
        if slot.generation != entity.generation {
            return None;
        }
        let location = slot.location.take()?;
        self.alive -= 1;
        // An exhausted generation retires the slot, so no stale id can alias it.
        if let Some(next) = slot.generation.checked_add(1) {
            slot.generation = next;
            self.free.push(entity.index);
        }
        Some(location)
    }

    /// The location of a live id.
    pub fn get(&self, entity: Entity) -> Option<Location> {
        let slot = self.slots.get(entity.index as usize)?;
        if slot.generation == entity.generation {
            slot.location
        } else {
            None
        }
    }

    /// Updates where a live entity's row is.
    pub fn set_location(&mut self, entity: Entity, location: Location) {
        self.slots[entity.index as usize].location = Some(location);
    }

    /// Number of live entities.
    pub fn len(&self) -> usize {
        self.alive
    }

    /// Live entities in ascending index order.
    pub fn iter(&self) -> impl Iterator<Item = Entity> + '_ {
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            slot.location.map(|_| Entity {
                index: index as u32,
                generation: slot.generation,
            })
        })
    }

    #[cfg(test)]
    pub fn force_generation(&mut self, index: u32, generation: NonZeroU32) {
        self.slots[index as usize].generation = generation;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HERE: Location = Location {
        archetype: 0,
        row: 0,
    };

    #[test]
    fn bits_round_trip() {
        let mut entities = Entities::default();
        let e = entities.alloc(HERE);
        assert_eq!(Entity::from_bits(e.to_bits()), Some(e));
        assert_eq!(Entity::from_bits(7), None, "generation zero is never valid");
    }

    #[test]
    fn reuse_bumps_generation_and_refuses_stale_ids() {
        let mut entities = Entities::default();
        let a = entities.alloc(HERE);
        assert!(entities.free(a).is_some());
        assert!(entities.free(a).is_none(), "double free refused");
        let b = entities.alloc(HERE);
        assert_eq!(b.index(), a.index());
        assert_eq!(b.generation(), a.generation() + 1);
        assert!(entities.get(a).is_none());
        assert!(entities.get(b).is_some());
        assert_eq!(entities.iter().collect::<Vec<_>>(), vec![b]);
    }

    #[test]
    fn exhausted_generation_retires_the_slot() {
        let mut entities = Entities::default();
        let a = entities.alloc(HERE);
        entities.force_generation(a.index(), NonZeroU32::MAX);
        let old = Entity {
            index: a.index(),
            generation: NonZeroU32::MAX,
        };
        assert!(entities.free(old).is_some());
        let b = entities.alloc(HERE);
        assert_ne!(b.index(), a.index(), "retired slot is not reused");
        assert_eq!(entities.len(), 1);
    }
}
