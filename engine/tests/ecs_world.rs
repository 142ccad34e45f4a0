//! World operations: entities, components, resources, commands and events.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use engine::ecs::{
    BorrowConflict, BorrowTarget, CommandBuffer, EcsError, Entity, EventReader, Events, World,
};

#[derive(Debug, Clone, Copy, PartialEq)]
struct Pos(f32);
#[derive(Debug, Clone, Copy, PartialEq)]
struct Vel(f32);
#[derive(Debug, Clone, PartialEq)]
struct Name(String);
#[derive(Debug, Clone, Copy, PartialEq)]
struct Marker;

/// Counts drops through a shared counter.
struct DropCounter(Arc<AtomicUsize>);
impl Drop for DropCounter {
    fn drop(&mut self) {
        self.0.fetch_add(1, Ordering::SeqCst);
    }
}

fn positions(world: &World) -> Vec<(Entity, f32)> {
    world
        .query::<(Entity, &Pos)>()
        .iter()
        .map(|(e, p)| (e, p.0))
        .collect()
}

#[test]
fn spawn_get_and_len() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0), Vel(2.0)));
    let b = world.spawn((Name("b".into()),));
    assert_eq!(world.len(), 2);
    assert!(world.contains(a) && world.contains(b));
    assert_eq!(*world.get::<Pos>(a).unwrap(), Pos(1.0));
    assert_eq!(world.get::<Name>(b).unwrap().0, "b");
    assert!(world.has::<Vel>(a));
    assert!(!world.has::<Vel>(b));
    world.get_mut::<Vel>(a).unwrap().0 = 5.0;
    assert_eq!(*world.get::<Vel>(a).unwrap(), Vel(5.0));
    assert_eq!(
        world.get::<Pos>(b).unwrap_err(),
        EcsError::MissingComponent {
            entity: b,
            type_name: std::any::type_name::<Pos>()
        }
    );
    assert_eq!(world.entities().collect::<Vec<_>>(), vec![a, b]);
}

#[test]
fn stale_ids_are_refused_after_reuse() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0),));
    world.despawn(a).unwrap();
    assert_eq!(world.despawn(a), Err(EcsError::NoSuchEntity(a)));
    let b = world.spawn((Pos(2.0),));
    assert_eq!(b.index(), a.index(), "slot reused");
    assert_eq!(b.generation(), a.generation() + 1, "generation bumped");
    assert!(!world.contains(a));
    assert_eq!(world.get::<Pos>(a).unwrap_err(), EcsError::NoSuchEntity(a));
    assert_eq!(
        world.insert_one(a, Vel(1.0)),
        Err(EcsError::NoSuchEntity(a))
    );
    assert_eq!(world.remove_one::<Pos>(a), Err(EcsError::NoSuchEntity(a)));
    assert_eq!(*world.get::<Pos>(b).unwrap(), Pos(2.0));
    assert!(Entity::from_bits(b.to_bits()) == Some(b));
}

#[test]
fn despawn_in_the_middle_keeps_other_rows_intact() {
    let mut world = World::new();
    let ids: Vec<Entity> = (0..5)
        .map(|i| world.spawn((Pos(i as f32), Name(format!("n{i}")))))
        .collect();
    world.despawn(ids[1]).unwrap();
    world.despawn(ids[0]).unwrap();
    for (i, &e) in ids.iter().enumerate().skip(2) {
        assert_eq!(*world.get::<Pos>(e).unwrap(), Pos(i as f32));
        assert_eq!(world.get::<Name>(e).unwrap().0, format!("n{i}"));
    }
    // The last row was swapped into the holes: order is deterministic.
    let order: Vec<f32> = positions(&world).iter().map(|p| p.1).collect();
    assert_eq!(order, vec![3.0, 4.0, 2.0]);
}

#[test]
fn insert_moves_between_archetypes_and_replaces_existing() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0),));
    let b = world.spawn((Pos(2.0),));
    world.insert(a, (Vel(3.0), Name("a".into()))).unwrap();
    assert_eq!(*world.get::<Pos>(a).unwrap(), Pos(1.0));
    assert_eq!(*world.get::<Vel>(a).unwrap(), Vel(3.0));
    assert_eq!(
        *world.get::<Pos>(b).unwrap(),
        Pos(2.0),
        "the swapped row keeps its data"
    );
    // Overwrite in place (same archetype).
    world.insert(a, (Vel(4.0),)).unwrap();
    assert_eq!(*world.get::<Vel>(a).unwrap(), Vel(4.0));
    // Overlapping bundle: replaces Pos, adds Marker.
    world.insert(a, (Pos(9.0), Marker)).unwrap();
    assert_eq!(*world.get::<Pos>(a).unwrap(), Pos(9.0));
    assert!(world.has::<Marker>(a));
    assert_eq!(world.get::<Name>(a).unwrap().0, "a");
    assert_eq!(
        world.insert(b, (Vel(1.0), Vel(2.0))),
        Err(EcsError::DuplicateComponent {
            type_name: std::any::type_name::<Vel>()
        })
    );
}

#[test]
fn remove_returns_components_and_fails_without_change() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0), Vel(2.0), Name("a".into())));
    let other = world.spawn((Pos(5.0), Vel(6.0), Name("o".into())));
    let (vel, name) = world.remove::<(Vel, Name)>(a).unwrap();
    assert_eq!((vel, name), (Vel(2.0), Name("a".into())));
    assert!(!world.has::<Vel>(a));
    assert_eq!(*world.get::<Pos>(a).unwrap(), Pos(1.0));
    assert_eq!(world.get::<Name>(other).unwrap().0, "o");
    assert_eq!(
        world.remove::<(Pos, Vel)>(a),
        Err(EcsError::MissingComponent {
            entity: a,
            type_name: std::any::type_name::<Vel>()
        })
    );
    assert_eq!(
        *world.get::<Pos>(a).unwrap(),
        Pos(1.0),
        "failed remove changes nothing"
    );
    assert_eq!(world.remove_one::<Pos>(a).unwrap(), Pos(1.0));
    assert!(
        world.contains(a),
        "an entity without components stays alive"
    );
    assert_eq!(world.query::<Entity>().iter().count(), 2);
}

#[test]
fn components_are_dropped_exactly_once() {
    let drops = Arc::new(AtomicUsize::new(0));
    let counter = || DropCounter(drops.clone());
    let count = || drops.load(Ordering::SeqCst);
    let mut world = World::new();
    let a = world.spawn((counter(), Pos(0.0)));
    let b = world.spawn((counter(), Pos(1.0)));
    let c = world.spawn((counter(),));
    world.despawn(a).unwrap();
    assert_eq!(count(), 1, "despawn drops");
    world.insert_one(b, Vel(1.0)).unwrap();
    assert_eq!(count(), 1, "moving between archetypes does not drop");
    world.insert_one(b, counter()).unwrap();
    assert_eq!(count(), 2, "replacing drops the old value");
    let taken = world.remove_one::<DropCounter>(c).unwrap();
    assert_eq!(count(), 2, "remove hands the value out");
    drop(taken);
    assert_eq!(count(), 3);
    world.insert_resource(counter());
    world.insert_resource(counter());
    assert_eq!(count(), 4, "replaced resource dropped");
    drop(world);
    assert_eq!(count(), 6, "dropping the world drops the rest");
}

#[test]
fn zero_sized_components() {
    let mut world = World::new();
    let a = world.spawn((Marker,));
    let b = world.spawn((Marker, Pos(1.0)));
    world.despawn(a).unwrap();
    assert_eq!(world.query::<&Marker>().iter().count(), 1);
    assert_eq!(world.remove_one::<Marker>(b).unwrap(), Marker);
    world.insert_one(b, Marker).unwrap();
    for marker in world.query_mut::<&mut Marker>() {
        *marker = Marker;
    }
    assert_eq!(world.query::<(&Marker, &Pos)>().iter().count(), 1);
}

#[test]
fn spawn_batch_keeps_order() {
    let mut world = World::new();
    let ids = world.spawn_batch((0..100).map(|i| (Pos(i as f32), Vel(1.0))));
    assert_eq!(ids.len(), 100);
    let seen: Vec<Entity> = world.query::<Entity>().iter().collect();
    assert_eq!(seen, ids);
}

#[test]
fn borrow_conflicts_name_the_type() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0),));
    let held = world.get_mut::<Pos>(a).unwrap();
    let error = world.get::<Pos>(a).unwrap_err();
    assert_eq!(
        error,
        EcsError::Borrow {
            target: BorrowTarget::Component,
            type_name: std::any::type_name::<Pos>(),
            conflict: BorrowConflict::AlreadyMutable
        }
    );
    assert!(
        error
            .to_string()
            .contains("ecs_world::Pos` is already borrowed mutably"),
        "{error}"
    );
    drop(held);
    let shared = world.get::<Pos>(a).unwrap();
    let error = world.get_mut::<Pos>(a).unwrap_err();
    assert!(
        error.to_string().contains("already borrowed (shared)"),
        "{error}"
    );
    drop(shared);
    assert!(world.get_mut::<Pos>(a).is_ok(), "released on drop");
}

#[test]
fn resources() {
    #[derive(Debug, PartialEq)]
    struct Gravity(f32);
    let mut world = World::new();
    assert!(!world.contains_resource::<Gravity>());
    assert!(world.get_resource::<Gravity>().is_none());
    assert_eq!(
        world.try_resource::<Gravity>().unwrap_err(),
        EcsError::MissingResource {
            type_name: std::any::type_name::<Gravity>()
        }
    );
    assert_eq!(world.insert_resource(Gravity(-9.8)), None);
    world.resource_mut::<Gravity>().0 = -1.0;
    assert_eq!(*world.resource::<Gravity>(), Gravity(-1.0));
    {
        let _held = world.resource_mut::<Gravity>();
        let error = world.try_resource_mut::<Gravity>().unwrap_err();
        assert_eq!(
            error.to_string(),
            format!(
                "resource `{}` is already borrowed mutably",
                std::any::type_name::<Gravity>()
            )
        );
    }
    assert_eq!(world.get_resource_mut::<Gravity>().map(|g| g.0), Some(-1.0));
    assert_eq!(world.insert_resource(Gravity(2.0)), Some(Gravity(-1.0)));
    assert_eq!(world.remove_resource::<Gravity>(), Some(Gravity(2.0)));
    assert!(!world.contains_resource::<Gravity>());
}

#[test]
#[should_panic(expected = "is already borrowed mutably")]
fn resource_borrowed_mutably_twice_panics_with_message() {
    let mut world = World::new();
    world.insert_resource(Pos(0.0));
    let _first = world.resource_mut::<Pos>();
    let _second = world.resource_mut::<Pos>();
}

#[test]
#[should_panic(expected = "does not exist in the world")]
fn missing_resource_panics_with_its_name() {
    let world = World::new();
    let _ = world.resource::<Pos>();
}

#[test]
fn command_buffer_applies_in_recording_order_and_reports_errors() {
    let mut world = World::new();
    let a = world.spawn((Pos(0.0),));
    let mut commands = CommandBuffer::new();
    commands.insert_one(a, Vel(1.0));
    commands.insert_one(a, Vel(2.0)); // later wins
    commands.remove::<(Pos,)>(a);
    commands.spawn((Pos(7.0),));
    commands.despawn(a);
    commands.despawn(a); // fails: already despawned
    commands.insert_one(a, Marker); // fails too
    commands.push(|w| {
        w.insert_resource(Name("ran".into()));
        Ok(())
    });
    assert_eq!(commands.len(), 8);
    let error = commands.run_on(&mut world).unwrap_err();
    assert!(commands.is_empty());
    assert_eq!(
        error.failures,
        vec![
            (5, EcsError::NoSuchEntity(a)),
            (6, EcsError::NoSuchEntity(a))
        ]
    );
    assert!(
        error
            .to_string()
            .starts_with("2 deferred command(s) failed: #5: entity"),
        "{error}"
    );
    assert_eq!(world.len(), 1);
    assert_eq!(
        positions(&world).iter().map(|p| p.1).collect::<Vec<_>>(),
        vec![7.0]
    );
    assert_eq!(world.resource::<Name>().0, "ran");
}

#[test]
fn commands_recorded_order_matters() {
    let mut world = World::new();
    let a = world.spawn((Pos(0.0),));
    let mut commands = CommandBuffer::new();
    commands.insert_one(a, Vel(1.0));
    commands.remove::<(Vel,)>(a);
    commands.run_on(&mut world).unwrap();
    assert!(!world.has::<Vel>(a), "insert then remove leaves no Vel");
    commands.remove::<(Vel,)>(a);
    commands.insert_one(a, Vel(1.0));
    assert!(
        commands.run_on(&mut world).is_err(),
        "the remove fails first"
    );
    assert!(world.has::<Vel>(a), "remove then insert leaves Vel");
}

#[test]
fn world_commands_work_through_a_shared_world() {
    let mut world = World::new();
    world.spawn_batch((0..4).map(|i| (Pos(i as f32),)));
    {
        let world = &world;
        for (entity, pos) in world.query::<(Entity, &Pos)>().iter() {
            if pos.0 >= 2.0 {
                world.commands().despawn(entity);
            }
        }
        assert_eq!(world.commands().len(), 2);
    }
    world.apply_commands().unwrap();
    assert_eq!(world.len(), 2);
    assert!(world.commands().is_empty());
}

#[test]
fn events_live_for_two_updates_and_readers_see_each_once() {
    #[derive(Debug, PartialEq)]
    struct Landed(u32);
    let mut world = World::new();
    let mut reader = EventReader::default();
    world.send_event(Landed(1));
    world.send_event(Landed(2));
    let read = |reader: &mut EventReader, world: &World| -> Vec<u32> {
        reader
            .read(&world.resource::<Events<Landed>>())
            .map(|e| e.0)
            .collect()
    };
    assert_eq!(read(&mut reader, &world), vec![1, 2]);
    world.update_events();
    world.send_event(Landed(3));
    assert_eq!(read(&mut reader, &world), vec![3]);
    let mut late = EventReader::default();
    assert_eq!(
        read(&mut late, &world),
        vec![1, 2, 3],
        "previous update still readable"
    );
    assert_eq!(
        world
            .resource::<Events<Landed>>()
            .iter_current_update()
            .map(|e| e.0)
            .collect::<Vec<_>>(),
        vec![3]
    );
    world.update_events();
    let mut fresh = EventReader::default();
    assert_eq!(
        read(&mut fresh, &world),
        vec![3],
        "events of two updates ago are gone"
    );
    let drained: Vec<u32> = world
        .resource_mut::<Events<Landed>>()
        .drain()
        .map(|e| e.0)
        .collect();
    assert_eq!(drained, vec![3]);
    assert!(world.resource::<Events<Landed>>().is_empty());
    world.send_event(Landed(4));
    assert_eq!(
        read(&mut reader, &world),
        vec![4],
        "cursor survives a drain"
    );
    let at_end = EventReader::new_at_end(&world.resource::<Events<Landed>>());
    let mut at_end = at_end;
    assert!(read(&mut at_end, &world).is_empty());
}

#[test]
fn world_is_send_and_sync() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<World>();
}
