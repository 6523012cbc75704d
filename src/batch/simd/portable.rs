//! The `Portable` level: sixteen lanes as `[f32; 16]`, each operation sixteen independent lane
//! expressions, which LLVM vectorises for whatever the build targets; an exact `1 / sqrt(x)`.

use super::super::simd::Simd;
use crate::batch::kernel::{Lanes, W};
use crate::math;

/// The `Portable` level's token (every build runs it).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Portable;

/// A lane's mask: all ones for `true`, 0 for `false`.
#[inline(always)]
fn mask(b: bool) -> u32 {
    0u32.wrapping_sub(u32::from(b))
}

/// `[f(0), f(1), …, f(15)]`, written out lane by lane rather than as a loop: LLVM vectorises the
/// sixteen expressions just the same, but a loop per operation cost it a rotation, a full unroll
/// and a scalar replacement of the array each time. This level's three kernels took half the
/// release library's optimisation time that way (50 of 107 s in `-Z llvm-time-trace`, x86_64);
/// written out, 17 s, and the level runs no slower (`levels_4096`).
macro_rules! each {
    (|$i:ident| $e:expr) => {{
        const { assert!(W == 16, "each!: sixteen lanes") };
        each!(@lanes $i, $e, [0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15])
    }};
    (@lanes $i:ident, $e:expr, [$($k:literal)+]) => {
        [$({
            let $i: usize = $k;
            $e
        }),+]
    };
}

// Where a vector level always exists (x86_64 has SSE2, aarch64 NEON), the portable level runs
// only when a caller forces it (the tests, the levels table in docs/performance.md): one general
// instance per output form keeps its code small there. It was 43% of the library's kernel code
// with eleven instances. Elsewhere it is the level every call runs, with every instance.
#[cfg(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", target_feature = "neon")
))]
level_entry!(Portable, general_only);
#[cfg(not(any(
    target_arch = "x86_64",
    all(target_arch = "aarch64", target_feature = "neon")
)))]
level_entry!(Portable);

impl Simd for Portable {
    type V = Lanes;
    type I = [i32; W];
    /// All ones where set, 0 where not (as the vector levels' masks), so the compiler can
    /// vectorise the selects as bit operations.
    type M = [u32; W];

    #[inline(always)]
    fn splat(self, x: f32) -> Lanes {
        [x; W]
    }
    #[inline(always)]
    fn load(self, a: &Lanes) -> Lanes {
        *a
    }
    #[inline(always)]
    fn store(self, v: Lanes) -> Lanes {
        v
    }
    #[inline(always)]
    fn add(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| a[i] + b[i])
    }
    #[inline(always)]
    fn sub(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| a[i] - b[i])
    }
    #[inline(always)]
    fn mul(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| a[i] * b[i])
    }
    #[inline(always)]
    fn div(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| a[i] / b[i])
    }
    #[inline(always)]
    fn mul_add(self, a: Lanes, b: Lanes, c: Lanes) -> Lanes {
        each!(|i| a[i] * b[i] + c[i])
    }
    #[inline(always)]
    fn mul_sub(self, a: Lanes, b: Lanes, c: Lanes) -> Lanes {
        each!(|i| a[i] * b[i] - c[i])
    }
    #[inline(always)]
    fn min(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| if a[i] < b[i] { a[i] } else { b[i] })
    }
    #[inline(always)]
    fn max(self, a: Lanes, b: Lanes) -> Lanes {
        each!(|i| if a[i] > b[i] { a[i] } else { b[i] })
    }
    #[inline(always)]
    fn rsqrt(self, x: Lanes) -> Lanes {
        each!(|i| 1.0 / math::sqrt(x[i]))
    }
    #[inline(always)]
    fn sqrt(self, x: Lanes) -> Lanes {
        each!(|i| math::sqrt(x[i]))
    }
    #[inline(always)]
    fn lt(self, a: Lanes, b: Lanes) -> [u32; W] {
        each!(|i| mask(a[i] < b[i]))
    }
    #[inline(always)]
    fn le(self, a: Lanes, b: Lanes) -> [u32; W] {
        each!(|i| mask(a[i] <= b[i]))
    }
    #[inline(always)]
    fn gt(self, a: Lanes, b: Lanes) -> [u32; W] {
        each!(|i| mask(a[i] > b[i]))
    }
    #[inline(always)]
    fn ge(self, a: Lanes, b: Lanes) -> [u32; W] {
        each!(|i| mask(a[i] >= b[i]))
    }
    #[inline(always)]
    fn and(self, a: [u32; W], b: [u32; W]) -> [u32; W] {
        each!(|i| a[i] & b[i])
    }
    #[inline(always)]
    fn select(self, m: [u32; W], a: Lanes, b: Lanes) -> Lanes {
        each!(|i| f32::from_bits((a[i].to_bits() & m[i]) | (b[i].to_bits() & !m[i])))
    }
    #[inline(always)]
    fn keep(self, m: [u32; W], a: Lanes) -> Lanes {
        each!(|i| f32::from_bits(a[i].to_bits() & m[i]))
    }
    #[inline(always)]
    fn bits(self, m: [u32; W]) -> u32 {
        let mut b = 0;
        for (i, &set) in m.iter().enumerate() {
            b |= (set & 1) << i;
        }
        b
    }
    #[inline(always)]
    fn to_bits(self, v: Lanes) -> [i32; W] {
        each!(|i| v[i].to_bits() as i32)
    }
    #[inline(always)]
    fn bits_to_f32(self, a: [i32; W]) -> Lanes {
        each!(|i| f32::from_bits(a[i] as u32))
    }
    #[inline(always)]
    fn splat_i(self, x: i32) -> [i32; W] {
        [x; W]
    }
    #[inline(always)]
    fn add_i(self, a: [i32; W], b: [i32; W]) -> [i32; W] {
        each!(|i| a[i].wrapping_add(b[i]))
    }
    #[inline(always)]
    fn sub_i(self, a: [i32; W], b: [i32; W]) -> [i32; W] {
        each!(|i| a[i].wrapping_sub(b[i]))
    }
    #[inline(always)]
    fn shl23(self, a: [i32; W]) -> [i32; W] {
        each!(|i| a[i].wrapping_shl(23))
    }
    #[inline(always)]
    fn sar23(self, a: [i32; W]) -> [i32; W] {
        each!(|i| a[i] >> 23)
    }
    #[inline(always)]
    fn to_f32(self, a: [i32; W]) -> Lanes {
        each!(|i| a[i] as f32)
    }
    /// `(v + 1.5·2²³) − 1.5·2²³`, exact for `|v| < 2²²` (`core` has no `round_ties_even`
    /// without `std`).
    #[inline(always)]
    fn round(self, v: Lanes) -> Lanes {
        each!(|i| (v[i] + 12_582_912.0) - 12_582_912.0)
    }
    #[inline(always)]
    fn to_i(self, v: Lanes) -> [i32; W] {
        each!(|i| v[i] as i32)
    }
    #[inline(always)]
    fn srl16(self, a: [i32; W]) -> [i32; W] {
        each!(|i| ((a[i] as u32) >> 16) as i32)
    }
    #[inline(always)]
    fn shl8(self, a: [i32; W]) -> [i32; W] {
        each!(|i| a[i].wrapping_shl(8))
    }
    #[inline(always)]
    fn shl16(self, a: [i32; W]) -> [i32; W] {
        each!(|i| a[i].wrapping_shl(16))
    }
    #[inline(always)]
    fn and_i(self, a: [i32; W], b: [i32; W]) -> [i32; W] {
        each!(|i| a[i] & b[i])
    }
    #[inline(always)]
    fn or_i(self, a: [i32; W], b: [i32; W]) -> [i32; W] {
        each!(|i| a[i] | b[i])
    }
    #[inline(always)]
    fn none_of(self, a: [i32; W], b: [i32; W]) -> [u32; W] {
        each!(|i| mask(a[i] & b[i] == 0))
    }
    #[inline(always)]
    fn gt_i(self, a: [i32; W], b: [i32; W]) -> [i32; W] {
        each!(|i| -i32::from(a[i] > b[i]))
    }
}
