//! Structure-of-arrays copy of the blades' upright geometry: the candidate
//! test of a deformation step scans contiguous grid slices of these columns in
//! fixed chunks of [`LANES`] blades, against every foot in one pass, a loop
//! without branches that the compiler vectorises.

use std::ops::Range;

use glam::Vec3;

use super::blade::Blade;
use super::lanes::{F8, LANES};

/// A point the candidate test measures blades against, and what the blades
/// within its reach become.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Marker {
    /// Foot position (world).
    pub(crate) at: Vec3,
    /// The blades it reaches are pushed this step.
    pub(crate) reaches: bool,
    /// The blades it reaches need their field computed anew.
    pub(crate) disturbs: bool,
}

/// Root X and Z and the heights of the upright middle and tip of the blades,
/// one column each, in storage order, each followed by [`LANES`] padding
/// entries out of every foot's reach (so any range can be read in whole chunks).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct BladeColumns {
    x: Vec<f32>,
    z: Vec<f32>,
    mid_y: Vec<f32>,
    tip_y: Vec<f32>,
    /// The lowest upright middle Y (infinite for no blades).
    lowest_mid: f32,
    /// The highest upright tip Y (minus infinity for no blades).
    highest_tip: f32,
}

impl BladeColumns {
    /// The columns of `blades`.
    pub(crate) fn new(blades: &[Blade]) -> Self {
        let column = |f: &dyn Fn(&Blade) -> f32| -> Vec<f32> {
            let padding = std::iter::repeat_n(f32::INFINITY, LANES);
            blades.iter().map(f).chain(padding).collect()
        };
        // Same arithmetic as `DeformationField::on_upright_blade`.
        let (mid_y, tip_y) = (
            column(&|b| b.root.y + 0.5 * b.height),
            column(&|b| b.root.y + b.height),
        );
        let blades = ..blades.len();
        Self {
            x: column(&|b| b.root.x),
            z: column(&|b| b.root.z),
            lowest_mid: mid_y[blades].iter().copied().fold(f32::INFINITY, f32::min),
            highest_tip: tip_y[blades]
                .iter()
                .copied()
                .fold(f32::NEG_INFINITY, f32::max),
            mid_y,
            tip_y,
        }
    }

    /// The lowest upright middle Y (infinite for no blades).
    pub(crate) fn lowest_mid(&self) -> f32 {
        self.lowest_mid
    }

    /// Root X, root Z, upright middle Y and upright tip Y of blade `i`.
    #[inline]
    pub(crate) fn upright(&self, i: usize) -> [f32; 4] {
        [self.x[i], self.z[i], self.mid_y[i], self.tip_y[i]]
    }

    /// Appends to `reached` the blades of `blades` that some marker that
    /// reaches is closer than `radius` to, and to `fresh` those of them that
    /// also some disturbing marker is within `radius` of, both in storage
    /// order. A blade is within reach when its upright middle or tip is: these
    /// are exactly the blades a foot there pushes (same arithmetic as
    /// [`DeformationField::on_upright_blade`](super::DeformationField::on_upright_blade)).
    pub(crate) fn collect_reached(
        &self,
        blades: Range<usize>,
        markers: &[Marker],
        radius: f32,
        reached: &mut Vec<u32>,
        fresh: &mut Vec<u32>,
    ) {
        let r2 = F8::splat(radius * radius);
        let chunks = blades.len().div_ceil(LANES);
        let end = blades.start + chunks * LANES;
        // Room for every blade of the range plus a whole chunk: each chunk
        // writes all its lanes and keeps those that matched (no branches).
        let mut reached_list = ChunkList::open(reached, blades.len());
        let mut fresh_list = ChunkList::open(fresh, blades.len());
        let columns = self.x[blades.start..end]
            .chunks_exact(LANES)
            .zip(self.z[blades.start..end].chunks_exact(LANES))
            .zip(self.mid_y[blades.start..end].chunks_exact(LANES))
            .zip(self.tip_y[blades.start..end].chunks_exact(LANES));
        for (c, (((x, z), mid), tip)) in columns.enumerate() {
            let (x, z) = (F8::load(x), F8::load(z));
            let (mid, tip) = (F8::load(mid), F8::load(tip));
            let (mut reaching, mut disturbing) = (0u32, 0u32);
            for m in markers {
                let (dx, dz) = (x - F8::splat(m.at.x), z - F8::splat(m.at.z));
                let (dx_sq, dz_sq) = (dx * dx, dz * dz);
                let within = |y: F8| {
                    let dy = y - F8::splat(m.at.y);
                    (dx_sq + dy * dy + dz_sq).lt(r2)
                };
                // A marker below every middle is nearer each blade's middle
                // than its tip, one above every tip nearer the tip (rounding
                // is monotonic): then one test decides.
                let near = if m.at.y <= self.lowest_mid {
                    within(mid)
                } else if m.at.y >= self.highest_tip {
                    within(tip)
                } else {
                    within(mid) | within(tip)
                }
                .bitmask();
                reaching |= near & u32::from(m.reaches).wrapping_neg();
                disturbing |= near & u32::from(m.disturbs).wrapping_neg();
            }
            let base = blades.start + c * LANES;
            // Lanes past the range's end belong to other blades.
            let valid = (1u32 << (blades.end - base).min(LANES)) - 1;
            let reaching = reaching & valid;
            reached_list.push(base, reaching);
            fresh_list.push(base, reaching & disturbing);
        }
        reached_list.close();
        fresh_list.close();
    }
}

/// A list of blade indices being appended to chunk by chunk.
struct ChunkList<'a> {
    out: &'a mut Vec<u32>,
    len: usize,
}

impl<'a> ChunkList<'a> {
    /// Starts appending to `out` at most `blades` indices.
    #[inline(always)]
    fn open(out: &'a mut Vec<u32>, blades: usize) -> Self {
        let len = out.len();
        out.resize(len + blades + LANES, 0);
        Self { out, len }
    }

    /// Appends `base + l` for every bit `l` set in `lanes`, in increasing order.
    #[inline(always)]
    fn push(&mut self, base: usize, lanes: u32) {
        let lanes = lanes as usize & 0xFF;
        let offsets = &COMPRESSED_LANES[lanes];
        let slots = &mut self.out[self.len..self.len + LANES];
        for (slot, &offset) in slots.iter_mut().zip(offsets) {
            *slot = (base + offset as usize) as u32;
        }
        self.len += lanes.count_ones() as usize;
    }

    /// Drops the unused room.
    #[inline(always)]
    fn close(self) {
        self.out.truncate(self.len);
    }
}

/// For each 8-bit lane mask, the indices of its set bits in increasing order
/// (the rest of the entry is padding).
const COMPRESSED_LANES: [[u8; LANES]; 256] = {
    let mut table = [[0u8; LANES]; 256];
    let mut mask = 0;
    while mask < 256 {
        let (mut bit, mut n) = (0, 0);
        while bit < LANES {
            if mask & (1 << bit) != 0 {
                table[mask][n] = bit as u8;
                n += 1;
            }
            bit += 1;
        }
        mask += 1;
    }
    table
};

#[cfg(test)]
mod tests {
    use super::*;

    fn blade(x: f32, y: f32, height: f32) -> Blade {
        Blade {
            root: Vec3::new(x, y, 0.0),
            height,
            width: 0.01,
            stiffness: 1.0,
            colour: [0.0; 3],
        }
    }

    fn marker(x: f32, y: f32, reaches: bool, disturbs: bool) -> Marker {
        Marker {
            at: Vec3::new(x, y, 0.0),
            reaches,
            disturbs,
        }
    }

    fn collect(
        columns: &BladeColumns,
        blades: Range<usize>,
        markers: &[Marker],
    ) -> (Vec<u32>, Vec<u32>) {
        let (mut reached, mut fresh) = (vec![99], vec![99]);
        columns.collect_reached(blades, markers, 0.5, &mut reached, &mut fresh);
        (reached[1..].to_vec(), fresh[1..].to_vec())
    }

    #[test]
    fn collects_blades_whose_middle_or_tip_is_within_the_radius() {
        // Beside the foot; below it (tip reaches up); far above it; far
        // aside; root and tip out of reach with the foot between them.
        let blades = [
            blade(0.3, 0.0, 0.5),
            blade(0.0, -1.0, 0.9),
            blade(0.0, 1.0, 0.5),
            blade(2.0, 0.0, 0.5),
            blade(0.0, -0.8, 3.2),
        ];
        let columns = BladeColumns::new(&blades);
        let still = collect(&columns, 0..5, &[marker(0.0, 0.2, true, false)]);
        assert_eq!(still, (vec![0, 1], vec![]), "appended after what was there");
        let moved = collect(&columns, 0..5, &[marker(0.0, 0.2, true, true)]);
        assert_eq!(moved, (vec![0, 1], vec![0, 1]));
        // A foot that left (disturbs only) and a still foot.
        let mixed = [
            marker(2.0, 0.1, false, true),
            marker(2.0, 0.1, true, false),
            marker(0.0, 1.2, true, false),
        ];
        assert_eq!(collect(&columns, 2..4, &mixed), (vec![2, 3], vec![3]));
        assert_eq!(
            collect(&columns, 0..2, &mixed),
            (vec![], vec![]),
            "range end respected"
        );
    }

    #[test]
    fn compressed_lanes_list_the_set_bits() {
        assert_eq!(COMPRESSED_LANES.len(), 256);
        for (mask, entry) in COMPRESSED_LANES.iter().enumerate() {
            let bits: Vec<u8> = (0..8).filter(|&b| mask & (1 << b) != 0).collect();
            assert_eq!(entry[..bits.len()], bits[..], "mask {mask:#b}");
        }
    }

    #[test]
    fn ranges_longer_than_a_chunk_collect_every_blade() {
        let blades: Vec<Blade> = (0..20).map(|k| blade(0.1 * k as f32, 0.0, 0.5)).collect();
        let columns = BladeColumns::new(&blades);
        let markers = [Marker {
            at: Vec3::new(1.0, 0.25, 0.0),
            reaches: true,
            disturbs: true,
        }];
        let (mut reached, mut fresh) = (Vec::new(), Vec::new());
        columns.collect_reached(3..20, &markers, 0.35, &mut reached, &mut fresh);
        assert_eq!(reached, [7, 8, 9, 10, 11, 12, 13]);
        assert_eq!(fresh, reached);
        columns.collect_reached(3..8, &markers, 0.35, &mut reached, &mut fresh);
        assert_eq!(reached[7..], [7]);
    }
}
