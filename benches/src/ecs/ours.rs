//! The workloads on our ECS.

use engine::ecs::{PreparedQuery, World};
use engine::schedule::Schedule;

use super::workload::*;
use super::{Contender, measure};

pub(crate) struct Ours;

fn simple_world(count: usize, bundle: fn() -> (Transform, Position, Rotation, Velocity)) -> World {
    let mut world = World::new();
    world.spawn_batch((0..count).map(|_| bundle()));
    world
}

fn swap_system<X: engine::ecs::Component, Y: engine::ecs::Component>(
    get: fn(&mut X, &mut Y),
) -> impl FnMut(&mut World) + Send + 'static {
    let mut query = PreparedQuery::<(&mut X, &mut Y)>::new();
    move |world: &mut World| query.query_mut(world).for_each(|(x, y)| get(x, y))
}

impl Contender for Ours {
    fn simple_insert(&self) -> f64 {
        measure(|| {
            std::hint::black_box(simple_world(SIMPLE_COUNT, simple_bundle));
        })
    }

    fn simple_iter(&self) -> f64 {
        let mut world = simple_world(SIMPLE_COUNT, simple_bundle);
        let mut query = PreparedQuery::<(&Velocity, &mut Position)>::new();
        measure(|| {
            query
                .query_mut(&mut world)
                .for_each(|(velocity, position)| position.0 += velocity.0);
        })
    }

    fn fragmented_iter(&self) -> f64 {
        let mut world = World::new();
        macro_rules! spawn {
            ($name:ident) => {
                world.spawn_batch((0..FRAGMENT_COUNT).map(|_| (fragments::$name(0.0), Data(1.0))));
            };
        }
        for_each_fragment!(spawn);
        let mut query = PreparedQuery::<&mut Data>::new();
        measure(|| query.query_mut(&mut world).for_each(|data| data.0 *= 2.0))
    }

    fn heavy_compute(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        let mut query = PreparedQuery::<(&mut Position, &mut Transform)>::new();
        measure(|| {
            query
                .query_mut(&mut world)
                .for_each(|(position, transform)| heavy_work(position, transform));
        })
    }

    fn heavy_compute_parallel(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        let mut query = PreparedQuery::<(&mut Position, &mut Transform)>::new();
        measure(|| {
            query
                .query_mut(&mut world)
                .par_for_each(BATCH, |(position, transform)| {
                    heavy_work(position, transform)
                });
        })
    }

    fn add_remove(&self) -> f64 {
        let mut world = World::new();
        let entities = world.spawn_batch((0..ADD_REMOVE_COUNT).map(|_| (AddA(0.0),)));
        measure(|| {
            for &entity in &entities {
                world.insert_one(entity, AddB(0.0)).expect("alive");
            }
            for &entity in &entities {
                world.remove_one::<AddB>(entity).expect("has B");
            }
        })
    }

    fn schedule(&self) -> Option<f64> {
        let mut world = World::new();
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0), SD(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0), SE(0.0))));
        let mut schedule = Schedule::new();
        schedule.add_system(
            "ab",
            swap_system::<SA, SB>(|a, b| std::mem::swap(&mut a.0, &mut b.0)),
        );
        schedule.add_system(
            "cd",
            swap_system::<SC, SD>(|c, d| std::mem::swap(&mut c.0, &mut d.0)),
        );
        schedule.add_system(
            "ce",
            swap_system::<SC, SE>(|c, e| std::mem::swap(&mut c.0, &mut e.0)),
        );
        schedule.build().expect("no constraints");
        Some(measure(|| schedule.run(&mut world).expect("no commands")))
    }
}
