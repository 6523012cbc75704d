//! 8-bit sRGB encoding in the kernel's lanes: each channel's level from the sRGB curve evaluated
//! by the kernel's own polynomial power, with the rare lanes that fall within a hair of a level
//! boundary left to the exact table encoder ([`linear_to_srgb8`](crate::linear_to_srgb8)), so
//! the levels are that encoder's, bit for bit, without a table lookup per channel.
//!
//! ```text
//! t = 255 · 12.92·x                        x ≤ 0.0031308
//! t = 255 · (1.055·x^(1/2.4) − 0.055)      0.0031308 < x < 1     (x^(1/2.4) by Poly7)
//! level = round(t),  trusted where |t − round(t)| < ½ − MARGIN
//! ```
//!
//! The exact level is `⌊255·srgb(x) + ½⌋`, the nearest whole number to `255·srgb(x)`: the lane's
//! `t` differs from `255·srgb(x)` by at most [`T_ERROR`] levels, so wherever `t` is further than
//! that from a half-level, its nearest whole number is the exact level.

use super::kernel::{exp2, log2};
use super::simd::Simd;
use crate::pow::{EXP2_5, LOG2_7};

/// Where the sRGB curve's linear segment ends (IEC 61966-2-1; the OpenGL 2.1 specification's
/// `GL_EXT_texture_sRGB` conversion uses the same knee).
const KNEE: f32 = 0.003_130_8;

/// The largest difference between a lane's `t` and the exact `255·srgb(x)`, in levels, over every
/// `f32` in `[0, 1]` at every level, rounded up: measured 8.0·10⁻⁵ without fused multiply-adds
/// (portable, SSE2) and 8.3·10⁻⁵ with them (AVX2, AVX-512), near `x = 1`, where `t ≈ 255` and
/// one ulp of `x^(1/2.4)` is 1.6·10⁻⁵ levels. The `lane_levels_error` test redoes it on every
/// 127th `f32` and around every level boundary; `every_f32_below_one` (ignored: a billion values
/// per level) on every `f32`.
pub(crate) const T_ERROR: f32 = 8.5e-5;

/// A lane is trusted where its `t` is further than `½ − MARGIN` from the nearest whole number.
/// `MARGIN > T_ERROR` is what makes a trusted level exact (the exact value is then on the same
/// side of the half-level); twice it leaves room for values between the tested ones. About
/// `2·MARGIN ≈ 3.4·10⁻⁴` of the lanes whose values spread over the levels go to the table.
const MARGIN: f32 = 2.0 * T_ERROR;

/// `2²³`: adding it to a value in `[0, 2²³)` rounds the value to a whole number (to nearest, ties
/// to even) and leaves that number in the low mantissa bits.
const ROUND: f32 = 8_388_608.0;

/// Each lane's 8-bit sRGB level as a whole `f32` in `[0, 255]` (NaN and negatives give 0, values
/// from 1 up give 255), and the lanes whose level the table must decide (see the module docs).
#[inline(always)]
pub(crate) fn levels<S: Simd>(s: S, x: S::V) -> (S::V, S::M) {
    let t = scaled(s, x);
    let level = s.sub(s.add(t, s.splat(ROUND)), s.splat(ROUND));
    let off = s.sub(t, level);
    let far = s.splat(0.5 - MARGIN);
    let near = s.ge(s.max(off, s.sub(s.splat(0.0), off)), far);
    (s.min(level, s.splat(255.0)), near)
}

/// `t`, `255·srgb(x)` as the lanes evaluate it (module docs), with `x` first clamped to `[0, 1]`
/// (NaN to 0).
#[inline(always)]
fn scaled<S: Simd>(s: S, x: S::V) -> S::V {
    // NaN and negatives to 0 (`max` returns its second operand for NaN), then at most 1.
    let x = s.min(s.max(x, s.splat(0.0)), s.splat(1.0));
    let linear = s.mul(x, s.splat(12.92 * 255.0));
    // `x^(1/2.4)` by Poly7's polynomials, for `x` in `[KNEE, 1]`: no subnormal, and the
    // exponent `log2(x)/2.4` is in `[−3.5, 0]`.
    let log = log2::<S, _, true>(s, s.max(x, s.splat(KNEE)), &LOG2_7);
    let root = exp2::<S, _, true>(s, s.mul(log, s.splat(1.0 / 2.4)), &EXP2_5);
    let curve = s.mul_sub(root, s.splat(1.055 * 255.0), s.splat(0.055 * 255.0));
    s.select(s.le(x, s.splat(KNEE)), linear, curve)
}

/// The 32-bit words `lo + 2⁸·mid + 2¹⁶·hi + top` from three lanes of whole levels in `[0, 255]`:
/// the float sums are exact, and their bits hold the whole numbers (`2²³ + a` for `a < 2²³`;
/// `2²⁴ + b` for even `b < 2²⁴`, whose bits hold `b/2`).
#[inline(always)]
pub(crate) fn pack<S: Simd>(s: S, lo: S::V, mid: S::V, hi: S::V, top: u32) -> S::I {
    let low = s.sub_i(
        s.to_bits(s.add(s.mul_add(mid, s.splat(256.0), lo), s.splat(ROUND))),
        s.splat_i(0x4b00_0000),
    );
    let half_high = s.sub_i(
        s.to_bits(s.mul_add(hi, s.splat(65_536.0), s.splat(2.0 * ROUND))),
        s.splat_i(0x4b80_0000),
    );
    s.add_i(
        s.add_i(low, s.add_i(half_high, half_high)),
        s.splat_i(top as i32),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::kernel::{Lanes, W};
    use crate::batch::simd::portable::Portable;

    /// `255·srgb(x)` in `f64`, the formula of IEC 61966-2-1.
    fn exact(x: f32) -> f64 {
        let x = f64::from(x);
        255.0
            * if x <= f64::from(KNEE) {
                12.92 * x
            } else {
                1.055 * x.powf(1.0 / 2.4) - 0.055
            }
    }

    /// The largest `|t − 255·srgb(x)|` at level `s` over the `f32`s in `[0, 1]` with bit patterns
    /// `0, step, 2·step, …`, and 64 `f32`s either side of the knee and of every level boundary.
    fn worst<S: Simd>(s: S, step: u32) -> f64 {
        let mut worst = 0.0f64;
        let mut run = |xs: &mut dyn Iterator<Item = f32>| {
            let mut lanes: Lanes = [0.0; W];
            let mut filled = 0;
            loop {
                let next = xs.next();
                if let Some(x) = next {
                    lanes[filled] = x;
                    filled += 1;
                }
                if filled == W || (next.is_none() && filled > 0) {
                    let t = s.store(scaled(s, s.load(&lanes)));
                    for (j, &x) in lanes[..filled].iter().enumerate() {
                        worst = worst.max((f64::from(t[j]) - exact(x)).abs());
                    }
                    filled = 0;
                }
                if next.is_none() {
                    break;
                }
            }
        };
        run(&mut (0..=1.0f32.to_bits())
            .step_by(step as usize)
            .map(f32::from_bits));
        let boundaries = (1..=255u32).map(|k| {
            let target = (f64::from(k) - 0.5) / 255.0;
            (if target <= 12.92 * f64::from(KNEE) {
                target / 12.92
            } else {
                ((target + 0.055) / 1.055).powf(2.4)
            }) as f32
        });
        for x in boundaries.chain([KNEE]) {
            let b = x.to_bits();
            run(&mut (b - 64..b + 64).map(f32::from_bits));
        }
        worst
    }

    fn each_level(step: u32, check: &mut dyn FnMut(&str, f64)) {
        check("portable", worst(Portable, step));
        #[cfg(target_arch = "x86_64")]
        {
            use crate::batch::simd::{avx2::Avx2, avx512::Avx512, sse2::Sse2};
            check("sse2", worst(Sse2, step));
            if let Some(t) = Avx2::new() {
                check("avx2", worst(t, step));
            }
            if let Some(t) = Avx512::new() {
                check("avx512", worst(t, step));
            }
        }
        #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
        check("neon", worst(crate::batch::simd::neon::Neon, step));
    }

    /// The stated error holds at every level on every 127th `f32` in `[0, 1]` (about 8 million)
    /// and around every level boundary.
    #[test]
    fn lane_levels_error() {
        each_level(127, &mut |name, w| {
            assert!(w <= f64::from(T_ERROR), "{name}: {w:e} levels");
        });
    }

    /// [`lane_levels_error`] on every `f32` in `[0, 1]` (about a minute per level in release:
    /// `cargo test --release --lib every_f32_below_one -- --ignored`).
    #[test]
    #[ignore = "a billion values per level"]
    fn every_f32_below_one() {
        each_level(1, &mut |name, w| {
            std::eprintln!("{name}: {w:e} levels");
            assert!(w <= f64::from(T_ERROR), "{name}: {w:e} levels");
        });
    }

    /// The levels are the table encoder's wherever the lanes trust them, and the words hold them
    /// in the right bytes.
    #[test]
    fn trusted_levels_are_exact_and_packed() {
        let mut xs: Vec<f32> = (0..=1.0f32.to_bits())
            .step_by(4099)
            .map(f32::from_bits)
            .collect();
        xs.extend([f32::NAN, -1.0, -0.0, 1.0, 1.5, f32::MAX, f32::INFINITY]);
        let s = Portable;
        let mut sent = 0;
        for chunk in xs.chunks(W) {
            let mut lanes: Lanes = [0.0; W];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let (level, near) = levels(s, s.load(&lanes));
            let (level, near) = (s.store(level), s.bits(near));
            let words = s.store(s.bits_to_f32(pack(s, level, s.splat(7.0), level, 0xff00_0000)));
            for (j, &x) in chunk.iter().enumerate() {
                let want = crate::colour::srgb8::level(x);
                if near & 1 << j == 0 {
                    assert_eq!(level[j], f32::from(want), "x = {x:e}");
                    assert_eq!(words[j].to_bits().to_le_bytes(), [want, 7, want, 255]);
                } else {
                    sent += 1;
                }
            }
        }
        // The table's share: about 2·MARGIN ≈ 3.4·10⁻⁴ of lanes whose `t` spreads evenly over
        // the fractions; a third of it is allowed for how unevenly this sample spreads.
        assert!(sent * 1000 < xs.len(), "{sent} of {} lanes sent", xs.len());
    }
}
