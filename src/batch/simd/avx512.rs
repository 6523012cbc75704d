//! The `Avx512` level: sixteen lanes as one `__m512`, with FMA, mask registers and `vrsqrt14ps` +
//! one Newton step.

#![allow(
    unsafe_code,
    reason = "AVX-512 intrinsics, called only through an `Avx512` token, which exists only where the CPU has AVX-512F/VL, AVX2 and FMA"
)]

use core::arch::x86_64::{
    __m512, __m512i, __mmask16, _CMP_LE_OQ, _CMP_LT_OQ, _MM_FROUND_NO_EXC,
    _MM_FROUND_TO_NEAREST_INT, _mm512_add_epi32, _mm512_add_ps, _mm512_and_si512,
    _mm512_cmp_ps_mask, _mm512_cmpgt_epi32_mask, _mm512_cvtepi32_ps, _mm512_cvttps_epi32,
    _mm512_div_ps, _mm512_fmadd_ps, _mm512_fmsub_ps, _mm512_fnmadd_ps, _mm512_i32gather_epi32,
    _mm512_loadu_ps, _mm512_mask_blend_ps, _mm512_maskz_mov_epi32, _mm512_maskz_mov_ps,
    _mm512_max_ps, _mm512_min_epu32, _mm512_min_ps, _mm512_mul_ps, _mm512_or_si512,
    _mm512_permutexvar_ps, _mm512_roundscale_ps, _mm512_rsqrt14_ps, _mm512_scalef_ps,
    _mm512_set1_epi32, _mm512_set1_ps, _mm512_slli_epi32, _mm512_sqrt_ps, _mm512_srai_epi32,
    _mm512_srli_epi32, _mm512_sub_epi32, _mm512_sub_ps, _mm512_testn_epi32_mask,
};

use crate::batch::Level;

/// The `Avx512` level's token: proof that the CPU has AVX-512F, AVX-512VL, AVX2 and FMA.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx512(());

impl Avx512 {
    /// The token, where the CPU has AVX-512F, AVX-512VL, AVX2 and FMA.
    #[inline]
    pub(crate) fn new() -> Option<Self> {
        Level::Avx512.is_supported().then_some(Avx512(()))
    }
}

simd_by_parts!(
    Avx512,
    [0],
    __m512,
    __m512i,
    __mmask16,
    native,
    gather = native,
    lookup16 = native,
    scale2 = native
);

level_entry!(Avx512, features = "avx512f,avx512vl,avx2,fma");

/// One `__m512` per operation. SAFETY (every `unsafe` block here): these functions are reached only
/// through an [`Avx512`] token's methods, and a token exists only where
/// `Level::Avx512.is_supported()` found AVX-512F, AVX-512VL, AVX2 and FMA, every feature these
/// intrinsics need.
mod native {
    use super::*;

    #[inline(always)]
    pub(super) fn splat(x: f32) -> __m512 {
        unsafe { _mm512_set1_ps(x) }
    }
    #[inline(always)]
    pub(super) fn add(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_add_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_sub_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn mul(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_mul_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn div(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_div_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn sqrt(x: __m512) -> __m512 {
        unsafe { _mm512_sqrt_ps(x) }
    }
    #[inline(always)]
    pub(super) fn mul_add(a: __m512, b: __m512, c: __m512) -> __m512 {
        unsafe { _mm512_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    pub(super) fn mul_sub(a: __m512, b: __m512, c: __m512) -> __m512 {
        unsafe { _mm512_fmsub_ps(a, b, c) }
    }
    #[inline(always)]
    pub(super) fn min(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_min_ps(a, b) }
    }
    #[inline(always)]
    pub(super) fn max(a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_max_ps(a, b) }
    }
    /// `vrsqrt14ps` (relative error ≤ 2⁻¹⁴) and one Newton step `y·(1.5 − 0.5·x·y²)`.
    #[inline(always)]
    pub(super) fn rsqrt(x: __m512) -> __m512 {
        unsafe {
            let y = _mm512_rsqrt14_ps(x);
            let hx = _mm512_mul_ps(x, _mm512_set1_ps(0.5));
            let t = _mm512_fnmadd_ps(hx, _mm512_mul_ps(y, y), _mm512_set1_ps(1.5));
            _mm512_mul_ps(y, t)
        }
    }
    #[inline(always)]
    pub(super) fn lt(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(a, b) }
    }
    #[inline(always)]
    pub(super) fn le(a: __m512, b: __m512) -> __mmask16 {
        unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(a, b) }
    }
    #[inline(always)]
    pub(super) fn and(a: __mmask16, b: __mmask16) -> __mmask16 {
        a & b
    }
    #[inline(always)]
    pub(super) fn select(m: __mmask16, a: __m512, b: __m512) -> __m512 {
        unsafe { _mm512_mask_blend_ps(m, b, a) }
    }
    #[inline(always)]
    pub(super) fn keep(m: __mmask16, a: __m512) -> __m512 {
        unsafe { _mm512_maskz_mov_ps(m, a) }
    }
    #[inline(always)]
    pub(super) fn bits(m: __mmask16) -> u32 {
        u32::from(m)
    }
    #[inline(always)]
    pub(super) fn splat_i(x: i32) -> __m512i {
        unsafe { _mm512_set1_epi32(x) }
    }
    #[inline(always)]
    pub(super) fn add_i(a: __m512i, b: __m512i) -> __m512i {
        unsafe { _mm512_add_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn sub_i(a: __m512i, b: __m512i) -> __m512i {
        unsafe { _mm512_sub_epi32(a, b) }
    }
    #[inline(always)]
    pub(super) fn shl23(a: __m512i) -> __m512i {
        unsafe { _mm512_slli_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn sar23(a: __m512i) -> __m512i {
        unsafe { _mm512_srai_epi32::<23>(a) }
    }
    #[inline(always)]
    pub(super) fn to_f32(a: __m512i) -> __m512 {
        unsafe { _mm512_cvtepi32_ps(a) }
    }
    /// `vrndscaleps` to whole numbers.
    #[inline(always)]
    pub(super) fn round(v: __m512) -> __m512 {
        unsafe { _mm512_roundscale_ps::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(v) }
    }
    /// `vscalefps`: `q·2^⌊r⌋`.
    #[inline(always)]
    pub(super) fn scale2(q: __m512, r: __m512) -> __m512 {
        unsafe { _mm512_scalef_ps(q, r) }
    }
    #[inline(always)]
    pub(super) fn to_i(v: __m512) -> __m512i {
        unsafe { _mm512_cvttps_epi32(v) }
    }
    #[inline(always)]
    pub(super) fn srl16(a: __m512i) -> __m512i {
        unsafe { _mm512_srli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn shl8(a: __m512i) -> __m512i {
        unsafe { _mm512_slli_epi32::<8>(a) }
    }
    #[inline(always)]
    pub(super) fn shl16(a: __m512i) -> __m512i {
        unsafe { _mm512_slli_epi32::<16>(a) }
    }
    #[inline(always)]
    pub(super) fn and_i(a: __m512i, b: __m512i) -> __m512i {
        unsafe { _mm512_and_si512(a, b) }
    }
    #[inline(always)]
    pub(super) fn or_i(a: __m512i, b: __m512i) -> __m512i {
        unsafe { _mm512_or_si512(a, b) }
    }
    /// `vptestnmd`.
    #[inline(always)]
    pub(super) fn none_of(a: __m512i, b: __m512i) -> __mmask16 {
        unsafe { _mm512_testn_epi32_mask(a, b) }
    }
    #[inline(always)]
    pub(super) fn gt_i(a: __m512i, b: __m512i) -> __m512i {
        unsafe { _mm512_maskz_mov_epi32(_mm512_cmpgt_epi32_mask(a, b), _mm512_set1_epi32(-1)) }
    }
    /// `vpgatherdd`, each index first clamped to the table's last (unsigned `min`), so every
    /// lane reads inside `table`.
    #[inline(always)]
    pub(super) fn gather(table: &[i32], idx: __m512i) -> __m512i {
        let Some(last) = table.len().checked_sub(1) else {
            return splat_i(0);
        };
        let last = i32::try_from(last).unwrap_or(i32::MAX);
        // SAFETY: as the module's, and every index is at most `last` after the `min`, so each
        // lane reads `table[i]` with `i < table.len()`.
        unsafe {
            let idx = _mm512_min_epu32(idx, _mm512_set1_epi32(last));
            _mm512_i32gather_epi32::<4>(idx, table.as_ptr())
        }
    }

    /// `vpermps` over the table in one register (the index's low four bits).
    #[inline(always)]
    pub(super) fn lookup16(table: &[f32; 16], idx: __m512i) -> __m512 {
        // SAFETY: as the module's; the load reads the sixteen entries of `table`.
        unsafe { _mm512_permutexvar_ps(idx, _mm512_loadu_ps(table.as_ptr())) }
    }
}
