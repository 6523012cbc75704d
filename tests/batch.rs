//! The batch path against the scalar `phong::shade`, at every dispatch level this machine runs,
//! for every model, gate, normalisation and several pow strategies, on random and adversarial
//! input; and the automatic pow choice against the 8-bit criterion.
//!
//! **Tolerance.** Per channel, `|batch − scalar| ≤ B·(2e-6·max(s, 1) + e_pow + 1e-5) + 1e-6·|scalar|`
//! with `B = Σ f·(|Ka⊙La| + |Kd⊙Ld| + |Ks⊙Ls|)` the most the lights can add at the point. Why:
//! the batch forms its cosines from approximate inverse norms (relative error ≤ 2.4e-7 each, three
//! of them, plus the dot products' rounding: a few 1e-7 on each cosine), and `x^s` turns a
//! relative error `δ` of its base into `s·δ`; `e_pow` is the strategy's documented error (0 for
//! exact and squaring); 1e-5 covers the different order of the sums. Points within 1e-4 of a
//! discontinuity of the equation (the step gate at `N·L = 0`, Blinn's `L = −V`, a lobe base at 0
//! when `s < 1`) are skipped for the value check (either side is right), but still checked for NaN.

use glam::{DVec3, Vec3};
use phong::{
    Attenuation, BatchLight, BatchModel, BlinnPhong, DirectionalLight, Lambert, Level, Light,
    LightColors, Material, Model, Normalization, Phong, PointLight, PowStrategy, Scene, SoaRgb,
    SoaVec3, SpecularGate, SpotLight, Viewer,
};

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.next()
    }
    fn vec(&mut self, a: f32, b: f32) -> Vec3 {
        Vec3::new(self.range(a, b), self.range(a, b), self.range(a, b))
    }
}

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

/// The documented max relative error of each strategy (src/pow.rs).
fn pow_bound(p: PowStrategy) -> f32 {
    match p {
        PowStrategy::Poly3 => 6e-2,
        PowStrategy::Poly5 => 1.2e-3,
        PowStrategy::Poly7 => 3e-5,
        PowStrategy::SplitPoly3 => 8e-4,
        PowStrategy::SplitPoly5 => 2e-5,
        PowStrategy::Auto => 3e-5,
        _ => 0.0,
    }
}

/// What the lights can add at `p` at most, per channel (`B` in the module docs).
fn light_bound<L: BatchLight>(m: &Material, scene: &Scene<'_, L>, p: Vec3) -> Vec3 {
    let mut b = Vec3::ZERO;
    for l in scene.lights {
        let f = l.sample(p).factor;
        let c = l.colors();
        b += f
            * (c.ambient() * m.ambient()
                + c.diffuse() * m.diffuse()
                + c.specular() * m.specular() * 3.0);
    }
    b
}

/// Whether `p` lies within 1e-4 of a discontinuity of the equation for some light.
fn near_edge<L: BatchLight>(scene: &Scene<'_, L>, s: f32, p: Vec3, n: Vec3) -> bool {
    let n = n.as_dvec3();
    if n.length() == 0.0 || !n.is_finite() {
        return false;
    }
    let n = n.normalize();
    let v = match scene.viewer {
        Viewer::At(e) => (e.as_dvec3() - p.as_dvec3()).normalize_or_zero(),
        Viewer::Infinite(d) => d.as_dvec3().normalize_or_zero(),
    };
    for light in scene.lights {
        let l = light.sample(p).direction.as_dvec3();
        if l == DVec3::ZERO {
            continue;
        }
        let nl = n.dot(l);
        let rv = 2.0 * nl * n.dot(v) - l.dot(v);
        if nl.abs() < 1e-4 || l.dot(v) < -1.0 + 1e-4 || (s < 1.0 && rv.abs() < 1e-4) {
            return true;
        }
        let nh = (n.dot(l) + n.dot(v)) / (2.0 + 2.0 * l.dot(v)).max(1e-300).sqrt();
        if s < 1.0 && nh.abs() < 1e-4 {
            return true;
        }
    }
    false
}

/// Batch (forced to each supported level) against scalar `shade`, point by point.
fn check<M: BatchModel, L: BatchLight>(
    what: &str,
    model: &M,
    pow: PowStrategy,
    m: &Material,
    scene: &Scene<'_, L>,
    b: &Batch,
) {
    let s = m.shininess();
    for level in Level::supported() {
        let out = run(level, model, m, scene, b);
        for (i, (&p, &n)) in b.p.iter().zip(&b.n).enumerate() {
            let got = out[i];
            assert!(
                got.is_finite() && got.min_element() >= 0.0,
                "{what} at {level}: point {i} ({p}, {n}) gave {got}"
            );
            if near_edge(scene, s, p, n) {
                continue;
            }
            let want = phong::shade(model, m, scene, p, n).total();
            let bound = light_bound(m, scene, p);
            let tol = bound * (2e-6 * s.max(1.0) + pow_bound(pow) + 1e-5) + want.abs() * 1e-6;
            assert!(
                (got - want).abs().cmple(tol).all(),
                "{what} at {level}: point {i} (p = {p}, n = {n}): batch {got} vs scalar {want}, \
                 tolerance {tol}"
            );
        }
    }
}

fn colors(rng: &mut Rng) -> LightColors {
    LightColors::try_new(rng.vec(0.0, 0.3), rng.vec(0.0, 1.0), rng.vec(0.0, 1.0)).unwrap()
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
    let p = (0..len).map(|_| rng.vec(-3.0, 3.0)).collect();
    let n = (0..len)
        .map(|_| rng.vec(-1.0, 1.0) * rng.range(0.01, 100.0))
        .collect();
    Batch { p, n }
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
        let q = rng.vec(-2.0, 2.0);
        push(q, Vec3::ZERO); // zero normal
        push(light, rng.vec(-1.0, 1.0)); // light at the point
        push(eye, rng.vec(-1.0, 1.0)); // viewer at the point
        // Grazing: the normal perpendicular to L.
        let l = (light - q).normalize();
        let t = l.any_orthonormal_vector();
        push(q, t);
        push(q, t + l * 1e-7);
        // Huge and tiny coordinates and normals.
        push(q * 1e20, rng.vec(-1.0, 1.0));
        push(q * 3e38, rng.vec(-1.0, 1.0));
        push(q, rng.vec(-1.0, 1.0) * 1e-20);
        push(q, rng.vec(-1.0, 1.0) * 1e-40);
        push(q, rng.vec(-1.0, 1.0) * 1e25);
        push(q * 1e-30, rng.vec(-1.0, 1.0));
        // Ordinary neighbours in the same chunk.
        push(q, rng.vec(-1.0, 1.0));
    }
    // L = −V: points on the segment between the light and the eye.
    for k in 1..20 {
        let t = k as f32 / 20.0;
        let q = light + (eye - light) * t;
        push(q, rng.vec(-1.0, 1.0));
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

#[test]
fn every_level_agrees_with_scalar_on_random_input() {
    let mut rng = Rng(1);
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
    for pow in [PowStrategy::Auto, PowStrategy::Exact, PowStrategy::Poly5] {
        for s in [0.0f32, 0.5, 1.0, 20.5, 32.0, 128.0] {
            let m = Material::try_new(rng.vec(0.0, 1.0), rng.vec(0.0, 1.0), rng.vec(0.0, 1.0), s)
                .unwrap()
                .try_with_emission(Vec3::splat(0.01))
                .unwrap();
            for (name, model) in models(pow) {
                check(&format!("{name} s={s}"), &model, pow, &m, &scene, &b);
            }
        }
    }
}

#[test]
fn concrete_model_types_match_the_enum() {
    let mut rng = Rng(2);
    let b = random_batch(&mut rng, 100);
    let lights = [point_light(&mut rng, Vec3::new(0.0, 2.0, 1.0))];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
    };
    let m = Material::try_from_color(Vec3::new(0.8, 0.4, 0.2), 20.5).unwrap();
    let pow = PowStrategy::Auto;
    check(
        "phong",
        &Phong {
            pow,
            ..Phong::default()
        },
        pow,
        &m,
        &scene,
        &b,
    );
    check(
        "blinn",
        &BlinnPhong {
            pow,
            ..BlinnPhong::default()
        },
        pow,
        &m,
        &scene,
        &b,
    );
    check("lambert", &Lambert::default(), pow, &m, &scene, &b);
}

#[test]
fn every_level_agrees_with_scalar_on_adversarial_input() {
    let mut rng = Rng(3);
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
            check(
                &format!("adversarial {name} s={s}"),
                &model,
                PowStrategy::Auto,
                &m,
                &scene,
                &b,
            );
        }
    }
}

#[test]
fn degenerate_points_have_the_documented_results() {
    let mut rng = Rng(4);
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
    let mut rng = Rng(5);
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
        check(
            &format!("3 lights, {viewer:?}"),
            &blinn,
            pow,
            &m,
            &scene,
            &b,
        );
    }
    for k in 0..9 {
        lights.push(point_light(&mut rng, Vec3::new(k as f32 - 4.0, 3.0, 1.0)).into());
    }
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    check("12 lights", &blinn, pow, &m, &scene, &b);
    // A spot light and another attenuation form: the whole batch takes the scalar path.
    lights.push(
        SpotLight::try_new(
            Vec3::new(0.0, 5.0, 0.0),
            -Vec3::Y,
            0.6,
            2.0,
            Attenuation::None,
            colors(&mut rng),
        )
        .unwrap()
        .into(),
    );
    lights.push(
        PointLight::try_new(
            Vec3::new(2.0, 2.0, 2.0),
            Attenuation::try_inverse_square(3.0).unwrap(),
            colors(&mut rng),
        )
        .unwrap()
        .into(),
    );
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    for level in Level::supported() {
        let out = run(level, &blinn, &m, &scene, &b);
        for (i, o) in out.iter().enumerate() {
            let want = phong::shade(&blinn, &m, &scene, b.p[i], b.n[i]).total();
            assert_eq!(*o, want, "{level}: scalar fallback, point {i}");
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
    for level in Level::ALL {
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
    let mut rng = Rng(6);
    let b = Batch {
        p: (0..len).map(|_| rng.vec(-2.0, 2.0)).collect(),
        n: (0..len).map(|_| rng.vec(-1.0, 1.0)).collect(),
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
