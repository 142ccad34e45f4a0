//! The workloads on hecs.

use hecs::{PreparedQuery, World};
use rayon::prelude::*;

use super::workload::*;
use super::{Contender, measure};

pub(crate) struct Hecs;

fn simple_world(count: usize, bundle: fn() -> (Transform, Position, Rotation, Velocity)) -> World {
    let mut world = World::new();
    world.spawn_batch((0..count).map(|_| bundle()));
    world
}

impl Contender for Hecs {
    fn simple_insert(&self) -> f64 {
        measure(|| {
            std::hint::black_box(simple_world(SIMPLE_COUNT, simple_bundle));
        })
    }

    fn simple_iter(&self) -> f64 {
        let mut world = simple_world(SIMPLE_COUNT, simple_bundle);
        let mut query = PreparedQuery::<(&Velocity, &mut Position)>::default();
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
        let mut query = PreparedQuery::<&mut Data>::default();
        measure(|| query.query_mut(&mut world).for_each(|data| data.0 *= 2.0))
    }

    fn heavy_compute(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        let mut query = PreparedQuery::<(&mut Position, &mut Transform)>::default();
        measure(|| {
            query
                .query_mut(&mut world)
                .for_each(|(position, transform)| heavy_work(position, transform));
        })
    }

    fn heavy_compute_parallel(&self) -> f64 {
        let mut world = simple_world(HEAVY_COUNT, heavy_bundle);
        measure(|| {
            world
                .query_mut::<(&mut Position, &mut Transform)>()
                .into_iter_batched(BATCH as u32)
                .par_bridge()
                .for_each(|batch| {
                    batch.for_each(|(position, transform)| heavy_work(position, transform))
                });
        })
    }

    fn add_remove(&self) -> f64 {
        let mut world = World::new();
        let entities: Vec<hecs::Entity> = world
            .spawn_batch((0..ADD_REMOVE_COUNT).map(|_| (AddA(0.0),)))
            .collect();
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
        None
    }
}
