//! The `Neon` level (aarch64): sixteen lanes as four `float32x4_t`, with FMA and NEON's inverse
//! square root estimate `frsqrte` and two Newton steps by `frsqrts` (which computes
//! `(3 − a·b)/2` fused), in place of a square root and a division per lane.
//!
//! NEON is part of the aarch64 baseline, and this module is compiled only where the build enables
//! it, so this level needs no CPU check and no `#[target_feature]` function.

#![allow(
    unsafe_code,
    reason = "NEON intrinsics: this module is compiled only where the build enables NEON"
)]

use core::arch::aarch64::{
    float32x4_t, int32x4_t, uint32x4_t, vaddq_f32, vaddq_s32, vaddvq_u32, vandq_s32, vandq_u32,
    vbslq_f32, vceqzq_s32, vcgtq_f32, vcgtq_s32, vcleq_f32, vcltq_f32, vcvtq_f32_s32,
    vcvtq_s32_f32, vdivq_f32, vdupq_n_f32, vdupq_n_s32, vfmaq_f32, vmulq_f32, vorrq_s32,
    vreinterpretq_s32_u32, vreinterpretq_u32_s32, vrndnq_f32, vrsqrteq_f32, vrsqrtsq_f32,
    vshlq_n_s32, vshrq_n_s32, vshrq_n_u32, vsqrtq_f32, vsubq_f32, vsubq_s32,
};

/// The `Neon` level's token (every aarch64 build with NEON runs it).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Neon;

simd_by_parts!(
    Neon,
    [0, 1, 2, 3],
    float32x4_t,
    int32x4_t,
    uint32x4_t,
    native,
    gather = default,
    lookup16 = default,
    scale2 = default
);

level_entry!(Neon);

/// One `float32x4_t` per operation. SAFETY (every `unsafe` block here): this module is compiled only where the build enables NEON (`target_feature = "neon"`), so every CPU it runs on has it.
mod native {
    use super::*;

    #[inline(always)]
    pub(super) fn splat(x: f32) -> float32x4_t {
        unsafe { vdupq_n_f32(x) }
    }
    #[inline(always)]
    pub(super) fn add(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vaddq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vsubq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn mul(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vmulq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn div(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vdivq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sqrt(x: float32x4_t) -> float32x4_t {
        unsafe { vsqrtq_f32(x) }
    }
    #[inline(always)]
    pub(super) fn mul_add(a: float32x4_t, b: float32x4_t, c: float32x4_t) -> float32x4_t {
        unsafe { vfmaq_f32(c, a, b) }
    }
    #[inline(always)]
    pub(super) fn mul_sub(a: float32x4_t, b: float32x4_t, c: float32x4_t) -> float32x4_t {
        unsafe { vsubq_f32(vmulq_f32(a, b), c) }
    }
    /// A compare and a select, not `fmin`: `fmin` returns NaN for a NaN operand, the trait's
    /// `min` the second operand.
    #[inline(always)]
    pub(super) fn min(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vbslq_f32(vcltq_f32(a, b), a, b) }
    }
    #[inline(always)]
    pub(super) fn max(a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vbslq_f32(vcgtq_f32(a, b), a, b) }
    }
    /// The estimate, then `y ← y·(3 − x·y²)/2` twice. Relative error about `1.5·(1.5·2⁻⁸)²` after
    /// the first step and below `1e-9` after the second, plus the steps' roundings (a few `2⁻²⁴`).
    /// With one step, 8 of the 17 batch tests fail.
    #[inline(always)]
    pub(super) fn rsqrt(x: float32x4_t) -> float32x4_t {
        unsafe {
            let y = vrsqrteq_f32(x);
            let y = vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(x, y), y));
            vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(x, y), y))
        }
    }
    #[inline(always)]
    pub(super) fn lt(a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        unsafe { vcltq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn le(a: float32x4_t, b: float32x4_t) -> uint32x4_t {
        unsafe { vcleq_f32(a, b) }
    }
    #[inline(always)]
    pub(super) fn and(a: uint32x4_t, b: uint32x4_t) -> uint32x4_t {
        unsafe { vandq_u32(a, b) }
    }
    #[inline(always)]
    pub(super) fn select(m: uint32x4_t, a: float32x4_t, b: float32x4_t) -> float32x4_t {
        unsafe { vbslq_f32(m, a, b) }
    }
    #[inline(always)]
    pub(super) fn keep(m: uint32x4_t, a: float32x4_t) -> float32x4_t {
        unsafe { vbslq_f32(m, a, vdupq_n_f32(0.0)) }
    }
    #[inline(always)]
    pub(super) fn bits(m: uint32x4_t) -> u32 {
        unsafe {
            let weights: uint32x4_t = bytemuck::must_cast([1u32, 2, 4, 8]);
            vaddvq_u32(vandq_u32(m, weights))
        }
    }
    #[inline(always)]
    pub(super) fn splat_i(x: i32) -> int32x4_t {
        unsafe { vdupq_n_s32(x) }
    }
    #[inline(always)]
    pub(super) fn add_i(a: int32x4_t, b: int32x4_t) -> int32x4_t {
        unsafe { vaddq_s32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub_i(a: int32x4_t, b: int32x4_t) -> int32x4_t {
        unsafe { vsubq_s32(a, b) }
    }
    #[inline(always)]
    pub(super) fn shl23(a: int32x4_t) -> int32x4_t {
        unsafe { vshlq_n_s32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn sar23(a: int32x4_t) -> int32x4_t {
        unsafe { vshrq_n_s32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn to_f32(a: int32x4_t) -> float32x4_t {
        unsafe { vcvtq_f32_s32(a) }
    }
    #[inline(always)]
    pub(super) fn round(v: float32x4_t) -> float32x4_t {
        unsafe { vrndnq_f32(v) }
    }
    #[inline(always)]
    pub(super) fn to_i(v: float32x4_t) -> int32x4_t {
        unsafe { vcvtq_s32_f32(v) }
    }
    #[inline(always)]
    pub(super) fn srl16(a: int32x4_t) -> int32x4_t {
        unsafe { vreinterpretq_s32_u32(vshrq_n_u32::<16>(vreinterpretq_u32_s32(a))) }
    }
    #[inline(always)]
    pub(super) fn shl8(a: int32x4_t) -> int32x4_t {
        unsafe { vshlq_n_s32::<8>(a) }
    }
    #[inline(always)]
    pub(super) fn shl16(a: int32x4_t) -> int32x4_t {
        unsafe { vshlq_n_s32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn and_i(a: int32x4_t, b: int32x4_t) -> int32x4_t {
        unsafe { vandq_s32(a, b) }
    }
    #[inline(always)]
    pub(super) fn or_i(a: int32x4_t, b: int32x4_t) -> int32x4_t {
        unsafe { vorrq_s32(a, b) }
    }
    #[inline(always)]
    pub(super) fn none_of(a: int32x4_t, b: int32x4_t) -> uint32x4_t {
        unsafe { vceqzq_s32(vandq_s32(a, b)) }
    }
    #[inline(always)]
    pub(super) fn gt_i(a: int32x4_t, b: int32x4_t) -> int32x4_t {
        unsafe { vreinterpretq_s32_u32(vcgtq_s32(a, b)) }
    }
}
