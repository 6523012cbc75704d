//! The batch path's documented accuracy as a check: the range of values the Phong-family equation
//! takes, in `f64`, when its inputs move by the perturbations the module docs of `phong::batch`
//! ("Accuracy") allow, with the saturation rule ("Saturation") applied. A batch result outside it
//! breaks the promise; so does a `shade` result (whose perturbations are smaller), except in the
//! overflow regime, where only the batch's rule is checked.

use core::any::Any;

use glam::{DVec3, Vec3};
use phong::{
    Light, LightSource, Material, Model, Normalization, PowStrategy, ResolvedModel, Scene,
    SpecularGate, SpotLight, Viewer,
};

/// The most `f32` operations between a light's inputs and the output channel, each of which may
/// underflow into the subnormal range (see `range`).
pub const UNDERFLOW_OPS: f64 = 32.0;
/// `f32`'s unit roundoff.
pub const U: f64 = 1.0 / 16_777_216.0;
/// How far each cosine the kernel uses may be from the exact one (module docs: `η`).
pub const ETA: f64 = 2e-6;
/// How far a point light's attenuation factor may be from the exact one, relative.
pub const ATT_REL: f64 = 2e-6;
/// How far Blinn-Phong's `(N·H)²` may be from the cosine form of the perturbed cosines, relative.
pub const BLINN_REL: f64 = 3.0 * U;
const MAX: f64 = f32::MAX as f64;

/// Per channel: the lowest and highest value the promise allows, and whether any of the three
/// sums or their products with the material's colours reaches `f32::MAX` (the overflow regime).
#[derive(Clone, Copy, Debug)]
pub struct Range {
    /// The lowest value per channel.
    pub lo: DVec3,
    /// The highest value per channel.
    pub hi: DVec3,
    /// Whether the point is in the overflow regime.
    pub saturated: bool,
}

impl Range {
    /// Whether `c` lies in the range, per channel.
    pub fn holds(&self, c: Vec3) -> bool {
        let c = c.as_dvec3();
        c.is_finite() && c.cmpge(self.lo).all() && c.cmple(self.hi).all()
    }
}

/// An interval `[lo, hi]`.
type Iv = (f64, f64);

fn clamp_iv((a, b): Iv, lo: f64, hi: f64) -> Iv {
    (a.clamp(lo, hi), b.clamp(lo, hi))
}

/// The cosine `c` moved by up to `ETA`. Not clamped to `[−1, 1]`: the promise is only that a
/// cosine the kernel uses is within `ETA` of the exact one, and dot products of rounded unit vectors
/// do leave `[−1, 1]` by a few ulps (with `L ≈ −V`, an `L·V` of `−1 − 2⁻²⁴` moves Phong's
/// `R·V = 2(N·L)(N·V) − L·V` up by an ulp, which the exponent then multiplies).
fn cosine(c: f64) -> Iv {
    (c - ETA, c + ETA)
}

fn mul_iv(a: Iv, b: Iv) -> Iv {
    let p = [a.0 * b.0, a.0 * b.1, a.1 * b.0, a.1 * b.1];
    (
        p.iter().copied().fold(f64::INFINITY, f64::min),
        p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

/// `x^p` for `x > 0`, 0 for `x ≤ 0` (the crate's `0^0 = 0`): non-decreasing in `x`.
fn lobe_pow(x: f64, p: f64) -> f64 {
    if x > 0.0 { x.min(1.0).powf(p) } else { 0.0 }
}

/// The lobe power over a base interval, widened by the strategy's error bound.
fn lobe_iv(base: Iv, p: f64, pow: PowStrategy) -> Iv {
    let eps = pow.max_relative_error() as f64;
    let floor = PowStrategy::ERROR_FLOOR as f64;
    let (lo, hi) = (lobe_pow(base.0, p), lobe_pow(base.1, p));
    (
        (lo - eps * lo.max(floor)).max(0.0),
        (hi + eps * hi.max(floor)).min(1.0),
    )
}

/// `v / ‖v‖` in `f64`, or `None` for the zero vector.
fn unit(v: Vec3) -> Option<DVec3> {
    let d = v.as_dvec3();
    let l = d.length();
    (l > 0.0).then(|| d / l)
}

/// `a − b` saturated to `±f32::MAX`, as the crate's total paths form differences.
fn sub_saturating(a: Vec3, b: Vec3) -> Vec3 {
    (a - b).clamp(Vec3::splat(-f32::MAX), Vec3::splat(f32::MAX))
}

/// For a spot light whose exponent `e` is neither 0 nor 1, the range of its factor `f·c^e` (`f` the
/// point light's factor, `c` the cosine to the axis) when the power is within
/// `PowStrategy::Auto`'s bound for `e` (the batch kernel's spot power, module docs of
/// `phong::batch`); `None` for every other light, whose factor is `shade`'s.
fn spot_power_range<L: LightSource + 'static>(light: &L, p: Vec3, l: Vec3) -> Option<Iv> {
    let any: &dyn Any = light;
    let spot = match any.downcast_ref::<Light>() {
        Some(Light::Spot(spot)) => spot,
        Some(_) => return None,
        None => any.downcast_ref::<SpotLight>()?,
    };
    let e = spot.exponent();
    if spot.cos_cutoff() < 0.0 || e == 0.0 || e == 1.0 {
        return None;
    }
    let c = -l.dot(spot.axis());
    let exact = if c >= spot.cos_cutoff() && c > 0.0 {
        f64::from(c.min(1.0)).powf(f64::from(e))
    } else {
        0.0
    };
    let f = f64::from(spot.point().sample(p).factor);
    let eps = f64::from(PowStrategy::Auto.resolve(e).max_relative_error())
        * exact.max(f64::from(PowStrategy::ERROR_FLOOR));
    Some((f * (exact - eps).max(0.0), (f * (exact + eps)).min(MAX)))
}

/// The model's gate, normalisation, pow strategy, and whether its lobe is Blinn-Phong's (`None`
/// for Lambert).
fn parts(model: &Model) -> (SpecularGate, Normalization, Option<(PowStrategy, bool)>) {
    match *model {
        Model::Lambert(m) => (SpecularGate::Step, m.normalization, None),
        Model::Phong(m) => (m.gate, m.normalization, Some((m.pow, false))),
        Model::BlinnPhong(m) => (m.gate, m.normalization, Some((m.pow, true))),
    }
}

/// The range the batch path promises for the point `p` with normal `n`, per channel (module docs
/// of `phong::batch`: every cosine within `ETA`, attenuation within `ATT_REL`, Blinn's base within
/// `BLINN_REL`, the lobe power within the strategy's error, the saturation rule, and a rounding
/// allowance of `(8 + 2·lights)·U` relative in each sum and in the total).
pub fn range<L: LightSource + 'static>(
    model: &Model,
    material: &Material,
    scene: &Scene<'_, L>,
    p: Vec3,
    n: Vec3,
) -> Range {
    let (gate, normalization, lobe) = parts(model);
    let normalized = normalization != Normalization::None;
    // The model's own lobe factor at this shininess (1 for a classic lobe).
    let k_norm = ResolvedModel::from(*model).specular_scale(material.shininess());
    let s = material.shininess() as f64;
    let n = unit(n);
    let v = match scene.viewer {
        Viewer::At(eye) => unit(sub_saturating(eye, p)),
        Viewer::Infinite(d) => unit(d),
    };
    let dscale = if normalized {
        1.0 / core::f64::consts::PI
    } else {
        1.0
    };
    let ia = scene.ambient.max(Vec3::ZERO).as_dvec3();
    // The three sums per channel, at the low and the high end.
    let (mut a, mut d, mut sp) = ([ia, ia], [DVec3::ZERO; 2], [DVec3::ZERO; 2]);
    let mut huge = false;
    // Gradual underflow: each f32 operation whose result falls below 2⁻¹²⁶ errs by up to 2⁻¹⁵⁰
    // absolute instead of relatively, and that error is multiplied by whatever follows it: at most
    // the light's factor, the normalisation factor and the light's and the material's colours, each
    // where it exceeds 1. `UNDERFLOW_OPS` bounds the operations per light.
    let big = |x: Vec3| x.as_dvec3().max(DVec3::ONE);
    let mut underflow = big(scene.ambient.max(Vec3::ZERO)) * big(material.ambient());
    for light in scene.lights {
        let sample = light.sample(p);
        let f0 = sample.factor as f64;
        let c = light.colors();
        underflow += f0.max(1.0)
            * (big(c.ambient()) * big(material.ambient())
                + big(c.diffuse()) * big(material.diffuse())
                + big(c.specular()) * big(material.specular()) * (k_norm as f64).max(1.0));
        if f0 == 0.0 {
            continue;
        }
        // `shade` before the saturation rule clamped each light's colour × material product.
        let products = [
            c.ambient() * material.ambient(),
            c.diffuse() * material.diffuse(),
            c.specular() * material.specular(),
        ];
        huge |= products.iter().any(|x| x.max_element() as f64 >= 0.5 * MAX);
        let (f_lo, f_hi) = spot_power_range(light, p, sample.direction).unwrap_or((f0, f0));
        let f = (f_lo * (1.0 - ATT_REL), f_hi * (1.0 + ATT_REL));
        a[0] += f.0 * c.ambient().as_dvec3();
        a[1] += f.1 * c.ambient().as_dvec3();
        let (Some(n), Some(l)) = (n, unit(sample.direction)) else {
            continue;
        };
        let nl = cosine(n.dot(l));
        let diffuse = (dscale * nl.0.max(0.0), dscale * nl.1.max(0.0));
        d[0] += f.0 * diffuse.0 * c.diffuse().as_dvec3();
        d[1] += f.1 * diffuse.1 * c.diffuse().as_dvec3();
        let (Some((pow, blinn)), Some(v)) = (lobe, v) else {
            continue;
        };
        let (nv, lv) = (cosine(n.dot(v)), cosine(l.dot(v)));
        let (base, exponent, factor) = if blinn {
            let t = ((nl.0 + nv.0).max(0.0), (nl.1 + nv.1).max(0.0));
            let den = (2.0 + 2.0 * lv.0, 2.0 + 2.0 * lv.1);
            let lo = t.0 * t.0 / den.1 * (1.0 - BLINN_REL);
            let hi = if den.0 > 0.0 {
                t.1 * t.1 / den.0 * (1.0 + BLINN_REL)
            } else {
                1.0
            };
            (clamp_iv((lo, hi), 0.0, 1.0), 0.5 * s, k_norm as f64)
        } else {
            let nn = mul_iv(nl, nv);
            let rv = (2.0 * nn.0 - lv.1, 2.0 * nn.1 - lv.0);
            (clamp_iv(rv, -1.0, 1.0), s, k_norm as f64)
        };
        let lobe = lobe_iv(base, exponent, pow);
        let g = if normalized {
            (factor * nl.0.max(0.0), factor * nl.1.max(0.0))
        } else {
            match gate {
                SpecularGate::Step => ((nl.0 > 0.0) as u8 as f64, (nl.1 > 0.0) as u8 as f64),
                SpecularGate::Cosine => (nl.0.max(0.0), nl.1.max(0.0)),
                SpecularGate::None => (1.0, 1.0),
            }
        };
        sp[0] += (f.0 * g.0 * lobe.0).min(MAX) * c.specular().as_dvec3();
        sp[1] += (f.1 * g.1 * lobe.1).min(MAX) * c.specular().as_dvec3();
    }
    let k = [
        material.ambient().as_dvec3(),
        material.diffuse().as_dvec3(),
        material.specular().as_dvec3(),
    ];
    let ke = material.emission().as_dvec3();
    // Rounding: relative `ρ` on each sum (its own additions and the products in its terms) and on
    // the total (the material's products and the final additions); all terms are ≥ 0, so a relative
    // allowance on the exact values bounds it, and the saturation rule is monotone in each.
    let rho = (8.0 + 2.0 * scene.lights.len() as f64) * U;
    let sat = |x: DVec3| x.min(DVec3::splat(MAX));
    let rule = |i: usize, sigma: f64| {
        let term = |k: DVec3, sum: DVec3| sat(k * sat(sum * sigma));
        sat((term(k[0], a[i]) + term(k[1], d[i]) + term(k[2], sp[i]) + ke) * sigma)
    };
    let saturated = huge
        || [a[1], d[1], sp[1], k[0] * a[1], k[1] * d[1], k[2] * sp[1]]
            .iter()
            .any(|x| x.max_element() >= 0.5 * MAX);
    let underflow = underflow * UNDERFLOW_OPS * 2f64.powi(-150);
    Range {
        lo: (rule(0, 1.0 - rho) - underflow).max(DVec3::ZERO),
        hi: rule(1, 1.0 + rho) + underflow,
        saturated,
    }
}
