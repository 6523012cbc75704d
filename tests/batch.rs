//! The batch path against its documented accuracy (module docs of `phong::batch`), at every
//! dispatch level this machine runs, for every model, gate, normalisation and pow strategy, on
//! random and adversarial input; and the automatic pow choice against the 8-bit criterion.
//!
//! **What is checked.** Each channel of the batch lies in the range the equation takes, in `f64`,
//! over the perturbations the docs allow (each cosine within `η = 2e-6`, attenuation within 2e-6
//! relative, Blinn's base within 3 ulps, the lobe power within the strategy's
//! `max_relative_error`, `(8 + 2·lights)` ulps of rounding in each sum), with the saturation rule
//! applied (tools/src/batch_range.rs). `shade` is checked against the same range outside the
//! overflow regime, so the two agree to its width. The range needs no exceptions: near a
//! discontinuity (the step gate at `N·L = 0`, a lobe base at 0 for `s < 1`, Blinn's `L = −V`) it
//! simply contains both sides.

use phong_tools::batch_range;

use glam::{DVec3, Vec3};
use phong::{
    Attenuation, BatchLight, BatchModel, BlinnPhong, DirectionalLight, Lambert, Level, Light,
    LightColors, Material, Model, Normalization, Phong, PointLight, PowStrategy, Scene, SoaRgb,
    SoaVec3, SpecularGate, SpotCone, SpotLight, Viewer,
};

use phong_tools::rng::Rng;

/// Positions and normals in array-of-structs form, converted to SoA for each call.
struct Batch {
    p: Vec<Vec3>,
    n: Vec<Vec3>,
}

impl Batch {
    fn soa(&self) -> [Vec<f32>; 6] {
        [
            self.p.iter().map(|v| v.x).collect(),
            self.p.iter().map(|v| v.y).collect(),
            self.p.iter().map(|v| v.z).collect(),
            self.n.iter().map(|v| v.x).collect(),
            self.n.iter().map(|v| v.y).collect(),
            self.n.iter().map(|v| v.z).collect(),
        ]
    }
}

fn run<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    m: &Material,
    scene: &Scene<'_, L>,
    b: &Batch,
) -> Vec<Vec3> {
    let s = b.soa();
    let len = b.p.len();
    let (mut r, mut g, mut bl) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
    let n = phong::shade_batch_with_level(
        level,
        model,
        m,
        scene,
        SoaVec3::new(&s[0], &s[1], &s[2]),
        SoaVec3::new(&s[3], &s[4], &s[5]),
        SoaRgb::new(&mut r, &mut g, &mut bl),
    )
    .expect("level reported as supported");
    assert_eq!(n, len, "every point shaded");
    (0..len).map(|i| Vec3::new(r[i], g[i], bl[i])).collect()
}

/// Batch (forced to each supported level) and `shade` against the documented range, point by
/// point: both follow the same saturation rule.
fn check<M, L>(what: &str, model: &M, m: &Material, scene: &Scene<'_, L>, b: &Batch)
where
    M: BatchModel + Copy + Into<Model>,
    L: BatchLight + 'static,
{
    let me: Model = (*model).into();
    let ranges: Vec<batch_range::Range> =
        b.p.iter()
            .zip(&b.n)
            .map(|(&p, &n)| batch_range::range(&me, m, scene, p, n))
            .collect();
    for (i, (&p, &n)) in b.p.iter().zip(&b.n).enumerate() {
        let r = ranges[i];
        let want = phong::shade(model, m, scene, p, n).total();
        assert!(
            r.holds(want),
            "{what}: shade at point {i} (p = {p}, n = {n}) gave {want}, outside [{}, {}]",
            r.lo,
            r.hi
        );
    }
    for level in Level::supported() {
        let out = run(level, model, m, scene, b);
        for (i, (&p, &n)) in b.p.iter().zip(&b.n).enumerate() {
            let got = out[i];
            let r = ranges[i];
            assert!(
                r.holds(got),
                "{what} at {level}: point {i} (p = {p}, n = {n}) gave {got}, outside [{}, {}] \
                 (shade: {})",
                r.lo,
                r.hi,
                phong::shade(model, m, scene, p, n).total()
            );
        }
    }
}

fn colors(rng: &mut Rng) -> LightColors {
    LightColors::try_new(
        rng.vec3_in(0.0, 0.3),
        rng.vec3_in(0.0, 1.0),
        rng.vec3_in(0.0, 1.0),
    )
    .unwrap()
}

fn point_light(rng: &mut Rng, at: Vec3) -> PointLight {
    PointLight::try_new(
        at,
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        colors(rng),
    )
    .unwrap()
}

/// Random points, with sizes that are not multiples of 16 so the tail is covered.
fn random_batch(rng: &mut Rng, len: usize) -> Batch {
    let p = (0..len).map(|_| rng.vec3_in(-3.0, 3.0)).collect();
    let n = (0..len)
        .map(|_| rng.vec3_in(-1.0, 1.0) * rng.range_f32(0.01, 100.0))
        .collect();
    Batch { p, n }
}

/// `len` random points followed by the adversarial ones for a light at `light`, a viewer at `eye`.
fn random_then_adversarial(rng: &mut Rng, len: usize, light: Vec3, eye: Vec3) -> Batch {
    let mut b = random_batch(rng, len);
    let adversarial = adversarial_batch(rng, light, eye);
    b.p.extend(&adversarial.p);
    b.n.extend(&adversarial.n);
    b
}

/// Adversarial points for a scene with a light at `light`, a viewer at `eye`.
fn adversarial_batch(rng: &mut Rng, light: Vec3, eye: Vec3) -> Batch {
    let mut p = Vec::new();
    let mut n = Vec::new();
    let mut push = |a: Vec3, b: Vec3| {
        p.push(a);
        n.push(b);
    };
    for _ in 0..8 {
        let q = rng.vec3_in(-2.0, 2.0);
        push(q, Vec3::ZERO); // zero normal
        push(light, rng.vec3_in(-1.0, 1.0)); // light at the point
        push(eye, rng.vec3_in(-1.0, 1.0)); // viewer at the point
        // Grazing: the normal perpendicular to L.
        let l = (light - q).normalize();
        let t = l.any_orthonormal_vector();
        push(q, t);
        push(q, t + l * 1e-7);
        // Huge and tiny coordinates and normals.
        push(q * 1e20, rng.vec3_in(-1.0, 1.0));
        push(q * 3e38, rng.vec3_in(-1.0, 1.0));
        push(q, rng.vec3_in(-1.0, 1.0) * 1e-20);
        push(q, rng.vec3_in(-1.0, 1.0) * 1e-40);
        push(q, rng.vec3_in(-1.0, 1.0) * 1e25);
        push(q * 1e-30, rng.vec3_in(-1.0, 1.0));
        // Ordinary neighbours in the same chunk.
        push(q, rng.vec3_in(-1.0, 1.0));
    }
    // L = −V: points on the segment between the light and the eye.
    for k in 1..20 {
        let t = k as f32 / 20.0;
        let q = light + (eye - light) * t;
        push(q, rng.vec3_in(-1.0, 1.0));
    }
    Batch { p, n }
}

fn models(pow: PowStrategy) -> Vec<(String, Model)> {
    let mut v: Vec<(String, Model)> = vec![
        ("lambert".into(), Lambert::default().into()),
        (
            "lambert energy".into(),
            Lambert {
                normalization: Normalization::Energy,
            }
            .into(),
        ),
    ];
    for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
        for normalization in [
            Normalization::None,
            Normalization::Energy,
            Normalization::EnergyExact,
        ] {
            v.push((
                format!("phong {gate:?} {normalization:?} {}", pow.name()),
                Phong {
                    gate,
                    normalization,
                    pow,
                }
                .into(),
            ));
            v.push((
                format!("blinn {gate:?} {normalization:?} {}", pow.name()),
                BlinnPhong {
                    gate,
                    normalization,
                    pow,
                }
                .into(),
            ));
        }
    }
    v
}

/// A light whose factor reaches `f32::MAX` (inverse-square, power `f32::MAX`) shining straight
/// down a normal: the kernel's `N·L`, from approximate inverse norms, can round above 1, and
/// `f·N·L` then overflowed to `+∞` where the exact product, and `shade`'s, is finite, so the
/// diffuse sum saturated (found by the fuzz campaign at 2×10⁸ evaluations: 2.96e38 for 2.75e38).
/// The weights of such a light are clamped at `f32::MAX`; the range holds at every level.
#[test]
fn a_factor_at_f32_max_does_not_overflow_its_weights() {
    let at = Vec3::new(1.4986923, -4.153731e-28, 0.07661843);
    let light: Light = PointLight::try_new(
        at,
        Attenuation::try_inverse_square_with_min_distance(f32::MAX, 9.060156e-26).unwrap(),
        LightColors::try_new(
            Vec3::new(9.029357e-19, 1.1754944e-38, 1.1754944e-38),
            Vec3::new(0.9282635, 0.10552591, 0.030394554),
            Vec3::new(0.0, 0.72638035, 3.0079384),
        )
        .unwrap(),
    )
    .unwrap()
    .into();
    let lights = [light];
    let m = Material::try_new(
        Vec3::new(0.5738926, 0.49116838, 0.13899434),
        Vec3::new(0.8704633, 0.966453, 0.8882274),
        Vec3::new(0.0, 2.8960936, 0.5),
        1587.0,
    )
    .unwrap();
    // The fuzz campaign's point, and points straight below the light at other distances, with
    // normals of other lengths pointing at it.
    let (mut p, mut n) = (
        vec![Vec3::new(1.4986923, 1.9860373e-9, 0.07661843)],
        vec![Vec3::new(6.656464e-20, -0.100385666, 1.1754944e-38)],
    );
    for k in 0..40 {
        let d = 1e-9 * (1.0 + k as f32 * 0.37);
        p.push(at + Vec3::new(0.0, d, 0.0));
        n.push(Vec3::new(0.0, -(0.01 + k as f32 * 0.77), 0.0));
    }
    let b = Batch { p, n };
    for gate in [SpecularGate::None, SpecularGate::Cosine, SpecularGate::Step] {
        for viewer in [Viewer::At(at), Viewer::Infinite(Vec3::Y)] {
            let scene = Scene {
                lights: &lights,
                ambient: Vec3::ZERO,
                viewer,
            };
            let phong = Phong {
                gate,
                ..Phong::default()
            };
            check(
                &format!("factor f32::MAX, {gate:?}, {viewer:?}"),
                &phong,
                &m,
                &scene,
                &b,
            );
        }
    }
}

#[test]
fn every_level_agrees_with_scalar_on_random_input() {
    let mut rng = Rng::new(1);
    let b = random_batch(&mut rng, 16 * 20 + 7);
    let lights = [
        point_light(&mut rng, Vec3::new(1.2, 1.0, 2.0)),
        point_light(&mut rng, Vec3::new(-2.0, 0.5, -1.0)),
    ];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
    };
    for pow in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
        for s in [0.0f32, 0.5, 1.0, 20.5, 32.0, 128.0, 1500.0] {
            let m = Material::try_new(
                rng.vec3_in(0.0, 1.0),
                rng.vec3_in(0.0, 1.0),
                rng.vec3_in(0.0, 1.0),
                s,
            )
            .unwrap()
            .try_with_emission(Vec3::splat(0.01))
            .unwrap();
            for (name, model) in models(pow) {
                check(&format!("{name} s={s}"), &model, &m, &scene, &b);
            }
        }
    }
}

#[test]
fn concrete_model_types_match_the_enum() {
    let mut rng = Rng::new(2);
    let b = random_batch(&mut rng, 100);
    let lights = [point_light(&mut rng, Vec3::new(0.0, 2.0, 1.0))];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
    };
    let m = Material::try_from_color(Vec3::new(0.8, 0.4, 0.2), 20.5).unwrap();
    let pow = PowStrategy::Auto;
    let phong = Phong {
        pow,
        ..Phong::default()
    };
    let blinn = BlinnPhong {
        pow,
        ..BlinnPhong::default()
    };
    check("phong", &phong, &m, &scene, &b);
    check("blinn", &blinn, &m, &scene, &b);
    check("lambert", &Lambert::default(), &m, &scene, &b);
    // The kernel sees only the model's constants: the concrete types and the enum give the same
    // bits.
    for level in Level::supported() {
        let pairs = [
            (
                run(level, &phong, &m, &scene, &b),
                run(level, &Model::from(phong), &m, &scene, &b),
            ),
            (
                run(level, &blinn, &m, &scene, &b),
                run(level, &Model::from(blinn), &m, &scene, &b),
            ),
            (
                run(level, &Lambert::default(), &m, &scene, &b),
                run(level, &Model::from(Lambert::default()), &m, &scene, &b),
            ),
        ];
        for (concrete, en) in pairs {
            assert_eq!(concrete, en, "{level}: concrete type vs Model");
        }
    }
}

#[test]
fn every_level_agrees_with_scalar_on_adversarial_input() {
    let mut rng = Rng::new(3);
    let light_at = Vec3::new(1.0, 1.0, 1.0);
    let eye = Vec3::new(-1.0, -1.0, 2.0);
    let b = adversarial_batch(&mut rng, light_at, eye);
    let lights = [point_light(&mut rng, light_at)];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.1),
        viewer: Viewer::At(eye),
    };
    for s in [0.0f32, 0.5, 10.25, 32.0] {
        let m = Material::try_from_color(Vec3::new(0.9, 0.5, 0.3), s).unwrap();
        for (name, model) in models(PowStrategy::Auto) {
            check(&format!("adversarial {name} s={s}"), &model, &m, &scene, &b);
        }
    }
}

#[test]
fn degenerate_points_have_the_documented_results() {
    let mut rng = Rng::new(4);
    let light_at = Vec3::new(0.0, 2.0, 0.0);
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let lights = [point_light(&mut rng, light_at)];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.1),
        viewer: Viewer::At(eye),
    };
    let m = Material::try_from_color(Vec3::new(0.9, 0.5, 0.3), 16.0)
        .unwrap()
        .try_with_emission(Vec3::splat(0.02))
        .unwrap();
    let model = Phong {
        gate: SpecularGate::None,
        ..Phong::default()
    };
    let b = Batch {
        p: vec![Vec3::new(0.3, 0.1, 0.0), light_at, eye, Vec3::ZERO],
        n: vec![Vec3::ZERO, Vec3::Y, Vec3::Z, Vec3::Y],
    };
    for level in Level::supported() {
        let out = run(level, &model, &m, &scene, &b);
        let t0 = phong::shade(&model, &m, &scene, b.p[0], b.n[0]);
        assert_eq!(t0.diffuse + t0.specular, Vec3::ZERO, "scalar: zero normal");
        assert_eq!(
            out[0],
            t0.total(),
            "{level}: zero normal → ambient + emission only"
        );
        let t1 = phong::shade(&model, &m, &scene, b.p[1], b.n[1]);
        assert_eq!(
            out[1],
            t1.total(),
            "{level}: light at the point → ambient only"
        );
        let t2 = phong::shade(&model, &m, &scene, b.p[2], b.n[2]);
        assert_eq!(t2.specular, Vec3::ZERO, "scalar: viewer at the point");
        assert_eq!(
            out[2],
            t2.total(),
            "{level}: viewer at the point → no specular"
        );
    }
    // L = −V for Blinn-Phong: the viewer straight below, the light straight above.
    let lights = [DirectionalLight::try_new(Vec3::Y, colors(&mut rng)).unwrap()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(-Vec3::Y),
    };
    let blinn = BlinnPhong {
        gate: SpecularGate::None,
        ..BlinnPhong::default()
    };
    let b = Batch {
        p: vec![Vec3::ZERO; 17],
        n: vec![Vec3::new(0.3, 0.9, 0.1); 17],
    };
    for level in Level::supported() {
        let out = run(level, &blinn, &m, &scene, &b);
        let t = phong::shade(&blinn, &m, &scene, b.p[0], b.n[0]);
        assert_eq!(
            t.specular,
            Vec3::ZERO,
            "scalar: L = −V has no Blinn specular"
        );
        for o in out {
            assert!(
                (o - t.total()).abs().max_element() < 1e-6,
                "{level}: L = −V: {o} vs {}",
                t.total()
            );
        }
    }
}

#[test]
fn every_light_kind_and_viewer() {
    let mut rng = Rng::new(5);
    let b = random_batch(&mut rng, 16 * 3 + 5);
    let m = Material::try_new(Vec3::splat(0.2), Vec3::new(0.7, 0.5, 0.3), Vec3::ONE, 32.0).unwrap();
    let pow = PowStrategy::Auto;
    let blinn = BlinnPhong {
        pow,
        ..BlinnPhong::default()
    };
    // Directional and no-attenuation point lights, both viewers, and more lights than the kernel
    // prepares up front (8).
    let mut lights: Vec<Light> = vec![
        DirectionalLight::try_new(Vec3::new(1.0, 2.0, 0.5), colors(&mut rng))
            .unwrap()
            .into(),
        DirectionalLight::try_new(Vec3::new(-0.3, 0.2, 1.0), colors(&mut rng))
            .unwrap()
            .into(),
        PointLight::try_new(
            Vec3::new(0.0, 4.0, 0.0),
            Attenuation::None,
            colors(&mut rng),
        )
        .unwrap()
        .into(),
    ];
    for viewer in [
        Viewer::At(Vec3::new(0.0, 1.0, 4.0)),
        Viewer::Infinite(Vec3::new(0.2, 0.3, 1.0)),
        Viewer::Infinite(Vec3::ZERO),
    ] {
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::splat(0.03),
            viewer,
        };
        check(&format!("3 lights, {viewer:?}"), &blinn, &m, &scene, &b);
    }
    for k in 0..9 {
        lights.push(point_light(&mut rng, Vec3::new(k as f32 - 4.0, 3.0, 1.0)).into());
    }
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    check("12 lights", &blinn, &m, &scene, &b);
    // 70 lights: past the 8 prepared up front and the 56 after them that a call of more than one
    // chunk prepares once (the rest per chunk), with a light whose denominator may overflow (the
    // kernel's test for it travels with the prepared light).
    let mut many = lights.clone();
    many.push(
        PointLight::try_new(
            Vec3::new(1.0, -2.0, 0.5),
            Attenuation::try_polynomial(1.0, 0.0, 1e9).unwrap(),
            colors(&mut rng),
        )
        .unwrap()
        .into(),
    );
    for k in 0..57 {
        let at = Vec3::new((k % 8) as f32 - 4.0, (k / 8) as f32 - 3.0, 2.0);
        many.push(point_light(&mut rng, at).into());
    }
    assert_eq!(many.len(), 70);
    let scene = Scene {
        lights: &many,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    check("70 lights", &blinn, &m, &scene, &b);
    // Spot lights (no cone, a whole and a fractional exponent, exponent 0) and every other
    // falloff, also under a spot's cone: all in the kernel, each light's falloff by the scalar
    // formula's operations and a cone's power within its documented bound (which the range
    // includes), so the documented range holds as for the lights above.
    let spot = |at: Vec3, axis: Vec3, cone: SpotCone, attenuation, rng: &mut Rng| -> Light {
        SpotLight::try_with_cone(at, axis, cone, attenuation, colors(rng))
            .unwrap()
            .into()
    };
    let falloffs = [
        Attenuation::try_inverse_square(3.0).unwrap(),
        Attenuation::try_unreal(4.0).unwrap(),
        Attenuation::try_frostbite(3.5).unwrap(),
        Attenuation::try_polynomial(1.0, 0.2, 0.05).unwrap(),
    ];
    let mut kernel_lights: Vec<Light> = vec![
        spot(
            Vec3::new(0.0, 5.0, 0.0),
            -Vec3::Y,
            SpotCone::degrees(35.0).with_exponent(2.0),
            Attenuation::None,
            &mut rng,
        ),
        spot(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(-0.3, -0.4, -1.0),
            SpotCone::degrees(50.0).with_exponent(7.3),
            falloffs[1],
            &mut rng,
        ),
        spot(
            Vec3::new(-2.0, 1.0, 1.0),
            Vec3::X,
            SpotCone::degrees(80.0),
            falloffs[2],
            &mut rng,
        ),
        spot(
            Vec3::new(0.5, -3.0, 0.5),
            Vec3::Y,
            SpotCone::NONE,
            falloffs[3],
            &mut rng,
        ),
    ];
    for (k, attenuation) in falloffs.into_iter().enumerate() {
        kernel_lights.push(
            PointLight::try_new(
                Vec3::new(2.0 - k as f32, 2.0, 1.5 * k as f32 - 2.0),
                attenuation,
                colors(&mut rng),
            )
            .unwrap()
            .into(),
        );
    }
    let phong = Phong {
        pow,
        ..Phong::default()
    };
    for viewer in [
        Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
        Viewer::Infinite(Vec3::new(0.2, 0.3, 1.0)),
    ] {
        let scene = Scene {
            lights: &kernel_lights,
            ambient: Vec3::splat(0.01),
            viewer,
        };
        check(
            &format!("spot and falloff lights, {viewer:?}"),
            &blinn,
            &m,
            &scene,
            &b,
        );
        check(
            &format!("spot and falloff lights, {viewer:?}"),
            &phong,
            &m,
            &scene,
            &b,
        );
        // One of them at a time too, so no other light hides a wrong factor.
        for (j, light) in kernel_lights.iter().enumerate() {
            let one = [*light];
            let scene = Scene {
                lights: &one,
                ..scene
            };
            check(
                &format!("kernel light {j}, {viewer:?}"),
                &phong,
                &m,
                &scene,
                &b,
            );
        }
    }
}

#[test]
fn unsupported_levels_are_errors_and_detect_is_supported() {
    assert!(
        Level::detect().is_supported(),
        "detect picks a level it can run"
    );
    assert!(Level::Portable.is_supported(), "portable runs everywhere");
    let lights: [PointLight; 0] = [];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ONE,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let m = Material::try_from_color(Vec3::ONE, 1.0).unwrap();
    for &level in Level::ALL {
        let (mut r, mut g, mut b) = ([0.0f32; 3], [0.0f32; 3], [0.0f32; 3]);
        let z = [0.0f32; 3];
        let res = phong::shade_batch_with_level(
            level,
            &Lambert::default(),
            &m,
            &scene,
            SoaVec3::new(&z, &z, &z),
            SoaVec3::new(&z, &z, &z),
            SoaRgb::new(&mut r, &mut g, &mut b),
        );
        assert_eq!(
            res.is_ok(),
            level.is_supported(),
            "{level}: error exactly when unsupported"
        );
        if res.is_ok() {
            assert_eq!(r, [1.0; 3], "{level}: ambient only");
        }
    }
    eprintln!(
        "batch levels supported here: {:?}",
        Level::supported().collect::<Vec<_>>()
    );
}

/// The 8-bit criterion of `PowStrategy::cheapest_for_8bit`: on random scenes the automatic
/// choice differs from the f64 reference in no more 8-bit sRGB channels than the exact f32 path
/// does, plus 5 per million.
#[test]
fn auto_choice_is_8bit_exact() {
    let len = 1 << 19;
    let mut rng = Rng::new(6);
    let b = Batch {
        p: (0..len).map(|_| rng.vec3_in(-2.0, 2.0)).collect(),
        n: (0..len).map(|_| rng.vec3_in(-1.0, 1.0)).collect(),
    };
    let light_at = Vec3::new(1.2, 1.0, 2.0);
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let lights = [PointLight::try_new(
        light_at,
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        LightColors::try_new(Vec3::splat(0.2), Vec3::splat(0.5), Vec3::ONE).unwrap(),
    )
    .unwrap()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(eye),
    };
    let level = Level::detect();
    for blinn in [false, true] {
        for s in [2.5f32, 10.25, 20.5, 32.0, 50.5] {
            let m = Material::try_new(
                Vec3::new(1.0, 0.5, 0.31),
                Vec3::new(1.0, 0.5, 0.31),
                Vec3::splat(0.5),
                s,
            )
            .unwrap();
            let mismatches = |out: &[Vec3]| -> usize {
                out.iter()
                    .zip(b.p.iter().zip(&b.n))
                    .map(|(o, (&p, &n))| {
                        let r = reference(blinn, s as f64, light_at, eye, p, n);
                        let x = phong::linear_to_srgb8(*o);
                        let y = phong::linear_to_srgb8(r.as_vec3());
                        x.iter().zip(&y).filter(|(a, b)| a != b).count()
                    })
                    .sum()
            };
            let (auto, exact) = if blinn {
                let a = BlinnPhong {
                    pow: PowStrategy::Auto,
                    ..BlinnPhong::default()
                };
                let e = BlinnPhong::default();
                (
                    run(level, &a, &m, &scene, &b),
                    b.p.iter()
                        .zip(&b.n)
                        .map(|(&p, &n)| phong::shade(&e, &m, &scene, p, n).total())
                        .collect::<Vec<_>>(),
                )
            } else {
                let a = Phong {
                    pow: PowStrategy::Auto,
                    ..Phong::default()
                };
                let e = Phong::default();
                (
                    run(level, &a, &m, &scene, &b),
                    b.p.iter()
                        .zip(&b.n)
                        .map(|(&p, &n)| phong::shade(&e, &m, &scene, p, n).total())
                        .collect::<Vec<_>>(),
                )
            };
            let channels = (3 * len) as f64;
            let rate_auto = mismatches(&auto) as f64 / channels;
            let rate_exact = mismatches(&exact) as f64 / channels;
            assert!(
                rate_auto <= rate_exact + 5e-6,
                "blinn={blinn} s={s}: auto ({:?}) mismatch rate {rate_auto:.2e} vs exact f32 \
                 {rate_exact:.2e}",
                PowStrategy::cheapest_for_8bit(if blinn { 0.5 * s } else { s })
            );
        }
    }
}

/// The benches' equation in f64: step gate, classic lobes, polynomial attenuation (1, 0.09,
/// 0.032), light colours (0.2, 0.5, 1), material (1, 0.5, 0.31) / 0.5.
fn reference(blinn: bool, s: f64, light: Vec3, eye: Vec3, p: Vec3, n: Vec3) -> DVec3 {
    let (p, n) = (p.as_dvec3(), n.as_dvec3().normalize_or_zero());
    let lp = light.as_dvec3();
    let l = (lp - p).normalize();
    let v = (eye.as_dvec3() - p).normalize();
    let nl = n.dot(l);
    let base = if blinn {
        n.dot((l + v).normalize()).max(0.0)
    } else {
        (2.0 * nl * n - l).dot(v).max(0.0)
    };
    let spec = if nl > 0.0 && base > 0.0 {
        base.powf(s)
    } else {
        0.0
    };
    let d = (lp - p).length();
    let f = 1.0 / (1.0 + 0.09 * d + 0.032 * d * d);
    let k = DVec3::new(1.0, 0.5, 0.31);
    f * (0.2 * k + 0.5 * k * nl.max(0.0) + 0.5 * spec)
}

#[test]
fn blinn_keeps_the_grazing_mirror_glint_at_every_level() {
    // A sun ε above the horizon and a viewer ε above it on the other side: H = N exactly, so the
    // Blinn-Phong lobe is 1 for every s. The cosine form (N·L + N·V)²/(2 + 2 L·V) loses it once
    // 2 + 2 L·V ≈ 4ε² is below f32's resolution of L·V; the kernels send such lanes to the scalar
    // path, whose (N·H)² comes from L + V. 16 + 3 points, so both full chunks and the tail run.
    let mut p = Vec::new();
    let mut n = Vec::new();
    let eps = [1e-2f32, 3e-3, 1e-3, 1e-4, 1e-5];
    for i in 0..19 {
        p.push(Vec3::new(i as f32 * 0.1, 0.0, 0.0));
        n.push(Vec3::Z);
    }
    let b = Batch { p, n };
    let m = Material::try_new(Vec3::ZERO, Vec3::ZERO, Vec3::ONE, 64.0).unwrap();
    for &e in &eps {
        let sun = DirectionalLight::try_new(
            Vec3::new(e.cos(), 0.0, e.sin()),
            LightColors::try_new(Vec3::ZERO, Vec3::ZERO, Vec3::ONE).unwrap(),
        )
        .unwrap();
        let scene = Scene {
            lights: &[sun],
            ambient: Vec3::ZERO,
            viewer: Viewer::Infinite(Vec3::new(-e.cos(), 0.0, e.sin())),
        };
        for level in Level::supported() {
            let out = run(level, &BlinnPhong::default(), &m, &scene, &b);
            for (i, c) in out.iter().enumerate() {
                // (N·H)² within a few ulps of 1, raised to s/2 = 32: error ≤ 32 · 4 · 2⁻²⁴.
                assert!(
                    (c.x - 1.0).abs() < 1e-5,
                    "{} ε = {e:e}, point {i}: Blinn-Phong glint {c}, want 1",
                    level.name()
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Overflow: no 0·∞, and the documented saturation rule.
// ---------------------------------------------------------------------------------------------

/// `count` copies of one point, so full chunks and the tail both run.
fn same_point(p: Vec3, n: Vec3, count: usize) -> Batch {
    Batch {
        p: vec![p; count],
        n: vec![n; count],
    }
}

#[test]
fn a_zero_lobe_under_a_huge_normalised_colour_stays_zero() {
    // Regression: with Energy normalisation at s = f32::MAX the factor (s + 2)/2π ≈ 5.4e37 times
    // Ls = 10 overflowed in the kernel's prepared colour, and a lane whose lobe is 0 computed
    // 0·∞ = NaN, which the final clamp turned into f32::MAX. R·V = 2·0.8·0.8 − 1 = 0.28, and
    // 0.28^MAX = 0: only the diffuse 0.5·1·0.8/π = 0.12732 remains.
    let model = Phong {
        normalization: Normalization::Energy,
        ..Phong::default()
    };
    let m = Material::try_new(Vec3::ZERO, Vec3::splat(0.5), Vec3::ONE, f32::MAX).unwrap();
    let sun = DirectionalLight::try_new(
        Vec3::Z,
        LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::splat(10.0)).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[sun],
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let b = same_point(Vec3::ZERO, Vec3::new(0.0, 0.6, 0.8), 19);
    let want = phong::shade(&model, &m, &scene, b.p[0], b.n[0]).total();
    let exact = 0.5 * 0.8 / std::f64::consts::PI;
    assert!(
        (want.as_dvec3() - DVec3::splat(exact)).abs().max_element() < 1e-6,
        "shade: {want}"
    );
    for level in Level::supported() {
        for (i, c) in run(level, &model, &m, &scene, &b).into_iter().enumerate() {
            assert!(
                (c - want).abs().max_element() < 1e-6,
                "{level}, point {i}: batch {c}, shade {want}"
            );
        }
    }
    check("energy, s = MAX, Ls = 10", &model, &m, &scene, &b);
}

#[test]
fn saturation_applies_the_material_colour_to_the_saturated_sum() {
    // Regression: Ka = 6e20, La = 3e25, f = 1/729. Ka·(f·La) = 6e20 · 4.1e22 overflows: the
    // documented rule (and shade) give f32::MAX; the kernel used to clamp Ka⊙La first and then
    // multiply by f, giving MAX/729 = 4.67e35.
    let light = PointLight::try_new(
        Vec3::new(0.0, 0.0, 2.0),
        Attenuation::try_polynomial(729.0, 0.0, 0.0).unwrap(),
        LightColors::try_new(Vec3::splat(3e25), Vec3::ZERO, Vec3::ZERO).unwrap(),
    )
    .unwrap();
    let m = Material::try_new(Vec3::splat(6e20), Vec3::ZERO, Vec3::ZERO, 8.0).unwrap();
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 1.0, 3.0)),
    };
    let b = same_point(Vec3::ZERO, Vec3::Z, 17);
    let model = Phong::default();
    assert_eq!(
        phong::shade(&model, &m, &scene, b.p[0], b.n[0]).total(),
        Vec3::splat(f32::MAX),
        "shade saturates"
    );
    for level in Level::supported() {
        for (i, c) in run(level, &model, &m, &scene, &b).into_iter().enumerate() {
            assert_eq!(c, Vec3::splat(f32::MAX), "{level}, point {i}");
        }
    }
    check("Ka = 6e20, La = 3e25, f = 1/729", &model, &m, &scene, &b);
}

/// A colour channel log-uniform in `[1e-3, f32::MAX]`, sometimes 0.
fn huge(rng: &mut Rng) -> f32 {
    if rng.unit_f32() < 0.1 {
        0.0
    } else {
        10f32.powf(rng.range_f32(-3.0, 38.53)).min(f32::MAX)
    }
}

fn huge_vec(rng: &mut Rng) -> Vec3 {
    Vec3::new(huge(rng), huge(rng), huge(rng))
}

#[test]
fn huge_colours_and_factors_follow_the_saturation_rule_at_every_level() {
    let mut rng = Rng::new(11);
    let b = random_batch(&mut rng, 16 * 4 + 3);
    for round in 0..12 {
        let lights: Vec<Light> = vec![
            DirectionalLight::try_new(
                rng.vec3_in(-1.0, 1.0),
                LightColors::try_new(huge_vec(&mut rng), huge_vec(&mut rng), huge_vec(&mut rng))
                    .unwrap(),
            )
            .unwrap()
            .into(),
            PointLight::try_new(
                rng.vec3_in(-3.0, 3.0),
                Attenuation::try_polynomial(rng.range_f32(0.0, 1.0), 0.0, rng.range_f32(0.0, 0.1))
                    .unwrap(),
                LightColors::try_new(huge_vec(&mut rng), huge_vec(&mut rng), huge_vec(&mut rng))
                    .unwrap(),
            )
            .unwrap()
            .into(),
        ];
        let scene = Scene {
            lights: &lights,
            ambient: huge_vec(&mut rng),
            viewer: Viewer::At(rng.vec3_in(-4.0, 4.0)),
        };
        for s in [0.0f32, 0.5, 20.0, 1e4, 1e30, f32::MAX] {
            let m = Material::try_new(
                huge_vec(&mut rng),
                huge_vec(&mut rng),
                huge_vec(&mut rng),
                s,
            )
            .unwrap()
            .try_with_emission(huge_vec(&mut rng))
            .unwrap();
            for (name, model) in models(PowStrategy::Auto) {
                check(
                    &format!("round {round}: huge {name} s={s}"),
                    &model,
                    &m,
                    &scene,
                    &b,
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Ill-conditioned lobes: the documented range at every level.
// ---------------------------------------------------------------------------------------------

/// A directional light along `l` and an infinite viewer along `v`, unit colours.
fn sun_and_viewer(l: Vec3, v: Vec3) -> ([DirectionalLight; 1], Viewer) {
    let colors = LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE).unwrap();
    (
        [DirectionalLight::try_new(l, colors).unwrap()],
        Viewer::Infinite(v),
    )
}

/// A random unit vector.
fn unit(rng: &mut Rng) -> Vec3 {
    loop {
        let v = rng.vec3_in(-1.0, 1.0);
        if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
            return v.normalize();
        }
    }
}

#[test]
fn blinn_near_the_scalar_cutoff_at_every_level() {
    // Light and viewer nearly opposite: 2 + 2 L·V from 1e-3 (scalar path) through the cutoff 1e-2
    // (where the kernel's cosine form is at its worst) to 0.3, with H = Z and normals spread
    // around H by about the lobe's width, at high shininess.
    let mut rng = Rng::new(12);
    let m = Material::try_new(Vec3::splat(0.1), Vec3::splat(0.5), Vec3::ONE, 284.0).unwrap();
    for k in 0..=40 {
        let den = 1e-3f64 * 300f64.powf(k as f64 / 40.0);
        let half = ((1.0 - den / 4.0).sqrt()).acos(); // cos² of the half angle = den/4
        let (sh, ch) = (half.sin() as f32, half.cos() as f32);
        let (l, v) = (Vec3::new(sh, 0.0, ch), Vec3::new(-sh, 0.0, ch));
        let (lights, viewer) = sun_and_viewer(l, v);
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer,
        };
        let b = Batch {
            p: (0..35).map(|_| rng.vec3_in(-1.0, 1.0)).collect(),
            n: (0..35)
                .map(|i| Vec3::Z + rng.vec3_in(-1.0, 1.0) * (0.02 * i as f32 / 35.0))
                .collect(),
        };
        for s in [32.0f32, 284.0, 1000.0, 2048.0] {
            let m = Material::try_new(m.ambient(), m.diffuse(), m.specular(), s).unwrap();
            for pow in [
                PowStrategy::Exact,
                PowStrategy::Auto,
                PowStrategy::SplitPoly5,
            ] {
                for normalization in [Normalization::None, Normalization::EnergyExact] {
                    let model = BlinnPhong {
                        pow,
                        normalization,
                        ..BlinnPhong::default()
                    };
                    let what = format!("2 + 2 L·V = {den:.3e}, s = {s}, {pow:?} {normalization:?}");
                    check(&what, &model, &m, &scene, &b);
                }
            }
        }
    }
}

#[test]
fn grazing_light_at_every_level() {
    // N·L within 1e-5 of 0, both signs: the step gate and the cosine gate switch there.
    let mut rng = Rng::new(13);
    for _ in 0..6 {
        let l = unit(&mut rng);
        let v = unit(&mut rng);
        let (lights, viewer) = sun_and_viewer(l, v);
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer,
        };
        let b = Batch {
            p: (0..37).map(|_| rng.vec3_in(-1.0, 1.0)).collect(),
            n: (0..37)
                .map(|_| {
                    let t = l.cross(unit(&mut rng)).normalize();
                    t + l * rng.range_f32(-1e-5, 1e-5)
                })
                .collect(),
        };
        for s in [0.5f32, 8.0, 64.0] {
            let m = Material::try_from_color(Vec3::splat(0.8), s).unwrap();
            for (name, model) in models(PowStrategy::Auto) {
                check(&format!("grazing {name} s={s}"), &model, &m, &scene, &b);
            }
        }
    }
}

#[test]
fn broad_lobes_near_their_zero_at_every_level() {
    // s < 1: the lobe's base within 1e-4 of 0, where x^s is steepest (Phong's cut-off edge).
    let mut rng = Rng::new(14);
    for _ in 0..6 {
        let l = unit(&mut rng);
        let v = unit(&mut rng);
        let (lights, viewer) = sun_and_viewer(l, v);
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer,
        };
        // Phong: R·V = 0 on a curve of normals; find points on it by bisection between a normal
        // with R·V > 0 (N = H) and one with R·V < 0, then move off it by up to 1e-4.
        let (ld, vd) = (l.as_dvec3(), v.as_dvec3());
        let rv = |n: DVec3| 2.0 * n.dot(ld) * n.dot(vd) - ld.dot(vd);
        let h = (ld + vd).normalize();
        let mut normals = Vec::new();
        while normals.len() < 37 {
            let away = unit(&mut rng).as_dvec3();
            if rv(away) >= 0.0 {
                continue;
            }
            let target = rng.range_f32(-1e-4, 1e-4) as f64;
            let (mut a, mut b) = (0.0f64, 1.0f64);
            for _ in 0..60 {
                let mid = 0.5 * (a + b);
                let n = (h * (1.0 - mid) + away * mid).normalize();
                if rv(n) > target { a = mid } else { b = mid }
            }
            normals.push((h * (1.0 - a) + away * a).normalize().as_vec3());
        }
        // Blinn-Phong: N·H = 0 on the great circle perpendicular to H.
        for _ in 0..37 {
            let t = h.cross(unit(&mut rng).as_dvec3()).normalize();
            normals.push((t + h * rng.range_f32(-1e-4, 1e-4) as f64).as_vec3());
        }
        let b = Batch {
            p: (0..normals.len()).map(|_| rng.vec3_in(-1.0, 1.0)).collect(),
            n: normals,
        };
        for s in [0.01f32, 0.3, 0.7, 1.0] {
            let m = Material::try_from_color(Vec3::splat(0.8), s).unwrap();
            for (name, model) in models(PowStrategy::Auto)
                .into_iter()
                .chain(models(PowStrategy::Poly3))
            {
                check(&format!("broad lobe {name} s={s}"), &model, &m, &scene, &b);
            }
        }
    }
}

#[test]
fn unsaturated_points_of_a_call_that_could_saturate_are_as_accurate() {
    // A call whose normalised specular term could overflow (factor ≈ 1.6e37 for Phong and 4e36
    // for Blinn-Phong, times Ls = 100) takes the kernels' nine-sum path at every point; at
    // s = 1e38 the lobe is 0 off the exact mirror direction, so the points are ordinary and must
    // meet the same range.
    let mut rng = Rng::new(15);
    let b = random_batch(&mut rng, 16 * 6 + 5);
    let lights = [
        PointLight::try_new(
            Vec3::new(1.2, 1.0, 2.0),
            Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
            LightColors::try_new(Vec3::splat(0.2), Vec3::ONE, Vec3::splat(100.0)).unwrap(),
        )
        .unwrap(),
        point_light(&mut rng, Vec3::new(-2.0, 0.5, -1.0)),
    ];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
    };
    let m = Material::try_new(
        rng.vec3_in(0.0, 1.0),
        rng.vec3_in(0.0, 1.0),
        Vec3::ONE,
        1e38,
    )
    .unwrap()
    .try_with_emission(Vec3::splat(0.01))
    .unwrap();
    for normalization in [Normalization::Energy, Normalization::EnergyExact] {
        for pow in [PowStrategy::Auto, PowStrategy::Exact] {
            let phong = Phong {
                normalization,
                pow,
                ..Phong::default()
            };
            let blinn = BlinnPhong {
                normalization,
                pow,
                ..BlinnPhong::default()
            };
            check(
                &format!("phong {normalization:?} {pow:?}"),
                &phong,
                &m,
                &scene,
                &b,
            );
            check(
                &format!("blinn {normalization:?} {pow:?}"),
                &blinn,
                &m,
                &scene,
                &b,
            );
        }
    }
}

/// The 8-bit outputs at every level: each pixel is `linear_to_srgb8` of the same level's `f32`
/// output, alpha 255, and `xrgb8` packs the same levels; a size that is not a multiple of the
/// kernel's 16 lanes, random and adversarial points, and a scene the kernel sends to the scalar
/// path. Against the scalar `shade`, a level may differ by one where the two colours straddle a
/// level boundary: at most 1 % of the channels here (the two differ by the kernel's documented
/// error, a few 1e-6, against a level spacing of about 4e-3 where it is narrowest in [0, 1]).
#[test]
fn eight_bit_outputs_are_the_encoded_batch_at_every_level() {
    let mut rng = Rng::new(8);
    let light_at = Vec3::new(1.2, 1.0, 2.0);
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let b = random_then_adversarial(&mut rng, 1024 + 256 * 3 + 37, light_at, eye);
    let s = b.soa();
    let len = b.p.len();
    let m = Material::try_new(Vec3::splat(0.2), Vec3::new(0.9, 0.5, 0.3), Vec3::ONE, 20.5).unwrap();
    let blinn = BlinnPhong {
        pow: PowStrategy::Auto,
        ..BlinnPhong::default()
    };
    let kernel_lights: Vec<Light> = vec![point_light(&mut rng, light_at).into()];
    let mut scalar_lights = kernel_lights.clone();
    scalar_lights.push(
        SpotLight::try_new(eye, -Vec3::Z, 0.6, 2.0, Attenuation::None, colors(&mut rng))
            .unwrap()
            .into(),
    );
    for lights in [&kernel_lights, &scalar_lights] {
        let scene = Scene {
            lights,
            ambient: Vec3::splat(0.02),
            viewer: Viewer::At(eye),
        };
        let (mut near, mut channels) = (0usize, 0usize);
        for level in Level::supported() {
            let linear = run(level, &blinn, &m, &scene, &b);
            let mut rgba = vec![[7u8; 4]; len];
            let n = phong::shade_batch_rgba8_with_level(
                level,
                &blinn,
                &m,
                &scene,
                SoaVec3::new(&s[0], &s[1], &s[2]),
                SoaVec3::new(&s[3], &s[4], &s[5]),
                &mut rgba,
            )
            .expect("level reported as supported");
            assert_eq!(n, len);
            for i in 0..len {
                let [r, g, bl] = phong::linear_to_srgb8(linear[i]);
                assert_eq!(rgba[i], [r, g, bl, 255], "{level}: point {i}");
                let want = phong::linear_to_srgb8(
                    phong::shade(&blinn, &m, &scene, b.p[i], b.n[i]).total(),
                );
                for c in 0..3 {
                    let d = rgba[i][c].abs_diff(want[c]);
                    assert!(
                        d <= 1,
                        "{level}: point {i} channel {c}: {} vs {}",
                        rgba[i][c],
                        want[c]
                    );
                    near += usize::from(d == 1);
                    channels += 1;
                }
            }
        }
        assert!(
            near * 100 <= channels,
            "{near} of {channels} channels one level off"
        );
        let mut rgba = vec![[0u8; 4]; len];
        let mut xrgb = vec![0xffff_ffffu32; len];
        let soa = |k: usize| &s[k][..];
        let positions = SoaVec3::new(soa(0), soa(1), soa(2));
        let normals = SoaVec3::new(soa(3), soa(4), soa(5));
        phong::shade_batch_rgba8(&blinn, &m, &scene, positions, normals, &mut rgba);
        let count = phong::shade_batch_xrgb8(&blinn, &m, &scene, positions, normals, &mut xrgb);
        assert_eq!(count, len);
        for i in 0..len {
            let [r, g, bl, a] = rgba[i].map(u32::from);
            assert_eq!(a, 255);
            assert_eq!(xrgb[i], r << 16 | g << 8 | bl, "point {i}");
        }
    }
}

/// The array-of-structs entry points, from every `AosVec3` element type, give `shade_batch`'s results bit for bit (the same kernel on
/// the same groups of 16: the 1024-point chunks are a multiple of them), with sizes that are not
/// multiples of a chunk, random and adversarial points, and a scene that takes the scalar path.
#[test]
fn array_of_structs_input_gives_the_soa_results() {
    let mut rng = Rng::new(9);
    let light_at = Vec3::new(-1.0, 2.0, 1.5);
    let eye = Vec3::new(0.5, 0.0, 4.0);
    let b = random_then_adversarial(&mut rng, 1024 * 2 + 100, light_at, eye);
    let len = b.p.len();
    let m = Material::try_new(Vec3::splat(0.1), Vec3::new(0.8, 0.6, 0.2), Vec3::ONE, 32.0).unwrap();
    let phong_model = Phong {
        pow: PowStrategy::Auto,
        ..Phong::default()
    };
    let kernel_lights: Vec<Light> = vec![
        point_light(&mut rng, light_at).into(),
        DirectionalLight::try_new(Vec3::new(0.3, 1.0, 0.2), colors(&mut rng))
            .unwrap()
            .into(),
    ];
    let mut scalar_lights = kernel_lights.clone();
    scalar_lights.push(
        PointLight::try_new(eye, Attenuation::try_unreal(6.0).unwrap(), colors(&mut rng))
            .unwrap()
            .into(),
    );
    for lights in [&kernel_lights, &scalar_lights] {
        let scene = Scene {
            lights,
            ambient: Vec3::splat(0.02),
            viewer: Viewer::At(eye),
        };
        let want = run(Level::detect(), &phong_model, &m, &scene, &b);
        let mut out = vec![Vec3::NAN; len];
        let n = phong::shade_batch_aos(&phong_model, &m, &scene, &b.p, &b.n, &mut out);
        assert_eq!(n, len);
        let mut rgba = vec![[0u8; 4]; len];
        phong::shade_batch_aos_rgba8(&phong_model, &m, &scene, &b.p, &b.n, &mut rgba);
        for i in 0..len {
            assert_eq!(
                out[i].to_array().map(f32::to_bits),
                want[i].to_array().map(f32::to_bits),
                "point {i}"
            );
            let [r, g, bl] = phong::linear_to_srgb8(want[i]);
            assert_eq!(rgba[i], [r, g, bl, 255], "point {i}");
        }
        // The four-wide layouts a G-buffer keeps (the fourth component ignored, so garbage
        // there must not matter), `Vec3A` and `[f32; 3]`: the same results, bit for bit.
        let p4: Vec<[f32; 4]> = b.p.iter().map(|v| [v.x, v.y, v.z, f32::NAN]).collect();
        let n4: Vec<glam::Vec4> = b.n.iter().map(|v| v.extend(-1.0e30)).collect();
        let p3a: Vec<glam::Vec3A> = b.p.iter().map(|&v| v.into()).collect();
        let n3: Vec<[f32; 3]> = b.n.iter().map(|v| v.to_array()).collect();
        let mut out4 = vec![Vec3::NAN; len];
        let mut out3 = vec![Vec3::NAN; len];
        assert_eq!(
            phong::shade_batch_aos(&phong_model, &m, &scene, &p4, &n4, &mut out4),
            len
        );
        assert_eq!(
            phong::shade_batch_aos(&phong_model, &m, &scene, &p3a, &n3, &mut out3),
            len
        );
        let mut rgba4 = vec![[0u8; 4]; len];
        phong::shade_batch_aos_rgba8(&phong_model, &m, &scene, &p4, &n4, &mut rgba4);
        let bits = |v: &Vec3| v.to_array().map(f32::to_bits);
        for i in 0..len {
            assert_eq!(bits(&out4[i]), bits(&want[i]), "[f32; 4] / Vec4, point {i}");
            assert_eq!(
                bits(&out3[i]),
                bits(&want[i]),
                "Vec3A / [f32; 3], point {i}"
            );
        }
        assert_eq!(rgba4, rgba);
    }
}

/// One `BatchShader`, prepared once and used for many calls (a frame's rows, here 64-point parts:
/// whole groups of 16 lanes, as each call's points are grouped), gives the free functions'
/// results bit for bit at every level, for every output form, with a scene the kernel takes and
/// one it sends point by point.
#[test]
fn a_prepared_batch_shader_gives_the_free_functions_results() {
    let mut rng = Rng::new(10);
    let light_at = Vec3::new(0.7, 1.5, 2.0);
    let eye = Vec3::new(0.0, 0.5, 3.5);
    let b = random_then_adversarial(&mut rng, 64 * 9 + 21, light_at, eye);
    let s = b.soa();
    let len = b.p.len();
    let m = Material::try_new(Vec3::splat(0.1), Vec3::new(0.7, 0.4, 0.9), Vec3::ONE, 20.5).unwrap();
    let model = BlinnPhong::default();
    let kernel_lights: Vec<Light> = vec![point_light(&mut rng, light_at).into()];
    let mut scalar_lights = kernel_lights.clone();
    scalar_lights.push(
        PointLight::try_new(eye, Attenuation::try_unreal(6.0).unwrap(), colors(&mut rng))
            .unwrap()
            .into(),
    );
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    for lights in [&kernel_lights, &scalar_lights] {
        let scene = Scene {
            lights,
            ambient: Vec3::splat(0.03),
            viewer: Viewer::At(eye),
        };
        for level in Level::supported() {
            let shader = phong::BatchShader::with_level(level, &model, &m, &scene)
                .expect("level reported as supported");
            assert_eq!(shader.level(), level);
            let want = run(level, &model, &m, &scene, &b);
            let (mut r, mut g, mut bl) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
            let mut rgba = vec![[7u8; 4]; len];
            let mut xrgb = vec![7u32; len];
            let mut start = 0;
            while start < len {
                let end = (start + 64).min(len);
                let part = |k: usize| &s[k][start..end];
                let positions = SoaVec3::new(part(0), part(1), part(2));
                let normals = SoaVec3::new(part(3), part(4), part(5));
                let out = SoaRgb::new(&mut r[start..end], &mut g[start..end], &mut bl[start..end]);
                assert_eq!(shader.shade(positions, normals, out), end - start);
                let count = shader.shade_rgba8(positions, normals, &mut rgba[start..end]);
                assert_eq!(count, end - start);
                let count = shader.shade_xrgb8(positions, normals, &mut xrgb[start..end]);
                assert_eq!(count, end - start);
                start = end;
            }
            let mut aos = vec![Vec3::NAN; len];
            assert_eq!(shader.shade_aos(&b.p, &b.n, &mut aos), len);
            let mut aos_rgba = vec![[0u8; 4]; len];
            assert_eq!(shader.shade_aos_rgba8(&b.p, &b.n, &mut aos_rgba), len);
            // A G-buffer of the same points with every third pixel uncovered: the free
            // functions' colours on the covered ones, the others keep what they had.
            let coverage: Vec<bool> = (0..len).map(|i| i % 3 != 0).collect();
            let gbuffer = phong::GBuffer::new(
                SoaVec3::new(&s[0], &s[1], &s[2]),
                SoaVec3::new(&s[3], &s[4], &s[5]),
            )
            .with_coverage(&coverage);
            let (mut gr, mut gg, mut gb) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
            let gout = SoaRgb::new(&mut gr, &mut gg, &mut gb);
            assert_eq!(shader.shade_gbuffer(&gbuffer, gout), len);
            let (mut fr, mut fg, mut fb) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
            let fout = SoaRgb::new(&mut fr, &mut fg, &mut fb);
            let n = phong::shade_gbuffer_with_level(level, &model, &m, &scene, &gbuffer, fout);
            assert_eq!(n, Ok(len));
            let mut g_rgba = vec![[7u8; 4]; len];
            assert_eq!(shader.shade_gbuffer_rgba8(&gbuffer, &mut g_rgba), len);
            let mut free_rgba = vec![[7u8; 4]; len];
            let n = phong::shade_gbuffer_rgba8_with_level(
                level,
                &model,
                &m,
                &scene,
                &gbuffer,
                &mut free_rgba,
            );
            assert_eq!(n, Ok(len));
            assert_eq!(g_rgba, free_rgba, "{level}: G-buffer RGBA8");
            for i in 0..len {
                let got = Vec3::new(r[i], g[i], bl[i]);
                assert_eq!(bits(got), bits(want[i]), "{level}: point {i}");
                assert_eq!(bits(aos[i]), bits(want[i]), "{level}: AoS point {i}");
                let [cr, cg, cb] = phong::linear_to_srgb8(want[i]);
                assert_eq!(rgba[i], [cr, cg, cb, 255], "{level}: RGBA8 point {i}");
                assert_eq!(aos_rgba[i], rgba[i], "{level}: AoS RGBA8 point {i}");
                let [cr, cg, cb] = [cr, cg, cb].map(u32::from);
                assert_eq!(xrgb[i], cr << 16 | cg << 8 | cb, "{level}: XRGB8 point {i}");
                let gcol = Vec3::new(gr[i], gg[i], gb[i]);
                let free = Vec3::new(fr[i], fg[i], fb[i]);
                assert_eq!(bits(gcol), bits(free), "{level}: G-buffer point {i}");
                if !coverage[i] {
                    assert_eq!(gcol, Vec3::splat(-1.0), "{level}: uncovered point {i}");
                    assert_eq!(g_rgba[i], [7; 4], "{level}: uncovered pixel {i}");
                }
            }
        }
    }
}
