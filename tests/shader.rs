//! The prepared per-point path: `Shader`, visibility (shadows), per-point surfaces, `Terms` algebra,
//! and the generic path for models defined outside the crate.

use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Incidence, Lambert, Light, LightColors, Material,
    Model, Normalization, Phong, PointLight, PowStrategy, ReflectionModel, Scene, Shader,
    SpecularGate, Surface, Terms, Unshadowed, Viewer, VisibilityFn,
};
use proptest::prelude::*;

/// One f32 rounding, relative.
const U: f32 = f32::EPSILON / 2.0;

/// Below `f32::MIN_POSITIVE` a rounding is absolute, at most half the subnormal spacing (`2⁻¹⁴⁹`):
/// allow one subnormal spacing per rounding in the bounds below.
fn subnormal(roundings: f32) -> Vec3 {
    Vec3::splat(roundings * f32::from_bits(1))
}

fn lights() -> [Light; 3] {
    let c = |a: f32, d: f32, s: f32| {
        LightColors::try_new(
            Vec3::splat(a),
            Vec3::new(d, 0.8 * d, 0.6 * d),
            Vec3::splat(s),
        )
        .unwrap()
    };
    [
        PointLight::try_new(
            Vec3::new(2.0, 3.0, 1.0),
            Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
            c(0.1, 1.0, 0.7),
        )
        .unwrap()
        .into(),
        DirectionalLight::try_new(Vec3::new(-1.0, 2.0, 0.5), c(0.05, 0.6, 0.4))
            .unwrap()
            .into(),
        PointLight::try_new(
            Vec3::new(-1.0, 0.5, 3.0),
            Attenuation::try_frostbite(8.0).unwrap(),
            c(0.02, 2.0, 1.5),
        )
        .unwrap()
        .into(),
    ]
}

/// Whether `model` evaluates its lobe with `PowStrategy::Auto`.
fn uses_auto(model: &Model) -> bool {
    match model {
        Model::Phong(m) => m.pow == PowStrategy::Auto,
        Model::BlinnPhong(m) => m.pow == PowStrategy::Auto,
        _ => false,
    }
}

fn models() -> Vec<Model> {
    let mut v = vec![Model::Lambert(Lambert::default())];
    for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
        for normalization in [Normalization::None, Normalization::Energy] {
            for pow in [PowStrategy::Exact, PowStrategy::Auto, PowStrategy::Poly7] {
                v.push(Model::Phong(Phong {
                    gate,
                    normalization,
                    pow,
                }));
                v.push(Model::BlinnPhong(BlinnPhong {
                    gate,
                    normalization,
                    pow,
                }));
            }
        }
    }
    v
}

fn material() -> Material {
    Material::try_new(
        Vec3::new(0.2, 0.1, 0.1),
        Vec3::new(0.8, 0.4, 0.3),
        Vec3::splat(0.6),
        24.0,
    )
    .unwrap()
    .try_with_emission(Vec3::new(0.01, 0.0, 0.02))
    .unwrap()
}

fn points() -> Vec<(Vec3, Vec3)> {
    let mut v = Vec::new();
    for i in 0..40 {
        let t = i as f32 * 0.37;
        let p = Vec3::new(t.sin() * 2.0, (t * 1.3).cos(), (t * 0.7).sin() * 1.5);
        let n = Vec3::new((t * 2.1).cos(), (t * 0.9).sin() + 0.3, (t * 1.7).cos());
        v.push((p, n));
    }
    v
}

#[test]
fn shade_is_the_prepared_shader_and_full_visibility_changes_nothing() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.03),
        viewer: Viewer::At(Vec3::new(0.0, 1.0, 5.0)),
    };
    for model in models() {
        let shader = Shader::new(model, &m, &scene);
        for (p, n) in points() {
            let a = phong::shade(&model, &m, &scene, p, n);
            assert_eq!(shader.shade(p, n), a, "{model:?}");
            assert_eq!(shader.shade_visible(p, n, [1.0; 3]), a);
            assert_eq!(shader.shade_visible(p, n, Unshadowed), a);
            // The material's own reflectances as a per-point surface: the same computation, but
            // for `Auto`'s power, which is Poly7 for a point's own exponent and squaring for the
            // material's whole 24.
            let t = shader.shade_surface(p, n, &Surface::of(&m), [1.0; 3]);
            if !uses_auto(&model) {
                assert_eq!(t, a, "{model:?}");
                continue;
            }
            assert_eq!(
                (t.ambient, t.diffuse, t.emission),
                (a.ambient, a.diffuse, a.emission)
            );
            // Each light's lobe moves by at most e·max(lobe, ERROR_FLOOR) with e the two
            // strategies' bounds together; the same products and sums follow (a few roundings,
            // 4U, relative). The floor's part is at most e·floor times Ks·scale·ΣLs·f < 0.6 ·
            // 4.2 · 2.6 · 1 < 7 here (Energy's Phong scale (s + 2)/2π at s = 24, the lights'
            // specular colours, attenuation ≤ 1).
            let e = PowStrategy::Poly7.max_relative_error()
                + PowStrategy::Squaring.max_relative_error();
            let tol =
                a.specular.abs() * (e + 4.0 * U) + Vec3::splat(7.0 * e * PowStrategy::ERROR_FLOOR);
            assert!(
                (t.specular - a.specular).abs().cmple(tol).all(),
                "{model:?} at {p}, {n}: {} against {}",
                t.specular,
                a.specular
            );
        }
    }
}

/// A scene with one directional or point light takes the straight-line one-light path (written so
/// the compiler can vectorise a loop over points); `phong::shade` and `Shader::one_at_a_time`
/// take the general light loop.
/// They are the same computation: every model, falloff, viewer, visibility and per-point surface
/// gives the same bits.
#[test]
fn the_one_light_path_is_the_light_loop_bit_for_bit() {
    let colors =
        LightColors::try_new(Vec3::splat(0.1), Vec3::new(1.0, 0.8, 0.6), Vec3::splat(0.7)).unwrap();
    let at = Vec3::new(2.0, 3.0, 1.0);
    let mut singles: Vec<Light> = [
        Attenuation::None,
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        Attenuation::try_inverse_square(3.0).unwrap(),
        Attenuation::try_unreal(4.0).unwrap(),
        Attenuation::try_frostbite(4.0).unwrap(),
    ]
    .into_iter()
    .map(|a| PointLight::try_new(at, a, colors).unwrap().into())
    .collect();
    singles.push(
        DirectionalLight::try_new(Vec3::new(-1.0, 2.0, 0.5), colors)
            .unwrap()
            .into(),
    );
    let m = material();
    let texel = Surface::textured(Vec3::new(0.5, 0.25, 0.1), Vec3::splat(0.4), 37.5);
    for light in singles {
        for viewer in [
            Viewer::At(Vec3::new(0.0, 1.0, 5.0)),
            Viewer::Infinite(Vec3::new(0.3, 0.2, 1.0)),
        ] {
            let scene = Scene {
                lights: core::slice::from_ref(&light),
                ambient: Vec3::splat(0.03),
                viewer,
            };
            for model in models() {
                let shader = Shader::new(model, &m, &scene);
                // Beyond the light loop's narrower range for Phong's squared base (squared lengths
                // in [2⁻²⁵, 2²⁵]): a far point, a long and a short normal, a point next to the
                // light; there it scales them as the one-light path does.
                let near = Vec3::new(0.3, 0.1, 0.2);
                for (p, n) in points().into_iter().chain([
                    (at, Vec3::Z),
                    (Vec3::ZERO, Vec3::ZERO),
                    (
                        Vec3::new(9000.0, -4000.0, 7000.0),
                        Vec3::new(-0.6, 0.2, -0.7),
                    ),
                    (near, Vec3::new(0.1, 1.0, 0.3) * 1e4),
                    (near, Vec3::new(0.1, 1.0, 0.3) * 1e-4),
                    (at - Vec3::new(1e-5, 2e-5, 3e-5), Vec3::new(0.2, 0.3, 1.0)),
                ]) {
                    let what = format!("{model:?} {light:?} {viewer:?} at {p}, {n}");
                    assert_eq!(
                        shader.shade(p, n),
                        phong::shade(&model, &m, &scene, p, n),
                        "{what}"
                    );
                    // The general loop again, through a scene of two lights whose second adds 0.
                    let dark =
                        PointLight::try_new(at, Attenuation::None, LightColors::BLACK).unwrap();
                    let two = [light, dark.into()];
                    let general = Shader::new(
                        model,
                        &m,
                        &Scene {
                            lights: &two,
                            ..scene
                        },
                    );
                    assert_eq!(
                        shader.shade_visible(p, n, [0.25]),
                        general.shade_visible(p, n, [0.25, 1.0]),
                        "{what}"
                    );
                    assert_eq!(
                        shader.shade_surface(p, n, &texel, [0.5]),
                        general.shade_surface(p, n, &texel, [0.5, 1.0]),
                        "{what}"
                    );
                    // The one-at-a-time form of the same shader is the light loop too.
                    let lone = shader.one_at_a_time();
                    assert_eq!(lone.shade(p, n), shader.shade(p, n), "{what}");
                    assert_eq!(
                        lone.shade_surface(p, n, &texel, [0.5]),
                        shader.shade_surface(p, n, &texel, [0.5]),
                        "{what}"
                    );
                    // A shadowed light: the light loop skips its power, the one-light form
                    // evaluates it and multiplies it by 0. The same bits either way.
                    for surface in [Surface::of(&m), texel] {
                        let one = shader.shade_surface(p, n, &surface, [0.0]);
                        assert_eq!(lone.shade_surface(p, n, &surface, [0.0]), one, "{what}");
                        assert_eq!(
                            general.shade_surface(p, n, &surface, [0.0, 1.0]),
                            one,
                            "{what}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn a_shadowed_light_keeps_its_ambient_part_only() {
    let (lights, m) = (lights(), material());
    for model in models() {
        for k in 0..3 {
            let all = Scene {
                lights: &lights,
                ambient: Vec3::ZERO,
                viewer: Viewer::Infinite(Vec3::new(0.2, 0.3, 1.0)),
            };
            let others: Vec<Light> = (0..3).filter(|&j| j != k).map(|j| lights[j]).collect();
            let rest = Scene {
                lights: &others,
                ..all
            };
            let mut vis = [1.0; 3];
            vis[k] = 0.0;
            for (p, n) in points() {
                let shadowed = Shader::new(model, &m, &all).shade_visible(p, n, vis);
                let without = Shader::new(model, &m, &rest).shade(p, n);
                let full = Shader::new(model, &m, &all).shade(p, n);
                // Diffuse and specular: the same sums without light k's term, except that an
                // added 0 can change the summation order's rounding by at most 2U of the sum.
                for (a, b) in [
                    (shadowed.diffuse, without.diffuse),
                    (shadowed.specular, without.specular),
                ] {
                    assert!(
                        (a - b).abs().cmple(b * 2.0 * U + subnormal(2.0)).all(),
                        "{model:?} light {k}: {a} vs {b}"
                    );
                }
                // Ambient: a shadow does not touch it.
                assert_eq!(shadowed.ambient, full.ambient);
                assert_eq!(shadowed.emission, m.emission());
            }
        }
    }
}

#[test]
fn visibility_scales_diffuse_and_specular_linearly() {
    let sun = DirectionalLight::try_new(
        Vec3::new(0.3, 0.2, 1.0),
        LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[sun],
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let m = material();
    let shader = Shader::new(Phong::default(), &m, &scene);
    for (p, n) in points() {
        let full = shader.shade(p, n);
        for vis in [0.0f32, 0.25, 0.5, 0.9] {
            let t = shader.shade_visible(p, n, [vis]);
            // Both sides are the exact product f·vis·w·L·K after four roundings each (the shader
            // rounds f·vis, ·w, ·L, ·K; the test rounds f·w, ·L, ·K and then ·vis): ≤ 8U apart.
            for (a, b) in [(t.diffuse, full.diffuse), (t.specular, full.specular)] {
                let want = b * vis;
                assert!(
                    (a - want)
                        .abs()
                        .cmple(want * 8.0 * U + subnormal(8.0))
                        .all(),
                    "vis {vis}: {a} vs {want}"
                );
            }
            assert_eq!(t.ambient, full.ambient);
        }
    }
}

#[test]
fn visibility_closure_is_asked_once_per_light_in_order() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 4.0)),
    };
    let shader = Shader::new(BlinnPhong::default(), &m, &scene);
    let mut asked = Vec::new();
    let t = shader.shade_visible(
        Vec3::ZERO,
        Vec3::Z,
        VisibilityFn(|i| {
            asked.push(i);
            [1.0, 0.0, 0.5][i]
        }),
    );
    assert_eq!(asked, [0, 1, 2]);
    assert_eq!(
        t,
        shader.shade_visible(Vec3::ZERO, Vec3::Z, [1.0, 0.0, 0.5])
    );
}

/// Release builds read visibilities outside [0, 1] clamped, and NaN as 0 (debug builds assert).
#[cfg(not(debug_assertions))]
#[test]
fn out_of_range_visibility_is_clamped_in_release() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 4.0)),
    };
    let shader = Shader::new(Phong::default(), &m, &scene);
    let (p, n) = (Vec3::ZERO, Vec3::new(0.1, 0.3, 1.0));
    assert_eq!(
        shader.shade_visible(p, n, [f32::NAN, -3.0, 7.0]),
        shader.shade_visible(p, n, [0.0, 0.0, 1.0])
    );
}

#[test]
fn a_per_point_surface_replaces_the_reflectances_and_keeps_the_emission() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.02),
        viewer: Viewer::At(Vec3::new(1.0, 1.0, 4.0)),
    };
    let texel = Surface {
        ambient: Vec3::new(0.1, 0.2, 0.3),
        diffuse: Vec3::new(0.5, 0.6, 0.7),
        specular: Vec3::new(0.9, 0.1, 0.4),
        shininess: 37.25,
    };
    let as_material = Material::try_new(texel.ambient, texel.diffuse, texel.specular, 37.25)
        .unwrap()
        .try_with_emission(m.emission())
        .unwrap();
    // Phong under `Auto` evaluates a point's own exponent on the squared base `(R·V)²` from the
    // vectors before normalisation, and the material's on `R·V` from the unit vectors: the same
    // lobe by two roundings. Each `R·V` is within 8 roundings (`8·U`, absolute: three
    // normalisations and the dot products of unit vectors) of the exact one, which `x^s`
    // turns into at most `s·8·U` absolutely (its slope is at most `s` on [0, 1]), plus `Poly7`'s
    // own error on each side (below `32·U` relatively, docs/accuracy.md). Each light adds
    // `f·Ls·ks` times that; here `f ≤ 1` and `Σ Ls = 0.7 + 0.4 + 1.5`.
    let tolerance = |ks: f32| ks * 2.6 * (2.0 * 8.0 * 37.25 + 2.0 * 32.0) * U;
    for model in models() {
        for (p, n) in points() {
            let a = Shader::new(model, &m, &scene).shade_surface(p, n, &texel, Unshadowed);
            let b = Shader::new(model, &as_material, &scene).shade(p, n);
            if matches!(model, Model::Phong(_)) && uses_auto(&model) {
                assert_eq!(
                    (a.ambient, a.diffuse, a.emission),
                    (b.ambient, b.diffuse, b.emission),
                    "{model:?}"
                );
                for ((x, y), ks) in a
                    .specular
                    .to_array()
                    .into_iter()
                    .zip(b.specular.to_array())
                    .zip(texel.specular.to_array())
                {
                    assert!((x - y).abs() <= tolerance(ks), "{model:?}: {x} vs {y}");
                }
            } else {
                assert_eq!(a, b, "{model:?}");
            }
        }
    }
    // Occlusion scales the ambient term only.
    let open = Shader::new(Phong::default(), &m, &scene).shade_surface(
        Vec3::ZERO,
        Vec3::Z,
        &texel,
        Unshadowed,
    );
    let half = Shader::new(Phong::default(), &m, &scene).shade_surface(
        Vec3::ZERO,
        Vec3::Z,
        &texel.with_occlusion(0.5),
        Unshadowed,
    );
    assert_eq!(half.diffuse, open.diffuse);
    assert_eq!(half.specular, open.specular);
    assert!(
        (half.ambient - open.ambient * 0.5)
            .abs()
            .cmple(open.ambient * 2.0 * U + subnormal(2.0))
            .all()
    );
}

/// Release builds sanitise a bad surface by the rule of `Material::new` (debug builds assert).
#[cfg(not(debug_assertions))]
#[test]
fn a_bad_surface_is_sanitised_in_release() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 4.0)),
    };
    let shader = Shader::new(BlinnPhong::default(), &m, &scene);
    let bad = Surface {
        ambient: Vec3::new(f32::NAN, -1.0, 0.5),
        diffuse: Vec3::new(f32::INFINITY, 0.3, -0.0),
        specular: Vec3::new(0.2, f32::NAN, 1.0),
        shininess: f32::NAN,
    };
    let good = Surface {
        ambient: Vec3::new(0.0, 0.0, 0.5),
        diffuse: Vec3::new(f32::MAX, 0.3, 0.0),
        specular: Vec3::new(0.2, 0.0, 1.0),
        shininess: 0.0,
    };
    for (p, n) in points() {
        let a = shader.shade_surface(p, n, &bad, Unshadowed);
        assert_eq!(a, shader.shade_surface(p, n, &good, Unshadowed));
        assert!(!a.total().is_nan());
    }
}

#[test]
fn incidence_is_what_shade_uses() {
    let (lights, m) = (lights(), material());
    let eye = Vec3::new(0.5, 2.0, 3.0);
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(eye),
    };
    let shader = Shader::new(Phong::default(), &m, &scene);
    for (p, n) in points() {
        for (k, light) in lights.iter().enumerate() {
            let (g, f) = shader.incidence(p, n, k).unwrap();
            let s = phong::LightSource::sample(light, p);
            let want = Incidence::new(
                phong::normalize_or_zero(n),
                s.direction,
                phong::normalize_or_zero(eye - p),
            );
            assert_eq!((g, f), (want, s.factor));
        }
        assert!(shader.incidence(p, n, 3).is_none());
    }
}

/// A model defined outside the crate: Phong's lobes through the trait only, without `resolve`.
struct External(Phong);

impl ReflectionModel for External {
    fn diffuse(&self, g: &Incidence) -> f32 {
        self.0.diffuse(g)
    }
    fn specular(&self, g: &Incidence, s: f32) -> f32 {
        self.0.specular(g, s)
    }
}

#[test]
fn a_model_from_outside_the_crate_shades_like_the_built_in_one() {
    let (lights, m) = (lights(), material());
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.01),
        viewer: Viewer::At(Vec3::new(0.0, 1.0, 4.0)),
    };
    for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
        let builtin = Phong {
            gate,
            ..Phong::default()
        };
        let ext = Shader::new(External(builtin), &m, &scene);
        let own = Shader::new(builtin, &m, &scene);
        for (p, n) in points() {
            let (a, b) = (ext.shade(p, n), own.shade(p, n));
            // The trait path forms R·V from the same cosines and clamps it the same way: the only
            // difference is where powf's argument is clamped, within a few roundings of each term.
            for (x, y) in [(a.diffuse, b.diffuse), (a.specular, b.specular)] {
                assert!(
                    (x - y).abs().cmple(y * 8.0 * U + subnormal(8.0)).all(),
                    "{gate:?}: {x} vs {y}"
                );
            }
            assert_eq!(a.ambient, b.ambient);
        }
    }
}

#[test]
fn terms_add_and_scale_channel_by_channel_and_saturate() {
    let a = Terms {
        ambient: Vec3::splat(1.0),
        diffuse: Vec3::new(2.0, 3.0, 4.0),
        specular: Vec3::splat(f32::MAX),
        emission: Vec3::ZERO,
    };
    let s = a + a;
    assert_eq!(s.diffuse, Vec3::new(4.0, 6.0, 8.0));
    assert_eq!(s.specular, Vec3::splat(f32::MAX));
    let mut t = a;
    t += a;
    assert_eq!(t, s);
    assert_eq!((a * 0.5).diffuse, Vec3::new(1.0, 1.5, 2.0));
    assert_eq!((a * f32::NAN).diffuse, Vec3::ZERO);
    assert_eq!((a * -2.0).ambient, Vec3::ZERO);
    assert_eq!((a * 4.0).specular, Vec3::splat(f32::MAX));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Shading with visibilities is the sum of one-light shadings, each scaled by its visibility:
    /// contributions add linearly and a shadow scales one light's diffuse and specular parts.
    #[test]
    fn shadowed_shading_is_the_visibility_weighted_sum_of_lights(
        v in proptest::array::uniform3(0.0f32..=1.0),
        px in -3.0f32..3.0, py in -3.0f32..3.0, pz in -3.0f32..3.0,
        nx in -1.0f32..1.0, ny in -1.0f32..1.0, nz in 0.1f32..1.0,
        which in 0usize..25,
    ) {
        let (lights, m) = (lights(), material());
        let model = models()[which % models().len()];
        let viewer = Viewer::At(Vec3::new(0.0, 1.0, 5.0));
        let (p, n) = (Vec3::new(px, py, pz), Vec3::new(nx, ny, nz));
        let all = Scene { lights: &lights, ambient: Vec3::ZERO, viewer };
        let got = Shader::new(model, &m, &all).shade_visible(p, n, v);
        let mut want = Vec3::ZERO;
        let mut mag = Vec3::ZERO;
        for k in 0..3 {
            let one = Scene { lights: &lights[k..k + 1], ..all };
            let t = Shader::new(model, &m, &one).shade(p, n);
            want += (t.diffuse + t.specular) * v[k];
            mag += t.diffuse + t.specular;
        }
        // Each one-light term is rounded in a different order than the three-light sum: a few
        // roundings (≤ 8U) of the summed magnitudes, all terms being ≥ 0.
        let got = got.diffuse + got.specular;
        prop_assert!((got - want).abs().cmple(mag * 8.0 * U + subnormal(8.0)).all(),
            "{model:?}: {got} vs {want}");
    }
}

/// Found by tests/fuzz_promises.rs while the shader learnt to skip saturation when nothing can
/// overflow: two ambient colours whose sum passes `f32::MAX`, under an ambient reflectance so
/// small that `Ka ⊙ Σ La` would look harmless. The sum must still saturate first (the equation's
/// rule), giving a finite ambient term, not +∞.
#[test]
fn an_overflowing_light_sum_under_a_tiny_reflectance_saturates() {
    let colors = |a: f32| {
        phong::LightColors::try_new(Vec3::new(0.0, 0.0, a), Vec3::splat(0.5), Vec3::splat(0.5))
            .unwrap()
    };
    let lights = [
        phong::DirectionalLight::try_new(Vec3::X, colors(1.02638766e37)).unwrap(),
        phong::DirectionalLight::try_new(Vec3::Y, colors(f32::MAX)).unwrap(),
    ];
    let m =
        phong::Material::try_new(Vec3::splat(4.1537027e-28), Vec3::ONE, Vec3::ONE, 8.0).unwrap();
    let scene = phong::Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: phong::Viewer::Infinite(Vec3::Z),
    };
    let t = phong::Shader::new(phong::Phong::default(), &m, &scene).shade(Vec3::ZERO, Vec3::Z);
    assert!(t.ambient.is_finite(), "{t:?}");
    // sat(Σ La) = f32::MAX, times Ka: the saturation rule's value, to the product's rounding.
    let want = f32::MAX * 4.1537027e-28;
    assert!(
        (t.ambient.z - want).abs() <= want * 2.0 * f32::EPSILON,
        "{t:?}"
    );
}

/// A light whose factor saturates at `f32::MAX` under a diffuse colour small enough that the light
/// sums' bounds stay below `f32::MAX / 4`: the sums cannot overflow, but the scalar weight
/// `f·vis·N·L` can, where `N·L` of two normalised vectors rounds above 1. The one-light form
/// keeps the weights' saturating `min`s even where the sums' bounds let it skip the products'
/// (a guard for any future skip of those `min`s: the test fails with +∞ without them), so it
/// stays the light loop, bit for bit, and finite.
#[test]
fn a_saturated_factor_under_a_dim_colour_keeps_its_weight_saturated() {
    let colors = LightColors::try_new(Vec3::ZERO, Vec3::splat(0.1), Vec3::splat(0.1)).unwrap();
    let m = Material::try_new(Vec3::ZERO, Vec3::splat(0.5), Vec3::splat(0.5), 8.0).unwrap();
    let p = Vec3::new(0.25, -0.5, 1.0);
    let mut above_one = 0;
    for i in 1..400 {
        let t = i as f32 * 0.173;
        let d = Vec3::new(t.sin() + 1.5, (t * 1.7).cos() + 1.5, (t * 0.3).sin() + 1.5);
        // 1e38 / (1e-3)² saturates: the factor at the point is f32::MAX.
        let at = p + d * 1e-3;
        let lamp = PointLight::try_new(at, Attenuation::try_inverse_square(1e38).unwrap(), colors)
            .unwrap();
        let (n, l) = (
            phong::normalize_or_zero(d),
            phong::normalize_or_zero(at - p),
        );
        if n.dot(l) > 1.0 {
            above_one += 1;
        }
        let lights = [lamp];
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer: Viewer::At(p + Vec3::Z),
        };
        for model in [
            Model::from(Phong::default()),
            Model::from(BlinnPhong::default()),
        ] {
            let shader = Shader::new(model, &m, &scene);
            let t = shader.shade(p, d);
            assert_eq!(t, shader.one_at_a_time().shade(p, d), "{model:?} d = {d}");
            assert!(t.total().is_finite(), "{model:?} d = {d}: {t:?}");
        }
    }
    // The case the test is about occurred.
    assert!(above_one > 0, "no direction had N·L > 1");
}

/// Phong's squared base for a point's own exponent where the normal, the offset to the light and
/// the offset to the viewer are all short (squared lengths near the light loop's lower bound for
/// keeping them unscaled, so their product `‖n‖⁴‖l‖²‖v‖²` is far below 1): the one-light form and
/// the light loop still agree bit for bit.
#[test]
fn short_vectors_keep_the_squared_base_bit_for_bit() {
    let colors = LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ONE).unwrap();
    let p = Vec3::new(0.25, -0.5, 0.75);
    let texel = Surface::textured(Vec3::splat(0.5), Vec3::ONE, 10.5);
    let m = material();
    let mut checked = 0;
    for k in [10, 12, 14, 15, 16, 17] {
        let s = 2f32.powi(-k);
        let light =
            PointLight::try_new(p + Vec3::new(0.3, 1.0, 0.2) * s, Attenuation::None, colors)
                .unwrap();
        let scene = Scene {
            lights: &[light],
            ambient: Vec3::ZERO,
            viewer: Viewer::At(p + Vec3::new(-0.2, 1.0, 0.1) * s),
        };
        let shader = Shader::new(Phong::default(), &m, &scene);
        for n in [Vec3::new(0.1, 1.0, 0.05), Vec3::new(-0.3, 1.0, 0.4)] {
            let n = n * s;
            let one = shader.shade_surface(p, n, &texel, Unshadowed);
            let lone = shader
                .one_at_a_time()
                .shade_surface(p, n, &texel, Unshadowed);
            assert_eq!(one, lone, "scale 2^-{k}, n = {n}");
            assert!(one.specular.x > 0.0, "scale 2^-{k}: a highlight to compare");
            checked += 1;
        }
    }
    assert_eq!(checked, 12);
}
