//! [`Row`]: one `f32` per child lane of a wide BVH node, with the few
//! element-wise operations a box test needs, written over a fixed-size array
//! so that the compiler vectorises them for whatever the code is compiled
//! for: one 8-lane `ymm` operation per step in an AVX2 compilation, two
//! 4-lane `xmm` ones on the SSE2 baseline. One implementation serves both,
//! and each operation is the IEEE one lane by lane (never fused), so every
//! compilation gives the same bits.

use std::ops::{Index, Mul, Sub};

use glam::{BVec4A, Vec4};

/// One value per lane, `N` lanes (a multiple of 4), aligned so that a row
/// is whole vector registers.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct Row<const N: usize>(pub(crate) [f32; N]);

impl<const N: usize> Row<N> {
    /// `value` in every lane.
    #[inline(always)]
    pub(crate) const fn splat(value: f32) -> Row<N> {
        Row([value; N])
    }

    /// Lane by lane, `self` where `self > other`, else `other` (the SSE
    /// `maxps` rule: `other` when either is NaN).
    #[inline(always)]
    pub(crate) fn max(self, other: Row<N>) -> Row<N> {
        self.zip(other, |a, b| if a > b { a } else { b })
    }

    /// Lane by lane, `self` where `self < other`, else `other` (the SSE
    /// `minps` rule: `other` when either is NaN).
    #[inline(always)]
    pub(crate) fn min(self, other: Row<N>) -> Row<N> {
        self.zip(other, |a, b| if a < b { a } else { b })
    }

    /// Lane by lane, `self` where `self <= other` (false with a NaN), else
    /// `instead`.
    #[inline(always)]
    pub(crate) fn where_le(self, other: Row<N>, instead: f32) -> Row<N> {
        self.zip(other, |a, b| if a <= b { a } else { instead })
    }

    /// The smallest lane, in every lane: a butterfly of lane swaps, each a
    /// whole-row operation (with no NaN lane, the order of the comparisons
    /// does not matter).
    #[inline(always)]
    pub(crate) fn min_all(self) -> Row<N> {
        let mut row = self;
        let mut stride = N / 2;
        while stride > 0 {
            row = row.min(Row(std::array::from_fn(|k| row.0[k ^ stride])));
            stride /= 2;
        }
        row
    }

    /// Bit `k` set when lane `k` is at most lane `k` of `other` (false
    /// with a NaN).
    #[inline(always)]
    pub(crate) fn lanes_le(&self, other: &Row<N>) -> u32 {
        self.mask(other, Vec4::cmple)
    }

    /// Bit `k` set when lane `k` equals lane `k` of `other`.
    #[inline(always)]
    pub(crate) fn lanes_eq(&self, other: &Row<N>) -> u32 {
        self.mask(other, Vec4::cmpeq)
    }

    #[inline(always)]
    fn zip(self, other: Row<N>, f: impl Fn(f32, f32) -> f32) -> Row<N> {
        Row(std::array::from_fn(|k| f(self.0[k], other.0[k])))
    }

    /// Bit `k` set where `test` holds for lane `k` of `self` and `other`,
    /// four lanes at a time: a form the compiler turns into one mask move
    /// per register, where a fold over single lanes comes out as a long
    /// sequence of bit shuffles.
    #[inline(always)]
    fn mask(&self, other: &Row<N>, test: impl Fn(Vec4, Vec4) -> BVec4A) -> u32 {
        self.0
            .chunks_exact(4)
            .zip(other.0.chunks_exact(4))
            .enumerate()
            .fold(0, |mask, (q, (a, b))| {
                mask | test(Vec4::from_slice(a), Vec4::from_slice(b)).bitmask() << (4 * q)
            })
    }
}

impl<const N: usize> Sub<f32> for Row<N> {
    type Output = Row<N>;
    #[inline(always)]
    fn sub(self, value: f32) -> Row<N> {
        Row(self.0.map(|a| a - value))
    }
}

impl<const N: usize> Mul<f32> for Row<N> {
    type Output = Row<N>;
    #[inline(always)]
    fn mul(self, value: f32) -> Row<N> {
        Row(self.0.map(|a| a * value))
    }
}

impl<const N: usize> Index<usize> for Row<N> {
    type Output = f32;
    #[inline(always)]
    fn index(&self, lane: usize) -> &f32 {
        &self.0[lane]
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use super::*;

    /// Two rows of four that exercise NaN, infinities, signed zeros and ties.
    fn samples() -> [(Row<4>, Row<4>); 3] {
        [
            (
                Row([f32::NAN, 1.0, -0.0, f32::INFINITY]),
                Row([2.0, f32::NAN, 0.0, f32::NEG_INFINITY]),
            ),
            (Row([1.0, 2.0, 3.0, 4.0]), Row([4.0, 2.0, 1.0, 5.0])),
            (Row([0.0; 4]), Row([-0.0, 1e-30, -1e30, f32::NAN])),
        ]
    }

    fn bits(r: Row<4>) -> [u32; 4] {
        r.0.map(f32::to_bits)
    }

    #[test]
    fn lane_operations_follow_the_sse_rules_bit_for_bit() {
        for (a, b) in samples() {
            let (va, vb) = (Vec4::from_array(a.0), Vec4::from_array(b.0));
            assert_eq!(bits(a.max(b)), va.max(vb).to_array().map(f32::to_bits));
            assert_eq!(bits(a.min(b)), va.min(vb).to_array().map(f32::to_bits));
            let le = Vec4::select(va.cmple(vb), va, Vec4::INFINITY);
            assert_eq!(
                bits(a.where_le(b, f32::INFINITY)),
                le.to_array().map(f32::to_bits)
            );
            assert_eq!(a.lanes_le(&b), va.cmple(vb).bitmask());
        }
        let row = Row([3.0, -1.0, 7.0, -1.0, 2.0, 9.0, 0.5, 4.0]);
        let least = row.min_all();
        assert_eq!(least, Row::splat(-1.0));
        assert_eq!(row.lanes_eq(&least), 0b1010);
        assert_eq!(row.lanes_le(&Row::splat(2.0)), 0b0101_1010);
        assert_eq!(
            (row - 1.0) * 2.0,
            Row([4.0, -4.0, 12.0, -4.0, 2.0, 16.0, -1.0, 6.0])
        );
        assert_eq!(Row::<8>::splat(2.0)[5], 2.0);
    }
}
