//! What the rasterizer's pictures must show, checked on small images.

use glam::{Mat4, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Light, LightColors, Material, Model, Phong,
    PointLight, Scene, SpotLight, Viewer,
};
use raster::{Camera, Framebuffer, Image, Mesh, PhongShader, ShadingMode, Term, draw};

fn colours(a: f32, d: f32, s: f32) -> LightColors {
    LightColors::try_from_strengths(Vec3::ONE, a, d, s).unwrap()
}

fn sun(dir: Vec3) -> Light {
    DirectionalLight::try_new(dir, colours(0.1, 0.8, 0.5))
        .unwrap()
        .into()
}

fn sphere_camera() -> Camera {
    Camera::look_at(Vec3::new(0.0, 0.0, 4.2), Vec3::ZERO)
}

fn render(
    n: usize,
    camera: &Camera,
    mesh: &Mesh,
    shader: &PhongShader<'_>,
    mode: ShadingMode,
) -> Framebuffer {
    let mut fb = Framebuffer::new(n, n, Vec3::ZERO);
    draw(&mut fb, camera, mesh, Mat4::IDENTITY, shader, mode);
    fb
}

#[test]
fn images_have_no_nan_and_stay_in_range() {
    let camera = sphere_camera();
    let lights = [
        sun(Vec3::new(-1.0, 1.0, 1.0)),
        PointLight::try_new(
            Vec3::new(1.0, 0.5, 2.0),
            Attenuation::polynomial(1.0, 0.09, 0.032),
            colours(0.1, 0.8, 0.5),
        )
        .unwrap()
        .into(),
        SpotLight::try_new(
            Vec3::new(0.0, 3.0, 1.0),
            -Vec3::Y,
            0.6,
            4.0,
            Attenuation::None,
            colours(0.0, 0.5, 0.5),
        )
        .unwrap()
        .into(),
    ];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer: Viewer::At(camera.eye),
    };
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0).unwrap();
    // The largest value a channel can take: ambient + every light at full strength.
    let ceiling = 0.05 + (0.1 + 0.8 + 0.5) * 1.0 + (0.1 + 0.8 + 0.5) + (0.5 + 0.5) + 1e-4;
    for mesh in [Mesh::icosphere(2), Mesh::cube(), Mesh::plane(1.0, 3)] {
        for mode in [
            ShadingMode::PerVertex,
            ShadingMode::PerPixel,
            ShadingMode::Adaptive,
        ] {
            for model in [
                Model::from(Phong::default()),
                Model::from(BlinnPhong::default()),
            ] {
                let shader = PhongShader::new(model, m, scene);
                let fb = render(48, &camera, &mesh, &shader, mode);
                for c in &fb.color {
                    assert!(c.is_finite(), "{mode:?} {model:?}: colour {c}");
                    assert!(
                        c.min_element() >= 0.0 && c.max_element() <= ceiling,
                        "{mode:?} {model:?}: colour {c} outside [0, {ceiling}]"
                    );
                }
                for d in fb.depth.iter().filter(|d| d.is_finite()) {
                    assert!((0.0..=1.0).contains(d), "depth {d} outside [0, 1]");
                }
                let img = Image::from_linear(&fb);
                assert_eq!(img.pixels.len(), 48 * 48, "one pixel per framebuffer pixel");
            }
        }
    }
}

/// The point of the unit sphere whose mirror direction points at the eye, by fixed-point
/// iteration: `N = normalize(L + V(N))`, `V(N) = normalize(eye − N)`.
fn mirror_point(l: Vec3, eye: Vec3) -> Vec3 {
    let mut n = (l + eye.normalize()).normalize();
    for _ in 0..100 {
        n = (l + (eye - n).normalize()).normalize();
    }
    n
}

fn brightest(fb: &Framebuffer) -> (usize, usize) {
    let mut best = (0, 0, f32::NEG_INFINITY);
    for y in 0..fb.height {
        for x in 0..fb.width {
            let v = fb.at(x, y).max_element();
            if v > best.2 {
                best = (x, y, v);
            }
        }
    }
    (best.0, best.1)
}

#[test]
fn the_highlight_lies_where_the_mirror_direction_predicts() {
    let camera = sphere_camera();
    let sphere = Mesh::icosphere(5);
    let m = Material::try_from_color(Vec3::ONE, 200.0).unwrap();
    for dir in [
        Vec3::new(-1.0, 1.0, 1.0),
        Vec3::new(0.5, 0.3, 1.0),
        Vec3::new(1.0, -0.6, 0.4),
    ] {
        let l = dir.normalize();
        let lights = [sun(l)];
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer: Viewer::At(camera.eye),
        };
        let shader = PhongShader::new(Phong::default(), m, scene).with_term(Term::Specular);
        let n = 96;
        let fb = render(n, &camera, &sphere, &shader, ShadingMode::PerPixel);
        let (bx, by) = brightest(&fb);
        let p = mirror_point(l, camera.eye);
        let (px, py) = camera.project(p, n, n).expect("the highlight is in front");
        // The brightest pixel's centre is at +0.5.
        let d = ((bx as f32 + 0.5 - px).powi(2) + (by as f32 + 0.5 - py).powi(2)).sqrt();
        assert!(
            d <= 2.0,
            "light {dir}: brightest pixel ({bx}, {by}), predicted ({px:.1}, {py:.1}): {d:.2} px apart"
        );
    }
}

#[test]
fn gouraud_and_phong_agree_at_the_vertices_and_differ_inside_under_the_highlight() {
    let camera = sphere_camera();
    let sphere = Mesh::icosphere(2);
    let lights = [sun(Vec3::new(-1.0, 1.0, 1.0))];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0).unwrap();
    let shader = PhongShader::new(Phong::default(), m, scene);
    let n = 160;
    let gouraud = render(n, &camera, &sphere, &shader, ShadingMode::PerVertex);
    let phong = render(n, &camera, &sphere, &shader, ShadingMode::PerPixel);

    // At every visible vertex: the pixel whose centre is nearest agrees. The two shadings differ
    // only at second order in the distance from the vertex, at most ~0.7 px here.
    let mut checked = 0;
    let mut worst = 0.0f32;
    for (i, p) in sphere.positions.iter().enumerate() {
        let normal = sphere.normals[i];
        if normal.dot(camera.eye - *p) <= 0.2 {
            continue; // back or near the silhouette
        }
        let Some((x, y)) = camera.project(*p, n, n) else {
            continue;
        };
        let (x, y) = (x as usize, y as usize);
        if !gouraud.covered(x, y) {
            continue;
        }
        worst = worst.max((gouraud.at(x, y) - phong.at(x, y)).abs().max_element());
        checked += 1;
    }
    assert!(checked > 40, "only {checked} vertices checked");
    assert!(worst < 0.03, "Gouraud vs Phong at the vertices: {worst}");

    // Inside the triangle under the highlight they differ by far more.
    let (hx, hy) = brightest(&phong);
    let t = phong.triangle[phong.index(hx, hy)];
    let inside = (0..phong.color.len())
        .filter(|&i| phong.triangle[i] == t && gouraud.triangle[i] == t)
        .map(|i| (gouraud.color[i] - phong.color[i]).abs().max_element())
        .fold(0.0f32, f32::max);
    assert!(
        inside > 5.0 * worst.max(0.01),
        "inside the highlight's triangle: {inside}, at the vertices: {worst}"
    );
}

#[test]
fn adaptive_shading_stays_within_its_tolerance() {
    let camera = sphere_camera();
    let sphere = Mesh::icosphere(2);
    let point: Light = PointLight::try_new(
        Vec3::new(2.0, 1.5, 2.5),
        Attenuation::polynomial(1.0, 0.09, 0.032),
        colours(0.1, 0.9, 0.6),
    )
    .unwrap()
    .into();
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0).unwrap();
    for light in [
        sun(Vec3::new(-3.0, 2.0, 0.0)),
        sun(Vec3::new(1.0, 1.0, 1.0)),
        point,
    ] {
        for model in [
            Model::from(Phong::default()),
            Model::from(BlinnPhong::default()),
        ] {
            for tolerance in [0.5 / 255.0, 2.0 / 255.0, 8.0 / 255.0] {
                let lights = [light];
                let scene = Scene {
                    lights: &lights,
                    ambient: Vec3::splat(0.02),
                    viewer: Viewer::At(camera.eye),
                };
                let mut shader = PhongShader::new(model, m, scene);
                shader.tolerance = tolerance;
                let pp = render(64, &camera, &sphere, &shader, ShadingMode::PerPixel);
                let mut ad = Framebuffer::new(64, 64, Vec3::ZERO);
                let stats = draw(
                    &mut ad,
                    &camera,
                    &sphere,
                    Mat4::IDENTITY,
                    &shader,
                    ShadingMode::Adaptive,
                );
                let err = ad.max_difference(&pp);
                assert!(
                    err <= tolerance,
                    "{light:?} {model:?}: adaptive error {err} > tolerance {tolerance} \
                     ({} of {} triangles per vertex)",
                    stats.per_vertex,
                    stats.triangles
                );
            }
        }
    }
}

#[test]
fn the_default_low_poly_sphere_is_a_third_per_vertex_at_two_steps() {
    // The gallery's default: 320-face icosphere, sun toward (−3, 2, 0), coral, s = 32, Phong.
    let camera = sphere_camera();
    let sphere = Mesh::icosphere(2);
    let lights = [sun(Vec3::new(-3.0, 2.0, 0.0))];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let m = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0).unwrap();
    let shader = PhongShader::new(Phong::default(), m, scene);
    let mut ad = Framebuffer::new(64, 64, Vec3::ZERO);
    let stats = draw(
        &mut ad,
        &camera,
        &sphere,
        Mat4::IDENTITY,
        &shader,
        ShadingMode::Adaptive,
    );
    assert!(
        3 * stats.per_vertex >= stats.triangles,
        "{} of {} front triangles per vertex",
        stats.per_vertex,
        stats.triangles
    );
}

/// The height/width ratio of the pixels above half the peak.
fn highlight_aspect(fb: &Framebuffer) -> f32 {
    let peak = fb.color.iter().map(|c| c.max_element()).fold(0.0, f32::max);
    let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
    for y in 0..fb.height {
        for x in 0..fb.width {
            if fb.at(x, y).max_element() >= 0.5 * peak {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
    }
    assert!(x0 <= x1, "no highlight");
    (y1 - y0 + 1) as f32 / (x1 - x0 + 1) as f32
}

#[test]
fn at_a_grazing_angle_blinn_phong_stretches_and_phong_stays_round() {
    let camera = Camera::look_at(Vec3::new(0.0, 0.4, 0.0), Vec3::new(0.0, 0.0, -3.0));
    let e = 8f32.to_radians();
    let lights = [sun(Vec3::new(0.0, e.sin(), -e.cos()))];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let floor = Mesh::plane(40.0, 4);
    let aspect = |model: Model, s: f32| {
        let m = Material::try_from_color(Vec3::ONE, s).unwrap();
        let shader = PhongShader::new(model, m, scene).with_term(Term::Specular);
        highlight_aspect(&render(96, &camera, &floor, &shader, ShadingMode::PerPixel))
    };
    let phong = aspect(Phong::default().into(), 256.0);
    let blinn = aspect(BlinnPhong::default().into(), 1024.0);
    assert!(
        blinn > 2.0 * phong,
        "aspect (height/width): Blinn-Phong {blinn}, Phong {phong}"
    );
    assert!(
        (0.5..2.0).contains(&phong),
        "Phong's highlight should be roughly round: {phong}"
    );
}

#[test]
fn light_culling_skips_far_lights_and_changes_each_pixel_by_less_than_its_threshold() {
    let camera = Camera::look_at(Vec3::new(0.0, 8.0, 8.0), Vec3::ZERO);
    let floor = Mesh::plane(6.0, 8);
    let lights: Vec<Light> = (0..9)
        .map(|k| {
            let p = Vec3::new(
                -4.0 + 4.0 * (k % 3) as f32,
                0.5,
                -4.0 + 4.0 * (k / 3) as f32,
            );
            let att = if k % 2 == 0 {
                Attenuation::polynomial(1.0, 0.7, 1.8)
            } else {
                Attenuation::try_frostbite(2.5).unwrap()
            };
            PointLight::try_new(p, att, colours(0.05, 0.8, 0.5))
                .unwrap()
                .into()
        })
        .collect();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let m = Material::try_from_color(Vec3::splat(0.9), 16.0).unwrap();
    let threshold = 0.5 / 255.0;
    for model in [
        Model::from(Phong::default()),
        Model::from(BlinnPhong {
            normalization: phong::Normalization::Energy,
            ..BlinnPhong::default()
        }),
    ] {
        let full = PhongShader::new(model, m, scene);
        let culled = PhongShader::new(model, m, scene).with_culling(threshold);
        let a = render(48, &camera, &floor, &full, ShadingMode::PerPixel);
        let b = render(48, &camera, &floor, &culled, ShadingMode::PerPixel);
        let skipped = culled.skipped.get();
        assert!(
            skipped > culled.evaluations.get() / 4,
            "{model:?}: only {skipped} of {} skipped",
            skipped + culled.evaluations.get()
        );
        // Each skipped light is below the threshold at that pixel.
        let err = a.max_difference(&b);
        assert!(
            err <= threshold * lights.len() as f32,
            "{model:?}: culling changed a pixel by {err}"
        );
    }
}
