//! The private switch between `std` and `libm` float functions.
//!
//! Every transcendental the crate calls goes through here, so the `std`/`libm` choice is made in one
//! place (the same pattern as glam's `f32/math.rs`). With both features on, `std` wins.

#[cfg(feature = "std")]
mod imp {
    #[inline(always)]
    pub fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline(always)]
    pub fn sqrt_f64(x: f64) -> f64 {
        x.sqrt()
    }
    #[inline(always)]
    pub fn powf(x: f32, y: f32) -> f32 {
        x.powf(y)
    }
    #[inline(always)]
    pub fn cos(x: f32) -> f32 {
        x.cos()
    }
}

#[cfg(all(not(feature = "std"), feature = "libm"))]
mod imp {
    #[inline(always)]
    pub fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline(always)]
    pub fn sqrt_f64(x: f64) -> f64 {
        libm::sqrt(x)
    }
    #[inline(always)]
    pub fn powf(x: f32, y: f32) -> f32 {
        libm::powf(x, y)
    }
    #[inline(always)]
    pub fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
}

/// Neither feature: lib.rs stops the build with a `compile_error!`; these stand-ins only keep that
/// message from being buried under unresolved-name errors.
#[cfg(not(any(feature = "std", feature = "libm")))]
mod imp {
    pub fn sqrt(x: f32) -> f32 {
        x
    }
    pub fn sqrt_f64(x: f64) -> f64 {
        x
    }
    pub fn powf(x: f32, _y: f32) -> f32 {
        x
    }
    pub fn cos(x: f32) -> f32 {
        x
    }
}

pub(crate) use imp::*;

/// `|x|` without relying on `f32::abs` being available in `core` on every toolchain.
#[inline(always)]
pub(crate) fn abs(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// The largest finite magnitude, used to saturate results that would overflow.
pub(crate) const MAX: f32 = f32::MAX;

/// Clamps to `[lo, hi]`, mapping NaN to `lo`. Used on the total paths so no NaN escapes.
#[inline(always)]
pub(crate) fn clamp_or_lo(x: f32, lo: f32, hi: f32) -> f32 {
    // `f32::max` returns the non-NaN operand, so NaN becomes `lo` here.
    x.max(lo).min(hi)
}
