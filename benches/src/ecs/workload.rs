//! Component types and sizes of the ecs_bench_suite workloads, shared by all contenders.
// The payload fields give the components the suite's sizes; not every workload reads them.
#![allow(dead_code)]

use bevy_ecs::component::Component;
use glam::{Mat4, Vec3};

/// Entities of `simple_insert` and `simple_iter`.
pub const SIMPLE_COUNT: usize = 10_000;
/// Entities of `heavy_compute`.
pub const HEAVY_COUNT: usize = 1_000;
/// Matrix inversions per entity in `heavy_compute`.
pub const HEAVY_INVERSIONS: usize = 100;
/// Rows per parallel batch.
pub const BATCH: usize = 64;
/// Entities per marker type in `fragmented_iter`.
pub const FRAGMENT_COUNT: usize = 20;
/// Entities of `add_remove`.
pub const ADD_REMOVE_COUNT: usize = 10_000;
/// Entities per archetype in `schedule`.
pub const SCHEDULE_COUNT: usize = 10_000;

#[derive(Component, Clone, Copy)]
pub struct Transform(pub Mat4);
#[derive(Component, Clone, Copy)]
pub struct Position(pub Vec3);
#[derive(Component, Clone, Copy)]
pub struct Rotation(pub Vec3);
#[derive(Component, Clone, Copy)]
pub struct Velocity(pub Vec3);

/// The four-component bundle of `simple_*`.
pub fn simple_bundle() -> (Transform, Position, Rotation, Velocity) {
    (
        Transform(Mat4::from_scale(Vec3::ONE)),
        Position(Vec3::X),
        Rotation(Vec3::X),
        Velocity(Vec3::X),
    )
}

/// The four-component bundle of `heavy_compute`.
pub fn heavy_bundle() -> (Transform, Position, Rotation, Velocity) {
    (
        Transform(Mat4::from_rotation_x(1.2)),
        Position(Vec3::X),
        Rotation(Vec3::X),
        Velocity(Vec3::X),
    )
}

/// The per-entity work of `heavy_compute`.
#[inline]
pub fn heavy_work(position: &mut Position, transform: &mut Transform) {
    for _ in 0..HEAVY_INVERSIONS {
        transform.0 = transform.0.inverse();
    }
    position.0 = transform.0.transform_vector3(position.0);
}

/// The fragmented payload.
#[derive(Component, Clone, Copy)]
pub struct Data(pub f32);

/// Calls `$m!(Type)` for each of the 26 fragment marker types.
macro_rules! for_each_fragment {
    ($m:ident) => {
        $m!(A);
        $m!(B);
        $m!(C);
        $m!(D);
        $m!(E);
        $m!(F);
        $m!(G);
        $m!(H);
        $m!(I);
        $m!(J);
        $m!(K);
        $m!(L);
        $m!(M);
        $m!(N);
        $m!(O);
        $m!(P);
        $m!(Q);
        $m!(R);
        $m!(S);
        $m!(T);
        $m!(U);
        $m!(V);
        $m!(W);
        $m!(X);
        $m!(Y);
        $m!(Z);
    };
}
pub(crate) use for_each_fragment;

/// The 26 fragment marker types `A`..`Z`.
pub mod fragments {
    use bevy_ecs::component::Component;
    macro_rules! marker {
        ($name:ident) => {
            #[derive(Component, Clone, Copy)]
            pub struct $name(pub f32);
        };
    }
    super::for_each_fragment!(marker);
}

/// Schedule workload components.
#[derive(Component, Clone, Copy)]
pub struct SA(pub f32);
#[derive(Component, Clone, Copy)]
pub struct SB(pub f32);
#[derive(Component, Clone, Copy)]
pub struct SC(pub f32);
#[derive(Component, Clone, Copy)]
pub struct SD(pub f32);
#[derive(Component, Clone, Copy)]
pub struct SE(pub f32);

/// Add/remove workload components.
#[derive(Component, Clone, Copy)]
pub struct AddA(pub f32);
#[derive(Component, Clone, Copy)]
pub struct AddB(pub f32);
