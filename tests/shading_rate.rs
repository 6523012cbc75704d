//! The shading-rate advisor's bound is a bound: on random triangles, the worst measured difference
//! between Gouraud and per-pixel shading over many interior points never exceeds it.

use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Lambert, Light, LightColors, Material, Model,
    Normalization, Phong, PointLight, Scene, SpecularGate, SpotLight, Viewer,
};
use proptest::prelude::*;

/// A point in the cube `[-r, r]³`.
fn point(r: f32) -> impl Strategy<Value = Vec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A unit vector (rejecting the near-zero draws).
fn unit_vec3() -> impl Strategy<Value = Vec3> {
    point(1.0).prop_filter_map("near zero", |v| v.try_normalize())
}

/// A small triangle near the origin with vertex normals spread around its face normal, as on a
/// coarse mesh of a curved surface.
fn triangle() -> impl Strategy<Value = ([Vec3; 3], [Vec3; 3])> {
    (
        point(1.0),
        point(0.4),
        point(0.4),
        point(0.6),
        point(0.6),
        point(0.6),
        any::<bool>(),
    )
        .prop_map(|(c, a, b, t0, t1, t2, flip)| {
            let p = [c, c + a, c + b];
            let face = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or(Vec3::Z);
            let face = if flip { -face } else { face };
            let n = [t0, t1, t2].map(|t| (face + t).normalize_or(face));
            (p, n)
        })
}

fn model() -> impl Strategy<Value = Model> {
    let gate = prop_oneof![
        Just(SpecularGate::Step),
        Just(SpecularGate::Cosine),
        Just(SpecularGate::None)
    ];
    let norm = prop_oneof![
        3 => Just(Normalization::None),
        1 => Just(Normalization::Energy),
        1 => Just(Normalization::EnergyExact)
    ];
    (0..3u8, gate, norm).prop_map(|(k, gate, normalization)| match k {
        0 => Lambert { normalization }.into(),
        1 => Phong {
            gate,
            normalization,
            ..Phong::default()
        }
        .into(),
        _ => BlinnPhong {
            gate,
            normalization,
            ..BlinnPhong::default()
        }
        .into(),
    })
}

fn attenuation() -> impl Strategy<Value = Attenuation> {
    prop_oneof![
        Just(Attenuation::None),
        Just(Attenuation::polynomial(1.0, 0.09, 0.032)),
        Just(Attenuation::try_inverse_square(4.0).unwrap()),
        Just(Attenuation::try_unreal(4.0).unwrap()),
        Just(Attenuation::try_frostbite(4.0).unwrap()),
    ]
}

fn light() -> impl Strategy<Value = Light> {
    let colors = (0.0f32..0.3, 0.0f32..1.0, 0.0f32..1.0)
        .prop_map(|(a, d, s)| LightColors::try_from_strengths(Vec3::ONE, a, d, s).unwrap());
    prop_oneof![
        (unit_vec3(), colors.clone())
            .prop_map(|(d, c)| DirectionalLight::try_new(d, c).unwrap().into()),
        (point(4.0), attenuation(), colors.clone()).prop_map(|(p, a, c)| PointLight::try_new(
            p, a, c
        )
        .unwrap()
        .into()),
        (
            point(4.0),
            unit_vec3(),
            0.2f32..1.5,
            0.0f32..8.0,
            attenuation(),
            colors
        )
            .prop_map(
                |(p, axis, cut, e, a, c)| SpotLight::try_new(p, axis, cut, e, a, c).unwrap().into()
            ),
    ]
}

fn viewer() -> impl Strategy<Value = Viewer> {
    prop_oneof![
        point(6.0).prop_map(Viewer::At),
        unit_vec3().prop_map(Viewer::Infinite),
    ]
}

fn shininess() -> impl Strategy<Value = f32> {
    prop_oneof![
        0.0f32..3.0,
        prop::sample::select(vec![1.0f32, 2.0, 8.0, 32.0, 128.0, 256.0])
    ]
}

fn colour() -> impl Strategy<Value = Vec3> {
    (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b))
}

/// The largest channel difference between Gouraud and per-pixel shading over a grid of
/// barycentric points (vertices, edges and interior).
fn measured_worst(
    model: &Model,
    material: &Material,
    scene: &Scene<'_, Light>,
    p: [Vec3; 3],
    n: [Vec3; 3],
) -> f32 {
    let at = |q: Vec3, m: Vec3| phong::shade(model, material, scene, q, m).total();
    let vertex = [at(p[0], n[0]), at(p[1], n[1]), at(p[2], n[2])];
    let k = 24;
    let mut worst = 0.0f32;
    for i in 0..=k {
        for j in 0..=(k - i) {
            let (b1, b2) = (i as f32 / k as f32, j as f32 / k as f32);
            let b0 = 1.0 - b1 - b2;
            let q = p[0] * b0 + p[1] * b1 + p[2] * b2;
            let m = n[0] * b0 + n[1] * b1 + n[2] * b2;
            let gouraud = vertex[0] * b0 + vertex[1] * b1 + vertex[2] * b2;
            worst = worst.max((gouraud - at(q, m)).abs().max_element());
        }
    }
    worst
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn the_bound_is_never_exceeded(
        (p, n) in triangle(),
        model in model(),
        light in light(),
        viewer in viewer(),
        s in shininess(),
        (ka, kd, ks) in (colour(), colour(), colour()),
    ) {
        let material = Material::try_new(ka, kd, ks, s).unwrap();
        let lights = [light];
        let scene = Scene { lights: &lights, ambient: Vec3::splat(0.05), viewer };
        let bound = phong::gouraud_error_bound(model, &material, &scene, p, n);
        let worst = measured_worst(&model, &material, &scene, p, n);
        prop_assert!(bound.is_finite() && bound >= 0.0, "bound {bound}");
        prop_assert!(
            worst <= bound,
            "measured {worst} > bound {bound} for {model:?} {light:?} {viewer:?} s={s} p={p:?} n={n:?}"
        );
    }
}

#[test]
fn a_flat_triangle_under_a_distant_light_is_nearly_exact() {
    let sun = DirectionalLight::try_new(
        Vec3::new(0.3, 0.2, 1.0),
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[sun],
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let m = Material::try_from_color(Vec3::ONE, 64.0).unwrap();
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let b = phong::gouraud_error_bound(Phong::default(), &m, &scene, p, [Vec3::Z; 3]);
    assert!(b < 1e-4, "flat triangle, constant L and V: bound {b}");
}

#[test]
fn the_bound_is_small_on_a_fine_sphere_away_from_the_highlight() {
    // A 5°-wide triangle of a unit sphere, lit at a grazing 80° from its normal.
    let sun = DirectionalLight::try_new(
        Vec3::X,
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[sun],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    let m = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let d = 5f32.to_radians();
    let dir = |a: f32, b: f32| Vec3::new(a.sin() * b.cos(), b.sin(), a.cos() * b.cos());
    let a0 = 10f32.to_radians();
    let n = [dir(a0, 0.0), dir(a0 + d, 0.0), dir(a0, d)];
    let bound = phong::gouraud_error_bound(Phong::default(), &m, &scene, n, n);
    assert!(bound < 1.0 / 255.0, "fine triangle: bound {bound}");
}

#[test]
fn a_tolerance_that_is_nan_or_negative_is_never_met() {
    let scene = Scene::<Light> {
        lights: &[],
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let m = Material::try_from_color(Vec3::ONE, 8.0).unwrap();
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
    for t in [f32::NAN, -1.0] {
        assert!(
            !phong::gouraud_within_tolerance(Lambert::default(), &m, &scene, p, [Vec3::Z; 3], t),
            "tolerance {t}"
        );
    }
    assert!(
        phong::gouraud_within_tolerance(Lambert::default(), &m, &scene, p, [Vec3::Z; 3], 0.0),
        "no lights: exact"
    );
}

/// A named triangle, its normals, a light and a viewer.
type Case = (&'static str, [Vec3; 3], [Vec3; 3], Light, Viewer);

#[test]
fn degenerate_triangles_still_get_a_finite_bound_that_holds() {
    let point = |p: Vec3| -> Light {
        PointLight::try_new(
            p,
            Attenuation::polynomial(1.0, 0.09, 0.032),
            LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5).unwrap(),
        )
        .unwrap()
        .into()
    };
    let m = Material::try_from_color(Vec3::ONE, 16.0).unwrap();
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let flat = [Vec3::Z; 3];
    let cases: [Case; 5] = [
        (
            "collinear vertices",
            [Vec3::ZERO, Vec3::X, 2.0 * Vec3::X],
            [Vec3::Z, Vec3::Y, Vec3::Z],
            point(Vec3::new(0.0, 1.0, 1.0)),
            Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
        ),
        (
            "normals that cancel",
            p,
            [Vec3::Z, -Vec3::Z, Vec3::X],
            point(Vec3::new(0.3, 0.3, 1.0)),
            Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
        ),
        (
            "light on the triangle",
            p,
            flat,
            point(Vec3::new(0.25, 0.25, 0.0)),
            Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
        ),
        (
            "eye on the triangle",
            p,
            flat,
            point(Vec3::new(0.0, 0.0, 2.0)),
            Viewer::At(Vec3::new(0.25, 0.25, 0.0)),
        ),
        (
            "zero infinite viewer",
            p,
            flat,
            point(Vec3::new(0.0, 0.0, 2.0)),
            Viewer::Infinite(Vec3::ZERO),
        ),
    ];
    for (name, p, n, light, viewer) in cases {
        let lights = [light];
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer,
        };
        for model in [Model::from(Phong::default()), BlinnPhong::default().into()] {
            let bound = phong::gouraud_error_bound(model, &m, &scene, p, n);
            let worst = measured_worst(&model, &m, &scene, p, n);
            assert!(bound.is_finite() && bound >= 0.0, "{name}: bound {bound}");
            assert!(worst <= bound, "{name}: measured {worst} > bound {bound}");
        }
    }
}

#[test]
fn a_directional_lights_diffuse_bound_is_sharp() {
    // A triangle of a unit sphere about 18° across (as on a 320-face icosphere), lit at 30°.
    let dir = |a: f32, b: f32| {
        let (a, b) = (a.to_radians(), b.to_radians());
        Vec3::new(a.sin() * b.cos(), b.sin(), a.cos() * b.cos())
    };
    let p = [dir(0.0, 0.0), dir(18.0, 0.0), dir(9.0, 15.6)];
    let sun = DirectionalLight::try_new(
        dir(30.0, 10.0),
        LightColors::try_from_strengths(Vec3::ONE, 0.0, 0.8, 0.0).unwrap(),
    )
    .unwrap();
    let lights = [Light::from(sun)];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 4.0)),
    };
    let m = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let model = Model::from(Lambert::default());
    let bound = phong::gouraud_error_bound(model, &m, &scene, p, p);
    let worst = measured_worst(&model, &m, &scene, p, p);
    assert!(
        worst <= bound && bound <= 1.2 * worst,
        "bound {bound} vs measured {worst}: should be within 20%"
    );
}
