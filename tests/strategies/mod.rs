//! Named proptest strategies shared by the integration tests (`crate::strategies` in tests/suite.rs).
//!
//! Every strategy produces *finite* values in the documented domain of the function under test, so
//! a failing case is a property violation, not a domain violation. Directions are built in `f64`
//! and rounded once to `f32`, so a "unit" vector is unit to within about one ulp: `|‖v‖² − 1|` is
//! at most a few `f32::EPSILON`.

// Each test file uses a different subset of these strategies.
#![allow(dead_code, reason = "each test file uses a different subset")]

use core::f64::consts::PI;

use glam::{DVec3, Mat3, Vec3};
use phong::{Attenuation, Model, Normalization, PowStrategy, SpecularGate};
use proptest::prelude::*;

use phong_tools::models;

/// A unit vector, uniform on the sphere (Archimedes: uniform `z` and uniform azimuth).
pub(crate) fn unit_vec3() -> impl Strategy<Value = Vec3> {
    (-1.0f64..=1.0, 0.0f64..(2.0 * PI)).prop_map(|(z, phi)| unit_from(z, phi))
}

fn unit_from(z: f64, phi: f64) -> Vec3 {
    let r = (1.0 - z * z).max(0.0).sqrt();
    let v = DVec3::new(r * phi.cos(), r * phi.sin(), z).normalize();
    v.as_vec3()
}

/// A unit vector in the open hemisphere around unit `n`, at least `min_cos` above the horizon
/// (`v·n ≥ min_cos`, with `min_cos ∈ [0, 1)`), uniform in solid angle over that cap.
pub(crate) fn hemisphere_min(n: Vec3, min_cos: f64) -> impl Strategy<Value = Vec3> {
    (min_cos..=1.0f64, 0.0f64..(2.0 * PI)).prop_map(move |(c, phi)| {
        let (t, b) = basis(n.as_dvec3());
        let s = (1.0 - c * c).max(0.0).sqrt();
        (n.as_dvec3() * c + t * (s * phi.cos()) + b * (s * phi.sin()))
            .normalize()
            .as_vec3()
    })
}

/// A unit vector in the hemisphere around unit `n`, at least 1e-3 above the horizon.
pub(crate) fn hemisphere(n: Vec3) -> impl Strategy<Value = Vec3> {
    hemisphere_min(n, 1e-3)
}

/// Two unit vectors spanning the plane perpendicular to unit `n` (Duff et al. 2017, "Building an
/// orthonormal basis, revisited").
pub(crate) fn basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// A unit normal and a unit light direction above its horizon (`N·L ≥ 1e-3`).
pub(crate) fn normal_and_light() -> impl Strategy<Value = (Vec3, Vec3)> {
    unit_vec3().prop_flat_map(|n| (Just(n), hemisphere(n)))
}

/// `N`, `L`, `V` in one plane, as the angles of `L` and `V` from `N` within that plane (radians,
/// each in `(−π/2 + 0.01, π/2 − 0.01)`, so both are above the horizon and `‖L + V‖ ≥ 2 sin 0.01`).
/// Returns `(n, l, v, theta_l, theta_v)`; the plane and `N` are random.
pub(crate) fn coplanar_nlv() -> impl Strategy<Value = (Vec3, Vec3, Vec3, f64, f64)> {
    let lim = PI / 2.0 - 0.01;
    (unit_vec3(), 0.0f64..(2.0 * PI), -lim..lim, -lim..lim).prop_map(|(n, phi, tl, tv)| {
        let nd = n.as_dvec3();
        let (t, b) = basis(nd);
        let u = t * phi.cos() + b * phi.sin(); // a unit direction in the plane, ⟂ N
        let at = |theta: f64| (nd * theta.cos() + u * theta.sin()).normalize().as_vec3();
        (n, at(tl), at(tv), tl, tv)
    })
}

/// A point with coordinates in `[-100, 100]`.
pub(crate) fn point() -> impl Strategy<Value = Vec3> {
    (-100.0f32..100.0, -100.0f32..100.0, -100.0f32..100.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A triangle with vertices in `[-100, 100]³` (possibly thin, never non-finite).
pub(crate) fn triangle() -> impl Strategy<Value = (Vec3, Vec3, Vec3)> {
    (point(), point(), point())
}

/// A non-zero translation of up to 1e3 per coordinate.
pub(crate) fn translation() -> impl Strategy<Value = Vec3> {
    (-1e3f32..1e3, -1e3f32..1e3, -1e3f32..1e3).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A shininess: the special values 0, 0.5 and 1, small integers, tutorial powers of two, and any
/// value in `[0, 512]`.
pub(crate) fn shininess() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(0.5f32),
        Just(1.0f32),
        (1u32..=16).prop_map(|s| s as f32),
        (0u32..=9).prop_map(|k| (1u32 << k) as f32),
        0.0f32..=512.0,
    ]
}

/// A linear RGB colour with channels in `[0, 2]` (HDR allowed).
pub(crate) fn color() -> impl Strategy<Value = Vec3> {
    (0.0f32..=2.0, 0.0f32..=2.0, 0.0f32..=2.0).prop_map(|(r, g, b)| Vec3::new(r, g, b))
}

/// A non-negative coefficient in `[0, 10]`, sometimes exactly 0.
fn coefficient() -> impl Strategy<Value = f32> {
    prop_oneof![1 => Just(0.0f32), 4 => 0.0f32..=10.0]
}

/// Any attenuation form with parameters in its documented domain.
pub(crate) fn attenuation() -> impl Strategy<Value = Attenuation> {
    prop_oneof![
        Just(Attenuation::None),
        (coefficient(), coefficient(), coefficient())
            .prop_map(|(c, l, q)| Attenuation::try_polynomial(c, l, q).unwrap()),
        (0.0f32..=100.0).prop_map(|p| Attenuation::try_inverse_square(p).unwrap()),
        (0.01f32..=100.0).prop_map(|r| Attenuation::try_unreal(r).unwrap()),
        (0.01f32..=100.0).prop_map(|r| Attenuation::try_frostbite(r).unwrap()),
    ]
}

/// A specular gate.
pub(crate) fn gate() -> impl Strategy<Value = SpecularGate> {
    prop_oneof![
        Just(SpecularGate::Step),
        Just(SpecularGate::Cosine),
        Just(SpecularGate::None),
    ]
}

/// An energy normalisation.
pub(crate) fn normalization() -> impl Strategy<Value = Normalization> {
    prop_oneof![
        Just(Normalization::None),
        Just(Normalization::Energy),
        Just(Normalization::EnergyExact),
    ]
}

/// A `pow` strategy whose error is `powf`'s or repeated squaring's: `Exact` or `Squaring`.
pub(crate) fn pow_strategy() -> impl Strategy<Value = PowStrategy> {
    prop_oneof![Just(PowStrategy::Exact), Just(PowStrategy::Squaring)]
}

/// Every `pow` strategy, `Auto` included.
pub(crate) fn any_pow() -> impl Strategy<Value = PowStrategy> {
    prop::sample::select(
        PowStrategy::ALL
            .iter()
            .copied()
            .chain([PowStrategy::Auto])
            .collect::<Vec<_>>(),
    )
}

/// One of the three models (uniformly) with its gate, normalisation and `pow` strategy drawn from
/// the given strategies: each test file picks the parts its property covers.
pub(crate) fn model_of(
    gate: impl Strategy<Value = SpecularGate>,
    normalization: impl Strategy<Value = Normalization>,
    pow: impl Strategy<Value = PowStrategy>,
) -> impl Strategy<Value = Model> {
    (0usize..3, gate, normalization, pow)
        .prop_map(|(k, gate, normalization, pow)| models::assemble(k, gate, normalization, pow))
}

/// Any of the three models, with any gate and normalisation, and `Exact` or `Squaring`.
pub(crate) fn model() -> impl Strategy<Value = Model> {
    model_of(gate(), normalization(), pow_strategy())
}

/// Any of the three models, with any gate, normalisation and `pow` strategy (`Auto` included).
pub(crate) fn any_model() -> impl Strategy<Value = Model> {
    model_of(gate(), normalization(), any_pow())
}

/// A unit quaternion's rotation matrix, from a random axis and angle.
pub(crate) fn rotation() -> impl Strategy<Value = Mat3> {
    (unit_vec3(), -PI..PI).prop_map(|(axis, angle)| Mat3::from_axis_angle(axis, angle as f32))
}

/// An invertible linear map `R₁ · diag(s) · R₂`: rotations around a non-uniform scale whose factors
/// have magnitudes in `[0.1, 10]` and random signs (so about half have a negative determinant).
pub(crate) fn invertible_mat3() -> impl Strategy<Value = Mat3> {
    let scale = (0.1f32..=10.0, any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m });
    (rotation(), rotation(), scale.clone(), scale.clone(), scale)
        .prop_map(|(r1, r2, a, b, c)| r1 * Mat3::from_diagonal(Vec3::new(a, b, c)) * r2)
}
