//! The AVX-512 level: the kernel's equations written with AVX-512 intrinsics, 16 points per step.
//!
//! Same equations, same fallbacks as [`kernel`](super::kernel) (whose module docs derive them),
//! with fused multiply-adds and `vrsqrt14ps` + one Newton step for the inverse norms. Every
//! function is safe: the `#[target_feature]` ones are called only from each other, and from
//! `dispatch` after the CPU check; `bytemuck::must_cast` moves `[f32; 16]` in and out of `__m512`
//! without `unsafe`.

use core::arch::x86_64::{
    __m512, __m512i, __mmask16, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm512_add_epi32,
    _mm512_add_ps, _mm512_castps_si512, _mm512_castsi512_ps, _mm512_cmp_ps_mask,
    _mm512_cvtepi32_ps, _mm512_div_ps, _mm512_fmadd_ps, _mm512_fmsub_ps, _mm512_fnmadd_ps,
    _mm512_mask_mul_ps, _mm512_mask_sub_ps, _mm512_maskz_mov_ps, _mm512_max_ps, _mm512_min_ps,
    _mm512_mul_ps, _mm512_rsqrt14_ps, _mm512_set1_epi32, _mm512_set1_ps, _mm512_setzero_ps,
    _mm512_slli_epi32, _mm512_srai_epi32, _mm512_sub_epi32, _mm512_sub_ps,
};

use super::kernel::{Lanes, PREPARED, PreparedLight, Setup, ViewK, W, load_tail};
use super::prepare::{BatchLight, BatchModel, LaneLight, Lobe};
use super::soa::{SoaRgb, SoaVec3};
use crate::attenuation::Attenuation;
use crate::gate::SpecularGate;
use crate::math;
use crate::pow::{EXP2_3, EXP2_4, EXP2_5, LOG2_3, LOG2_5, LOG2_7, Poly, PowPlan, lobe_pow};
use bytemuck::must_cast;

type V = __m512;

const LO: f32 = 1.0e-30;
const HI: f32 = 1.0e30;

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn splat(x: f32) -> V {
    _mm512_set1_ps(x)
}

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn store(s: &mut [f32], v: V) {
    if let Ok(a) = <&mut Lanes>::try_from(s) {
        *a = must_cast(v);
    }
}

/// `1/√x`: `vrsqrt14ps` (relative error ≤ 2⁻¹⁴) and one Newton step `y·(1.5 − 0.5·x·y²)`.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn rsqrt(x: V) -> V {
    let y = _mm512_rsqrt14_ps(x);
    let hx = _mm512_mul_ps(x, splat(0.5));
    let t = _mm512_fnmadd_ps(hx, _mm512_mul_ps(y, y), splat(1.5));
    _mm512_mul_ps(y, t)
}

/// Lanes whose squared norm is in `[LO, HI]` (false for NaN).
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn in_range(x: V) -> __mmask16 {
    _mm512_cmp_ps_mask::<_CMP_GE_OQ>(x, splat(LO)) & _mm512_cmp_ps_mask::<_CMP_LE_OQ>(x, splat(HI))
}

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn dot(a: [V; 3], b: [V; 3]) -> V {
    _mm512_fmadd_ps(
        a[0],
        b[0],
        _mm512_fmadd_ps(a[1], b[1], _mm512_mul_ps(a[2], b[2])),
    )
}

/// `Σ c[k] t^k` by Estrin's scheme: pairs `c[2i] + c[2i+1]·t` first, then pairs of those with
/// `t²`, `t⁴`, …; the dependency chain is `⌈log2 N⌉` fused multiply-adds deep instead of Horner's
/// `N`, which matters because the chains of successive chunks are what limits this loop.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn poly<const N: usize>(t: V, c: &[f32; N]) -> V {
    let mut cur = [_mm512_setzero_ps(); 8];
    for (slot, &k) in cur.iter_mut().zip(c) {
        *slot = splat(k);
    }
    let mut m = N.min(8);
    let mut pw = t;
    while m > 1 {
        let half = m.div_ceil(2);
        for j in 0..half {
            cur[j] = if 2 * j + 1 < m {
                _mm512_fmadd_ps(cur[2 * j + 1], pw, cur[2 * j])
            } else {
                cur[2 * j]
            };
        }
        m = half;
        pw = _mm512_mul_ps(pw, pw);
    }
    cur[0]
}

/// `log2 x` for `x ∈ (0, 1]` (as `pow::log2_poly`).
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn log2<const N: usize>(x: V, c: &[f32; N]) -> V {
    let sub = _mm512_cmp_ps_mask::<_CMP_LT_OQ>(x, splat(f32::MIN_POSITIVE));
    let xs = _mm512_mask_mul_ps(x, sub, x, splat(16_777_216.0));
    let bits: __m512i = _mm512_castps_si512(xs);
    let e = _mm512_srai_epi32::<23>(_mm512_sub_epi32(bits, _mm512_set1_epi32(0x3f35_04f3)));
    let m = _mm512_castsi512_ps(_mm512_sub_epi32(bits, _mm512_slli_epi32::<23>(e)));
    let t = _mm512_sub_ps(m, splat(1.0));
    let ef = _mm512_cvtepi32_ps(e);
    let ef = _mm512_mask_sub_ps(ef, sub, ef, splat(24.0));
    _mm512_fmadd_ps(t, poly(t, c), ef)
}

/// `2^y`, 0 where `y < −100` (as `pow::poly_pow`'s).
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn exp2<const N: usize>(y: V, c: &[f32; N]) -> V {
    let keep = _mm512_cmp_ps_mask::<_CMP_GE_OQ>(y, splat(-100.0));
    let y = _mm512_min_ps(_mm512_max_ps(y, splat(-100.0)), splat(0.0));
    let big = _mm512_add_ps(y, splat(12_582_912.0));
    let r = _mm512_sub_ps(big, splat(12_582_912.0));
    let ri = _mm512_sub_epi32(_mm512_castps_si512(big), _mm512_set1_epi32(0x4b40_0000));
    let f = _mm512_sub_ps(y, r);
    let q = _mm512_fmadd_ps(f, poly(f, c), splat(1.0));
    let scale = _mm512_castsi512_ps(_mm512_slli_epi32::<23>(_mm512_add_epi32(
        ri,
        _mm512_set1_epi32(127),
    )));
    _mm512_maskz_mov_ps(keep, _mm512_mul_ps(q, scale))
}

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn poly_pow(p: Poly, x: V, s: f32) -> V {
    match p {
        Poly::P3 => exp2(_mm512_mul_ps(splat(s), log2(x, &LOG2_3)), &EXP2_3),
        Poly::P5 => exp2(_mm512_mul_ps(splat(s), log2(x, &LOG2_5)), &EXP2_4),
        Poly::P7 => exp2(_mm512_mul_ps(splat(s), log2(x, &LOG2_7)), &EXP2_5),
    }
}

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn squaring(x: V, flush: f32, n: u32) -> V {
    let keep = _mm512_cmp_ps_mask::<_CMP_GE_OQ>(x, splat(flush));
    let mut base = _mm512_maskz_mov_ps(keep, x);
    if n == 0 {
        return splat(1.0);
    }
    // x^n = (x^(2^z))^(n / 2^z) with z trailing zeros: z plain squarings first.
    let z = n.trailing_zeros();
    for _ in 0..z {
        base = _mm512_mul_ps(base, base);
    }
    let mut acc = base;
    let mut e = n >> (z + 1);
    while e > 0 {
        base = _mm512_mul_ps(base, base);
        if e & 1 == 1 {
            acc = _mm512_mul_ps(acc, base);
        }
        e >>= 1;
    }
    acc
}

/// Which [`PowPlan`] a kernel instance is compiled for (a const parameter, so the per-lane pow
/// has no branches and inlines).
const EXACT: u8 = 0;
const SQUARING: u8 = 1;
const POLY: u8 = 2;
const SPLIT: u8 = 3;

/// `x^s` for bases `≤ 1`; 0 where `x ≤ 0`. `P` is the plan's kind, `POLY_DEG` its polynomial.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn pow<const P: u8, const POLY_DEG: u8>(plan: PowPlan, flush: f32, x: V) -> V {
    let pos = _mm512_cmp_ps_mask::<_CMP_GT_OQ>(x, _mm512_setzero_ps());
    let (s, n, frac) = match plan {
        PowPlan::Exact { s } | PowPlan::Poly { s, .. } => (s, 0, 0.0),
        PowPlan::Squaring { n } => (0.0, n, 0.0),
        PowPlan::Split { n, frac, .. } => (0.0, n, frac),
    };
    let poly = |x: V, s: f32| match POLY_DEG {
        3 => poly_pow(Poly::P3, x, s),
        5 => poly_pow(Poly::P5, x, s),
        _ => poly_pow(Poly::P7, x, s),
    };
    let r = match P {
        EXACT => {
            let mut a: Lanes = must_cast(x);
            for v in &mut a {
                *v = lobe_pow(*v, s);
            }
            must_cast(a)
        }
        SQUARING => squaring(x, flush, n),
        POLY => poly(x, s),
        _ => _mm512_mul_ps(squaring(x, flush, n), poly(x, frac)),
    };
    _mm512_maskz_mov_ps(pos, r)
}

/// A prepared light with every constant already broadcast, so the loop reads them as memory
/// operands instead of loading and broadcasting scalars for every 16 points.
#[derive(Clone, Copy)]
struct LightV {
    lane: LaneLight,
    /// Position (point light) or direction (directional light).
    q: [V; 3],
    /// Attenuation coefficients `c`, `l`, `q`.
    c: [V; 3],
    la: [V; 3],
    ld: [V; 3],
    ls: [V; 3],
    /// The products with the material's colours, for a folded call.
    ka: [V; 3],
    kd: [V; 3],
    ks: [V; 3],
}

/// The material's colours, broadcast once per call.
struct MaterialV {
    ka: [V; 3],
    kd: [V; 3],
    ks: [V; 3],
    ke: [V; 3],
}

#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
#[inline]
fn light_v(l: PreparedLight) -> LightV {
    let v3 = |v: glam::Vec3| [splat(v.x), splat(v.y), splat(v.z)];
    let (q, c) = match l.lane {
        LaneLight::Point {
            position,
            coefficients,
        } => (v3(position), v3(glam::Vec3::from_array(coefficients))),
        LaneLight::Directional(d) => (v3(d), v3(glam::Vec3::ZERO)),
        // Dispatch never runs this kernel with a falloff light (`Setup::portable_only`).
        LaneLight::AmbientOnly | LaneLight::Falloff { .. } => {
            (v3(glam::Vec3::ZERO), v3(glam::Vec3::ZERO))
        }
    };
    LightV {
        lane: l.lane,
        q,
        c,
        la: v3(l.la),
        ld: v3(l.ld),
        ls: v3(l.ls),
        ka: v3(l.ka),
        kd: v3(l.kd),
        ks: v3(l.ks),
    }
}

/// Re-shades the lanes in `bad` (of the 16 points at the start of the slices) with the scalar
/// path, reading the inputs again from the slices so the fast path need not keep them alive.
#[inline(never)]
#[cold]
fn fix<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: [&[f32]; 3],
    nor: [&[f32]; 3],
    out: [&mut [f32]; 3],
    bad: u16,
) {
    let [r, g, b] = out;
    for j in 0..W {
        if bad & (1 << j) != 0 && j < r.len() && j < pos[0].len() {
            let c = crate::shade(
                k.model,
                k.material,
                k.scene,
                glam::Vec3::new(pos[0][j], pos[1][j], pos[2][j]),
                glam::Vec3::new(nor[0][j], nor[1][j], nor[2][j]),
            )
            .total();
            r[j] = c.x;
            g[j] = c.y;
            b[j] = c.z;
        }
    }
}

/// The AVX-512 batch: shades the common prefix of the slices; returns its length.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
pub(super) fn avx512<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> usize {
    let deg = |p: Poly| match p {
        Poly::P3 => 3,
        Poly::P5 => 5,
        Poly::P7 => 7,
    };
    // One instance per plan kind and per colour order (see `Setup::folded`).
    macro_rules! go {
        ($p:expr, $deg:expr) => {
            if k.folded {
                run::<M, L, $p, $deg, true>(k, pos, nor, out)
            } else {
                run::<M, L, $p, $deg, false>(k, pos, nor, out)
            }
        };
    }
    match k.plan {
        PowPlan::Exact { .. } => go!(EXACT, 0),
        PowPlan::Squaring { .. } => go!(SQUARING, 0),
        PowPlan::Poly { poly, .. } => match deg(poly) {
            3 => go!(POLY, 3),
            5 => go!(POLY, 5),
            _ => go!(POLY, 7),
        },
        PowPlan::Split { poly, .. } => match deg(poly) {
            3 => go!(SPLIT, 3),
            5 => go!(SPLIT, 5),
            _ => go!(SPLIT, 7),
        },
    }
}

/// The loop, for one pow plan kind and colour order (`FOLDED`: [`Setup::folded`], sum the
/// products of light and material colours; else the three sums of the saturation rule). The
/// chunk is called from one place so that it inlines.
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn run<M: BatchModel, L: BatchLight, const P: u8, const POLY_DEG: u8, const FOLDED: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> usize {
    let len = pos.len().min(nor.len()).min(out.len());
    let (px, py, pz) = (&pos.x[..len], &pos.y[..len], &pos.z[..len]);
    let (nx, ny, nz) = (&nor.x[..len], &nor.y[..len], &nor.z[..len]);
    let (r, g, b) = (&mut out.r[..len], &mut out.g[..len], &mut out.b[..len]);
    let pre: [LightV; PREPARED] = [
        light_v(k.prepared[0]),
        light_v(k.prepared[1]),
        light_v(k.prepared[2]),
        light_v(k.prepared[3]),
        light_v(k.prepared[4]),
        light_v(k.prepared[5]),
        light_v(k.prepared[6]),
        light_v(k.prepared[7]),
    ];
    let v3 = |v: glam::Vec3| [splat(v.x), splat(v.y), splat(v.z)];
    let mat = MaterialV {
        ka: v3(k.material.ambient()),
        kd: v3(k.material.diffuse()),
        ks: v3(k.material.specular()),
        ke: v3(k.material.emission()),
    };
    let max = splat(math::MAX);
    let scale = splat(k.lm.specular_scale);
    let start = k.base;
    // The chunk body is a macro, expanded at its two uses (full chunks and the tail), so nothing
    // keeps it out of line: as a function or closure LLVM did not inline it, and every vector
    // then went through the stack.
    macro_rules! chunk {
        ($p:expr, $n:expr) => {{
            let p: [V; 3] = $p;
            let n: [V; 3] = $n;
            let nn = dot(n, n);
            let mut ok = in_range(nn);
            let inv_n = rsqrt(nn);
            // Cosines from unnormalised vectors times inverse norms, N·V = (n·V)/(‖n‖‖V‖) and so
            // on: the dot products run alongside the inverse square roots instead of after them.
            // The loop is bound by these dependency chains, not by the number of operations.
            let (v, inv_v) = match k.view {
                ViewK::At(e) => {
                    let d = [
                        _mm512_sub_ps(splat(e.x), p[0]),
                        _mm512_sub_ps(splat(e.y), p[1]),
                        _mm512_sub_ps(splat(e.z), p[2]),
                    ];
                    let vv = dot(d, d);
                    ok &= in_range(vv);
                    (d, rsqrt(vv))
                }
                ViewK::Infinite(d) => ([splat(d.x), splat(d.y), splat(d.z)], splat(1.0)),
            };
            let nv = _mm512_mul_ps(dot(n, v), _mm512_mul_ps(inv_n, inv_v));
            // Three sums per channel, multiplied by the material's colours once at the end (the
            // saturation rule in the module docs of `batch`; as `kernel::chunk`).
            // Folded, `amb` alone holds Ke + Ka⊙Ia + Σ f·(Ka⊙La + max(N·L, 0)·Kd⊙Ld + w·Ks⊙Ls).
            let mut amb = if FOLDED {
                [splat(start.x), splat(start.y), splat(start.z)]
            } else {
                [splat(k.ambient.x), splat(k.ambient.y), splat(k.ambient.z)]
            };
            let mut dif = [_mm512_setzero_ps(); 3];
            let mut spe = [_mm512_setzero_ps(); 3];
            let lm = &k.lm;
            let zero = _mm512_setzero_ps();
            for j in 0..k.scene.lights.len() {
                let owned;
                let lj: &LightV = if k.all_prepared {
                    &pre[j % PREPARED]
                } else {
                    owned = light_v(k.light(j));
                    &owned
                };
                let (la, ld, ls) = if FOLDED {
                    (&lj.ka, &lj.kd, &lj.ks)
                } else {
                    (&lj.la, &lj.ld, &lj.ls)
                };
                // (N·L, L unnormalised, 1/(‖L‖‖V‖), attenuation)
                let (nl, l, inv_lv, att) = match lj.lane {
                    LaneLight::AmbientOnly => {
                        amb = [
                            _mm512_add_ps(amb[0], la[0]),
                            _mm512_add_ps(amb[1], la[1]),
                            _mm512_add_ps(amb[2], la[2]),
                        ];
                        continue;
                    }
                    LaneLight::Falloff { .. } => {
                        // Not run here (`Setup::portable_only`); were it, every lane would go to
                        // the scalar path, which is exact.
                        ok = 0;
                        continue;
                    }
                    LaneLight::Directional(_) => {
                        let l = lj.q;
                        (_mm512_mul_ps(dot(n, l), inv_n), l, inv_v, splat(1.0))
                    }
                    LaneLight::Point { .. } => {
                        let [q0, q1, q2] = lj.q;
                        let [c0, c1, c2] = lj.c;
                        let d = [
                            _mm512_sub_ps(q0, p[0]),
                            _mm512_sub_ps(q1, p[1]),
                            _mm512_sub_ps(q2, p[2]),
                        ];
                        let ll = dot(d, d);
                        ok &= in_range(ll);
                        let nd = dot(n, d);
                        let inv = rsqrt(ll);
                        let dist = _mm512_mul_ps(ll, inv);
                        let den = _mm512_fmadd_ps(dist, _mm512_fmadd_ps(c2, dist, c1), c0);
                        // An overflowed denominator is `Attenuation::factor`'s f64 case: scalar.
                        ok &= _mm512_cmp_ps_mask::<_CMP_LT_OQ>(den, splat(f32::INFINITY));
                        let att = _mm512_div_ps(
                            splat(1.0),
                            _mm512_max_ps(den, splat(Attenuation::MIN_DENOMINATOR)),
                        );
                        (
                            _mm512_mul_ps(nd, _mm512_mul_ps(inv_n, inv)),
                            d,
                            _mm512_mul_ps(inv, inv_v),
                            att,
                        )
                    }
                };
                let nl0 = _mm512_max_ps(nl, zero);
                // Folded, per channel: amb += f · (Ka⊙La + max(N·L, 0)·Kd⊙Ld + gate·lobe·Ks⊙Ls),
                // the light's terms summed in `t` first so the chains into `amb` stay short.
                let mut t = [zero; 3];
                if FOLDED {
                    t = [
                        _mm512_fmadd_ps(nl0, ld[0], la[0]),
                        _mm512_fmadd_ps(nl0, ld[1], la[1]),
                        _mm512_fmadd_ps(nl0, ld[2], la[2]),
                    ];
                } else {
                    // f and f·max(N·L, 0) are finite and so is every colour: no 0·∞ below.
                    let wd = _mm512_mul_ps(att, nl0);
                    amb = [
                        _mm512_fmadd_ps(att, la[0], amb[0]),
                        _mm512_fmadd_ps(att, la[1], amb[1]),
                        _mm512_fmadd_ps(att, la[2], amb[2]),
                    ];
                    dif = [
                        _mm512_fmadd_ps(wd, ld[0], dif[0]),
                        _mm512_fmadd_ps(wd, ld[1], dif[1]),
                        _mm512_fmadd_ps(wd, ld[2], dif[2]),
                    ];
                }
                if k.specular_on {
                    let lv = _mm512_mul_ps(dot(l, v), inv_lv);
                    let base = match lm.lobe {
                        Lobe::Blinn => {
                            let s = _mm512_max_ps(_mm512_add_ps(nl, nv), zero);
                            let den = _mm512_fmadd_ps(splat(2.0), lv, splat(2.0));
                            let okd = _mm512_cmp_ps_mask::<_CMP_GT_OQ>(den, splat(1e-12));
                            // Lanes near L = −V go to the scalar path (see kernel::BLINN_DEN_MIN).
                            ok &= _mm512_cmp_ps_mask::<_CMP_GE_OQ>(
                                den,
                                splat(super::kernel::BLINN_DEN_MIN),
                            );
                            let q =
                                _mm512_min_ps(_mm512_div_ps(_mm512_mul_ps(s, s), den), splat(1.0));
                            _mm512_maskz_mov_ps(okd, q)
                        }
                        _ => {
                            let rv = _mm512_fmsub_ps(_mm512_add_ps(nl, nl), nv, lv);
                            _mm512_min_ps(rv, splat(1.0))
                        }
                    };
                    let lobe = pow::<P, POLY_DEG>(k.plan, k.flush, base);
                    let spec = match lm.gate {
                        SpecularGate::Step => {
                            _mm512_maskz_mov_ps(_mm512_cmp_ps_mask::<_CMP_GT_OQ>(nl, zero), lobe)
                        }
                        SpecularGate::Cosine => _mm512_mul_ps(nl0, lobe),
                        SpecularGate::None => lobe,
                    };
                    if FOLDED {
                        // The scale is in `ks`, and nothing overflows.
                        t = [
                            _mm512_fmadd_ps(spec, ls[0], t[0]),
                            _mm512_fmadd_ps(spec, ls[1], t[1]),
                            _mm512_fmadd_ps(spec, ls[2], t[2]),
                        ];
                    } else {
                        let mut ws = _mm512_mul_ps(att, spec);
                        if k.scaled {
                            // The normalisation factor can be as large as f32::MAX: clamp
                            // f·factor·lobe there before it meets a colour, so a zero lobe
                            // stays 0 (never 0·∞).
                            ws = _mm512_min_ps(_mm512_mul_ps(ws, scale), max);
                        }
                        spe = [
                            _mm512_fmadd_ps(ws, ls[0], spe[0]),
                            _mm512_fmadd_ps(ws, ls[1], spe[1]),
                            _mm512_fmadd_ps(ws, ls[2], spe[2]),
                        ];
                    }
                }
                if FOLDED {
                    amb = [
                        _mm512_fmadd_ps(att, t[0], amb[0]),
                        _mm512_fmadd_ps(att, t[1], amb[1]),
                        _mm512_fmadd_ps(att, t[2], amb[2]),
                    ];
                }
            }
            if FOLDED {
                (
                    [
                        _mm512_min_ps(amb[0], max),
                        _mm512_min_ps(amb[1], max),
                        _mm512_min_ps(amb[2], max),
                    ],
                    !ok,
                )
            } else {
                // Each sum saturates before the material's colour multiplies it; the total again.
                let term = |kc: &V, sum: V| {
                    _mm512_min_ps(_mm512_mul_ps(*kc, _mm512_min_ps(sum, max)), max)
                };
                let total = |c: usize| {
                    let t = _mm512_add_ps(term(&mat.ka[c], amb[c]), term(&mat.kd[c], dif[c]));
                    let t = _mm512_add_ps(t, term(&mat.ks[c], spe[c]));
                    _mm512_min_ps(_mm512_add_ps(t, mat.ke[c]), max)
                };
                ([total(0), total(1), total(2)], !ok)
            }
        }};
    }
    let ld = |s: &[f32]| -> V {
        match <&Lanes>::try_from(s) {
            Ok(a) => must_cast(*a),
            Err(_) => _mm512_setzero_ps(), // unreachable: chunks_exact gives W elements
        }
    };
    let full = len / W * W;
    let inputs = px[..full]
        .chunks_exact(W)
        .zip(py[..full].chunks_exact(W))
        .zip(pz[..full].chunks_exact(W))
        .zip(nx[..full].chunks_exact(W))
        .zip(ny[..full].chunks_exact(W))
        .zip(nz[..full].chunks_exact(W));
    let outputs = r[..full]
        .chunks_exact_mut(W)
        .zip(g[..full].chunks_exact_mut(W))
        .zip(b[..full].chunks_exact_mut(W));
    for ((((((qx, qy), qz), mx), my), mz), ((ro, go), bo)) in inputs.zip(outputs) {
        let (c, bad): ([V; 3], __mmask16) =
            chunk!([ld(qx), ld(qy), ld(qz)], [ld(mx), ld(my), ld(mz)]);
        store(ro, c[0]);
        store(go, c[1]);
        store(bo, c[2]);
        if bad != 0 {
            fix(k, [qx, qy, qz], [mx, my, mz], [ro, go, bo], bad);
        }
    }
    if full < len {
        let count = len - full;
        let tail = |s: &[f32]| -> V { must_cast(load_tail(s, full, count)) };
        let (c, bad): ([V; 3], __mmask16) = chunk!(
            [tail(px), tail(py), tail(pz)],
            [tail(nx), tail(ny), tail(nz)]
        );
        let c: [Lanes; 3] = [must_cast(c[0]), must_cast(c[1]), must_cast(c[2])];
        r[full..].copy_from_slice(&c[0][..count]);
        g[full..].copy_from_slice(&c[1][..count]);
        b[full..].copy_from_slice(&c[2][..count]);
        let bad = bad & (((1u32 << count) - 1) as u16);
        if bad != 0 {
            fix(
                k,
                [&px[full..], &py[full..], &pz[full..]],
                [&nx[full..], &ny[full..], &nz[full..]],
                [&mut r[full..], &mut g[full..], &mut b[full..]],
                bad,
            );
        }
    }
    len
}

#[cfg(all(test, feature = "std"))]
mod tests {
    // Calling a `#[target_feature]` function needs `unsafe`; each call is guarded by the CPU
    // check, as in `dispatch`.
    #![allow(
        unsafe_code,
        reason = "the tests call the AVX-512 kernel after checking the CPU, as dispatch does"
    )]

    use super::*;
    use crate::batch::Level;
    use crate::batch::kernel::flush_below;
    use crate::pow::PowStrategy;
    use crate::pow::error_bounds::worst_over_domain;

    /// The kernel's `pow` for any plan (the const parameters chosen as `avx512` chooses them).
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn pow_any(plan: PowPlan, flush: f32, x: V) -> V {
        let deg = |p: Poly| match p {
            Poly::P3 => 3,
            Poly::P5 => 5,
            Poly::P7 => 7,
        };
        match plan {
            PowPlan::Exact { .. } => pow::<EXACT, 0>(plan, flush, x),
            PowPlan::Squaring { .. } => pow::<SQUARING, 0>(plan, flush, x),
            PowPlan::Poly { poly, .. } => match deg(poly) {
                3 => pow::<POLY, 3>(plan, flush, x),
                5 => pow::<POLY, 5>(plan, flush, x),
                _ => pow::<POLY, 7>(plan, flush, x),
            },
            PowPlan::Split { poly, .. } => match deg(poly) {
                3 => pow::<SPLIT, 3>(plan, flush, x),
                5 => pow::<SPLIT, 5>(plan, flush, x),
                _ => pow::<SPLIT, 7>(plan, flush, x),
            },
        }
    }

    #[test]
    fn the_avx512_lobe_power_meets_each_strategys_bound() {
        // Estrin's scheme with fused multiply-adds rounds differently from the scalar Horner
        // polynomials, and the squarings run in another order: the same bound must hold.
        if !Level::Avx512.is_supported() {
            std::eprintln!("AVX-512 not available: nothing to check");
            return;
        }
        for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let (e, x, s) = worst_over_domain(p, |s, xs| {
                let plan = p.plan(s);
                // SAFETY: `Level::Avx512.is_supported()` checked AVX-512F/VL, AVX2 and FMA above.
                let r = unsafe { pow_any(plan, flush_below(plan), must_cast(*xs)) };
                must_cast(r)
            });
            assert!(
                e <= p.max_relative_error() as f64,
                "{p:?}: err {e:e} at x = {x:e}, s = {s:e}"
            );
        }
    }
}
