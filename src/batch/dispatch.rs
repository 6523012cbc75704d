//! The library's only `unsafe` code (four `unsafe` blocks around eight kernel calls; the AVX-512
//! kernel's tests have their own):
//! calling a `#[target_feature]` kernel after checking the CPU.

#![allow(
    unsafe_code,
    reason = "the one dispatch site: target-feature kernels called after the CPU check"
)]

use super::kernel::{PointInputs, Setup, run, run_inputs};
use super::level::Level;
use super::prepare::{BatchLight, BatchModel};
use super::soa::{SoaRgb, SoaVec3};

/// Runs the kernel compiled for `level`. The caller has checked `level.is_supported()`; a level
/// that is not supported (or does not exist on this architecture) runs the portable kernel.
pub(super) fn run_level<M: BatchModel, L: BatchLight>(
    level: Level,
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
) -> usize {
    // Without per-point inputs: the plain kernel (see `kernel::run_inputs`).
    let plain = !inputs.per_point_surface() && inputs.visibility.is_none();
    #[cfg(target_arch = "x86_64")]
    {
        use super::{avx512, x86};
        match level {
            Level::Avx512 if level.is_supported() => {
                // SAFETY: `is_supported` checked AVX-512F, AVX-512VL, AVX2 and FMA (at run time
                // with `std`, in the build's target features without), which is every feature
                // `avx512::avx512` and `x86::avx512` enable. The intrinsics kernel has no
                // per-point inputs and no falloff light other than polynomial ones: such calls
                // run the one source compiled for AVX-512.
                return unsafe {
                    if plain && !k.portable_only {
                        avx512::avx512(k, pos, nor, out)
                    } else if plain {
                        x86::avx512::<M, L, false>(k, pos, nor, inputs, out)
                    } else {
                        x86::avx512::<M, L, true>(k, pos, nor, inputs, out)
                    }
                };
            }
            Level::Avx2 if level.is_supported() => {
                // SAFETY: `is_supported` checked AVX2 and FMA, the features `x86::avx2` enables.
                return unsafe {
                    if plain {
                        x86::avx2::<M, L, false>(k, pos, nor, inputs, out)
                    } else {
                        x86::avx2::<M, L, true>(k, pos, nor, inputs, out)
                    }
                };
            }
            Level::Sse2 => {
                // SAFETY: SSE2 is part of the x86_64 baseline: every x86_64 CPU has it.
                return unsafe {
                    if plain {
                        x86::sse2::<M, L, false>(k, pos, nor, inputs, out)
                    } else {
                        x86::sse2::<M, L, true>(k, pos, nor, inputs, out)
                    }
                };
            }
            _ => {}
        }
    }
    #[cfg(target_arch = "aarch64")]
    if level == Level::Neon && level.is_supported() {
        // SAFETY: `is_supported` checked that the build enables NEON (every aarch64 target
        // does), the one feature `neon::neon` enables.
        return unsafe { super::neon::neon(k, pos, nor, (!plain).then_some(inputs), out) };
    }
    let _ = level;
    portable(k, pos, nor, (!plain).then_some(inputs), out)
}

/// The portable kernel: an exact `1 / sqrt(x)`.
fn portable<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: Option<&PointInputs<'_>>,
    out: SoaRgb<'_>,
) -> usize {
    let rsqrt = |x: super::kernel::Lanes| {
        let mut r = x;
        for v in &mut r {
            *v = 1.0 / crate::math::sqrt(*v);
        }
        r
    };
    match inputs {
        None => run(k, pos, nor, out, rsqrt),
        Some(inputs) => run_inputs(k, pos, nor, inputs, out, rsqrt),
    }
}
