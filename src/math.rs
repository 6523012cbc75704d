//! The private switch between `std` and `libm` float functions.
//!
//! Every transcendental the crate calls goes through here, so the `std`/`libm` choice is made in one
//! place (the same pattern as glam's `f32/math.rs`). With both features on, `std` wins.

#[cfg(feature = "std")]
mod imp {
    #[inline(always)]
    pub(crate) fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    #[inline(always)]
    pub(crate) fn sqrt_f64(x: f64) -> f64 {
        x.sqrt()
    }
    #[inline(always)]
    pub(crate) fn powf(x: f32, y: f32) -> f32 {
        x.powf(y)
    }
    #[inline(always)]
    pub(crate) fn cos(x: f32) -> f32 {
        x.cos()
    }
}

#[cfg(all(not(feature = "std"), feature = "libm"))]
mod imp {
    #[inline(always)]
    pub(crate) fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline(always)]
    pub(crate) fn sqrt_f64(x: f64) -> f64 {
        libm::sqrt(x)
    }
    #[inline(always)]
    pub(crate) fn powf(x: f32, y: f32) -> f32 {
        libm::powf(x, y)
    }
    #[inline(always)]
    pub(crate) fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
}

/// Neither feature: lib.rs stops the build with a `compile_error!`; these stand-ins only keep that
/// message from being buried under unresolved-name errors.
#[cfg(not(any(feature = "std", feature = "libm")))]
mod imp {
    pub(crate) fn sqrt(x: f32) -> f32 {
        x
    }
    pub(crate) fn sqrt_f64(x: f64) -> f64 {
        x
    }
    pub(crate) fn powf(x: f32, _y: f32) -> f32 {
        x
    }
    pub(crate) fn cos(x: f32) -> f32 {
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

/// `max(x, lo)` that maps NaN to `lo`, in one `maxss`.
///
/// `f32::max` implements IEEE maxNum, which costs a NaN test and a blend on x86; this
/// compare-and-select is the machine's own `max` and gives the same answer for every non-NaN `x`.
/// The shading loop runs a dozen of these per light, so the difference is measurable.
#[inline(always)]
pub(crate) fn max_or(x: f32, lo: f32) -> f32 {
    let x = quiet(x);
    if x > lo { x } else { lo }
}

/// `min(x, hi)` that maps NaN to `hi`, in one `minss` (see [`max_or`]).
#[inline(always)]
pub(crate) fn min_or(x: f32, hi: f32) -> f32 {
    let x = quiet(x);
    if x < hi { x } else { hi }
}

/// `x` with a signalling NaN made quiet, where the compare-and-selects above need it.
///
/// x86's `maxss`/`minss` return the second operand for every NaN, so there the select is exact
/// and this is the identity. Elsewhere LLVM may lower the select to IEEE maxNum/minNum (AArch64's
/// `fmaxnm`/`fminnm`), which return a quiet NaN, not the bound, for a *signalling* NaN; adding 0
/// quiets it first and changes nothing else but the sign of a zero (found by the aarch64 run of
/// the unchecked-constructor property tests, which feed arbitrary bit patterns).
#[inline(always)]
fn quiet(x: f32) -> f32 {
    if cfg!(any(target_arch = "x86", target_arch = "x86_64")) {
        x
    } else {
        x + 0.0
    }
}

/// Clamps to `[lo, hi]`, mapping NaN to `lo`. Used on the total paths so no NaN escapes.
#[inline(always)]
pub(crate) fn clamp_or_lo(x: f32, lo: f32, hi: f32) -> f32 {
    min_or(max_or(x, lo), hi)
}
