//! A hash of the simulated world's state, for determinism checks.

use engine::ecs::World;
use engine::schedule::Time;
use glam::Vec3;

use super::components::Feet;
use super::ground_state::GroundState;
use crate::character::{Gait, Pose, RigidProxy};
use crate::vegetation::{Bend, GrassPatch};

/// FNV-1a over the exact bits of what it is fed: equal hashes mean bit-identical inputs
/// (up to the usual 64-bit collision odds).
#[derive(Debug, Clone, Copy)]
pub struct WorldHasher(u64);

impl Default for WorldHasher {
    fn default() -> Self {
        WorldHasher(0xcbf2_9ce4_8422_2325)
    }
}

impl WorldHasher {
    /// Feeds raw bytes.
    pub fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }

    /// Feeds a `u64`.
    pub fn u64(&mut self, v: u64) {
        self.bytes(&v.to_le_bytes());
    }

    /// Feeds the bits of an `f32` (so -0.0 and 0.0 differ, as they do in state).
    pub fn f32(&mut self, v: f32) {
        self.bytes(&v.to_bits().to_le_bytes());
    }

    /// Feeds the bits of every value.
    pub fn f32s(&mut self, vs: &[f32]) {
        for &v in vs {
            self.f32(v);
        }
    }

    /// Feeds a vector's three components.
    pub fn vec3(&mut self, v: Vec3) {
        self.f32s(&v.to_array());
    }

    /// The hash so far.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

fn bend(h: &mut WorldHasher, b: &Bend) {
    h.vec3(b.mid);
    h.vec3(b.tip);
}

/// Hash of the world's simulated state: the clock, every terrain height and
/// trodden mark, every character's pose, proxy, gait and feet, and every blade's
/// state. Rendering never changes it.
pub fn world_hash(world: &World) -> u64 {
    let mut h = WorldHasher::default();
    if let Some(t) = world.get_resource::<Time>() {
        h.u64(t.step);
    }
    if let Some(ground) = world.get_resource::<GroundState>() {
        let hf = ground.terrain();
        h.f32s(hf.grid().heights());
        h.bytes(hf.disturbed());
    }
    for (pose, proxy, gait, feet) in world.query::<(&Pose, &RigidProxy, &Gait, &Feet)>().iter() {
        for &j in &pose.joints {
            h.vec3(j);
        }
        h.f32s(&[
            proxy.tilt,
            proxy.tilt_rate,
            proxy.torque,
            gait.distance,
            gait.phase,
        ]);
        for f in &feet.0 {
            h.vec3(f.sole.heel);
            h.vec3(f.sole.toe);
            h.bytes(&[u8::from(f.contact), u8::from(f.pressing)]);
        }
    }
    for patch in world.query::<&GrassPatch>().iter() {
        for s in patch.states() {
            bend(&mut h, &s.held);
            bend(&mut h, &s.rest);
            h.u64(s.treads.into());
            h.bytes(&[u8::from(s.broken)]);
        }
    }
    h.finish()
}
