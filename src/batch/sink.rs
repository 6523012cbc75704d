//! Where the batch kernel writes: the total colour ([`SoaRgb`]) or the three terms
//! ([`SoaTerms`]), from the vector lanes of a chunk or from the scalar path's [`Terms`] for a
//! point it redoes.

use core::ops::Range;

use super::kernel::{Job, Lanes, W};
use super::simd::{Kernels, Simd};
use super::soa::{SoaRgb, SoaTerms};
use crate::terms::Terms;

/// An output form of the kernel.
pub(crate) trait Sink {
    /// Whether the kernel must give the three terms (otherwise their total, in the first row).
    const TERMS: bool;

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

/// One channel's lanes over `out[i..i + count]`: a whole chunk as one fixed-size copy.
#[inline(always)]
fn write_lanes(out: &mut [f32], i: usize, count: usize, v: &Lanes) {
    if count == W {
        if let Ok(a) = <&mut Lanes>::try_from(&mut out[i..i + W]) {
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
