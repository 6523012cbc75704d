//! The rasterizer's frame in `phong`'s shapes: a 400×400 per-pixel frame of a lit sphere (the
//! explorer's frame), `raster_frame` in docs/performance.md.
//!
//! - `batch`: [`PhongShader`], which shades a draw's visible pixels through
//!   `phong::shade_gbuffer`;
//! - `point`: the same shader seen only through `shade`, one `phong::shade` per pixel.
//!
//! Both pictures are compared before timing. Run: `cargo bench -p raster`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use phong::{Attenuation, LightColors, Material, PointLight, Scene};
use raster::{Camera, Framebuffer, Mesh, PhongShader, ShadingMode, SurfaceShader, draw};

/// The light of `phong`'s `fragment` bench (benches/renderers.rs): LearnOpenGL's point light
/// with the 50-unit attenuation.
fn light() -> PointLight {
    PointLight::try_new(
        Vec3::new(1.2, 2.0, 2.0),
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        LightColors::try_new(Vec3::splat(0.15), Vec3::splat(0.8), Vec3::ONE).unwrap(),
    )
    .unwrap()
}

/// `raster`'s `PhongShader` seen only through `shade`: the trait's default `shade_many`, one
/// `phong::shade` per pixel.
struct PointByPoint<'a>(&'a PhongShader<'a>);

impl SurfaceShader for PointByPoint<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, uv: glam::Vec2) -> Vec3 {
        self.0.shade(position, normal, uv)
    }
}

/// One per-pixel draw of `mesh` into `fb`.
fn draw_frame<S: SurfaceShader>(fb: &mut Framebuffer, camera: &Camera, mesh: &Mesh, shader: &S) {
    let mode = ShadingMode::PerPixel;
    draw(fb, camera, mesh, glam::Mat4::IDENTITY, shader, mode);
}

fn raster_frame(c: &mut Criterion) {
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let lights = [phong::Light::from(light())];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: phong::Viewer::At(eye),
    };
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0).unwrap();
    let shader = PhongShader::new(phong::Phong::default(), m, scene);
    let (mesh, camera) = (Mesh::icosphere(4), Camera::look_at(eye, Vec3::ZERO));
    let frame = |s: &dyn Fn(&mut Framebuffer)| {
        let mut fb = Framebuffer::new(400, 400, Vec3::ZERO);
        s(&mut fb);
        fb
    };
    let batch = |fb: &mut Framebuffer| draw_frame(fb, &camera, &mesh, &shader);
    let point = |fb: &mut Framebuffer| draw_frame(fb, &camera, &mesh, &PointByPoint(&shader));
    let (a, b) = (frame(&batch), frame(&point));
    // The batch's documented accuracy (`phong::batch`): every cosine within η = 2e-6 and the
    // factor within 2e-6 relative, so a lobe `x^s` moves by at most `s·η`: with s = 32 and the
    // light's diffuse 0.8 and specular 1, per channel at most (32 + 1)·2e-6·1.8 ≈ 1.2e-4.
    let diff = a.max_difference(&b);
    assert!(
        diff <= 1.2e-4,
        "batch and point-by-point frames differ by {diff:e}"
    );

    let mut g = c.benchmark_group("raster_frame");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(30);
    g.bench_function("batch", |bch| bch.iter(|| black_box(frame(&batch))));
    g.bench_function("point", |bch| bch.iter(|| black_box(frame(&point))));
    g.finish();
}

criterion_group!(benches, raster_frame);
criterion_main!(benches);
