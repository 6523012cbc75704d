//! Shades the benches' 4096 points a given number of times through one batch entry point at one
//! dispatch level, for counting executed instructions with an emulator or valgrind, where
//! timings mean nothing (`scripts/count-instructions.sh` runs it).
//!
//! ```text
//! shade_loop <form> <level> <calls>
//!   form:  batch | gbuffer_f32 | gbuffer_rgba8 | gbuffer_albedo8_rgba8
//!   level: a name from `Level::supported()` (portable, sse2, avx2, avx512, neon)
//! ```
//!
//! `batch` is `shade_batch` with the benches' Phong material at s = 20.5 (`batch_frac`); the
//! G-buffer forms are `gbuffer_4096`'s rows: a per-point surface with non-integer shininess in
//! [2, 128], a shadow factor per point, and `f32` or RGBA8 output, or RGBA8 with the albedo as
//! 8-bit sRGB texels. The difference between two call counts is the calls' own work.

use std::hint::black_box;
use std::process::ExitCode;

use glam::Vec3;
use phong::{
    Attenuation, GBuffer, Level, LightColors, Material, Phong, PointLight, Scene, SoaRgb,
    SoaSurface, SoaVec3, Viewer,
};
use phong_tools::bench_scene::{ATT, KA, KD, KS, LA, LD, LIGHT_POS, LS, VIEW_POS, points};

const N: usize = 4096;

/// The surface's values: uniform in `[0, 1)` from a xorshift generator.
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn many(&mut self, f: impl Fn(f32) -> f32) -> Vec<f32> {
        (0..N).map(|_| f(self.next())).collect()
    }
}

fn column(v: &[Vec3], k: usize) -> Vec<f32> {
    v.iter().map(|p| p[k]).collect()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let (Some(form), Some(level), Some(calls)) = (args.get(1), args.get(2), args.get(3)) else {
        eprintln!("usage: shade_loop <form> <level> <calls>");
        return ExitCode::FAILURE;
    };
    let Some(level) = Level::supported()
        .into_iter()
        .find(|l| l.name() == level.as_str())
    else {
        eprintln!("level {level} is not supported here");
        return ExitCode::FAILURE;
    };
    let Ok(calls) = calls.parse::<usize>() else {
        eprintln!("calls: {calls} is not a count");
        return ExitCode::FAILURE;
    };

    let (p, n) = points(N, 0x5eed);
    let (px, py, pz) = (column(&p, 0), column(&p, 1), column(&p, 2));
    let (nx, ny, nz) = (column(&n, 0), column(&n, 1), column(&n, 2));
    let lights = [PointLight::try_new(
        LIGHT_POS,
        Attenuation::try_polynomial(ATT.0, ATT.1, ATT.2).expect("the benches' falloff"),
        LightColors::try_new(LA, LD, LS).expect("the benches' colours"),
    )
    .expect("the benches' light")];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let material = Material::try_new(KA, KD, KS, 20.5).expect("the benches' material");
    let model = Phong::default();

    let mut rng = Uniform(0x2545_f491_4f6c_dd1d);
    let (tr, tg, tb) = (rng.many(|u| u), rng.many(|u| u), rng.many(|u| u));
    let strength = rng.many(|u| u);
    let shininess = rng.many(|u| 2.0 + 126.0 * u);
    // A filtered shadow map: mostly lit or mostly shadowed, soft at the edges.
    let shadow = rng.many(|u| {
        if u < 0.3 {
            1.0
        } else if u < 0.4 {
            u * 10.0 - 3.0
        } else {
            0.0
        }
    });
    let ones = vec![1.0; N];
    let texels: Vec<[u8; 4]> = (0..N)
        .map(|i| {
            let [r, g, b] = phong::linear_to_srgb8(Vec3::new(tr[i], tg[i], tb[i]));
            [r, g, b, 255]
        })
        .collect();
    let positions = SoaVec3::new(&px, &py, &pz);
    let normals = SoaVec3::new(&nx, &ny, &nz);
    let specular = SoaVec3::new(&strength, &strength, &strength);
    let surface = |albedo| SoaSurface {
        ambient: albedo,
        diffuse: albedo,
        specular,
        shininess: &shininess,
    };
    let textured = GBuffer::new(positions, normals)
        .with_surface(surface(SoaVec3::new(&tr, &tg, &tb)))
        .with_visibility(&shadow);
    let albedo8 = GBuffer::new(positions, normals)
        .with_surface(surface(SoaVec3::new(&ones, &ones, &ones)))
        .with_albedo_srgb8(&texels)
        .with_visibility(&shadow);

    let (mut r, mut g, mut b) = (vec![0.0; N], vec![0.0; N], vec![0.0; N]);
    let mut frame = vec![[0u8; 4]; N];
    let mut shaded = 0;
    for _ in 0..calls {
        let out = SoaRgb::new(&mut r, &mut g, &mut b);
        let model = black_box(&model);
        shaded += match form.as_str() {
            "batch" => phong::shade_batch_with_level(
                level, model, &material, &scene, positions, normals, out,
            ),
            "gbuffer_f32" => {
                phong::shade_gbuffer_with_level(level, model, &material, &scene, &textured, out)
            }
            "gbuffer_rgba8" => phong::shade_gbuffer_rgba8_with_level(
                level, model, &material, &scene, &textured, &mut frame,
            ),
            "gbuffer_albedo8_rgba8" => phong::shade_gbuffer_rgba8_with_level(
                level, model, &material, &scene, &albedo8, &mut frame,
            ),
            other => {
                eprintln!("unknown form {other}");
                return ExitCode::FAILURE;
            }
        }
        .expect("a supported level");
    }
    // Read the outputs, so no call is dropped as unused.
    println!(
        "{shaded} points shaded; checksum {}",
        r.iter().sum::<f32>() + frame.iter().map(|p| f32::from(p[1])).sum::<f32>()
    );
    ExitCode::SUCCESS
}
