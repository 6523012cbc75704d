//! The AVX2 and SSE2 levels, and the AVX-512 level's G-buffer calls: the portable kernel compiled
//! with each instruction set, and its inverse square root.
//!
//! Each function here is safe; the `#[target_feature]` ones may only be *called* where the CPU
//! has the features, which `dispatch` checks. The intrinsics they use are safe inside them (the
//! closures inherit the features), and `bytemuck::must_cast` moves `[f32; 16]` in and out of
//! vector registers without `unsafe` (its size check is at compile time).

use core::arch::x86_64::{
    __m128, __m256, __m512, _mm_rsqrt_ps, _mm256_fnmadd_ps, _mm256_mul_ps, _mm256_rsqrt_ps,
    _mm256_set1_ps, _mm512_fnmadd_ps, _mm512_mul_ps, _mm512_rsqrt14_ps, _mm512_set1_ps,
};

use bytemuck::must_cast;

use super::kernel::{Lanes, PointInputs, Setup, run, run_inputs};
use super::prepare::{BatchLight, BatchModel};
use super::soa::{SoaRgb, SoaVec3};

/// AVX-512F/VL with AVX2 and FMA: `vrsqrt14ps` (relative error ≤ 2⁻¹⁴) and one Newton step, on
/// all 16 lanes at once.
///
/// The same source as the other levels, which LLVM compiles to 16-lane instructions here. Only
/// G-buffer calls (per-point surfaces or visibilities) run it: the intrinsics kernel in
/// `avx512.rs`, which has no per-point inputs, is about 2.5× faster on the rest.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
pub(super) fn avx512<M: BatchModel, L: BatchLight, const INPUTS: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
) -> usize {
    let rsqrt = |x: Lanes| -> Lanes {
        let x: __m512 = must_cast(x);
        let y = _mm512_rsqrt14_ps(x);
        let hx = _mm512_mul_ps(x, _mm512_set1_ps(0.5));
        let t = _mm512_fnmadd_ps(hx, _mm512_mul_ps(y, y), _mm512_set1_ps(1.5));
        must_cast(_mm512_mul_ps(y, t))
    };
    run_any::<M, L, _, INPUTS>(k, pos, nor, inputs, out, rsqrt)
}

/// AVX2 + FMA: `vrsqrtps` (relative error ≤ 1.5·2⁻¹²) and one Newton step, on two halves.
#[target_feature(enable = "avx2,fma")]
pub(super) fn avx2<M: BatchModel, L: BatchLight, const INPUTS: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
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
    run_any::<M, L, _, INPUTS>(k, pos, nor, inputs, out, rsqrt)
}

/// SSE2 (the x86_64 baseline): `rsqrtps` and one Newton step, on four quarters.
#[target_feature(enable = "sse2")]
pub(super) fn sse2<M: BatchModel, L: BatchLight, const INPUTS: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
) -> usize {
    // Only the estimate through intrinsics, the Newton step in plain code the compiler
    // vectorises: a closure this small is inlined into the kernel's loop, where the whole step
    // in intrinsics was left out of line (a call per inverse norm).
    let rsqrt = |x: Lanes| -> Lanes {
        let q: [__m128; 4] = must_cast(x);
        let y: Lanes = must_cast([
            _mm_rsqrt_ps(q[0]),
            _mm_rsqrt_ps(q[1]),
            _mm_rsqrt_ps(q[2]),
            _mm_rsqrt_ps(q[3]),
        ]);
        let mut r = [0.0f32; 16];
        for i in 0..16 {
            r[i] = y[i] * (1.5 - (x[i] * 0.5) * (y[i] * y[i]));
        }
        r
    };
    run_any::<M, L, _, INPUTS>(k, pos, nor, inputs, out, rsqrt)
}

/// [`run`] where `INPUTS` is false (a call without per-point inputs), [`run_inputs`] where it is
/// true. Each level's function is generic over `INPUTS`, so the two are compiled as separate
/// functions: the plain loop is not grown by the G-buffer's instances.
#[inline(always)]
fn run_any<M: BatchModel, L: BatchLight, R: Fn(Lanes) -> Lanes, const INPUTS: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
    rsqrt: R,
) -> usize {
    if INPUTS {
        run_inputs(k, pos, nor, inputs, out, rsqrt)
    } else {
        run(k, pos, nor, out, rsqrt)
    }
}
