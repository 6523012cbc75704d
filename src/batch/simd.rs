//! The per-level primitives of the batch kernel: one small trait, [`Simd`], over 16 lanes.
//!
//! The kernel ([`kernel`](super::kernel)) is written once, generic over `S: Simd`; each level
//! implements the trait with its own instructions, as libm's `select_implementation!` picks an
//! architecture's routine for one operation:
//!
//! | level | file | 16 lanes are | inverse square root |
//! |---|---|---|---|
//! | `Portable` | `simd/portable.rs` | `[f32; 16]`, a loop LLVM vectorises | `1 / sqrt(x)` |
//! | `Sse2` | `simd/sse2.rs` | 4 × `__m128` | `rsqrtps` + one Newton step |
//! | `Avx2` | `simd/avx2.rs` | 2 × `__m256`, with FMA | `vrsqrtps` + one Newton step |
//! | `Avx512` | `simd/avx512.rs` | 1 × `__m512`, with FMA and mask registers | `vrsqrt14ps` + one Newton step |
//! | `Neon` | `simd/neon.rs` | 4 × `float32x4_t`, with FMA | `frsqrte` + two `frsqrts` steps |
//!
//! Two table lookups differ more than the rest: `gather` (the 8-bit encoder's bucket table) is
//! `vpgatherdd` at AVX2 and AVX-512 and lane by lane elsewhere; `lookup16` (a table of sixteen)
//! is `vpermps` at AVX-512, two `vpermps` and a blend at AVX2, and lane by lane elsewhere, and
//! `LOOKUP16_IN_REGISTERS` tells the kernel which it gets.
//!
//! A value of an implementing type is a *token*: it exists only where its instructions run (each
//! level's constructor checks the CPU), so its methods may call the intrinsics. The kernel runs
//! inside the level's `#[target_feature]` function, where every method inlines into the loop.
//!
//! Every comparison is ordered (false for NaN), `min`/`max` return the second operand when either
//! is NaN (x86's `minps`/`maxps`: `a < b ? a : b`), as [`math::min_or`](crate::math) does for
//! one value, so a NaN can be mapped to a bound by its argument order.

use super::kernel::Lanes;

/// Sixteen `f32` lanes and the operations the batch kernel needs on them (see the module docs).
///
/// `I` is sixteen `i32` lanes for the bit manipulations of `log2`/`exp2`; `M` a sixteen-lane
/// mask.
pub(crate) trait Simd: Copy {
    /// Sixteen `f32` lanes.
    type V: Copy;
    /// Sixteen `i32` lanes.
    type I: Copy;
    /// A mask over sixteen lanes.
    type M: Copy;

    /// Every lane `x`.
    fn splat(self, x: f32) -> Self::V;
    /// The lanes of `a`.
    fn load(self, a: &Lanes) -> Self::V;
    /// The lanes as an array.
    fn store(self, v: Self::V) -> Lanes;

    /// `a + b`.
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a − b`.
    fn sub(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a · b`.
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a / b`.
    fn div(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a · b + c`, fused where the level has FMA.
    fn mul_add(self, a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    /// `a · b − c`, fused where the level has FMA.
    fn mul_sub(self, a: Self::V, b: Self::V, c: Self::V) -> Self::V;
    /// `a < b ? a : b` (`b` where either is NaN).
    fn min(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a > b ? a : b` (`b` where either is NaN).
    fn max(self, a: Self::V, b: Self::V) -> Self::V;
    /// `1/√x` for `x` in `[1e-30, 1e30]`, to a relative error of a few `2⁻²⁴` (the level's estimate
    /// and Newton steps, or the exact quotient).
    fn rsqrt(self, x: Self::V) -> Self::V;
    /// `√x`, correctly rounded (IEEE 754's square root, as `f32::sqrt`).
    fn sqrt(self, x: Self::V) -> Self::V;

    /// `a < b` per lane.
    fn lt(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ≤ b` per lane.
    fn le(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a > b` per lane.
    fn gt(self, a: Self::V, b: Self::V) -> Self::M;
    /// `a ≥ b` per lane.
    fn ge(self, a: Self::V, b: Self::V) -> Self::M;
    /// Both masks.
    fn and(self, a: Self::M, b: Self::M) -> Self::M;
    /// `m ? a : b` per lane.
    fn select(self, m: Self::M, a: Self::V, b: Self::V) -> Self::V;
    /// `m ? a : 0` per lane.
    fn keep(self, m: Self::M, a: Self::V) -> Self::V;
    /// Bit `i` set where lane `i` of `m` is set.
    fn bits(self, m: Self::M) -> u32;

    /// The bits of each lane.
    fn to_bits(self, v: Self::V) -> Self::I;
    /// Lanes with the given bits.
    fn bits_to_f32(self, i: Self::I) -> Self::V;
    /// Every lane `x`.
    fn splat_i(self, x: i32) -> Self::I;
    /// `a + b`, wrapping.
    fn add_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a − b`, wrapping.
    fn sub_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a << 23`.
    fn shl23(self, a: Self::I) -> Self::I;
    /// `a >> 23`, arithmetic.
    fn sar23(self, a: Self::I) -> Self::I;
    /// Each lane converted to `f32` (exact below `2²⁴`).
    fn to_f32(self, a: Self::I) -> Self::V;
    /// Each lane rounded to the nearest integer, ties to even, for `|v| < 2²²` (the levels
    /// without a rounding instruction add and subtract `1.5·2²³`).
    fn round(self, v: Self::V) -> Self::V;
    /// `q·2^r` for whole numbers `r` in `[−126, 127]` where the product is a normal number (so
    /// exact): AVX-512's `vscalefps`, elsewhere a product by `2^r` built in the exponent bits
    /// (with wrapping integer arithmetic). Other lanes get an unspecified value, never a panic:
    /// `exp2`'s lanes for bases `≤ 0`, which its callers clear.
    #[inline(always)]
    fn scale2(self, q: Self::V, r: Self::V) -> Self::V {
        let biased = self.add_i(self.to_i(r), self.splat_i(127));
        self.mul(q, self.bits_to_f32(self.shl23(biased)))
    }
    /// Each lane converted to `i32`, truncated (exact for a whole number below `2³¹`).
    fn to_i(self, v: Self::V) -> Self::I;
    /// `a >> 16`, logical.
    fn srl16(self, a: Self::I) -> Self::I;
    /// `a << 8`.
    fn shl8(self, a: Self::I) -> Self::I;
    /// `a << 16`.
    fn shl16(self, a: Self::I) -> Self::I;
    /// `a & b`.
    fn and_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// `a | b`.
    fn or_i(self, a: Self::I, b: Self::I) -> Self::I;
    /// The lanes where `a & b` is 0 (AVX-512's `vptestnmd`).
    fn none_of(self, a: Self::I, b: Self::I) -> Self::M;
    /// `a > b` (signed) per lane as an integer mask: −1 where it holds, 0 elsewhere.
    fn gt_i(self, a: Self::I, b: Self::I) -> Self::I;

    /// `table[idx]` per lane, with each index first clamped into the table (as unsigned, so a
    /// negative one reads the last entry): a table lookup that cannot read outside it.
    ///
    /// One load per lane through memory; the levels with a gather instruction override it.
    #[inline(always)]
    fn gather(self, table: &[i32], idx: Self::I) -> Self::I {
        let last = table.len().saturating_sub(1);
        let idx = self.store(self.bits_to_f32(idx));
        let mut got: super::kernel::Lanes = [0.0; super::kernel::W];
        // A loop, not `array::from_fn`: a closure would not inherit a level's target features.
        for (g, i) in got.iter_mut().zip(idx) {
            let at = (i.to_bits() as usize).min(last);
            *g = f32::from_bits(table.get(at).copied().unwrap_or(0) as u32);
        }
        self.to_bits(self.load(&got))
    }

    /// Whether [`lookup16`](Self::lookup16) runs in registers (a permute instruction), not
    /// lane by lane through memory.
    const LOOKUP16_IN_REGISTERS: bool = false;

    /// `table[idx & 15]` per lane: a lookup in a table of sixteen, which the levels with a
    /// variable permute keep in registers.
    ///
    /// One load per lane through memory; the levels with a permute instruction override it.
    #[inline(always)]
    fn lookup16(self, table: &[f32; 16], idx: Self::I) -> Self::V {
        let idx = self.store(self.bits_to_f32(idx));
        let mut got: super::kernel::Lanes = [0.0; super::kernel::W];
        for (g, i) in got.iter_mut().zip(idx) {
            *g = table[(i.to_bits() & 15) as usize];
        }
        self.load(&got)
    }
}

/// A level's kernel entries: the batch kernel compiled with the level's instructions, for each
/// output form. Written by [`level_entry!`] for every level token.
pub(crate) trait Kernels: Copy {
    /// Runs the kernel writing total colours over the common prefix of the job's slices;
    /// returns its length.
    fn run(self, job: super::kernel::Job<'_>) -> usize;

    /// [`run`](Self::run) writing 8-bit pixels.
    fn run_pixels(self, job: super::kernel::Job<'_, super::sink::Pixels8<'_>>) -> usize;

    /// Runs the kernel writing the three terms (one instance per level; see
    /// [`run_terms`](super::kernel::run_terms)).
    fn run_terms(self, job: super::kernel::Job<'_, super::soa::SoaTerms<'_>>) -> usize;

    /// Runs [`run_with`](super::kernel::run_with)'s instance for these parameters, compiled
    /// for the level as a function of its own (a level that keeps only the general instance
    /// runs that one: its results differ from the others' only by rounding).
    fn instance<
        O: super::sink::Sink,
        const FOLDED: bool,
        const GREY: bool,
        const CALLS: bool,
        const SURFACE: bool,
        const VISIBILITY: bool,
        const PLAN: u8,
    >(
        self,
        job: super::kernel::Job<'_, O>,
    ) -> usize;
}

/// A level's entry: `kernel`, the loop compiled for the level, one function per instance, and
/// the token's [`Kernels`], whose `instance` calls it (the token's `run`, `run_pixels` and
/// `run_terms` pick the instance once per call). With a feature list the kernel is compiled
/// inside `#[target_feature]`, and `instance` calls it in an `unsafe` block whose proof is the
/// token: it exists only where the CPU has every feature listed. Without one, the kernel is the
/// build's own instructions, called plainly. Either way the kernel is kept out of line.
macro_rules! level_entry {
    ($level:ident $(, features = $features:literal)?) => {
        /// One instance of the kernel compiled for this level. Each instance is its own
        /// function: inlined together, a level's instances made one function per output form
        /// whose stack frame, in a build at opt-level 0, outgrew a spawned thread's stack.
        $(#[target_feature(enable = $features)])?
        #[inline(never)]
        fn kernel<
            O: $crate::batch::sink::Sink,
            const FOLDED: bool,
            const GREY: bool,
            const CALLS: bool,
            const SURFACE: bool,
            const VISIBILITY: bool,
            const PLAN: u8,
        >(
            t: $level,
            job: $crate::batch::kernel::Job<'_, O>,
        ) -> usize {
            $crate::batch::kernel::run_with::<
                $level, O, FOLDED, GREY, CALLS, SURFACE, VISIBILITY, PLAN,
            >(t, job)
        }

        level_entry!(@impl $level, |t, job| level_entry!(@call $($features)?;
            kernel::<O, FOLDED, GREY, CALLS, SURFACE, VISIBILITY, PLAN>(t, job)));
    };
    // A level that runs only when a caller forces it: one instance per output form, the general
    // one (no folding, per-point inputs read where the call has them), so the build compiles
    // three kernels for the level instead of eleven. See `portable.rs` for where this applies.
    ($level:ident, general_only) => {
        /// The kernel compiled for this level: the general instance.
        #[inline(never)]
        fn kernel<O: $crate::batch::sink::Sink>(
            t: $level,
            job: $crate::batch::kernel::Job<'_, O>,
        ) -> usize {
            $crate::batch::kernel::run_with::<
                $level, O, false, false, true, true, true, { $crate::batch::kernel::PLAN_ANY },
            >(t, job)
        }

        // Every instance is the general one.
        level_entry!(@impl $level, |t, job| kernel(t, job));
    };
    // The token's `Kernels`, whose `instance` is `$call` (with the token as `$t` and the job as
    // `$job`). The entries are not generic, so the kernels are compiled once, in this crate, and
    // not again in every crate that calls the batch API.
    (@impl $level:ident, |$t:ident, $job:ident| $call:expr) => {
        impl $crate::batch::simd::Kernels for $level {
            fn run(self, job: $crate::batch::kernel::Job<'_>) -> usize {
                if $crate::batch::kernel::has_inputs(job.inputs) {
                    $crate::batch::kernel::run::<_, _, true>(self, job)
                } else {
                    $crate::batch::kernel::run::<_, _, false>(self, job)
                }
            }

            // 8-bit output is the G-buffer's: only the instances with per-point inputs run
            // (without inputs their visibilities read as 1 and the material is the surface),
            // so the build compiles four kernels fewer per level. A plain call pays the
            // visibility's load and two products per light and chunk.
            fn run_pixels(
                self,
                job: $crate::batch::kernel::Job<'_, $crate::batch::sink::Pixels8<'_>>,
            ) -> usize {
                $crate::batch::kernel::run::<_, _, true>(self, job)
            }

            fn run_terms(
                self,
                job: $crate::batch::kernel::Job<'_, $crate::batch::soa::SoaTerms<'_>>,
            ) -> usize {
                $crate::batch::kernel::run_general(self, job)
            }

            #[inline]
            fn instance<
                O: $crate::batch::sink::Sink,
                const FOLDED: bool,
                const GREY: bool,
                const CALLS: bool,
                const SURFACE: bool,
                const VISIBILITY: bool,
                const PLAN: u8,
            >(
                self,
                $job: $crate::batch::kernel::Job<'_, O>,
            ) -> usize {
                let $t = self;
                $call
            }
        }
    };
    // A call of the level's kernel: `unsafe` where it is a `#[target_feature]` function.
    (@call $features:literal; $call:expr) => {
        // SAFETY: a token of this level exists only where the CPU has every feature the kernel
        // enables (its constructor checks them), and the call takes the token.
        unsafe { $call }
    };
    (@call; $call:expr) => {
        $call
    };
}

/// Implements [`Simd`] for a level whose sixteen lanes are native vectors (one per index in `[$j]`), from one method per
/// native operation (`$n`: the native `f32` vector, `$ni`: `i32` vector, `$nm`: mask vector).
/// Each method applies the native operation to every part, written out (no closure, which might
/// be left out of line without the level's target features).
#[cfg_attr(
    not(any(
        target_arch = "x86_64",
        all(target_arch = "aarch64", target_feature = "neon")
    )),
    allow(
        unused_macros,
        reason = "only the vector levels use it; this target has none"
    )
)]
macro_rules! simd_by_parts {
    ($token:ty, [$($j:tt),+], $n:ty, $ni:ty, $nm:ty, $native:ident, gather = $gather:ident, lookup16 = $lookup16:ident, scale2 = $scale2:ident) => {
        impl $crate::batch::simd::Simd for $token {
            type V = [$n; [$($j),+].len()];
            type I = [$ni; [$($j),+].len()];
            type M = [$nm; [$($j),+].len()];

            #[inline(always)]
            fn splat(self, x: f32) -> Self::V {
                [$({ let _ = $j; $native::splat(x) }),+]
            }
            #[inline(always)]
            fn load(self, a: &$crate::batch::kernel::Lanes) -> Self::V {
                bytemuck::must_cast(*a)
            }
            #[inline(always)]
            fn store(self, v: Self::V) -> $crate::batch::kernel::Lanes {
                bytemuck::must_cast(v)
            }
            #[inline(always)]
            fn add(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::add(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn sub(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::sub(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn mul(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::mul(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn div(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::div(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn mul_add(self, a: Self::V, b: Self::V, c: Self::V) -> Self::V {
                [$($native::mul_add(a[$j], b[$j], c[$j])),+]
            }
            #[inline(always)]
            fn mul_sub(self, a: Self::V, b: Self::V, c: Self::V) -> Self::V {
                [$($native::mul_sub(a[$j], b[$j], c[$j])),+]
            }
            #[inline(always)]
            fn min(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::min(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn max(self, a: Self::V, b: Self::V) -> Self::V {
                [$($native::max(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn rsqrt(self, x: Self::V) -> Self::V {
                [$($native::rsqrt(x[$j])),+]
            }
            #[inline(always)]
            fn sqrt(self, x: Self::V) -> Self::V {
                [$($native::sqrt(x[$j])),+]
            }
            #[inline(always)]
            fn lt(self, a: Self::V, b: Self::V) -> Self::M {
                [$($native::lt(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn le(self, a: Self::V, b: Self::V) -> Self::M {
                [$($native::le(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn gt(self, a: Self::V, b: Self::V) -> Self::M {
                [$($native::lt(b[$j], a[$j])),+]
            }
            #[inline(always)]
            fn ge(self, a: Self::V, b: Self::V) -> Self::M {
                [$($native::le(b[$j], a[$j])),+]
            }
            #[inline(always)]
            fn and(self, a: Self::M, b: Self::M) -> Self::M {
                [$($native::and(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn select(self, m: Self::M, a: Self::V, b: Self::V) -> Self::V {
                [$($native::select(m[$j], a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn keep(self, m: Self::M, a: Self::V) -> Self::V {
                [$($native::keep(m[$j], a[$j])),+]
            }
            #[inline(always)]
            fn bits(self, m: Self::M) -> u32 {
                let per = $crate::batch::kernel::W / m.len();
                0 $(| ($native::bits(m[$j]) << ($j * per)))+
            }
            #[inline(always)]
            fn to_bits(self, v: Self::V) -> Self::I {
                bytemuck::must_cast(v)
            }
            #[inline(always)]
            fn bits_to_f32(self, i: Self::I) -> Self::V {
                bytemuck::must_cast(i)
            }
            #[inline(always)]
            fn splat_i(self, x: i32) -> Self::I {
                [$({ let _ = $j; $native::splat_i(x) }),+]
            }
            #[inline(always)]
            fn add_i(self, a: Self::I, b: Self::I) -> Self::I {
                [$($native::add_i(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn sub_i(self, a: Self::I, b: Self::I) -> Self::I {
                [$($native::sub_i(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn shl23(self, a: Self::I) -> Self::I {
                [$($native::shl23(a[$j])),+]
            }
            #[inline(always)]
            fn sar23(self, a: Self::I) -> Self::I {
                [$($native::sar23(a[$j])),+]
            }
            #[inline(always)]
            fn to_f32(self, a: Self::I) -> Self::V {
                [$($native::to_f32(a[$j])),+]
            }
            #[inline(always)]
            fn round(self, v: Self::V) -> Self::V {
                [$($native::round(v[$j])),+]
            }
            #[inline(always)]
            fn to_i(self, v: Self::V) -> Self::I {
                [$($native::to_i(v[$j])),+]
            }
            #[inline(always)]
            fn srl16(self, a: Self::I) -> Self::I {
                [$($native::srl16(a[$j])),+]
            }
            #[inline(always)]
            fn shl8(self, a: Self::I) -> Self::I {
                [$($native::shl8(a[$j])),+]
            }
            #[inline(always)]
            fn shl16(self, a: Self::I) -> Self::I {
                [$($native::shl16(a[$j])),+]
            }
            #[inline(always)]
            fn and_i(self, a: Self::I, b: Self::I) -> Self::I {
                [$($native::and_i(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn or_i(self, a: Self::I, b: Self::I) -> Self::I {
                [$($native::or_i(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn none_of(self, a: Self::I, b: Self::I) -> Self::M {
                [$($native::none_of(a[$j], b[$j])),+]
            }
            #[inline(always)]
            fn gt_i(self, a: Self::I, b: Self::I) -> Self::I {
                [$($native::gt_i(a[$j], b[$j])),+]
            }
            $crate::batch::simd::default_or_native!($native, gather = $gather, [$($j),+]);
            $crate::batch::simd::default_or_native!($native, lookup16 = $lookup16, [$($j),+]);
            $crate::batch::simd::default_or_native!($native, scale2 = $scale2, [$($j),+]);
        }
    };
}

#[cfg_attr(
    not(any(
        target_arch = "x86_64",
        all(target_arch = "aarch64", target_feature = "neon")
    )),
    allow(
        unused_macros,
        unused_imports,
        reason = "only the vector levels use it; this target has none"
    )
)]
/// An operation of [`Simd`] that the trait defines from the others ([`gather`](Simd::gather),
/// [`lookup16`](Simd::lookup16), [`scale2`](Simd::scale2)) for a level built by
/// [`simd_by_parts!`]: the trait's default (`default`), or the level's own instruction on each
/// part (`native`).
macro_rules! default_or_native {
    ($native:ident, $op:ident = default, [$($j:expr),+]) => {};
    ($native:ident, gather = native, [$($j:expr),+]) => {
        #[inline(always)]
        fn gather(self, table: &[i32], idx: Self::I) -> Self::I {
            [$($native::gather(table, idx[$j])),+]
        }
    };
    ($native:ident, lookup16 = native, [$($j:expr),+]) => {
        const LOOKUP16_IN_REGISTERS: bool = true;

        #[inline(always)]
        fn lookup16(self, table: &[f32; 16], idx: Self::I) -> Self::V {
            [$($native::lookup16(table, idx[$j])),+]
        }
    };
    ($native:ident, scale2 = native, [$($j:expr),+]) => {
        #[inline(always)]
        fn scale2(self, q: Self::V, r: Self::V) -> Self::V {
            [$($native::scale2(q[$j], r[$j])),+]
        }
    };
}
pub(crate) use default_or_native;

#[cfg(target_arch = "x86_64")]
pub(crate) mod avx2;
#[cfg(target_arch = "x86_64")]
pub(crate) mod avx512;
#[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
pub(crate) mod neon;
pub(crate) mod portable;
#[cfg(target_arch = "x86_64")]
pub(crate) mod sse2;
