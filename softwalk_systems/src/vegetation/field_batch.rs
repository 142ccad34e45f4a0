//! The paper's field (eq. 2) on many upright blades at once.
//!
//! The blades a moving foot reaches are gathered into chunks of [`LANES`]
//! blades (structure of arrays inside each chunk), and every foot's field is
//! evaluated on whole chunks with selects instead of branches, so the compiler
//! vectorises it. Each lane performs exactly the IEEE operations of
//! [`DeformationField::on_upright_blade`] in the same order (a skipped foot
//! adds `+0.0`, which leaves the sum unchanged as it is never `-0.0`), so the
//! result is bit-identical to the scalar path.
//!
//! With many feet, the feet are binned into a coarse grid ([`FootBins`],
//! bins as wide as the field's reach) and each chunk is evaluated only
//! against the feet of the bins within reach of its blades, in their index
//! order: the feet left out would add only `+0.0`, so the result is the same
//! bits and the cost follows the feet near each blade, not all of them.

use glam::Vec3;

use super::blade::Bend;
use super::field::DeformationField;
use super::field_memo::FieldMemo;
use super::foot_bins::FootBins;
use super::lanes::{F8, LANES, Mask};

/// Upright geometry of [`LANES`] blades: root X and Z, middle and tip Y.
#[derive(Debug, Clone, Copy, Default)]
struct Upright {
    x: [f32; LANES],
    z: [f32; LANES],
    mid_y: [f32; LANES],
    tip_y: [f32; LANES],
}

impl Upright {
    /// The XZ bounding box `(min, max)` of the first `used` blades.
    fn bounds(&self, used: usize) -> ([f32; 2], [f32; 2]) {
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for l in 0..used {
            lo = [lo[0].min(self.x[l]), lo[1].min(self.z[l])];
            hi = [hi[0].max(self.x[l]), hi[1].max(self.z[l])];
        }
        (lo, hi)
    }
}

/// A translation of [`LANES`] points.
#[derive(Debug, Clone, Copy)]
struct Points {
    x: F8,
    y: F8,
    z: F8,
}

impl Points {
    #[inline(always)]
    fn length_squared(self) -> F8 {
        self.x * self.x + self.y * self.y + self.z * self.z
    }

    /// Per lane, `self` where `mask` holds, else zero.
    #[inline(always)]
    fn or_zero(self, mask: Mask) -> Points {
        Points {
            x: mask.or_zero(self.x),
            y: mask.or_zero(self.y),
            z: mask.or_zero(self.z),
        }
    }

    #[inline(always)]
    fn add(self, other: Points) -> Points {
        Points {
            x: self.x + other.x,
            y: self.y + other.y,
            z: self.z + other.z,
        }
    }

    /// The points, lane by lane.
    #[inline(always)]
    fn lanes(self) -> [Vec3; LANES] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|l| Vec3::new(x[l], y[l], z[l]))
    }
}

/// Blades gathered for one batch evaluation; kept between steps so a step
/// does not allocate.
#[derive(Debug, Clone, Default)]
pub(crate) struct FieldBatch {
    upright: Vec<Upright>,
    len: usize,
    bins: FootBins,
    near_index: Vec<u32>,
    near: Vec<Vec3>,
}

/// Above this many feet a chunk gathers the feet near it from [`FootBins`]
/// instead of looping over all of them.
const BINNED_FEET: usize = 8;

impl FieldBatch {
    /// Empties the batch.
    pub(crate) fn clear(&mut self) {
        self.upright.clear();
        self.len = 0;
    }

    /// Adds a blade by its upright geometry `[root x, root z, middle y, tip y]`.
    pub(crate) fn push(&mut self, [x, z, mid_y, tip_y]: [f32; 4]) {
        let l = self.len % LANES;
        if l == 0 {
            self.upright.push(Upright::default());
        }
        let chunk = self.upright.last_mut().expect("a chunk was just ensured");
        chunk.x[l] = x;
        chunk.z[l] = z;
        chunk.mid_y[l] = mid_y;
        chunk.tip_y[l] = tip_y;
        self.len += 1;
    }

    /// Evaluates the combined field of `feet` on every blade of the batch and
    /// hands each result, in insertion order, to `out`.
    pub(crate) fn evaluate(
        &mut self,
        field: &DeformationField,
        feet: &[Vec3],
        mut out: impl FnMut(FieldMemo),
    ) {
        let binned = feet.len() > BINNED_FEET;
        let reach = field.radius();
        if binned {
            self.bins.rebuild(feet, reach);
        }
        let mut left = self.len;
        for chunk in &self.upright {
            let used = LANES.min(left);
            let near = if binned {
                let (lo, hi) = chunk.bounds(used);
                self.near_index.clear();
                self.bins.gather(
                    [lo[0] - reach, lo[1] - reach],
                    [hi[0] + reach, hi[1] + reach],
                    &mut self.near_index,
                );
                self.near.clear();
                self.near
                    .extend(self.near_index.iter().map(|&k| feet[k as usize]));
                &self.near[..]
            } else {
                feet
            };
            let (mid, tip, size) = evaluate_chunk(field, near, chunk);
            let (mid, tip, size) = (mid.lanes(), tip.lanes(), size.to_array());
            for l in 0..used {
                let bend = Bend {
                    mid: mid[l],
                    tip: tip[l],
                };
                out(FieldMemo {
                    bend,
                    size: size[l],
                });
            }
            left = left.saturating_sub(LANES);
        }
    }
}

/// The field on one chunk: the capped middle and tip translations and their
/// size `|mid| + |tip|` (as `DeformationField::on_upright_blade` and
/// `FieldMemo::new`).
#[inline]
fn evaluate_chunk(field: &DeformationField, feet: &[Vec3], b: &Upright) -> (Points, Points, F8) {
    let radius_sq = F8::splat(field.radius() * field.radius());
    let (x, z) = (F8::new(b.x), F8::new(b.z));
    let (mid_y, tip_y) = (F8::new(b.mid_y), F8::new(b.tip_y));
    let zero = F8::splat(0.0);
    let mut mid = Points {
        x: zero,
        y: zero,
        z: zero,
    };
    let mut tip = mid;
    for foot in feet {
        let dx = x - F8::splat(foot.x);
        let dz = z - F8::splat(foot.z);
        let reach = (dx * dx + dz * dz).lt(radius_sq);
        if reach.bitmask() == 0 {
            // Out of every lane's reach: it would add only zeros.
            continue;
        }
        let foot_y = F8::splat(foot.y);
        mid = mid.add(for_offset(field, dx, mid_y - foot_y, dz).or_zero(reach));
        tip = tip.add(for_offset(field, dx, tip_y - foot_y, dz).or_zero(reach));
    }
    let (mid, mid_len) = capped(field.t_max, mid);
    let (tip, tip_len) = capped(field.t_max, tip);
    (mid, tip, mid_len + tip_len)
}

/// `DeformationField::for_offset` on lanes, with selects for its branches.
#[inline(always)]
fn for_offset(field: &DeformationField, dx: F8, dy: F8, dz: F8) -> Points {
    let radius = field.radius();
    let t_max = F8::splat(field.t_max);
    let zero = F8::splat(0.0);
    let d = Points {
        x: dx,
        y: dy,
        z: dz,
    };
    let dist_sq = d.length_squared();
    let inside = dist_sq.lt(F8::splat(radius * radius));
    if inside.bitmask() == 0 {
        // No lane within reach: the field is zero in all of them.
        return Points {
            x: zero,
            y: zero,
            z: zero,
        };
    }
    let dist = dist_sq.sqrt();
    let raw = t_max - F8::splat(field.gamma) * dist;
    let floored = raw.lt(zero).select(zero, raw);
    let magnitude = floored.gt(t_max).select(t_max, floored);
    let at_foot = dist.le(F8::splat(f32::EPSILON * radius));
    let scale = magnitude / dist;
    let t = Points {
        x: at_foot.select(zero, dx * scale),
        y: at_foot.select(-magnitude, -dy.abs() * scale),
        z: at_foot.select(zero, dz * scale),
    };
    t.or_zero(inside)
}

/// `v` with its length capped at `t_max` (as `DeformationField::capped`),
/// and the length of the result (as `Vec3::length`).
#[inline(always)]
fn capped(t_max: f32, v: Points) -> (Points, F8) {
    let len_sq = v.length_squared();
    let len = len_sq.sqrt();
    let cap = len_sq.gt(F8::splat(t_max * t_max));
    if cap.bitmask() == 0 {
        // Nothing to cap (the usual case: one foot alone never exceeds
        // `t_max`): the length is the one just taken.
        return (v, len);
    }
    let scale = F8::splat(t_max) / len;
    let scaled = Points {
        x: v.x * scale,
        y: v.y * scale,
        z: v.z * scale,
    };
    let out = Points {
        x: cap.select(scaled.x, v.x),
        y: cap.select(scaled.y, v.y),
        z: cap.select(scaled.z, v.z),
    };
    (out, cap.select(scaled.length_squared().sqrt(), len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::rng::SplitMix64;

    /// The batch against the scalar field, bit for bit, on random blades and
    /// feet, plus the edge cases: a foot on a blade's middle, far feet, and
    /// feet on top of each other (the cap).
    #[test]
    fn batch_is_bit_identical_to_the_scalar_field() {
        let field = DeformationField {
            t_max: 0.35,
            gamma: 0.8,
        };
        let mut rng = SplitMix64::new(7);
        let mut blades: Vec<(Vec3, f32)> = (0..203)
            .map(|_| {
                let root = Vec3::new(
                    rng.range(-0.6, 0.6),
                    rng.range(-0.1, 0.1),
                    rng.range(-0.6, 0.6),
                );
                (root, rng.range(0.3, 0.9))
            })
            .collect();
        let feet = [
            Vec3::new(0.05, 0.1, -0.1),
            Vec3::new(0.1, 0.1, -0.1),
            Vec3::new(9.0, 0.0, 0.0),
        ];
        // A blade whose middle is exactly at the first foot.
        blades.push((Vec3::new(0.05, 0.0, -0.1), 0.2));
        for n_feet in 0..=feet.len() {
            let feet = &feet[..n_feet];
            let mut batch = FieldBatch::default();
            for &(root, h) in &blades {
                batch.push([root.x, root.z, root.y + 0.5 * h, root.y + h]);
            }
            let mut got = Vec::new();
            batch.evaluate(&field, feet, |m| got.push(m));
            assert_eq!(got.len(), blades.len());
            for (k, (&(root, h), memo)) in blades.iter().zip(&got).enumerate() {
                let [mid, tip] = field.on_upright_blade(root, h, feet);
                let want = FieldMemo::new(Bend { mid, tip });
                let bits = |m: &FieldMemo| {
                    let b = m.bend;
                    [b.mid, b.tip].map(|v| v.to_array().map(f32::to_bits))
                };
                assert_eq!(bits(memo), bits(&want), "blade {k}, {n_feet} feet");
                assert_eq!(memo.size.to_bits(), want.size.to_bits(), "blade {k}");
            }
            if n_feet >= 1 {
                assert!(got.iter().any(|m| m.size > 0.0));
            }
        }
    }

    #[test]
    fn cleared_batch_is_empty() {
        let mut batch = FieldBatch::default();
        batch.push([0.0; 4]);
        batch.clear();
        let mut n = 0;
        batch.evaluate(
            &DeformationField {
                t_max: 0.3,
                gamma: 1.0,
            },
            &[Vec3::ZERO],
            |_| n += 1,
        );
        assert_eq!(n, 0);
    }
}
