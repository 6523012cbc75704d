//! 8-bit sRGB encoding by a table of level thresholds: the level of the exact sRGB value, with
//! no `powf` and the same result on every platform.

use crate::math;

/// `THRESHOLDS[k]` for `k ≥ 1`: the bits of the smallest `f32` whose exact sRGB value (the
/// piecewise formula of [`srgb_encode`](crate::srgb_encode), evaluated without rounding) is at
/// least `(k − ½)/255`; from it upwards the nearest 8-bit level, ties up, is `k` or more.
/// `THRESHOLDS[0]` is 0 and never read, and `THRESHOLDS[256]` is `u32::MAX`, above every `f32`, so
/// a search may look one past level 255. The positive `f32` order is the order of their bits.
///
/// Found by bisection over the `f32` bit patterns with the formula in `f64`; every level
/// boundary lies at least `8.8·10⁻¹²` from both neighbouring `f32` values' sRGB values, far above
/// `f64`'s rounding, so the table does not depend on how `f64` evaluates the power. The
/// `thresholds_are_the_exact_level_boundaries` test redoes the search.
const THRESHOLDS: [u32; 257] = [
    0x00000000,
    0x391f22b4,
    0x39eeb40e,
    0x3a46eb61,
    0x3a8b3e5e,
    0x3ab3070b,
    0x3adacfb8,
    0x3b014c33,
    0x3b153089,
    0x3b2914df,
    0x3b3cf936,
    0x3b50f2d1,
    0x3b65fb9b,
    0x3b7c3403,
    0x3b89d060,
    0x3b962333,
    0x3ba314bd,
    0x3bb0a731,
    0x3bbedcb7,
    0x3bcdb76d,
    0x3bdd3967,
    0x3bed64af,
    0x3bfe3b46,
    0x3c07df91,
    0x3c10f91b,
    0x3c1a6b32,
    0x3c2436c8,
    0x3c2e5cc7,
    0x3c38de1a,
    0x3c43bba4,
    0x3c4ef648,
    0x3c5a8ee4,
    0x3c668654,
    0x3c72dd71,
    0x3c7f950f,
    0x3c865702,
    0x3c8d148f,
    0x3c940396,
    0x3c9b247c,
    0x3ca277a6,
    0x3ca9fd78,
    0x3cb1b653,
    0x3cb9a298,
    0x3cc1c2a9,
    0x3cca16e3,
    0x3cd29fa4,
    0x3cdb5d4b,
    0x3ce45032,
    0x3ced78b5,
    0x3cf6d72e,
    0x3d0035fc,
    0x3d051bb4,
    0x3d0a1cec,
    0x3d0f39d0,
    0x3d14728a,
    0x3d19c745,
    0x3d1f382c,
    0x3d24c567,
    0x3d2a6f22,
    0x3d303584,
    0x3d3618b7,
    0x3d3c18e4,
    0x3d423632,
    0x3d4870ca,
    0x3d4ec8d2,
    0x3d553e73,
    0x3d5bd1d3,
    0x3d628318,
    0x3d69526a,
    0x3d703fee,
    0x3d774bca,
    0x3d7e7624,
    0x3d82df90,
    0x3d869372,
    0x3d8a56cb,
    0x3d8e29ab,
    0x3d920c27,
    0x3d95fe4f,
    0x3d9a0035,
    0x3d9e11ec,
    0x3da23384,
    0x3da66510,
    0x3daaa6a0,
    0x3daef847,
    0x3db35a15,
    0x3db7cc1b,
    0x3dbc4e6b,
    0x3dc0e114,
    0x3dc58429,
    0x3dca37b9,
    0x3dcefbd6,
    0x3dd3d08f,
    0x3dd8b5f5,
    0x3dddac19,
    0x3de2b30a,
    0x3de7cad9,
    0x3decf395,
    0x3df22d50,
    0x3df77817,
    0x3dfcd3fc,
    0x3e012087,
    0x3e03dfae,
    0x3e06a77b,
    0x3e0977f6,
    0x3e0c5126,
    0x3e0f3314,
    0x3e121dc5,
    0x3e151143,
    0x3e180d95,
    0x3e1b12c2,
    0x3e1e20d1,
    0x3e2137cb,
    0x3e2457b6,
    0x3e278099,
    0x3e2ab27d,
    0x3e2ded68,
    0x3e313161,
    0x3e347e70,
    0x3e37d49c,
    0x3e3b33ec,
    0x3e3e9c67,
    0x3e420e15,
    0x3e4588fb,
    0x3e490d22,
    0x3e4c9a90,
    0x3e50314c,
    0x3e53d15d,
    0x3e577aca,
    0x3e5b2d9a,
    0x3e5ee9d4,
    0x3e62af7e,
    0x3e667e9f,
    0x3e6a573e,
    0x3e6e3962,
    0x3e722511,
    0x3e761a52,
    0x3e7a192c,
    0x3e7e21a5,
    0x3e8119e2,
    0x3e8327c7,
    0x3e853a86,
    0x3e875222,
    0x3e896e9d,
    0x3e8b8ffc,
    0x3e8db641,
    0x3e8fe170,
    0x3e92118b,
    0x3e944696,
    0x3e968095,
    0x3e98bf89,
    0x3e9b0377,
    0x3e9d4c62,
    0x3e9f9a4c,
    0x3ea1ed38,
    0x3ea4452b,
    0x3ea6a226,
    0x3ea9042e,
    0x3eab6b44,
    0x3eadd76d,
    0x3eb048aa,
    0x3eb2bf00,
    0x3eb53a71,
    0x3eb7bb00,
    0x3eba40b1,
    0x3ebccb85,
    0x3ebf5b81,
    0x3ec1f0a7,
    0x3ec48af9,
    0x3ec72a7c,
    0x3ec9cf32,
    0x3ecc791e,
    0x3ecf2842,
    0x3ed1dca2,
    0x3ed49641,
    0x3ed75521,
    0x3eda1946,
    0x3edce2b2,
    0x3edfb168,
    0x3ee2856a,
    0x3ee55ebd,
    0x3ee83d63,
    0x3eeb215d,
    0x3eee0ab1,
    0x3ef0f95f,
    0x3ef3ed6b,
    0x3ef6e6d8,
    0x3ef9e5a8,
    0x3efce9de,
    0x3efff37e,
    0x3f018145,
    0x3f030b82,
    0x3f049877,
    0x3f062827,
    0x3f07ba92,
    0x3f094fb9,
    0x3f0ae79f,
    0x3f0c8244,
    0x3f0e1faa,
    0x3f0fbfd2,
    0x3f1162be,
    0x3f13086e,
    0x3f14b0e4,
    0x3f165c22,
    0x3f180a29,
    0x3f19bafa,
    0x3f1b6e96,
    0x3f1d24ff,
    0x3f1ede36,
    0x3f209a3c,
    0x3f225913,
    0x3f241abc,
    0x3f25df38,
    0x3f27a689,
    0x3f2970af,
    0x3f2b3dad,
    0x3f2d0d83,
    0x3f2ee032,
    0x3f30b5bd,
    0x3f328e24,
    0x3f346968,
    0x3f36478b,
    0x3f38288f,
    0x3f3a0c73,
    0x3f3bf33a,
    0x3f3ddce5,
    0x3f3fc975,
    0x3f41b8eb,
    0x3f43ab48,
    0x3f45a08f,
    0x3f4798bf,
    0x3f4993db,
    0x3f4b91e3,
    0x3f4d92d8,
    0x3f4f96bd,
    0x3f519d92,
    0x3f53a758,
    0x3f55b411,
    0x3f57c3be,
    0x3f59d65f,
    0x3f5bebf7,
    0x3f5e0486,
    0x3f60200e,
    0x3f623e90,
    0x3f64600c,
    0x3f668485,
    0x3f68abfb,
    0x3f6ad670,
    0x3f6d03e5,
    0x3f6f345a,
    0x3f7167d2,
    0x3f739e4d,
    0x3f75d7cc,
    0x3f781451,
    0x3f7a53dd,
    0x3f7c9671,
    0x3f7edc0e,
    u32::MAX,
];

/// `x` falls in bucket `bits(x) >> SHIFT`: its exponent and top seven mantissa bits. (With five,
/// a bucket holds up to three boundaries; with seven at most one, so one comparison decides.)
pub(crate) const SHIFT: u32 = 16;
/// The bits of the smallest `f32` with a bucket of its own: every smaller one (zero, and up to
/// `THRESHOLDS[1]`, about `1.5·10⁻⁴`) is level 0, as this bucket's start is.
pub(crate) const LOWEST: u32 = 0x3900_0000;
/// The bits of 1.0, whose bucket is the last: every `x ≥ 1` is level 255.
const ONE: u32 = 0x3f80_0000;
/// The buckets from `LOWEST`'s to 1.0's.
const BUCKETS: usize = ((ONE - LOWEST) >> SHIFT) as usize + 1;

const _: () = assert!(THRESHOLDS[1] > LOWEST, "level 0 must cover LOWEST's bucket");

/// `BUCKET[b]` for bucket `b` (counted from `LOWEST`'s): `k << 16 | c`, with `k` the level of
/// the bucket's smallest `f32` and `c` the bound its low 16 bits must exceed for the level to be
/// `k + 1`: the next threshold's low bits minus one where that threshold lies inside the bucket,
/// `0xffff` (never exceeded) where it does not. One entry decides a channel: 6660 bytes, which
/// stay in the L1 cache beside a shading loop's data, and one entry per lane is what a gather
/// instruction loads.
pub(crate) const BUCKET: [i32; BUCKETS] = buckets();

const fn buckets() -> [i32; BUCKETS] {
    let mut bucket = [0i32; BUCKETS];
    let (mut b, mut k) = (0, 0);
    while b < BUCKETS {
        let first = LOWEST + ((b as u32) << SHIFT);
        while k < 255 && first >= THRESHOLDS[k + 1] {
            k += 1;
        }
        // `THRESHOLDS[k + 1] > first` (for k = 255 it is `u32::MAX`), so this is at least 1.
        let gap = THRESHOLDS[k + 1] - first;
        let c = if gap <= 0xffff { gap - 1 } else { 0xffff };
        bucket[b] = ((k as u32) << 16 | c) as i32;
        b += 1;
    }
    bucket
}

/// The 8-bit sRGB level of a linear value: `⌊255·srgb(x) + ½⌋` with the exact `srgb`, clamped to
/// `[0, 255]`; NaN and negatives give 0, `+∞` gives 255.
///
/// The level at the start of `x`'s bucket and the position of the one level boundary the bucket
/// may hold, from one table entry, then one comparison, with no branch (the clamp keeps every
/// index in the table). The batch kernel's 8-bit output evaluates the same steps in its lanes.
#[inline]
pub(crate) fn level(x: f32) -> u8 {
    // `max_or` maps NaN to 0; the bits of a non-negative `f32` (`+∞` included) order as it does.
    let bits = math::max_or(x, 0.0).to_bits().clamp(LOWEST, ONE);
    let entry = BUCKET[((bits - LOWEST) >> SHIFT) as usize] as u32;
    ((entry >> 16) + u32::from(bits & 0xffff > entry & 0xffff)) as u8
}

/// The exact sRGB value in `f64`, what the tests measure the encoders against.
#[cfg(test)]
pub(crate) fn srgb64(x: f64) -> f64 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds_are_the_exact_level_boundaries() {
        for (k, &threshold) in THRESHOLDS.iter().enumerate().take(256).skip(1) {
            let target = (k as f64 - 0.5) / 255.0;
            let (mut lo, mut hi) = (0u32, 1.0f32.to_bits() + 1);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if srgb64(f32::from_bits(mid) as f64) >= target {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            assert_eq!(threshold, lo, "level {k}: 0x{lo:08x}");
            // Far from the boundary on both sides, so f64's rounding cannot move it.
            let above = srgb64(f32::from_bits(lo) as f64) - target;
            let below = target - srgb64(f32::from_bits(lo - 1) as f64);
            assert!(
                above > 1e-12 && below > 1e-12,
                "level {k}: {above:e}, {below:e}"
            );
        }
    }

    /// The level at the top of each bucket is at most one above its start: [`level`]'s one
    /// comparison decides every `f32`.
    #[test]
    fn no_bucket_holds_more_boundaries_than_the_search_covers() {
        for (b, &entry) in BUCKET.iter().enumerate() {
            let top = LOWEST + (((b + 1) as u32) << SHIFT) - 1;
            let last = THRESHOLDS[..256].iter().filter(|&&t| t <= top).count() - 1;
            assert!(last - (entry >> 16) as usize <= 1, "bucket {b}");
        }
    }

    /// On both sides of every level boundary, and at each end of every bucket.
    #[test]
    fn level_steps_at_each_threshold_and_nowhere_else() {
        for (k, &t) in THRESHOLDS.iter().enumerate().take(256).skip(1) {
            assert_eq!(
                level(f32::from_bits(t)),
                k as u8,
                "at level {k}'s threshold"
            );
            assert_eq!(
                level(f32::from_bits(t - 1)),
                k as u8 - 1,
                "below level {k}'s"
            );
        }
        for b in 0..BUCKETS as u32 {
            let first = LOWEST + (b << SHIFT);
            for bits in [first, first + (1 << SHIFT) - 1] {
                let want = THRESHOLDS[1..256].iter().filter(|&&t| t <= bits).count();
                assert_eq!(
                    usize::from(level(f32::from_bits(bits))),
                    want,
                    "0x{bits:08x}"
                );
            }
        }
    }

    #[test]
    fn level_is_the_nearest_level_of_the_exact_value() {
        let mut x = 0.0f32;
        while x <= 1.0 {
            let want = (255.0 * srgb64(x as f64) + 0.5).floor() as u8;
            assert_eq!(level(x), want, "x = {x:e}");
            x = f32::from_bits(x.to_bits() + 997);
        }
        for (x, want) in [
            (f32::NAN, 0),
            (-1.0, 0),
            (-0.0, 0),
            (f32::MIN_POSITIVE / 4.0, 0),
            (1.0, 255),
            (1.5, 255),
            (f32::MAX, 255),
            (f32::INFINITY, 255),
        ] {
            assert_eq!(level(x), want, "x = {x:e}");
        }
    }
}

#[cfg(test)]
mod agreement {
    use super::*;

    /// `quantize_u8(srgb_encode(x))` rounds in `f32` (its `powf` within an ulp or so); where it
    /// picks another level than the exact one, `x` is within a few ulps of that level's boundary.
    #[test]
    fn the_f32_pipeline_differs_only_at_level_boundaries() {
        // Every 1009th `f32` in [0, 1], about a million (3 in 10⁷ differ when every 101st is run).
        let mut x = 0.0f32;
        while x <= 1.0 {
            let (old, new) = (crate::quantize_u8(crate::srgb_encode(x)), level(x));
            if old != new {
                let boundary = THRESHOLDS[usize::from(old.max(new))];
                let ulps = x.to_bits().abs_diff(boundary);
                assert!(
                    ulps <= 4,
                    "x = {x:e}: {old} vs {new}, {ulps} ulps from the boundary"
                );
            }
            x = f32::from_bits(x.to_bits() + 1009);
        }
    }
}
