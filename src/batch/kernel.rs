//! The batch kernel: one source, 16 points at a time, generic over the level's primitives
//! ([`Simd`]), so every level (`Portable`, `Sse2`, `Avx2`, `Avx512`, `Neon`) runs the same
//! algorithm, and every call (per-point surfaces, shadows, every light) runs at every level.
//!
//! Work per point and light, with unnormalised `n`, `L = P_light − p`, `V = eye − p`, and inverse
//! norms `rn = rsqrt(n·n)`, `rl = rsqrt(L·L)`, `rv = rsqrt(V·V)` (the level's own estimate and
//! Newton steps, or the exact quotient):
//!
//! ```text
//! N·L = (n·L)·rn·rl,  N·V = (n·V)·rn·rv,  L·V = (L·V)·rl·rv,  d = (L·L)·rl
//! f     = 1 / max(c + d(l + q d), MIN_DENOMINATOR)
//! Phong: R·V = 2(N·L)(N·V) − L·V                      (no reflect vector)
//! Blinn: (N·H)² = max(N·L + N·V, 0)² / (2 + 2 L·V)    (no halfway vector, no sqrt)
//! ```
//!
//! Spot lights and the other falloffs take their direction, distance and falloff per lane by the
//! scalar path's own operations ([`falloff`]), so those are `shade`'s bit for bit; a spot cone's
//! power is the kernel's own (`PowStrategy::Auto`'s plan for the exponent).
//!
//! The colours follow the saturation rule in the module docs of `batch`: per channel three sums
//! over the lights, `Ia + Σ f·La`, `Σ f·max(N·L, 0)·Ld` and `Σ min(f·w, MAX)·Ls` (`w` the gated,
//! normalised specular lobe), each saturated and then multiplied by the material's colour once.
//!
//! Points the fast path cannot represent (a squared norm outside `[1e-30, 1e30]`: a zero or huge
//! normal, the viewer or a light at the point, huge coordinates; an overflowing attenuation
//! denominator; Blinn-Phong near `L = −V`) are flagged and shaded again by the scalar
//! [`shade`](crate::shade), so the batch has its degenerate-case results exactly.

use glam::Vec3;

use super::falloff_lanes::falloff;
use super::prepare::{BatchLight, BatchModel, LaneLight, LaneModel, Lobe};
use super::simd::{Kernels, Simd};
use super::sink::Sink;
use super::soa::{SoaRgb, SoaVec3};
use super::tiled::TileSpans;
use crate::attenuation::{Attenuation, FlatAttenuation};
use crate::gate::SpecularGate;
use crate::material::Material;
use crate::math;
use crate::pow::{
    EXP2_3, EXP2_4, EXP2_5, LOG2_3, LOG2_5, LOG2_7, Poly, PowPlan, PowStrategy, lobe_pow,
};
use crate::reflection::normalization::Normalization;
use crate::shade::{Scene, Viewer};
use crate::shader::Shader;
use crate::surface::Surface;
use crate::terms::Terms;
use crate::visibility::VisibilityFn;

/// Lanes per step.
pub(crate) const W: usize = 16;
/// One value per lane.
pub(crate) type Lanes = [f32; W];

/// Squared norms in this range take the fast path (the same range `normalize_or_zero` handles
/// directly).
const LO: f32 = 1.0e-30;
const HI: f32 = 1.0e30;

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
    /// A spot light's power plan for its exponent; unused by the other kinds.
    pub(crate) spot_pow: SpotPow,
    /// Whether a point light's attenuation denominator may pass `f32::MAX` at a distance the
    /// range tests let through (see [`may_overflow`]); false for the other kinds.
    pub(crate) may_overflow: bool,
}

/// How the kernel raises a spot light's cosine to its exponent `e`: [`PowStrategy::Auto`]'s plan
/// for `e`, chosen once per call (squaring for a whole `e ≤ 1024`, the degree-7 polynomial
/// otherwise), and the base below which the power is flushed to 0 (see [`flush_below`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SpotPow {
    pub(crate) plan: PowPlan,
    pub(crate) flush: f32,
}

impl SpotPow {
    /// For lights without a cone (never read).
    pub(crate) const NONE: SpotPow = SpotPow {
        plan: PowPlan::Squaring { n: 0 },
        flush: 0.0,
    };

    /// The plan for exponent `e` (finite and `≥ 0`, as a spot light's is).
    pub(crate) fn new(e: f32) -> SpotPow {
        let plan = PowStrategy::Auto.plan(e);
        SpotPow {
            plan,
            flush: flush_below(plan),
        }
    }
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
        may_overflow: match lane {
            LaneLight::Point { coefficients, .. } => may_overflow(coefficients),
            _ => false,
        },
        spot_pow: match lane {
            LaneLight::Falloff {
                spot: Some(spot), ..
            } => SpotPow::new(spot.exponent()),
            _ => SpotPow::NONE,
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

/// Everything constant over one call that the kernel reads. It names no model or light type, so
/// each level compiles the kernel once, not once per model and light type: what needs those types
/// (lights past the first [`PREPARED`], the scalar path for flagged lanes) is behind [`Call`].
pub(crate) struct Setup<'a> {
    pub(crate) material: &'a Material,
    /// How many lights the scene has.
    pub(crate) lights: usize,
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
    /// Whether every light's three colours and the scene's ambient light are grey (the three
    /// channels the same bits) and every light is prepared, so the unfolded sums are the same
    /// in every channel: a chunk keeps one sum per term, not three ([`chunk`]'s `GREY`), and the
    /// results are the same bits.
    pub(crate) grey: bool,
    /// `Ia`, sanitised: where the ambient sum starts.
    pub(crate) ambient: Vec3,
    /// `Ke + Ka ⊙ Ia`: where a folded call's single sum starts.
    pub(crate) base: Vec3,
    /// The first lights, prepared; all of them when `all_prepared`.
    pub(crate) prepared: [PreparedLight; PREPARED],
    pub(crate) all_prepared: bool,
    /// Whether the loop may call out of line for the material's own lobe: the scene has a
    /// light that does ([`Setup::lights_call_out`]), or the pow plan is [`PowPlan::Exact`]
    /// (`powf` per lane). Otherwise the loop is compiled with no call in it, around which every
    /// live vector register would have to be saved: measured, 10–15% of the AVX-512 level's
    /// time.
    pub(crate) calls_out: bool,
    /// The same for a per-point surface, whose lobe takes the polynomial power whatever the
    /// plan: only the exact Blinn-Phong normalisation (`powf` per lane) adds a call.
    pub(crate) surface_calls_out: bool,
}

/// The call's model and scene with their types: the kernel's way out to them, as a trait object,
/// so the kernel itself is compiled once per level.
pub(crate) trait Call {
    /// Light `j` of the scene, prepared.
    fn light(&self, k: &Setup<'_>, j: usize) -> PreparedLight;

    /// Re-shades the points `i + j` for each lane `j` in `bad` with the scalar path, reading
    /// their inputs again from the slices (so the fast loop need not keep them alive), and hands
    /// each point's terms to `put` to be written over the kernel's: [`shade`](crate::shade), or
    /// with per-point `inputs`, [`Shader::shade_surface`] (which sanitises the raw surface) with
    /// the point's visibilities.
    fn fixup(
        &self,
        pos: (&SoaVec3<'_>, &SoaVec3<'_>),
        inputs: Option<&PointInputs<'_>>,
        i: usize,
        bad: u32,
        put: &mut dyn FnMut(usize, &Terms),
    );
}

/// One kernel call, as dispatch hands it to a level: the call's setup and its way out to the
/// scalar path, the point slices, the per-point inputs and the output (a [`Sink`]: the total
/// colour, or the terms).
pub(crate) struct Job<'a, O = SoaRgb<'a>> {
    pub(crate) setup: &'a Setup<'a>,
    pub(crate) call: &'a dyn Call,
    pub(crate) pos: SoaVec3<'a>,
    pub(crate) nor: SoaVec3<'a>,
    pub(crate) inputs: &'a PointInputs<'a>,
    pub(crate) out: O,
    /// The runs of points to shade, in increasing order, or `None` for all of them: one call for
    /// the rows of a tile (`shade_gbuffer_tiled`), so the call's preparation is paid once a tile
    /// rather than once a row.
    pub(crate) spans: Option<TileSpans<'a>>,
}

/// A call's model, material and scene: its [`Call`].
pub(crate) struct CallOf<'a, 's, M, L> {
    pub(crate) model: &'a M,
    pub(crate) material: &'a Material,
    pub(crate) scene: &'a Scene<'s, L>,
}

impl<M: BatchModel, L: BatchLight> Call for CallOf<'_, '_, M, L> {
    fn light(&self, k: &Setup<'_>, j: usize) -> PreparedLight {
        prepare_light(&self.scene.lights[j], self.material, &k.lm)
    }

    #[cold]
    #[inline(never)]
    fn fixup(
        &self,
        (pos, nor): (&SoaVec3<'_>, &SoaVec3<'_>),
        inputs: Option<&PointInputs<'_>>,
        i: usize,
        bad: u32,
        put: &mut dyn FnMut(usize, &Terms),
    ) {
        let shader = Shader::for_one_point(self.model, self.material, self.scene);
        for j in 0..W {
            if bad & (1 << j) == 0 {
                continue;
            }
            let at = i + j;
            let p = Vec3::new(pos.x[at], pos.y[at], pos.z[at]);
            let n = Vec3::new(nor.x[at], nor.y[at], nor.z[at]);
            let c = match inputs {
                None => crate::shade(self.model, self.material, self.scene, p, n),
                Some(inputs) => {
                    let surface = match inputs.surface(at, 1) {
                        Some(r) => Surface {
                            ambient: Vec3::new(r[0][0], r[1][0], r[2][0]),
                            diffuse: Vec3::new(r[3][0], r[4][0], r[5][0]),
                            specular: Vec3::new(r[6][0], r[7][0], r[8][0]),
                            shininess: r[9][0],
                        },
                        None => Surface::of(self.material),
                    };
                    let vis = VisibilityFn(|l| inputs.visibility(l, at, 1)[0]);
                    shader.shade_surface(p, n, &surface, vis)
                }
            };
            put(at, &c);
        }
    }
}

impl<'a> Setup<'a> {
    /// Whether some light needs a call: a [`LaneLight::Falloff`] (evaluated out of line), or a
    /// light past the first [`PREPARED`] (prepared per chunk through [`Call::light`]). A call in
    /// the light loop, even on a branch never taken, made the AVX-512 level keep its sums on the
    /// stack: 8–10% of its time in `levels_4096`.
    fn lights_call_out<L: BatchLight>(scene: &Scene<'_, L>) -> bool {
        scene.lights.len() > PREPARED
            || scene
                .lights
                .iter()
                .any(|l| matches!(l.lane_light(), Some(LaneLight::Falloff { .. })))
    }

    pub(crate) fn new<M: BatchModel, L: BatchLight>(
        model: &M,
        material: &'a Material,
        scene: &Scene<'_, L>,
    ) -> Self {
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
            spot_pow: SpotPow::NONE,
            may_overflow: false,
        }; PREPARED];
        for (slot, light) in prepared.iter_mut().zip(scene.lights) {
            *slot = prepare_light(light, material, &lm);
        }
        let folded = cannot_overflow(scene, material, &lm);
        let lights_call = Self::lights_call_out(scene);
        let ambient = crate::light::sanitize_colour(scene.ambient);
        let sat = Vec3::splat(math::MAX);
        let grey = !lights_call
            && is_grey(ambient)
            && prepared[..scene.lights.len()]
                .iter()
                .all(|l| is_grey(l.la) && is_grey(l.ld) && is_grey(l.ls));
        Setup {
            prepared,
            all_prepared: scene.lights.len() <= PREPARED,
            lights: scene.lights.len(),
            calls_out: lights_call || matches!(plan, PowPlan::Exact { .. }),
            surface_calls_out: lights_call
                || (lm.lobe == Lobe::Blinn && lm.normalization == Normalization::EnergyExact),
            material,
            lm,
            plan,
            flush,
            view,
            specular_on,
            scaled: lm.specular_scale != 1.0,
            folded,
            grey,
            ambient,
            base: (material.emission() + (ambient * material.ambient()).min(sat)).min(sat),
        }
    }
}

/// Whether the three channels of `c` are the same bits.
fn is_grey(c: Vec3) -> bool {
    c.x.to_bits() == c.y.to_bits() && c.y.to_bits() == c.z.to_bits()
}

/// The base below which a plan's repeated squaring reads it as 0, so that no subnormal is ever
/// produced: the scalar path's [`squaring_floor`](crate::pow::squaring_floor) for the plan's
/// whole part (its lobe is then below `2⁻⁶⁰`), so the two flush the same bases; 0 when the plan
/// does not square.
pub(crate) fn flush_below(plan: PowPlan) -> f32 {
    match plan {
        PowPlan::Squaring { n } | PowPlan::Split { n, .. } if n > 0 => {
            crate::pow::squaring_floor(n)
        }
        _ => 0.0,
    }
}

#[inline(always)]
fn load(s: &[f32], i: usize) -> Lanes {
    match <&Lanes>::try_from(&s[i..i + W]) {
        Ok(a) => *a,
        Err(_) => [0.0; W], // unreachable: the range is W long
    }
}

#[inline(always)]
pub(crate) fn load_tail(s: &[f32], i: usize, count: usize) -> Lanes {
    // A whole chunk by a fixed-size load: a copy of variable length is a call to `memcpy`, ten
    // of them a chunk for a G-buffer's surface, where the compiler does not see `count == W`.
    if count == W {
        return load(s, i);
    }
    let mut a = [0.0f32; W];
    a[..count].copy_from_slice(&s[i..i + count]);
    a
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
    /// Whether `Ka` is `Kd` at every point and whether `Ks` is grey ([`same`](Self::same) of
    /// their values), found once by [`new`](Self::new): tested per chunk, the ten comparisons
    /// and their branches cost `gbuffer_f32` 2–3% at AVX-512 (the RGBA8 row under 1%).
    shares: Shares,
}

/// See [`PointInputs::shares`]; both `false` by default (each plane loaded apart).
#[derive(Clone, Copy, Default)]
struct Shares {
    ambient_is_diffuse: bool,
    grey_specular: bool,
}

impl<'a> PointInputs<'a> {
    /// The inputs with their sharing of planes found.
    pub(crate) fn new(
        surface: Option<[&'a [f32]; 10]>,
        albedo: Option<&'a [[u8; 4]]>,
        base: [f32; 10],
        visibility: Option<(&'a [f32], usize)>,
    ) -> Self {
        let mut inputs = PointInputs {
            surface,
            albedo,
            base,
            visibility,
            shares: Shares::default(),
        };
        inputs.shares = Shares {
            ambient_is_diffuse: inputs.same(0, 3) && inputs.same(1, 4) && inputs.same(2, 5),
            grey_specular: inputs.same(6, 7) && inputs.same(6, 8),
        };
        inputs
    }
}

impl PointInputs<'_> {
    /// The same inputs from point `start` on (the same planes, so the same sharing).
    pub(crate) fn from(&self, start: usize) -> Self {
        PointInputs {
            surface: self.surface.map(|s| s.map(|a| &a[start..])),
            albedo: self.albedo.map(|a| &a[start..]),
            base: self.base,
            visibility: self.visibility.map(|(v, stride)| (&v[start..], stride)),
            shares: self.shares,
        }
    }

    /// Whether surface values `a` and `b` are the same at every point: the same slice, or, without
    /// a surface, the same material value.
    #[inline(always)]
    pub(crate) fn same(&self, a: usize, b: usize) -> bool {
        match self.surface {
            Some(slices) => core::ptr::eq(slices[a], slices[b]),
            None => self.base[a].to_bits() == self.base[b].to_bits(),
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
                let at = j * stride + i;
                if count == W {
                    load(v, at)
                } else {
                    let mut a = [1.0f32; W];
                    a[..count].copy_from_slice(&v[at..at + count]);
                    a
                }
            }
            None => [1.0; W],
        }
    }

    /// The raw surface values at points `i..i + count`: the surface's (or the material's), with
    /// `Ka` and `Kd` multiplied by the decoded albedo where there is one. `None` without either.
    #[inline(always)]
    pub(crate) fn surface(&self, i: usize, count: usize) -> Option<[Lanes; 10]> {
        let mut raw = [[0.0f32; W]; 10];
        self.surface_into(i, count, &mut raw).then_some(raw)
    }

    /// [`surface`](Self::surface) written into `raw` (whether there is one): the kernel's form,
    /// since moving the 640-byte array by value cost a `memcpy` call or more per chunk.
    #[inline(always)]
    pub(crate) fn surface_into(&self, i: usize, count: usize, raw: &mut [Lanes; 10]) -> bool {
        match self.surface {
            Some(slices) => {
                for (r, a) in raw.iter_mut().zip(slices) {
                    *r = load_tail(a, i, count);
                }
            }
            None if self.albedo.is_some() => {
                for (r, b) in raw.iter_mut().zip(self.base) {
                    *r = [b; W];
                }
            }
            None => return false,
        }
        if let Some(albedo) = self.albedo {
            for (lane, texel) in albedo[i..i + count].iter().enumerate() {
                for c in 0..3 {
                    let x = crate::srgb8_to_linear(texel[c]);
                    raw[c][lane] *= x;
                    raw[3 + c][lane] *= x;
                }
            }
        }
        true
    }
}

/// `Σ c[k] t^k` by Estrin's scheme: pairs `c[2i] + c[2i+1]·t` first, then pairs of those with
/// `t²`, `t⁴`, …; the dependency chain is `⌈log2 N⌉` multiply-adds deep instead of Horner's `N`,
/// which matters because the chains of successive chunks are what limits this loop.
#[inline(always)]
pub(super) fn poly<S: Simd, const N: usize>(s: S, t: S::V, c: &[f32; N]) -> S::V {
    const { assert!(N <= 8, "poly: at most 8 coefficients") };
    let mut cur = [s.splat(0.0); 8];
    for (slot, &k) in cur.iter_mut().zip(c) {
        *slot = s.splat(k);
    }
    let mut m = N;
    let mut pw = t;
    while m > 1 {
        let half = m.div_ceil(2);
        for j in 0..half {
            cur[j] = if 2 * j + 1 < m {
                s.mul_add(cur[2 * j + 1], pw, cur[2 * j])
            } else {
                cur[2 * j]
            };
        }
        m = half;
        pw = s.mul(pw, pw);
    }
    cur[0]
}

/// `log2 x` for `x ∈ (0, 1]` (as `pow::log2_poly`): `x = m·2^e` with `m ∈ [√½, √2)`, then
/// `e + t·P(t)` with `t = m − 1`; `x` scaled by `2²⁴` first (and 24 taken from `e`), so that a
/// subnormal `x` has its exponent in the bits, unless `NORMAL` says every `x` is a normal number.
#[inline(always)]
pub(super) fn log2<S: Simd, const N: usize, const NORMAL: bool>(
    s: S,
    x: S::V,
    c: &[f32; N],
) -> S::V {
    // Every `x ≤ 1` times `2²⁴` is a normal number, exactly (subnormals included), with the
    // same significand: scaling every lane and taking 24 from the exponent gives the bits that
    // scaling only the subnormal lanes gave, for one product and one integer subtraction
    // instead of a compare, a product, two selects and a subtraction.
    let xs = if NORMAL {
        x
    } else {
        s.mul(x, s.splat(16_777_216.0))
    };
    let bits = s.to_bits(xs);
    let e = s.sar23(s.sub_i(bits, s.splat_i(0x3f35_04f3)));
    let m = s.bits_to_f32(s.sub_i(bits, s.shl23(e)));
    let t = s.sub(m, s.splat(1.0));
    let ef = s.to_f32(if NORMAL { e } else { s.sub_i(e, s.splat_i(24)) });
    s.mul_add(t, poly(s, t, c), ef)
}

/// `2^y` for `y ≤ 0`, 0 where `y < −100` (as `pow::poly_pow`'s, bit for bit): `y = r + f` with `r`
/// the nearest integer (the level's rounding instruction, or the `1.5·2²³` trick), `2^f ≈ 1 +
/// f·R(f)`, and the product by `2^r` exact (`Simd::scale2`: at AVX-512 one `vscalefps`, where
/// building `2^r` in the exponent bits and multiplying took three operations, and the trick's
/// rounding three more). `IN_RANGE` says every `y` is already in `[−100, 0]`.
#[inline(always)]
pub(super) fn exp2<S: Simd, const N: usize, const IN_RANGE: bool>(
    s: S,
    y: S::V,
    c: &[f32; N],
) -> S::V {
    let keep = s.ge(y, s.splat(-100.0));
    // No `min(y, 0)`: every caller's `y` is `e·log2 x` with `e ≥ 0` and `x ≤ 1`, where `log2`
    // gives 0 at 1 and a negative value below (its polynomial is positive on its interval), and
    // any other lane (`x ≤ 0`) is cleared by the caller. The floor keeps `2^r` a normal number.
    let y = if IN_RANGE {
        y
    } else {
        s.max(y, s.splat(-100.0))
    };
    let r = s.round(y);
    let f = s.sub(y, r);
    let q = s.mul_add(f, poly(s, f, c), s.splat(1.0));
    // `q ∈ [2^−½, 2^½]` and `r ≥ −100`: a normal product, exact.
    let p = s.scale2(q, r);
    if IN_RANGE { p } else { s.keep(keep, p) }
}

/// `exp2(e·log2 x)` per lane by the polynomial pair `p`, for `x ∈ (0, 1]`.
#[inline(always)]
fn poly_pow<S: Simd>(s: S, p: Poly, x: S::V, e: S::V) -> S::V {
    match p {
        Poly::P3 => exp2::<S, _, false>(s, s.mul(e, log2::<S, _, false>(s, x, &LOG2_3)), &EXP2_3),
        Poly::P5 => exp2::<S, _, false>(s, s.mul(e, log2::<S, _, false>(s, x, &LOG2_5)), &EXP2_4),
        Poly::P7 => exp2::<S, _, false>(s, s.mul(e, log2::<S, _, false>(s, x, &LOG2_7)), &EXP2_5),
    }
}

/// `x^n` by repeated squaring, the same `n` in every lane; bases below `flush` first set to 0.
#[inline(always)]
fn squaring<S: Simd>(s: S, x: S::V, flush: f32, n: u32) -> S::V {
    if n == 0 {
        return s.splat(1.0);
    }
    let mut base = s.keep(s.ge(x, s.splat(flush)), x);
    // x^n = (x^(2^z))^(n / 2^z) with z trailing zeros: z plain squarings first, as straight-line
    // runs of 8, 4, 2 and 1 chosen by z's bits (a plan's n is at most 1024, so z ≤ 10; a loop
    // cost a counter and a branch per squaring: at s = 32, 28.0 → 26.5 instructions a point at
    // the AVX2 level). The same squarings in the same order.
    debug_assert!(
        n <= 1024,
        "a squaring plan's exponent is at most 1024, got {n}"
    );
    let z = n.trailing_zeros();
    macro_rules! squarings {
        ($count:literal) => {
            for _ in 0..$count {
                base = s.mul(base, base);
            }
        };
    }
    if z & 8 != 0 {
        squarings!(8);
    }
    if z & 4 != 0 {
        squarings!(4);
    }
    if z & 2 != 0 {
        squarings!(2);
    }
    if z & 1 != 0 {
        squarings!(1);
    }
    let mut acc = base;
    let mut e = n >> (z + 1);
    while e > 0 {
        base = s.mul(base, base);
        if e & 1 == 1 {
            acc = s.mul(acc, base);
        }
        e >>= 1;
    }
    acc
}

/// `x^s` for bases in `[0, 1]` by the call's plan (the same in every lane); 0 for `x ≤ 0`.
#[inline(always)]
pub(super) fn pow<S: Simd, const CALLS: bool>(s: S, plan: PowPlan, flush: f32, x: S::V) -> S::V {
    let r = match plan {
        // Never met: the chunk sends every lane to the scalar path for this plan without `CALLS`.
        PowPlan::Exact { .. } if !CALLS => s.splat(0.0),
        PowPlan::Exact { s: e } => {
            let a = s.store(x);
            s.load(&core::array::from_fn(|i| lobe_pow(a[i], e)))
        }
        PowPlan::Squaring { n } => squaring(s, x, flush, n),
        PowPlan::Poly { s: e, poly } => poly_pow(s, poly, x, s.splat(e)),
        PowPlan::Split { n, frac, poly } => s.mul(
            squaring(s, x, flush, n),
            poly_pow(s, poly, x, s.splat(frac)),
        ),
    };
    s.keep(s.gt(x, s.splat(0.0)), r)
}

/// Which pow plan a kernel instance is compiled for: any plan, read from the call's
/// [`Setup`] per chunk (a jump table per light and chunk), or one kind, whose evaluation the
/// instance runs inline with only the plan's numbers read at run time.
pub(crate) const PLAN_ANY: u8 = 0;
/// [`PowPlan::Squaring`], `Auto`'s plan for a whole exponent.
pub(crate) const PLAN_SQUARING: u8 = 1;
/// [`PowPlan::Poly`] with [`Poly::P7`], `Auto`'s plan for any other exponent.
pub(crate) const PLAN_POLY7: u8 = 2;

/// The call's plan as instance `PLAN` evaluates it: for one kind, a value of that kind built
/// here, so that the compiler knows its kind in the instance (the instance runs only for calls
/// with a plan of that kind: `run` picks it).
#[inline(always)]
fn plan_of<const PLAN: u8>(plan: PowPlan) -> PowPlan {
    match (PLAN, plan) {
        (PLAN_SQUARING, _) => PowPlan::Squaring {
            n: match plan {
                PowPlan::Squaring { n } => n,
                _ => 0,
            },
        },
        (PLAN_POLY7, _) => PowPlan::Poly {
            s: match plan {
                PowPlan::Poly { s, .. } => s,
                _ => 0.0,
            },
            poly: Poly::P7,
        },
        _ => plan,
    }
}

/// A chunk's per-point lobe, sanitised as [`Shader::shade_surface`] does: each lane's specular
/// scale and exponent. The reflectances are loaded apart ([`reflectances`]), after the light
/// sums: loaded with these, their nine vectors were live across the whole light loop, and the
/// AVX2 level (sixteen registers, two per vector of sixteen lanes) kept them on the stack. Loaded
/// after, `shade_gbuffer` ran about a fifth faster there (`gbuffer_4096`).
pub(crate) struct SurfaceV<S: Simd> {
    /// The lobe's normalisation factor per lane; `None` for a model without one (a factor of 1).
    scale: Option<S::V>,
    /// The lobe's exponent per lane (half the shininess for Blinn-Phong), evaluated by the
    /// polynomial at every value, as `auto_split_per_point` plans it for one point.
    exponent: S::V,
}

/// Loads one of `inputs`' ten surface values at points `i..i + count` in every lane: the
/// surface's slice, or the material's value where the call has an albedo alone (a macro, not a
/// closure: a closure may be left out of line, without the level's features).
macro_rules! surface_lanes {
    ($s:expr, $inputs:expr, $i:expr, $count:expr, $a:expr) => {
        match $inputs.surface {
            Some(slices) => $s.load(&load_tail(slices[$a], $i, $count)),
            None => $s.splat($inputs.base[$a]),
        }
    };
}

impl<S: Simd> SurfaceV<S> {
    /// Points `i..i + count` of `inputs`' per-point lobe; `None` without a per-point surface or
    /// albedo.
    #[inline(always)]
    fn load(
        s: S,
        lm: &LaneModel,
        inputs: &PointInputs<'_>,
        i: usize,
        count: usize,
    ) -> Option<Self> {
        if !inputs.per_point_surface() {
            return None;
        }
        let sh = clean(s, surface_lanes!(s, inputs, i, count, 9));
        let scale = match lm.normalization {
            Normalization::None if lm.lobe != Lobe::None => None,
            _ => Some(s.load(&lane_scales(lm, &s.store(sh)))),
        };
        let half = if lm.lobe == Lobe::Blinn { 0.5 } else { 1.0 };
        Some(SurfaceV {
            scale,
            // `auto_split_per_point`'s exponent, lane by lane (`sh` is in `[0, f32::MAX]`
            // already, and so is its half).
            exponent: s.mul(s.splat(half), sh),
        })
    }
}

/// Points `i..i + count` of `inputs`' per-point reflectances `[Ka, Kd, Ks]` (the material's values
/// where the call has an albedo alone), sanitised as [`Shader::shade_surface`] does (`clean`);
/// `None` without a per-point surface or albedo.
#[inline(always)]
fn reflectances<S: Simd>(
    s: S,
    inputs: &PointInputs<'_>,
    i: usize,
    count: usize,
) -> Option<[[S::V; 3]; 3]> {
    if !inputs.per_point_surface() {
        return None;
    }
    // The decoded texel multiplies Ka and Kd before they are sanitised, as the scalar path
    // orders it (`PointInputs::surface`, then `Shader::shade_surface`).
    let albedo = inputs
        .albedo
        .map(|albedo| decoded_albedo(s, albedo, i, count));
    macro_rules! tinted {
        ($a:expr) => {
            match albedo {
                Some(x) => clean(s, s.mul(surface_lanes!(s, inputs, i, count, $a), x[$a % 3])),
                None => clean(s, surface_lanes!(s, inputs, i, count, $a)),
            }
        };
    }
    macro_rules! plain {
        ($a:expr) => {
            clean(s, surface_lanes!(s, inputs, i, count, $a))
        };
    }
    // LearnOpenGL's textured material passes one texture as both `Ka` and `Kd`, and a specular
    // strength map as a grey `Ks`: such planes are loaded and sanitised once.
    let diffuse = [tinted!(3), tinted!(4), tinted!(5)];
    let ambient = if inputs.shares.ambient_is_diffuse {
        diffuse
    } else {
        [tinted!(0), tinted!(1), tinted!(2)]
    };
    let specular = if inputs.shares.grey_specular {
        let k = plain!(6);
        [k, k, k]
    } else {
        [plain!(6), plain!(7), plain!(8)]
    };
    Some([ambient, diffuse, specular])
}

/// Texels `i..i + count` of `albedo` decoded from 8-bit sRGB, `[r, g, b]`: one load of the chunk's
/// texels, each channel's byte as an index and one gather per channel from
/// [`srgb8_to_linear`](crate::srgb8_to_linear)'s table, so every lane holds that function's bits
/// (the scalar path's). Lanes past `count` decode texel 0 (black); nothing reads them.
///
/// Decoded lane by lane instead (48 table loads and scalar stores into three arrays, then a
/// vector load of each, which the stores cannot forward), `gbuffer_albedo8_rgba8` took 1.24× the
/// time of `gbuffer_rgba8` (the same call without an albedo) at AVX-512 on the development
/// machine (an Intel Xeon, family 6 model 207), against 1.11× gathered: 15.2–16.0 µs against 13.6–14.5 in six interleaved
/// criterion runs of each, 2026-12-07.
#[inline(always)]
fn decoded_albedo<S: Simd>(s: S, albedo: &[[u8; 4]], i: usize, count: usize) -> [S::V; 3] {
    let texels: [[u8; 4]; W] = match <&[[u8; 4]; W]>::try_from(&albedo[i..i + count]) {
        // A whole chunk by a fixed-size load (see `load_tail`).
        Ok(whole) => *whole,
        Err(_) => {
            let mut part = [[0u8; 4]; W];
            part[..count].copy_from_slice(&albedo[i..i + count]);
            part
        }
    };
    // `[r, g, b, a]` is the little-endian word `a << 24 | b << 16 | g << 8 | r`.
    let words: [u32; W] = bytemuck::must_cast(texels);
    let words = s.to_bits(s.load(&bytemuck::must_cast(words.map(u32::from_le))));
    let byte = s.splat_i(0xff);
    let table = &crate::colour::srgb8_to_linear::LINEAR_BITS;
    // Written out, not a closure: a closure would not inherit the level's target features.
    [
        s.bits_to_f32(s.gather(table, s.and_i(words, byte))),
        s.bits_to_f32(s.gather(table, s.and_i(s.srl16(s.shl8(words)), byte))),
        s.bits_to_f32(s.gather(table, s.and_i(s.srl16(words), byte))),
    ]
}

/// `v` with NaN and negatives as 0 and values past `f32::MAX` as `f32::MAX` (`Material::new`'s
/// rule, [`math::clamp_or_lo`]), in every lane.
#[inline(always)]
fn clean<S: Simd>(s: S, v: S::V) -> S::V {
    s.min(s.max(v, s.splat(0.0)), s.splat(math::MAX))
}

/// Each lane's specular normalisation factor for its shininess. The matches are outside the
/// loops: inside, the compiler evaluates every arm for every lane and selects, which called
/// `exp2f` (the exact Blinn-Phong factor's `2^(−s/2)`) sixteen times a chunk for every model.
#[inline(always)]
fn lane_scales(lm: &LaneModel, sh: &Lanes) -> Lanes {
    // A macro, not a closure: a closure may be left out of line, without the level's features.
    macro_rules! each {
        ($f:expr) => {{
            let mut r = [0.0f32; W];
            for (r, &s) in r.iter_mut().zip(sh) {
                *r = $f(s);
            }
            r
        }};
    }
    match (lm.lobe, lm.normalization) {
        (Lobe::None, _) => [0.0; W],
        (_, Normalization::None) => [1.0; W],
        (Lobe::Phong, norm) => each!(|s| norm.phong_factor(s)),
        (Lobe::Blinn, Normalization::Energy) => each!(|s| Normalization::Energy.blinn_factor(s)),
        (Lobe::Blinn, norm) => each!(|s| norm.blinn_factor(s)),
    }
}

/// `PowStrategy::Auto`'s `x^e` with an exponent per lane (`surface.exponent`): the degree-7
/// polynomial, as for one point with its own exponent (`auto_split_per_point`, bit for bit); 1
/// where the exponent is 0, and 0 for `x ≤ 0`.
///
/// No select is needed for either case: for `x ∈ (0, 1]` the logarithm is finite, so an exponent
/// of 0 makes `exp2(±0)`, which the polynomial gives as exactly 1; and the lanes with `x ≤ 0`,
/// whose logarithm is meaningless (but raises nothing), are cleared at the end.
#[inline(always)]
fn auto_pow<S: Simd>(s: S, x: S::V, sf: &SurfaceV<S>) -> S::V {
    let pos = s.gt(x, s.splat(0.0));
    s.keep(pos, poly_pow(s, Poly::P7, x, sf.exponent))
}

/// `a·b` summed over the three components.
#[inline(always)]
fn dot<S: Simd>(s: S, a: &[S::V; 3], b: &[S::V; 3]) -> S::V {
    s.mul_add(a[0], b[0], s.mul_add(a[1], b[1], s.mul(a[2], b[2])))
}

/// The three components of `v` in every lane.
#[inline(always)]
fn splat3<S: Simd>(s: S, v: Vec3) -> [S::V; 3] {
    [s.splat(v.x), s.splat(v.y), s.splat(v.z)]
}

/// Lanes whose squared norm lies in `[LO, HI]` (false for NaN).
#[inline(always)]
fn in_range<S: Simd>(s: S, x: S::V) -> S::M {
    s.and(s.ge(x, s.splat(LO)), s.le(x, s.splat(HI)))
}

/// `q − p` per lane, its squared length, and `ok` with the lanes whose squared length leaves
/// `[LO, HI]` cleared (for the scalar path).
#[inline(always)]
fn offset_to<S: Simd>(s: S, q: &[S::V; 3], p: &[S::V; 3], ok: &mut S::M) -> ([S::V; 3], S::V) {
    let d = [s.sub(q[0], p[0]), s.sub(q[1], p[1]), s.sub(q[2], p[2])];
    let dd = dot(s, &d, &d);
    *ok = s.and(*ok, in_range(s, dd));
    (d, dd)
}

/// Below this `2 + 2 L·V` (an angle between `L` and `V` above about 174°) the Blinn-Phong lane is
/// re-shaded by the scalar path: the cosine form's relative error there, about
/// `2e-7 / (2 + 2 L·V)` in `(N·H)²`, times `s/2` in the lobe, would otherwise reach the 8-bit
/// level at high shininess. For random directions about 0.25% of lanes are affected.
pub(super) const BLINN_DEN_MIN: f32 = 1e-2;

/// A prepared light with its constants in every lane, built once per call, so the loop reads
/// them as memory operands instead of broadcasting scalars for every chunk.
#[derive(Clone, Copy)]
pub(crate) struct LightLanes<S: Simd> {
    light: PreparedLight,
    /// Position (point light) or direction (directional light).
    q: [S::V; 3],
    /// Attenuation coefficients `c`, `l`, `q` (point light).
    c: [S::V; 3],
    /// The colours the call sums: the light's, or folded, their products with the material's.
    la: [S::V; 3],
    ld: [S::V; 3],
    ls: [S::V; 3],
    /// [`PreparedLight::may_overflow`].
    may_overflow: bool,
    /// Whether the light is a point light (`LaneLight::Point`), the common kind, which the
    /// chunk tests before the others: a flag of its own, since LLVM folds a test of the kind
    /// itself back into one jump table over all four kinds, taken per light and chunk.
    point: bool,
}

/// Whether `c + l·d + q·d²` may reach `f32::MAX` for some `d ≤ 10¹⁵`: the lanes the kernel
/// keeps have `d² ≤ HI = 10³⁰`, so otherwise no lane needs the test. Bounded in `f64` with a
/// factor of two to spare for the lanes' rounding and their inverse square root's error.
fn may_overflow(coefficients: [f32; 3]) -> bool {
    let [c, l, q] = coefficients.map(f64::from);
    // √HI.
    let d = 1e15;
    // NaN coefficients never reach here (the light is validated); were one there, `!(<)`
    // keeps the test.
    !(c + l * d + q * d * d < f64::from(f32::MAX) / 2.0)
}

impl<S: Simd> LightLanes<S> {
    #[inline(always)]
    fn new(s: S, light: PreparedLight, folded: bool) -> Self {
        let (q, c) = match light.lane {
            LaneLight::Point {
                position,
                coefficients,
            } => (position, Vec3::from_array(coefficients)),
            LaneLight::Directional(d) => (d, Vec3::ZERO),
            LaneLight::AmbientOnly | LaneLight::Falloff { .. } => (Vec3::ZERO, Vec3::ZERO),
        };
        let (la, ld, ls) = if folded {
            (light.ka, light.kd, light.ks)
        } else {
            (light.la, light.ld, light.ls)
        };
        LightLanes {
            light,
            q: splat3(s, q),
            c: splat3(s, c),
            la: splat3(s, la),
            ld: splat3(s, ld),
            ls: splat3(s, ls),
            may_overflow: light.may_overflow,
            point: matches!(light.lane, LaneLight::Point { .. }),
        }
    }
}

/// The scene's lights as the chunk loop reads them: the first [`PREPARED`] with their constants
/// in every lane (built once per call), and, for a scene with more, the next ones prepared once
/// per call ([`MORE`] at most; past those, each is prepared per chunk through [`Call::light`]).
/// With them, the viewer's position in every lane, for the same reason.
///
/// Built in place once per call, and only for the lights there are: the first light's lanes,
/// then a slot per further light up to [`PREPARED`], empty past the scene's last. When they were
/// filled as one array of `PREPARED` copies and then moved into place, the lanes (about 1.2 KiB
/// a light) cost every call 10 KiB of stores and a `memcpy` of as much: 4–5% of a 4096-point
/// `shade_batch` at AVX-512 (sampled profile of `levels_4096`, 2026-11-29).
pub(crate) struct ChunkLights<'a, S: Simd> {
    zeroth: LightLanes<S>,
    rest: [Option<LightLanes<S>>; PREPARED - 1],
    more: &'a [PreparedLight],
    /// The eye of a viewer at a point ([`ViewK::At`]); zero for an infinite viewer.
    eye: [S::V; 3],
}

impl<S: Simd> ChunkLights<'_, S> {
    /// Light `j < PREPARED`'s lanes (the first light's for an empty slot, which the chunk loop
    /// never reads: it stops at the scene's last light).
    #[inline(always)]
    fn prepared(&self, j: usize) -> &LightLanes<S> {
        match self.rest.get(j.wrapping_sub(1)) {
            Some(Some(lanes)) => lanes,
            _ => &self.zeroth,
        }
    }
}

/// Blinn-Phong's cosine-form denominator `2 + 2 L·V = ‖L + V‖²` for unit `L`, `V`, from `L·V`.
#[inline(always)]
fn blinn_den<S: Simd>(s: S, lv: S::V) -> S::V {
    s.mul_add(s.splat(2.0), lv, s.splat(2.0))
}

/// How many lights past the first [`PREPARED`] a call prepares once, on the stack of the level's
/// kernel (about 14 KiB: 252 bytes each on x86_64), instead of once per chunk: a scene of 64
/// lights (per-tile culling's case) prepares each light once per call. Before, each was
/// prepared per chunk, a trait-object call and an `f64` overflow test that took about a third
/// of the every-light G-buffer bench.
pub(crate) const MORE: usize = 56;

/// Shades 16 points. Returns the colours and the lanes the scalar path must redo (bit `i` for
/// lane `i`). `FOLDED` is [`Setup::folded`]: sum the products of light and material colours
/// (nothing can overflow) instead of the three sums of the saturation rule (never with a
/// per-point `surface`). `visibility`, the call's inputs with this chunk's first point and count,
/// gives each light's visibility per lane (clamped to `[0, 1]` here, NaN read as 0), which scales
/// the light's diffuse and specular parts, not its ambient part.
///
/// Cosines come from unnormalised vectors times inverse norms, `N·V = (n·V)/(‖n‖‖V‖)` and so on:
/// the dot products run alongside the inverse square roots instead of after them, and the loop is
/// bound by these dependency chains, not by the number of operations.
#[inline(always)]
#[allow(
    clippy::too_many_arguments,
    reason = "the level, the call, its way out to the scalar path, the chunk's lanes and inputs"
)]
fn chunk<S, const FOLDED: bool, const GREY: bool, const CALLS: bool>(
    s: S,
    k: &Setup<'_>,
    call: &dyn Call,
    lights: &ChunkLights<'_, S>,
    p: &[S::V; 3],
    n: &[S::V; 3],
    surface: Option<&SurfaceV<S>>,
    visibility: Option<(&PointInputs<'_>, usize, usize)>,
    plan: PowPlan,
) -> ([[S::V; 3]; 3], u32)
where
    S: Simd,
{
    let zero = s.splat(0.0);
    let one = s.splat(1.0);
    let max = s.splat(math::MAX);
    let nn = dot(s, n, n);
    let mut ok = in_range(s, nn);
    if !CALLS && surface.is_none() && matches!(plan, PowPlan::Exact { .. }) {
        // Never met (see `Setup::calls_out`); were it met, the scalar path shades every lane.
        ok = s.and(ok, s.lt(zero, zero));
    }
    let inv_n = s.rsqrt(nn);
    let (v, inv_v) = match k.view {
        ViewK::At(_) => {
            let (d, vv) = offset_to(s, &lights.eye, p, &mut ok);
            (d, s.rsqrt(vv))
        }
        ViewK::Infinite(d) => (splat3(s, d), one),
    };
    let nv = s.mul(dot(s, n, &v), s.mul(inv_n, inv_v));
    // Phong's base `2(N·L)(N·V) − L·V` takes `2·N·V`, doubled once here rather than `N·L` once
    // per light: the same product, exactly (a power of two).
    let nv2 = s.add(nv, nv);

    // Per channel, three sums over the lights, each multiplied by the material's colour once at
    // the end (the saturation rule in the module docs of `batch`):
    //   amb = Ia + Σ f·La,   dif = Σ f·max(N·L, 0)·Ld,   spe = Σ min(f·ws, MAX)·Ls.
    // Folded, `amb` alone holds Ke + Ka⊙Ia + Σ f·(Ka⊙La + max(N·L, 0)·Kd⊙Ld + ws·Ks⊙Ls).
    let mut amb = splat3(s, if FOLDED { k.base } else { k.ambient });
    // Grey lights (`Setup::grey`): every channel's sums are the same operations on the same
    // values, so the first channel's stand for all three. Six accumulators fewer per chunk, which
    // at AVX2 and AVX-512 kept values on the stack (gbuffer_4096 +15% at AVX-512 on the Zen 4
    // host).
    let channels = if GREY { 1 } else { 3 };
    let mut dif = [zero; 3];
    let mut spe = [zero; 3];
    let lm = &k.lm;
    // The specular gate as `keep(N·L > t, lobe · (a·max(N·L, 0) + b))`, `(t, a, b)` per kind:
    // the step keeps the lobe where N·L > 0 (times exactly 0·x + 1 = 1), the cosine multiplies
    // it by max(N·L, 0) (exactly, as 1·x + 0), and no gate keeps it (N·L is finite in every lane
    // the scalar path does not redo). One fused multiply-add for the factor: a `clamp` took a
    // `max` and a `min`. The instances with per-point inputs (`visibility`, a constant in each)
    // use it: there a `match` per light made the AVX-512 level pass the gated lobe through the
    // stack, on the loop's critical path (gbuffer_4096 +2–5%). Without inputs the `match` costs
    // no store, and this form's extra operations per light (three, with the `clamp`) cost 1–2%
    // in levels_4096.
    let gate = match lm.gate {
        SpecularGate::Step => (zero, zero, one),
        SpecularGate::Cosine => (zero, one, zero),
        SpecularGate::None => (s.splat(f32::NEG_INFINITY), zero, one),
    };
    // Where N·L ≤ 0 leaves a light no diffuse and no specular part: every N·L without a
    // specular lobe, and with one the step and cosine gates' (their threshold, `gate.0`, is 0);
    // with no gate (−∞) the lobe may shine from behind, and no lane is unlit by N·L.
    // (A scalar, splat at the test: sixteen lanes live across the light loop cost the portable
    // level's spills about 9 instructions a point.)
    let unlit_below = match lm.gate {
        SpecularGate::None if k.specular_on => f32::NEG_INFINITY,
        _ => 0.0,
    };
    // One light's terms added to the sums (a macro: its `continue`s are the loop's).
    macro_rules! add_light {
        ($lj:expr, $j:expr) => {{
            let lj: &LightLanes<S> = $lj;
            let j: usize = $j;
        let (la, ld, ls) = (&lj.la, &lj.ld, &lj.ls);
        let light = lj.light;
        // (N·L, L unnormalised, 1/(‖L‖‖V‖), attenuation)
        // A point light, the common kind, first (see `LightLanes::point`).
        macro_rules! point_light {
            () => {{
                let [c0, c1, c2] = lj.c;
                let d = [
                    s.sub(lj.q[0], p[0]),
                    s.sub(lj.q[1], p[1]),
                    s.sub(lj.q[2], p[2]),
                ];
                let dd = dot(s, &d, &d);
                ok = s.and(ok, in_range(s, dd));
                let inv = s.rsqrt(dd);
                let dist = s.mul(dd, inv);
                let den = s.mul_add(dist, s.mul_add(c2, dist, c1), c0);
                // A denominator past f32::MAX (coefficients near it) is evaluated in f64 by
                // `Attenuation::factor`: such lanes go to the scalar path. Tested only where
                // the light's coefficients allow it, a branch the same for every chunk.
                if lj.may_overflow {
                    ok = s.and(ok, s.lt(den, s.splat(f32::INFINITY)));
                }
                let att = s.div(one, s.max(den, s.splat(Attenuation::MIN_DENOMINATOR)));
                (
                    s.mul(dot(s, n, &d), s.mul(inv_n, inv)),
                    d,
                    s.mul(inv, inv_v),
                    att,
                )
            }};
        }
        let (nl, l, inv_lv, att) = if lj.point {
            point_light!()
        } else {
            match light.lane {
                LaneLight::AmbientOnly => {
                    amb = [
                        s.add(amb[0], la[0]),
                        s.add(amb[1], la[1]),
                        s.add(amb[2], la[2]),
                    ];
                    continue;
                }
                LaneLight::Directional(_) => {
                    let l = lj.q;
                    (s.mul(dot(s, n, &l), inv_n), l, inv_v, one)
                }
                LaneLight::Point { .. } => point_light!(),
                // Never met: `CALLS` is false only where no light is a falloff light (and were
                // it met, every lane would go to the scalar path).
                LaneLight::Falloff { .. } if !CALLS => {
                    ok = s.and(ok, s.lt(zero, zero));
                    continue;
                }
                LaneLight::Falloff { position, spot, .. } => {
                    let (d, _) = offset_to(s, &splat3(s, position), p, &mut ok);
                    let spot = spot.as_ref().map(|spot| (spot, light.spot_pow));
                    let (l, att) = falloff(s, &d, &light.flat, spot);
                    // N·L at most 1, as the exact cosine is: this light's factor can reach
                    // f32::MAX (an inverse-square falloff with a huge power), and a cosine
                    // rounded above 1 would carry `f·max(N·L, 0)` (or the cosine gate's
                    // `f·w·N·L`) past it to +∞ where the exact product is finite. Point lights'
                    // factors are at most 1/MIN_DENOMINATOR, and directional lights' 1.
                    let nl = s.min(s.mul(dot(s, n, &l), inv_n), one);
                    (nl, l, inv_v, att)
                }
            }
        };
        let nl0 = s.max(nl, zero);
        // The visibility scales the diffuse and specular parts.
        let vis = match visibility {
            Some((inputs, i, count)) => {
                let vis = s.load(&inputs.visibility(j, i, count));
                Some(s.min(s.max(vis, zero), one))
            }
            None => None,
        };
        // A light dark at every point of the chunk adds its ambient part alone: shadowed
        // (visibility 0 in every lane, as across a shadow map's dark regions), or behind every
        // point's surface (N·L ≤ 0 in every lane, as across a sphere's far side from the light)
        // where the gate zeroes the lobe there (`unlit_below`). Its diffuse and specular
        // products are then f·0·w = 0 and f·w·0 = 0 in every lane the scalar path does not
        // redo (f and w finite; a lane whose N·L is NaN is redone), and the ambient sums below
        // take `att·La` (`Ka⊙La` folded) exactly as here, so the skip keeps the bits. One test
        // per light and chunk, where there are visibilities.
        if let Some(vis) = vis {
            if s.bits(s.and(s.gt(vis, zero), s.gt(nl, s.splat(unlit_below)))) == 0 {
                if k.specular_on && lm.lobe == Lobe::Blinn {
                    // The lanes that Blinn-Phong's cosine form sends to the scalar path (below)
                    // go there still: which path shades a point must not depend on whether its
                    // neighbours in the chunk are shadowed (a coverage mask or a tile moves them).
                    // (Computed again here rather than hoisted above the skip for both: hoisted,
                    // `shade_batch` ran about 5% more instructions at SSE2, by callgrind.)
                    let den = blinn_den(s, s.mul(dot(s, &l, &v), inv_lv));
                    ok = s.and(ok, s.ge(den, s.splat(BLINN_DEN_MIN)));
                }
                for c in 0..if FOLDED { 3 } else { channels } {
                    amb[c] = s.mul_add(att, la[c], amb[c]);
                }
                continue;
            }
        }
        let attv = match vis {
            Some(vis) => s.mul(att, vis),
            None => att,
        };
        // The light's gated, scaled-later specular lobe, without its factor.
        let spec = if k.specular_on {
            let lv = s.mul(dot(s, &l, &v), inv_lv);
            let base = match lm.lobe {
                Lobe::Blinn => {
                    let sum = s.max(s.add(nl, nv), zero);
                    let den = blinn_den(s, lv);
                    // Near L = −V the cosine form's 2 + 2 L·V has lost its digits
                    // (docs/accuracy.md): those rare lanes go to the scalar path, which uses
                    // ‖L+V‖² from the vectors.
                    ok = s.and(ok, s.ge(den, s.splat(BLINN_DEN_MIN)));
                    let q = s.min(s.div(s.mul(sum, sum), den), one);
                    s.keep(s.gt(den, s.splat(1e-12)), q)
                }
                _ => s.min(s.mul_sub(nl, nv2, lv), one),
            };
            let lobe = match surface {
                Some(sf) => auto_pow(s, base, sf),
                None => pow::<S, CALLS>(s, plan, k.flush, base),
            };
            Some(if visibility.is_some() {
                // The gate without a branch on its kind (see `gate` above).
                s.keep(s.gt(nl, gate.0), s.mul(lobe, s.mul_add(nl0, gate.1, gate.2)))
            } else {
                match lm.gate {
                    SpecularGate::Step => s.keep(s.gt(nl, zero), lobe),
                    SpecularGate::Cosine => s.mul(nl0, lobe),
                    SpecularGate::None => lobe,
                }
            })
        } else {
            None
        };
        // f and f·max(N·L, 0) are finite (f ≤ 1/MIN_DENOMINATOR), and so is every colour: no
        // product below is 0·∞, and the sums of terms ≥ 0 can reach +∞ but never NaN.
        if FOLDED {
            // Per channel: amb += f·(La' + vis·max(N·L, 0)·Ld' + vis·lobe·Ls'), the light's
            // terms summed first so the chains into `amb` stay short. The scale is in `ks`, and
            // nothing overflows. The visibility multiplies the cosine and the lobe, so where it
            // is 1 (a call without visibilities, run by this instance for 8-bit output) those
            // products are exact and the bits are the instance's without inputs: 8-bit output
            // stays `shade_batch`'s, encoded.
            let (nlv, specv) = match (vis, spec) {
                (Some(vis), Some(w)) => (s.mul(nl0, vis), Some(s.mul(w, vis))),
                (Some(vis), None) => (s.mul(nl0, vis), None),
                (None, spec) => (nl0, spec),
            };
            for c in 0..3 {
                let t = s.mul_add(nlv, ld[c], la[c]);
                let t = match specv {
                    Some(w) => s.mul_add(w, ls[c], t),
                    None => t,
                };
                amb[c] = s.mul_add(att, t, amb[c]);
            }
            continue;
        }
        let wd = s.mul(attv, nl0);
        for c in 0..channels {
            amb[c] = s.mul_add(att, la[c], amb[c]);
            dif[c] = s.mul_add(wd, ld[c], dif[c]);
        }
        if let Some(w) = spec {
            // A normalisation factor can be as large as f32::MAX: f·factor·lobe is clamped there
            // (as `shade` clamps its weight) before it meets a colour, so a zero lobe stays 0.
            let ws = s.mul(attv, w);
            let ws = match surface {
                Some(SurfaceV {
                    scale: Some(scale),
                    ..
                }) => s.min(s.mul(ws, *scale), max),
                // f ≤ 1/MIN_DENOMINATOR, the visibility and the lobe ≤ 1: finite.
                Some(_) => ws,
                None if k.scaled => s.min(s.mul(ws, s.splat(lm.specular_scale)), max),
                None => ws,
            };
            for c in 0..channels {
                spe[c] = s.mul_add(ws, ls[c], spe[c]);
            }
        }
        }};
    }
    for j in 0..k.lights {
        let owned;
        let lj: &LightLanes<S> = if !CALLS || k.all_prepared {
            // Without calls, every light is prepared (`Setup::calls_out`).
            lights.prepared(j % PREPARED)
        } else if j < PREPARED {
            lights.prepared(j)
        } else {
            let light = match lights.more.get(j - PREPARED) {
                Some(&light) => light,
                None => call.light(k, j),
            };
            owned = LightLanes::new(s, light, FOLDED);
            &owned
        };
        add_light!(lj, j);
    }
    let bad = !s.bits(ok) & 0xffff;
    (
        if FOLDED {
            [amb, [zero; 3], [zero; 3]]
        } else if GREY {
            [[amb[0]; 3], [dif[0]; 3], [spe[0]; 3]]
        } else {
            [amb, dif, spe]
        },
        bad,
    )
}

/// A chunk's colours from [`chunk`]'s light sums: the three terms `[ambient, diffuse, specular]`
/// (`terms`, a constant wherever this is inlined), or the total in the first row. Each sum saturates at `f32::MAX` before the
/// material's colour multiplies it; the total saturates again (`shade`'s order: ambient +
/// diffuse + specular + emission). `FOLDED`: the first sum is already the total.
#[inline(always)]
fn finish<S: Simd, const FOLDED: bool>(
    s: S,
    terms: bool,
    saturate: bool,
    k: &Setup<'_>,
    reflectances: Option<&[[S::V; 3]; 3]>,
    sums: [[S::V; 3]; 3],
) -> [[S::V; 3]; 3] {
    let max = s.splat(math::MAX);
    let zero = s.splat(0.0);
    let [amb, dif, spe] = sums;
    if FOLDED {
        let total = if saturate {
            [s.min(amb[0], max), s.min(amb[1], max), s.min(amb[2], max)]
        } else {
            amb
        };
        return [total, [zero; 3], [zero; 3]];
    }
    let ke = k.material.emission();
    let mut rows = [[zero; 3]; 3];
    for c in 0..3 {
        let (ka, kd, ks) = match reflectances {
            Some(r) => (r[0][c], r[1][c], r[2][c]),
            None => (
                s.splat(k.material.ambient()[c]),
                s.splat(k.material.diffuse()[c]),
                s.splat(k.material.specular()[c]),
            ),
        };
        // Each sum clamped first, so that a zero colour times it stays 0 (never 0·∞).
        let td = s.mul(kd, s.min(dif[c], max));
        let ts = s.mul(ks, s.min(spe[c], max));
        if terms {
            let ta = s.mul(ka, s.min(amb[c], max));
            (rows[0][c], rows[1][c], rows[2][c]) = (s.min(ta, max), s.min(td, max), s.min(ts, max));
        } else {
            // The emission joins the ambient product in one fused multiply-add: for `Ke = 0`
            // (most materials) that is the product's own bits, and otherwise `Terms::total`'s order
            // (ambient and emission first) with one rounding fewer. The terms are `≥ 0` (or +∞), so
            // their sum reaches `f32::MAX` or +∞ exactly when it does with each term clamped
            // first, as `Terms::total` sums them: one `min` at the end gives the same bits, and
            // a sink that clamps below 1 anyway (`saturate` false: 8-bit pixels) skips it.
            let ta = s.mul_add(ka, s.min(amb[c], max), s.splat(ke[c]));
            let total = s.add(s.add(ta, td), ts);
            rows[0][c] = if saturate { s.min(total, max) } else { total };
        }
    }
    rows
}

/// Runs the kernel at level `S` over the common prefix of the slices; returns its length.
/// `INPUTS` says whether `inputs` may hold per-point inputs. Each combination of the call's
/// parameters is a separate instance of [`run_with`], compiled for the level as a function of
/// its own ([`Kernels::instance`]); this picks it, once per call.
#[inline(always)]
pub(crate) fn run<S: Kernels, O: Sink, const INPUTS: bool>(s: S, job: Job<'_, O>) -> usize {
    if !INPUTS {
        return match (job.setup.folded, job.setup.calls_out) {
            // `CALLS` is false only where the plan is not `Exact`.
            (true, false) => match job.setup.plan {
                PowPlan::Squaring { .. } => {
                    s.instance::<O, true, false, false, false, false, PLAN_SQUARING>(job)
                }
                PowPlan::Poly { poly: Poly::P7, .. } => {
                    s.instance::<O, true, false, false, false, false, PLAN_POLY7>(job)
                }
                _ => s.instance::<O, true, false, false, false, false, PLAN_ANY>(job),
            },
            (true, true) => s.instance::<O, true, false, true, false, false, PLAN_ANY>(job),
            (false, false) => s.instance::<O, false, false, false, false, false, PLAN_ANY>(job),
            (false, true) => s.instance::<O, false, false, true, false, false, PLAN_ANY>(job),
        };
    }
    // A per-point surface without visibilities runs the instance with both, its visibilities
    // read as 1 (`PointInputs::visibility`): `f·clamp(1, 0, 1)` is `f`, so the bits are those
    // of an instance without them, and the build compiles one kernel fewer per level and sink.
    let k = job.setup;
    match job.inputs.per_point_surface() {
        false => match (k.folded, k.calls_out) {
            (true, true) => s.instance::<O, true, false, true, false, true, PLAN_ANY>(job),
            (true, false) => s.instance::<O, true, false, false, false, true, PLAN_ANY>(job),
            (false, true) => s.instance::<O, false, false, true, false, true, PLAN_ANY>(job),
            (false, false) => s.instance::<O, false, false, false, false, true, PLAN_ANY>(job),
        },
        true if k.surface_calls_out => {
            s.instance::<O, false, false, true, true, true, PLAN_ANY>(job)
        }
        true if k.grey => s.instance::<O, false, true, false, true, true, PLAN_ANY>(job),
        true => s.instance::<O, false, false, false, true, true, PLAN_ANY>(job),
    }
}

/// The general instance, for any job and sink: products not folded (valid whatever the scene's
/// magnitudes), per-lane calls allowed, and per-point surfaces and visibilities read where the
/// call has them (the material's values and full visibility where it has not). [`run`]'s other
/// instances are this one specialised; their results differ from it only by rounding. It is
/// the one instance that writes the three terms.
#[inline(always)]
pub(crate) fn run_general<S: Kernels, O: Sink>(s: S, job: Job<'_, O>) -> usize {
    s.instance::<O, false, false, true, true, true, PLAN_ANY>(job)
}

/// Whether a call has per-point inputs (a G-buffer's surfaces or visibilities).
#[inline]
pub(crate) fn has_inputs(inputs: &PointInputs<'_>) -> bool {
    inputs.per_point_surface() || inputs.visibility.is_some()
}

/// One chunk of [`run_with`]: points `i..i + count` (their positions `p` and normals `n`)
/// shaded, as [`finish`] gives them, with the lanes the scalar path must redo.
#[inline(always)]
#[allow(
    clippy::too_many_arguments,
    reason = "the level, the call, the chunk's lanes and where they are"
)]
fn shade_chunk<
    S,
    const FOLDED: bool,
    const GREY: bool,
    const CALLS: bool,
    const SURFACE: bool,
    const VISIBILITY: bool,
>(
    s: S,
    terms: bool,
    saturate: bool,
    k: &Setup<'_>,
    call: &dyn Call,
    lights: &ChunkLights<'_, S>,
    p: [Lanes; 3],
    n: [Lanes; 3],
    inputs: &PointInputs<'_>,
    i: usize,
    count: usize,
    plan: PowPlan,
) -> ([[S::V; 3]; 3], u32)
where
    S: Simd,
{
    let surface = if SURFACE {
        SurfaceV::load(s, &k.lm, inputs, i, count)
    } else {
        None
    };
    let visibility = if VISIBILITY {
        Some((inputs, i, count))
    } else {
        None
    };
    let (sums, bad) = chunk::<S, FOLDED, GREY, CALLS>(
        s,
        k,
        call,
        lights,
        &[s.load(&p[0]), s.load(&p[1]), s.load(&p[2])],
        &[s.load(&n[0]), s.load(&n[1]), s.load(&n[2])],
        surface.as_ref(),
        visibility,
        plan,
    );
    // The reflectances only now, after the sums (see `SurfaceV`).
    let reflectances = if SURFACE {
        reflectances(s, inputs, i, count)
    } else {
        None
    };
    (
        finish::<S, FOLDED>(s, terms, saturate, k, reflectances.as_ref(), sums),
        bad,
    )
}

/// [`run`] for one combination: `SURFACE` and `VISIBILITY` say which of `inputs` are present;
/// the sink `O` says whether the terms or their total are written.
#[inline(always)]
pub(crate) fn run_with<
    S,
    O: Sink,
    const FOLDED: bool,
    const GREY: bool,
    const CALLS: bool,
    const SURFACE: bool,
    const VISIBILITY: bool,
    const PLAN: u8,
>(
    s: S,
    job: Job<'_, O>,
) -> usize
where
    S: Simd,
{
    let Job {
        setup: k,
        call,
        pos,
        nor,
        inputs,
        mut out,
        spans,
    } = job;
    let len = pos.len().min(nor.len()).min(out.len());
    let plan = plan_of::<PLAN>(k.plan);
    let pos = SoaVec3 {
        x: &pos.x[..len],
        y: &pos.y[..len],
        z: &pos.z[..len],
    };
    let nor = SoaVec3 {
        x: &nor.x[..len],
        y: &nor.y[..len],
        z: &nor.z[..len],
    };
    // The scalar fix-up reads per-point inputs only where the call has some: an instance with
    // inputs also runs calls without them (8-bit output), whose lanes `shade` redoes with the
    // material's own pow plan, as the instance without inputs did.
    let per_point = ((SURFACE || VISIBILITY) && has_inputs(inputs)).then_some(inputs);
    // Lights past the first PREPARED, prepared once here (a loop, as above), where the call has
    // more than one chunk: for one chunk (a row of a tile in `shade_gbuffer_tiled`) each light
    // is prepared once either way, and filling the array would cost more than it saves.
    let mut more_store;
    let more: &[PreparedLight] = if CALLS && !k.all_prepared && len > W {
        more_store = [k.prepared[0]; MORE];
        let count = (k.lights - PREPARED).min(MORE);
        for (j, slot) in more_store.iter_mut().enumerate().take(count) {
            *slot = call.light(k, PREPARED + j);
        }
        &more_store[..count]
    } else {
        &[]
    };
    // The first lights' constants in every lane, once per call, in place (see `ChunkLights`; a
    // loop, not `array::from_fn`: a closure may be left out of line, without the level's target
    // features).
    let mut lights = ChunkLights {
        zeroth: LightLanes::new(s, k.prepared[0], FOLDED),
        rest: [None; PREPARED - 1],
        more,
        eye: match k.view {
            ViewK::At(e) => splat3(s, e),
            ViewK::Infinite(_) => [s.splat(0.0); 3],
        },
    };
    // The zip stops at the last slot; `take` at the scene's last light.
    for (slot, &light) in lights
        .rest
        .iter_mut()
        .zip(&k.prepared[1..])
        .take(k.lights.saturating_sub(1))
    {
        *slot = Some(LightLanes::new(s, light, FOLDED));
    }
    // A sink that encodes its output (`Sink::DEFER`: 8-bit pixels) writes each chunk after the
    // next one is shaded: the encoding's chain of dependent operations then overlaps the next
    // chunk's shading instead of following its own chunk's (`shade_batch_rgba8` +24% at AVX-512,
    // +9% at AVX2 on the Zen 4 host; the G-buffer's longer chunks +3%). A chunk with lanes for
    // the scalar path is written at once (after the one pending), so the scalar path's points
    // land after the kernel's.
    // Only the total is held (`!O::TERMS`): the other rows are zero.
    let defer = O::DEFER && !O::TERMS;
    let zero = s.splat(0.0);
    let mut pending: Option<(usize, usize, [S::V; 3])> = None;
    macro_rules! write_total {
        ($held:expr) => {
            if let Some((at, n, total)) = $held {
                out.write(s, at, n, &[total, [zero; 3], [zero; 3]]);
            }
        };
    }
    // One chunk: a macro, not a closure (a closure may be left out of line, without the
    // level's target features).
    macro_rules! chunk_at {
        ($i:expr, $count:expr, $p:expr, $n:expr) => {{
            let (i, count) = ($i, $count);
            let (rows, bad) = shade_chunk::<S, FOLDED, GREY, CALLS, SURFACE, VISIBILITY>(
                s,
                O::TERMS,
                O::SATURATES,
                k,
                call,
                &lights,
                $p,
                $n,
                inputs,
                i,
                count,
                plan,
            );
            let bad = bad & (u32::MAX >> (32 - count));
            if defer && bad == 0 {
                write_total!(pending.replace((i, count, rows[0])));
            } else {
                write_total!(pending.take());
                out.write(s, i, count, &rows);
                if bad != 0 {
                    call.fixup((&pos, &nor), per_point, i, bad, &mut |at, t| out.put(at, t));
                }
            }
        }};
    }
    let mut runs = spans.map(TileSpans::runs);
    let mut whole = Some(0..len);
    loop {
        let span = match runs.as_mut() {
            Some(runs) => runs.next(),
            None => whole.take(),
        };
        let Some(span) = span else { break };
        let end = span.end.min(len);
        let mut i = span.start.min(end);
        let full = i + (end - i) / W * W;
        while i < full {
            chunk_at!(
                i,
                W,
                [load(pos.x, i), load(pos.y, i), load(pos.z, i)],
                [load(nor.x, i), load(nor.y, i), load(nor.z, i)]
            );
            i += W;
        }
        if i < end {
            // The padding lanes are shaded too (zero normals: flagged) and fixed only up to
            // `count`.
            let count = end - i;
            chunk_at!(
                i,
                count,
                [
                    load_tail(pos.x, i, count),
                    load_tail(pos.y, i, count),
                    load_tail(pos.z, i, count),
                ],
                [
                    load_tail(nor.x, i, count),
                    load_tail(nor.y, i, count),
                    load_tail(nor.z, i, count),
                ]
            );
        }
    }
    write_total!(pending);
    len
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::batch::simd::portable::Portable;
    use crate::pow::error_bounds::worst_over_domain;

    /// The kernel's `pow` at level `s` meets every strategy's bound: the kernels' pow flushes
    /// the bases whose power would fall below 2⁻⁶⁰ as the scalar one does (an absolute error
    /// under 2⁻⁶⁰, far below the bound's 2⁻²⁴ floor), and differs from it where the level fuses
    /// multiply-adds, in the polynomials' rounding.
    fn lobe_power_meets_each_strategys_bound<S: Simd>(s: S, level: &str) {
        for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let (e, x, sh) = worst_over_domain(p, |sh, xs| {
                let plan = p.plan(sh);
                s.store(pow::<S, true>(s, plan, flush_below(plan), s.load(xs)))
            });
            assert!(
                e <= p.max_relative_error() as f64,
                "{level}, {p:?}: err {e:e} at x = {x:e}, s = {sh:e}"
            );
        }
    }

    /// The per-point power at its edges, with no select for them: an exponent of 0 gives exactly
    /// 1 for every base in `(0, 1]`, subnormal ones included, and a base `≤ 0` (or NaN) gives 0
    /// at every exponent.
    fn per_point_power_edges<S: Simd>(s: S, level: &str) {
        let bases = [
            1.0,
            0.5,
            1e-20,
            f32::MIN_POSITIVE,
            f32::MIN_POSITIVE / 3.0,
            f32::from_bits(1),
            0.999_999_9,
            0.25,
            0.0,
            -0.0,
            -1.0,
            -f32::MIN_POSITIVE,
            f32::NAN,
            -f32::MAX,
            0.75,
            0.125,
        ];
        for e in [0.0, 1e-30, 0.5, 1.0, 20.5, 128.0, 1e30, math::MAX] {
            let sf = SurfaceV::<S> {
                scale: None,
                exponent: s.splat(e),
            };
            let got = s.store(auto_pow(s, s.load(&bases), &sf));
            for (&x, &y) in bases.iter().zip(&got) {
                if x > 0.0 && e == 0.0 {
                    assert_eq!(y, 1.0, "{level}: {x:e}^0");
                } else if !(x > 0.0) {
                    assert_eq!(y.to_bits(), 0, "{level}: {x:e}^{e:e}");
                } else {
                    assert!((0.0..=1.0).contains(&y), "{level}: {x:e}^{e:e} = {y:e}");
                }
            }
        }
    }

    /// `squaring` at level `s` is the scalar `pow_u32`, bit for bit, for every exponent a plan
    /// can hold and bases at or above the flush (below it, 0).
    fn squaring_is_pow_u32<S: Simd>(s: S, level: &str) {
        let mut bases: Lanes = [
            1.0,
            0.999_999_9,
            0.999,
            0.99,
            0.9,
            0.75,
            0.7,
            0.5,
            0.3,
            0.25,
            0.1,
            0.01,
            1e-3,
            1e-6,
            0.0,
            0.0,
        ];
        for n in 0..=1024u32 {
            let flush = flush_below(PowPlan::Squaring { n });
            // The last two lanes: the flush itself and the largest base below it.
            (bases[14], bases[15]) = (flush, f32::from_bits(flush.to_bits().saturating_sub(1)));
            let got = s.store(squaring(s, s.load(&bases), flush, n));
            for (&x, &y) in bases.iter().zip(&got) {
                let want = if x >= flush {
                    crate::pow::pow_u32(x, n)
                } else {
                    0.0
                };
                assert_eq!(y.to_bits(), want.to_bits(), "{level}: {x:e}^{n}");
            }
        }
    }

    /// Where `may_overflow` lets the kernel skip its test, the `f32` denominator stays finite
    /// at the largest distance a kept lane can have (`√HI`, and a little past it for the inverse
    /// square root's error), for coefficients on both sides of the bound.
    #[test]
    fn a_skipped_overflow_test_could_not_have_failed() {
        // `may_overflow`'s distance is √HI.
        assert!((f64::from(HI).sqrt() / 1e15 - 1.0).abs() < 1e-6);
        let d = HI.sqrt() * (1.0 + 1e-3);
        let mut skipped = 0;
        for k in 0..=80 {
            let x = f32::MAX * 2f32.powi(-k);
            for c in [
                [x, 0.0, 0.0],
                [0.0, x / 1e15, 0.0],
                [0.0, 0.0, x / 1e30],
                [x, x, x],
            ] {
                if may_overflow(c) {
                    continue;
                }
                skipped += 1;
                let den = d.mul_add(c[2].mul_add(d, c[1]), c[0]);
                assert!(den < f32::INFINITY, "{c:?}: {den}");
            }
        }
        // The bound is not vacuous: most of these sets skip the test, the largest keep it.
        assert!(skipped > 200, "{skipped}");
        assert!(may_overflow([0.0, 0.0, 1e9]));
    }

    /// Runs `$check(level, name)` at every level this CPU has.
    macro_rules! at_every_level {
        ($check:ident) => {{
            $check(Portable, "portable");
            #[cfg(target_arch = "x86_64")]
            {
                use crate::batch::simd::{avx2::Avx2, avx512::Avx512, sse2::Sse2};
                $check(Sse2, "sse2");
                if let Some(t) = Avx2::new() {
                    $check(t, "avx2");
                }
                if let Some(t) = Avx512::new() {
                    $check(t, "avx512");
                }
            }
            #[cfg(all(target_arch = "aarch64", target_feature = "neon"))]
            $check(crate::batch::simd::neon::Neon, "neon");
        }};
    }
    pub(in crate::batch) use at_every_level;

    #[test]
    fn squaring_is_the_scalar_ladder_at_every_level() {
        at_every_level!(squaring_is_pow_u32);
    }

    #[test]
    fn the_per_point_power_keeps_its_edges_at_every_level() {
        at_every_level!(per_point_power_edges);
    }

    #[test]
    fn the_lobe_power_meets_each_strategys_bound_at_every_level() {
        at_every_level!(lobe_power_meets_each_strategys_bound);
    }
}
