//! The SIMD crates considered for the batch kernel's lanes and dispatch, measured on a slice of
//! that kernel: normalise N, L and V, form the halfway vector's cosine, a Blinn-Phong lobe
//! squared up to the 32nd power and the diffuse cosine, over 4096 points in structure-of-arrays
//! form. Each variant is the same arithmetic; they differ in how the vector code is written and
//! how the instruction set is chosen:
//!
//! - `autovec`: a plain `f32` loop, vectorised by LLVM for the build's baseline (SSE2 on x86-64).
//! - `wide`: `wide::f32x8` (the `wide` crate) in an ordinary function.
//! - `wide_in_avx2_fn`: the same `wide` code inside a `#[target_feature(enable = "avx2,fma")]`
//!   function, as a run-time dispatcher (`multiversion`, or the crate's own `Level`) would call
//!   it. `wide` picks its instructions by `cfg(target_feature)` when it is compiled, so it stays
//!   on SSE2 here unless the whole program is built with `-C target-cpu`.
//! - `std_arch_avx2`: `core::arch` AVX2 and FMA intrinsics in a `#[target_feature]` function:
//!   what the crate's `Simd` trait does per level.
//! - `pulp`: one generic body through `pulp::Arch::new().dispatch` (run-time dispatch; pulp's
//!   default features go up to AVX2 + FMA, its `x86-v4` feature adds AVX-512).
//!
//! Every variant is checked against `autovec` before timing. x86-64 only (with AVX2 and FMA at
//! run time); elsewhere the bench does nothing.
//!
//! Run: `cargo bench --bench simd_crates`.

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics and calls into #[target_feature] functions, after detection"
)]
mod x86 {
    use std::hint::black_box;
    use std::time::Duration;

    use criterion::{Criterion, Throughput};
    use wide::f32x8;

    const N: usize = 4096;
    /// The light's and the eye's positions.
    const LIGHT: [f32; 3] = [1.2, 1.0, 2.0];
    const EYE: [f32; 3] = [0.0, 0.0, 3.0];
    /// The diffuse and specular weights of the result.
    const KD: f32 = 0.8;
    const KS: f32 = 0.5;

    /// Positions and (unnormalised) normals, one slice per component.
    pub(crate) struct Soa {
        p: [Vec<f32>; 3],
        n: [Vec<f32>; 3],
    }

    impl Soa {
        fn new(seed: u64) -> Self {
            let mut state = seed;
            // SplitMix64, as the other benches' points.
            let mut next = move || {
                state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
            };
            let mut slice = |k: f32| (0..N).map(|_| next() * k).collect::<Vec<f32>>();
            Soa {
                p: [slice(2.0), slice(2.0), slice(2.0)],
                n: [slice(1.0), slice(1.0), slice(1.0)],
            }
        }
    }

    /// The slice of the kernel for point `i`, in plain `f32`.
    #[inline(always)]
    fn point(s: &Soa, i: usize) -> f32 {
        let [px, py, pz] = [s.p[0][i], s.p[1][i], s.p[2][i]];
        let [nx, ny, nz] = [s.n[0][i], s.n[1][i], s.n[2][i]];
        let rn = 1.0 / (nx * nx + ny * ny + nz * nz).sqrt();
        let (nx, ny, nz) = (nx * rn, ny * rn, nz * rn);
        let (lx, ly, lz) = (LIGHT[0] - px, LIGHT[1] - py, LIGHT[2] - pz);
        let rl = 1.0 / (lx * lx + ly * ly + lz * lz).sqrt();
        let (lx, ly, lz) = (lx * rl, ly * rl, lz * rl);
        let (vx, vy, vz) = (EYE[0] - px, EYE[1] - py, EYE[2] - pz);
        let rv = 1.0 / (vx * vx + vy * vy + vz * vz).sqrt();
        let (hx, hy, hz) = (lx + vx * rv, ly + vy * rv, lz + vz * rv);
        let rh = 1.0 / (hx * hx + hy * hy + hz * hz).sqrt();
        let n_dot_h = ((nx * hx + ny * hy + nz * hz) * rh).max(0.0);
        let mut lobe = n_dot_h * n_dot_h;
        for _ in 0..4 {
            lobe *= lobe;
        }
        let n_dot_l = (nx * lx + ny * ly + nz * lz).max(0.0);
        KD * n_dot_l + KS * lobe
    }

    #[inline(never)]
    fn autovec(s: &Soa, out: &mut [f32]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = point(s, i);
        }
    }

    /// The slice for points `i..i + 8` with `wide`.
    #[inline(always)]
    fn wide8(s: &Soa, i: usize) -> f32x8 {
        let load = |v: &[f32]| f32x8::from(<[f32; 8]>::try_from(&v[i..i + 8]).unwrap_or([1.0; 8]));
        let splat = f32x8::splat;
        let [px, py, pz] = [load(&s.p[0]), load(&s.p[1]), load(&s.p[2])];
        let [nx, ny, nz] = [load(&s.n[0]), load(&s.n[1]), load(&s.n[2])];
        let one = splat(1.0);
        let rn = one / (nx * nx + ny * ny + nz * nz).sqrt();
        let (nx, ny, nz) = (nx * rn, ny * rn, nz * rn);
        let (lx, ly, lz) = (
            splat(LIGHT[0]) - px,
            splat(LIGHT[1]) - py,
            splat(LIGHT[2]) - pz,
        );
        let rl = one / (lx * lx + ly * ly + lz * lz).sqrt();
        let (lx, ly, lz) = (lx * rl, ly * rl, lz * rl);
        let (vx, vy, vz) = (splat(EYE[0]) - px, splat(EYE[1]) - py, splat(EYE[2]) - pz);
        let rv = one / (vx * vx + vy * vy + vz * vz).sqrt();
        let (hx, hy, hz) = (lx + vx * rv, ly + vy * rv, lz + vz * rv);
        let rh = one / (hx * hx + hy * hy + hz * hz).sqrt();
        let n_dot_h = ((nx * hx + ny * hy + nz * hz) * rh).max(f32x8::ZERO);
        let mut lobe = n_dot_h * n_dot_h;
        for _ in 0..4 {
            lobe *= lobe;
        }
        let n_dot_l = (nx * lx + ny * ly + nz * lz).max(f32x8::ZERO);
        n_dot_l.mul_add(splat(KD), splat(KS) * lobe)
    }

    #[inline(never)]
    fn wide(s: &Soa, out: &mut [f32]) {
        for (c, o) in out.chunks_exact_mut(8).enumerate() {
            o.copy_from_slice(&wide8(s, 8 * c).to_array());
        }
    }

    #[target_feature(enable = "avx2,fma")]
    fn wide_in_avx2_fn(s: &Soa, out: &mut [f32]) {
        for (c, o) in out.chunks_exact_mut(8).enumerate() {
            o.copy_from_slice(&wide8(s, 8 * c).to_array());
        }
    }

    #[target_feature(enable = "avx2,fma")]
    fn std_arch_avx2(s: &Soa, out: &mut [f32]) {
        use core::arch::x86_64::*;
        let splat = _mm256_set1_ps;
        let dot = |a: [__m256; 3], b: [__m256; 3]| {
            _mm256_fmadd_ps(
                a[0],
                b[0],
                _mm256_fmadd_ps(a[1], b[1], _mm256_mul_ps(a[2], b[2])),
            )
        };
        let scale = |a: [__m256; 3], k: __m256| a.map(|x| _mm256_mul_ps(x, k));
        let inv_len = |a: [__m256; 3]| _mm256_div_ps(splat(1.0), _mm256_sqrt_ps(dot(a, a)));
        for (c, o) in out.chunks_exact_mut(8).enumerate() {
            let i = 8 * c;
            let load = |v: &[f32]| {
                let a = <[f32; 8]>::try_from(&v[i..i + 8]).unwrap_or([1.0; 8]);
                // SAFETY: `a` is eight readable f32s.
                unsafe { _mm256_loadu_ps(a.as_ptr()) }
            };
            let p = [load(&s.p[0]), load(&s.p[1]), load(&s.p[2])];
            let n = [load(&s.n[0]), load(&s.n[1]), load(&s.n[2])];
            let n = scale(n, inv_len(n));
            let l = [0, 1, 2].map(|k| _mm256_sub_ps(splat(LIGHT[k]), p[k]));
            let l = scale(l, inv_len(l));
            let v = [0, 1, 2].map(|k| _mm256_sub_ps(splat(EYE[k]), p[k]));
            let rv = inv_len(v);
            let h = [0, 1, 2].map(|k| _mm256_fmadd_ps(v[k], rv, l[k]));
            let n_dot_h = _mm256_max_ps(_mm256_mul_ps(dot(n, h), inv_len(h)), _mm256_setzero_ps());
            let mut lobe = _mm256_mul_ps(n_dot_h, n_dot_h);
            for _ in 0..4 {
                lobe = _mm256_mul_ps(lobe, lobe);
            }
            let n_dot_l = _mm256_max_ps(dot(n, l), _mm256_setzero_ps());
            let r = _mm256_fmadd_ps(n_dot_l, splat(KD), _mm256_mul_ps(splat(KS), lobe));
            let mut a = [0.0f32; 8];
            // SAFETY: `a` is eight writable f32s.
            unsafe { _mm256_storeu_ps(a.as_mut_ptr(), r) };
            o.copy_from_slice(&a);
        }
    }

    /// The slice as one generic body for `pulp`'s dispatch.
    struct Pulp<'a> {
        s: &'a Soa,
        out: &'a mut [f32],
    }

    impl pulp::WithSimd for Pulp<'_> {
        type Output = ();

        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, simd: S) {
            let s = self.s;
            let (px, py, pz) = (
                S::as_simd_f32s(&s.p[0]).0,
                S::as_simd_f32s(&s.p[1]).0,
                S::as_simd_f32s(&s.p[2]).0,
            );
            let (nx0, ny0, nz0) = (
                S::as_simd_f32s(&s.n[0]).0,
                S::as_simd_f32s(&s.n[1]).0,
                S::as_simd_f32s(&s.n[2]).0,
            );
            let out = S::as_mut_simd_f32s(self.out).0;
            for (i, o) in out.iter_mut().enumerate() {
                let p = [px[i], py[i], pz[i]];
                let n = [nx0[i], ny0[i], nz0[i]];
                let n = scale(simd, n, inv_len(simd, n));
                let l = sub_from(simd, LIGHT, p);
                let l = scale(simd, l, inv_len(simd, l));
                let v = sub_from(simd, EYE, p);
                let rv = inv_len(simd, v);
                let h = [
                    simd.mul_add_f32s(v[0], rv, l[0]),
                    simd.mul_add_f32s(v[1], rv, l[1]),
                    simd.mul_add_f32s(v[2], rv, l[2]),
                ];
                let zero = simd.splat_f32s(0.0);
                let n_dot_h = simd.max_f32s(simd.mul_f32s(dot(simd, n, h), inv_len(simd, h)), zero);
                let mut lobe = simd.mul_f32s(n_dot_h, n_dot_h);
                for _ in 0..4 {
                    lobe = simd.mul_f32s(lobe, lobe);
                }
                let n_dot_l = simd.max_f32s(dot(simd, n, l), zero);
                let ks_lobe = simd.mul_f32s(simd.splat_f32s(KS), lobe);
                *o = simd.mul_add_f32s(n_dot_l, simd.splat_f32s(KD), ks_lobe);
            }
        }
    }

    // pulp's helpers as `#[inline(always)]` functions, and no `array::map`: written with closures,
    // they were left out of line without the dispatched level's features, and the variant ran
    // ten times slower (the trap the crate's own kernel avoids the same way).
    #[inline(always)]
    fn sub_from<S: pulp::Simd>(simd: S, q: [f32; 3], p: [S::f32s; 3]) -> [S::f32s; 3] {
        [
            simd.sub_f32s(simd.splat_f32s(q[0]), p[0]),
            simd.sub_f32s(simd.splat_f32s(q[1]), p[1]),
            simd.sub_f32s(simd.splat_f32s(q[2]), p[2]),
        ]
    }

    #[inline(always)]
    fn dot<S: pulp::Simd>(simd: S, a: [S::f32s; 3], b: [S::f32s; 3]) -> S::f32s {
        let zz = simd.mul_f32s(a[2], b[2]);
        simd.mul_add_f32s(a[0], b[0], simd.mul_add_f32s(a[1], b[1], zz))
    }

    #[inline(always)]
    fn scale<S: pulp::Simd>(simd: S, a: [S::f32s; 3], k: S::f32s) -> [S::f32s; 3] {
        [
            simd.mul_f32s(a[0], k),
            simd.mul_f32s(a[1], k),
            simd.mul_f32s(a[2], k),
        ]
    }

    #[inline(always)]
    fn inv_len<S: pulp::Simd>(simd: S, a: [S::f32s; 3]) -> S::f32s {
        simd.div_f32s(simd.splat_f32s(1.0), simd.sqrt_f32s(dot(simd, a, a)))
    }

    pub(crate) fn simd_crates(c: &mut Criterion) {
        if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
            eprintln!("simd_crates: this CPU lacks AVX2 or FMA; nothing measured");
            return;
        }
        let s = Soa::new(0x51d);
        let arch = pulp::Arch::new();
        let mut want = vec![0.0f32; N];
        autovec(&s, &mut want);
        let mut out = vec![0.0f32; N];
        // SAFETY (each `unsafe` below): AVX2 and FMA were detected above.
        type Variant<'v> = (&'static str, Box<dyn Fn(&Soa, &mut [f32]) + 'v>);
        let variants: [Variant<'_>; 5] = [
            ("autovec", Box::new(autovec)),
            ("wide", Box::new(wide)),
            (
                "wide_in_avx2_fn",
                Box::new(|s, o| unsafe { wide_in_avx2_fn(s, o) }),
            ),
            (
                "std_arch_avx2",
                Box::new(|s, o| unsafe { std_arch_avx2(s, o) }),
            ),
            ("pulp", Box::new(|s, out| arch.dispatch(Pulp { s, out }))),
        ];
        for (name, f) in &variants {
            f(&s, &mut out);
            // The same arithmetic in another order (FMA, vector division): within a few roundings
            // of results below 2 (KD + KS·lobe with cosines ≤ 1); 1e-5 absolute is ~40 ulps there.
            for (i, (a, b)) in out.iter().zip(&want).enumerate() {
                assert!((a - b).abs() <= 1e-5, "{name}: point {i}: {a} against {b}");
            }
        }
        let mut g = c.benchmark_group("simd_crates_4096");
        g.throughput(Throughput::Elements(N as u64))
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
        for (name, f) in &variants {
            g.bench_function(*name, |b| b.iter(|| f(black_box(&s), &mut out)));
        }
        g.finish();
    }
}

#[cfg(target_arch = "x86_64")]
criterion::criterion_group!(benches, x86::simd_crates);
#[cfg(target_arch = "x86_64")]
criterion::criterion_main!(benches);

#[cfg(not(target_arch = "x86_64"))]
fn main() {}
