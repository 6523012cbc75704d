//! The portable batch kernel: one source, 16 points at a time, compiled for the `Portable`,
//! `Sse2` and `Avx2` levels, and for `Avx512` where a call has per-point inputs (a G-buffer's
//! surfaces or visibilities). The `Avx512` level's plain calls run the intrinsics kernel in
//! `avx512.rs`, which follows the same algorithm.
//!
//! Every quantity is a `[f32; 16]` and every operation a loop over the 16 lanes with no
//! cross-lane dependency, so LLVM turns each into two AVX2 instructions or four SSE2 ones. Work per point and light, with unnormalised `L = P_light − p`, `V = eye − p`:
//!
//! ```text
//! N = n·rsqrt(n·n),  V̂ = V·rsqrt(V·V),  L̂ = L·rsqrt(L·L),  d = (L·L)·rsqrt(L·L)
//! f     = 1 / max(c + d(l + q d), MIN_DENOMINATOR)
//! Phong: R·V = 2(N·L̂)(N·V̂) − L̂·V̂                      (no reflect vector)
//! Blinn: (N·H)² = max(N·L̂ + N·V̂, 0)² / (2 + 2 L̂·V̂)    (no halfway vector, no sqrt)
//! ```
//!
//! The colours follow the saturation rule in the module docs of `batch`: per channel three sums
//! over the lights, `Ia + Σ f·La`, `Σ f·max(N·L, 0)·Ld` and `Σ min(f·w, MAX)·Ls` (`w` the gated,
//! normalised specular lobe), each saturated and then multiplied by the material's colour once.
//!
//! Among the levels that compile this source, the inverse square root is the one level-specific
//! operation (passed in as `rsqrt`). Points the
//! fast path cannot represent (a squared norm outside `[1e-30, 1e30]`: a zero or huge normal, the
//! viewer or a light at the point, huge coordinates) are flagged and shaded again by the scalar
//! [`shade`](crate::shade), so the batch has its degenerate-case results exactly.

use glam::Vec3;

use super::prepare::{BatchLight, BatchModel, LaneLight, LaneModel, Lobe};
use super::soa::{SoaRgb, SoaVec3};
use crate::attenuation::{Attenuation, FlatAttenuation};
use crate::gate::SpecularGate;
use crate::material::Material;
use crate::math;
use crate::pow::{Poly, PowPlan, auto_split, lobe_pow, poly_pow};
use crate::shade::{Scene, Viewer};
use crate::shader::Shader;
use crate::surface::Surface;
use crate::visibility::VisibilityFn;

/// Lanes per step.
pub(crate) const W: usize = 16;
/// One value per lane.
pub(crate) type Lanes = [f32; W];

/// Squared norms in this range take the fast path (the same range `normalize_or_zero` handles
/// directly).
const LO: f32 = 1.0e-30;
const HI: f32 = 1.0e30;

/// `[e(0), e(1), …, e(15)]`.
macro_rules! lanes {
    (|$i:ident| $e:expr) => {{
        let mut r = [0.0f32; W];
        for $i in 0..W {
            r[$i] = $e;
        }
        r
    }};
}

/// The viewer as the kernel sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ViewK {
    At(Vec3),
    /// A unit direction (specular is off for a zero one).
    Infinite(Vec3),
}

/// A light's kernel form with its colours. In general the material's colours are applied once
/// per point, to the sums over the lights (see [`chunk`]), as [`shade`](crate::shade) applies
/// them; when nothing can overflow ([`Setup::folded`]) both kernels use the products instead, which give the same values up to rounding with a third of the accumulators.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreparedLight {
    pub(crate) lane: LaneLight,
    /// `La`.
    pub(crate) la: Vec3,
    /// `Ld · diffuse scale` (the scale is 1 or `1/π`, so this cannot overflow).
    pub(crate) ld: Vec3,
    /// `Ls`. The specular scale, which can be huge, is applied per lane and clamped.
    pub(crate) ls: Vec3,
    /// `Ka ⊙ La`, `Kd ⊙ Ld · diffuse scale` and `Ks ⊙ Ls · specular scale`: finite, and used,
    /// only when the call is [`folded`](Setup::folded).
    pub(crate) ka: Vec3,
    pub(crate) kd: Vec3,
    pub(crate) ks: Vec3,
    /// A [`LaneLight::Falloff`]'s attenuation as one formula (`Attenuation::factor`'s own
    /// operations, bit for bit); unused by the other kinds.
    pub(crate) flat: FlatAttenuation,
}

/// Lights prepared once per call (more are prepared per chunk).
pub(crate) const PREPARED: usize = 8;

/// The kernel form of `light` (an ambient-only light for a form the kernel does not handle, which
/// callers rule out first).
#[inline]
pub(crate) fn prepare_light<L: BatchLight>(
    light: &L,
    material: &Material,
    lm: &LaneModel,
) -> PreparedLight {
    let colors = light.colors();
    let ld = colors.diffuse() * lm.diffuse_scale;
    // The folded products, formed in f64 and rounded once: `Ls ⊙ Ks · scale` in f32 could
    // overflow in its first product although the whole is finite (`cannot_overflow` checks the
    // whole). Unfolded calls never read them.
    let product = |a: Vec3, b: Vec3, k: f32| {
        let c = |x: f32, y: f32| (f64::from(x) * f64::from(y) * f64::from(k)) as f32;
        Vec3::new(c(a.x, b.x), c(a.y, b.y), c(a.z, b.z))
    };
    let lane = light.lane_light().unwrap_or(LaneLight::AmbientOnly);
    PreparedLight {
        lane,
        flat: match lane {
            LaneLight::Falloff { attenuation, .. } => attenuation.flat(),
            _ => Attenuation::None.flat(),
        },
        la: colors.ambient(),
        ld,
        ls: colors.specular(),
        ka: product(colors.ambient(), material.ambient(), 1.0),
        kd: product(ld, material.diffuse(), 1.0),
        ks: product(colors.specular(), material.specular(), lm.specular_scale),
    }
}

/// The most a light's attenuation factor can be: 1, or `1/max(c, MIN_DENOMINATOR)` (the
/// denominator `c + l·d + q·d²` is at least `c`).
fn factor_max(lane: &LaneLight) -> f64 {
    match *lane {
        LaneLight::Point {
            coefficients: [c, _, _],
            ..
        } => 1.0 / f64::from(c.max(Attenuation::MIN_DENOMINATOR)),
        // Every form is largest at distance 0; a spot factor is at most 1.
        LaneLight::Falloff { attenuation, .. } => f64::from(attenuation.factor(0.0)),
        _ => 1.0,
    }
}

/// Whether no sum, product or total of the saturation rule can come near `f32::MAX` for any
/// point: every lobe and cosine is at most 1 (plus rounding), so each sum is at most its lights'
/// largest factor times their colours. Then the products `Ka ⊙ La` etc. can be summed instead
/// (half of `f32::MAX` leaves room for rounding).
fn cannot_overflow<L: BatchLight>(
    scene: &Scene<'_, L>,
    material: &Material,
    lm: &LaneModel,
) -> bool {
    let d3 = |v: Vec3| [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
    let (mut a, mut d, mut s) = (
        d3(crate::light::sanitize_colour(scene.ambient)),
        [0.0; 3],
        [0.0; 3],
    );
    let spec = if lm.lobe == Lobe::None {
        0.0
    } else {
        f64::from(lm.specular_scale)
    };
    let (ka, kd, ks, ke) = (
        d3(material.ambient()),
        d3(material.diffuse()),
        d3(material.specular()),
        d3(material.emission()),
    );
    let half = 0.5 * f64::from(math::MAX);
    for light in scene.lights {
        let f = light.lane_light().map_or(1.0, |l| factor_max(&l));
        let c = light.colors();
        let (la, ld, ls) = (d3(c.ambient()), d3(c.diffuse()), d3(c.specular()));
        for i in 0..3 {
            a[i] += f * la[i];
            d[i] += f * ld[i];
            s[i] += f * spec * ls[i];
            // The folded kernel multiplies each light's colours by the material's before the
            // factor: those products must stay finite even where the factor would shrink them.
            if ka[i] * la[i] >= half || kd[i] * ld[i] >= half || ks[i] * spec * ls[i] >= half {
                return false;
            }
        }
    }
    // The sums themselves too: the rule saturates a sum before the material multiplies it, so a
    // sum past `f32::MAX` under a reflectance below 1 must not be folded into the products.
    (0..3).all(|i| {
        a[i] < half
            && d[i] < half
            && s[i] < half
            && ka[i] * a[i] + kd[i] * d[i] + ks[i] * s[i] + ke[i] < half
    })
}

/// Everything constant over one call.
pub(crate) struct Setup<'a, M, L> {
    pub(crate) model: &'a M,
    pub(crate) material: &'a Material,
    pub(crate) scene: &'a Scene<'a, L>,
    pub(crate) lm: LaneModel,
    pub(crate) plan: PowPlan,
    /// Bases below this give a lobe below 2^-100; they are flushed to 0 before squaring so no
    /// subnormal is ever produced.
    pub(crate) flush: f32,
    pub(crate) view: ViewK,
    pub(crate) specular_on: bool,
    /// Whether the specular weight is scaled (a normalised model), and so must be clamped.
    pub(crate) scaled: bool,
    /// Whether nothing can overflow in this call, so the portable kernel may sum the products of
    /// light and material colours (three accumulators, not nine: the difference is rounding).
    pub(crate) folded: bool,
    /// `Ia`, sanitised: where the ambient sum starts.
    pub(crate) ambient: Vec3,
    /// `Ke + Ka ⊙ Ia`: where a folded call's single sum starts.
    pub(crate) base: Vec3,
    /// The first lights, prepared; all of them when `all_prepared`.
    pub(crate) prepared: [PreparedLight; PREPARED],
    pub(crate) all_prepared: bool,
    /// Whether a light is a [`LaneLight::Falloff`], which only this portable kernel evaluates
    /// (the `Avx512` level then runs it instead of the intrinsics kernel).
    pub(crate) portable_only: bool,
}

impl<M, L: BatchLight> Setup<'_, M, L> {
    /// Light `j`, prepared.
    #[inline(always)]
    pub(crate) fn light(&self, j: usize) -> PreparedLight {
        if self.all_prepared {
            self.prepared[j % PREPARED]
        } else {
            prepare_light(&self.scene.lights[j], self.material, &self.lm)
        }
    }
}

impl<'a, M: BatchModel, L: BatchLight> Setup<'a, M, L> {
    pub(crate) fn new(model: &'a M, material: &'a Material, scene: &'a Scene<'a, L>) -> Self {
        let lm = model.lane_model(material.shininess());
        let plan = lm.pow.plan(lm.exponent);
        let flush = flush_below(plan);
        let view = match scene.viewer {
            Viewer::At(eye) => ViewK::At(eye),
            Viewer::Infinite(d) => ViewK::Infinite(crate::normalize_or_zero(d)),
        };
        let specular_on =
            lm.lobe != Lobe::None && !matches!(view, ViewK::Infinite(v) if v == Vec3::ZERO);
        let mut prepared = [PreparedLight {
            lane: LaneLight::AmbientOnly,
            la: Vec3::ZERO,
            ld: Vec3::ZERO,
            ls: Vec3::ZERO,
            ka: Vec3::ZERO,
            kd: Vec3::ZERO,
            ks: Vec3::ZERO,
            flat: Attenuation::None.flat(),
        }; PREPARED];
        for (slot, light) in prepared.iter_mut().zip(scene.lights) {
            *slot = prepare_light(light, material, &lm);
        }
        let folded = cannot_overflow(scene, material, &lm);
        let ambient = crate::light::sanitize_colour(scene.ambient);
        let sat = Vec3::splat(math::MAX);
        let portable_only = scene
            .lights
            .iter()
            .any(|l| matches!(l.lane_light(), Some(LaneLight::Falloff { .. })));
        Setup {
            prepared,
            all_prepared: scene.lights.len() <= PREPARED,
            portable_only,
            model,
            material,
            scene,
            lm,
            plan,
            flush,
            view,
            specular_on,
            scaled: lm.specular_scale != 1.0,
            folded,
            ambient,
            base: (material.emission() + (ambient * material.ambient()).min(sat)).min(sat),
        }
    }
}

/// The base below which a plan's repeated squaring would give a lobe below `2⁻¹⁰⁰`: such bases
/// are set to 0 first, so no subnormal is ever produced (0 when the plan does not square).
pub(crate) fn flush_below(plan: PowPlan) -> f32 {
    let n = match plan {
        PowPlan::Squaring { n } | PowPlan::Split { n, .. } => n,
        _ => 0,
    };
    if n > 0 {
        math::powf(2.0, -100.0 / n as f32)
    } else {
        0.0
    }
}

#[inline(always)]
fn load(s: &[f32], i: usize) -> Lanes {
    let mut a = [0.0f32; W];
    a.copy_from_slice(&s[i..i + W]);
    a
}

#[inline(always)]
pub(crate) fn load_tail(s: &[f32], i: usize, count: usize) -> Lanes {
    let mut a = [0.0f32; W];
    a[..count].copy_from_slice(&s[i..i + count]);
    a
}

/// `x^n` per lane by repeated squaring, bases below `flush` first set to 0.
#[inline(always)]
fn squaring_lanes(x: &Lanes, flush: f32, n: u32) -> Lanes {
    let mut base = lanes!(|i| if x[i] < flush { 0.0 } else { x[i] });
    let mut acc = [1.0f32; W];
    let mut e = n;
    while e > 0 {
        if e & 1 == 1 {
            acc = lanes!(|i| acc[i] * base[i]);
        }
        base = lanes!(|i| base[i] * base[i]);
        e >>= 1;
    }
    acc
}

/// `exp2(s·log2 x)` per lane.
#[inline(always)]
fn poly_lanes(p: Poly, x: &Lanes, s: f32) -> Lanes {
    match p {
        Poly::P3 => lanes!(|i| poly_pow(Poly::P3, x[i], s)),
        Poly::P5 => lanes!(|i| poly_pow(Poly::P5, x[i], s)),
        Poly::P7 => lanes!(|i| poly_pow(Poly::P7, x[i], s)),
    }
}

/// `x^s` per lane for bases in `[0, 1]`; 0 for `x ≤ 0`.
#[inline(always)]
fn pow_lanes(plan: PowPlan, flush: f32, x: Lanes) -> Lanes {
    let r = match plan {
        PowPlan::Exact { s } => lanes!(|i| lobe_pow(x[i], s)),
        PowPlan::Squaring { n } => squaring_lanes(&x, flush, n),
        PowPlan::Poly { s, poly } => poly_lanes(poly, &x, s),
        PowPlan::Split { n, frac, poly } => {
            let a = squaring_lanes(&x, flush, n);
            let b = poly_lanes(poly, &x, frac);
            lanes!(|i| a[i] * b[i])
        }
    };
    lanes!(|i| if x[i] > 0.0 { r[i] } else { 0.0 })
}

/// The inputs of a call beyond positions and normals, as slices over the call's points: a
/// G-buffer's per-point surface, 8-bit sRGB albedo and per-light visibility (see
/// `shade_gbuffer`).
#[derive(Clone, Copy, Default)]
pub(crate) struct PointInputs<'a> {
    /// `Ka` (x, y, z), `Kd`, `Ks`, then the shininess: ten slices.
    pub(crate) surface: Option<[&'a [f32]; 10]>,
    /// 8-bit sRGB texels whose decoded colour multiplies `Ka` and `Kd` (of `surface`, or of
    /// `base` without one).
    pub(crate) albedo: Option<&'a [[u8; 4]]>,
    /// The call's material as the ten surface values, for an albedo without a surface.
    pub(crate) base: [f32; 10],
    /// Light `j`'s visibility at point `i` is `visibility[j * stride + i]`.
    pub(crate) visibility: Option<(&'a [f32], usize)>,
}

impl PointInputs<'_> {
    /// The same inputs from point `start` on.
    pub(crate) fn from(&self, start: usize) -> Self {
        PointInputs {
            surface: self.surface.map(|s| s.map(|a| &a[start..])),
            albedo: self.albedo.map(|a| &a[start..]),
            base: self.base,
            visibility: self.visibility.map(|(v, stride)| (&v[start..], stride)),
        }
    }

    /// Whether the points have surfaces of their own (a surface or an albedo).
    pub(crate) fn per_point_surface(&self) -> bool {
        self.surface.is_some() || self.albedo.is_some()
    }

    /// Light `j`'s visibilities at points `i..i + count` (1 without shadows).
    #[inline(always)]
    pub(crate) fn visibility(&self, j: usize, i: usize, count: usize) -> Lanes {
        match self.visibility {
            Some((v, stride)) => {
                let mut a = [1.0f32; W];
                a[..count].copy_from_slice(&v[j * stride + i..j * stride + i + count]);
                a
            }
            None => [1.0; W],
        }
    }

    /// The raw surface values at points `i..i + count`: the surface's (or the material's), with
    /// `Ka` and `Kd` multiplied by the decoded albedo where there is one. `None` without either.
    #[inline(always)]
    pub(crate) fn surface(&self, i: usize, count: usize) -> Option<[Lanes; 10]> {
        let mut raw = match self.surface {
            Some(slices) => {
                let mut raw = [[0.0f32; W]; 10];
                for (r, a) in raw.iter_mut().zip(slices) {
                    r[..count].copy_from_slice(&a[i..i + count]);
                }
                raw
            }
            None if self.albedo.is_some() => self.base.map(|b| [b; W]),
            None => return None,
        };
        if let Some(albedo) = self.albedo {
            for (lane, texel) in albedo[i..i + count].iter().enumerate() {
                for c in 0..3 {
                    let x = crate::srgb8_to_linear(texel[c]);
                    raw[c][lane] *= x;
                    raw[3 + c][lane] *= x;
                }
            }
        }
        Some(raw)
    }
}

/// A chunk's per-point surface, sanitised as [`Shader::shade_surface`] does: reflectances, and
/// each lane's specular scale and `Auto` split of its exponent (`auto_split`).
pub(crate) struct SurfaceLanes {
    ka: [Lanes; 3],
    kd: [Lanes; 3],
    ks: [Lanes; 3],
    scale: Lanes,
    whole: [u32; W],
    frac: Lanes,
}

impl SurfaceLanes {
    #[inline(always)]
    fn new(lm: &LaneModel, raw: &[Lanes; 10]) -> Self {
        let clean = |c: &Lanes| lanes!(|i| math::clamp_or_lo(c[i], 0.0, math::MAX));
        let s = clean(&raw[9]);
        let e = if lm.lobe == Lobe::Blinn {
            lanes!(|i| 0.5 * s[i])
        } else {
            s
        };
        let norm = lm.normalization;
        let scale = match lm.lobe {
            Lobe::None => [0.0; W],
            _ if !norm.is_normalized() => [1.0; W],
            Lobe::Phong => lanes!(|i| norm.phong_factor(s[i])),
            Lobe::Blinn => lanes!(|i| norm.blinn_factor(s[i])),
        };
        let mut whole = [0u32; W];
        let mut frac = [0.0f32; W];
        for i in 0..W {
            (whole[i], frac[i]) = auto_split(e[i]);
        }
        SurfaceLanes {
            ka: [clean(&raw[0]), clean(&raw[1]), clean(&raw[2])],
            kd: [clean(&raw[3]), clean(&raw[4]), clean(&raw[5])],
            ks: [clean(&raw[6]), clean(&raw[7]), clean(&raw[8])],
            scale,
            whole,
            frac,
        }
    }
}

/// Bases and partial products below this are set to 0 in [`auto_pow_lanes`]: a product of two
/// kept values is then at least `2⁻¹²⁶`, never subnormal, and a lobe that loses them is below
/// `2⁻⁶³` (an absolute error far under every tolerance of the batch).
const LANE_FLUSH: f32 = 1.0 / (1u64 << 63) as f32;

/// `PowStrategy::Auto`'s `x^e` with an exponent per lane (`surface.whole`, `surface.frac`):
/// squaring where it is whole, by the ladder of `pow_u32_fixed` (the same products in the same
/// order), the degree-7 polynomial elsewhere; 0 for `x ≤ 0`. The ladder runs only over the bits
/// some lane has, and the polynomial only when some lane needs it: a chunk of fractional
/// shininesses squares nothing.
#[inline(always)]
fn auto_pow_lanes(x: &Lanes, surface: &SurfaceLanes) -> Lanes {
    let flush = |v: f32| if v < LANE_FLUSH { 0.0 } else { v };
    let whole = &surface.whole;
    let steps = 32 - whole.iter().fold(0u32, |a, &n| a | n).leading_zeros();
    let mut acc = [1.0f32; W];
    let mut base = lanes!(|i| flush(x[i]));
    for k in 0..steps {
        acc = lanes!(|i| if (whole[i] >> k) & 1 == 1 {
            flush(acc[i] * base[i])
        } else {
            acc[i]
        });
        base = lanes!(|i| if whole[i] >> (k + 1) != 0 {
            flush(base[i] * base[i])
        } else {
            base[i]
        });
    }
    let frac = &surface.frac;
    let poly = if frac.iter().fold(0u32, |a, f| a | f.to_bits()) != 0 {
        lanes!(|i| poly_pow(Poly::P7, if x[i] > 0.0 { x[i] } else { 1.0 }, frac[i]))
    } else {
        [0.0; W]
    };
    lanes!(|i| if x[i] > 0.0 {
        if frac[i] != 0.0 { poly[i] } else { acc[i] }
    } else {
        0.0
    })
}

/// `min(x, f32::MAX)`.
#[inline(always)]
fn saturate(x: f32) -> f32 {
    math::min_or(x, math::MAX)
}

/// `q − p` per lane and its squared length; lanes whose squared length leaves `[LO, HI]` are
/// marked in `bad` for the scalar path.
#[inline(always)]
fn offset_to(q: Vec3, p: [&Lanes; 3], bad: &mut Lanes) -> ([Lanes; 3], Lanes) {
    let [px, py, pz] = p;
    let dx = lanes!(|i| q.x - px[i]);
    let dy = lanes!(|i| q.y - py[i]);
    let dz = lanes!(|i| q.z - pz[i]);
    let ll = lanes!(|i| dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i]);
    *bad = lanes!(|i| if ll[i] >= LO && ll[i] <= HI {
        bad[i]
    } else {
        1.0
    });
    ([dx, dy, dz], ll)
}

/// `d · inv` per component and lane.
#[inline(always)]
fn scaled([dx, dy, dz]: &[Lanes; 3], inv: &Lanes) -> (Lanes, Lanes, Lanes) {
    (
        lanes!(|i| dx[i] * inv[i]),
        lanes!(|i| dy[i] * inv[i]),
        lanes!(|i| dz[i] * inv[i]),
    )
}

/// Below this `2 + 2 L·V` (an angle between `L` and `V` above about 174°) the Blinn-Phong lane is
/// re-shaded by the scalar path: the cosine form's relative error there, about
/// `2e-7 / (2 + 2 L·V)` in `(N·H)²`, times `s/2` in the lobe, would otherwise reach the 8-bit
/// level at high shininess. For random directions about 0.25% of lanes are affected.
pub(super) const BLINN_DEN_MIN: f32 = 1e-2;

/// Shades 16 points. Returns the colours and which lanes need the scalar path. `FOLDED` is
/// [`Setup::folded`]: sum the products of light and material colours (nothing can overflow)
/// instead of the three sums of the saturation rule (never with a per-point `surface`).
/// `visibility`, the call's inputs with this chunk's first point and count, gives each light's
/// visibility per lane (clamped to `[0, 1]` here, NaN read as 0), which scales the light's
/// diffuse and specular parts, not its ambient part. (Plain functions and options, not closures:
/// a closure is not always inlined, and out of line it would lose the level's target features.)
#[inline(always)]
fn chunk<M, L, R, const FOLDED: bool>(
    k: &Setup<'_, M, L>,
    p: &[Lanes; 3],
    n: &[Lanes; 3],
    rsqrt: &R,
    surface: Option<&SurfaceLanes>,
    visibility: Option<(&PointInputs<'_>, usize, usize)>,
) -> [Lanes; 4]
where
    M: BatchModel,
    L: BatchLight,
    R: Fn(Lanes) -> Lanes,
{
    let [px, py, pz] = p;
    let [nx, ny, nz] = n;
    let nn = lanes!(|i| nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i]);
    // 1.0 marks a lane for the scalar path (an f32 mask keeps every lane loop vectorisable).
    let mut bad = lanes!(|i| if nn[i] >= LO && nn[i] <= HI { 0.0 } else { 1.0 });
    let inv_n = rsqrt(nn);
    let ux = lanes!(|i| nx[i] * inv_n[i]);
    let uy = lanes!(|i| ny[i] * inv_n[i]);
    let uz = lanes!(|i| nz[i] * inv_n[i]);

    let (vx, vy, vz) = match k.view {
        ViewK::At(e) => {
            let (d, vv) = offset_to(e, [px, py, pz], &mut bad);
            scaled(&d, &rsqrt(vv))
        }
        ViewK::Infinite(v) => ([v.x; W], [v.y; W], [v.z; W]),
    };
    let nv = lanes!(|i| ux[i] * vx[i] + uy[i] * vy[i] + uz[i] * vz[i]);

    // Per channel, three sums over the lights, each multiplied by the material's colour once at
    // the end (see the module docs' saturation rule):
    //   amb = Ia + Σ f·La,   dif = Σ f·max(N·L, 0)·Ld,   spe = Σ min(f·ws, MAX)·Ls.
    // Folded, `amb` alone holds Ke + Ka⊙Ia + Σ f·(Ka⊙La + max(N·L, 0)·Kd⊙Ld + ws·Ks⊙Ls).
    let start = if FOLDED { k.base } else { k.ambient };
    let mut amb = [[start.x; W], [start.y; W], [start.z; W]];
    let mut dif = [[0.0f32; W]; 3];
    let mut spe = [[0.0f32; W]; 3];
    let lm = &k.lm;
    for j in 0..k.scene.lights.len() {
        let light = k.light(j);
        let (la, ld, ls) = if FOLDED {
            (light.ka, light.kd, light.ks)
        } else {
            (light.la, light.ld, light.ls)
        };
        let (la, ld, ls) = (la.to_array(), ld.to_array(), ls.to_array());
        let (lx, ly, lz, att) = match light.lane {
            LaneLight::AmbientOnly => {
                for c in 0..3 {
                    amb[c] = lanes!(|i| amb[c][i] + la[c]);
                }
                continue;
            }
            LaneLight::Directional(d) => ([d.x; W], [d.y; W], [d.z; W], [1.0f32; W]),
            LaneLight::Point {
                position: q,
                coefficients: [c0, c1, c2],
            } => {
                let (offset, ll) = offset_to(q, [px, py, pz], &mut bad);
                let inv = rsqrt(ll);
                let d = lanes!(|i| ll[i] * inv[i]);
                let den = lanes!(|i| c0 + d[i] * (c1 + c2 * d[i]));
                // A denominator past f32::MAX (coefficients near it) is evaluated in f64 by
                // `Attenuation::factor`: such lanes go to the scalar path.
                bad = lanes!(|i| if den[i] < f32::INFINITY { bad[i] } else { 1.0 });
                let att = lanes!(|i| 1.0 / math::max_or(den[i], Attenuation::MIN_DENOMINATOR));
                let (lx, ly, lz) = scaled(&offset, &inv);
                (lx, ly, lz, att)
            }
            LaneLight::Falloff {
                position: q, spot, ..
            } => {
                // `LightSource::sample`'s own operations: the direction and distance of
                // `direction_and_distance` (an exact square root, then `v · (1/d)`), the factor
                // of `Attenuation::factor` (as `FlatAttenuation`) times the spot factor.
                let (offset, ll) = offset_to(q, [px, py, pz], &mut bad);
                let d = lanes!(|i| math::sqrt(ll[i]));
                let (lx, ly, lz) = scaled(&offset, &lanes!(|i| 1.0 / d[i]));
                let flat = light.flat;
                let att = lanes!(|i| flat.factor(d[i]));
                let att = match spot {
                    Some(spot) => lanes!(|i| {
                        let c = spot.spot_factor(Vec3::new(lx[i], ly[i], lz[i]));
                        if c > 0.0 {
                            (att[i] * c).min(math::MAX)
                        } else {
                            0.0
                        }
                    }),
                    None => att,
                };
                (lx, ly, lz, att)
            }
        };
        let nl = lanes!(|i| ux[i] * lx[i] + uy[i] * ly[i] + uz[i] * lz[i]);
        // The visibility scales the diffuse and specular parts (a constant 1 without shadows,
        // which the compiler removes).
        let attv = match visibility {
            Some((inputs, i, count)) => {
                let vis = inputs.visibility(j, i, count);
                lanes!(|i| att[i] * math::clamp_or_lo(vis[i], 0.0, 1.0))
            }
            None => att,
        };
        // f and f·max(N·L, 0) are finite (f ≤ 1/MIN_DENOMINATOR), and so is every colour: no
        // product below is 0·∞, and the sums of terms ≥ 0 can reach +∞ but never NaN.
        let wd = lanes!(|i| attv[i] * math::max_or(nl[i], 0.0));
        for c in 0..3 {
            if FOLDED {
                amb[c] = lanes!(|i| amb[c][i] + att[i] * la[c] + wd[i] * ld[c]);
            } else {
                amb[c] = lanes!(|i| amb[c][i] + att[i] * la[c]);
                dif[c] = lanes!(|i| dif[c][i] + wd[i] * ld[c]);
            }
        }
        if !k.specular_on {
            continue;
        }
        let lv = lanes!(|i| lx[i] * vx[i] + ly[i] * vy[i] + lz[i] * vz[i]);
        let base = match lm.lobe {
            Lobe::Blinn => lanes!(|i| {
                let s = math::max_or(nl[i] + nv[i], 0.0);
                let den = 2.0 + 2.0 * lv[i];
                if den > 1e-12 {
                    math::min_or(s * s / den, 1.0)
                } else {
                    0.0
                }
            }),
            _ => lanes!(|i| math::min_or(math::max_or(2.0 * nl[i] * nv[i] - lv[i], -1.0), 1.0)),
        };
        if let Lobe::Blinn = lm.lobe {
            // Near L = −V the cosine form's 2 + 2 L·V has lost its digits (docs/accuracy.md);
            // those rare lanes go to the scalar path, which uses ‖L+V‖² from the vectors.
            bad = lanes!(|i| if 2.0 + 2.0 * lv[i] >= BLINN_DEN_MIN {
                bad[i]
            } else {
                1.0
            });
        }
        let lobe = match surface {
            Some(sf) => auto_pow_lanes(&base, sf),
            None => pow_lanes(k.plan, k.flush, base),
        };
        let ws = match lm.gate {
            SpecularGate::Step => lanes!(|i| if nl[i] > 0.0 { attv[i] * lobe[i] } else { 0.0 }),
            SpecularGate::Cosine => lanes!(|i| attv[i] * math::max_or(nl[i], 0.0) * lobe[i]),
            SpecularGate::None => lanes!(|i| attv[i] * lobe[i]),
        };
        if FOLDED {
            // The scale is in `ks`, and nothing overflows.
            for c in 0..3 {
                amb[c] = lanes!(|i| amb[c][i] + ws[i] * ls[c]);
            }
            continue;
        }
        // A normalisation factor can be as large as f32::MAX: f·factor·lobe is clamped there (as
        // `shade` clamps its weight) before it meets a colour, so a zero lobe stays 0.
        let ws = if let Some(sf) = surface {
            lanes!(|i| math::min_or(ws[i] * sf.scale[i], math::MAX))
        } else if k.scaled {
            let scale = lm.specular_scale;
            lanes!(|i| math::min_or(ws[i] * scale, math::MAX))
        } else {
            ws
        };
        for c in 0..3 {
            spe[c] = lanes!(|i| spe[c][i] + ws[i] * ls[c]);
        }
    }
    if FOLDED {
        return [
            lanes!(|i| math::min_or(amb[0][i], math::MAX)),
            lanes!(|i| math::min_or(amb[1][i], math::MAX)),
            lanes!(|i| math::min_or(amb[2][i], math::MAX)),
            bad,
        ];
    }
    let ke = k.material.emission().to_array();
    // Each sum saturates at f32::MAX before the material's colour multiplies it; the total
    // saturates again (`shade`'s order: ambient + diffuse + specular + emission). A loop, not a
    // closure per channel: a closure may be left out of line, without the level's features.
    let mut rgb = [[0.0f32; W]; 3];
    for (c, out) in rgb.iter_mut().enumerate() {
        let (ka, kd, ks) = match surface {
            Some(sf) => (sf.ka[c], sf.kd[c], sf.ks[c]),
            None => (
                [k.material.ambient()[c]; W],
                [k.material.diffuse()[c]; W],
                [k.material.specular()[c]; W],
            ),
        };
        *out = lanes!(|i| saturate(
            saturate(ka[i] * saturate(amb[c][i]))
                + saturate(kd[i] * saturate(dif[c][i]))
                + saturate(ks[i] * saturate(spe[c][i]))
                + ke[c]
        ));
    }
    [rgb[0], rgb[1], rgb[2], bad]
}

/// Re-shades the flagged lanes with the scalar path.
#[cold]
#[inline(never)]
pub(crate) fn fixup<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    p: [Lanes; 3],
    n: [Lanes; 3],
    mut out: [Lanes; 4],
    count: usize,
) -> [Lanes; 4] {
    for i in 0..count {
        if out[3][i] != 0.0 {
            let c = crate::shade(
                k.model,
                k.material,
                k.scene,
                Vec3::new(p[0][i], p[1][i], p[2][i]),
                Vec3::new(n[0][i], n[1][i], n[2][i]),
            )
            .total();
            out[0][i] = c.x;
            out[1][i] = c.y;
            out[2][i] = c.z;
        }
    }
    out
}

/// [`fixup`] for a call with per-point inputs: [`Shader::shade_surface`] (which sanitises the raw
/// surface) with the point's visibilities, point `i` of `inputs` being lane `i`.
#[cold]
#[inline(never)]
fn fixup_inputs<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    p: [Lanes; 3],
    n: [Lanes; 3],
    inputs: &PointInputs<'_>,
    mut out: [Lanes; 4],
    count: usize,
) -> [Lanes; 4] {
    let raw = inputs.surface(0, count);
    let shader = Shader::for_one_point(k.model, k.material, k.scene);
    for i in 0..count {
        if out[3][i] != 0.0 {
            let surface = match raw {
                Some(r) => Surface {
                    ambient: Vec3::new(r[0][i], r[1][i], r[2][i]),
                    diffuse: Vec3::new(r[3][i], r[4][i], r[5][i]),
                    specular: Vec3::new(r[6][i], r[7][i], r[8][i]),
                    shininess: r[9][i],
                },
                None => Surface::of(k.material),
            };
            let vis = VisibilityFn(|j| inputs.visibility(j, i, 1)[0]);
            let c = shader
                .shade_surface(
                    Vec3::new(p[0][i], p[1][i], p[2][i]),
                    Vec3::new(n[0][i], n[1][i], n[2][i]),
                    &surface,
                    vis,
                )
                .total();
            out[0][i] = c.x;
            out[1][i] = c.y;
            out[2][i] = c.z;
        }
    }
    out
}

/// One chunk of [`run_with`]: its points `i..i + count` shaded, the lanes the scalar path must
/// redo flagged.
#[inline(always)]
#[allow(
    clippy::too_many_arguments,
    reason = "one argument per lane array the kernel reads"
)]
fn shade_chunk<M, L, R, const FOLDED: bool, const SURFACE: bool, const VISIBILITY: bool>(
    k: &Setup<'_, M, L>,
    p: &[Lanes; 3],
    n: &[Lanes; 3],
    rsqrt: &R,
    inputs: &PointInputs<'_>,
    i: usize,
    count: usize,
) -> [Lanes; 4]
where
    M: BatchModel,
    L: BatchLight,
    R: Fn(Lanes) -> Lanes,
{
    let raw = if SURFACE {
        inputs.surface(i, count)
    } else {
        None
    };
    // A match, not `Option::map`: a closure may be left out of line, without the level's features.
    #[allow(
        clippy::manual_map,
        reason = "a closure may be left out of line, without the level's target features"
    )]
    let surface = match raw {
        Some(raw) => Some(SurfaceLanes::new(&k.lm, &raw)),
        None => None,
    };
    let visibility = if VISIBILITY {
        Some((inputs, i, count))
    } else {
        None
    };
    chunk::<M, L, R, FOLDED>(k, p, n, rsqrt, surface.as_ref(), visibility)
}

/// The flagged lanes of a chunk re-shaded: [`fixup`], or [`fixup_inputs`] with per-point inputs.
#[inline(always)]
fn fix<M: BatchModel, L: BatchLight>(
    k: &Setup<'_, M, L>,
    p: [Lanes; 3],
    n: [Lanes; 3],
    inputs: Option<&PointInputs<'_>>,
    i: usize,
    c: [Lanes; 4],
    count: usize,
) -> [Lanes; 4] {
    match inputs {
        Some(inputs) => fixup_inputs(k, p, n, &inputs.from(i), c, count),
        None => fixup(k, p, n, c, count),
    }
}

/// Shades the common prefix of all slices with the given inverse square root; returns its length.
#[inline(always)]
pub(crate) fn run<M, L, R>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    out: SoaRgb<'_>,
    rsqrt: R,
) -> usize
where
    M: BatchModel,
    L: BatchLight,
    R: Fn(Lanes) -> Lanes,
{
    let none = PointInputs::default();
    if k.folded {
        run_with::<M, L, R, true, false, false>(k, pos, nor, &none, out, rsqrt)
    } else {
        run_with::<M, L, R, false, false, false>(k, pos, nor, &none, out, rsqrt)
    }
}

/// [`run`] with per-point `inputs` over at least as many points (the caller checks). Each
/// combination of inputs is its own instance of the loop; a level compiles this in a function of
/// its own, so the plain calls' function stays the size it was.
#[inline(always)]
pub(crate) fn run_inputs<M, L, R>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
    rsqrt: R,
) -> usize
where
    M: BatchModel,
    L: BatchLight,
    R: Fn(Lanes) -> Lanes,
{
    match (inputs.per_point_surface(), inputs.visibility.is_some()) {
        (false, _) if k.folded => {
            run_with::<M, L, R, true, false, true>(k, pos, nor, inputs, out, rsqrt)
        }
        (false, _) => run_with::<M, L, R, false, false, true>(k, pos, nor, inputs, out, rsqrt),
        (true, false) => run_with::<M, L, R, false, true, false>(k, pos, nor, inputs, out, rsqrt),
        (true, true) => run_with::<M, L, R, false, true, true>(k, pos, nor, inputs, out, rsqrt),
    }
}

/// [`run`] for one combination: `SURFACE` and `VISIBILITY` say which of `inputs` are present.
#[inline(always)]
fn run_with<M, L, R, const FOLDED: bool, const SURFACE: bool, const VISIBILITY: bool>(
    k: &Setup<'_, M, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &PointInputs<'_>,
    out: SoaRgb<'_>,
    rsqrt: R,
) -> usize
where
    M: BatchModel,
    L: BatchLight,
    R: Fn(Lanes) -> Lanes,
{
    let len = pos.len().min(nor.len()).min(out.len());
    let (px, py, pz) = (&pos.x[..len], &pos.y[..len], &pos.z[..len]);
    let (nx, ny, nz) = (&nor.x[..len], &nor.y[..len], &nor.z[..len]);
    let (r, g, b) = (&mut out.r[..len], &mut out.g[..len], &mut out.b[..len]);
    let mut i = 0;
    while i + W <= len {
        let p = [load(px, i), load(py, i), load(pz, i)];
        let n = [load(nx, i), load(ny, i), load(nz, i)];
        let mut c =
            shade_chunk::<M, L, R, FOLDED, SURFACE, VISIBILITY>(k, &p, &n, &rsqrt, inputs, i, W);
        // An integer OR reduction (a float max would be a serial chain).
        if c[3].iter().fold(0u32, |a, &b| a | b.to_bits()) != 0 {
            c = fix(k, p, n, (SURFACE || VISIBILITY).then_some(inputs), i, c, W);
        }
        r[i..i + W].copy_from_slice(&c[0]);
        g[i..i + W].copy_from_slice(&c[1]);
        b[i..i + W].copy_from_slice(&c[2]);
        i += W;
    }
    if i < len {
        let count = len - i;
        let p = [
            load_tail(px, i, count),
            load_tail(py, i, count),
            load_tail(pz, i, count),
        ];
        let n = [
            load_tail(nx, i, count),
            load_tail(ny, i, count),
            load_tail(nz, i, count),
        ];
        let c = shade_chunk::<M, L, R, FOLDED, SURFACE, VISIBILITY>(
            k, &p, &n, &rsqrt, inputs, i, count,
        );
        // The padding lanes are shaded too (zero normals: flagged) and fixed only up to `count`.
        let c = fix(
            k,
            p,
            n,
            (SURFACE || VISIBILITY).then_some(inputs),
            i,
            c,
            count,
        );
        r[i..].copy_from_slice(&c[0][..count]);
        g[i..].copy_from_slice(&c[1][..count]);
        b[i..].copy_from_slice(&c[2][..count]);
    }
    len
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pow::PowStrategy;
    use crate::pow::error_bounds::worst_over_domain;

    #[test]
    fn the_portable_lobe_power_meets_each_strategys_bound() {
        // The kernels' pow differs from the scalar one only in flushing bases whose power would
        // fall below 2⁻¹⁰⁰, an absolute error under 2⁻¹⁰⁰, far below the bound's 2⁻²⁴ floor.
        for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let (e, x, s) = worst_over_domain(p, |s, xs| {
                let plan = p.plan(s);
                pow_lanes(plan, flush_below(plan), *xs)
            });
            assert!(
                e <= p.max_relative_error() as f64,
                "{p:?}: err {e:e} at x = {x:e}, s = {s:e}"
            );
        }
    }
}
