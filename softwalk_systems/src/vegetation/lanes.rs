//! Eight `f32` lanes for the vectorised loops of a deformation step.
//!
//! Every operation is the IEEE operation of each lane, so a lane gives bit for
//! bit what the same scalar code gives; branches become [`Mask`] selects. The
//! lanes are two glam [`Vec4`]s, which glam maps to SSE2 registers on x86-64
//! (part of that target's baseline), to NEON or SIMD128 where those exist and
//! to plain arrays elsewhere, all without `unsafe` here. A test checks every
//! operation against the scalar one, lane by lane.

use std::ops::{Add, BitOr, Div, Mul, Neg, Sub};

use glam::{BVec4A, Vec4};

/// Lanes per vector.
pub(crate) const LANES: usize = 8;

/// Eight `f32` lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct F8([Vec4; 2]);

/// Eight lane conditions, from a comparison of lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mask([BVec4A; 2]);

impl F8 {
    /// The lanes of `values`.
    #[inline(always)]
    pub(crate) fn new(values: [f32; LANES]) -> Self {
        let [a, b, c, d, e, f, g, h] = values;
        F8([Vec4::new(a, b, c, d), Vec4::new(e, f, g, h)])
    }

    /// Every lane `v`.
    #[inline(always)]
    pub(crate) fn splat(v: f32) -> Self {
        F8([Vec4::splat(v); 2])
    }

    /// The lanes from a slice of exactly [`LANES`] values.
    #[inline(always)]
    pub(crate) fn load(values: &[f32]) -> Self {
        Self::new(values.try_into().expect("a whole chunk of lanes"))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f32; LANES] {
        let ([a, b, c, d], [e, f, g, h]) = (self.0[0].to_array(), self.0[1].to_array());
        [a, b, c, d, e, f, g, h]
    }

    #[inline(always)]
    fn map(self, f: impl Fn(Vec4) -> Vec4) -> Self {
        F8(self.0.map(f))
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(Vec4, Vec4) -> Vec4) -> Self {
        F8([f(self.0[0], other.0[0]), f(self.0[1], other.0[1])])
    }

    #[inline(always)]
    fn compare(self, other: Self, f: impl Fn(Vec4, Vec4) -> BVec4A) -> Mask {
        Mask([f(self.0[0], other.0[0]), f(self.0[1], other.0[1])])
    }

    /// Square root of each lane.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> Self {
        self.map(Vec4::sqrt)
    }

    /// Absolute value of each lane.
    #[inline(always)]
    pub(crate) fn abs(self) -> Self {
        self.map(Vec4::abs)
    }

    /// Lanes where `self < other`.
    #[inline(always)]
    pub(crate) fn lt(self, other: Self) -> Mask {
        self.compare(other, Vec4::cmplt)
    }

    /// Lanes where `self <= other`.
    #[inline(always)]
    pub(crate) fn le(self, other: Self) -> Mask {
        self.compare(other, Vec4::cmple)
    }

    /// Lanes where `self > other`.
    #[inline(always)]
    pub(crate) fn gt(self, other: Self) -> Mask {
        self.compare(other, Vec4::cmpgt)
    }
}

impl Mask {
    /// Per lane, `yes` where the condition holds, else `no`.
    #[inline(always)]
    pub(crate) fn select(self, yes: F8, no: F8) -> F8 {
        let [m0, m1] = self.0;
        F8([
            Vec4::select(m0, yes.0[0], no.0[0]),
            Vec4::select(m1, yes.0[1], no.0[1]),
        ])
    }

    /// Per lane, the value where the condition holds, else `+0.0`.
    #[inline(always)]
    pub(crate) fn or_zero(self, yes: F8) -> F8 {
        self.select(yes, F8::splat(0.0))
    }

    /// One bit per lane: bit `l` set when lane `l` holds.
    #[inline(always)]
    pub(crate) fn bitmask(self) -> u32 {
        self.0[0].bitmask() | (self.0[1].bitmask() << 4)
    }
}

impl BitOr for Mask {
    type Output = Mask;
    #[inline(always)]
    fn bitor(self, other: Mask) -> Mask {
        Mask([self.0[0] | other.0[0], self.0[1] | other.0[1]])
    }
}

/// Implements the lane-wise binary operator `$trait::$method` of [`F8`] with
/// the same operator on each [`Vec4`] half.
macro_rules! lane_wise {
    ($($trait:ident :: $method:ident),+ $(,)?) => {
        $(
            impl $trait for F8 {
                type Output = F8;
                #[inline(always)]
                fn $method(self, other: F8) -> F8 {
                    self.zip(other, Vec4::$method)
                }
            }
        )+
    };
}

lane_wise!(Add::add, Sub::sub, Mul::mul, Div::div);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        self.map(Vec4::neg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [f32; LANES] = [1.0, -2.0, 0.5, 4.0, -0.0, 9.0, 3.0, f32::INFINITY];
    // No lane makes a NaN: its bits are not specified.
    const B: [f32; LANES] = [2.0, 2.0, 0.5, -1.0, 0.5, 3.0, 7.0, 1.0];

    #[test]
    fn lanes_match_scalar_operations() {
        let (a, b) = (F8::new(A), F8::new(B));
        let bits = |v: F8| v.to_array().map(f32::to_bits);
        for l in 0..LANES {
            let (x, y) = (A[l], B[l]);
            assert_eq!(bits(a + b)[l], (x + y).to_bits());
            assert_eq!(bits(a - b)[l], (x - y).to_bits());
            assert_eq!(bits(a * b)[l], (x * y).to_bits());
            assert_eq!(bits(a / b)[l], (x / y).to_bits());
            assert_eq!(bits(-a)[l], (-x).to_bits());
            assert_eq!(bits(a.abs())[l], x.abs().to_bits());
            assert_eq!(bits(b.sqrt())[l], y.sqrt().to_bits());
            let pick = |m: Mask| m.select(a, b).to_array()[l].to_bits();
            assert_eq!(pick(a.lt(b)), if x < y { x } else { y }.to_bits());
            assert_eq!(pick(a.le(b)), if x <= y { x } else { y }.to_bits());
            assert_eq!(pick(a.gt(b)), if x > y { x } else { y }.to_bits());
            assert_eq!(
                pick(a.lt(b) | a.gt(b)),
                if x != y { x } else { y }.to_bits()
            );
            let zeroed = a.gt(b).or_zero(a).to_array()[l];
            assert_eq!(zeroed.to_bits(), if x > y { x } else { 0.0 }.to_bits());
            assert_eq!((a.lt(b).bitmask() >> l) & 1, u32::from(x < y));
        }
        assert_eq!(F8::splat(2.5).to_array(), [2.5; LANES]);
        assert_eq!(F8::load(&B).to_array(), B);
    }
}
