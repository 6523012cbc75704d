//! Which level's kernel runs a call: the level's token, where the CPU has its instructions.

use super::kernel::Job;
use super::level::Level;
use super::simd::portable::Portable;
use super::sink::Sink;

/// Runs the kernel compiled for `level`. A level that is not supported (or does not exist on this
/// architecture) runs the portable kernel; callers check `level.is_supported()` first.
pub(super) fn run_level<O: Sink>(level: Level, job: Job<'_, O>) -> usize {
    #[cfg(target_arch = "x86_64")]
    {
        use super::simd::{avx2::Avx2, avx512::Avx512, sse2::Sse2};
        match level {
            Level::Avx512 => {
                if let Some(t) = Avx512::new() {
                    return O::run_on(t, job);
                }
            }
            Level::Avx2 => {
                if let Some(t) = Avx2::new() {
                    return O::run_on(t, job);
                }
            }
            Level::Sse2 => return O::run_on(Sse2, job),
            _ => {}
        }
    }
    #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
    if level == Level::Neon {
        return O::run_on(super::simd::neon::Neon, job);
    }
    let _ = level;
    O::run_on(Portable, job)
}
