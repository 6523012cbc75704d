//! Units: a scene measured in metres or in millimetres shades the same.
//!
//! With no falloff (`Attenuation::None`, directional lights) the equation reads directions only:
//! `L`, `V` and `N` normalised, and Phong's squared base, whose numerator and denominator carry the
//! same powers of the vectors' lengths. Multiplying by a power of two is exact in `f32` wherever
//! no value leaves the normal range, and every normalisation divides the factor out again exactly
//! (`√(4ᵏ·x) = 2ᵏ·√x`, and the full-range path rescales by a power of two of its own). So
//! scaling every position (the shaded point, the lights, a viewer at a point) by `2ᵏ`, and the
//! normal by `2ʲ`, must leave every term of every per-point path unchanged, bit for bit.
//!
//! The scales run over `2^±100`: far enough that squared lengths underflow `f32` at one end and
//! overflow it at the other (the full-range normalisation takes over), and through the common
//! range of the light loop's squared base, `[2⁻²⁵, 2²⁵]`, where vectors are kept as they are.
//! Coordinates lie on a grid of `2⁻⁸` in `[−64, 64]`, so every coordinate and every difference of
//! two is exact and stays a normal `f32` at every scale: the condition under which the scaled
//! scene is the same scene.
//!
//! The batch kernel is not held to bits here: its inverse norms are approximations whose rounding
//! depends on the magnitude, and its out-of-range lanes take this scalar path; it agrees with the
//! scalar path within its documented range at every scale (tests/batch.rs).

use glam::Vec3;
use phong::{
    Attenuation, DirectionalLight, Light, LightColors, Material, Model, PointLight, Scene, Shader,
    SpotLight, Surface, Terms, Unshadowed, Viewer, shade,
};
use proptest::prelude::*;

use crate::strategies;

/// A coordinate on the grid `2⁻⁸·m`, `|m| < 2¹⁴`.
fn coordinate() -> impl Strategy<Value = f32> {
    (-16_383i32..=16_383).prop_map(|m| m as f32 / 256.0)
}

fn grid_point() -> impl Strategy<Value = Vec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A light without falloff: its kind, its position (point and spot lights), its direction (spot
/// axis, directional light), and its colours.
#[derive(Clone, Copy, Debug)]
struct LightSpec {
    kind: u8,
    position: Vec3,
    direction: Vec3,
    colors: LightColors,
}

impl LightSpec {
    /// The light in a scene scaled by `scale` (a power of two): positions scale, directions do not.
    fn at_scale(&self, scale: f32) -> Light {
        // A zero grid vector is no direction; any fixed one will do.
        let direction = if self.direction == Vec3::ZERO {
            Vec3::new(0.25, -1.0, 0.5)
        } else {
            self.direction
        };
        match self.kind {
            0 => PointLight::try_new(self.position * scale, Attenuation::None, self.colors)
                .unwrap()
                .into(),
            1 => SpotLight::try_new(
                self.position * scale,
                direction,
                0.7,
                2.0,
                Attenuation::None,
                self.colors,
            )
            .unwrap()
            .into(),
            _ => DirectionalLight::try_new(direction, self.colors)
                .unwrap()
                .into(),
        }
    }
}

fn light() -> impl Strategy<Value = LightSpec> {
    (
        0u8..3,
        grid_point(),
        grid_point(),
        strategies::color(),
        strategies::color(),
        strategies::color(),
    )
        .prop_map(|(kind, position, direction, a, d, s)| LightSpec {
            kind,
            position,
            direction,
            colors: LightColors::try_new(a, d, s).unwrap(),
        })
}

/// Everything a point's shading reads, before scaling.
#[derive(Clone, Debug)]
struct Case {
    model: Model,
    material: Material,
    surface: Surface,
    lights: Vec<LightSpec>,
    visibility: [f32; 3],
    /// `Some(position)` for a viewer at a point, `None` for the infinite viewer below.
    viewer: Option<Vec3>,
    point: Vec3,
    normal: Vec3,
}

fn case() -> impl Strategy<Value = Case> {
    (
        (
            strategies::any_model(),
            strategies::color(),
            strategies::color(),
            strategies::color(),
            strategies::shininess(),
        ),
        (
            strategies::color(),
            strategies::color(),
            strategies::shininess(),
        ),
        prop::collection::vec(light(), 1..=3),
        [0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0],
        prop::option::of(grid_point()),
        grid_point(),
        grid_point(),
    )
        .prop_map(
            |((model, ka, kd, ks, s), (td, ts, ss), lights, visibility, viewer, point, normal)| {
                Case {
                    model,
                    material: Material::try_new(ka, kd, ks, s).unwrap(),
                    surface: Surface::textured(td, ts, ss),
                    lights,
                    visibility,
                    viewer,
                    point,
                    normal,
                }
            },
        )
}

/// The terms of every per-point path, positions scaled by `scale` and the normal by `normal_scale`:
/// `shade`; a prepared `Shader`'s `shade`, `shade_visible` and `shade_surface`, in the form
/// `Shader::new` prepares (with one light, the branch-free one-light form) and in
/// `one_at_a_time`'s (the light loop).
fn every_path(c: &Case, scale: f32, normal_scale: f32) -> Vec<Terms> {
    let lights: Vec<Light> = c.lights.iter().map(|l| l.at_scale(scale)).collect();
    let viewer = match c.viewer {
        Some(at) => Viewer::At(at * scale),
        None => Viewer::Infinite(Vec3::new(0.125, 0.25, 1.0)),
    };
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.03),
        viewer,
    };
    let (p, n) = (c.point * scale, c.normal * normal_scale);
    let visibility = &c.visibility[..lights.len()];
    let looped = Shader::new(c.model, &c.material, &scene);
    let lone = looped.one_at_a_time();
    let mut out = vec![shade(&c.model, &c.material, &scene, p, n)];
    for shader in [looped, lone] {
        out.push(shader.shade(p, n));
        out.push(shader.shade_visible(p, n, visibility));
        out.push(shader.shade_surface(p, n, &c.surface, visibility));
        out.push(shader.shade_surface(p, n, &c.surface, Unshadowed));
    }
    out
}

fn bits(t: &Terms) -> [u32; 12] {
    let mut b = [0; 12];
    for (k, v) in [t.ambient, t.diffuse, t.specular, t.emission]
        .into_iter()
        .enumerate()
    {
        for (i, x) in v.to_array().into_iter().enumerate() {
            b[3 * k + i] = x.to_bits();
        }
    }
    b
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn a_power_of_two_change_of_units_changes_no_bit(
        c in case(),
        k in -100i32..=100,
        j in -100i32..=100,
    ) {
        let reference = every_path(&c, 1.0, 1.0);
        let scaled = every_path(&c, 2f32.powi(k), 2f32.powi(j));
        for (path, (a, b)) in reference.iter().zip(&scaled).enumerate() {
            prop_assert_eq!(
                bits(a),
                bits(b),
                "path {}: positions × 2^{}, normal × 2^{}: {:?} against {:?}",
                path, k, j, a, b
            );
        }
    }
}

/// The scales at which the common-range tests switch paths: squared lengths just inside and just
/// outside the light loop's `[2⁻²⁵, 2²⁵]` and the plain normalisations' `[1e-30, 1e30]`, for a
/// fixed scene with a point light and a viewer at a point (Phong at a fractional shininess, whose
/// per-point lobe is the squared base).
#[test]
fn every_range_boundary_keeps_the_bits() {
    let c = Case {
        model: Model::Phong(phong::Phong::default()),
        material: Material::try_new(Vec3::splat(0.1), Vec3::splat(0.6), Vec3::ONE, 20.5).unwrap(),
        surface: Surface::textured(Vec3::new(0.8, 0.5, 0.2), Vec3::splat(0.7), 37.25),
        lights: vec![LightSpec {
            kind: 0,
            position: Vec3::new(1.5, 2.0, 1.25),
            direction: Vec3::ZERO,
            colors: LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE).unwrap(),
        }],
        visibility: [1.0; 3],
        // Near the mirror direction of the light, so that the lobe is lit.
        viewer: Some(Vec3::new(-0.75, -1.75, 1.5)),
        point: Vec3::new(0.25, 0.0, 0.5),
        normal: Vec3::new(0.125, 0.0, 1.0),
    };
    let reference = every_path(&c, 1.0, 1.0);
    // Some lobe must be lit, or the specular bits would be zero at every scale.
    assert!(reference.iter().all(|t| t.specular.x > 0.0));
    // Every coordinate of this scene and every difference of two stays a normal `f32` up to
    // `2^±120`; the squared lengths cross `[2⁻²⁵, 2²⁵]` near `k = ±12` and `[1e-30, 1e30]` near
    // `k = ±50`, and the normal's (about 1) near `j = ±12.5` and `j = ±50`.
    for k in -120..=120 {
        let scale = 2f32.powi(k);
        for j in [-120, -60, -50, -49, -13, -12, 0, 12, 13, 49, 50, 60, 120] {
            let scaled = every_path(&c, scale, 2f32.powi(j));
            for (path, (a, b)) in reference.iter().zip(&scaled).enumerate() {
                assert_eq!(
                    bits(a),
                    bits(b),
                    "path {path}: positions × 2^{k}, normal × 2^{j}"
                );
            }
        }
    }
}
