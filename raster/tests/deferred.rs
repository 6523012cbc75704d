//! Deferred per-pixel shading: the rasterizer shades each visible pixel once, at the end of a
//! draw, through `SurfaceShader::shade_many`, and `PhongShader` answers that through the crate's
//! batch path. Both must give the picture that shading each pixel with `phong::shade` gives.

use std::cell::Cell;

use glam::{Mat4, Vec2, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Light, LightColors, Material, Model, Phong,
    PointLight, Scene, SpotLight, Viewer,
};
use raster::{Camera, Framebuffer, Mesh, PhongShader, ShadingMode, SurfaceShader, draw};

/// `PhongShader` seen only through `shade`: the trait's default `shade_many`, one point at a
/// time with `phong::shade`, the reference for the batch path.
struct PointByPoint<'a>(&'a PhongShader<'a>);

impl SurfaceShader for PointByPoint<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, uv: Vec2) -> Vec3 {
        self.0.shade(position, normal, uv)
    }
}

fn colours(a: f32, d: f32, s: f32) -> LightColors {
    LightColors::try_from_strengths(Vec3::ONE, a, d, s).unwrap()
}

fn render(n: usize, mesh: &Mesh, shader: &impl SurfaceShader) -> Framebuffer {
    let camera = Camera::look_at(Vec3::new(0.3, 0.8, 3.6), Vec3::ZERO);
    let mut fb = Framebuffer::new(n, n, Vec3::ZERO);
    draw(
        &mut fb,
        &camera,
        mesh,
        Mat4::from_rotation_y(0.4),
        shader,
        ShadingMode::PerPixel,
    );
    fb
}

/// A checkerboard of two diffuse texels and two specular strengths.
fn checker(uv: Vec2) -> (Vec3, Vec3) {
    let odd = ((uv.x * 8.0).floor() + (uv.y * 8.0).floor()) as i32 % 2 != 0;
    if odd {
        (Vec3::new(0.9, 0.3, 0.1), Vec3::splat(0.8))
    } else {
        (Vec3::new(0.1, 0.4, 0.9), Vec3::splat(0.1))
    }
}

#[test]
fn the_batch_path_draws_the_point_by_point_picture() {
    let point = PointLight::try_new(
        Vec3::new(1.5, 1.0, 2.0),
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        colours(0.1, 0.9, 0.6),
    )
    .unwrap();
    let sun =
        DirectionalLight::try_new(Vec3::new(-1.0, 1.0, 0.5), colours(0.05, 0.4, 0.3)).unwrap();
    let spot = SpotLight::try_new(
        Vec3::new(0.0, 3.0, 1.0),
        -Vec3::Y,
        0.6,
        4.0,
        Attenuation::None,
        colours(0.0, 0.5, 0.5),
    )
    .unwrap();
    let kernel_lights = [Light::from(point), Light::from(sun)];
    // A spot light: the kernel evaluates its factor by the scalar formula, so the same picture.
    let with_spot = [Light::from(point), Light::from(spot)];
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 24.5).unwrap();
    let mut compared = 0;
    for lights in [&kernel_lights[..], &with_spot[..]] {
        let scene = Scene {
            lights,
            ambient: Vec3::splat(0.02),
            viewer: Viewer::At(Vec3::new(0.3, 0.8, 3.6)),
        };
        for model in [
            Model::from(Phong::default()),
            Model::from(BlinnPhong::default()),
        ] {
            for texture in [None, Some(checker as raster::Texture)] {
                for mesh in [Mesh::icosphere(3), Mesh::plane(1.2, 4)] {
                    let mut shader = PhongShader::new(model, m, scene);
                    shader.texture = texture;
                    let batch = render(64, &mesh, &shader);
                    let reference = render(64, &mesh, &PointByPoint(&shader));
                    assert!(
                        batch.triangle.iter().filter(|&&t| t != 0).count() > 400,
                        "the mesh covers the picture"
                    );
                    // The batch's documented accuracy (`phong::batch`): every cosine within
                    // η = 2e-6, the factor within 2e-6 relative, so a lobe `x^s` moves by at
                    // most `s·η`. Summed over the lights' diffuse and specular strengths (at
                    // most 0.9 + 0.6 + 0.5 + 0.5): (24.5 + 1)·2e-6·2.5 ≈ 1.3e-4 per channel,
                    // far below an 8-bit step (3.9e-3).
                    let diff = batch.max_difference(&reference);
                    assert!(
                        diff <= 1.3e-4,
                        "{model:?}, texture {}, {} lights: batch and point-by-point pictures \
                         differ by {diff:e}",
                        texture.is_some(),
                        lights.len()
                    );
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, 16);
}

/// Counts the points a shader is asked for.
struct Counting<'a> {
    inner: &'a PhongShader<'a>,
    points: Cell<usize>,
}

impl SurfaceShader for Counting<'_> {
    fn shade(&self, position: Vec3, normal: Vec3, uv: Vec2) -> Vec3 {
        self.points.set(self.points.get() + 1);
        self.inner.shade(position, normal, uv)
    }
}

#[test]
fn each_visible_pixel_is_shaded_once_after_the_depth_test() {
    // Two overlapping squares facing the eye, the far one drawn last half the time: either way
    // every covered pixel is shaded exactly once, and the overdrawn fragments are never shaded.
    let square = |z: f32| {
        [
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(1.0, -1.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(-1.0, 1.0, z),
        ]
    };
    let lights = [Light::from(
        DirectionalLight::try_new(Vec3::Z, colours(0.1, 0.8, 0.5)).unwrap(),
    )];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 4.0)),
    };
    let m = Material::try_from_color(Vec3::ONE, 16.0).unwrap();
    let shader = PhongShader::new(Phong::default(), m, scene);
    for near_first in [true, false] {
        let (a, b) = if near_first { (0.5, -0.5) } else { (-0.5, 0.5) };
        let positions: Vec<Vec3> = square(a).into_iter().chain(square(b)).collect();
        let triangles = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
        let mesh = Mesh::new(positions, vec![Vec2::ZERO; 8], triangles);
        let counting = Counting {
            inner: &shader,
            points: Cell::new(0),
        };
        let camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
        let mut fb = Framebuffer::new(40, 40, Vec3::ZERO);
        let stats = draw(
            &mut fb,
            &camera,
            &mesh,
            Mat4::IDENTITY,
            &counting,
            ShadingMode::PerPixel,
        );
        let covered = fb.triangle.iter().filter(|&&t| t != 0).count();
        assert!(covered > 100, "the squares cover the picture");
        assert_eq!(counting.points.get(), covered, "near first: {near_first}");
        assert_eq!(stats.shader_calls, covered);
        if near_first {
            assert_eq!(stats.pixels, covered, "the far square fails the depth test");
        } else {
            assert!(
                stats.pixels > covered,
                "the near square overdraws the far one"
            );
        }
    }
}
