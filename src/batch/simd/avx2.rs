//! The `Avx2` level: sixteen lanes as two `__m256`, with FMA and `vrsqrtps` + one Newton step.

#![allow(
    unsafe_code,
    reason = "AVX2 and FMA intrinsics, called only through an `Avx2` token, which exists only where the CPU has both"
)]

use core::arch::x86_64::{
    __m256, __m256i, _CMP_LE_OQ, _CMP_LT_OQ, _MM_FROUND_NO_EXC, _MM_FROUND_TO_NEAREST_INT,
    _mm256_add_epi32, _mm256_add_ps, _mm256_and_ps, _mm256_and_si256, _mm256_blendv_ps,
    _mm256_castsi256_ps, _mm256_cmp_ps, _mm256_cmpeq_epi32, _mm256_cmpgt_epi32, _mm256_cvtepi32_ps,
    _mm256_cvttps_epi32, _mm256_div_ps, _mm256_fmadd_ps, _mm256_fmsub_ps, _mm256_fnmadd_ps,
    _mm256_i32gather_epi32, _mm256_loadu_ps, _mm256_max_ps, _mm256_min_epu32, _mm256_min_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_or_si256, _mm256_permutevar8x32_ps, _mm256_round_ps,
    _mm256_rsqrt_ps, _mm256_set1_epi32, _mm256_set1_ps, _mm256_setzero_si256, _mm256_slli_epi32,
    _mm256_sqrt_ps, _mm256_srai_epi32, _mm256_srli_epi32, _mm256_sub_epi32, _mm256_sub_ps,
};

use crate::batch::Level;

/// The `Avx2` level's token: proof that the CPU has AVX2 and FMA.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2(());

impl Avx2 {
    /// The token, where the CPU has AVX2 and FMA.
    #[inline]
    pub(crate) fn new() -> Option<Self> {
        Level::Avx2.is_supported().then_some(Avx2(()))
    }
}

simd_by_parts!(
    Avx2,
    [0, 1],
    __m256,
    __m256i,
    __m256,
    native,
    gather = native,
    lookup16 = native,
    scale2 = default
);

level_entry!(Avx2, features = "avx2,fma");

/// One `__m256` per operation. SAFETY (every `unsafe` block here): these functions are reached only
/// through an [`Avx2`] token's methods, and a token exists only where `Level::Avx2.is_supported()`
/// found AVX2 and FMA, every feature these intrinsics need.
mod native {
    use super::*;

    #[inline(always)]
    pub(super) fn splat(x: f32) -> __m256 {
        unsafe { _mm256_set1_ps(x) }
    }
    #[inline(always)]
    pub(super) fn add(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_add_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_sub_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn mul(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_mul_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn div(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_div_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sqrt(x: __m256) -> __m256 {
        unsafe { _mm256_sqrt_ps(x) }
    }
    #[inline(always)]
    pub(super) fn mul_add(a: __m256, b: __m256, c: __m256) -> __m256 {
        unsafe { _mm256_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    pub(super) fn mul_sub(a: __m256, b: __m256, c: __m256) -> __m256 {
        unsafe { _mm256_fmsub_ps(a, b, c) }
    }
    #[inline(always)]
    pub(super) fn min(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_min_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn max(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_max_ps(a, b) }
    }
    /// `vrsqrtps` (relative error ≤ 1.5·2⁻¹²) and one Newton step `y·(1.5 − 0.5·x·y²)`.
    #[inline(always)]
    pub(super) fn rsqrt(x: __m256) -> __m256 {
        unsafe {
            let y = _mm256_rsqrt_ps(x);
            let hx = _mm256_mul_ps(x, _mm256_set1_ps(0.5));
            let t = _mm256_fnmadd_ps(hx, _mm256_mul_ps(y, y), _mm256_set1_ps(1.5));
            _mm256_mul_ps(y, t)
        }
    }
    #[inline(always)]
    pub(super) fn lt(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    pub(super) fn le(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    pub(super) fn and(a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_and_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn select(m: __m256, a: __m256, b: __m256) -> __m256 {
        unsafe { _mm256_blendv_ps(b, a, m) }
    }
    #[inline(always)]
    pub(super) fn keep(m: __m256, a: __m256) -> __m256 {
        unsafe { _mm256_and_ps(m, a) }
    }
    #[inline(always)]
    pub(super) fn bits(m: __m256) -> u32 {
        unsafe { _mm256_movemask_ps(m) as u32 }
    }
    #[inline(always)]
    pub(super) fn splat_i(x: i32) -> __m256i {
        unsafe { _mm256_set1_epi32(x) }
    }
    #[inline(always)]
    pub(super) fn add_i(a: __m256i, b: __m256i) -> __m256i {
        unsafe { _mm256_add_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub_i(a: __m256i, b: __m256i) -> __m256i {
        unsafe { _mm256_sub_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn shl23(a: __m256i) -> __m256i {
        unsafe { _mm256_slli_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn sar23(a: __m256i) -> __m256i {
        unsafe { _mm256_srai_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn to_f32(a: __m256i) -> __m256 {
        unsafe { _mm256_cvtepi32_ps(a) }
    }
    #[inline(always)]
    pub(super) fn round(v: __m256) -> __m256 {
        unsafe { _mm256_round_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(v) }
    }
    #[inline(always)]
    pub(super) fn to_i(v: __m256) -> __m256i {
        unsafe { _mm256_cvttps_epi32(v) }
    }
    #[inline(always)]
    pub(super) fn srl16(a: __m256i) -> __m256i {
        unsafe { _mm256_srli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn shl8(a: __m256i) -> __m256i {
        unsafe { _mm256_slli_epi32::<8>(a) }
    }
    #[inline(always)]
    pub(super) fn shl16(a: __m256i) -> __m256i {
        unsafe { _mm256_slli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn and_i(a: __m256i, b: __m256i) -> __m256i {
        unsafe { _mm256_and_si256(a, b) }
    }
    #[inline(always)]
    pub(super) fn or_i(a: __m256i, b: __m256i) -> __m256i {
        unsafe { _mm256_or_si256(a, b) }
    }
    #[inline(always)]
    pub(super) fn none_of(a: __m256i, b: __m256i) -> __m256 {
        unsafe {
            _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                _mm256_and_si256(a, b),
                _mm256_setzero_si256(),
            ))
        }
    }
    #[inline(always)]
    pub(super) fn gt_i(a: __m256i, b: __m256i) -> __m256i {
        unsafe { _mm256_cmpgt_epi32(a, b) }
    }
    /// Two `vpermps`, one per half of the table, and a blend on the index's bit 3 (moved to the
    /// sign bit): the index's low four bits.
    #[inline(always)]
    pub(super) fn lookup16(table: &[f32; 16], idx: __m256i) -> __m256 {
        let (lo, hi) = table.split_at(8);
        // SAFETY: as the module's; each load reads eight entries of `table`.
        unsafe {
            let lo = _mm256_permutevar8x32_ps(_mm256_loadu_ps(lo.as_ptr()), idx);
            let hi = _mm256_permutevar8x32_ps(_mm256_loadu_ps(hi.as_ptr()), idx);
            _mm256_blendv_ps(lo, hi, _mm256_castsi256_ps(_mm256_slli_epi32::<28>(idx)))
        }
    }
    /// `vpgatherdd`, each index first clamped to the table's last (unsigned `min`), so every
    /// lane reads inside `table`.
    #[inline(always)]
    pub(super) fn gather(table: &[i32], idx: __m256i) -> __m256i {
        let Some(last) = table.len().checked_sub(1) else {
            return splat_i(0);
        };
        let last = i32::try_from(last).unwrap_or(i32::MAX);
        // SAFETY: as the module's, and every index is at most `last` after the `min`, so each
        // lane reads `table[i]` with `i < table.len()`.
        unsafe {
            let idx = _mm256_min_epu32(idx, _mm256_set1_epi32(last));
            _mm256_i32gather_epi32::<4>(table.as_ptr(), idx)
        }
    }
}
