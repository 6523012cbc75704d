//! The `f64` reference: every formula of `phong`, written the plain way, in double precision.
//!
//! This is the ruler the `accuracy` tool and the accuracy tests measure the `f32` functions
//! against. It follows the crate's documented conventions (directions point away from the surface,
//! `0^0 = 0` for a lobe, the listed degenerate-case values) but not its implementation: vectors are
//! built explicitly (the reflection vector, the halfway vector) instead of the crate's dot-product
//! shortcuts, and nothing is rescaled or guarded beyond what the documented answer needs.
//!
//! Inputs are the `f32` values the crate sees, widened exactly to `f64`. It depends only on `glam`
//! and the public API of `phong`.

use core::f64::consts::PI;

use glam::{DMat3, DVec3, Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, Lambert, Light, LightSource, Material, Model, Normalization, Phong,
    PowStrategy, SpecularGate, Viewer,
};

// ---------------------------------------------------------------------------------------------
// Conversions

/// Widens exactly.
pub fn d3(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// Widens exactly.
pub fn dm3(m: Mat3) -> DMat3 {
    m.as_dmat3()
}

// ---------------------------------------------------------------------------------------------
// Geometry

/// ‖v‖. `f64` has room for the square of every finite `f32` component, so no rescaling is needed.
pub fn length(v: DVec3) -> f64 {
    v.dot(v).sqrt()
}

/// `v/‖v‖`, or zero for the zero vector or a non-finite one (the crate's documented answer).
pub fn normalize_or_zero(v: DVec3) -> DVec3 {
    let l = length(v);
    if l > 0.0 && l.is_finite() {
        v / l
    } else {
        DVec3::ZERO
    }
}

/// `a·b + c` with one rounding would be nicer; for the ruler we need exact products instead:
/// `a·b = p + e` exactly (`p` rounded, `e` the rounding error), valid while `a·b` does not underflow.
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `a + b = s + e` exactly.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a·b − c·d` to about 2⁻¹⁰⁰ relative to the larger product: double-double arithmetic.
fn diff_of_products_dd(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let (p, pe) = two_product(a, b);
    let (q, qe) = two_product(c, d);
    let (s, se) = two_sum(p, -q);
    s + (se + (pe - qe))
}

/// The area vector `(P1 − P0) × (P2 − P0)` of the given `f32` vertices, to within about 2⁻¹⁰⁰
/// relative to ‖P1 − P0‖·‖P2 − P0‖: the edges of `f32` points are exact in `f64` (their exponents
/// are close), and each component is a difference of two products done in double-double.
///
/// This is a stricter ruler than the plain `f64` cross product the crate itself uses, so the
/// sliver study does not measure the crate against its own arithmetic.
pub fn triangle_area_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> DVec3 {
    let e1 = d3(p1) - d3(p0);
    let e2 = d3(p2) - d3(p0);
    DVec3::new(
        diff_of_products_dd(e1.y, e2.z, e1.z, e2.y),
        diff_of_products_dd(e1.z, e2.x, e1.x, e2.z),
        diff_of_products_dd(e1.x, e2.y, e1.y, e2.x),
    )
}

/// The unit normal of the `f32` triangle, or zero when its exact area is zero.
pub fn triangle_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> DVec3 {
    normalize_or_zero(triangle_area_normal(p0, p1, p2))
}

/// `R = 2(N·L)N − L`.
pub fn reflect(n: DVec3, l: DVec3) -> DVec3 {
    2.0 * n.dot(l) * n - l
}

/// `H = (L + V)/‖L + V‖`, zero when `L = −V`.
pub fn halfway(l: DVec3, v: DVec3) -> DVec3 {
    normalize_or_zero(l + v)
}

/// `N` if `Nref·V > 0`, else `−N`.
pub fn face_forward(n: DVec3, v: DVec3, n_ref: DVec3) -> DVec3 {
    if n_ref.dot(v) > 0.0 { n } else { -n }
}

/// The inverse transpose `M⁻ᵀ` (undefined for singular `M`: glam returns non-finite entries).
pub fn inverse_transpose(m: DMat3) -> DMat3 {
    m.inverse().transpose()
}

/// `sign(det M) · cof(M)` with `sign(0) = +1`; `cof(M) = det(M)·M⁻ᵀ`, built from the columns.
pub fn normal_matrix(m: DMat3) -> DMat3 {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    let cof = DMat3::from_cols(b.cross(c), c.cross(a), a.cross(b));
    if m.determinant() < 0.0 { -cof } else { cof }
}

/// `normalize(NM · n)` with the reference normal matrix.
pub fn transform_normal(m: DMat3, n: DVec3) -> DVec3 {
    normalize_or_zero(normal_matrix(m) * n)
}

// ---------------------------------------------------------------------------------------------
// Attenuation and spot lights

/// `saturate(1 − (d/r)⁴)²`.
fn window(d: f64, r: f64) -> f64 {
    if d < r {
        let x = (d / r).powi(4);
        (1.0 - x) * (1.0 - x)
    } else {
        0.0
    }
}

/// The attenuation factor at distance `d ≥ 0`, from the table on [`Attenuation`].
pub fn attenuation(a: &Attenuation, d: f64) -> f64 {
    let d = if d.is_nan() || d < 0.0 { 0.0 } else { d };
    match *a {
        Attenuation::None => 1.0,
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => {
            let den = constant as f64 + linear as f64 * d + quadratic as f64 * d * d;
            1.0 / den.max(Attenuation::MIN_DENOMINATOR as f64)
        }
        Attenuation::InverseSquare {
            power,
            min_distance,
        } => power as f64 / d.max(min_distance as f64).powi(2),
        Attenuation::Unreal { radius } => window(d, radius as f64) / (d * d + 1.0),
        Attenuation::Frostbite {
            radius,
            min_distance,
        } => window(d, radius as f64) / d.max(min_distance as f64).powi(2),
    }
}

/// The cull radius: `inf{r : factor(d) < t for every d > r}`, solved in `f64`.
pub fn cull_radius(a: &Attenuation, t: f64) -> f64 {
    if t.is_nan() || t <= 0.0 {
        return f64::INFINITY;
    }
    if attenuation(a, 0.0) < t {
        return 0.0;
    }
    match *a {
        Attenuation::None => f64::INFINITY,
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => {
            let (c, l, q) = (constant as f64, linear as f64, quadratic as f64);
            let k = 1.0 / t - c;
            if l == 0.0 && q == 0.0 {
                f64::INFINITY
            } else if k <= 0.0 {
                0.0
            } else if q == 0.0 {
                k / l
            } else {
                // The textbook root of q·d² + l·d − k = 0.
                (-l + (l * l + 4.0 * q * k).sqrt()) / (2.0 * q)
            }
        }
        Attenuation::InverseSquare { power, .. } => (power as f64 / t).sqrt(),
        Attenuation::Unreal { radius } | Attenuation::Frostbite { radius, .. } => {
            // The factor decreases on [0, r]: bisect in f64 to full precision.
            let (mut lo, mut hi) = (0.0f64, radius as f64);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if attenuation(a, mid) >= t {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        }
    }
}

/// OpenGL's spot factor: `(−L·D)^e` inside the cone `−L·D ≥ cos cutoff`, else 0; 0 for zero `L`.
pub fn spot_factor(l: DVec3, axis: DVec3, cos_cutoff: f64, exponent: f64) -> f64 {
    let c = -l.dot(axis);
    if l == DVec3::ZERO || c < cos_cutoff {
        0.0
    } else {
        lobe_pow(c.min(1.0), exponent)
    }
}

// ---------------------------------------------------------------------------------------------
// Lobes

/// `x^s` for `x > 0` (clamped to 1 above), 0 for `x ≤ 0`: the crate's lobe power with `0^0 = 0`.
pub fn lobe_pow(x: f64, s: f64) -> f64 {
    if x > 0.0 {
        x.min(1.0).powf(s.max(0.0))
    } else {
        0.0
    }
}

/// The gate's weight for `N·L`.
pub fn gate(g: SpecularGate, n_dot_l: f64) -> f64 {
    match g {
        SpecularGate::Step => {
            if n_dot_l > 0.0 {
                1.0
            } else {
                0.0
            }
        }
        SpecularGate::Cosine => n_dot_l.max(0.0),
        SpecularGate::None => 1.0,
    }
}

/// The diffuse lobe `max(N·L, 0)`, over `π` when normalised.
pub fn diffuse(norm: Normalization, n_dot_l: f64) -> f64 {
    let c = n_dot_l.max(0.0);
    if norm == Normalization::None {
        c
    } else {
        c / PI
    }
}

/// Phong's normalisation: `(s + 2)/(2π)` (the same for `Energy` and `EnergyExact`).
pub fn phong_factor(norm: Normalization, s: f64) -> f64 {
    if norm == Normalization::None {
        1.0
    } else {
        (s.max(0.0) + 2.0) / (2.0 * PI)
    }
}

/// Blinn-Phong's normalisation: `(s + 8)/(8π)` or the exact `(s+2)(s+4)/(8π(2^(−s/2) + s))`.
pub fn blinn_factor(norm: Normalization, s: f64) -> f64 {
    let s = s.max(0.0);
    match norm {
        Normalization::None => 1.0,
        Normalization::Energy => (s + 8.0) / (8.0 * PI),
        Normalization::EnergyExact => {
            (s + 2.0) * (s + 4.0) / (8.0 * PI * (2f64.powf(-s / 2.0) + s))
        }
    }
}

/// Phong's specular lobe from the vectors: `R = reflect(N, L)`, `max(R·V, 0)^s`, gated or
/// normalised. `n`, `l`, `v` unit.
pub fn phong_specular(m: &Phong, n: DVec3, l: DVec3, v: DVec3, s: f64) -> f64 {
    let n_dot_l = n.dot(l);
    let lobe = lobe_pow(reflect(n, l).dot(v), s);
    if m.normalization == Normalization::None {
        lobe * gate(m.gate, n_dot_l)
    } else {
        phong_factor(m.normalization, s) * lobe * n_dot_l.max(0.0)
    }
}

/// Blinn-Phong's specular lobe from the vectors: `H = normalize(L + V)`, `max(N·H, 0)^s`, gated or
/// normalised; 0 when `L = −V` (no halfway vector).
pub fn blinn_specular(m: &BlinnPhong, n: DVec3, l: DVec3, v: DVec3, s: f64) -> f64 {
    let n_dot_l = n.dot(l);
    let lobe = lobe_pow(n.dot(halfway(l, v)), s);
    if m.normalization == Normalization::None {
        lobe * gate(m.gate, n_dot_l)
    } else {
        blinn_factor(m.normalization, s) * lobe * n_dot_l.max(0.0)
    }
}

/// The diffuse lobe of any model.
pub fn model_diffuse(m: &Model, n_dot_l: f64) -> f64 {
    let norm = match m {
        Model::Lambert(Lambert { normalization }) => *normalization,
        Model::Phong(p) => p.normalization,
        Model::BlinnPhong(b) => b.normalization,
    };
    diffuse(norm, n_dot_l)
}

/// The specular lobe of any model (0 for Lambert).
pub fn model_specular(m: &Model, n: DVec3, l: DVec3, v: DVec3, s: f64) -> f64 {
    match m {
        Model::Lambert(_) => 0.0,
        Model::Phong(p) => phong_specular(p, n, l, v, s),
        Model::BlinnPhong(b) => blinn_specular(b, n, l, v, s),
    }
}

/// `x^s` as each [`PowStrategy`] promises it: the same function, `lobe_pow`.
pub fn pow_strategy(_p: PowStrategy, x: f64, s: f64) -> f64 {
    lobe_pow(x, s)
}

// ---------------------------------------------------------------------------------------------
// Shading

/// The four terms of [`phong::shade`], in `f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Terms {
    /// The ambient term.
    pub ambient: DVec3,
    /// The diffuse term.
    pub diffuse: DVec3,
    /// The specular term.
    pub specular: DVec3,
    /// The material's emission.
    pub emission: DVec3,
}

impl Terms {
    /// The sum of the four terms.
    pub fn total(&self) -> DVec3 {
        self.ambient + self.diffuse + self.specular + self.emission
    }
}

/// What a light delivers at `p`: the direction to it and attenuation × spot factor.
pub fn light_sample(light: &Light, p: DVec3) -> (DVec3, f64) {
    match light {
        Light::Directional(l) => (d3(l.direction()), 1.0),
        Light::Point(l) => {
            let to = d3(l.position()) - p;
            (
                normalize_or_zero(to),
                attenuation(&l.attenuation(), length(to)),
            )
        }
        Light::Spot(l) => {
            let to = d3(l.position()) - p;
            let dir = normalize_or_zero(to);
            let spot = spot_factor(
                dir,
                d3(l.axis()),
                l.cos_cutoff() as f64,
                l.exponent() as f64,
            );
            let f = if spot > 0.0 {
                attenuation(&l.attenuation(), length(to)) * spot
            } else {
                0.0
            };
            (dir, f)
        }
    }
}

/// One point shaded under `lights`: the Phong-family equation with the crate's conventions (a zero
/// normal gets ambient and emission only; a viewer at the point gets no specular; a light at the
/// point adds only its ambient part).
pub fn shade(
    model: &Model,
    material: &Material,
    lights: &[Light],
    ambient: Vec3,
    viewer: Viewer,
    position: Vec3,
    normal: Vec3,
) -> Terms {
    let p = d3(position);
    let n = normalize_or_zero(d3(normal));
    let v = match viewer {
        Viewer::At(eye) => normalize_or_zero(d3(eye) - p),
        Viewer::Infinite(dir) => normalize_or_zero(d3(dir)),
    };
    let s = material.shininess() as f64;
    let (ka, kd, ks) = (
        d3(material.ambient()),
        d3(material.diffuse()),
        d3(material.specular()),
    );
    let mut ambient_light = d3(ambient).max(DVec3::ZERO);
    let mut diffuse = DVec3::ZERO;
    let mut specular = DVec3::ZERO;
    for light in lights {
        let (l, f) = light_sample(light, p);
        let c = light.colors();
        ambient_light += d3(c.ambient()) * f;
        if n == DVec3::ZERO || l == DVec3::ZERO {
            continue;
        }
        diffuse += d3(c.diffuse()) * kd * f * model_diffuse(model, n.dot(l));
        if v != DVec3::ZERO {
            specular += d3(c.specular()) * ks * f * model_specular(model, n, l, v, s);
        }
    }
    Terms {
        ambient: ambient_light * ka,
        diffuse,
        specular,
        emission: d3(material.emission()),
    }
}

// ---------------------------------------------------------------------------------------------
// Colour

/// Linear → sRGB (IEC 61966-2-1); NaN gives 0.
pub fn srgb_encode(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// sRGB → linear; NaN gives 0.
pub fn srgb_decode(y: f64) -> f64 {
    if y.is_nan() {
        0.0
    } else if y <= 0.040_45 {
        y / 12.92
    } else {
        ((y + 0.055) / 1.055).powf(2.4)
    }
}

/// `max(x, 0)^(1/γ)`; `γ ≤ 0` leaves `max(x, 0)` unchanged.
pub fn gamma_encode(x: f64, gamma: f64) -> f64 {
    let x = if x > 0.0 { x } else { 0.0 };
    if gamma > 0.0 { x.powf(1.0 / gamma) } else { x }
}

/// `max(y, 0)^γ`; `γ ≤ 0` leaves `max(y, 0)` unchanged.
pub fn gamma_decode(y: f64, gamma: f64) -> f64 {
    let y = if y > 0.0 { y } else { 0.0 };
    if gamma > 0.0 { y.powf(gamma) } else { y }
}

/// `⌊255·clamp(y, 0, 1) + 0.5⌋`; NaN gives 0.
pub fn quantize_u8(y: f64) -> u8 {
    let y = if y.is_nan() { 0.0 } else { y.clamp(0.0, 1.0) };
    (255.0 * y + 0.5).floor() as u8
}

/// Linear RGB → 8-bit sRGB, per channel.
pub fn linear_to_srgb8(c: DVec3) -> [u8; 3] {
    [
        quantize_u8(srgb_encode(c.x)),
        quantize_u8(srgb_encode(c.y)),
        quantize_u8(srgb_encode(c.z)),
    ]
}

// ---------------------------------------------------------------------------------------------
// Self-checks of the ruler, run wherever it is compiled into a test target.

#[cfg(test)]
mod ruler_checks {
    use super::*;

    #[test]
    fn reference_basics_hold() {
        let n = DVec3::Z;
        let l = DVec3::new(0.6, 0.0, 0.8);
        assert_eq!(reflect(n, l), DVec3::new(-0.6, 0.0, 0.8), "mirror about Z");
        assert_eq!(halfway(l, -l), DVec3::ZERO, "no halfway vector at L = -V");
        let a = triangle_area_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
        assert_eq!(a, DVec3::Z, "unit right triangle: doubled area 1 along +Z");
        assert!(
            (blinn_factor(Normalization::EnergyExact, 0.0) - 1.0 / PI).abs() < 1e-15,
            "exact Blinn factor is 1/pi at s = 0"
        );
        assert!(
            (srgb_decode(srgb_encode(0.3)) - 0.3).abs() < 1e-15,
            "sRGB round trip"
        );
        let m = DMat3::from_cols(
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(0.0, -2.0, 0.3),
            DVec3::new(0.2, 0.0, 3.0),
        );
        let cof = normal_matrix(m);
        let it = inverse_transpose(m) * m.determinant().abs();
        assert!(
            (cof - it).abs_diff_eq(DMat3::ZERO, 1e-12),
            "cofactor·sign(det) = |det|·M^-T"
        );
    }
}
