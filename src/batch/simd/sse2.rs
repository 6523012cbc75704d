//! The `Sse2` level: sixteen lanes as four `__m128`, with `rsqrtps` and one Newton step.
//!
//! SSE2 is part of the x86_64 baseline, so this level needs no CPU check and no
//! `#[target_feature]` function: the kernel is compiled with the build's own features.

#![allow(
    unsafe_code,
    reason = "SSE intrinsics: SSE2 is part of the x86_64 baseline, so every x86_64 CPU runs them"
)]

use core::arch::x86_64::{
    __m128, __m128i, _mm_add_epi32, _mm_add_ps, _mm_and_ps, _mm_and_si128, _mm_andnot_ps,
    _mm_castsi128_ps, _mm_cmpeq_epi32, _mm_cmpgt_epi32, _mm_cmple_ps, _mm_cmplt_ps,
    _mm_cvtepi32_ps, _mm_cvttps_epi32, _mm_div_ps, _mm_max_ps, _mm_min_ps, _mm_movemask_ps,
    _mm_mul_ps, _mm_or_ps, _mm_or_si128, _mm_rsqrt_ps, _mm_set1_epi32, _mm_set1_ps,
    _mm_setzero_si128, _mm_slli_epi32, _mm_sqrt_ps, _mm_srai_epi32, _mm_srli_epi32, _mm_sub_epi32,
    _mm_sub_ps,
};

/// The `Sse2` level's token (every x86_64 CPU runs it).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sse2;

simd_by_parts!(
    Sse2,
    [0, 1, 2, 3],
    __m128,
    __m128i,
    __m128,
    native,
    gather = default,
    lookup16 = default,
    scale2 = default
);

level_entry!(Sse2);

/// One `__m128` per operation. SAFETY (every `unsafe` block here): SSE2 is part of the x86_64 baseline: every CPU this code is compiled for has it.
mod native {
    use super::*;

    #[inline(always)]
    pub(super) fn splat(x: f32) -> __m128 {
        unsafe { _mm_set1_ps(x) }
    }
    #[inline(always)]
    pub(super) fn add(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_add_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_sub_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn mul(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_mul_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn div(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_div_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sqrt(x: __m128) -> __m128 {
        unsafe { _mm_sqrt_ps(x) }
    }
    #[inline(always)]
    pub(super) fn mul_add(a: __m128, b: __m128, c: __m128) -> __m128 {
        unsafe { _mm_add_ps(_mm_mul_ps(a, b), c) }
    }
    #[inline(always)]
    pub(super) fn mul_sub(a: __m128, b: __m128, c: __m128) -> __m128 {
        unsafe { _mm_sub_ps(_mm_mul_ps(a, b), c) }
    }
    #[inline(always)]
    pub(super) fn min(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_min_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn max(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_max_ps(a, b) }
    }
    /// `rsqrtps` (relative error ≤ 1.5·2⁻¹²) and one Newton step `y·(1.5 − 0.5·x·y²)`.
    #[inline(always)]
    pub(super) fn rsqrt(x: __m128) -> __m128 {
        unsafe {
            let y = _mm_rsqrt_ps(x);
            let hx = _mm_mul_ps(x, _mm_set1_ps(0.5));
            let t = _mm_sub_ps(_mm_set1_ps(1.5), _mm_mul_ps(hx, _mm_mul_ps(y, y)));
            _mm_mul_ps(y, t)
        }
    }
    #[inline(always)]
    pub(super) fn lt(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_cmplt_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn le(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_cmple_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn and(a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_and_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn select(m: __m128, a: __m128, b: __m128) -> __m128 {
        unsafe { _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)) }
    }
    #[inline(always)]
    pub(super) fn keep(m: __m128, a: __m128) -> __m128 {
        unsafe { _mm_and_ps(m, a) }
    }
    #[inline(always)]
    pub(super) fn bits(m: __m128) -> u32 {
        unsafe { _mm_movemask_ps(m) as u32 }
    }
    #[inline(always)]
    pub(super) fn splat_i(x: i32) -> __m128i {
        unsafe { _mm_set1_epi32(x) }
    }
    #[inline(always)]
    pub(super) fn add_i(a: __m128i, b: __m128i) -> __m128i {
        unsafe { _mm_add_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub_i(a: __m128i, b: __m128i) -> __m128i {
        unsafe { _mm_sub_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn shl23(a: __m128i) -> __m128i {
        unsafe { _mm_slli_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn sar23(a: __m128i) -> __m128i {
        unsafe { _mm_srai_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn to_f32(a: __m128i) -> __m128 {
        unsafe { _mm_cvtepi32_ps(a) }
    }
    /// SSE2 has no rounding instruction: `(v + 1.5·2²³) − 1.5·2²³`, exact for `|v| < 2²²`.
    #[inline(always)]
    pub(super) fn round(v: __m128) -> __m128 {
        unsafe {
            let big = _mm_set1_ps(12_582_912.0);
            _mm_sub_ps(_mm_add_ps(v, big), big)
        }
    }
    #[inline(always)]
    pub(super) fn to_i(v: __m128) -> __m128i {
        unsafe { _mm_cvttps_epi32(v) }
    }
    #[inline(always)]
    pub(super) fn srl16(a: __m128i) -> __m128i {
        unsafe { _mm_srli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn shl8(a: __m128i) -> __m128i {
        unsafe { _mm_slli_epi32::<8>(a) }
    }
    #[inline(always)]
    pub(super) fn shl16(a: __m128i) -> __m128i {
        unsafe { _mm_slli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn and_i(a: __m128i, b: __m128i) -> __m128i {
        unsafe { _mm_and_si128(a, b) }
    }
    #[inline(always)]
    pub(super) fn or_i(a: __m128i, b: __m128i) -> __m128i {
        unsafe { _mm_or_si128(a, b) }
    }
    #[inline(always)]
    pub(super) fn none_of(a: __m128i, b: __m128i) -> __m128 {
        unsafe { _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(a, b), _mm_setzero_si128())) }
    }
    #[inline(always)]
    pub(super) fn gt_i(a: __m128i, b: __m128i) -> __m128i {
        unsafe { _mm_cmpgt_epi32(a, b) }
    }
}
