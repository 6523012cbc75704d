//! Instruction-set levels the batch kernel is compiled for, and which of them the CPU runs.

use core::fmt;

/// An instruction-set level of the batch kernel.
///
/// Every level runs the same kernel source: one 16-lane loop, generic over a private trait of
/// vector primitives (fused or separate multiply-add, inverse square root, compares and selects,
/// the integer bit operations of `log2`/`exp2`), which each level implements with its own
/// instructions and compiles inside its own `#[target_feature]` function. The levels differ in
/// the vector width, in whether multiply-adds are fused, and in how the three inverse norms
/// `1/‖n‖`, `1/‖L‖`, `1/‖V‖` are computed, so their results differ by rounding:
///
/// | level | vectors | inverse norm | its relative error |
/// |---|---|---|---|
/// | `Portable` | `[f32; 16]` loops, vectorised for whatever the build targets | `1 / sqrt(x)` | ≤ 1 ulp + 0.5 ulp |
/// | `Neon` (aarch64) | 4 × 4 f32, fused | `frsqrte` + two Newton steps (`frsqrts`) | ≈ 2e-7 |
/// | `Sse2` (x86_64) | 4 × 4 f32 | `rsqrtps` + one Newton step | ≤ 1.5·(1.5·2⁻¹²)² + rounding ≈ 3e-7 |
/// | `Avx2` (AVX2 + FMA) | 2 × 8 f32, fused | `vrsqrtps` + one Newton step (fused) | ≈ 3e-7, as `Sse2` |
/// | `Avx512` (AVX-512F/VL + AVX2 + FMA) | 1 × 16 f32, fused, mask registers | `vrsqrt14ps` + one Newton step | ≤ 1.5·2⁻²⁸ + rounding ≈ 1.5e-7 |
///
/// (A Newton step `y' = y·(3 − x·y²)/2` turns a relative error `e` into about `1.5·e²`.) Every
/// level sends the same points to the scalar [`shade`](crate::shade) (degenerate points, and
/// Blinn-Phong lanes with light and viewer nearly opposite; see the [`batch`](crate::batch)
/// module docs), and every level computes `PowStrategy::Exact` with `powf` lane by lane. The
/// batch tests compare every level with the scalar [`shade`](crate::shade); docs/performance.md
/// has each level's speed and 8-bit accuracy.
///
/// On x86_64 and on aarch64 with NEON, where a vector level always exists, `Portable` runs only
/// when a caller forces it (with [`shade_batch_with_level`](crate::shade_batch_with_level)), and
/// it is compiled as the kernel's one general form (no folded products, no specialisation for
/// calls without per-point inputs): it keeps the build small and is slower than it would be
/// on a target where it is the level every call runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Level {
    /// Plain Rust, no intrinsics: runs on every target.
    Portable,
    /// x86_64's baseline SSE2 (every x86_64 CPU).
    Sse2,
    /// AVX2 with FMA.
    Avx2,
    /// AVX-512 F and VL, with AVX2 and FMA.
    Avx512,
    /// aarch64's NEON (every aarch64 CPU): the kernel on NEON vectors, with fused multiply-adds
    /// and NEON's inverse square root estimate.
    Neon,
}

impl Level {
    /// Every level, lowest first within each architecture (`Neon` is aarch64's, the others after
    /// it x86_64's). A slice, not an array: the enum is `#[non_exhaustive]`, and a level added
    /// later lengthens it without changing its type.
    pub const ALL: &'static [Level] = &[
        Level::Portable,
        Level::Neon,
        Level::Sse2,
        Level::Avx2,
        Level::Avx512,
    ];

    /// Whether this CPU (with `std`: detected at run time) or this build (without `std`: the
    /// target features enabled at compile time) can run the level.
    #[must_use]
    pub fn is_supported(self) -> bool {
        match self {
            Level::Portable => true,
            Level::Sse2 => cfg!(target_arch = "x86_64"),
            Level::Avx2 => has_avx2(),
            Level::Avx512 => has_avx512(),
            Level::Neon => cfg!(all(target_arch = "aarch64", target_feature = "neon")),
        }
    }

    /// The best level [`is_supported`](Self::is_supported): what [`shade_batch`](crate::shade_batch)
    /// uses.
    #[must_use]
    pub fn detect() -> Level {
        let mut best = Level::Portable;
        for &l in Level::ALL {
            if l.is_supported() {
                best = l;
            }
        }
        best
    }

    /// Every level this machine supports, lowest first (for tests and benchmarks).
    pub fn supported() -> impl Iterator<Item = Level> {
        Level::ALL.iter().copied().filter(|l| l.is_supported())
    }

    /// A short name: `"portable"`, `"neon"`, `"sse2"`, `"avx2"`, `"avx512"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Level::Portable => "portable",
            Level::Sse2 => "sse2",
            Level::Avx2 => "avx2",
            Level::Avx512 => "avx512",
            Level::Neon => "neon",
        }
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A requested [`Level`] that this CPU or build cannot run; returned by
/// [`shade_batch_with_level`](crate::shade_batch_with_level) instead of running it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnsupportedLevel(pub Level);

impl fmt::Display for UnsupportedLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "batch level {} is not supported on this CPU or build",
            self.0
        )
    }
}

impl core::error::Error for UnsupportedLevel {}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
fn has_avx2() -> bool {
    std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
}

#[cfg(all(feature = "std", target_arch = "x86_64"))]
fn has_avx512() -> bool {
    has_avx2()
        && std::is_x86_feature_detected!("avx512f")
        && std::is_x86_feature_detected!("avx512vl")
}

#[cfg(not(all(feature = "std", target_arch = "x86_64")))]
fn has_avx2() -> bool {
    cfg!(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma"
    ))
}

#[cfg(not(all(feature = "std", target_arch = "x86_64")))]
fn has_avx512() -> bool {
    has_avx2() && cfg!(all(target_feature = "avx512f", target_feature = "avx512vl"))
}
