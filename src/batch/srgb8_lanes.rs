//! 8-bit sRGB encoding in the kernel's lanes, with [`linear_to_srgb8`](crate::linear_to_srgb8)'s
//! levels bit for bit: `⌊255·srgb(x) + ½⌋` with the exact `srgb`.
//!
//! Two ways, one result:
//!
//! - **The bucket table**, [`linear_to_srgb8`](crate::linear_to_srgb8)'s own, one entry per
//!   lane, loaded lane by lane (SSE2, NEON, portable):
//!
//!   ```text
//!   bits  = bits(min(max(x, LOWEST), 1))           NaN and everything below LOWEST: level 0
//!   entry = BUCKET[(bits >> 16) − (LOWEST >> 16)]  = k << 16 | c
//!   level = k + (bits & 0xffff > c)
//!   ```
//!
//! - **Arithmetic, checked against the rounding boundary** where the level keeps a table of
//!   sixteen in registers ([`Simd::LOOKUP16_IN_REGISTERS`]: AVX-512's `vpermps`, AVX2's two
//!   `vpermps` and a blend). With `x = 2^e·m`, `m ∈ [1, 2)`, the power segment
//!   `255·(1.055·x^(1/2.4) − 0.055)` is `255·1.055·2^(5e/12) · m^(5/12) − 255·0.055`: the first
//!   factor from a table of the 14 binades in `[2⁻¹³, 1]`, indexed by the biased exponent
//!   modulo 16, the second a polynomial of degree 5 in `m` (Chebyshev interpolation, relative
//!   error 1.9·10⁻⁶, by Horner's rule). Call that `w`; it is within [`ERROR`] of `255·srgb(x)`
//!   (checked at every `f32` of the range).
//!
//!   `w` is formed in fixed point, `u = 2¹⁶·w + 2¹⁵ + GUARD`: every constant of the last fused
//!   operation (the binade's factor, the linear segment's slope) is scaled by `2¹⁶` exactly,
//!   and that operation adds the rounding's half and a guard of [`GUARD`] units. Truncated to
//!   the integer `b`, bits 16–23 of `b` are the level, unless `b`'s low 16 bits are below
//!   `2·GUARD` (one `vptestnmd`): then `w` lies within [`MARGIN`] of a half-integer, the rounding
//!   boundary, the exact level may be either neighbour, and the channel's lanes take the table
//!   (its gather instruction, one per half at AVX2). Every other lane's level is exact, because
//!   the true `255·srgb(x)` lies on the same side of the boundary. [`pack`] takes the levels
//!   from bits 16–23 as it places them (two `vpternlogd` and two shifts at AVX-512).
//!
//!   About one channel's vector in thirty has such a lane (`2·MARGIN` per lane); one branch
//!   tests the three channels of a chunk. Per channel the arithmetic is 14 operations at
//!   AVX-512: the clamp (1 for the shaded totals, which are never negative), `m` and the
//!   exponent (2), the polynomial (5), the binade's factor, the linear segment and the select
//!   between them (4), the truncation and the test (2); the destructive fused operations add
//!   copies of their constants (register moves). Rounded in floating point instead
//!   (`vrndscaleps`, a subtraction, the absolute value and a compare beside the conversion),
//!   the rounding and its test took 5 operations a channel where these take 2; the packing
//!   takes 5 either way. On the development machine (an Intel Xeon, family 6 model 207;
//!   interleaved criterion runs, 2026-12-07) `gbuffer_rgba8` ran faster at AVX-512 in six
//!   pairs of eight, by about 3% in the quieter runs. On the Zen 4 host of earlier sessions,
//!   the first arithmetic form took that row from 229 to 261 M points/s at AVX-512, and at AVX2,
//!   where the gather had been 5–8% faster than an earlier arithmetic form, from 178 to 186
//!   (DESIGN.md, "What did not work out"). The gather runs for the few declined channels only,
//!   which also spares the CPUs whose microcode slows it (Intel's mitigation of Downfall).

use super::simd::Simd;
use crate::colour::srgb8::{BUCKET, LOWEST, SHIFT};

/// Each channel's 8-bit sRGB level, `⌊255·srgb(x) + ½⌋` with the exact `srgb`, in `[0, 255]`: NaN
/// and negatives give 0, values from 1 up give 255.
///
/// Each level sits in its lane's word as [`AT16`] says: where the level keeps a table of sixteen
/// in a register, in bits 16–23 (bits 24–31 clear, bits 0–15 unspecified), and elsewhere in bits
/// 0–7 (the rest clear). [`pack`] reads either (and the tests' `level_of`).
///
/// Where the level keeps a table of sixteen in a register, the three channels take the
/// arithmetic, with one branch for all three on whether a lane of any channel lies too near a
/// rounding boundary; only a channel with such a lane is redone by the table.
///
/// `NONNEG`: the caller's lanes are all `≥ 0` or `+∞` (never NaN): the shaded totals are. The
/// arithmetic then clamps them at 1 only, since below `LOWEST` its linear segment already gives
/// level 0 (a `max` fewer per channel); the table, which needs the full clamp, gets it where it
/// runs.
#[inline(always)]
pub(crate) fn levels3<S: Simd, const NONNEG: bool>(s: S, [r, g, b]: [S::V; 3]) -> [S::I; 3] {
    if S::LOOKUP16_IN_REGISTERS {
        let (ar, ag, ab) = (
            for_arithmetic::<S, NONNEG>(s, r),
            for_arithmetic::<S, NONNEG>(s, g),
            for_arithmetic::<S, NONNEG>(s, b),
        );
        let ((lr, nr), (lg, ng), (lb, nb)) = (
            checked_levels(s, ar),
            checked_levels(s, ag),
            checked_levels(s, ab),
        );
        let (near_r, near_g, near_b) = (s.bits(nr), s.bits(ng), s.bits(nb));
        if near_r | near_g | near_b == 0 {
            return [lr, lg, lb];
        }
        // Written out, not a closure: a closure would not inherit the level's target features.
        // The table's levels moved to bits 16–23, where the arithmetic's are.
        return [
            if near_r == 0 {
                lr
            } else {
                s.shl16(table_levels(s, clamped(s, r)))
            },
            if near_g == 0 {
                lg
            } else {
                s.shl16(table_levels(s, clamped(s, g)))
            },
            if near_b == 0 {
                lb
            } else {
                s.shl16(table_levels(s, clamped(s, b)))
            },
        ];
    }
    let (r, g, b) = (clamped(s, r), clamped(s, g), clamped(s, b));
    [table_levels(s, r), table_levels(s, g), table_levels(s, b)]
}

/// Whether [`levels3`] at level `S` gives each level in bits 16–23 of its word (the arithmetic's
/// fixed point), not in bits 0–7 (the table's).
pub(crate) const fn at16<S: Simd>() -> bool {
    S::LOOKUP16_IN_REGISTERS
}

/// A word of [`levels3`] as the bare level, in bits 0–7.
#[cfg(test)]
fn level_of<S: Simd>(word: u32) -> u32 {
    if at16::<S>() { word >> 16 } else { word }
}

/// `x` clamped for [`checked_levels`]: [`clamped`], or where every lane is `≥ 0` or `+∞`
/// (`NONNEG`), `min(x, 1)` alone: `fixed`'s linear segment covers `[0, LOWEST)` too (its
/// binade table is read there, but not selected).
#[inline(always)]
fn for_arithmetic<S: Simd, const NONNEG: bool>(s: S, x: S::V) -> S::V {
    if NONNEG {
        s.min(x, s.splat(1.0))
    } else {
        clamped(s, x)
    }
}

/// `min(max(x, LOWEST), 1)`: every lane in the tables' range, NaN at `LOWEST` (level 0).
#[inline(always)]
fn clamped<S: Simd>(s: S, x: S::V) -> S::V {
    // `max` returns its second operand for NaN.
    s.min(s.max(x, s.splat(f32::from_bits(LOWEST))), s.splat(1.0))
}

/// The levels of `x ∈ [LOWEST, 1]` by the arithmetic, in bits 16–23 of each word, and the lanes
/// where `255·srgb(x)` may lie within [`MARGIN`] of a rounding boundary, whose levels are not to
/// be kept (module docs).
#[inline(always)]
fn checked_levels<S: Simd>(s: S, x: S::V) -> (S::I, S::M) {
    // `fixed` is in `(0, 2²⁴)`: truncation is its floor. With `v = 2¹⁶·255·srgb(x) + 2¹⁵`, whose
    // floor over `2¹⁶` is the level, `fixed` is `v + GUARD` within `2¹⁶·ERROR < GUARD`; so where
    // `b`'s low 16 bits are at least `2·GUARD`, `v` lies in the same block of `2¹⁶` as `b`.
    let b = s.to_i(fixed(s, x));
    (b, s.none_of(b, s.splat_i(NEAR)))
}

/// `2¹⁶·255·srgb(x) + 2¹⁵ + GUARD` for `x ∈ [LOWEST, 1]`, within `2¹⁶·`[`ERROR`]: the linear
/// segment `255·12.92·x` up to 0.0031308, then the power segment by binade (module docs), each
/// in fixed point by one fused operation at the end.
#[inline(always)]
fn fixed<S: Simd>(s: S, x: S::V) -> S::V {
    let bits = s.to_bits(x);
    // The biased exponent: 114 at LOWEST = 2⁻¹³, 127 at 1; `lookup16` reads it modulo 16.
    let exponent = s.sar23(bits);
    // `m` has `x`'s mantissa and the exponent of 1.
    let m = s.bits_to_f32(s.add_i(
        s.and_i(bits, s.splat_i(0x007f_ffff)),
        s.splat_i(0x3f80_0000),
    ));
    // Horner's rule: five operations, where Estrin's scheme takes seven for a shorter chain;
    // the chunk loop is bound by the operations' count, not their latency.
    let mut root = s.splat(ROOT[5]);
    for &c in ROOT[..5].iter().rev() {
        root = s.mul_add(root, m, s.splat(c));
    }
    let curve = s.mul_sub(
        s.lookup16(&SCALE_FIXED, exponent),
        root,
        s.splat(CURVE_OFFSET),
    );
    let line = s.mul_add(x, s.splat(LINE_FIXED), s.splat(OFFSET));
    s.select(s.le(x, s.splat(0.003_130_8)), line, curve)
}

/// `m^(5/12)` for `m ∈ [1, 2)`, coefficients of `m⁰ … m⁵`: Chebyshev interpolation of degree 5
/// (relative error 1.9·10⁻⁶).
const ROOT: [f32; 6] = [
    0.378_249_17,
    0.946_032_17,
    -0.482_285_2,
    0.202_089_76,
    -0.049_227_59,
    0.005_143_488_3,
];

/// `255·1.055·2^(5e/12)` for the binade `x ∈ [2^e, 2^(e+1))`, `e ∈ [−13, 0]`, at the index of
/// `x`'s biased exponent modulo 16 (`e + 127 − 112`: 2 to 15), rounded from the exact value.
const SCALE: [f32; 16] = [
    0.0, 0.0, 6.298_157, 8.407_031, 11.222_04, 14.979_627, 19.995_403, 26.690_66, 35.627_758,
    47.557_35, 63.481_445, 84.737_564, 113.111_08, 150.985_18, 201.541_03, 269.025,
];

/// The fixed point's unit: `2¹⁶` to a level.
const ONE: f32 = 65536.0;

/// [`SCALE`] in fixed point (each entry times `2¹⁶`, exactly).
const SCALE_FIXED: [f32; 16] = {
    let mut t = SCALE;
    let mut i = 0;
    while i < t.len() {
        t[i] *= ONE;
        i += 1;
    }
    t
};

/// The guard added to the fixed point, in its units (`2⁻¹⁶` of a level): [`MARGIN`] in levels.
const GUARD: i32 = 64;

/// The rounding's half and the guard, added to `2¹⁶·w`.
const OFFSET: f32 = ONE / 2.0 + GUARD as f32;

/// `2¹⁶·255·0.055 − OFFSET`, subtracted from the power segment (exact in `f32`).
const CURVE_OFFSET: f32 = (255.0 * 0.055) * ONE - OFFSET;

/// `2¹⁶·255·12.92`, the linear segment's slope in fixed point.
const LINE_FIXED: f32 = (255.0 * 12.92) * ONE;

/// The bits of a truncated fixed-point word that are all 0 exactly where its low 16 bits are below
/// `2·GUARD`: bits 7–15.
const NEAR: i32 = 0xffff & !(2 * GUARD - 1);

/// A bound on `|w − 255·srgb(x)|`, in levels, with `w = (fixed(x) − 2¹⁵ − GUARD)/2¹⁶`, at every
/// level's arithmetic (`exhaustive_error` measures it over every `f32` in `[LOWEST, 1]`).
pub(crate) const ERROR: f32 = 9e-4;

/// How close to a half-integer `255·srgb(x)` may lie and still be kept: `GUARD/2¹⁶` levels
/// (9.8·10⁻⁴), more than [`ERROR`]. A kept lane's `fixed` lies at least `GUARD` from the
/// boundary, so the exact value, within `2¹⁶·ERROR` of it, lies on the same side (no exact value
/// lies on a boundary: `THRESHOLDS` in `srgb8.rs`).
pub(crate) const MARGIN: f32 = GUARD as f32 / ONE;

const _: () = assert!(ERROR < MARGIN && NEAR == 0xff80);

/// The bucket table's level per lane (module docs).
#[inline(always)]
fn table_levels<S: Simd>(s: S, x: S::V) -> S::I {
    let bits = s.to_bits(x);
    let index = s.sub_i(s.srl16(bits), s.splat_i((LOWEST >> SHIFT) as i32));
    let entry = s.gather(&BUCKET, index);
    let low = s.splat_i(0xffff);
    // `gt_i` is −1 where the lane is past the bucket's boundary.
    s.sub_i(
        s.srl16(entry),
        s.gt_i(s.and_i(bits, low), s.and_i(entry, low)),
    )
}

/// The 32-bit words `lo | mid << 8 | hi << 16 | top` from three lanes of [`levels3`]'s words
/// (each level where [`at16`] puts it); `top`'s low 24 bits are 0.
#[inline(always)]
pub(crate) fn pack<S: Simd>(s: S, lo: S::I, mid: S::I, hi: S::I, top: u32) -> S::I {
    let top = s.splat_i(top as i32);
    if at16::<S>() {
        // Bits 16–23 of each word, moved to bits 0–7, 8–15 and kept at 16–23; at AVX-512 the
        // masks and `or`s become two `vpternlogd`.
        let lo = s.srl16(lo);
        let mid = s.shl8(s.srl16(mid));
        let hi = s.and_i(hi, s.splat_i(0x00ff_0000));
        return s.or_i(s.or_i(lo, mid), s.or_i(hi, top));
    }
    s.add_i(s.add_i(lo, s.shl8(mid)), s.add_i(s.shl16(hi), top))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::kernel::{Lanes, W};
    use crate::batch::simd::portable::Portable;

    /// Runs `check` at every level this CPU has.
    macro_rules! at_every_level {
        ($check:ident, $($arg:expr),*) => {{
            let mut got = vec![("portable", $check(Portable, $($arg),*))];
            #[cfg(target_arch = "x86_64")]
            {
                use crate::batch::simd::{avx2::Avx2, avx512::Avx512, sse2::Sse2};
                got.push(("sse2", $check(Sse2, $($arg),*)));
                if let Some(t) = Avx2::new() {
                    got.push(("avx2", $check(t, $($arg),*)));
                }
                if let Some(t) = Avx512::new() {
                    got.push(("avx512", $check(t, $($arg),*)));
                }
            }
            #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
            got.push(("neon", $check(crate::batch::simd::neon::Neon, $($arg),*)));
            got
        }};
    }

    /// Every level's lanes against the scalar encoder on `xs`, and the packed words' bytes.
    fn agrees<S: Simd, const NONNEG: bool>(s: S, xs: &[f32]) {
        let name = core::any::type_name::<S>();
        for chunk in xs.chunks(W) {
            let mut lanes: Lanes = [0.0; W];
            lanes[..chunk.len()].copy_from_slice(chunk);
            // The chunk as red, and as blue with its lanes rotated by one; green the linear
            // values of the levels 0, 16, …, 240, whose arithmetic is never near a boundary, so a
            // channel redone by the table sits beside one kept from the arithmetic.
            let mut rotated = lanes;
            rotated.rotate_left(1);
            let mut far: Lanes = [0.0; W];
            for (j, f) in far.iter_mut().enumerate() {
                *f = crate::srgb_decode(16.0 * j as f32 / 255.0);
            }
            let [r, g, b] =
                levels3::<S, NONNEG>(s, [s.load(&lanes), s.load(&far), s.load(&rotated)]);
            let words = s.store(s.bits_to_f32(pack(s, r, g, b, 0xff00_0000)));
            let want = |x: f32| crate::colour::srgb8::level(x);
            for (k, (got, from)) in [(r, lanes), (g, far), (b, rotated)].into_iter().enumerate() {
                let got = s.store(s.bits_to_f32(got));
                for j in 0..W {
                    let x = from[j];
                    assert_eq!(
                        level_of::<S>(got[j].to_bits()),
                        u32::from(want(x)),
                        "{name}: x = {x:e}"
                    );
                    assert_eq!(words[j].to_bits().to_le_bytes()[k], want(x), "{name}");
                }
            }
            for word in words {
                assert_eq!(word.to_bits() >> 24, 255, "{name}");
            }
        }
    }

    /// The largest `|w − 255·srgb(x)|` over `xs` (each in `[LOWEST, 1]`) at level `s`, with
    /// `w = (fixed(x) − OFFSET)/2¹⁶` (exact in `f64`).
    fn scaled_error<S: Simd>(s: S, xs: &[f32]) -> f64 {
        let mut worst = 0.0f64;
        for chunk in xs.chunks(W) {
            let mut lanes: Lanes = [1.0; W];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let w = s.store(fixed(s, s.load(&lanes)));
            for (j, &x) in chunk.iter().enumerate() {
                let exact = 255.0 * crate::colour::srgb8::srgb64(f64::from(x));
                let w = (f64::from(w[j]) - f64::from(OFFSET)) / f64::from(ONE);
                worst = worst.max((w - exact).abs());
            }
        }
        worst
    }

    /// Every `checked_levels` answer against the scalar encoder on `xs`; returns how many chunks
    /// of `W` it declined.
    fn checked_agrees<S: Simd>(s: S, xs: &[f32]) -> usize {
        let name = core::any::type_name::<S>();
        let mut declined = 0;
        for chunk in xs.chunks(W) {
            let mut lanes: Lanes = [1.0; W];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let (level, near) = checked_levels(s, s.load(&lanes));
            let (level, near) = (s.store(s.bits_to_f32(level)), s.bits(near));
            declined += usize::from(near != 0);
            for (j, &x) in chunk.iter().enumerate() {
                if near & (1 << j) == 0 {
                    let want = crate::colour::srgb8::level(x);
                    assert_eq!(
                        level[j].to_bits() >> 16,
                        u32::from(want),
                        "{name}: x = {x:e}"
                    );
                }
            }
        }
        declined
    }

    /// Every 1021st `f32` of `[LOWEST, 1]`, and 64 either side of each binade's start and of the
    /// segments' join at 0.0031308: where the table, the polynomial's ends and the select change.
    fn scaled_sample() -> Vec<f32> {
        let mut xs: Vec<u32> = (LOWEST..=1.0f32.to_bits()).step_by(1021).collect();
        for start in (LOWEST..=1.0f32.to_bits()).step_by(1 << 23) {
            xs.extend(start.saturating_sub(64).max(LOWEST)..(start + 64).min(1.0f32.to_bits()));
        }
        let join = 0.003_130_8f32.to_bits();
        xs.extend(join - 64..join + 64);
        xs.into_iter().map(f32::from_bits).collect()
    }

    /// The arithmetic's error bound, which makes its kept levels exact, on a sample at every
    /// level (every `f32`: `exhaustive_error`).
    #[test]
    fn scaled_is_within_its_error_bound() {
        let xs = scaled_sample();
        for (name, worst) in at_every_level!(scaled_error, &xs) {
            assert!(
                worst <= f64::from(ERROR),
                "{name}: error {worst:e} > {ERROR:e}"
            );
        }
    }

    /// Every `f32` of `[LOWEST, 1]` at every level (about 10⁸ values: run it in release,
    /// `cargo test --release --lib exhaustive_error -- --ignored --nocapture`).
    #[test]
    #[ignore = "10^8 values: minutes at opt-level 0"]
    fn exhaustive_error() {
        let xs: Vec<f32> = (LOWEST..=1.0f32.to_bits()).map(f32::from_bits).collect();
        for (name, worst) in at_every_level!(scaled_error, &xs) {
            println!("{name}: max |w − 255·srgb| = {worst:e}");
            assert!(
                worst <= f64::from(ERROR),
                "{name}: error {worst:e} > {ERROR:e}"
            );
        }
    }

    /// The arithmetic's levels, where it keeps them, are the table's, at every level (not
    /// only where `levels3` uses it); on colours uniform in `[0, 1]` it declines about one chunk
    /// in thirty (`1 − (1 − 2·MARGIN)^16` = 3.2%), and the bound allows twice that.
    #[test]
    fn checked_levels_are_exact_and_rarely_declined() {
        let mut rng = 0x9e37_79b9_7f4a_7c15u64;
        let uniform: Vec<f32> = (0..1 << 16)
            .map(|_| {
                rng ^= rng << 13;
                rng ^= rng >> 7;
                rng ^= rng << 17;
                ((rng >> 40) as f32 / (1u64 << 24) as f32).max(f32::from_bits(LOWEST))
            })
            .collect();
        let chunks = uniform.len() / W;
        for (name, declined) in at_every_level!(checked_agrees, &uniform) {
            let rate = declined as f64 / chunks as f64;
            assert!(
                rate < 0.064,
                "{name}: {declined} of {chunks} chunks declined"
            );
        }
        // Near the level boundaries, where it declines most, what it keeps is still exact.
        let near: Vec<f32> = boundary_sample()
            .into_iter()
            .filter(|x| (f32::from_bits(LOWEST)..=1.0).contains(x))
            .collect();
        at_every_level!(checked_agrees, &near);
    }

    /// Every 4099th `f32` from 0 to past 1, either side of every level boundary, and the values
    /// outside `[0, 1]`.
    fn boundary_sample() -> Vec<f32> {
        let mut xs: Vec<f32> = (0..=1.5f32.to_bits())
            .step_by(4099)
            .map(f32::from_bits)
            .collect();
        for k in 1..=255u8 {
            // The smallest `f32` at level k, found by bisection on the scalar encoder.
            let (mut lo, mut hi) = (0u32, 1.0f32.to_bits());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if crate::colour::srgb8::level(f32::from_bits(mid)) >= k {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            xs.extend((lo - 3..lo + 3).map(f32::from_bits));
        }
        xs.extend([
            f32::NAN,
            -f32::NAN,
            -1.0,
            -0.0,
            f32::MIN_POSITIVE / 4.0,
            f32::MIN,
            1.0,
            1.5,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ]);
        xs
    }

    fn agrees_any<S: Simd>(s: S, xs: &[f32]) {
        agrees::<S, false>(s, xs);
    }

    fn agrees_nonneg<S: Simd>(s: S, xs: &[f32]) {
        agrees::<S, true>(s, xs);
    }

    /// Every level's lanes against the scalar encoder on [`boundary_sample`].
    #[test]
    fn lanes_are_the_table_encoders_levels() {
        at_every_level!(agrees_any, &boundary_sample());
    }

    /// The same for lanes `≥ 0` or `+∞` (the shaded totals), with the arithmetic's shorter
    /// clamp: zero, negative zero, subnormals and the values below `LOWEST` included.
    #[test]
    fn nonnegative_lanes_are_the_table_encoders_levels() {
        let mut xs: Vec<f32> = boundary_sample()
            .into_iter()
            .filter(|&x| x >= 0.0)
            .collect();
        let lowest = f32::from_bits(LOWEST);
        xs.extend((0..=4096).map(|k| lowest * k as f32 / 4096.0));
        xs.extend((1..64).map(f32::from_bits));
        at_every_level!(agrees_nonneg, &xs);
    }
}
