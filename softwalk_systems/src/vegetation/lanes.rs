//! Eight `f32` lanes for the vectorised loops of a deformation step.
//!
//! Every operation is the IEEE operation of each lane, so a lane gives bit for
//! bit what the same scalar code gives; branches become [`Mask`] selects. On
//! x86-64 the lanes are two SSE2 registers (SSE2 is part of the x86-64
//! baseline: the `cfg` checks it at compile time, so no runtime detection is
//! needed); elsewhere they are plain arrays the compiler vectorises as it
//! can. Tests check both give the same bits as scalar code.

use std::ops::{Add, BitOr, Div, Mul, Neg, Sub};

/// Lanes per vector.
pub(crate) const LANES: usize = 8;

#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
use sse2 as quad;

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
use portable as quad;

/// Four lanes as SSE2 registers.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
mod sse2 {
    use std::arch::x86_64::*;

    pub(super) type Quad = __m128;

    #[inline(always)]
    pub(super) fn from_array(v: [f32; 4]) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_setr_ps(v[0], v[1], v[2], v[3]) }
    }

    #[inline(always)]
    pub(super) fn to_array(v: Quad) -> [f32; 4] {
        let mut out = [0.0; 4];
        // SAFETY: SSE2 is enabled at compile time on this target (see the
        // cfg), and `out` has room for the four lanes `_mm_storeu_ps` writes.
        unsafe { _mm_storeu_ps(out.as_mut_ptr(), v) };
        out
    }

    #[inline(always)]
    pub(super) fn splat(v: f32) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_set1_ps(v) }
    }

    #[inline(always)]
    pub(super) fn add(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_add_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn sub(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_sub_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn mul(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_mul_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn div(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_div_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn sqrt(a: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_sqrt_ps(a) }
    }

    /// Flips the sign bit.
    #[inline(always)]
    pub(super) fn neg(a: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_xor_ps(a, _mm_set1_ps(-0.0)) }
    }

    /// Clears the sign bit.
    #[inline(always)]
    pub(super) fn abs(a: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), a) }
    }

    #[inline(always)]
    pub(super) fn lt(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_cmplt_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn le(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_cmple_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn gt(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_cmpgt_ps(a, b) }
    }

    #[inline(always)]
    pub(super) fn or(a: Quad, b: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_or_ps(a, b) }
    }

    /// `yes` where `mask` is set, else `no`.
    #[inline(always)]
    pub(super) fn select(mask: Quad, yes: Quad, no: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_or_ps(_mm_and_ps(mask, yes), _mm_andnot_ps(mask, no)) }
    }

    /// `yes` where `mask` is set, else `+0.0`.
    #[inline(always)]
    pub(super) fn and(mask: Quad, yes: Quad) -> Quad {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_and_ps(mask, yes) }
    }

    /// One bit per lane: bit `l` set when lane `l` of `mask` is set.
    #[inline(always)]
    pub(super) fn bitmask(mask: Quad) -> u32 {
        // SAFETY: SSE2 is enabled at compile time on this target (see the cfg).
        unsafe { _mm_movemask_ps(mask) as u32 }
    }
}

/// Four lanes as an array (other targets, and the reference in tests).
#[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "sse2"))))]
mod portable {
    pub(super) type Quad = [f32; 4];

    #[inline(always)]
    fn zip(a: Quad, b: Quad, f: impl Fn(f32, f32) -> f32) -> Quad {
        std::array::from_fn(|l| f(a[l], b[l]))
    }

    #[inline(always)]
    fn bits(a: Quad, b: Quad, f: impl Fn(u32, u32) -> u32) -> Quad {
        zip(a, b, |x, y| f32::from_bits(f(x.to_bits(), y.to_bits())))
    }

    #[inline(always)]
    fn compare(a: Quad, b: Quad, f: impl Fn(f32, f32) -> bool) -> Quad {
        zip(a, b, |x, y| {
            f32::from_bits(u32::from(f(x, y)).wrapping_neg())
        })
    }

    pub(super) fn from_array(v: [f32; 4]) -> Quad {
        v
    }
    pub(super) fn to_array(v: Quad) -> [f32; 4] {
        v
    }
    pub(super) fn splat(v: f32) -> Quad {
        [v; 4]
    }
    pub(super) fn add(a: Quad, b: Quad) -> Quad {
        zip(a, b, |x, y| x + y)
    }
    pub(super) fn sub(a: Quad, b: Quad) -> Quad {
        zip(a, b, |x, y| x - y)
    }
    pub(super) fn mul(a: Quad, b: Quad) -> Quad {
        zip(a, b, |x, y| x * y)
    }
    pub(super) fn div(a: Quad, b: Quad) -> Quad {
        zip(a, b, |x, y| x / y)
    }
    pub(super) fn sqrt(a: Quad) -> Quad {
        a.map(f32::sqrt)
    }
    pub(super) fn neg(a: Quad) -> Quad {
        a.map(|x| -x)
    }
    pub(super) fn abs(a: Quad) -> Quad {
        a.map(f32::abs)
    }
    pub(super) fn lt(a: Quad, b: Quad) -> Quad {
        compare(a, b, |x, y| x < y)
    }
    pub(super) fn le(a: Quad, b: Quad) -> Quad {
        compare(a, b, |x, y| x <= y)
    }
    pub(super) fn gt(a: Quad, b: Quad) -> Quad {
        compare(a, b, |x, y| x > y)
    }
    pub(super) fn or(a: Quad, b: Quad) -> Quad {
        bits(a, b, |x, y| x | y)
    }
    pub(super) fn select(mask: Quad, yes: Quad, no: Quad) -> Quad {
        or(and(mask, yes), bits(mask, no, |m, x| !m & x))
    }
    pub(super) fn and(mask: Quad, yes: Quad) -> Quad {
        bits(mask, yes, |m, x| m & x)
    }
    pub(super) fn bitmask(mask: Quad) -> u32 {
        (0..4).map(|l| (mask[l].to_bits() >> 31) << l).sum()
    }
}

/// Eight `f32` lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct F8([quad::Quad; 2]);

/// Eight lane conditions, from a comparison of lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mask([quad::Quad; 2]);

impl F8 {
    /// The lanes of `values`.
    #[inline(always)]
    pub(crate) fn new(values: [f32; LANES]) -> Self {
        let [a, b, c, d, e, f, g, h] = values;
        F8([
            quad::from_array([a, b, c, d]),
            quad::from_array([e, f, g, h]),
        ])
    }

    /// Every lane `v`.
    #[inline(always)]
    pub(crate) fn splat(v: f32) -> Self {
        F8([quad::splat(v); 2])
    }

    /// The lanes from a slice of exactly [`LANES`] values.
    #[inline(always)]
    pub(crate) fn load(values: &[f32]) -> Self {
        Self::new(values.try_into().expect("a whole chunk of lanes"))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f32; LANES] {
        let ([a, b, c, d], [e, f, g, h]) = (quad::to_array(self.0[0]), quad::to_array(self.0[1]));
        [a, b, c, d, e, f, g, h]
    }

    #[inline(always)]
    fn map(self, f: impl Fn(quad::Quad) -> quad::Quad) -> Self {
        F8([f(self.0[0]), f(self.0[1])])
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(quad::Quad, quad::Quad) -> quad::Quad) -> Self {
        F8([f(self.0[0], other.0[0]), f(self.0[1], other.0[1])])
    }

    /// Square root of each lane.
    #[inline(always)]
    pub(crate) fn sqrt(self) -> Self {
        self.map(quad::sqrt)
    }

    /// Absolute value of each lane.
    #[inline(always)]
    pub(crate) fn abs(self) -> Self {
        self.map(quad::abs)
    }

    /// Lanes where `self < other`.
    #[inline(always)]
    pub(crate) fn lt(self, other: Self) -> Mask {
        Mask(self.zip(other, quad::lt).0)
    }

    /// Lanes where `self <= other`.
    #[inline(always)]
    pub(crate) fn le(self, other: Self) -> Mask {
        Mask(self.zip(other, quad::le).0)
    }

    /// Lanes where `self > other`.
    #[inline(always)]
    pub(crate) fn gt(self, other: Self) -> Mask {
        Mask(self.zip(other, quad::gt).0)
    }
}

impl Mask {
    /// Per lane, `yes` where the condition holds, else `no`.
    #[inline(always)]
    pub(crate) fn select(self, yes: F8, no: F8) -> F8 {
        let [m0, m1] = self.0;
        F8([
            quad::select(m0, yes.0[0], no.0[0]),
            quad::select(m1, yes.0[1], no.0[1]),
        ])
    }

    /// Per lane, the value where the condition holds, else `+0.0`.
    #[inline(always)]
    pub(crate) fn or_zero(self, yes: F8) -> F8 {
        F8([
            quad::and(self.0[0], yes.0[0]),
            quad::and(self.0[1], yes.0[1]),
        ])
    }

    /// One bit per lane: bit `l` set when lane `l` holds.
    #[inline(always)]
    pub(crate) fn bitmask(self) -> u32 {
        quad::bitmask(self.0[0]) | (quad::bitmask(self.0[1]) << 4)
    }
}

impl BitOr for Mask {
    type Output = Mask;
    #[inline(always)]
    fn bitor(self, other: Mask) -> Mask {
        Mask([
            quad::or(self.0[0], other.0[0]),
            quad::or(self.0[1], other.0[1]),
        ])
    }
}

/// Implements the lane-wise binary operator `$trait::$method` of [`F8`] with
/// the 4-lane operation `$quad` on each half.
macro_rules! lane_wise {
    ($($trait:ident :: $method:ident => $quad:path),+ $(,)?) => {
        $(
            impl $trait for F8 {
                type Output = F8;
                #[inline(always)]
                fn $method(self, other: F8) -> F8 {
                    self.zip(other, $quad)
                }
            }
        )+
    };
}

lane_wise!(
    Add::add => quad::add,
    Sub::sub => quad::sub,
    Mul::mul => quad::mul,
    Div::div => quad::div,
);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        self.map(quad::neg)
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

    /// The array lanes used off x86-64 give the same bits as the SSE2 ones.
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    #[test]
    fn portable_lanes_match_sse2() {
        let quads = |v: [f32; LANES]| [[v[0], v[1], v[2], v[3]], [v[4], v[5], v[6], v[7]]];
        for (a, b) in quads(A).into_iter().zip(quads(B)) {
            let (sa, sb) = (sse2::from_array(a), sse2::from_array(b));
            let same = |p: portable::Quad, s: sse2::Quad| {
                assert_eq!(p.map(f32::to_bits), sse2::to_array(s).map(f32::to_bits));
            };
            same(portable::add(a, b), sse2::add(sa, sb));
            same(portable::sub(a, b), sse2::sub(sa, sb));
            same(portable::mul(a, b), sse2::mul(sa, sb));
            same(portable::div(a, b), sse2::div(sa, sb));
            same(portable::sqrt(b), sse2::sqrt(sb));
            same(portable::neg(a), sse2::neg(sa));
            same(portable::abs(a), sse2::abs(sa));
            same(portable::splat(a[1]), sse2::splat(a[1]));
            let (pm, sm) = (portable::lt(a, b), sse2::lt(sa, sb));
            same(pm, sm);
            same(portable::le(a, b), sse2::le(sa, sb));
            same(portable::gt(a, b), sse2::gt(sa, sb));
            same(portable::select(pm, a, b), sse2::select(sm, sa, sb));
            same(portable::and(pm, a), sse2::and(sm, sa));
            same(
                portable::or(pm, portable::gt(a, b)),
                sse2::or(sm, sse2::gt(sa, sb)),
            );
            assert_eq!(portable::bitmask(pm), sse2::bitmask(sm));
            assert_eq!(portable::to_array(portable::from_array(a)), a);
        }
    }
}
