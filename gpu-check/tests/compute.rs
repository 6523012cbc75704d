//! `shaders/phong.wgsl`, run through wgpu, against `phong::shade` on the CPU.
//!
//! Tolerance: the shader and the crate evaluate the same formulas in f32 in the same order, except
//! that the GPU's `pow`, `inverseSqrt` and division are not correctly rounded (Mesa's `pow` error
//! is up to ~2.5e-5 relative, as measured on the Mesa vectors of the crate's tests/conformance.rs;
//! lavapipe's inverseSqrt is within a few ulps). A relative 2e-4 (`pow`'s error amplified by at most the exponent's condition, which
//! the inputs keep small) plus an absolute 1e-5 floor (values near zero after cancellation in
//! R·V) covers that, and is still ~1000× smaller than an 8-bit step.
//!
//! Needs a Vulkan adapter. `.ci/run` installs Mesa's lavapipe and sets `PHONG_REQUIRE_GPU=1`, so in
//! CI a missing adapter fails the test instead of skipping it.

use gpu_check::GpuShader;
use phong::glam::Vec3;
use phong::gpu::{GpuLight, GpuMaterial, GpuParams};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Lambert, Light, LightColors, Material, Model,
    Normalization, Phong, PointLight, Scene, SpecularGate, SpotLight, Viewer,
};

fn shader() -> Option<GpuShader> {
    let s = GpuShader::new();
    if s.is_none() {
        assert!(
            std::env::var_os("PHONG_REQUIRE_GPU").is_none(),
            "PHONG_REQUIRE_GPU is set but no Vulkan adapter was found (install mesa-vulkan-drivers)"
        );
        eprintln!(
            "no Vulkan adapter: GPU comparison skipped (set PHONG_REQUIRE_GPU=1 to require it)"
        );
    }
    s
}

fn close(a: Vec3, b: Vec3, what: &str) -> Result<(), String> {
    for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
        if !x.is_finite() || (x - y).abs() > 2e-4 * y.abs().max(x.abs()) + 1e-5 {
            return Err(format!("{what}: gpu {a} vs cpu {b}"));
        }
    }
    Ok(())
}

fn v3(j: &serde_json::Value) -> Vec3 {
    let a = j.as_array().expect("a vector is an array");
    Vec3::new(
        a[0].as_f64().unwrap() as f32,
        a[1].as_f64().unwrap() as f32,
        a[2].as_f64().unwrap() as f32,
    )
}

#[test]
fn conformance_inputs_shade_the_same_on_gpu_and_cpu() {
    let Some(gpu) = shader() else { return };
    let data = include_str!("../../tests/data/glsl_learnopengl_phong.jsonl");
    let model: Model = Phong::learnopengl().into();
    let mut failures = Vec::new();
    let mut count = 0;
    for line in data.lines() {
        let c: serde_json::Value = serde_json::from_str(line).unwrap();
        let f = |k: &str| c[k].as_f64().unwrap() as f32;
        let Ok(colors) = LightColors::try_from_strengths(
            v3(&c["light_color"]),
            f("ambient_strength"),
            f("diffuse_strength"),
            f("specular_strength"),
        ) else {
            continue;
        };
        let Ok(material) = Material::try_from_color(v3(&c["object_color"]), f("shininess")) else {
            continue;
        };
        let light: Light = PointLight::try_new(v3(&c["light_pos"]), Attenuation::None, colors)
            .unwrap()
            .into();
        let viewer = Viewer::At(v3(&c["view_pos"]));
        let (p, n) = (v3(&c["frag_pos"]), v3(&c["normal"]));
        let scene = Scene {
            lights: &[light],
            ambient: Vec3::ZERO,
            viewer,
        };
        let cpu = phong::shade(&model, &material, &scene, p, n);
        let out = gpu.shade(
            &GpuParams::new(&model, viewer, Vec3::ZERO, 1),
            &GpuMaterial::from(&material),
            &[GpuLight::from(&light)],
            &[p],
            &[n],
        )[0];
        count += 1;
        for (g, cc, what) in [
            (out.ambient, cpu.ambient, "ambient"),
            (out.diffuse, cpu.diffuse, "diffuse"),
            (out.specular, cpu.specular, "specular"),
        ] {
            if let Err(e) = close(g, cc, what) {
                failures.push(format!("id {} ({}): {e}", c["id"], c["label"]));
            }
        }
    }
    assert!(count > 2000, "only {count} cases ran");
    assert!(
        failures.is_empty(),
        "{} of {count} cases differ on {}:\n{}",
        failures.len(),
        gpu.adapter,
        failures.join("\n")
    );
}

/// A small deterministic generator, so the scene set is the same on every run.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
    fn vec(&mut self, r: f32) -> Vec3 {
        Vec3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }
}

#[test]
fn every_model_gate_light_and_falloff_matches() {
    let Some(gpu) = shader() else { return };
    let mut rng = Lcg(7);
    let colors = |rng: &mut Lcg| {
        LightColors::try_new(rng.vec(0.5).abs(), rng.vec(1.0).abs(), rng.vec(1.0).abs()).unwrap()
    };
    let falloffs = [
        Attenuation::None,
        Attenuation::polynomial(1.0, 0.09, 0.032),
        Attenuation::try_inverse_square(30.0).unwrap(),
        Attenuation::try_unreal(9.0).unwrap(),
        Attenuation::try_frostbite(9.0).unwrap(),
    ];
    let mut lights: Vec<Light> = Vec::new();
    for (i, a) in falloffs.into_iter().enumerate() {
        lights.push(
            PointLight::try_new(rng.vec(6.0), a, colors(&mut rng))
                .unwrap()
                .into(),
        );
        lights.push(
            SpotLight::try_new(
                rng.vec(6.0),
                -rng.vec(1.0),
                0.3 + 0.2 * i as f32,
                4.0,
                a,
                colors(&mut rng),
            )
            .unwrap()
            .into(),
        );
    }
    lights.push(
        DirectionalLight::try_new(rng.vec(1.0), colors(&mut rng))
            .unwrap()
            .into(),
    );
    let material = Material::try_new(Vec3::splat(0.2), Vec3::new(0.8, 0.5, 0.3), Vec3::ONE, 24.0)
        .unwrap()
        .try_with_emission(Vec3::new(0.01, 0.0, 0.02))
        .unwrap();
    let positions: Vec<Vec3> = (0..512).map(|_| rng.vec(4.0)).collect();
    let normals: Vec<Vec3> = (0..512).map(|_| rng.vec(1.0)).collect();
    let gpu_lights: Vec<GpuLight> = lights.iter().map(GpuLight::from).collect();
    let mut models: Vec<Model> = vec![Lambert::default().into()];
    for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
        for normalization in [
            Normalization::None,
            Normalization::Energy,
            Normalization::EnergyExact,
        ] {
            models.push(
                Phong {
                    gate,
                    normalization,
                    ..Default::default()
                }
                .into(),
            );
            models.push(
                BlinnPhong {
                    gate,
                    normalization,
                    ..Default::default()
                }
                .into(),
            );
        }
    }
    for model in models {
        for viewer in [
            Viewer::At(Vec3::new(0.5, 1.0, 7.0)),
            Viewer::Infinite(Vec3::new(0.2, 0.3, 1.0)),
        ] {
            let scene = Scene {
                lights: &lights,
                ambient: Vec3::splat(0.05),
                viewer,
            };
            let out = gpu.shade(
                &GpuParams::new(&model, viewer, scene.ambient, lights.len() as u32),
                &GpuMaterial::from(&material),
                &gpu_lights,
                &positions,
                &normals,
            );
            for (i, (p, n)) in positions.iter().zip(&normals).enumerate() {
                let cpu = phong::shade(&model, &material, &scene, *p, *n);
                let g = out[i];
                for (a, b, what) in [
                    (g.ambient, cpu.ambient, "ambient"),
                    (g.diffuse, cpu.diffuse, "diffuse"),
                    (g.specular, cpu.specular, "specular"),
                    (g.emission, cpu.emission, "emission"),
                ] {
                    close(a, b, what)
                        .unwrap_or_else(|e| panic!("{model:?} {viewer:?} point {i}: {e}"));
                }
            }
        }
    }
}
