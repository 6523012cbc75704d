//! 8-bit sRGB encoding in the kernel's lanes: [`linear_to_srgb8`](crate::linear_to_srgb8)'s
//! bucket table, one entry per lane, so the levels are that encoder's, bit for bit.
//!
//! ```text
//! bits  = bits(min(max(x, LOWEST), 1))           NaN and everything below LOWEST: level 0
//! entry = BUCKET[(bits >> 16) − (LOWEST >> 16)]  = k << 16 | c
//! level = k + (bits & 0xffff > c)
//! ```
//!
//! The entry is loaded by the level's gather instruction (AVX2, AVX-512) or lane by lane.

use super::simd::Simd;
use crate::colour::srgb8::{BUCKET, LOWEST, SHIFT};

/// Each lane's 8-bit sRGB level, `⌊255·srgb(x) + ½⌋` with the exact `srgb`, as an integer in
/// `[0, 255]`: NaN and negatives give 0, values from 1 up give 255.
#[inline(always)]
pub(crate) fn levels<S: Simd>(s: S, x: S::V) -> S::I {
    // `max` returns its second operand for NaN.
    let x = s.min(s.max(x, s.splat(f32::from_bits(LOWEST))), s.splat(1.0));
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

/// The 32-bit words `lo | mid << 8 | hi << 16 | top` from three lanes of levels in `[0, 255]`.
#[inline(always)]
pub(crate) fn pack<S: Simd>(s: S, lo: S::I, mid: S::I, hi: S::I, top: u32) -> S::I {
    s.add_i(
        s.add_i(lo, s.shl8(mid)),
        s.add_i(s.shl16(hi), s.splat_i(top as i32)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::kernel::{Lanes, W};
    use crate::batch::simd::portable::Portable;

    /// Every level's lanes against the scalar encoder on `xs`, and the packed words' bytes.
    fn agrees<S: Simd>(name: &str, s: S, xs: &[f32]) {
        for chunk in xs.chunks(W) {
            let mut lanes: Lanes = [0.0; W];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let level = levels(s, s.load(&lanes));
            let words = s.store(s.bits_to_f32(pack(s, level, s.splat_i(7), level, 0xff00_0000)));
            let level = s.store(s.bits_to_f32(level));
            for (j, &x) in chunk.iter().enumerate() {
                let want = crate::colour::srgb8::level(x);
                assert_eq!(level[j].to_bits(), u32::from(want), "{name}: x = {x:e}");
                assert_eq!(
                    words[j].to_bits().to_le_bytes(),
                    [want, 7, want, 255],
                    "{name}"
                );
            }
        }
    }

    fn each_level(xs: &[f32]) {
        agrees("portable", Portable, xs);
        #[cfg(target_arch = "x86_64")]
        {
            use crate::batch::simd::{avx2::Avx2, avx512::Avx512, sse2::Sse2};
            agrees("sse2", Sse2, xs);
            if let Some(t) = Avx2::new() {
                agrees("avx2", t, xs);
            }
            if let Some(t) = Avx512::new() {
                agrees("avx512", t, xs);
            }
        }
        #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
        agrees("neon", crate::batch::simd::neon::Neon, xs);
    }

    /// Every 4099th `f32` from 0 to past 1, either side of every level boundary, and the values
    /// outside `[0, 1]`.
    #[test]
    fn lanes_are_the_table_encoders_levels() {
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
        each_level(&xs);
    }
}
