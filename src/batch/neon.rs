//! The NEON level (aarch64): the portable kernel with NEON's inverse square root estimate.
//!
//! NEON is part of the aarch64 baseline, so LLVM already compiles the portable kernel's 16-lane
//! loops to 4-lane NEON instructions at every level on aarch64. What this level changes is the
//! one level-specific operation, the inverse square root: `frsqrte` (an estimate to about 8
//! bits) and two Newton steps by `frsqrts`, which computes `(3 − a·b)/2` fused, in place of a
//! square root and a division per lane (both long-latency instructions on aarch64 cores).
//!
//! Both functions enable `neon`, so the intrinsics are safe inside them (the closure inherits the
//! feature); `dispatch` calls [`neon`] where `Level::Neon.is_supported()` found NEON in the
//! build's target features. `bytemuck::must_cast` moves `[f32; 16]` in and out of vector
//! registers without `unsafe`.

use core::arch::aarch64::{float32x4_t, vmulq_f32, vrsqrteq_f32, vrsqrtsq_f32};

use bytemuck::must_cast;

use super::kernel::{Lanes, PointInputs, Setup, run, run_inputs};
use super::prepare::{BatchLight, BatchModel};
use super::soa::{SoaRgb, SoaVec3};

/// `1/√x` on four lanes: the estimate, then `y ← y·(3 − x·y²)/2` twice. Relative error about
/// `1.5·(1.5·2⁻⁸)²` after the first step and below `1e-9` after the second, plus the steps'
/// roundings (a few `2⁻²⁴`): within the `3.5e-7` the batch accuracy analysis allows per inverse
/// norm.
#[target_feature(enable = "neon")]
#[inline]
fn rsqrt4(x: float32x4_t) -> float32x4_t {
    let y = vrsqrteq_f32(x);
    let y = vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(x, y), y));
    vmulq_f32(y, vrsqrtsq_f32(vmulq_f32(x, y), y))
}

/// The portable kernel with [`rsqrt4`] on each quarter of the 16 lanes; with per-point inputs
/// (a G-buffer call) when `inputs` is `Some`.
#[target_feature(enable = "neon")]
pub(super) fn neon<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: Option<&PointInputs<'_>>,
    out: SoaRgb<'_>,
) -> usize {
    let rsqrt = |x: Lanes| -> Lanes {
        let q: [float32x4_t; 4] = must_cast(x);
        must_cast([rsqrt4(q[0]), rsqrt4(q[1]), rsqrt4(q[2]), rsqrt4(q[3])])
    };
    match inputs {
        None => run(k, pos, nor, out, rsqrt),
        Some(inputs) => run_inputs(k, pos, nor, inputs, out, rsqrt),
    }
}
