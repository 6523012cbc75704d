//! Lighting in the shapes real renderers have, `phong` against the same lighting written by hand.
//!
//! - `raytrace`: a Whitted-style ray tracer shades one hit at a time: recorded hits (position,
//!   normal, direction back along the ray) under three point lights, with each light's visibility
//!   from a shadow ray. `phong` is `Shader::with_viewer(Viewer::Infinite(to_eye)).shade_visible(..)`:
//!   `examples/raytracer.rs` makes the same call with `Viewer::along_ray(ray direction)`, which is
//!   `Viewer::Infinite(−ray direction)`.
//! - `raytrace_one_light`: the same hits under the first of those lights alone.
//! - `fragment`: a rasterizer shades fragments with texture maps and a shadow map: a per-pixel
//!   diffuse colour, specular strength, shininess (non-integer, uniform in [2, 128]) and shadow
//!   factor, one point light, a camera at a point. `phong` is `Shader::shade_surface(..)` in a
//!   loop over the fragments' arrays, which the compiler vectorises; `hand_callback` and
//!   `phong_callback` shade the same fragments one per call (each position read through
//!   `black_box` of a reference to it), as a rasterizer's per-fragment callback does,
//!   `phong_callback` through `Shader::one_at_a_time`. Through a reference, not by value:
//!   `black_box` of the value writes it to the stack as an 8-byte and a 4-byte store and reads it
//!   back, and code that reloads it as 4 + 8 bytes then waits on a failed store forward (about 50
//!   cycles a fragment, on this harness's round trip alone); which way LLVM reloads it changed with
//!   unrelated code (DESIGN.md).
//!
//! The workspace's rasterizer has its own frame bench (`raster_frame`, `cargo bench -p raster`).
//!
//! In `raytrace` and `fragment`, `hand` is LearnOpenGL-style code (normalize, `reflect`, `powf`, `1/(c + l·d + q·d²)`)
//! with glam, and the `phong` side uses the hand code's gate (`SpecularGate::None`, LearnOpenGL's
//! `Phong::learnopengl()`). Before timing, each group asserts that the two agree on every input.
//!
//! Run: `cargo bench --bench renderers`.

// Index loops over parallel input arrays read like the renderer code they stand for.
#![allow(
    clippy::needless_range_loop,
    reason = "index loops over parallel arrays, as the renderer code they stand for"
)]

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use phong::{
    Attenuation, LightColors, Material, Phong, PointLight, Scene, Shader, Surface, Viewer,
};

use phong_tools::rng::Rng;

const N: usize = 4096;
const ATT: (f32, f32, f32) = (1.0, 0.09, 0.032);

/// A light as the hand-written code keeps it.
#[derive(Clone, Copy)]
struct HandLight {
    position: Vec3,
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
}

/// The same light for `phong`.
fn phong_light(l: &HandLight) -> PointLight {
    PointLight::try_new(
        l.position,
        Attenuation::try_polynomial(ATT.0, ATT.1, ATT.2).unwrap(),
        LightColors::try_new(l.ambient, l.diffuse, l.specular).unwrap(),
    )
    .unwrap()
}

fn unit(rng: &mut Rng) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.range_f32(-1.0, 1.0),
            rng.range_f32(-1.0, 1.0),
            rng.range_f32(-1.0, 1.0),
        );
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return v.normalize();
        }
    }
}

fn point(rng: &mut Rng, r: f32) -> Vec3 {
    Vec3::new(
        rng.range_f32(-r, r),
        rng.range_f32(-r, r),
        rng.range_f32(-r, r),
    )
}

/// `|a − b| ≤ 1e-4 + 1e-4·|b|` per channel: `f32` rounding in different operation orders on
/// outputs of order 1 (both sides use `powf`; no approximation is involved).
fn assert_close(what: &str, a: Vec3, b: Vec3, i: usize) {
    let tol = Vec3::splat(1e-4) + b.abs() * 1e-4;
    assert!(
        (a - b).abs().cmple(tol).all(),
        "{what}: phong and hand disagree at {i}: {a} vs {b}"
    );
}

// ---------------------------------------------------------------------------------------------
// raytrace
// ---------------------------------------------------------------------------------------------

/// What a ray tracer has at a hit, once its shadow rays are traced.
struct Hits {
    position: Vec<Vec3>,
    normal: Vec<Vec3>,
    /// Unit direction from the hit back toward where the ray came from.
    to_eye: Vec<Vec3>,
    visibility: Vec<[f32; 3]>,
}

fn hits(n: usize, seed: u64) -> Hits {
    let mut rng = Rng::new(seed);
    let mut h = Hits {
        position: Vec::with_capacity(n),
        normal: Vec::with_capacity(n),
        to_eye: Vec::with_capacity(n),
        visibility: Vec::with_capacity(n),
    };
    for _ in 0..n {
        h.position.push(point(&mut rng, 3.0));
        h.normal.push(unit(&mut rng));
        h.to_eye.push(unit(&mut rng));
        // A shadow ray either reaches the light or not: about a third of the lights are blocked.
        let mut vis = [1.0; 3];
        for v in &mut vis {
            if rng.unit_f32() < 0.33 {
                *v = 0.0;
            }
        }
        h.visibility.push(vis);
    }
    h
}

fn rt_lights() -> [HandLight; 3] {
    [
        HandLight {
            position: Vec3::new(4.0, 5.0, 3.0),
            ambient: Vec3::splat(0.05),
            diffuse: Vec3::new(0.9, 0.85, 0.8),
            specular: Vec3::ONE,
        },
        HandLight {
            position: Vec3::new(-5.0, 3.0, 1.0),
            ambient: Vec3::splat(0.05),
            diffuse: Vec3::new(0.3, 0.4, 0.8),
            specular: Vec3::splat(0.5),
        },
        HandLight {
            position: Vec3::new(0.0, 6.0, -4.0),
            ambient: Vec3::splat(0.05),
            diffuse: Vec3::new(0.8, 0.5, 0.3),
            specular: Vec3::splat(0.8),
        },
    ]
}

/// The material of the hand-written side.
struct HandMaterial {
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
    shininess: f32,
}

/// LearnOpenGL's multiple-lights fragment shader (point lights), per hit, with a shadow factor per
/// light on the diffuse and specular parts.
#[inline(never)]
fn rt_hand(lights: &[HandLight], m: &HandMaterial, h: &Hits, out: &mut [Vec3]) {
    for i in 0..h.position.len() {
        let (p, norm, view_dir) = (h.position[i], h.normal[i].normalize(), h.to_eye[i]);
        let mut result = Vec3::ZERO;
        for (k, light) in lights.iter().enumerate() {
            let light_dir = (light.position - p).normalize();
            let diff = norm.dot(light_dir).max(0.0);
            let reflect_dir = (-light_dir).reflect(norm);
            let spec = view_dir.dot(reflect_dir).max(0.0).powf(m.shininess);
            let distance = (light.position - p).length();
            let attenuation = 1.0 / (ATT.0 + ATT.1 * distance + ATT.2 * distance * distance);
            let ambient = light.ambient * m.ambient;
            let diffuse = light.diffuse * diff * m.diffuse;
            let specular = light.specular * spec * m.specular;
            let shadow = h.visibility[i][k];
            result += (ambient + shadow * (diffuse + specular)) * attenuation;
        }
        out[i] = result;
    }
}

/// The same with `phong`: one shader per scene, its viewer set per hit.
#[inline(never)]
fn rt_phong(scene: &Scene<'_, PointLight>, m: &Material, h: &Hits, out: &mut [Vec3]) {
    let shader = Shader::new(Phong::learnopengl(), m, scene);
    for i in 0..h.position.len() {
        let hit = shader.with_viewer(Viewer::Infinite(h.to_eye[i]));
        out[i] = hit
            .shade_visible(h.position[i], h.normal[i], &h.visibility[i])
            .total();
    }
}

fn raytrace(c: &mut Criterion) {
    raytrace_with(c, "raytrace", 3);
    raytrace_with(c, "raytrace_one_light", 1);
}

/// The `raytrace` group under the first `count` of its lights.
fn raytrace_with(c: &mut Criterion, name: &str, count: usize) {
    let h = hits(N, 0x7ace);
    let lights = &rt_lights()[..count];
    let hm = HandMaterial {
        ambient: Vec3::new(0.8, 0.3, 0.2),
        diffuse: Vec3::new(0.8, 0.3, 0.2),
        specular: Vec3::splat(0.6),
        shininess: 48.0,
    };
    let pl: Vec<PointLight> = lights.iter().map(phong_light).collect();
    let scene = Scene {
        lights: &pl,
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let m = Material::try_new(hm.ambient, hm.diffuse, hm.specular, hm.shininess).unwrap();
    let (mut a, mut b) = (vec![Vec3::ZERO; N], vec![Vec3::ZERO; N]);
    rt_hand(lights, &hm, &h, &mut a);
    rt_phong(&scene, &m, &h, &mut b);
    for i in 0..N {
        assert_close(name, b[i], a[i], i);
    }

    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(N as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("hand", |bch| {
        bch.iter(|| rt_hand(black_box(lights), &hm, black_box(&h), &mut a))
    });
    g.bench_function("phong", |bch| {
        bch.iter(|| rt_phong(black_box(&scene), &m, black_box(&h), &mut b))
    });
    g.finish();
}

// ---------------------------------------------------------------------------------------------
// fragment
// ---------------------------------------------------------------------------------------------

/// A G-buffer-like stream of fragments with their texel values and shadow-map lookups.
struct Fragments {
    position: Vec<Vec3>,
    normal: Vec<Vec3>,
    albedo: Vec<Vec3>,
    specular_strength: Vec<f32>,
    shininess: Vec<f32>,
    shadow: Vec<f32>,
}

/// The fragment arrays cut to one length, as a rasterizer's G-buffer rows are: both sides index
/// these, so the compiler knows every index is in bounds and can vectorise either loop.
struct Rows<'a> {
    position: &'a [Vec3],
    normal: &'a [Vec3],
    albedo: &'a [Vec3],
    specular_strength: &'a [f32],
    shininess: &'a [f32],
    shadow: &'a [f32],
}

impl Fragments {
    fn rows(&self, n: usize) -> Rows<'_> {
        Rows {
            position: &self.position[..n],
            normal: &self.normal[..n],
            albedo: &self.albedo[..n],
            specular_strength: &self.specular_strength[..n],
            shininess: &self.shininess[..n],
            shadow: &self.shadow[..n],
        }
    }
}

fn fragments(n: usize, seed: u64) -> Fragments {
    let mut rng = Rng::new(seed);
    let mut f = Fragments {
        position: Vec::with_capacity(n),
        normal: Vec::with_capacity(n),
        albedo: Vec::with_capacity(n),
        specular_strength: Vec::with_capacity(n),
        shininess: Vec::with_capacity(n),
        shadow: Vec::with_capacity(n),
    };
    for _ in 0..n {
        f.position.push(point(&mut rng, 2.0));
        f.normal.push(unit(&mut rng));
        f.albedo
            .push(Vec3::new(rng.unit_f32(), rng.unit_f32(), rng.unit_f32()));
        f.specular_strength.push(rng.unit_f32());
        f.shininess.push(rng.range_f32(2.0, 128.0));
        // A filtered shadow map: mostly lit or mostly shadowed, soft at the edges.
        let s = rng.unit_f32();
        f.shadow.push(if s < 0.3 {
            1.0
        } else if s < 0.4 {
            rng.unit_f32()
        } else {
            0.0
        });
    }
    f
}

const FRAG_LIGHT: HandLight = HandLight {
    position: Vec3::new(1.2, 2.0, 2.0),
    ambient: Vec3::splat(0.15),
    diffuse: Vec3::splat(0.8),
    specular: Vec3::ONE,
};
const CAMERA: Vec3 = Vec3::new(0.0, 1.0, 4.0);

/// LearnOpenGL's lighting maps with a point light and a shadow factor (shadow-mapping chapter).
///
/// `CALLBACK`: each fragment's position is read through `black_box` (of a reference, see the
/// module docs), so the compiler cannot vectorise across fragments: one fragment per call, as a
/// rasterizer's per-fragment callback (texture lookups and shadow-map tests between fragments)
/// shades.
#[inline(never)]
fn frag_hand<const CALLBACK: bool>(
    light: &HandLight,
    view_pos: Vec3,
    f: &Fragments,
    out: &mut [Vec3],
) {
    let f = f.rows(out.len());
    for i in 0..out.len() {
        let p = if CALLBACK {
            *black_box(&f.position[i])
        } else {
            f.position[i]
        };
        let color = f.albedo[i];
        let norm = f.normal[i].normalize();
        let light_dir = (light.position - p).normalize();
        let diff = norm.dot(light_dir).max(0.0);
        let view_dir = (view_pos - p).normalize();
        let reflect_dir = (-light_dir).reflect(norm);
        let spec = view_dir.dot(reflect_dir).max(0.0).powf(f.shininess[i]);
        let distance = (light.position - p).length();
        let attenuation = 1.0 / (ATT.0 + ATT.1 * distance + ATT.2 * distance * distance);
        let ambient = light.ambient * color;
        let diffuse = light.diffuse * diff * color;
        let specular = light.specular * spec * f.specular_strength[i];
        let shadow = f.shadow[i];
        out[i] = (ambient + (1.0 - shadow) * (diffuse + specular)) * attenuation;
    }
}

/// The same with `phong`: a per-point `Surface` and the shadow as visibility `1 − shadow`. Like
/// `frag_hand`, it takes its one light at run time and the camera, and builds its scene here.
/// `CALLBACK` as in `frag_hand`, with the shader's form for one point per call
/// (`Shader::one_at_a_time`).
#[inline(never)]
fn frag_phong<const CALLBACK: bool>(
    light: &PointLight,
    view_pos: Vec3,
    base: &Material,
    f: &Fragments,
    out: &mut [Vec3],
) {
    let lights = [*light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(view_pos),
    };
    let shader = Shader::new(Phong::learnopengl(), base, &scene);
    let shader = if CALLBACK {
        shader.one_at_a_time()
    } else {
        shader
    };
    let f = f.rows(out.len());
    for i in 0..out.len() {
        let p = if CALLBACK {
            *black_box(&f.position[i])
        } else {
            f.position[i]
        };
        let texel = Surface::textured(
            f.albedo[i],
            Vec3::splat(f.specular_strength[i]),
            f.shininess[i],
        );
        let vis = [1.0 - f.shadow[i]];
        out[i] = shader.shade_surface(p, f.normal[i], &texel, vis).total();
    }
}

fn fragment(c: &mut Criterion) {
    let f = fragments(N, 0xf4a9);
    let light = phong_light(&FRAG_LIGHT);
    let base = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let (mut a, mut b) = (vec![Vec3::ZERO; N], vec![Vec3::ZERO; N]);
    frag_hand::<false>(&FRAG_LIGHT, CAMERA, &f, &mut a);
    frag_phong::<false>(&light, CAMERA, &base, &f, &mut b);
    for i in 0..N {
        assert_close("fragment", b[i], a[i], i);
    }
    frag_hand::<true>(&FRAG_LIGHT, CAMERA, &f, &mut a);
    frag_phong::<true>(&light, CAMERA, &base, &f, &mut b);
    for i in 0..N {
        assert_close("fragment callback", b[i], a[i], i);
    }

    let mut g = c.benchmark_group("fragment");
    g.throughput(Throughput::Elements(N as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("hand", |bch| {
        bch.iter(|| frag_hand::<false>(black_box(&FRAG_LIGHT), CAMERA, black_box(&f), &mut a))
    });
    g.bench_function("phong", |bch| {
        bch.iter(|| frag_phong::<false>(black_box(&light), CAMERA, &base, black_box(&f), &mut b))
    });
    g.bench_function("hand_callback", |bch| {
        bch.iter(|| frag_hand::<true>(black_box(&FRAG_LIGHT), CAMERA, black_box(&f), &mut a))
    });
    g.bench_function("phong_callback", |bch| {
        bch.iter(|| frag_phong::<true>(black_box(&light), CAMERA, &base, black_box(&f), &mut b))
    });
    g.finish();
}

criterion_group!(benches, raytrace, fragment);
criterion_main!(benches);
