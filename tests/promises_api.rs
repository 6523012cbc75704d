//! The API points an outside porting exercise found awkward, each pinned by a test: OpenGL's 180°
//! spot cutoff, the named spot cone, the unchecked spot constructor, where the Wikipedia shader's
//! light power goes, the LearnOpenGL presets, the inverse-square `ε`, and the incidence `shade`
//! uses for a light.

use glam::Vec3;
use phong::gpu::GpuLight;
use phong::{
    Attenuation, BlinnPhong, Incidence, Light, LightColors, LightSource, Material, Phong,
    PhongError, PointLight, ReflectionModel, Scene, Shader, SpecularGate, SpotCone, SpotLight,
    Viewer,
};
use proptest::prelude::*;

fn white() -> LightColors {
    LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE).unwrap()
}

#[test]
fn a_180_degree_cutoff_is_not_a_spot() {
    let att = Attenuation::polynomial(1.0, 0.09, 0.032);
    let pos = Vec3::new(0.0, 3.0, 0.0);
    // OpenGL: GL_SPOT_CUTOFF = 180 turns the cone off; the light is a point light.
    let spot =
        SpotLight::try_with_cone(pos, -Vec3::Y, SpotCone::degrees(180.0), att, white()).unwrap();
    let point = PointLight::try_new(pos, att, white()).unwrap();
    for p in [
        Vec3::ZERO,
        Vec3::new(0.0, 9.0, 0.0), // behind the light, along the reversed axis
        Vec3::new(5.0, 3.0, -1.0),
    ] {
        assert_eq!(spot.sample(p), point.sample(p), "at {p}");
    }
    // The positional constructor accepts exactly π as well, with any exponent (ignored, as in GL).
    let positional = SpotLight::try_new(
        pos,
        -Vec3::Y,
        core::f32::consts::PI,
        7.0,
        att,
        LightColors::BLACK,
    )
    .unwrap();
    assert_eq!(
        positional.sample(Vec3::new(0.0, 9.0, 0.0)).factor,
        att.factor(6.0)
    );
    // Anything else beyond π/2 is still rejected, naming the field.
    assert!(matches!(
        SpotLight::try_with_cone(pos, Vec3::X, SpotCone::degrees(120.0), att, white()),
        Err(PhongError::OutOfRange {
            field: "light.cutoff",
            ..
        })
    ));
    // The GPU mirror encodes it as the shaders' point light (kind 1), not a cone with cos = −1.
    let g = GpuLight::from(&Light::from(spot));
    assert_eq!(g.kind, GpuLight::from(&Light::from(point)).kind);
}

#[test]
fn the_named_cone_is_the_positional_one() {
    let a = SpotLight::try_new(
        Vec3::Y,
        -Vec3::Y,
        0.4,
        8.0,
        Attenuation::None,
        LightColors::BLACK,
    )
    .unwrap();
    let b = SpotLight::try_with_cone(
        Vec3::Y,
        -Vec3::Y,
        SpotCone {
            cutoff: 0.4,
            exponent: 8.0,
        },
        Attenuation::None,
        LightColors::BLACK,
    )
    .unwrap();
    assert_eq!(a, b);
    assert_eq!(
        a.cone(),
        SpotCone {
            cutoff: 0.4,
            exponent: 8.0
        }
    );
    // A swapped exponent as cutoff is caught by the positional form's range check...
    assert!(
        SpotLight::try_new(
            Vec3::Y,
            -Vec3::Y,
            8.0,
            0.4,
            Attenuation::None,
            LightColors::BLACK
        )
        .is_err()
    );
    // ...and the degree helper lands on the exact radian constants OpenGL's table uses.
    assert_eq!(SpotCone::degrees(90.0).cutoff, core::f32::consts::FRAC_PI_2);
    assert_eq!(SpotCone::degrees(180.0), SpotCone::NONE);
    assert!((SpotCone::degrees(30.0).cutoff - core::f32::consts::FRAC_PI_6).abs() <= 1e-7);
}

/// Any `f32`, biased toward the values that break unchecked constructors.
fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(0.0f32),
        Just(-0.0f32),
        Just(core::f32::consts::PI),
        -10.0f32..10.0,
        any::<f32>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// `SpotLight::new` sanitises like the other unchecked constructors: whatever it is given, its
    /// cone is inside the domain and its factor is finite and in `[0, attenuation max]`.
    #[test]
    fn the_unchecked_spot_is_always_in_its_domain(
        cutoff in wild(), exponent in wild(),
        ax in wild(), ay in wild(), az in wild(),
        px in -10.0f32..10.0, py in -10.0f32..10.0, pz in -10.0f32..10.0,
    ) {
        // Debug builds assert the domain (the documented contract): only release sanitises.
        let checked = SpotLight::try_with_cone(
            Vec3::ZERO, Vec3::new(ax, ay, az), SpotCone { cutoff, exponent },
            Attenuation::None, white());
        if cfg!(debug_assertions) && checked.is_err() {
            return Ok(());
        }
        let spot = SpotLight::new(
            Vec3::ZERO, Vec3::new(ax, ay, az), SpotCone { cutoff, exponent }, Attenuation::None,
            white());
        let c = spot.cone();
        prop_assert!(c.cutoff.is_finite() && c.exponent.is_finite() && c.exponent >= 0.0);
        prop_assert!((0.0..=core::f32::consts::FRAC_PI_2).contains(&c.cutoff) || c.is_none());
        let f = spot.sample(Vec3::new(px, py, pz)).factor;
        prop_assert!((0.0..=1.0).contains(&f), "factor {f}");
        if let Ok(ok) = checked {
            prop_assert_eq!(ok, spot);
        }
    }
}

#[test]
fn the_wikipedia_power_is_applied_once() {
    // Wikipedia's Blinn-Phong shader: diffuse = λ · diffuseColor · lightColor · lightPower / d².
    let (power, color) = (40.0f32, Vec3::new(1.0, 0.9, 0.8));
    let light_pos = Vec3::new(1.0, 2.0, 2.0);
    let lamp = PointLight::try_new(
        light_pos,
        Attenuation::try_inverse_square(1.0).unwrap(),
        LightColors::try_from_power(color, power).unwrap(),
    )
    .unwrap();
    let kd = Vec3::new(0.5, 0.25, 0.125);
    let m = Material::try_new(Vec3::ZERO, kd, Vec3::ZERO, 16.0).unwrap();
    let lights = [lamp];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    let t = Shader::new(BlinnPhong::learnopengl(), &m, &scene).shade(Vec3::ZERO, Vec3::Z);
    let d2 = light_pos.length_squared(); // 9
    let lambert = light_pos.normalize().z; // 2/3
    let wikipedia = kd * color * power * lambert / d2;
    // A handful of roundings in each evaluation of a product of order 1: 1e-6 relative.
    assert!(
        (t.diffuse - wikipedia).abs().max_element() <= 1e-6 * wikipedia.max_element(),
        "{} vs {wikipedia}",
        t.diffuse
    );
}

#[test]
fn both_models_have_the_learnopengl_preset() {
    for (gate, norm) in [
        (
            Phong::learnopengl().gate,
            Phong::learnopengl().normalization,
        ),
        (
            BlinnPhong::learnopengl().gate,
            BlinnPhong::learnopengl().normalization,
        ),
    ] {
        assert_eq!(gate, SpecularGate::None);
        assert_eq!(norm, phong::Normalization::None);
    }
    // No gate: a light below the surface still gives Blinn-Phong a highlight, as in the tutorial.
    let g = Incidence::new(Vec3::Z, Vec3::new(0.8, 0.0, -0.6), Vec3::Z); // N·L < 0 < N·H
    assert!(BlinnPhong::learnopengl().specular(&g, 2.0) > 0.0);
    assert_eq!(BlinnPhong::default().specular(&g, 2.0), 0.0);
}

#[test]
fn the_inverse_square_epsilon_has_a_constructor() {
    let a = Attenuation::try_inverse_square_with_min_distance(2.0, 0.25).unwrap();
    assert_eq!(
        a,
        Attenuation::InverseSquare {
            power: 2.0,
            min_distance: 0.25
        }
    );
    assert_eq!(a.factor(0.0), 32.0); // 2 / 0.25²
    assert_eq!(a.factor(2.0), 0.5);
    assert!(matches!(
        Attenuation::try_inverse_square_with_min_distance(1.0, 0.0),
        Err(PhongError::OutOfRange {
            field: "attenuation.min_distance",
            ..
        })
    ));
    let f = Attenuation::try_frostbite_with_min_distance(10.0, 0.5).unwrap();
    assert_eq!(
        f,
        Attenuation::Frostbite {
            radius: 10.0,
            min_distance: 0.5
        }
    );
    assert!(Attenuation::try_frostbite_with_min_distance(10.0, -1.0).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// `Shader::incidence` returns the cosines `shade` uses: a model's own lobes evaluated on it,
    /// weighted by the returned factor, give `shade`'s diffuse and specular for a one-light scene.
    #[test]
    fn the_public_incidence_is_the_one_shade_uses(
        lx in -3.0f32..3.0, ly in -3.0f32..3.0, lz in 0.1f32..3.0,
        nx in -1.0f32..1.0, ny in -1.0f32..1.0, nz in -1.0f32..1.0,
        zero_normal in any::<bool>(), light_at_point in any::<bool>(),
        s in 0.0f32..64.0, blinn in any::<bool>(),
    ) {
        let light_pos = if light_at_point { Vec3::ZERO } else { Vec3::new(lx, ly, lz) };
        let normal = if zero_normal { Vec3::ZERO } else { Vec3::new(nx, ny, nz) };
        let lamp = PointLight::try_new(light_pos, Attenuation::None,
            LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ONE).unwrap()).unwrap();
        let m = Material::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ONE, s).unwrap();
        let lights = [lamp];
        let scene = Scene { lights: &lights, ambient: Vec3::ZERO,
            viewer: Viewer::At(Vec3::new(0.3, -0.2, 2.0)) };
        let model: phong::Model = if blinn { BlinnPhong::default().into() } else { Phong::default().into() };
        let shader = Shader::new(model, &m, &scene);
        let t = shader.shade(Vec3::ZERO, normal);
        let (g, f) = shader.incidence(Vec3::ZERO, normal, 0).unwrap();
        prop_assert!(shader.incidence(Vec3::ZERO, normal, 1).is_none());
        let (wd, ws) = (model.diffuse(&g) * f, model.specular(&g, s) * f);
        // The shader's loop and the trait methods round the same cosines in different orders:
        // a few ulps of lobes ≤ 1.
        prop_assert!((t.diffuse.x - wd).abs() <= 4e-6, "diffuse {} vs {wd}", t.diffuse.x);
        prop_assert!((t.specular.x - ws).abs() <= 4e-6 * ws.max(1.0), "specular {} vs {ws}", t.specular.x);
    }
}

/// A signalling NaN is still NaN to the sanitising rule (NaN reads as 0). On AArch64 the
/// compiler's max/min instructions turn a signalling NaN into a quiet one instead of returning
/// the bound, which made `Attenuation::polynomial` keep `f32::MAX` there (found by the aarch64
/// run of tests/promises_attenuation.rs). Release builds only: debug builds assert the domain.
#[test]
fn a_signalling_nan_sanitises_to_zero() {
    if cfg!(debug_assertions) {
        return;
    }
    let snan = f32::from_bits(0x7fa0_0000);
    assert!(snan.is_nan());
    for x in [snan, -snan, f32::NAN] {
        let x = std::hint::black_box(x);
        assert_eq!(
            Attenuation::polynomial(0.0, x, 0.0),
            Attenuation::Polynomial {
                constant: 0.0,
                linear: 0.0,
                quadratic: 0.0
            },
            "{:#x}",
            x.to_bits()
        );
        let c = LightColors::new(Vec3::splat(x), Vec3::ONE, Vec3::new(x, 1.0, x));
        assert_eq!((c.ambient(), c.specular()), (Vec3::ZERO, Vec3::Y));
    }
}
