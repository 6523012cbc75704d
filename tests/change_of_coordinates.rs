//! Changes of coordinates that the equation cannot see: units, origin and handedness.
//!
//! Every term is a function of directions, of distances, and of the material and lights. So a
//! scene shades the same after
//!
//! - **a change of units** by a power of two, where there is no falloff (distances change, so
//!   only `Attenuation::None` and directional lights): multiplying by `2ᵏ` is exact in `f32`
//!   wherever no value leaves the normal range, and every normalisation divides the factor out
//!   exactly (`√(4ᵏ·x) = 2ᵏ·√x`, or a power-of-two rescaling of its own; Phong's squared base
//!   carries the same powers in its numerator and denominator). Positions × `2ᵏ` and the normal
//!   × `2ʲ` must leave every term of every per-point path unchanged, bit for bit, from scales
//!   where squared lengths underflow `f32` to scales where they overflow;
//! - **a move of the origin**, with any falloff: every path reads positions only through
//!   differences (`P_light − p`, `eye − p`), and on a grid whose sums are exact the moved
//!   differences are the same numbers;
//! - **a mirror image** (every x component negated: points, normals, lights, spot axes, the
//!   viewer), with any falloff: dot products and lengths see `(−a)(−b) = ab` and `|−a| = |a|`,
//!   and IEEE rounding is symmetric in sign.
//!
//! The move and the mirror hold for the batch kernel too, at every level this CPU runs and for
//! G-buffers with per-point surfaces: they change no value its approximate inverse norms see.
//! A change of units does (the approximations' rounding depends on the magnitude, and its
//! out-of-range lanes take the scalar path), so there the kernel is held to its documented range
//! instead (tests/batch.rs).
//!
//! Coordinates lie on a grid of `2⁻⁸` in `[−64, 64]`, moves on the same grid: every coordinate,
//! every moved coordinate and every difference of two is exact and a normal `f32` at every scale.

use glam::Vec3;
use phong::{
    Attenuation, DirectionalLight, GBuffer, Level, Light, LightColors, Material, Model, PointLight,
    Scene, Shader, SoaRgb, SoaSurface, SoaVec3, SpotLight, Surface, Terms, Unshadowed, Viewer,
    shade, shade_batch_with_level, shade_gbuffer_with_level,
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

/// A change of coordinates: positions `p ↦ mirror(2ᵏ·p + offset)`, normals
/// `n ↦ mirror(2ʲ·n)`, directions `d ↦ mirror(d)`, where `mirror` negates x or does nothing.
#[derive(Clone, Copy, Debug)]
struct Change {
    scale: f32,
    normal_scale: f32,
    offset: Vec3,
    mirror: bool,
}

impl Change {
    const NONE: Change = Change {
        scale: 1.0,
        normal_scale: 1.0,
        offset: Vec3::ZERO,
        mirror: false,
    };

    fn units(k: i32, j: i32) -> Change {
        Change {
            scale: 2f32.powi(k),
            normal_scale: 2f32.powi(j),
            ..Change::NONE
        }
    }

    fn flip(&self, v: Vec3) -> Vec3 {
        if self.mirror {
            Vec3::new(-v.x, v.y, v.z)
        } else {
            v
        }
    }

    fn point(&self, p: Vec3) -> Vec3 {
        self.flip(p * self.scale + self.offset)
    }

    fn normal(&self, n: Vec3) -> Vec3 {
        self.flip(n * self.normal_scale)
    }

    fn direction(&self, d: Vec3) -> Vec3 {
        self.flip(d)
    }
}

/// A light: its kind, its position (point and spot lights), its direction (spot axis,
/// directional light), its falloff and its colours.
#[derive(Clone, Copy, Debug)]
struct LightSpec {
    kind: u8,
    position: Vec3,
    direction: Vec3,
    attenuation: Attenuation,
    colors: LightColors,
}

impl LightSpec {
    /// The light after the change `c`: positions move, directions only mirror.
    fn after(&self, c: &Change) -> Light {
        // A zero grid vector is no direction; any fixed one will do.
        let direction = if self.direction == Vec3::ZERO {
            Vec3::new(0.25, -1.0, 0.5)
        } else {
            self.direction
        };
        let (position, direction) = (c.point(self.position), c.direction(direction));
        match self.kind {
            0 => PointLight::try_new(position, self.attenuation, self.colors)
                .unwrap()
                .into(),
            1 => SpotLight::try_new(position, direction, 0.7, 2.0, self.attenuation, self.colors)
                .unwrap()
                .into(),
            _ => DirectionalLight::try_new(direction, self.colors)
                .unwrap()
                .into(),
        }
    }
}

/// A light with a falloff drawn from `attenuation`.
fn light(attenuation: impl Strategy<Value = Attenuation>) -> impl Strategy<Value = LightSpec> {
    (
        0u8..3,
        grid_point(),
        grid_point(),
        attenuation,
        strategies::color(),
        strategies::color(),
        strategies::color(),
    )
        .prop_map(
            |(kind, position, direction, attenuation, a, d, s)| LightSpec {
                kind,
                position,
                direction,
                attenuation,
                colors: LightColors::try_new(a, d, s).unwrap(),
            },
        )
}

/// Everything the shading of a few points reads, before the change of coordinates.
#[derive(Clone, Debug)]
struct Case {
    model: Model,
    material: Material,
    surface: Surface,
    lights: Vec<LightSpec>,
    visibility: [f32; 3],
    /// `Some(position)` for a viewer at a point, `None` for an infinite viewer.
    viewer: Option<Vec3>,
    /// Points and normals; the per-point paths shade the first, the batch paths all of them
    /// (one chunk of the kernel and a tail).
    points: Vec<(Vec3, Vec3)>,
}

fn case(attenuation: impl Strategy<Value = Attenuation>) -> impl Strategy<Value = Case> {
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
        prop::collection::vec(light(attenuation), 1..=3),
        [0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0],
        prop::option::of(grid_point()),
        prop::collection::vec((grid_point(), grid_point()), 1..=21),
    )
        .prop_map(
            |((model, ka, kd, ks, s), (td, ts, ss), lights, visibility, viewer, points)| Case {
                model,
                material: Material::try_new(ka, kd, ks, s).unwrap(),
                surface: Surface::textured(td, ts, ss),
                lights,
                visibility,
                viewer,
                points,
            },
        )
}

fn case_without_falloff() -> impl Strategy<Value = Case> {
    case(Just(Attenuation::None))
}

fn case_with_any_falloff() -> impl Strategy<Value = Case> {
    case(strategies::attenuation())
}

/// The scene's lights and viewer after the change `c`.
fn scene_parts(case: &Case, c: &Change) -> (Vec<Light>, Viewer) {
    let lights = case.lights.iter().map(|l| l.after(c)).collect();
    let viewer = match case.viewer {
        Some(at) => Viewer::At(c.point(at)),
        None => Viewer::Infinite(c.direction(Vec3::new(0.125, 0.25, 1.0))),
    };
    (lights, viewer)
}

/// The terms of every per-point path at the first point, after the change `c`: `shade`; a
/// prepared `Shader`'s `shade`, `shade_visible` and `shade_surface`, in the form `Shader::new`
/// prepares (with one light, the branch-free one-light form) and in `one_at_a_time`'s (the light
/// loop).
fn every_path(case: &Case, c: &Change) -> Vec<Terms> {
    let (lights, viewer) = scene_parts(case, c);
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.03),
        viewer,
    };
    let (p, n) = case.points[0];
    let (p, n) = (c.point(p), c.normal(n));
    let visibility = &case.visibility[..lights.len()];
    let looped = Shader::new(case.model, &case.material, &scene);
    let lone = looped.one_at_a_time();
    let mut out = vec![shade(&case.model, &case.material, &scene, p, n)];
    for shader in [looped, lone] {
        out.push(shader.shade(p, n));
        out.push(shader.shade_visible(p, n, visibility));
        out.push(shader.shade_surface(p, n, &case.surface, visibility));
        out.push(shader.shade_surface(p, n, &case.surface, Unshadowed));
    }
    out
}

fn soa(v: &[Vec3]) -> [Vec<f32>; 3] {
    [
        v.iter().map(|p| p.x).collect(),
        v.iter().map(|p| p.y).collect(),
        v.iter().map(|p| p.z).collect(),
    ]
}

/// Every point's total from `shade_batch` and from `shade_gbuffer` (the case's surface at every
/// point, the lights' visibilities), at every level this CPU runs, after the change
/// `c`, as bits: one row per level and entry point.
fn batch_paths(case: &Case, c: &Change) -> Vec<(Level, &'static str, Vec<[u32; 3]>)> {
    let (lights, viewer) = scene_parts(case, c);
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.03),
        viewer,
    };
    let count = case.points.len();
    let ps: Vec<Vec3> = case.points.iter().map(|&(p, _)| c.point(p)).collect();
    let ns: Vec<Vec3> = case.points.iter().map(|&(_, n)| c.normal(n)).collect();
    let ([px, py, pz], [nx, ny, nz]) = (soa(&ps), soa(&ns));
    let s = &case.surface;
    let [dr, dg, db] = soa(&vec![s.diffuse; count]);
    let [sr, sg, sb] = soa(&vec![s.specular; count]);
    let shininess = vec![s.shininess; count];
    // Light j's visibility at point i is `visibility[j * count + i]`.
    let visibility: Vec<f32> = (0..lights.len())
        .flat_map(|j| vec![case.visibility[j]; count])
        .collect();
    let gbuffer = GBuffer::new(SoaVec3::new(&px, &py, &pz), SoaVec3::new(&nx, &ny, &nz))
        .with_surface(SoaSurface {
            ambient: SoaVec3::new(&dr, &dg, &db),
            diffuse: SoaVec3::new(&dr, &dg, &db),
            specular: SoaVec3::new(&sr, &sg, &sb),
            shininess: &shininess,
        })
        .with_visibility(&visibility);
    let mut rows = vec![];
    for level in Level::supported() {
        for entry in ["shade_batch", "shade_gbuffer"] {
            let (mut r, mut g, mut b) = (vec![0.0; count], vec![0.0; count], vec![0.0; count]);
            let out = SoaRgb::new(&mut r, &mut g, &mut b);
            if entry == "shade_batch" {
                let (positions, normals) =
                    (SoaVec3::new(&px, &py, &pz), SoaVec3::new(&nx, &ny, &nz));
                shade_batch_with_level(
                    level,
                    &case.model,
                    &case.material,
                    &scene,
                    positions,
                    normals,
                    out,
                )
                .unwrap();
            } else {
                shade_gbuffer_with_level(level, &case.model, &case.material, &scene, &gbuffer, out)
                    .unwrap();
            }
            let bits = (0..count)
                .map(|i| [r[i].to_bits(), g[i].to_bits(), b[i].to_bits()])
                .collect();
            rows.push((level, entry, bits));
        }
    }
    rows
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

/// Every per-point path gives the same bits before and after the change `c`.
fn per_point_paths_agree(case: &Case, c: &Change) -> Result<(), TestCaseError> {
    let reference = every_path(case, &Change::NONE);
    let changed = every_path(case, c);
    for (path, (a, b)) in reference.iter().zip(&changed).enumerate() {
        prop_assert_eq!(
            bits(a),
            bits(b),
            "path {} after {:?}: {:?} against {:?}",
            path,
            c,
            a,
            b
        );
    }
    Ok(())
}

/// Every batch path gives the same bits before and after the change `c`.
fn batch_paths_agree(case: &Case, c: &Change) -> Result<(), TestCaseError> {
    let reference = batch_paths(case, &Change::NONE);
    let changed = batch_paths(case, c);
    for ((level, entry, a), (_, _, b)) in reference.iter().zip(&changed) {
        prop_assert_eq!(a, b, "{} at {:?} after {:?}", entry, level, c);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn a_power_of_two_change_of_units_changes_no_bit(
        case in case_without_falloff(),
        k in -100i32..=100,
        j in -100i32..=100,
    ) {
        per_point_paths_agree(&case, &Change::units(k, j))?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn moving_the_origin_changes_no_bit(case in case_with_any_falloff(), offset in grid_point()) {
        let c = Change { offset, ..Change::NONE };
        per_point_paths_agree(&case, &c)?;
        batch_paths_agree(&case, &c)?;
    }

    #[test]
    fn a_mirror_image_changes_no_bit(case in case_with_any_falloff()) {
        let c = Change { mirror: true, ..Change::NONE };
        per_point_paths_agree(&case, &c)?;
        batch_paths_agree(&case, &c)?;
    }
}

/// The scales at which the common-range tests switch paths: squared lengths just inside and just
/// outside the light loop's `[2⁻²⁵, 2²⁵]` and the plain normalisations' `[1e-30, 1e30]`, for a
/// fixed scene with a point light and a viewer at a point (Phong at a fractional shininess, whose
/// per-point lobe is the squared base).
#[test]
fn every_range_boundary_keeps_the_bits() {
    let case = Case {
        model: Model::Phong(phong::Phong::default()),
        material: Material::try_new(Vec3::splat(0.1), Vec3::splat(0.6), Vec3::ONE, 20.5).unwrap(),
        surface: Surface::textured(Vec3::new(0.8, 0.5, 0.2), Vec3::splat(0.7), 37.25),
        lights: vec![LightSpec {
            kind: 0,
            position: Vec3::new(1.5, 2.0, 1.25),
            direction: Vec3::ZERO,
            attenuation: Attenuation::None,
            colors: LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE).unwrap(),
        }],
        visibility: [1.0; 3],
        // Near the mirror direction of the light, so that the lobe is lit.
        viewer: Some(Vec3::new(-0.75, -1.75, 1.5)),
        points: vec![(Vec3::new(0.25, 0.0, 0.5), Vec3::new(0.125, 0.0, 1.0))],
    };
    let reference = every_path(&case, &Change::NONE);
    // Some lobe must be lit, or the specular bits would be zero at every scale.
    assert!(reference.iter().all(|t| t.specular.x > 0.0));
    // Every coordinate of this scene and every difference of two stays a normal `f32` up to
    // `2^±120`; the squared lengths cross `[2⁻²⁵, 2²⁵]` near `k = ±12` and `[1e-30, 1e30]` near
    // `k = ±50`, and the normal's (about 1) near `j = ±12.5` and `j = ±50`.
    for k in -120..=120 {
        for j in [-120, -60, -50, -49, -13, -12, 0, 12, 13, 49, 50, 60, 120] {
            let changed = every_path(&case, &Change::units(k, j));
            for (path, (a, b)) in reference.iter().zip(&changed).enumerate() {
                assert_eq!(
                    bits(a),
                    bits(b),
                    "path {path}: positions × 2^{k}, normal × 2^{j}"
                );
            }
        }
    }
}
