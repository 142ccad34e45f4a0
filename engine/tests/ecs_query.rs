//! Queries: kinds, filters, order, borrow checks, prepared and parallel queries.

use engine::ecs::{BorrowConflict, EcsError, Entity, PreparedQuery, With, Without, World};

#[derive(Debug, Clone, Copy, PartialEq)]
struct Pos(f32);
#[derive(Debug, Clone, Copy, PartialEq)]
struct Vel(f32);
#[derive(Debug, Clone, Copy, PartialEq)]
struct Tag;

fn sample_world() -> (World, [Entity; 4]) {
    let mut world = World::new();
    let a = world.spawn((Pos(0.0), Vel(1.0)));
    let b = world.spawn((Pos(10.0),));
    let c = world.spawn((Pos(20.0), Vel(2.0), Tag));
    let d = world.spawn((Vel(3.0),));
    (world, [a, b, c, d])
}

#[test]
fn order_is_archetype_creation_then_row() {
    let (mut world, [a, b, c, _]) = sample_world();
    let e = world.spawn((Pos(30.0), Vel(4.0)));
    let seen: Vec<Entity> = world
        .query::<(Entity, &Pos)>()
        .iter()
        .map(|(e, _)| e)
        .collect();
    assert_eq!(seen, vec![a, e, b, c]);
}

#[test]
fn mutable_and_optional_items() {
    let (mut world, [a, b, c, d]) = sample_world();
    for (pos, vel) in world.query_mut::<(&mut Pos, &Vel)>() {
        pos.0 += vel.0;
    }
    assert_eq!(*world.get::<Pos>(a).unwrap(), Pos(1.0));
    assert_eq!(*world.get::<Pos>(c).unwrap(), Pos(22.0));
    let rows: Vec<(Entity, Option<f32>, Option<f32>)> = world
        .query::<(Entity, Option<&Pos>, Option<&Vel>)>()
        .iter()
        .map(|(e, p, v)| (e, p.map(|p| p.0), v.map(|v| v.0)))
        .collect();
    assert_eq!(
        rows,
        vec![
            (a, Some(1.0), Some(1.0)),
            (b, Some(10.0), None),
            (c, Some(22.0), Some(2.0)),
            (d, None, Some(3.0)),
        ]
    );
    for vel in world.query_mut::<Option<&mut Vel>>().flatten() {
        vel.0 = 0.0;
    }
    let total: f32 = world.query::<&Vel>().iter().map(|v| v.0).sum();
    assert_eq!(total, 0.0);
}

#[test]
fn filters() {
    let (world, [a, b, c, _]) = sample_world();
    let with: Vec<Entity> = world
        .query_filtered::<Entity, (With<Pos>, With<Vel>)>()
        .iter()
        .collect();
    assert_eq!(with, vec![a, c]);
    let without: Vec<Entity> = world
        .query_filtered::<Entity, (With<Pos>, Without<Tag>)>()
        .iter()
        .collect();
    assert_eq!(without, vec![a, b]);
    let mut prepared = PreparedQuery::<&Pos, Without<Vel>>::new();
    assert_eq!(
        prepared
            .query(&world)
            .iter()
            .map(|p| p.0)
            .collect::<Vec<_>>(),
        vec![10.0]
    );
}

#[test]
fn twelve_element_tuples() {
    #[derive(Clone, Copy)]
    struct C<const N: usize>(usize);
    let mut world = World::new();
    world.spawn((
        C::<0>(0),
        C::<1>(1),
        C::<2>(2),
        C::<3>(3),
        C::<4>(4),
        C::<5>(5),
        C::<6>(6),
        C::<7>(7),
        C::<8>(8),
        C::<9>(9),
        C::<10>(10),
        C::<11>(11),
    ));
    let mut query = world.query::<(
        &C<0>,
        &C<1>,
        &C<2>,
        &C<3>,
        &C<4>,
        &C<5>,
        &C<6>,
        &C<7>,
        &C<8>,
        &C<9>,
        &C<10>,
        &mut C<11>,
    )>();
    let (c0, .., c11) = query.iter().next().unwrap();
    assert_eq!(c0.0 + c11.0, 11);
}

#[test]
fn aliasing_query_is_refused_with_the_type_name() {
    let (world, _) = sample_world();
    let error = world.try_query::<(&mut Pos, &mut Pos)>().err().unwrap();
    assert!(matches!(
        error,
        EcsError::Borrow {
            conflict: BorrowConflict::AliasedInQuery,
            ..
        }
    ));
    assert!(
        error
            .to_string()
            .contains("ecs_query::Pos` appears twice in one query"),
        "{error}"
    );
    assert!(world.try_query::<(&Pos, &mut Pos)>().is_err());
    assert!(
        world.try_query::<(&Pos, &Pos)>().is_ok(),
        "two shared reads are fine"
    );
    // A type never stored is still checked for aliasing.
    struct Unused;
    assert!(world.try_query::<(&mut Unused, Option<&Unused>)>().is_err());
}

#[test]
fn live_query_blocks_conflicting_borrows_until_dropped() {
    let (mut world, [a, ..]) = sample_world();
    world.insert_resource(0u32);
    {
        let mut writing = world.query::<&mut Pos>();
        let error = world.try_query::<&Pos>().err().unwrap();
        assert_eq!(
            error.to_string(),
            format!(
                "component `{}` is already borrowed mutably",
                std::any::type_name::<Pos>()
            )
        );
        assert!(world.get::<Pos>(a).is_err());
        assert!(world.try_query::<&Vel>().is_ok(), "other types are free");
        assert_eq!(writing.iter().count(), 3);
    }
    let _reading = world.query::<&Pos>();
    assert!(world.try_query::<&Pos>().is_ok(), "shared + shared");
    assert!(world.try_query::<(&mut Vel, &Pos)>().is_ok());
    let error = world.try_query::<&mut Pos>().err().unwrap();
    assert!(matches!(
        error,
        EcsError::Borrow {
            conflict: BorrowConflict::AlreadyShared,
            ..
        }
    ));
    // A failed acquisition releases what it took.
    assert!(world.try_query::<(&mut Vel, &mut Pos)>().is_err());
    assert!(world.get_mut::<Vel>(a).is_ok());
}

#[test]
#[should_panic(expected = "is already borrowed mutably")]
fn plain_query_panics_on_conflict() {
    let (world, _) = sample_world();
    let _first = world.query::<&mut Pos>();
    let _second = world.query::<&Pos>();
}

#[test]
#[should_panic(expected = "appears twice in one query")]
fn query_mut_refuses_aliasing() {
    let (mut world, _) = sample_world();
    let _ = world.query_mut::<(&mut Vel, &Vel)>().count();
}

#[test]
fn prepared_query_updates_incrementally_and_follows_world_swaps() {
    let (mut world, _) = sample_world();
    let mut query = PreparedQuery::<&mut Pos>::new();
    assert_eq!(query.query_mut(&mut world).count(), 3);
    let late = world.spawn((Pos(5.0), Tag));
    for pos in query.query_mut(&mut world) {
        pos.0 += 1.0;
    }
    assert_eq!(*world.get::<Pos>(late).unwrap(), Pos(6.0));
    assert_eq!(query.query(&world).iter().count(), 4);
    let mut other = World::new();
    other.spawn((Pos(1.0),));
    assert_eq!(
        query.query(&other).iter().count(),
        1,
        "cache rebuilt for another world"
    );
    assert!(query.try_query(&world).is_ok());
}

#[test]
fn prepared_query_finds_columns_at_every_position_and_in_late_archetypes() {
    // Archetypes sort their columns by type id, so `Pos` and `Vel` sit at
    // different column positions in each of these; the prepared query keeps
    // one position per archetype and must agree with a plain query.
    #[derive(Clone, Copy)]
    struct Extra<const N: usize>;
    let mut world = World::new();
    world.spawn((Pos(1.0), Vel(1.0)));
    world.spawn((Extra::<0>, Pos(2.0)));
    world.spawn((Vel(3.0), Extra::<1>, Pos(3.0), Tag));
    let mut prepared = PreparedQuery::<(Entity, &mut Pos, Option<&Vel>)>::new();
    let rows = |world: &World| -> Vec<(Entity, f32, Option<f32>)> {
        world
            .query::<(Entity, &Pos, Option<&Vel>)>()
            .iter()
            .map(|(e, p, v)| (e, p.0, v.map(|v| v.0)))
            .collect()
    };
    for round in 0..3 {
        for (_, pos, vel) in prepared.query_mut(&mut world) {
            pos.0 += vel.map_or(10.0, |v| v.0);
        }
        let seen: Vec<(Entity, f32, Option<f32>)> = prepared
            .query(&world)
            .iter()
            .map(|(e, p, v)| (e, p.0, v.map(|v| v.0)))
            .collect();
        assert_eq!(seen, rows(&world), "round {round}");
        world.spawn((Extra::<2>, Vel(0.5), Pos(0.0), Extra::<3>));
    }
    let positions: Vec<f32> = rows(&world).iter().map(|row| row.1).collect();
    // Each run adds `Vel` (or 10 without it); late entities miss earlier runs.
    assert_eq!(positions, vec![4.0, 32.0, 12.0, 1.0, 0.5, 0.0]);
}

#[test]
fn empty_archetypes_are_skipped() {
    let mut world = World::new();
    let a = world.spawn((Pos(1.0),));
    world.despawn(a).unwrap();
    let b = world.spawn((Pos(2.0), Vel(0.0)));
    assert_eq!(world.query::<Entity>().iter().collect::<Vec<_>>(), vec![b]);
    let c = world.spawn((Tag,));
    world.remove_one::<Tag>(c).unwrap();
    assert_eq!(
        world.query::<Entity>().iter().collect::<Vec<_>>(),
        vec![c, b],
        "empty archetype first"
    );
}

fn parallel_result(threads: usize) -> Vec<(u32, f32)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut world = World::new();
    for i in 0..1000u32 {
        if i % 3 == 0 {
            world.spawn((Pos(i as f32), Vel(0.5), Tag));
        } else {
            world.spawn((Pos(i as f32), Vel(0.25)));
        }
    }
    pool.install(|| {
        world
            .query::<(&mut Pos, &Vel)>()
            .par_for_each(7, |(pos, vel)| {
                for _ in 0..10 {
                    pos.0 = (pos.0 + vel.0).sqrt() * 3.0;
                }
            });
        let mut prepared = PreparedQuery::<&mut Pos, With<Tag>>::new();
        prepared.query(&world).par_for_each(0, |pos| pos.0 *= 2.0);
        prepared
            .query_mut(&mut world)
            .par_for_each(64, |pos| pos.0 += 1.0);
    });
    world
        .query::<(Entity, &Pos)>()
        .iter()
        .map(|(e, p)| (e.index(), p.0))
        .collect()
}

#[test]
fn parallel_iteration_does_not_depend_on_thread_count() {
    let one = parallel_result(1);
    assert_eq!(one.len(), 1000);
    let four = parallel_result(4);
    assert_eq!(one.len(), four.len());
    for (x, y) in one.iter().zip(&four) {
        assert_eq!(x.0, y.0);
        assert_eq!(x.1.to_bits(), y.1.to_bits());
    }
    // Same as a sequential walk.
    let mut world = World::new();
    world.spawn((Pos(4.0), Vel(0.0)));
    world
        .query::<&mut Pos>()
        .par_for_each(1, |p| p.0 = p.0.sqrt());
    assert_eq!(world.query::<&Pos>().iter().next().unwrap().0, 2.0);
}

#[test]
fn partially_consumed_iterator_continues_in_parallel() {
    let mut world = World::new();
    world.spawn_batch((0..10).map(|i| (Pos(i as f32),)));
    let mut iter = world.query_mut::<&mut Pos>();
    for pos in iter.by_ref().take(3) {
        pos.0 = -1.0;
    }
    iter.par_for_each(2, |pos| pos.0 = 100.0);
    let values: Vec<f32> = world.query::<&Pos>().iter().map(|p| p.0).collect();
    assert_eq!(values, [vec![-1.0; 3], vec![100.0; 7]].concat());
}
