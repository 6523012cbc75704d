//! `shade_gbuffer`: per-point surfaces and per-light visibilities in the batch kernel, at every
//! dispatch level this machine runs, against the documented accuracy of the batch and against the
//! scalar `Shader::shade_surface`.
//!
//! **What is checked.** A point with surface `(Ka, Kd, Ks, s)` and visibilities `visⱼ` is, by the
//! equation, the same as the point under a material `(Ka, Kd, Ks, s)` (the call's emission kept)
//! and a scene whose light `j` has diffuse and specular colours `visⱼ·Ldⱼ`, `visⱼ·Lsⱼ` (ambient
//! unchanged). So each output must lie in that point's range from tools/src/batch_range.rs,
//! the one the plain batch is held to. The scalar `shade_surface` is checked against the same
//! range, and the 8-bit entry point against `linear_to_srgb8` of the `f32` one, bit for bit.

use phong_tools::batch_range;

use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, GBuffer, Lambert, Level, Light, LightColors,
    LightSource, Material, Model, Normalization, Phong, PointLight, PowStrategy, Scene, Shader,
    SoaRgb, SoaSurface, SoaTerms, SoaVec3, SpecularGate, SpotCone, SpotLight, Surface, TileCulling,
    Viewer, VisibilityFn,
};
use phong_tools::rng::Rng;

/// One point light's parameters, so the test can rebuild it with its colours scaled.
#[derive(Clone, Copy)]
struct Lamp {
    at: Vec3,
    attenuation: Attenuation,
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
}

impl Lamp {
    fn light(&self, vis: f32) -> PointLight {
        let colors =
            LightColors::try_new(self.ambient, self.diffuse * vis, self.specular * vis).unwrap();
        PointLight::try_new(self.at, self.attenuation, colors).unwrap()
    }
}

/// A G-buffer in array-of-structs form, with its SoA copy made per call.
#[derive(Clone)]
struct Points {
    p: Vec<Vec3>,
    n: Vec<Vec3>,
    ka: Vec<Vec3>,
    kd: Vec<Vec3>,
    ks: Vec<Vec3>,
    s: Vec<f32>,
    /// Light-major: `vis[j * len + i]`.
    vis: Vec<f32>,
}

fn split(v: &[Vec3]) -> [Vec<f32>; 3] {
    [
        v.iter().map(|a| a.x).collect(),
        v.iter().map(|a| a.y).collect(),
        v.iter().map(|a| a.z).collect(),
    ]
}

/// Random points around the lights, with textured surfaces: shininess uniform in `[2, 128]`
/// (fractional) in most lanes and whole in some (the two `Auto` forms side by side in one
/// vector), shadow factors that are mostly 0 or 1 and sometimes between (and 0 across every
/// fourth chunk of 16 points, a shadow map's dark region, where the kernel skips the light's
/// diffuse and specular parts), and a few degenerate points (zero normal, a point at a light,
/// the viewer's position) for the scalar path.
fn points(rng: &mut Rng, len: usize, lamps: &[Lamp], eye: Vec3) -> Points {
    let mut g = Points {
        p: vec![],
        n: vec![],
        ka: vec![],
        kd: vec![],
        ks: vec![],
        s: vec![],
        vis: vec![],
    };
    for i in 0..len {
        let p = match i % 37 {
            5 => lamps[0].at,
            11 => eye,
            _ => rng.vec3_in(-2.0, 2.0),
        };
        let n = if i % 41 == 7 {
            Vec3::ZERO
        } else {
            rng.vec3_in(-1.0, 1.0)
        };
        let texel = rng.vec3_in(0.0, 1.0);
        g.p.push(p);
        g.n.push(n);
        g.ka.push(texel * rng.unit_f32());
        g.kd.push(texel);
        g.ks.push(Vec3::splat(rng.unit_f32()));
        g.s.push(match i % 5 {
            0 => [1.0, 8.0, 32.0, 64.0, 100.0][(i / 5) % 5],
            _ => rng.range_f32(2.0, 128.0),
        });
    }
    for j in 0..lamps.len() {
        for i in 0..len {
            let u = rng.unit_f32();
            g.vis.push(if (i / 16 + j) % 4 == 1 {
                0.0
            } else if u < 0.4 {
                1.0
            } else if u < 0.6 {
                rng.unit_f32()
            } else {
                0.0
            });
        }
    }
    g
}

fn lamps(rng: &mut Rng, count: usize) -> Vec<Lamp> {
    (0..count)
        .map(|_| Lamp {
            at: rng.vec3_in(-3.0, 3.0),
            attenuation: Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
            ambient: Vec3::splat(0.05),
            diffuse: rng.vec3_in(0.2, 1.0),
            specular: Vec3::splat(rng.range_f32(0.2, 1.0)),
        })
        .collect()
}

fn models() -> Vec<(String, Model)> {
    let mut v: Vec<(String, Model)> = vec![("lambert".into(), Lambert::default().into())];
    for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
        for normalization in [Normalization::None, Normalization::Energy] {
            v.push((
                format!("phong {gate:?} {normalization:?}"),
                Phong {
                    gate,
                    normalization,
                    pow: PowStrategy::Auto,
                }
                .into(),
            ));
            v.push((
                format!("blinn {gate:?} {normalization:?}"),
                BlinnPhong {
                    gate,
                    normalization,
                    pow: PowStrategy::Auto,
                }
                .into(),
            ));
        }
    }
    v
}

/// The points' vectors as the G-buffer's `f32` slices.
struct Split {
    p: [Vec<f32>; 3],
    n: [Vec<f32>; 3],
    ka: [Vec<f32>; 3],
    kd: [Vec<f32>; 3],
    ks: [Vec<f32>; 3],
}

impl Split {
    fn new(g: &Points) -> Self {
        Split {
            p: split(&g.p),
            n: split(&g.n),
            ka: split(&g.ka),
            kd: split(&g.kd),
            ks: split(&g.ks),
        }
    }

    /// The G-buffer of `g`'s positions and normals, with its surfaces and visibilities if asked.
    fn gbuffer<'a>(&'a self, g: &'a Points, with_surface: bool, with_vis: bool) -> GBuffer<'a> {
        let v3 = |a: &'a [Vec<f32>; 3]| SoaVec3::new(&a[0], &a[1], &a[2]);
        let mut buffer = GBuffer::new(v3(&self.p), v3(&self.n));
        if with_surface {
            buffer = buffer.with_surface(SoaSurface {
                ambient: v3(&self.ka),
                diffuse: v3(&self.kd),
                specular: v3(&self.ks),
                shininess: &g.s,
            });
        }
        if with_vis {
            buffer = buffer.with_visibility(&g.vis);
        }
        buffer
    }
}

/// `shade_gbuffer` at `level`, every point's colour.
fn run(
    level: Level,
    model: &Model,
    base: &Material,
    scene: &Scene<'_, PointLight>,
    g: &Points,
    with_surface: bool,
    with_vis: bool,
) -> Vec<Vec3> {
    let len = g.p.len();
    let sp = Split::new(g);
    let buffer = sp.gbuffer(g, with_surface, with_vis);
    let (mut r, mut gr, mut b) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
    let shaded = phong::shade_gbuffer_with_level(
        level,
        model,
        base,
        scene,
        &buffer,
        SoaRgb::new(&mut r, &mut gr, &mut b),
    )
    .expect("a supported level");
    assert_eq!(shaded, len);
    (0..len).map(|i| Vec3::new(r[i], gr[i], b[i])).collect()
}

/// `a[i]` and `b[i]` are the same bits at every listed point.
fn assert_same_bits(what: &str, a: &[Vec3], b: &[Vec3], points: impl Iterator<Item = usize>) {
    for i in points {
        assert_eq!(
            a[i].to_array().map(f32::to_bits),
            b[i].to_array().map(f32::to_bits),
            "{what}: point {i}: {} vs {}",
            a[i],
            b[i]
        );
    }
}

/// The equation tests' inputs from `seed`: `lights` lamps, 203 points around them seen from
/// `eye`, the base material (with an emission) and the lamps as unshadowed point lights.
fn setup(seed: u64, lights: usize, eye: Vec3) -> (Vec<Lamp>, Points, Material, Vec<PointLight>) {
    let mut rng = Rng::new(seed);
    let lamps = lamps(&mut rng, lights);
    let g = points(&mut rng, 203, &lamps, eye);
    let base = Material::try_new(Vec3::splat(0.2), Vec3::splat(0.6), Vec3::splat(0.4), 24.0)
        .unwrap()
        .try_with_emission(Vec3::splat(0.01))
        .unwrap();
    let plain = lamps.iter().map(|l| l.light(1.0)).collect();
    (lamps, g, base, plain)
}

/// The equation tests' scene: `lights`, a small scene ambient, the viewer at `eye`.
fn scene_at(lights: &[PointLight], eye: Vec3) -> Scene<'_, PointLight> {
    Scene {
        lights,
        ambient: Vec3::splat(0.02),
        viewer: Viewer::At(eye),
    }
}

/// Every level, with and without each per-point input, against the range of the equivalent
/// material and scene, and the scalar `shade_surface` against the same range.
fn check(seed: u64, lights: usize, eye: Vec3) {
    let (lamps, g, base, plain) = setup(seed, lights, eye);
    let len = g.p.len();
    let scene = scene_at(&plain, eye);
    for (name, model) in models() {
        for (with_surface, with_vis) in [(true, true), (true, false), (false, true)] {
            // The equivalent material and scene of point i.
            let equivalent = |i: usize| {
                let m = if with_surface {
                    Material::try_new(g.ka[i], g.kd[i], g.ks[i], g.s[i])
                        .unwrap()
                        .try_with_emission(base.emission())
                        .unwrap()
                } else {
                    base
                };
                let lights: Vec<PointLight> = lamps
                    .iter()
                    .enumerate()
                    .map(|(j, l)| l.light(if with_vis { g.vis[j * len + i] } else { 1.0 }))
                    .collect();
                (m, lights)
            };
            let shader = Shader::new(model, &base, &scene);
            let ranges: Vec<batch_range::Range> = (0..len)
                .map(|i| {
                    let (m, lights) = equivalent(i);
                    let s = Scene {
                        lights: &lights,
                        ..scene
                    };
                    batch_range::range(&model, &m, &s, g.p[i], g.n[i])
                })
                .collect();
            for (i, r) in ranges.iter().enumerate() {
                let surface = if with_surface {
                    Surface {
                        ambient: g.ka[i],
                        diffuse: g.kd[i],
                        specular: g.ks[i],
                        shininess: g.s[i],
                    }
                } else {
                    Surface::of(&base)
                };
                let vis = VisibilityFn(|j| if with_vis { g.vis[j * len + i] } else { 1.0 });
                let want = shader.shade_surface(g.p[i], g.n[i], &surface, vis).total();
                assert!(
                    r.holds(want),
                    "{name}: shade_surface at point {i} gave {want}, outside [{}, {}]",
                    r.lo,
                    r.hi
                );
            }
            for level in Level::supported() {
                let out = run(level, &model, &base, &scene, &g, with_surface, with_vis);
                for (i, r) in ranges.iter().enumerate() {
                    assert!(
                        r.holds(out[i]),
                        "{name} at {level} (surface {with_surface}, visibility {with_vis}): \
                         point {i} (p = {}, n = {}, s = {}) gave {}, outside [{}, {}]",
                        g.p[i],
                        g.n[i],
                        g.s[i],
                        out[i],
                        r.lo,
                        r.hi
                    );
                }
            }
        }
    }
}

#[test]
fn every_level_agrees_with_the_equation_for_one_light() {
    check(0x9b1f, 1, Vec3::new(0.0, 1.0, 5.0));
}

#[test]
fn every_level_agrees_with_the_equation_for_three_lights() {
    check(0x5eed_0003, 3, Vec3::new(1.0, -2.0, 4.0));
}

/// Where a light's visibility is 0 at every point of a chunk, the kernel adds its ambient part
/// and skips the rest: bit for bit the same light with black diffuse and specular colours and
/// visibility 1 there, at every level, with and without a per-point surface (and so folded
/// and not). The points' first light is dark over chunks 2–5 (points 32–95).
#[test]
fn a_light_dark_over_whole_chunks_adds_its_ambient_part_alone() {
    let eye = Vec3::new(0.0, 1.0, 5.0);
    let (lamps, mut dark, base, plain) = setup(0x5adc, 2, eye);
    let chunks = 32..96;
    for i in chunks.clone() {
        dark.vis[i] = 0.0;
    }
    let mut lit = dark.clone();
    for i in chunks.clone() {
        lit.vis[i] = 1.0;
    }
    let black = [lamps[0].light(0.0), plain[1]];
    let (scene, black_scene) = (scene_at(&plain, eye), scene_at(&black, eye));
    for (name, model) in models() {
        for with_surface in [true, false] {
            for level in Level::supported() {
                let a = run(level, &model, &base, &scene, &dark, with_surface, true);
                let b = run(level, &model, &base, &black_scene, &lit, with_surface, true);
                let what = format!("{name} at {level} (surface {with_surface})");
                assert_same_bits(&what, &a, &b, chunks.clone());
            }
        }
    }
}

/// A light behind the surface at every point of a chunk (N·L ≤ 0 in all 16 lanes) adds its
/// ambient part alone, and the skip keeps the bits: each lane of such chunks is shaded as when
/// one lane of its chunk faces the light (so the chunk is shaded in full), for every model whose
/// gate zeroes the lobe behind the surface. Degenerate lanes (a zero normal, a point at the
/// light) stay in the chunks.
#[test]
fn a_light_behind_whole_chunks_adds_its_ambient_part_alone() {
    let eye = Vec3::new(0.0, 1.0, 5.0);
    let (lamps, mut behind, base, plain) = setup(0xbac4, 2, eye);
    let len = behind.p.len();
    let chunks = 32..96;
    let mut rng = Rng::new(0xface);
    for i in chunks.clone() {
        let to_light = lamps[0].at - behind.p[i];
        if behind.n[i] != Vec3::ZERO && to_light != Vec3::ZERO {
            // Away from the light, tilted at random but kept behind it.
            let away = -to_light.normalize();
            let tilt = rng.vec3_in(-0.5, 0.5);
            behind.n[i] = (away + tilt - away * tilt.dot(away).min(0.0)).normalize();
            assert!(behind.n[i].dot(to_light) < 0.0, "point {i}");
        }
        // Lit, so that the skip of a shadowed light is not what runs.
        behind.vis[i] = 0.25 + 0.75 * rng.unit_f32();
    }
    // The reference: the first lane of each chunk faces the light.
    let mut facing = behind.clone();
    for i in chunks.clone().step_by(16) {
        facing.n[i] = (lamps[0].at - facing.p[i]).normalize();
    }
    assert_eq!(facing.vis.len(), 2 * len);
    let scene = scene_at(&plain, eye);
    for (name, model) in models() {
        if name.split(' ').nth(1) == Some("None") {
            continue; // no gate: the lobe may shine from behind
        }
        for with_surface in [true, false] {
            for level in Level::supported() {
                let a = run(level, &model, &base, &scene, &behind, with_surface, true);
                let b = run(level, &model, &base, &scene, &facing, with_surface, true);
                let what = format!("{name} at {level} (surface {with_surface})");
                assert_same_bits(&what, &a, &b, chunks.clone().filter(|i| i % 16 != 0));
            }
        }
    }
}

/// The 8-bit entry point is `linear_to_srgb8` of the `f32` one, at every level and at every
/// chunk boundary (more than 1024 points), with alpha 255.
#[test]
fn eight_bit_output_is_the_encoded_f32_output() {
    let mut rng = Rng::new(0x88);
    let lamps = lamps(&mut rng, 2);
    let eye = Vec3::new(0.5, 1.0, 4.0);
    let g = points(&mut rng, 2100, &lamps, eye);
    let lights: Vec<PointLight> = lamps.iter().map(|l| l.light(1.0)).collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(eye),
    };
    let base = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let model: Model = Phong::default().into();
    let (p, n) = (split(&g.p), split(&g.n));
    let (ka, kd, ks) = (split(&g.ka), split(&g.kd), split(&g.ks));
    let buffer = GBuffer::new(
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&n[0], &n[1], &n[2]),
    )
    .with_surface(SoaSurface {
        ambient: SoaVec3::new(&ka[0], &ka[1], &ka[2]),
        diffuse: SoaVec3::new(&kd[0], &kd[1], &kd[2]),
        specular: SoaVec3::new(&ks[0], &ks[1], &ks[2]),
        shininess: &g.s,
    })
    .with_visibility(&g.vis);
    for level in Level::supported() {
        let f = run(level, &model, &base, &scene, &g, true, true);
        let mut frame = vec![[0u8; 4]; g.p.len()];
        let shaded = phong::shade_gbuffer_rgba8_with_level(
            level, &model, &base, &scene, &buffer, &mut frame,
        )
        .unwrap();
        assert_eq!(shaded, g.p.len());
        for (i, px) in frame.iter().enumerate() {
            let [r, gr, b] = phong::linear_to_srgb8(f[i]);
            assert_eq!(*px, [r, gr, b, 255], "{level}: point {i}");
        }
    }
}

/// A textured surface as LearnOpenGL builds it, one texture as both `Ka` and `Kd` and a specular
/// strength map as a grey `Ks` (the kernel loads such shared planes once), shades to the same
/// bits as the same values in separate planes, at every level.
#[test]
fn shared_surface_planes_shade_as_separate_copies() {
    let mut rng = Rng::new(0x5a4e);
    let lamps = lamps(&mut rng, 2);
    let eye = Vec3::new(-0.5, 1.5, 4.0);
    let g = points(&mut rng, 203, &lamps, eye);
    let lights: Vec<PointLight> = lamps.iter().map(|l| l.light(1.0)).collect();
    let scene = scene_at(&lights, eye);
    let base =
        Material::try_new(Vec3::splat(0.2), Vec3::splat(0.6), Vec3::splat(0.4), 24.0).unwrap();
    let (p, n) = (split(&g.p), split(&g.n));
    let kd = split(&g.kd);
    let strength: Vec<f32> = g.ks.iter().map(|k| k.x).collect();
    // The copies: equal values, distinct slices.
    let (ka_copy, ks_copy) = (
        kd.clone(),
        [strength.clone(), strength.clone(), strength.clone()],
    );
    fn v3(a: &[Vec<f32>; 3]) -> SoaVec3<'_> {
        SoaVec3::new(&a[0], &a[1], &a[2])
    }
    let positions = GBuffer::new(v3(&p), v3(&n));
    let shared = positions
        .with_surface(SoaSurface {
            ambient: v3(&kd),
            diffuse: v3(&kd),
            specular: SoaVec3::new(&strength, &strength, &strength),
            shininess: &g.s,
        })
        .with_visibility(&g.vis);
    let separate = positions
        .with_surface(SoaSurface {
            ambient: v3(&ka_copy),
            diffuse: v3(&kd),
            specular: v3(&ks_copy),
            shininess: &g.s,
        })
        .with_visibility(&g.vis);
    let len = g.p.len();
    for (name, model) in models() {
        for level in Level::supported() {
            let shade = |buffer: &GBuffer<'_>| {
                let mut out = [vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]];
                let [r, gr, b] = &mut out;
                let shaded = phong::shade_gbuffer_with_level(
                    level,
                    &model,
                    &base,
                    &scene,
                    buffer,
                    SoaRgb::new(r, gr, b),
                )
                .unwrap();
                assert_eq!(shaded, len);
                (0..len)
                    .map(|i| Vec3::new(out[0][i], out[1][i], out[2][i]))
                    .collect::<Vec<_>>()
            };
            let (a, b) = (shade(&shared), shade(&separate));
            let what = format!("{name} at {level}, shared planes vs copies");
            assert_same_bits(&what, &a, &b, 0..len);
        }
    }
}

/// Without per-point inputs the G-buffer call is `shade_batch`, bit for bit; a visibility slice
/// too short for its planes shades nothing (release builds; debug builds assert).
#[test]
fn a_plain_gbuffer_is_shade_batch() {
    let mut rng = Rng::new(0x77);
    let lamps = lamps(&mut rng, 2);
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let g = points(&mut rng, 100, &lamps, eye);
    let lights: Vec<PointLight> = lamps.iter().map(|l| l.light(1.0)).collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(eye),
    };
    let base = Material::try_from_color(Vec3::new(0.8, 0.5, 0.2), 20.5).unwrap();
    let (p, n) = (split(&g.p), split(&g.n));
    let (pos, nor) = (
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&n[0], &n[1], &n[2]),
    );
    let len = g.p.len();
    let (mut a, mut b, mut c) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
    let (mut d, mut e, mut f) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
    for level in Level::supported() {
        let model = BlinnPhong::default();
        phong::shade_gbuffer_with_level(
            level,
            &model,
            &base,
            &scene,
            &GBuffer::new(pos, nor),
            SoaRgb::new(&mut a, &mut b, &mut c),
        )
        .unwrap();
        phong::shade_batch_with_level(
            level,
            &model,
            &base,
            &scene,
            pos,
            nor,
            SoaRgb::new(&mut d, &mut e, &mut f),
        )
        .unwrap();
        assert_eq!((&a, &b, &c), (&d, &e, &f), "{level}");
    }
    if !cfg!(debug_assertions) {
        let short = vec![1.0; len];
        let n = phong::shade_gbuffer(
            &Phong::default(),
            &base,
            &scene,
            &GBuffer::new(pos, nor).with_visibility(&short),
            SoaRgb::new(&mut a, &mut b, &mut c),
        );
        assert_eq!(n, 0, "two lights need two planes of visibility");
    }
}

/// A coverage mask: the covered points get exactly the unmasked call's colours (the kernel's
/// lanes are independent, and each run of covered points is one call of the same kernel), and
/// every other output keeps its previous value, in the `f32`, RGBA and `0x00RRGGBB` outputs, at
/// every level. The uncovered points' inputs are NaN: the documented "left unread" (a NaN read
/// would trip the debug assertions or change a covered run's fall-back point by point).
#[test]
fn coverage_shades_the_covered_points_and_leaves_the_rest() {
    let mut rng = Rng::new(0xc0fe);
    let lamps = lamps(&mut rng, 2);
    let eye = Vec3::new(0.5, 1.0, 4.0);
    let len = 2100; // past two 1024-point chunks of the 8-bit outputs
    let g = points(&mut rng, len, &lamps, eye);
    let lights: Vec<PointLight> = lamps.iter().map(|l| l.light(1.0)).collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.02),
        viewer: Viewer::At(eye),
    };
    let base = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let model: Model = BlinnPhong::default().into();
    // Spans of 1 to 40 points, covered or not, as scanlines cut a frame; one run crosses the
    // chunk boundary at 1024 and the last run ends at the last point.
    let mut coverage = Vec::with_capacity(len);
    let mut covered = true;
    while coverage.len() < len {
        let span = 1 + (rng.unit_f32() * 40.0) as usize;
        coverage.extend(core::iter::repeat_n(
            covered,
            span.min(len - coverage.len()),
        ));
        covered = !covered;
    }
    coverage[1010..1040].fill(true);
    coverage[len - 3..].fill(true);
    assert!(coverage.contains(&false));

    let poison = |v: &[f32]| -> Vec<f32> {
        v.iter()
            .enumerate()
            .map(|(i, &x)| if coverage[i % len] { x } else { f32::NAN })
            .collect()
    };
    let soa = |v: &[Vec3]| {
        let [x, y, z] = split(v);
        [poison(&x), poison(&y), poison(&z)]
    };
    let (p, n, ka, kd, ks) = (soa(&g.p), soa(&g.n), soa(&g.ka), soa(&g.kd), soa(&g.ks));
    let (s, vis) = (poison(&g.s), poison(&g.vis));
    let buffer = GBuffer::new(
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&n[0], &n[1], &n[2]),
    )
    .with_surface(SoaSurface {
        ambient: SoaVec3::new(&ka[0], &ka[1], &ka[2]),
        diffuse: SoaVec3::new(&kd[0], &kd[1], &kd[2]),
        specular: SoaVec3::new(&ks[0], &ks[1], &ks[2]),
        shininess: &s,
    })
    .with_visibility(&vis)
    .with_coverage(&coverage);
    {
        for level in Level::supported() {
            let want = run(level, &model, &base, &scene, &g, true, true);
            let (mut r, mut gr, mut b) = (vec![-1.0; len], vec![-2.0; len], vec![-3.0; len]);
            let shaded = phong::shade_gbuffer_with_level(
                level,
                &model,
                &base,
                &scene,
                &buffer,
                SoaRgb::new(&mut r, &mut gr, &mut b),
            )
            .unwrap();
            let mut rgba = vec![[1, 2, 3, 4]; len];
            let mut xrgb = vec![0xdead_beef; len];
            let shaded8 = phong::shade_gbuffer_rgba8_with_level(
                level, &model, &base, &scene, &buffer, &mut rgba,
            )
            .unwrap();
            let shaded32 = phong::shade_gbuffer_xrgb8_with_level(
                level, &model, &base, &scene, &buffer, &mut xrgb,
            )
            .unwrap();
            assert_eq!((shaded, shaded8, shaded32), (len, len, len), "{level}");
            for i in 0..len {
                let got = Vec3::new(r[i], gr[i], b[i]);
                if coverage[i] {
                    assert_eq!(got, want[i], "{level}: covered point {i}");
                    let [cr, cg, cb] = phong::linear_to_srgb8(want[i]);
                    assert_eq!(rgba[i], [cr, cg, cb, 255], "{level}: covered pixel {i}");
                    let x = u32::from(cr) << 16 | u32::from(cg) << 8 | u32::from(cb);
                    assert_eq!(xrgb[i], x, "{level}: covered pixel {i}");
                } else {
                    assert_eq!(got, Vec3::new(-1.0, -2.0, -3.0), "{level}: background {i}");
                    assert_eq!(rgba[i], [1, 2, 3, 4], "{level}: background pixel {i}");
                    assert_eq!(xrgb[i], 0xdead_beef, "{level}: background pixel {i}");
                }
            }
        }
    }
}

/// A 96 × 40 image of a bumpy floor under 64 lights (polynomial, inverse-square and Unreal
/// falloffs, a spot light, a sun), with some background pixels.
struct Frame {
    width: usize,
    p: [Vec<f32>; 3],
    n: [Vec<f32>; 3],
    coverage: Vec<bool>,
    lights: Vec<Light>,
}

fn many_lights(seed: u64) -> Frame {
    let mut rng = Rng::new(seed);
    let (width, height) = (96, 40);
    let mut pts = vec![];
    let mut nor = vec![];
    for y in 0..height {
        for x in 0..width {
            let (fx, fy) = (x as f32 * 0.25, y as f32 * 0.25);
            pts.push(Vec3::new(fx, fy, 0.2 * (fx * 1.3).sin() * (fy * 0.7).cos()));
            nor.push((Vec3::Z + rng.vec3_in(-0.3, 0.3)).normalize());
        }
    }
    let coverage = (0..width * height)
        .map(|i| (i % width) < 90 || i / width < 30)
        .collect();
    let colors = |rng: &mut Rng| {
        LightColors::try_new(
            Vec3::splat(0.02),
            rng.vec3_in(0.3, 1.0),
            Vec3::splat(rng.range_f32(0.2, 1.0)),
        )
        .unwrap()
    };
    let mut lights: Vec<Light> = (0..62)
        .map(|k| {
            let at = Vec3::new(rng.range_f32(0.0, 24.0), rng.range_f32(0.0, 10.0), 0.8);
            let attenuation = match k % 3 {
                0 => Attenuation::try_polynomial(1.0, 0.7, 1.8).unwrap(),
                1 => Attenuation::try_inverse_square(0.3).unwrap(),
                _ => Attenuation::try_unreal(3.0).unwrap(),
            };
            PointLight::try_new(at, attenuation, colors(&mut rng))
                .unwrap()
                .into()
        })
        .collect();
    lights.push(
        SpotLight::try_with_cone(
            Vec3::new(12.0, 5.0, 3.0),
            -Vec3::Z,
            SpotCone::degrees(25.0).with_exponent(3.0),
            Attenuation::try_inverse_square(2.0).unwrap(),
            colors(&mut rng),
        )
        .unwrap()
        .into(),
    );
    lights.push(
        DirectionalLight::try_new(Vec3::new(0.3, 0.2, 1.0), colors(&mut rng))
            .unwrap()
            .into(),
    );
    Frame {
        width,
        p: split(&pts),
        n: split(&nor),
        coverage,
        lights,
    }
}

/// `shade_gbuffer` and `shade_gbuffer_tiled` of `frame` at `level`, with the sentinel −1 where
/// nothing is written.
fn culled_and_not(
    level: Level,
    model: &Model,
    m: &Material,
    frame: &Frame,
    threshold: f32,
    visibility: Option<&[f32]>,
    albedo: Option<&[[u8; 4]]>,
) -> (Vec<Vec3>, Vec<Vec3>) {
    let scene = Scene {
        lights: &frame.lights,
        ambient: Vec3::splat(0.01),
        viewer: Viewer::At(Vec3::new(12.0, -6.0, 9.0)),
    };
    let (p, n) = (&frame.p, &frame.n);
    let mut g = GBuffer::new(
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&n[0], &n[1], &n[2]),
    )
    .with_coverage(&frame.coverage);
    if let Some(v) = visibility {
        g = g.with_visibility(v);
    }
    if let Some(a) = albedo {
        g = g.with_albedo_srgb8(a);
    }
    let len = frame.coverage.len();
    let shade = |tiled: bool| {
        let (mut r, mut gr, mut b) = (vec![-1.0; len], vec![-1.0; len], vec![-1.0; len]);
        let out = SoaRgb::new(&mut r, &mut gr, &mut b);
        let shaded = if tiled {
            let culling = TileCulling {
                width: frame.width,
                tile: 16,
                threshold,
            };
            let mut scratch = frame.lights.clone();
            phong::shade_gbuffer_tiled_with_level(
                level,
                model,
                m,
                &scene,
                &g,
                culling,
                &mut scratch,
                out,
            )
        } else {
            phong::shade_gbuffer_with_level(level, model, m, &scene, &g, out)
        };
        assert_eq!(shaded.unwrap(), len);
        (0..len)
            .map(|i| Vec3::new(r[i], gr[i], b[i]))
            .collect::<Vec<_>>()
    };
    (shade(false), shade(true))
}

/// Tile culling drops lights (the pictures differ), but at each pixel by no more than
/// `TileCulling`'s bound summed over the lights whose factor there is below the threshold (only
/// those can have been dropped: a light reaching the threshold at a pixel reaches it in the
/// pixel's tile), plus the rounding of both sums; background pixels stay unwritten.
#[test]
fn tile_culling_stays_within_its_documented_bound() {
    let frame = many_lights(0x711e);
    let threshold = 2e-3;
    let m = Material::try_new(
        Vec3::splat(0.3),
        Vec3::new(0.8, 0.6, 0.4),
        Vec3::splat(0.5),
        24.0,
    )
    .unwrap();
    let models: [Model; 2] = [
        Phong::default().into(),
        BlinnPhong {
            normalization: Normalization::Energy,
            ..BlinnPhong::default()
        }
        .into(),
    ];
    let models = models.map(|model| {
        let r = phong::ResolvedModel::from(model);
        (model, r.diffuse(1.0), r.specular_scale(24.0))
    });
    let lights = frame.lights.len() as f32;
    for (model, dscale, sscale) in models {
        for level in Level::supported() {
            let (full, culled) = culled_and_not(level, &model, &m, &frame, threshold, None, None);
            let mut differ = 0;
            for i in 0..full.len() {
                if !frame.coverage[i] {
                    assert_eq!(culled[i], Vec3::splat(-1.0), "{level}: background {i}");
                    continue;
                }
                let p = Vec3::new(frame.p[0][i], frame.p[1][i], frame.p[2][i]);
                let mut bound = Vec3::ZERO;
                for light in &frame.lights {
                    // Only a light whose factor here is below the threshold (with room for the
                    // rounding of the tile's distance) can have been left out.
                    if light.sample(p).factor >= threshold * (1.0 + 1e-4) {
                        continue;
                    }
                    let c = light.colors();
                    bound += threshold
                        * (1.0 + 1e-4)
                        * (m.ambient() * c.ambient()
                            + m.diffuse() * c.diffuse() * dscale
                            + m.specular() * c.specular() * sscale);
                }
                let rounding = (full[i] + culled[i]) * (8.0 + 2.0 * lights) * f32::EPSILON / 2.0;
                let diff = (culled[i] - full[i]).abs();
                differ += usize::from(diff != Vec3::ZERO);
                assert!(
                    diff.cmple(bound + rounding).all(),
                    "{level}: pixel {i}: culled {} against {}, bound {bound}",
                    culled[i],
                    full[i]
                );
            }
            assert!(differ > 100, "{level}: only {differ} pixels changed");
        }
    }
}

/// With a threshold of 0 no light is dropped, and with visibility planes the call does not cull:
/// both are `shade_gbuffer`, bit for bit.
#[test]
fn tile_culling_without_dropping_is_shade_gbuffer() {
    let frame = many_lights(0x5eed);
    let m = Material::try_from_color(Vec3::ONE, 16.0).unwrap();
    let model: Model = Phong::default().into();
    let len = frame.coverage.len();
    let visibility: Vec<f32> = (0..len * frame.lights.len())
        .map(|k| (k % 7) as f32 / 6.0)
        .collect();
    let albedo: Vec<[u8; 4]> = (0..len)
        .map(|i| {
            [
                (i * 37 % 256) as u8,
                (i * 11 % 256) as u8,
                (i * 101 % 256) as u8,
                255,
            ]
        })
        .collect();
    for level in Level::supported() {
        let (full, culled) = culled_and_not(level, &model, &m, &frame, 0.0, None, None);
        assert_eq!(full, culled, "{level}: threshold 0");
        // A per-point input read by the points' own index, in a tile's runs.
        let (full, culled) = culled_and_not(level, &model, &m, &frame, 0.0, None, Some(&albedo));
        assert_eq!(full, culled, "{level}: threshold 0, 8-bit albedo");
        let (full, culled) =
            culled_and_not(level, &model, &m, &frame, 0.1, Some(&visibility), None);
        assert_eq!(full, culled, "{level}: with visibility");
    }
}

/// 8-bit sRGB albedo: the kernel decodes each texel with `srgb8_to_linear` and multiplies the
/// surface's (or the material's) ambient and diffuse reflectance by it, so the output equals the
/// call with those products as an `f32` surface, bit for bit, at every level, with and without a
/// surface, degenerate points included (they take the scalar path with the same surface).
#[test]
fn albedo_texels_are_the_decoded_surface() {
    let mut rng = Rng::new(0xa1be);
    let lamps = lamps(&mut rng, 2);
    let eye = Vec3::new(0.0, 1.0, 4.0);
    let len = 300;
    let g = points(&mut rng, len, &lamps, eye);
    let lights: Vec<PointLight> = lamps.iter().map(|l| l.light(1.0)).collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer: Viewer::At(eye),
    };
    let base = Material::try_new(
        Vec3::splat(0.3),
        Vec3::new(0.9, 0.8, 0.7),
        Vec3::splat(0.4),
        20.5,
    )
    .unwrap();
    let model: Model = Phong::default().into();
    let texels: Vec<[u8; 4]> = (0..len)
        .map(|_| {
            let mut t = [0u8; 4];
            for c in &mut t {
                *c = (rng.unit_f32() * 256.0).min(255.0) as u8;
            }
            t
        })
        .collect();
    let decoded: Vec<Vec3> = texels
        .iter()
        .map(|t| {
            let [r, g, b, _] = t.map(phong::srgb8_to_linear);
            Vec3::new(r, g, b)
        })
        .collect();
    let (p, n) = (split(&g.p), split(&g.n));
    let (pos, nor) = (
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&n[0], &n[1], &n[2]),
    );
    let (ka, kd, ks) = (split(&g.ka), split(&g.kd), split(&g.ks));
    let surface = SoaSurface {
        ambient: SoaVec3::new(&ka[0], &ka[1], &ka[2]),
        diffuse: SoaVec3::new(&kd[0], &kd[1], &kd[2]),
        specular: SoaVec3::new(&ks[0], &ks[1], &ks[2]),
        shininess: &g.s,
    };
    // The same reflectances as f32 surfaces: the surface's, and the material's, times the texel.
    let times = |v: &[Vec3]| {
        split(
            &v.iter()
                .zip(&decoded)
                .map(|(a, d)| *a * *d)
                .collect::<Vec<_>>(),
        )
    };
    let (ka_t, kd_t) = (times(&g.ka), times(&g.kd));
    let (ma, md) = (
        times(&vec![base.ambient(); len]),
        times(&vec![base.diffuse(); len]),
    );
    let ms = split(&vec![base.specular(); len]);
    let s_base = vec![base.shininess(); len];
    let with_texels = SoaSurface {
        ambient: SoaVec3::new(&ka_t[0], &ka_t[1], &ka_t[2]),
        diffuse: SoaVec3::new(&kd_t[0], &kd_t[1], &kd_t[2]),
        ..surface
    };
    let material_texels = SoaSurface {
        ambient: SoaVec3::new(&ma[0], &ma[1], &ma[2]),
        diffuse: SoaVec3::new(&md[0], &md[1], &md[2]),
        specular: SoaVec3::new(&ms[0], &ms[1], &ms[2]),
        shininess: &s_base,
    };
    let cases = [
        (
            GBuffer::new(pos, nor)
                .with_surface(surface)
                .with_albedo_srgb8(&texels),
            GBuffer::new(pos, nor).with_surface(with_texels),
            "surface",
        ),
        (
            GBuffer::new(pos, nor).with_albedo_srgb8(&texels),
            GBuffer::new(pos, nor).with_surface(material_texels),
            "material",
        ),
    ];
    for level in Level::supported() {
        for (textured, want, what) in &cases {
            let shade = |g: &GBuffer<'_>| {
                let (mut r, mut gr, mut b) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
                let k = phong::shade_gbuffer_with_level(
                    level,
                    &model,
                    &base,
                    &scene,
                    g,
                    SoaRgb::new(&mut r, &mut gr, &mut b),
                )
                .unwrap();
                assert_eq!(k, len);
                (r, gr, b)
            };
            assert_eq!(
                shade(textured),
                shade(want),
                "{level}: albedo over the {what}"
            );
        }
    }
}

/// `shade_gbuffer_terms` at `level`, every point's three terms (`-1` where nothing was written).
fn run_terms(
    level: Level,
    model: &Model,
    base: &Material,
    scene: &Scene<'_, PointLight>,
    buffer: &GBuffer<'_>,
) -> Vec<[Vec3; 3]> {
    let len = buffer.len();
    let mut t: Vec<Vec<f32>> = (0..9).map(|_| vec![-1.0; len]).collect();
    let [ar, ag, ab, dr, dg, db, sr, sg, sb] = &mut t[..] else {
        unreachable!()
    };
    let out = SoaTerms::new(
        SoaRgb::new(ar, ag, ab),
        SoaRgb::new(dr, dg, db),
        SoaRgb::new(sr, sg, sb),
    );
    let shaded = phong::shade_gbuffer_terms_with_level(level, model, base, scene, buffer, out)
        .expect("a supported level");
    assert_eq!(shaded, len);
    (0..len)
        .map(|i| {
            let v = |k: usize| Vec3::new(t[k][i], t[k + 1][i], t[k + 2][i]);
            [v(0), v(3), v(6)]
        })
        .collect()
}

/// The separate-terms output, term by term, against the equation. Each term of the equation is
/// the whole equation for a material that keeps only that term's reflectance (the other two and
/// the emission zero), so each term written must lie in that material's range from
/// tools/src/batch_range.rs: the accuracy the batch documents, with no tolerance of its own.
/// Every model, with and without per-point surfaces and visibilities, every level, random points
/// with the degenerate ones `points` mixes in (zero normals, a point at a light or at the eye);
/// a coverage mask leaves the uncovered points' nine values untouched.
#[test]
fn the_terms_output_is_each_term_of_the_equation_at_every_level() {
    let eye = Vec3::new(1.0, -2.0, 4.0);
    let (lamps, g, base, plain) = setup(0x7e5_0003, 2, eye);
    let len = g.p.len();
    let scene = scene_at(&plain, eye);
    let sp = Split::new(&g);
    let coverage: Vec<bool> = (0..len).map(|i| i % 3 != 1).collect();
    for (name, model) in models() {
        for (with_surface, with_vis, with_coverage) in [
            (false, false, false),
            (true, true, false),
            (true, false, true),
            (false, true, false),
        ] {
            let mut buffer = sp.gbuffer(&g, with_surface, with_vis);
            if with_coverage {
                buffer = buffer.with_coverage(&coverage);
            }
            // Point i's range for each term: its material reduced to that term, under the scene
            // whose light j is scaled by the point's visibility of it (as in `check`).
            let ranges: Vec<[batch_range::Range; 3]> = (0..len)
                .map(|i| {
                    let (a, d, s, sh) = if with_surface {
                        (g.ka[i], g.kd[i], g.ks[i], g.s[i])
                    } else {
                        (
                            base.ambient(),
                            base.diffuse(),
                            base.specular(),
                            base.shininess(),
                        )
                    };
                    let lights: Vec<PointLight> = lamps
                        .iter()
                        .enumerate()
                        .map(|(j, l)| l.light(if with_vis { g.vis[j * len + i] } else { 1.0 }))
                        .collect();
                    let sc = Scene {
                        lights: &lights,
                        ..scene
                    };
                    let z = Vec3::ZERO;
                    let only = |a, d, s| Material::try_new(a, d, s, sh).unwrap();
                    [only(a, z, z), only(z, d, z), only(z, z, s)]
                        .map(|m| batch_range::range(&model, &m, &sc, g.p[i], g.n[i]))
                })
                .collect();
            for level in Level::supported() {
                let out = run_terms(level, &model, &base, &scene, &buffer);
                for i in 0..len {
                    if with_coverage && !coverage[i] {
                        assert_eq!(
                            out[i],
                            [Vec3::splat(-1.0); 3],
                            "{name}: uncovered point {i}"
                        );
                        continue;
                    }
                    for (t, term) in ["ambient", "diffuse", "specular"].iter().enumerate() {
                        let r = &ranges[i][t];
                        assert!(
                            r.holds(out[i][t]),
                            "{name} at {level} (surface {with_surface}, visibility {with_vis}): \
                             the {term} term at point {i} (p = {}, n = {}, s = {}) is {}, \
                             outside [{}, {}]",
                            g.p[i],
                            g.n[i],
                            g.s[i],
                            out[i][t],
                            r.lo,
                            r.hi
                        );
                    }
                }
            }
        }
    }
}
