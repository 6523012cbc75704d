//! The AVX2 and SSE2 levels: the portable kernel compiled with each instruction set, and its
//! inverse square root.
//!
//! Each function here is safe; the `#[target_feature]` ones may only be *called* where the CPU
//! has the features, which `dispatch` checks. The intrinsics they use are safe inside them (the
//! closures inherit the features), and `bytemuck::must_cast` moves `[f32; 16]` in and out of
//! vector registers without `unsafe` (its size check is at compile time).

use core::arch::x86_64::{
    __m128, __m256, _mm_mul_ps, _mm_rsqrt_ps, _mm_set1_ps, _mm_sub_ps, _mm256_fnmadd_ps,
    _mm256_mul_ps, _mm256_rsqrt_ps, _mm256_set1_ps,
};

use bytemuck::must_cast;

use super::kernel::{Lanes, Setup, run};
use super::prepare::{BatchLight, BatchModel};
use super::soa::{SoaRgb, SoaVec3};

/// AVX2 + FMA: `vrsqrtps` (relative error ≤ 1.5·2⁻¹²) and one Newton step, on two halves.
#[target_feature(enable = "avx2,fma")]
pub(super) fn avx2<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> usize {
    let rsqrt = |x: Lanes| -> Lanes {
        let halves: [__m256; 2] = must_cast(x);
        let f = |x: __m256| {
            let y = _mm256_rsqrt_ps(x);
            let hx = _mm256_mul_ps(x, _mm256_set1_ps(0.5));
            let t = _mm256_fnmadd_ps(hx, _mm256_mul_ps(y, y), _mm256_set1_ps(1.5));
            _mm256_mul_ps(y, t)
        };
        must_cast([f(halves[0]), f(halves[1])])
    };
    run(k, pos, nor, out, rsqrt)
}

/// SSE2 (the x86_64 baseline): `rsqrtps` and one Newton step, on four quarters.
#[target_feature(enable = "sse2")]
pub(super) fn sse2<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> usize {
    let rsqrt = |x: Lanes| -> Lanes {
        let q: [__m128; 4] = must_cast(x);
        let f = |x: __m128| {
            let y = _mm_rsqrt_ps(x);
            let hx = _mm_mul_ps(x, _mm_set1_ps(0.5));
            let t = _mm_sub_ps(_mm_set1_ps(1.5), _mm_mul_ps(hx, _mm_mul_ps(y, y)));
            _mm_mul_ps(y, t)
        };
        must_cast([f(q[0]), f(q[1]), f(q[2]), f(q[3])])
    };
    run(k, pos, nor, out, rsqrt)
}
