//! Shading throughput: plain per-point glam code against the crate's scalar and batch paths.
//!
//! Groups `phong_4096`, `blinn_4096`, `phong_1m`, `blinn_1m`, each with
//! - `naive_glam`: LearnOpenGL's point-light shader transcribed per point with glam `Vec3`
//!   (normalize, reflect / halfway, `powf`, `1/(c + l·d + q·d²)`), written here, not in the crate;
//! - `scalar`: the per-point API of the README and `examples/raytracer.rs`: a
//!   [`phong::Shader`] prepared once from the model's defaults, then `shade(p, n).total()` per point,
//!   written as the quick start writes it (the scene built around its one light where the points
//!   are shaded, so the compiler sees one light, as it does in `naive_glam`);
//! - `scalar_opaque`: the same with each point passed through `black_box`, so the compiler cannot
//!   vectorise across points, as in a recursive ray tracer or a per-pixel callback;
//! - `shade`: the free function `phong::shade` per point (it prepares the shader on every call);
//! - `batch`: `phong::shade_batch` on structure-of-arrays copies (shininess 32);
//! - `batch_frac`: the same at shininess 20.5 (a non-integer exponent: polynomial pow).
//!
//! Real-shaped groups, each with `phong` against `hand` (the same lighting written by hand in the
//! LearnOpenGL style, with glam), over the same recorded inputs:
//! - `raytrace`: a ray tracer's hits (position, normal, direction back along the ray) under three
//!   point lights with per-light visibility from shadow rays;
//! - `fragment`: a rasterizer's fragments with a per-pixel diffuse colour, specular strength,
//!   shininess (non-integer, uniform in [2, 128]) and shadow factor.
//!
//! Extra groups for docs/performance.md: `pow_4096` (every pow strategy, both models, s = 32 and
//! 20.5), `levels_4096` (every dispatch level this CPU runs), `parallel_1m` (one call against
//! one part per core on scoped threads, the batch module's "Many cores" recipe) and
//! `falloff_4096` (a spot light and an Unreal-falloff point light: the batch against `shade`) and
//! `tiled_64_lights` (64 lights over a G-buffer: every light against per-tile culling).
//!
//! `paired_4096` holds the targets' ratios again (`scalar` ÷ `naive_glam`, each level ÷ AVX-512
//! and SSE2 ÷ portable, the G-buffer's 8-bit rows ÷ `batch_frac`), each row one ratio whose two
//! calls are timed in alternation inside every sample (`support/paired_ratio.rs`), so that the
//! host's slow spells fall on both sides alike.
//!
//! Before timing, each group asserts that `scalar`, `scalar_opaque`, `batch` and `batch_frac` agree with
//! `naive_glam` (same step gate, ambient and attenuation) on the same inputs.
//!
//! Run: `cargo bench --bench shading`; then `cargo run --release -p phong-tools --bin performance`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, Level, LightColors, Material, Phong, PointLight, PowStrategy, Scene,
    SoaRgb, SoaVec3, Viewer,
};

use phong_tools::bench_scene::*;

#[path = "support/paired_ratio.rs"]
mod paired_ratio;

/// The padding between arrays carved from one buffer: 272 `f32`s, 1088 bytes, so that arrays of
/// 4096 points start at different offsets within a 4 KiB page.
const STAGGER: usize = 272;

/// Nine structure-of-arrays slices carved from one buffer at staggered offsets, so no two arrays
/// start at the same offset within a 4 KiB page (4 KiB aliasing between arrays at equal page offsets).
struct Soa {
    buf: Vec<f32>,
    n: usize,
    stride: usize,
}
impl Soa {
    fn new(n: usize) -> Self {
        let stride = n + STAGGER; // a different 4 KiB offset per array
        Soa {
            buf: vec![0.0; 9 * stride + 64],
            n,
            stride,
        }
    }
    fn arr(&self, k: usize) -> &[f32] {
        &self.buf[k * self.stride..k * self.stride + self.n]
    }
    fn fill(&mut self, p: &[Vec3], nn: &[Vec3]) {
        for i in 0..self.n {
            let v = [p[i].x, p[i].y, p[i].z, nn[i].x, nn[i].y, nn[i].z];
            for (k, x) in v.into_iter().enumerate() {
                self.buf[k * self.stride + i] = x;
            }
        }
    }
    /// Positions, normals, and the mutable outputs.
    fn split(&mut self) -> (SoaVec3<'_>, SoaVec3<'_>, SoaRgb<'_>) {
        let (s, n) = (self.stride, self.n);
        let (inp, outp) = self.buf.split_at_mut(6 * s);
        let a = |k: usize| &inp[k * s..k * s + n];
        let (r, rest) = outp.split_at_mut(s);
        let (g, b) = rest.split_at_mut(s);
        (
            SoaVec3::new(a(0), a(1), a(2)),
            SoaVec3::new(a(3), a(4), a(5)),
            SoaRgb::new(&mut r[..n], &mut g[..n], &mut b[..n]),
        )
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Phong,
    Blinn,
}

/// LearnOpenGL's point-light shader (basic lighting + attenuation), per point, with glam, with the
/// crate's default step gate on the specular term.
#[inline(never)]
fn naive_glam(kind: Kind, shininess: f32, p: &[Vec3], n: &[Vec3], out: &mut [Vec3]) {
    for i in 0..p.len() {
        let norm = n[i].normalize();
        let light_dir = (LIGHT_POS - p[i]).normalize();
        let diff = norm.dot(light_dir).max(0.0);
        let view_dir = (VIEW_POS - p[i]).normalize();
        let spec_base = match kind {
            Kind::Phong => {
                let reflect_dir = (-light_dir).reflect(norm);
                view_dir.dot(reflect_dir).max(0.0)
            }
            Kind::Blinn => {
                let halfway = (light_dir + view_dir).normalize();
                norm.dot(halfway).max(0.0)
            }
        };
        let spec = if norm.dot(light_dir) > 0.0 {
            spec_base.powf(shininess)
        } else {
            0.0
        };
        let distance = (LIGHT_POS - p[i]).length();
        let attenuation = 1.0 / (ATT.0 + ATT.1 * distance + ATT.2 * distance * distance);
        let ambient = LA * KA;
        let diffuse = LD * diff * KD;
        let specular = LS * spec * KS;
        out[i] = (ambient + diffuse + specular) * attenuation;
    }
}

fn light() -> PointLight {
    PointLight::try_new(
        LIGHT_POS,
        Attenuation::try_polynomial(ATT.0, ATT.1, ATT.2).unwrap(),
        LightColors::try_new(LA, LD, LS).unwrap(),
    )
    .unwrap()
}

/// The benches' scene around `lights`: no scene ambient, the viewer at `VIEW_POS`.
fn scene(lights: &[PointLight]) -> Scene<'_, PointLight> {
    Scene {
        lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    }
}

/// The points as staggered SoA arrays for the batch path.
fn soa_of(p: &[Vec3], nn: &[Vec3]) -> Soa {
    let mut soa = Soa::new(p.len());
    soa.fill(p, nn);
    soa
}

fn material(shininess: f32) -> Material {
    Material::try_new(KA, KD, KS, shininess).unwrap()
}

/// The crate's models, configured like `naive_glam`: step gate, classic lobes, automatic pow.
fn phong_model(pow: PowStrategy) -> Phong {
    Phong {
        pow,
        ..Phong::default()
    }
}
fn blinn_model(pow: PowStrategy) -> BlinnPhong {
    BlinnPhong {
        pow,
        ..BlinnPhong::default()
    }
}

/// The README's per-point API as its quick start writes it: the scene built around its light where
/// the points are shaded, a shader prepared once from the model's defaults, then each point.
///
/// The compiler sees here what it sees in `naive_glam`: one light and the model (there written
/// into the code, here `M::default()`); the light's values and the material arrive at run time
/// on both sides. `OPAQUE` passes each point through `black_box`, so the compiler cannot vectorise
/// across points: one point per call, as a recursive ray tracer or a per-pixel callback shades
/// (`scalar_opaque`). `LONE` takes the shader's form for one point per call
/// ([`phong::Shader::one_at_a_time`], `scalar_lone`).
#[inline(never)]
fn shader_loop<M: phong::ReflectionModel + Default, const OPAQUE: bool, const LONE: bool>(
    light: &PointLight,
    mat: &Material,
    p: &[Vec3],
    n: &[Vec3],
    out: &mut [Vec3],
) {
    let lights = [*light];
    let shader = phong::Shader::new(M::default(), mat, &scene(&lights));
    let shader = if LONE { shader.one_at_a_time() } else { shader };
    for i in 0..p.len() {
        let q = if OPAQUE { black_box(p[i]) } else { p[i] };
        out[i] = shader.shade(q, n[i]).total();
    }
}

/// A per-point row's loop: light, material, positions, normals, output.
type PerPointLoop = fn(&PointLight, &Material, &[Vec3], &[Vec3], &mut [Vec3]);

/// The per-point rows of a group, each with its instance of [`shader_loop`].
fn per_point_rows<M: phong::ReflectionModel + Default>() -> [(&'static str, PerPointLoop); 3] {
    [
        ("scalar", shader_loop::<M, false, false>),
        ("scalar_opaque", shader_loop::<M, true, false>),
        ("scalar_lone", shader_loop::<M, true, true>),
    ]
}

#[inline(never)]
fn scalar_loop<M: phong::ReflectionModel>(
    model: &M,
    mat: &Material,
    scene: &Scene<'_, PointLight>,
    p: &[Vec3],
    n: &[Vec3],
    out: &mut [Vec3],
) {
    for i in 0..p.len() {
        out[i] = phong::shade(model, mat, scene, p[i], n[i]).total();
    }
}

fn batch_run<M: phong::BatchModel>(
    level: Level,
    model: &M,
    mat: &Material,
    scene: &Scene<'_, PointLight>,
    soa: &mut Soa,
) {
    let (pos, nor, out) = soa.split();
    phong::shade_batch_with_level(level, model, mat, scene, pos, nor, out).unwrap();
}

fn soa_out(soa: &Soa, i: usize) -> Vec3 {
    Vec3::new(soa.arr(6)[i], soa.arr(7)[i], soa.arr(8)[i])
}

/// `|a − b| ≤ 1e-4 + 1e-4·|b|` per channel: the pow strategies' and inverse norms' error on
/// outputs of order 1, with room for f32 rounding in the different operation orders.
fn assert_close(what: &str, a: Vec3, b: Vec3, i: usize) {
    let tol = Vec3::splat(1e-4) + b.abs() * 1e-4;
    assert!(
        (a - b).abs().cmple(tol).all(),
        "{what} disagrees with naive_glam at point {i}: {a} vs {b}"
    );
}

/// One model's group: `kind` picks `naive_glam`'s lobe, `model_with` the crate's model with a
/// pow strategy (the per-point rows use `M::default()`, as the quick start does).
fn group<M: phong::ReflectionModel + phong::BatchModel + Default>(
    c: &mut Criterion,
    name: &str,
    kind: Kind,
    n: usize,
    model_with: fn(PowStrategy) -> M,
) {
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let (m32, m20) = (material(32.0), material(20.5));
    let mut soa = soa_of(&p, &nn);
    let mut naive = vec![Vec3::ZERO; n];
    let mut scalar = vec![Vec3::ZERO; n];
    let level = Level::detect();

    // Agreement on the same inputs, before any timing.
    let check = |soa: &mut Soa, scalar: &mut Vec<Vec3>, naive: &mut Vec<Vec3>, s: f32| {
        let m = material(s);
        naive_glam(kind, s, &p, &nn, naive);
        for (row, run) in per_point_rows::<M>() {
            run(&lights[0], &m, &p, &nn, scalar);
            for i in 0..n {
                assert_close(row, scalar[i], naive[i], i);
            }
        }
        scalar_loop(&M::default(), &m, &scene, &p, &nn, scalar);
        batch_run(level, &model_with(PowStrategy::Auto), &m, &scene, soa);
        for i in 0..n {
            assert_close("shade", scalar[i], naive[i], i);
            assert_close("batch", soa_out(soa, i), naive[i], i);
        }
    };
    check(&mut soa, &mut scalar, &mut naive, 20.5);
    check(&mut soa, &mut scalar, &mut naive, 32.0);

    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(n as u64));
    if n > 100_000 {
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
    } else {
        g.warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
    }
    g.bench_function("naive_glam", |b| {
        b.iter(|| naive_glam(kind, 32.0, black_box(&p), black_box(&nn), &mut naive))
    });
    let model = model_with(PowStrategy::Auto);
    for (row, run) in per_point_rows::<M>() {
        g.bench_function(row, |b| {
            b.iter(|| run(black_box(&lights[0]), &m32, black_box(&p), &nn, &mut scalar))
        });
    }
    g.bench_function("shade", |b| {
        b.iter(|| {
            scalar_loop(
                black_box(&M::default()),
                &m32,
                &scene,
                black_box(&p),
                &nn,
                &mut scalar,
            )
        })
    });
    g.bench_function("batch", |b| {
        b.iter(|| batch_run(level, black_box(&model), &m32, &scene, &mut soa))
    });
    g.bench_function("batch_frac", |b| {
        b.iter(|| batch_run(level, black_box(&model), &m20, &scene, &mut soa))
    });
    g.finish();

    // The same `scalar` ÷ `naive_glam`, timed in alternation within each sample (`paired_4096`).
    if n <= 100_000 {
        let mut pc = paired_ratio::criterion();
        let mut pg = pc.benchmark_group("paired_4096");
        let (model_name, _) = name.split_once('_').unwrap_or((name, ""));
        let scalar_loop = per_point_rows::<M>()[0].1;
        pg.bench_function(format!("{model_name}_scalar_over_naive_glam"), |b| {
            b.iter_custom(|iters| {
                paired_ratio::ratio(
                    iters,
                    &mut (&mut scalar, &mut naive),
                    |(out, _)| scalar_loop(black_box(&lights[0]), &m32, black_box(&p), &nn, out),
                    |(_, out)| naive_glam(kind, 32.0, black_box(&p), black_box(&nn), out),
                )
            })
        });
        pg.finish();
    }
}

fn phong_4096(c: &mut Criterion) {
    group(c, "phong_4096", Kind::Phong, 4096, phong_model);
}
fn blinn_4096(c: &mut Criterion) {
    group(c, "blinn_4096", Kind::Blinn, 4096, blinn_model);
}
fn phong_1m(c: &mut Criterion) {
    group(c, "phong_1m", Kind::Phong, 1 << 20, phong_model);
}
fn blinn_1m(c: &mut Criterion) {
    group(c, "blinn_1m", Kind::Blinn, 1 << 20, blinn_model);
}

/// Every pow strategy in the batch path, both models, at s = 32 and s = 20.5 (N = 4096).
fn pow_4096(c: &mut Criterion) {
    let n = 4096;
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let mut soa = soa_of(&p, &nn);
    let level = Level::detect();
    let mut g = c.benchmark_group("pow_4096");
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500));
    for s in [32.0f32, 20.5] {
        let m = material(s);
        for pow in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let id = format!("{}/{}", pow.name(), s);
            let (pm, bm) = (phong_model(pow), blinn_model(pow));
            g.bench_function(BenchmarkId::new("phong", &id), |b| {
                b.iter(|| batch_run(level, black_box(&pm), &m, &scene, &mut soa))
            });
            g.bench_function(BenchmarkId::new("blinn", &id), |b| {
                b.iter(|| batch_run(level, black_box(&bm), &m, &scene, &mut soa))
            });
        }
    }
    g.finish();
}

/// The batch path forced to each dispatch level this CPU runs (N = 4096, s = 32 and 20.5).
fn levels_4096(c: &mut Criterion) {
    let n = 4096;
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let mut soa = soa_of(&p, &nn);
    let mut g = c.benchmark_group("levels_4096");
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500));
    for level in Level::supported() {
        for s in [32.0f32, 20.5] {
            let m = material(s);
            let (pm, bm) = (
                phong_model(PowStrategy::Auto),
                blinn_model(PowStrategy::Auto),
            );
            let id = format!("{}/{}", level.name(), s);
            g.bench_function(BenchmarkId::new("phong", &id), |b| {
                b.iter(|| batch_run(level, black_box(&pm), &m, &scene, &mut soa))
            });
            g.bench_function(BenchmarkId::new("blinn", &id), |b| {
                b.iter(|| batch_run(level, black_box(&bm), &m, &scene, &mut soa))
            });
        }
    }
    g.finish();

    // The levels' ratios of the targets, each pair timed in alternation within each sample
    // (`paired_4096`): `levels_<subject>_over_<baseline>/<model>/<s>`.
    let supported: Vec<Level> = Level::supported().collect();
    let pairs = [
        (Level::Avx2, Level::Avx512),
        (Level::Sse2, Level::Avx512),
        (Level::Sse2, Level::Portable),
    ];
    let mut pc = paired_ratio::criterion();
    let mut pg = pc.benchmark_group("paired_4096");
    for (subject, baseline) in pairs {
        if !(supported.contains(&subject) && supported.contains(&baseline)) {
            continue;
        }
        for s in [32.0f32, 20.5] {
            let m = material(s);
            let (pm, bm) = (
                phong_model(PowStrategy::Auto),
                blinn_model(PowStrategy::Auto),
            );
            let id = format!("levels_{}_over_{}", subject.name(), baseline.name());
            let levels = (subject, baseline);
            let phong_id = BenchmarkId::new(id.clone(), format!("phong/{s}"));
            paired_levels(&mut pg, phong_id, levels, &pm, &m, &scene, &mut soa);
            let blinn_id = BenchmarkId::new(id, format!("blinn/{s}"));
            paired_levels(&mut pg, blinn_id, levels, &bm, &m, &scene, &mut soa);
        }
    }
    pg.finish();
}

/// One `paired_4096` row: `model` shaded at the `subject` level ÷ at the `baseline` level.
#[allow(
    clippy::too_many_arguments,
    reason = "the row's group and name, the two levels, and the call's inputs"
)]
fn paired_levels<M: phong::BatchModel>(
    pg: &mut criterion::BenchmarkGroup<'_, paired_ratio::PairedRatio>,
    id: BenchmarkId,
    (subject, baseline): (Level, Level),
    model: &M,
    m: &Material,
    scene: &Scene<'_, PointLight>,
    soa: &mut Soa,
) {
    pg.bench_function(id, |b| {
        b.iter_custom(|iters| {
            paired_ratio::ratio(
                iters,
                soa,
                |soa| batch_run(subject, black_box(model), m, scene, soa),
                |soa| batch_run(baseline, black_box(model), m, scene, soa),
            )
        })
    });
}

/// The batch module's "Many cores" recipe: 2²⁰ points shaded by one call, and cut into one part
/// per core shaded on scoped threads (the output is bit-identical: tests/batch_parallel.rs).
fn parallel_1m(c: &mut Criterion) {
    let n = 1 << 20;
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let m = material(32.0);
    let model = Phong::default();
    let col = |v: &[Vec3], k: usize| v.iter().map(|q| q[k]).collect::<Vec<f32>>();
    let (px, py, pz) = (col(&p, 0), col(&p, 1), col(&p, 2));
    let (nx, ny, nz) = (col(&nn, 0), col(&nn, 1), col(&nn, 2));
    let (mut r, mut g, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    let mut group = c.benchmark_group("parallel_1m");
    group
        .throughput(Throughput::Elements(n as u64))
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("serial", |bch| {
        bch.iter(|| {
            phong::shade_batch(
                black_box(&model),
                &m,
                &scene,
                SoaVec3::new(&px, &py, &pz),
                SoaVec3::new(&nx, &ny, &nz),
                SoaRgb::new(&mut r, &mut g, &mut b),
            )
        })
    });
    group.bench_function("threads", |bch| {
        bch.iter(|| {
            let part = n.div_ceil(threads);
            std::thread::scope(|s| {
                let outs = r
                    .chunks_mut(part)
                    .zip(g.chunks_mut(part))
                    .zip(b.chunks_mut(part));
                for (k, ((r, g), b)) in outs.enumerate() {
                    let (lo, hi) = (k * part, (k * part + part).min(n));
                    let positions = SoaVec3::new(&px[lo..hi], &py[lo..hi], &pz[lo..hi]);
                    let normals = SoaVec3::new(&nx[lo..hi], &ny[lo..hi], &nz[lo..hi]);
                    let (model, m, scene) = (&model, &m, &scene);
                    s.spawn(move || {
                        phong::shade_batch(
                            black_box(model),
                            m,
                            scene,
                            positions,
                            normals,
                            SoaRgb::new(r, g, b),
                        )
                    });
                }
            })
        })
    });
    // 8-bit RGBA output moves 4 bytes per point instead of 12: serial and on threads.
    let mut frame = vec![[0u8; 4]; n];
    group.bench_function("serial_rgba8", |bch| {
        bch.iter(|| {
            phong::shade_batch_rgba8(
                black_box(&model),
                &m,
                &scene,
                SoaVec3::new(&px, &py, &pz),
                SoaVec3::new(&nx, &ny, &nz),
                &mut frame,
            )
        })
    });
    group.bench_function("threads_rgba8", |bch| {
        bch.iter(|| {
            let part = n.div_ceil(threads);
            std::thread::scope(|s| {
                for (k, out) in frame.chunks_mut(part).enumerate() {
                    let (lo, hi) = (k * part, (k * part + part).min(n));
                    let positions = SoaVec3::new(&px[lo..hi], &py[lo..hi], &pz[lo..hi]);
                    let normals = SoaVec3::new(&nx[lo..hi], &ny[lo..hi], &nz[lo..hi]);
                    let (model, m, scene) = (&model, &m, &scene);
                    s.spawn(move || {
                        phong::shade_batch_rgba8(
                            black_box(model),
                            m,
                            scene,
                            positions,
                            normals,
                            out,
                        )
                    });
                }
            })
        })
    });
    group.finish();
}

/// 8-bit output: `linear_to_srgb8` (a search over the level thresholds) against the same levels
/// computed through `srgb_encode` (`powf`) and `quantize_u8`, over 4096 shaded colours.
fn srgb8_4096(c: &mut Criterion) {
    let n = 4096;
    let mut rng = Rng::new(0x5eb8);
    let colours: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(rng.unit_f32(), rng.unit_f32(), rng.unit_f32()))
        .collect();
    let mut out = vec![[0u8; 3]; n];
    let pipeline = |c: Vec3| [c.x, c.y, c.z].map(|x| phong::quantize_u8(phong::srgb_encode(x)));
    // Before timing: the two agree except within a few ulps of a level boundary.
    let differ = colours
        .iter()
        .filter(|&&c| phong::linear_to_srgb8(c) != pipeline(c))
        .count();
    assert!(differ <= 1, "{differ} colours differ");
    let mut g = c.benchmark_group("srgb8_4096");
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("linear_to_srgb8", |b| {
        b.iter(|| {
            for (o, &c) in out.iter_mut().zip(black_box(&colours)) {
                *o = phong::linear_to_srgb8(c);
            }
        })
    });
    g.bench_function("encode_then_quantize", |b| {
        b.iter(|| {
            for (o, &c) in out.iter_mut().zip(black_box(&colours)) {
                *o = pipeline(c);
            }
        })
    });
    // A frame's worth of shading: linear `f32` output against 8-bit RGBA written directly.
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let m = material(32.0);
    let model = Phong::default();
    let mut soa = soa_of(&p, &nn);
    let mut frame = vec![[0u8; 4]; n];
    g.bench_function("batch_f32", |b| {
        b.iter(|| batch_run(Level::detect(), black_box(&model), &m, &scene, &mut soa))
    });
    g.bench_function("batch_rgba8", |b| {
        b.iter(|| {
            let (pos, nor, _) = soa.split();
            phong::shade_batch_rgba8(black_box(&model), &m, &scene, pos, nor, &mut frame)
        })
    });
    // Each level's kernel, both outputs: what the encoding costs where a gather instruction loads
    // its table (AVX2, AVX-512) and where the lanes load it one by one.
    for level in Level::supported() {
        g.bench_function(BenchmarkId::new("batch_f32", level.name()), |b| {
            b.iter(|| batch_run(level, black_box(&model), &m, &scene, &mut soa))
        });
        g.bench_function(BenchmarkId::new("batch_rgba8", level.name()), |b| {
            b.iter(|| {
                let (pos, nor, _) = soa.split();
                phong::shade_batch_rgba8_with_level(
                    level,
                    black_box(&model),
                    &m,
                    &scene,
                    pos,
                    nor,
                    &mut frame,
                )
            })
        });
    }
    g.finish();
}

/// Array-of-structs input (a G-buffer's `Vec3`s): `shade_batch_aos` against what a caller of
/// `shade_batch` writes, copying into preallocated SoA `Vec`s and the colours back.
fn aos_4096(c: &mut Criterion) {
    aos_group(c, "aos_4096", 4096);
}

/// [`aos_4096`] over a frame's worth of points (2²⁰), where the copies leave the cache.
fn aos_1m(c: &mut Criterion) {
    aos_group(c, "aos_1m", 1 << 20);
}

fn aos_group(c: &mut Criterion, name: &str, n: usize) {
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let m = material(32.0);
    let model = Phong::default();
    let mut out = vec![Vec3::ZERO; n];
    let mut soa: [Vec<f32>; 9] = core::array::from_fn(|_| vec![0.0; n]);
    let copy_soa = |soa: &mut [Vec<f32>; 9], p: &[Vec3], nn: &[Vec3], out: &mut [Vec3]| {
        let [px, py, pz, nx, ny, nz, r, g, b] = soa;
        for i in 0..p.len() {
            (px[i], py[i], pz[i]) = (p[i].x, p[i].y, p[i].z);
            (nx[i], ny[i], nz[i]) = (nn[i].x, nn[i].y, nn[i].z);
        }
        phong::shade_batch(
            &model,
            &m,
            &scene,
            SoaVec3::new(px, py, pz),
            SoaVec3::new(nx, ny, nz),
            SoaRgb::new(r, g, b),
        );
        for (i, o) in out.iter_mut().enumerate() {
            *o = Vec3::new(r[i], g[i], b[i]);
        }
    };
    let mut check = vec![Vec3::ZERO; n];
    copy_soa(&mut soa, &p, &nn, &mut check);
    phong::shade_batch_aos(&model, &m, &scene, &p, &nn, &mut out);
    assert_eq!(out, check, "shade_batch_aos agrees with shade_batch");
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    if n > 100_000 {
        g.sample_size(10);
    }
    g.bench_function("shade_batch_aos", |b| {
        b.iter(|| {
            phong::shade_batch_aos(black_box(&model), &m, &scene, black_box(&p), &nn, &mut out)
        })
    });
    // The same points as four-wide texels, read in place.
    let p4: Vec<[f32; 4]> = p.iter().map(|v| v.extend(1.0).to_array()).collect();
    let n4: Vec<[f32; 4]> = nn.iter().map(|v| v.extend(0.0).to_array()).collect();
    g.bench_function("shade_batch_aos_f32x4", |b| {
        b.iter(|| {
            phong::shade_batch_aos(black_box(&model), &m, &scene, black_box(&p4), &n4, &mut out)
        })
    });
    g.bench_function("copy_soa", |b| {
        b.iter(|| copy_soa(&mut soa, black_box(&p), &nn, &mut out))
    });
    g.finish();
}

/// `gbuffer_4096`: deferred shading of a G-buffer with a per-point surface (textured colours,
/// shininess uniform in [2, 128], fractional) and a shadow factor per point, through
/// `shade_gbuffer` into `f32`, into 8-bit RGBA and (`gbuffer_terms`) into the three terms, against `batch_frac` (the same scene and
/// points with one material of shininess 20.5, `shade_batch`); `_tinted`: the first two under a
/// light whose diffuse colour is not grey.
fn gbuffer_4096(c: &mut Criterion) {
    let n = 4096;
    let (p, nn) = points(n, 0x5eed);
    let lights = [light()];
    let scene = scene(&lights);
    let m20 = material(20.5);
    let model = phong_model(PowStrategy::Auto);
    let level = Level::detect();
    let mut soa = soa_of(&p, &nn);
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 40) as f32 / (1u64 << 24) as f32
    };
    let texel: Vec<[f32; 3]> = (0..n).map(|_| [next(), next(), next()]).collect();
    let (tr, tg, tb): (Vec<f32>, Vec<f32>, Vec<f32>) = (
        texel.iter().map(|t| t[0]).collect(),
        texel.iter().map(|t| t[1]).collect(),
        texel.iter().map(|t| t[2]).collect(),
    );
    let strength: Vec<f32> = (0..n).map(|_| next()).collect();
    let shininess: Vec<f32> = (0..n).map(|_| 2.0 + 126.0 * next()).collect();
    let shadow: Vec<f32> = (0..n)
        .map(|_| {
            let u = next();
            if u < 0.3 {
                1.0
            } else if u < 0.4 {
                next()
            } else {
                0.0
            }
        })
        .collect();
    // The same proportions in runs of 64 points (four chunks), as a shadow map's regions come:
    // a run is dark (visibility 0) with probability 0.6, lit with 0.3, and soft otherwise.
    let shadow_runs: Vec<f32> = {
        let mut v = Vec::with_capacity(n);
        while v.len() < n {
            let u = next();
            for _ in 0..64 {
                v.push(if u < 0.6 {
                    0.0
                } else if u < 0.9 {
                    1.0
                } else {
                    next()
                });
            }
        }
        v.truncate(n);
        v
    };
    // The normals again, with runs of 64 points (four chunks) turned away from the light with
    // probability 0.5, as across a lit sphere's far side: the kernel adds only the ambient part
    // of a light behind every point of a chunk.
    let far_side: Vec<Vec3> = {
        let mut v = nn.clone();
        for (run, points) in v.chunks_mut(64).enumerate() {
            if next() < 0.5 {
                continue;
            }
            for (k, normal) in points.iter_mut().enumerate() {
                let i = run * 64 + k;
                let away = -(LIGHT_POS - p[i]).normalize();
                let tilt = Vec3::new(next(), next(), next()) - Vec3::splat(0.5);
                *normal = (away + tilt - away * tilt.dot(away).min(0.0)).normalize();
            }
        }
        v
    };
    // Every array of the group carved from one buffer at staggered 4 KiB offsets, as
    // `batch_frac`'s are (`Soa`): separate `Vec`s of 16 KiB each start 16 bytes apart within a
    // page, and 4 KiB aliasing between them slows the loop.
    let stride = n + STAGGER;
    let mut arena = vec![0.0f32; 31 * stride];
    // The shadow runs' plane and then the far side's normals last, after the outputs, so the
    // other planes keep the offsets they had before these were added (their 4 KiB aliasing with
    // each other, and so their timings).
    let (arena, far_planes) = arena.split_at_mut(28 * stride);
    let (arena, runs_plane) = arena.split_at_mut(27 * stride);
    runs_plane[..n].copy_from_slice(&shadow_runs);
    let shadow_runs_s: &[f32] = &runs_plane[..n];
    for (c, plane) in far_planes.chunks_mut(stride).enumerate() {
        for (x, v) in plane.iter_mut().zip(&far_side) {
            *x = v[c];
        }
    }
    let far_plane = |c: usize| &far_planes[c * stride..c * stride + n];
    let far_normals = SoaVec3::new(far_plane(0), far_plane(1), far_plane(2));
    let (inputs, outputs) = arena.split_at_mut(13 * stride);
    let columns: [Vec<f32>; 13] = [
        p.iter().map(|v| v.x).collect(),
        p.iter().map(|v| v.y).collect(),
        p.iter().map(|v| v.z).collect(),
        nn.iter().map(|v| v.x).collect(),
        nn.iter().map(|v| v.y).collect(),
        nn.iter().map(|v| v.z).collect(),
        tr,
        tg,
        tb,
        strength,
        shininess,
        shadow,
        vec![1.0; n],
    ];
    for (k, column) in columns.iter().enumerate() {
        inputs[k * stride..k * stride + n].copy_from_slice(column);
    }
    let column = |k: usize| &inputs[k * stride..k * stride + n];
    let (px, py, pz, nx, ny, nz) = (
        column(0),
        column(1),
        column(2),
        column(3),
        column(4),
        column(5),
    );
    let (strength_s, shininess_s, shadow_s, ones) = (column(9), column(10), column(11), column(12));
    let texels = SoaVec3::new(column(6), column(7), column(8));
    let buffer = phong::GBuffer::new(SoaVec3::new(px, py, pz), SoaVec3::new(nx, ny, nz))
        .with_surface(phong::SoaSurface {
            ambient: texels,
            diffuse: texels,
            specular: SoaVec3::new(strength_s, strength_s, strength_s),
            shininess: shininess_s,
        })
        .with_visibility(shadow_s);
    let buffer_runs = buffer.with_visibility(shadow_runs_s);
    let buffer_far = phong::GBuffer {
        normals: far_normals,
        ..buffer
    };
    // The same texels as a renderer keeps them, 8-bit sRGB, decoded in the kernel: a white
    // surface whose ambient and diffuse the texel multiplies.
    let (texel_plane, outputs) = outputs.split_at_mut(stride);
    let texels8: &mut [[u8; 4]] = bytemuck::cast_slice_mut(&mut texel_plane[..n]);
    for (t8, t) in texels8.iter_mut().zip(&texel) {
        let [r, g, b] = phong::linear_to_srgb8(Vec3::from(*t));
        *t8 = [r, g, b, 255];
    }
    let texels8: &[[u8; 4]] = texels8;
    let white = SoaVec3::new(ones, ones, ones);
    let buffer8 = phong::GBuffer::new(SoaVec3::new(px, py, pz), SoaVec3::new(nx, ny, nz))
        .with_surface(phong::SoaSurface {
            ambient: white,
            diffuse: white,
            specular: SoaVec3::new(strength_s, strength_s, strength_s),
            shininess: shininess_s,
        })
        .with_albedo_srgb8(texels8)
        .with_visibility(shadow_s);
    // The outputs: three colour planes, an 8-bit frame, and the nine term planes.
    let mut planes: Vec<&mut [f32]> = outputs.chunks_mut(stride).map(|c| &mut c[..n]).collect();
    let mut terms = planes.split_off(4);
    let [r, gr, b, frame_plane] = &mut planes[..] else {
        unreachable!("four planes")
    };
    let frame: &mut [[u8; 4]] = bytemuck::cast_slice_mut(&mut frame_plane[..]);

    // Agreement before timing: the G-buffer calls against the scalar path point by point.
    let shader = phong::Shader::new(model, &m20, &scene);
    for (what, buf, vis, normals) in [
        ("gbuffer", &buffer, shadow_s, &nn),
        ("gbuffer, shadows in runs", &buffer_runs, shadow_runs_s, &nn),
        (
            "gbuffer, far sides in runs",
            &buffer_far,
            shadow_s,
            &far_side,
        ),
    ] {
        phong::shade_gbuffer(&model, &m20, &scene, buf, SoaRgb::new(r, gr, b));
        for i in 0..n {
            let surface = phong::Surface::textured(
                Vec3::from(texel[i]),
                Vec3::splat(strength_s[i]),
                shininess_s[i],
            );
            let want = shader
                .shade_surface(p[i], normals[i], &surface, [vis[i]])
                .total();
            assert_close(what, Vec3::new(r[i], gr[i], b[i]), want, i);
        }
    }

    let mut g = c.benchmark_group("gbuffer_4096");
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("batch_frac", |bch| {
        bch.iter(|| batch_run(level, black_box(&model), &m20, &scene, &mut soa))
    });
    // The scene's light is grey (LearnOpenGL's), which lets the kernel keep one sum per term;
    // the same calls under a tinted light keep three (`_tinted`).
    let tinted_lights = [PointLight::try_new(
        LIGHT_POS,
        Attenuation::try_polynomial(ATT.0, ATT.1, ATT.2).unwrap(),
        LightColors::try_new(LA, LD * Vec3::new(1.0, 0.9, 0.8), LS).unwrap(),
    )
    .unwrap()];
    let tinted = Scene {
        lights: &tinted_lights,
        ..scene
    };
    for (suffix, sc) in [("", &scene), ("_tinted", &tinted)] {
        g.bench_function(format!("gbuffer_f32{suffix}"), |bch| {
            bch.iter(|| {
                phong::shade_gbuffer(
                    black_box(&model),
                    &m20,
                    sc,
                    black_box(&buffer),
                    SoaRgb::new(r, gr, b),
                )
            })
        });
        g.bench_function(format!("gbuffer_rgba8{suffix}"), |bch| {
            bch.iter(|| {
                phong::shade_gbuffer_rgba8(black_box(&model), &m20, sc, black_box(&buffer), frame)
            })
        });
    }
    g.bench_function("gbuffer_terms", |bch| {
        bch.iter(|| {
            let [ar, ag, ab, dr, dg, db, sr, sg, sb] = &mut terms[..] else {
                unreachable!("nine slices")
            };
            phong::shade_gbuffer_terms(
                black_box(&model),
                &m20,
                &scene,
                black_box(&buffer),
                phong::SoaTerms::new(
                    SoaRgb::new(ar, ag, ab),
                    SoaRgb::new(dr, dg, db),
                    SoaRgb::new(sr, sg, sb),
                ),
            )
        })
    });
    g.bench_function("gbuffer_albedo8_rgba8", |bch| {
        bch.iter(|| {
            phong::shade_gbuffer_rgba8(black_box(&model), &m20, &scene, black_box(&buffer8), frame)
        })
    });
    // `gbuffer_rgba8` with its shadows in runs (`shadow_runs`): the kernel adds only the ambient
    // part of a light that is dark across a whole chunk.
    g.bench_function("gbuffer_rgba8_shadow_runs", |bch| {
        bch.iter(|| {
            phong::shade_gbuffer_rgba8(
                black_box(&model),
                &m20,
                &scene,
                black_box(&buffer_runs),
                frame,
            )
        })
    });
    // `gbuffer_rgba8` with half its normals turned away from the light in runs
    // (`far_side`): the kernel adds only the ambient part of a light behind a whole chunk.
    g.bench_function("gbuffer_rgba8_far_side_runs", |bch| {
        bch.iter(|| {
            phong::shade_gbuffer_rgba8(
                black_box(&model),
                &m20,
                &scene,
                black_box(&buffer_far),
                frame,
            )
        })
    });
    g.finish();

    // The two 8-bit rows ÷ `batch_frac`, each pair timed in alternation within each sample
    // (`paired_4096`).
    let mut pc = paired_ratio::criterion();
    let mut pg = pc.benchmark_group("paired_4096");
    for (row, buf) in [
        ("gbuffer_rgba8", &buffer),
        ("gbuffer_albedo8_rgba8", &buffer8),
    ] {
        pg.bench_function(format!("{row}_over_batch_frac"), |bch| {
            bch.iter_custom(|iters| {
                paired_ratio::ratio(
                    iters,
                    &mut (&mut *frame, &mut soa),
                    |(frame, _)| {
                        phong::shade_gbuffer_rgba8(
                            black_box(&model),
                            &m20,
                            &scene,
                            black_box(buf),
                            frame,
                        );
                    },
                    |(_, soa)| batch_run(level, black_box(&model), &m20, &scene, soa),
                )
            })
        });
    }
    pg.finish();
}

/// Spot lights and falloffs other than the polynomial one, which the batch kernel evaluates per
/// lane by the scalar formulas (a spot cone with a fractional exponent: `powf` per lane): the
/// batch against `shade` point by point, which is how a call with such a light was shaded before
/// the kernel took them (N = 4096, Phong, s = 32).
fn falloff_4096(c: &mut Criterion) {
    let n = 4096;
    let (p, nn) = points(n, 0x5eed);
    let colors = LightColors::try_new(LA, LD, LS).unwrap();
    let lights = [
        phong::Light::from(
            phong::SpotLight::try_with_cone(
                LIGHT_POS,
                -LIGHT_POS,
                phong::SpotCone::degrees(60.0).with_exponent(4.5),
                Attenuation::try_inverse_square(4.0).unwrap(),
                colors,
            )
            .unwrap(),
        ),
        phong::Light::from(
            PointLight::try_new(
                Vec3::new(-1.0, 2.0, 1.0),
                Attenuation::try_unreal(6.0).unwrap(),
                colors,
            )
            .unwrap(),
        ),
    ];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let m = material(32.0);
    let model = Phong::default();
    let mut soa = soa_of(&p, &nn);
    let mut scalar = vec![Vec3::ZERO; n];
    let shade_all = |out: &mut [Vec3]| {
        for i in 0..n {
            out[i] = phong::shade(&model, &m, &scene, p[i], nn[i]).total();
        }
    };
    let level = Level::detect();
    let batch = |soa: &mut Soa| {
        let (pos, nor, out) = soa.split();
        phong::shade_batch_with_level(level, &model, &m, &scene, pos, nor, out).unwrap();
    };
    shade_all(&mut scalar);
    batch(&mut soa);
    for (i, &want) in scalar.iter().enumerate() {
        let tol = Vec3::splat(1e-4) + want.abs() * 1e-4;
        assert!(
            (soa_out(&soa, i) - want).abs().cmple(tol).all(),
            "batch disagrees with shade at point {i}"
        );
    }
    let mut g = c.benchmark_group("falloff_4096");
    g.throughput(Throughput::Elements(n as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("batch", |b| b.iter(|| batch(black_box(&mut soa))));
    g.bench_function("shade", |b| b.iter(|| shade_all(black_box(&mut scalar))));
    g.finish();
}

/// 64 lights over a 256 × 128 G-buffer (a bumpy 128 × 64 floor, lights scattered 2 above it with
/// LearnOpenGL's falloff 1/(1 + 0.7d + 1.8d²), which falls below 1e-3 at d ≈ 23): every light at
/// every pixel (`shade_gbuffer`) against 16 × 16 tiles shaded with the lights whose factor
/// reaches 1e-3 in the tile (`shade_gbuffer_tiled`).
fn tiled_64_lights(c: &mut Criterion) {
    let (width, height) = (256usize, 128usize);
    let n = width * height;
    let mut rng = Rng::new(0x7113);
    let (mut p, mut nn) = ([vec![], vec![], vec![]], [vec![], vec![], vec![]]);
    for y in 0..height {
        for x in 0..width {
            let (fx, fy) = (x as f32 * 0.5, y as f32 * 0.5);
            let q = Vec3::new(fx, fy, 0.2 * (fx * 1.3).sin() * (fy * 0.7).cos());
            let nq = Vec3::new(rng.range_f32(-0.3, 0.3), rng.range_f32(-0.3, 0.3), 1.0).normalize();
            for k in 0..3 {
                p[k].push(q[k]);
                nn[k].push(nq[k]);
            }
        }
    }
    let lights: Vec<PointLight> = (0..64)
        .map(|_| {
            PointLight::try_new(
                Vec3::new(rng.range_f32(0.0, 128.0), rng.range_f32(0.0, 64.0), 2.0),
                Attenuation::try_polynomial(1.0, 0.7, 1.8).unwrap(),
                LightColors::try_new(Vec3::splat(0.01), Vec3::splat(0.5), Vec3::splat(0.5))
                    .unwrap(),
            )
            .unwrap()
        })
        .collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(64.0, -30.0, 45.0)),
    };
    let m = material(32.0);
    let model = Phong::default();
    let g = phong::GBuffer::new(
        SoaVec3::new(&p[0], &p[1], &p[2]),
        SoaVec3::new(&nn[0], &nn[1], &nn[2]),
    );
    let culling = phong::TileCulling {
        width,
        tile: 16,
        threshold: 1e-3,
    };
    let mut scratch = lights.clone();
    let (mut r, mut gr, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut group = c.benchmark_group("tiled_64_lights");
    group
        .throughput(Throughput::Elements(n as u64))
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("gbuffer", |bch| {
        bch.iter(|| {
            phong::shade_gbuffer(
                black_box(&model),
                &m,
                &scene,
                &g,
                SoaRgb::new(&mut r, &mut gr, &mut b),
            )
        })
    });
    group.bench_function("tiled", |bch| {
        bch.iter(|| {
            phong::shade_gbuffer_tiled(
                black_box(&model),
                &m,
                &scene,
                &g,
                culling,
                &mut scratch,
                SoaRgb::new(&mut r, &mut gr, &mut b),
            )
        })
    });
    group.finish();
}

criterion_group!(
    benches,
    phong_4096,
    blinn_4096,
    phong_1m,
    blinn_1m,
    pow_4096,
    levels_4096,
    parallel_1m,
    srgb8_4096,
    aos_4096,
    aos_1m,
    gbuffer_4096,
    falloff_4096,
    tiled_64_lights
);
criterion_main!(benches);
