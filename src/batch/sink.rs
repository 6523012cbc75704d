//! Where the batch kernel writes: the total colour ([`SoaRgb`]) or the three terms
//! ([`SoaTerms`]), from the vector lanes of a chunk or from the scalar path's [`Terms`] for a
//! point it redoes.

use core::ops::Range;

use super::kernel::{Job, W};
use super::simd::{Kernels, Simd};
use super::soa::{SoaRgb, SoaTerms};
use super::srgb8_lanes;
use crate::terms::Terms;

/// An output form of the kernel.
pub(crate) trait Sink {
    /// Whether the kernel must give the three terms (otherwise their total, in the first row).
    const TERMS: bool;

    /// Whether [`write`](Self::write) encodes (a chain of dependent operations), so the kernel
    /// writes a chunk after shading the next (see `kernel::run_with`).
    const DEFER: bool = false;

    /// Whether the total must be saturated at `f32::MAX` (`Terms::total`'s rule); false where
    /// [`write`](Self::write) clamps it below 1 anyway (8-bit pixels), so the `min` would change
    /// no output. The terms are saturated either way.
    const SATURATES: bool = true;

    /// How many points it holds.
    fn len(&self) -> usize;

    /// Writes lanes `..count` of a chunk of points `i..i + count` (`count ≤ W`): `rows` is
    /// `[ambient, diffuse, specular]`, each `[r, g, b]`, with [`TERMS`](Self::TERMS); otherwise
    /// only `rows[0]`, the total, is read. Each vector goes straight to its slice (a buffer of
    /// the nine rows on the stack cost a `memset` call per chunk).
    fn write<S: Simd>(&mut self, s: S, i: usize, count: usize, rows: &[[S::V; 3]; 3]);

    /// Writes point `at` from the scalar path's terms.
    fn put(&mut self, at: usize, terms: &Terms);

    /// The same output form over points `r` of this one.
    type Part<'b>: Sink
    where
        Self: 'b;

    /// Points `r` of this output (`r` within [`len`](Self::len)).
    fn part(&mut self, r: Range<usize>) -> Self::Part<'_>;

    /// Runs `job` with level `t`'s kernel for this output form.
    fn run_on<T: Kernels>(t: T, job: Job<'_, Self>) -> usize
    where
        Self: Sized;
}

/// One channel's lanes (or one pixel per lane) over `out[i..i + count]`: a whole chunk as one
/// fixed-size copy.
#[inline(always)]
fn write_lanes<T: Copy>(out: &mut [T], i: usize, count: usize, v: &[T; W]) {
    if count == W {
        if let Ok(a) = <&mut [T; W]>::try_from(&mut out[i..i + W]) {
            *a = *v;
        }
    } else {
        out[i..i + count].copy_from_slice(&v[..count]);
    }
}

#[inline(always)]
fn write_rgb<S: Simd>(s: S, out: &mut SoaRgb<'_>, i: usize, count: usize, rgb: &[S::V; 3]) {
    write_lanes(out.r, i, count, &s.store(rgb[0]));
    write_lanes(out.g, i, count, &s.store(rgb[1]));
    write_lanes(out.b, i, count, &s.store(rgb[2]));
}

fn put_rgb(out: &mut SoaRgb<'_>, at: usize, c: glam::Vec3) {
    (out.r[at], out.g[at], out.b[at]) = (c.x, c.y, c.z);
}

fn part_rgb<'b>(out: &'b mut SoaRgb<'_>, r: Range<usize>) -> SoaRgb<'b> {
    SoaRgb::new(&mut out.r[r.clone()], &mut out.g[r.clone()], &mut out.b[r])
}

impl Sink for SoaRgb<'_> {
    const TERMS: bool = false;
    type Part<'b>
        = SoaRgb<'b>
    where
        Self: 'b;

    fn part(&mut self, r: Range<usize>) -> SoaRgb<'_> {
        part_rgb(self, r)
    }

    #[inline(always)]
    fn len(&self) -> usize {
        SoaRgb::len(self)
    }

    #[inline(always)]
    fn write<S: Simd>(&mut self, s: S, i: usize, count: usize, rows: &[[S::V; 3]; 3]) {
        write_rgb(s, self, i, count, &rows[0]);
    }

    fn put(&mut self, at: usize, terms: &Terms) {
        put_rgb(self, at, terms.total());
    }

    fn run_on<T: Kernels>(t: T, job: Job<'_, Self>) -> usize {
        t.run(job)
    }
}

impl Sink for SoaTerms<'_> {
    const TERMS: bool = true;
    type Part<'b>
        = SoaTerms<'b>
    where
        Self: 'b;

    fn part(&mut self, r: Range<usize>) -> SoaTerms<'_> {
        SoaTerms::new(
            part_rgb(&mut self.ambient, r.clone()),
            part_rgb(&mut self.diffuse, r.clone()),
            part_rgb(&mut self.specular, r),
        )
    }

    #[inline(always)]
    fn len(&self) -> usize {
        SoaTerms::len(self)
    }

    #[inline(always)]
    fn write<S: Simd>(&mut self, s: S, i: usize, count: usize, rows: &[[S::V; 3]; 3]) {
        write_rgb(s, &mut self.ambient, i, count, &rows[0]);
        write_rgb(s, &mut self.diffuse, i, count, &rows[1]);
        write_rgb(s, &mut self.specular, i, count, &rows[2]);
    }

    fn put(&mut self, at: usize, terms: &Terms) {
        put_rgb(&mut self.ambient, at, terms.ambient);
        put_rgb(&mut self.diffuse, at, terms.diffuse);
        put_rgb(&mut self.specular, at, terms.specular);
    }

    fn run_on<T: Kernels>(t: T, job: Job<'_, Self>) -> usize {
        t.run_terms(job)
    }
}

/// An 8-bit frame: the total colour encoded to sRGB levels in the kernel's lanes by
/// [`linear_to_srgb8`](crate::linear_to_srgb8)'s table ([`srgb8_lanes`](super::srgb8_lanes)), as
/// `[r, g, b, 255]` or as `0x00RRGGBB`.
pub(crate) enum Pixels8<'a> {
    /// `[r, g, b, 255]` per point.
    Rgba(&'a mut [[u8; 4]]),
    /// `r << 16 | g << 8 | b` per point.
    Xrgb(&'a mut [u32]),
}

impl Pixels8<'_> {
    /// Point `at`'s pixel from its three levels.
    fn set(&mut self, at: usize, [r, g, b]: [u8; 3]) {
        match self {
            Pixels8::Rgba(out) => out[at] = [r, g, b, 255],
            Pixels8::Xrgb(out) => out[at] = u32::from(r) << 16 | u32::from(g) << 8 | u32::from(b),
        }
    }
}

impl Sink for Pixels8<'_> {
    const TERMS: bool = false;
    const DEFER: bool = true;
    // `srgb8_lanes::levels3` clamps at 1: `f32::MAX` and +∞ both give 255.
    const SATURATES: bool = false;
    type Part<'b>
        = Pixels8<'b>
    where
        Self: 'b;

    fn part(&mut self, r: Range<usize>) -> Pixels8<'_> {
        match self {
            Pixels8::Rgba(out) => Pixels8::Rgba(&mut out[r]),
            Pixels8::Xrgb(out) => Pixels8::Xrgb(&mut out[r]),
        }
    }

    #[inline(always)]
    fn len(&self) -> usize {
        match self {
            Pixels8::Rgba(out) => out.len(),
            Pixels8::Xrgb(out) => out.len(),
        }
    }

    #[inline(always)]
    fn write<S: Simd>(&mut self, s: S, i: usize, count: usize, rows: &[[S::V; 3]; 3]) {
        // The total is `≥ 0` or +∞ in every lane the scalar path does not redo
        // (`kernel::finish`); a lane it redoes is written again by `put`.
        let [lr, lg, lb] = srgb8_lanes::levels3::<S, true>(s, rows[0]);
        let (lo, hi, top) = match self {
            Pixels8::Rgba(_) => (lr, lb, 0xff00_0000),
            Pixels8::Xrgb(_) => (lb, lr, 0),
        };
        let words: [u32; W] =
            bytemuck::must_cast(s.store(s.bits_to_f32(srgb8_lanes::pack(s, lo, lg, hi, top))));
        match self {
            // `[r, g, b, 255]` is the word's little-endian byte order.
            Pixels8::Rgba(out) => {
                write_lanes(out, i, count, &bytemuck::must_cast(words.map(u32::to_le)));
            }
            Pixels8::Xrgb(out) => write_lanes(out, i, count, &words),
        }
    }

    fn put(&mut self, at: usize, terms: &Terms) {
        self.set(at, crate::linear_to_srgb8(terms.total()));
    }

    fn run_on<T: Kernels>(t: T, job: Job<'_, Self>) -> usize {
        t.run_pixels(job)
    }
}
