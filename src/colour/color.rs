//! Output encoding: linear ↔ sRGB, gamma, clamping and 8-bit quantisation.
//!
//! Shading happens in linear light; displays expect sRGB-encoded values. Writing linear values
//! straight into an 8-bit image makes everything too dark and the highlights too hard (LearnOpenGL's
//! "Gamma Correction" chapter shows the effect on a Blinn-Phong scene).

use glam::Vec3;

use crate::math;
use crate::srgb8;

/// Linear → sRGB transfer function (IEC 61966-2-1), exact piecewise form.
///
/// ```text
/// encode(x) = 12.92·x                  for x ≤ 0.0031308
///           = 1.055·x^(1/2.4) − 0.055  for x > 0.0031308
/// ```
///
/// Derivation and constants: docs/derivations.md, section "sRGB".
///
/// **Domain:** any finite `x`; `[0, 1]` maps onto `[0, 1]`. Values above 1 follow the same curve
/// (useful before tone mapping), negatives the linear segment, saturated at `−f32::MAX`.
/// **Degenerate input:** NaN gives 0.
///
/// ```
/// assert_eq!(phong::srgb_encode(0.0), 0.0);
/// assert!((phong::srgb_encode(1.0) - 1.0).abs() < 1e-6);
/// assert!((phong::srgb_encode(0.214_041) - 0.5).abs() < 1e-5);
/// ```
#[must_use]
#[inline]
pub fn srgb_encode(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else if x <= 0.003_130_8 {
        // Saturated: 12.92·x overflows for x below −2.6e37.
        (12.92 * x).max(-math::MAX)
    } else {
        1.055 * math::powf(x, 1.0 / 2.4) - 0.055
    }
}

/// sRGB → linear, the exact inverse of [`srgb_encode`].
///
/// ```text
/// decode(y) = y / 12.92                    for y ≤ 0.04045
///           = ((y + 0.055) / 1.055)^2.4    for y > 0.04045
/// ```
///
/// **Domain:** any finite `y`; `[0, 1]` onto `[0, 1]`. Results above `f32::MAX` saturate.
/// **Degenerate input:** NaN gives 0.
///
/// ```
/// let y = 0.7;
/// assert!((phong::srgb_encode(phong::srgb_decode(y)) - y).abs() < 1e-6);
/// ```
#[must_use]
#[inline]
pub fn srgb_decode(y: f32) -> f32 {
    if y.is_nan() {
        0.0
    } else if y <= 0.040_45 {
        y * (1.0 / 12.92)
    } else {
        math::powf((y + 0.055) * (1.0 / 1.055), 2.4).min(math::MAX)
    }
}

/// A pure power-law encoding `x^(1/γ)`, e.g. `γ = 2.2`, the approximation of sRGB many shaders use.
///
/// ```text
/// gamma_encode(x, γ) = max(x, 0)^(1/γ)
/// ```
///
/// **Domain:** `γ > 0`. **Degenerate input:** `x ≤ 0` or NaN gives 0; `γ ≤ 0` or NaN returns `x`
/// clamped to `≥ 0` unchanged (no encoding); huge results saturate at `f32::MAX`.
#[must_use]
#[inline]
pub fn gamma_encode(x: f32, gamma: f32) -> f32 {
    let x = math::clamp_or_lo(x, 0.0, math::MAX);
    if !(gamma > 0.0) || x == 0.0 {
        return x;
    }
    math::clamp_or_lo(math::powf(x, 1.0 / gamma), 0.0, math::MAX)
}

/// The inverse of [`gamma_encode`]: `max(y, 0)^γ`, with the same degenerate cases.
#[must_use]
#[inline]
pub fn gamma_decode(y: f32, gamma: f32) -> f32 {
    let y = math::clamp_or_lo(y, 0.0, math::MAX);
    if !(gamma > 0.0) || y == 0.0 {
        return y;
    }
    math::clamp_or_lo(math::powf(y, gamma), 0.0, math::MAX)
}

/// Clamps each channel to `[0, 1]`; NaN becomes 0.
#[must_use]
#[inline]
pub fn saturate(c: Vec3) -> Vec3 {
    Vec3::new(
        math::clamp_or_lo(c.x, 0.0, 1.0),
        math::clamp_or_lo(c.y, 0.0, 1.0),
        math::clamp_or_lo(c.z, 0.0, 1.0),
    )
}

/// Quantises an encoded value to 8 bits, rounding to nearest.
///
/// ```text
/// quantize(y) = ⌊255 · clamp(y, 0, 1) + 0.5⌋
/// ```
///
/// **Degenerate input:** NaN gives 0; values outside `[0, 1]` clamp.
///
/// ```
/// assert_eq!(phong::quantize_u8(0.5), 128);
/// assert_eq!(phong::quantize_u8(2.0), 255);
/// assert_eq!(phong::quantize_u8(-1.0), 0);
/// ```
#[must_use]
#[inline]
pub fn quantize_u8(y: f32) -> u8 {
    // `as` saturates and maps NaN to 0; the +0.5 and truncation round half up.
    (math::clamp_or_lo(y, 0.0, 1.0) * 255.0 + 0.5) as u8
}

/// A linear colour to 8-bit sRGB, per channel: the level nearest the exact sRGB value, ties up.
///
/// ```text
/// level(c) = ⌊255 · srgb(clamp(c, 0, 1)) + ½⌋      (srgb: the formula of `srgb_encode`, exact)
/// ```
///
/// No `powf`: each channel is located among the 255 level boundaries, precomputed as `f32`
/// thresholds (a table lookup and one comparison), so the result is the same on every platform
/// and with `libm`.
/// [`quantize_u8`]`(`[`srgb_encode`]`(c))` computes the same level in `f32` arithmetic and agrees
/// except where `c` lies within the `f32` rounding of `powf` (about `10⁻⁷` relative) of a level
/// boundary.
///
/// **Degenerate input:** NaN and negatives give 0; values above 1 (and `+∞`) give 255.
///
/// ```
/// use glam::Vec3;
/// let mid = phong::srgb_decode(128.0 / 255.0);
/// assert_eq!(phong::linear_to_srgb8(Vec3::new(0.0, 1.0, mid)), [0, 255, 128]);
/// assert_eq!(phong::linear_to_srgb8(Vec3::new(f32::NAN, -1.0, 2.0)), [0, 0, 255]);
/// ```
#[must_use]
#[inline]
pub fn linear_to_srgb8(c: Vec3) -> [u8; 3] {
    [srgb8::level(c.x), srgb8::level(c.y), srgb8::level(c.z)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_is_continuous_at_the_knee() {
        let k = 0.003_130_8f32;
        let below = 12.92 * k;
        let above = 1.055 * (k as f64).powf(1.0 / 2.4) - 0.055;
        assert!((below as f64 - above).abs() < 1e-6, "{below} vs {above}");
    }

    #[test]
    fn decode_inverts_encode_on_all_8bit_levels() {
        for i in 0..=255u8 {
            let y = i as f32 / 255.0;
            assert_eq!(quantize_u8(srgb_encode(srgb_decode(y))), i);
        }
    }
}
