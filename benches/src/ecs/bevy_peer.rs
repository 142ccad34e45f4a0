//! The workloads on bevy_ecs (multi-threaded executor, `ComputeTaskPool`
//! initialised once before timing).

use bevy_ecs::batching::BatchingStrategy;
use bevy_ecs::prelude::{Mut, Query};
use bevy_ecs::schedule::Schedule;
use bevy_ecs::world::World;
use bevy_tasks::{ComputeTaskPool, TaskPool};

use super::workload::*;
use super::{Contender, measure};

pub(crate) struct Bevy;

/// Creates bevy's compute pool once, outside every timed loop.
pub(crate) fn init_task_pool() {
    ComputeTaskPool::get_or_init(TaskPool::default);
}

fn simple_world(count: usize, bundle: fn() -> (Transform, Position, Rotation, Velocity)) -> World {
    let mut world = World::new();
    world.spawn_batch((0..count).map(|_| bundle()));
    world
}

fn ab(mut query: Query<(&mut SA, &mut SB)>) {
    for (mut a, mut b) in &mut query {
        std::mem::swap(&mut a.0, &mut b.0);
    }
}

fn cd(mut query: Query<(&mut SC, &mut SD)>) {
    for (mut c, mut d) in &mut query {
        std::mem::swap(&mut c.0, &mut d.0);
    }
}

fn ce(mut query: Query<(&mut SC, &mut SE)>) {
    for (mut c, mut e) in &mut query {
        std::mem::swap(&mut c.0, &mut e.0);
    }
}

impl Contender for Bevy {
    fn simple_insert(&self) -> f64 {
        measure(|| {
            std::hint::black_box(simple_world(SIMPLE_COUNT, simple_bundle));
        })
    }

    fn simple_iter(&self) -> f64 {
        let mut world = simple_world(SIMPLE_COUNT, simple_bundle);
        let mut query = world.query::<(&Velocity, &mut Position)>();
        measure(|| {
            query
                .iter_mut(&mut world)
                .for_each(|(velocity, mut position)| position.0 += velocity.0);
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
        let mut query = world.query::<&mut Data>();
        measure(|| {
            query
                .iter_mut(&mut world)
                .for_each(|mut data| data.0 *= 2.0)
        })
    }

    fn heavy_compute(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        let mut query = world.query::<(&mut Position, &mut Transform)>();
        measure(|| {
            query
                .iter_mut(&mut world)
                .for_each(|(mut position, mut transform)| {
                    heavy_work(&mut position, &mut transform)
                });
        })
    }

    fn heavy_compute_parallel(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        let mut query = world.query::<(&mut Position, &mut Transform)>();
        measure(|| {
            query
                .par_iter_mut(&mut world)
                .batching_strategy(BatchingStrategy::fixed(BATCH))
                .for_each(
                    |(mut position, mut transform): (Mut<Position>, Mut<Transform>)| {
                        heavy_work(&mut position, &mut transform)
                    },
                );
        })
    }

    fn add_remove(&self) -> f64 {
        let mut world = World::new();
        let entities: Vec<bevy_ecs::entity::Entity> = world
            .spawn_batch((0..ADD_REMOVE_COUNT).map(|_| (AddA(0.0),)))
            .collect();
        measure(|| {
            for &entity in &entities {
                world.entity_mut(entity).insert(AddB(0.0));
            }
            for &entity in &entities {
                world.entity_mut(entity).remove::<AddB>();
            }
        })
    }

    fn schedule(&self) -> Option<f64> {
        let mut world = World::new();
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0), SD(0.0))));
        world.spawn_batch((0..SCHEDULE_COUNT).map(|_| (SA(0.0), SB(0.0), SC(0.0), SE(0.0))));
        let mut schedule = Schedule::default();
        schedule.add_systems((ab, cd, ce));
        schedule.run(&mut world);
        Some(measure(|| schedule.run(&mut world)))
    }
}
