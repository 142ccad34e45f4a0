//! Property test: random operation sequences on the world agree with a simple
//! model (`BTreeMap<Entity, components>`).

use std::collections::BTreeMap;

use engine::ecs::{EcsError, Entity, World};
use proptest::prelude::*;

#[derive(Debug, Clone, Copy, PartialEq)]
struct A(u32);
#[derive(Debug, Clone, PartialEq)]
struct B(String);
#[derive(Debug, Clone, Copy, PartialEq)]
struct C;

#[derive(Debug, Clone, Default, PartialEq)]
struct Model {
    a: Option<A>,
    b: Option<B>,
    c: Option<C>,
}

#[derive(Debug, Clone)]
enum Op {
    Spawn(u8, u32),
    InsertA(usize, u32),
    InsertB(usize, u32),
    InsertC(usize),
    RemoveA(usize),
    RemoveAB(usize),
    RemoveC(usize),
    Despawn(usize),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (0u8..8, any::<u32>()).prop_map(|(m, v)| Op::Spawn(m, v)),
        (any::<usize>(), any::<u32>()).prop_map(|(i, v)| Op::InsertA(i, v)),
        (any::<usize>(), any::<u32>()).prop_map(|(i, v)| Op::InsertB(i, v)),
        any::<usize>().prop_map(Op::InsertC),
        any::<usize>().prop_map(Op::RemoveA),
        any::<usize>().prop_map(Op::RemoveAB),
        any::<usize>().prop_map(Op::RemoveC),
        any::<usize>().prop_map(Op::Despawn),
    ]
}

/// Spawns an entity with the components selected by the bits of `mask`.
fn spawn(world: &mut World, mask: u8, value: u32) -> (Entity, Model) {
    let a = A(value);
    let b = B(value.to_string());
    let entity = match mask % 8 {
        0 => world.spawn((a,)),
        1 => world.spawn((a, b.clone())),
        2 => world.spawn((b.clone(),)),
        3 => world.spawn((a, b.clone(), C)),
        4 => world.spawn((C,)),
        5 => world.spawn((C, a)),
        6 => world.spawn((b.clone(), C)),
        _ => {
            let e = world.spawn((a,));
            world.remove_one::<A>(e).unwrap();
            return (e, Model::default());
        }
    };
    let m = mask % 8;
    let model = Model {
        a: [0, 1, 3, 5].contains(&m).then_some(a),
        b: [1, 2, 3, 6].contains(&m).then_some(b),
        c: [3, 4, 5, 6].contains(&m).then_some(C),
    };
    (entity, model)
}

fn check(world: &World, model: &BTreeMap<Entity, Model>, dead: &[Entity]) {
    assert_eq!(world.len(), model.len());
    assert_eq!(
        world.entities().collect::<Vec<_>>(),
        model.keys().copied().collect::<Vec<_>>()
    );
    for (&entity, expected) in model {
        assert_eq!(world.get::<A>(entity).ok().map(|r| *r), expected.a);
        assert_eq!(world.get::<B>(entity).ok().map(|r| r.clone()), expected.b);
        assert_eq!(world.get::<C>(entity).ok().map(|r| *r), expected.c);
    }
    for &entity in dead {
        assert!(!world.contains(entity));
        assert_eq!(
            world.get::<A>(entity).unwrap_err(),
            EcsError::NoSuchEntity(entity)
        );
    }
    let mut from_query: Vec<(Entity, Option<u32>, Option<String>, bool)> = world
        .query::<(Entity, Option<&A>, Option<&B>, Option<&C>)>()
        .iter()
        .map(|(e, a, b, c)| (e, a.map(|a| a.0), b.map(|b| b.0.clone()), c.is_some()))
        .collect();
    from_query.sort_by_key(|row| row.0);
    let expected: Vec<(Entity, Option<u32>, Option<String>, bool)> = model
        .iter()
        .map(|(&e, m)| (e, m.a.map(|a| a.0), m.b.clone().map(|b| b.0), m.c.is_some()))
        .collect();
    assert_eq!(from_query, expected);
}

fn apply(world: &mut World, model: &mut BTreeMap<Entity, Model>, dead: &mut Vec<Entity>, op: Op) {
    // Targets include dead ids, so stale handles are exercised too.
    let pick = |i: usize| -> Option<Entity> {
        let live: Vec<Entity> = model.keys().copied().collect();
        let all: Vec<Entity> = live.iter().chain(dead.iter()).copied().collect();
        (!all.is_empty()).then(|| all[i % all.len()])
    };
    match op {
        Op::Spawn(mask, value) => {
            let (entity, m) = spawn(world, mask, value);
            assert!(model.insert(entity, m).is_none(), "ids are fresh");
        }
        Op::InsertA(i, v) => {
            let Some(e) = pick(i) else { return };
            let result = world.insert_one(e, A(v));
            match model.get_mut(&e) {
                Some(m) => {
                    assert_eq!(result, Ok(()));
                    m.a = Some(A(v));
                }
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::InsertB(i, v) => {
            let Some(e) = pick(i) else { return };
            let result = world.insert(e, (B(v.to_string()), A(v)));
            match model.get_mut(&e) {
                Some(m) => {
                    assert_eq!(result, Ok(()));
                    m.b = Some(B(v.to_string()));
                    m.a = Some(A(v));
                }
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::InsertC(i) => {
            let Some(e) = pick(i) else { return };
            let result = world.insert_one(e, C);
            match model.get_mut(&e) {
                Some(m) => {
                    assert_eq!(result, Ok(()));
                    m.c = Some(C);
                }
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::RemoveA(i) => {
            let Some(e) = pick(i) else { return };
            let result = world.remove_one::<A>(e);
            match model.get_mut(&e) {
                Some(m) => assert_eq!(result.ok(), m.a.take()),
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::RemoveAB(i) => {
            let Some(e) = pick(i) else { return };
            let result = world.remove::<(A, B)>(e);
            match model.get_mut(&e) {
                Some(m) if m.a.is_some() && m.b.is_some() => {
                    assert_eq!(result, Ok((m.a.take().unwrap(), m.b.take().unwrap())));
                }
                Some(_) => assert!(matches!(result, Err(EcsError::MissingComponent { .. }))),
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::RemoveC(i) => {
            let Some(e) = pick(i) else { return };
            let result = world.remove_one::<C>(e);
            match model.get_mut(&e) {
                Some(m) => assert_eq!(result.ok(), m.c.take()),
                None => assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e))),
            }
        }
        Op::Despawn(i) => {
            let Some(e) = pick(i) else { return };
            let result = world.despawn(e);
            if model.remove(&e).is_some() {
                assert_eq!(result, Ok(()));
                dead.push(e);
            } else {
                assert_eq!(result.err(), Some(EcsError::NoSuchEntity(e)));
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn world_matches_model(ops in prop::collection::vec(op(), 1..120)) {
        let mut world = World::new();
        let mut model = BTreeMap::new();
        let mut dead = Vec::new();
        for op in ops {
            apply(&mut world, &mut model, &mut dead, op);
            check(&world, &model, &dead);
        }
    }
}
