//! Promises about numerics that an outside conformance and fuzz campaign found broken at the
//! extremes, each with its reproducer as a regression test and a property test that searches the
//! part of the domain where it broke:
//!
//! 1. a missing direction (the zero `N`, `L` or `V` in `Incidence::new`) gives no lobe;
//! 2. `PowStrategy::max_relative_error` bounds every strategy, fractional and huge exponents
//!    included;
//! 3. the batch path stays in its documented range on ill-conditioned and overflowing input (the
//!    reproducers and the per-group adversarial tests are in tests/batch.rs).
//!
//! `gouraud_error_bound`'s rounding and pow-strategy allowances are tested in
//! tests/shading_rate.rs, next to the bound's other tests.

use crate::strategies;
use phong_tools::batch_range;

use glam::{DVec3, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Incidence, Lambert, Level, Light, LightColors,
    LightSource, Material, Model, Normalization, Phong, PointLight, PowStrategy, ReflectionModel,
    Scene, SoaRgb, SoaVec3, SpecularGate, Viewer,
};
use proptest::prelude::*;
use strategies::any_model;

// ---------------------------------------------------------------------------------------------
// Strategies
// ---------------------------------------------------------------------------------------------

/// A unit vector, uniform on the sphere (built in f64, rounded once).
fn unit_vec3() -> impl Strategy<Value = Vec3> {
    (-1.0f64..=1.0, 0.0f64..core::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
            .normalize()
            .as_vec3()
    })
}

/// A shininess: 0, fractional below 1, ordinary, past the squaring limit, and huge.
fn any_shininess() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        0.0f32..1.0,
        0.0f32..256.0,
        (0u32..=2048).prop_map(|s| s as f32),
        1024.0f32..1e6,
        Just(f32::MAX),
    ]
}

// ---------------------------------------------------------------------------------------------
// 1. A missing direction gives no lobe.
// ---------------------------------------------------------------------------------------------

#[test]
fn the_viewer_at_the_point_has_no_blinn_highlight() {
    // Regression: L = N = Z and V missing gave a Blinn-Phong lobe of 1 ((N·H)² was read from
    // L + V = L alone). Mesa gives 0 for the viewer at the fragment, as does Phong.
    let g = Incidence::new(Vec3::Z, Vec3::Z, Vec3::ZERO);
    assert_eq!(BlinnPhong::default().specular(&g, 16.0), 0.0);
    assert_eq!(Phong::default().specular(&g, 16.0), 0.0);
    // The diffuse lobe does not need the viewer.
    assert_eq!(BlinnPhong::default().diffuse(&g), 1.0);
}

#[test]
fn a_missing_normal_has_no_phong_halo() {
    // Without a surface, R·V = 2(N·L)(N·V) − L·V would read −L·V: a highlight of 1 at L = −V for
    // the ungated model. No normal means no lobe.
    let g = Incidence::new(Vec3::ZERO, Vec3::Z, -Vec3::Z);
    let ungated = Phong {
        gate: SpecularGate::None,
        ..Phong::default()
    };
    assert_eq!(ungated.specular(&g, 8.0), 0.0);
    assert_eq!(ungated.diffuse(&g), 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn a_missing_direction_gives_no_lobe(
        model in any_model(),
        s in any_shininess(),
        (n, l, v) in (unit_vec3(), unit_vec3(), unit_vec3()),
        missing in 1u8..8,
    ) {
        // `missing` picks a non-empty set of N (bit 0), L (bit 1), V (bit 2) to replace by zero.
        let pick = |bit: u8, x: Vec3| if missing & bit != 0 { Vec3::ZERO } else { x };
        let (n, l, v) = (pick(1, n), pick(2, l), pick(4, v));
        let pairs = [
            (Incidence::new(n, l, v), Incidence::new(n, l, Vec3::Z)),
            (
                Incidence::from_unnormalized(n * 3.0, l, v * 0.5),
                Incidence::from_unnormalized(n * 3.0, l, Vec3::Z),
            ),
        ];
        for (g, with_viewer) in pairs {
            prop_assert_eq!(model.specular(&g, s), 0.0, "{:?} s={} g={:?}", model, s, g);
            if n == Vec3::ZERO || l == Vec3::ZERO {
                prop_assert_eq!(model.diffuse(&g), 0.0, "{:?} g={:?}", model, g);
            } else {
                // A missing viewer leaves the diffuse lobe alone.
                prop_assert_eq!(model.diffuse(&g), model.diffuse(&with_viewer));
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. One error bound per pow strategy, over the whole domain.
// ---------------------------------------------------------------------------------------------

/// `|lobe(x, s) − x^s| / max(x^s, 2⁻²⁴)` against the exact power in `f64`.
fn pow_err(p: PowStrategy, x: f32, s: f32) -> f64 {
    let want = (x as f64).powf(s as f64);
    (p.lobe(x, s) as f64 - want).abs() / want.max(PowStrategy::ERROR_FLOOR as f64)
}

#[test]
fn the_reported_pow_errors_are_within_the_stated_bound() {
    // Regression: 9.40e-4 against a documented 8e-4, and 2.013e-5 against 2e-5.
    let cases = [
        (PowStrategy::SplitPoly3, 2.155_651_2e-5, 0.988_268_6, 9.3e-4),
        (PowStrategy::SplitPoly5, 0.707_114_46, 0.999, 2.0e-5),
    ];
    for (p, x, s, at_least) in cases {
        let e = pow_err(p, x, s);
        assert!(
            e >= at_least,
            "{p:?}({x}, {s}): the reproducer has err {e:e}"
        );
        assert!(
            e <= p.max_relative_error() as f64,
            "{p:?}({x}, {s}): err {e:e} > bound {:e}",
            p.max_relative_error()
        );
    }
}

/// An exponent where the strategies differ: fractional below 1, up to past the squaring limit
/// (whole and not), and huge.
fn pow_exponent() -> impl Strategy<Value = f32> {
    prop_oneof![
        0.0f32..1.0,
        0.0f32..2048.0,
        (0u32..=2048).prop_map(|s| s as f32),
        1.0f32..1e30,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn every_strategy_meets_its_bound(s in pow_exponent(), y in -48.0f64..0.0, uniform in 0.0f32..=1.0) {
        // x where x^s = 2^y (the error is largest for x^s near 2⁻²⁴), and a uniform x; each with
        // its 63 neighbours above, a cheap way to search ulp-scale rounding.
        let tuned = if s > 0.0 { (2f64.powf(y / s as f64) as f32).max(f32::MIN_POSITIVE) } else { uniform };
        for x0 in [tuned, uniform.max(f32::MIN_POSITIVE)] {
            for k in 0..64u32 {
                let x = f32::from_bits(x0.to_bits() + k).min(1.0);
                for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
                    let e = pow_err(p, x, s);
                    prop_assert!(
                        e <= p.max_relative_error() as f64,
                        "{:?}.lobe({:e}, {:e}): err {:e} > bound {:e}", p, x, s, e, p.max_relative_error()
                    );
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 3. The batch path stays in its documented range, overflow and ill-conditioning included.
// ---------------------------------------------------------------------------------------------

/// A colour channel: ordinary, or log-uniform up to `f32::MAX`, or 0.
fn channel() -> impl Strategy<Value = f32> {
    prop_oneof![
        2 => 0.0f32..=1.0,
        1 => (-3.0f32..38.53).prop_map(|e| 10f32.powf(e).min(f32::MAX)),
        1 => Just(0.0f32),
    ]
}

fn colour() -> impl Strategy<Value = Vec3> {
    (channel(), channel(), channel()).prop_map(|(r, g, b)| Vec3::new(r, g, b))
}

fn light_colors() -> impl Strategy<Value = LightColors> {
    (colour(), colour(), colour()).prop_map(|(a, d, s)| LightColors::try_new(a, d, s).unwrap())
}

fn light() -> impl Strategy<Value = Light> {
    prop_oneof![
        (unit_vec3(), light_colors())
            .prop_map(|(d, c)| DirectionalLight::try_new(d, c).unwrap().into()),
        (
            (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0),
            (0.0f32..2.0, 0.0f32..1.0, 0.0f32..1.0),
            light_colors()
        )
            .prop_map(|((x, y, z), (c, l, q), colors)| PointLight::try_new(
                Vec3::new(x, y, z),
                Attenuation::try_polynomial(c, l, q).unwrap(),
                colors
            )
            .unwrap()
            .into()),
    ]
}

/// Normals for 17 points (a full chunk and a tail) relative to the first light `l` and the
/// viewer `v` at the origin: random, grazing the light, with the Blinn-Phong base near 0 or the
/// light and viewer nearly opposite, and Phong's base near 0.
fn normals(l: Vec3, v: Vec3, picks: &[(u8, Vec3, f32)]) -> Vec<Vec3> {
    let h = (l + v).normalize_or(l);
    picks
        .iter()
        .map(|&(kind, u, t)| match kind {
            0 => u * (1.0 + 50.0 * t.abs()),
            1 => l.cross(u).normalize_or(u) + l * (t * 1e-5),
            2 => h.cross(u).normalize_or(u) + h * (t * 1e-4),
            _ => {
                // Between H (R·V > 0) and u: somewhere R·V crosses 0 when u is away from it.
                let w = 0.5 + 0.5 * t;
                (h * (1.0 - w) + u * w).normalize_or(h)
            }
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn the_batch_stays_in_its_documented_range(
        model in any_model(),
        s in any_shininess(),
        (ka, kd, ks, ke) in (colour(), colour(), colour(), colour()),
        lights in prop::collection::vec(light(), 1..3),
        ambient in colour(),
        (at, eye, dir) in (any::<bool>(), (-4.0f32..4.0, -4.0f32..4.0, -4.0f32..4.0), unit_vec3()),
        opposite in -1e-1f32..1e-1,
        picks in prop::collection::vec((0u8..4, unit_vec3(), -1.0f32..1.0), 17),
    ) {
        let material = Material::try_new(ka, kd, ks, s).unwrap().try_with_emission(ke).unwrap();
        // The viewer: anywhere, or (infinite) nearly opposite the first light, which puts
        // 2 + 2 L·V near the kernel's cutoff for every point.
        let first = lights[0].sample(Vec3::ZERO).direction.normalize_or(Vec3::Z);
        let viewer = if at {
            Viewer::At(Vec3::new(eye.0, eye.1, eye.2))
        } else {
            Viewer::Infinite((-first + dir * opposite).normalize_or(dir))
        };
        let v = match viewer {
            Viewer::At(e) => e.normalize_or(Vec3::Z),
            Viewer::Infinite(d) => d.normalize_or(Vec3::Z),
        };
        let n = normals(first, v, &picks);
        let p = vec![Vec3::ZERO; n.len()];
        let scene = Scene { lights: &lights, ambient, viewer };
        let soa = |f: fn(Vec3) -> f32, v: &[Vec3]| v.iter().map(|x| f(*x)).collect::<Vec<f32>>();
        let (px, py, pz) = (soa(|v| v.x, &p), soa(|v| v.y, &p), soa(|v| v.z, &p));
        let (nx, ny, nz) = (soa(|v| v.x, &n), soa(|v| v.y, &n), soa(|v| v.z, &n));
        for level in Level::supported() {
            let len = n.len();
            let (mut r, mut g, mut b) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
            phong::shade_batch_with_level(
                level,
                &model,
                &material,
                &scene,
                SoaVec3::new(&px, &py, &pz),
                SoaVec3::new(&nx, &ny, &nz),
                SoaRgb::new(&mut r, &mut g, &mut b),
            )
            .unwrap();
            for i in 0..len {
                let got = Vec3::new(r[i], g[i], b[i]);
                let range = batch_range::range(&model, &material, &scene, p[i], n[i]);
                let scalar = phong::shade(&model, &material, &scene, p[i], n[i]).total();
                prop_assert!(range.holds(scalar), "{} point {}: shade {} outside [{}, {}]",
                    level, i, scalar, range.lo, range.hi);
                prop_assert!(
                    range.holds(got),
                    "{} point {}: n = {}, batch {} outside [{}, {}] (shade {})",
                    level, i, n[i], got, range.lo, range.hi, scalar
                );
            }
        }
    }
}

/// Shades `p`/`n` at every level and checks each lane against the documented range.
fn assert_batch_in_range<L: LightSource + phong::BatchLight + 'static>(
    model: Model,
    material: &Material,
    scene: &Scene<'_, L>,
    p: Vec3,
    n: Vec3,
) {
    let range = batch_range::range(&model, material, scene, p, n);
    for level in Level::supported() {
        let (mut r, mut g, mut b) = ([0.0f32], [0.0f32], [0.0f32]);
        phong::shade_batch_with_level(
            level,
            &model,
            material,
            scene,
            SoaVec3::new(&[p.x], &[p.y], &[p.z]),
            SoaVec3::new(&[n.x], &[n.y], &[n.z]),
            SoaRgb::new(&mut r, &mut g, &mut b),
        )
        .unwrap();
        let got = Vec3::new(r[0], g[0], b[0]);
        assert!(
            range.holds(got),
            "{level}: batch {got} outside [{}, {}]",
            range.lo,
            range.hi
        );
    }
}

/// Found by tests/fuzz_promises.rs: the ambient sum `Σ La` passes `f32::MAX` (one light's ambient
/// is `f32::MAX`), so the rule saturates it before `Ka = 0.17` scales it; the kernel used to fold
/// `Ka ⊙ La` per light (allowed only when nothing can overflow) and skipped that saturation.
#[test]
fn a_saturating_ambient_sum_is_not_folded() {
    let colors = |a: Vec3| LightColors::try_new(a, Vec3::splat(0.5), Vec3::splat(0.5)).unwrap();
    let lights = [
        DirectionalLight::try_new(Vec3::X, colors(Vec3::new(1.0, 3.14e34, 1.0))).unwrap(),
        DirectionalLight::try_new(Vec3::Y, colors(Vec3::new(1.0, f32::MAX, 1.0))).unwrap(),
    ];
    let material = Material::try_new(Vec3::splat(0.17281538), Vec3::ONE, Vec3::ONE, 32.0).unwrap();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(3.0, 8.0, 1.0)),
    };
    assert_batch_in_range(
        Phong::default().into(),
        &material,
        &scene,
        Vec3::ZERO,
        Vec3::new(-0.5, 0.5, 0.7),
    );
}

/// Found by tests/fuzz_promises.rs: a light's diffuse colour times the material's (`3.9e34 ·
/// 1.8e19`) overflows `f32` even though the light's attenuation (`≈ 2e-25`) makes every shaded
/// value modest; folding that product gave `f32::MAX` where the equation gives at most ~1e10.
#[test]
fn a_colour_product_past_max_is_not_folded() {
    let lamp = PointLight::try_new(
        Vec3::ZERO,
        Attenuation::try_polynomial(4.6752956e24, 2.2371418e26, 0.0).unwrap(),
        LightColors::try_new(
            Vec3::splat(0.3),
            Vec3::new(0.0, 3.8989763e34, 0.0),
            Vec3::ONE,
        )
        .unwrap(),
    )
    .unwrap();
    let lights = [lamp];
    let material = Material::try_new(
        Vec3::ONE,
        Vec3::new(0.0, 1.7732853e19, 0.0),
        Vec3::ONE,
        0.27,
    )
    .unwrap();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::ZERO),
    };
    assert_batch_in_range(
        BlinnPhong::default().into(),
        &material,
        &scene,
        Vec3::new(-0.00012388136, 0.00017625102, 2.1709244e-5),
        Vec3::new(-0.8513977, 0.39934915, 0.3400623),
    );
}

/// Found by tests/fuzz_promises.rs: `Ls ⊙ Ks` overflows `f32` (`Ls = f32::MAX`, `Ks = 1.05`) while
/// `Ls ⊙ Ks · k` (k = 1/π, the energy factor at s = 0) does not, so the folded product must not be
/// formed in that order; with every specular weight 0 the lane was `f32::MAX` instead of ≈ 0.42.
#[test]
fn a_folded_product_does_not_overflow_in_its_first_factor() {
    let dim = LightColors::try_new(Vec3::splat(0.06), Vec3::splat(0.9), Vec3::splat(0.7)).unwrap();
    let hot =
        LightColors::try_new(Vec3::ZERO, Vec3::splat(0.8), Vec3::new(f32::MAX, 1.0, 1.0)).unwrap();
    let lights = [
        DirectionalLight::try_new(-Vec3::X, dim).unwrap(),
        DirectionalLight::try_new(Vec3::new(0.4443581, -0.15425405, -0.88246906), hot).unwrap(),
    ];
    let material = Material::try_new(
        Vec3::splat(0.6),
        Vec3::splat(0.9),
        Vec3::new(1.0549212, 1.0, 1.0),
        0.0,
    )
    .unwrap();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(8.650287e-5, -0.00014428791, 7.4741956e-6)),
    };
    let model = Phong {
        gate: SpecularGate::None,
        normalization: Normalization::EnergyExact,
        pow: PowStrategy::SplitPoly5,
    };
    assert_batch_in_range(
        model.into(),
        &material,
        &scene,
        Vec3::new(-5.2654867, 3.705335, 0.5617167),
        Vec3::new(0.062991224, 0.9971614, 0.041246988),
    );
}

/// Found by tests/fuzz_promises.rs once `Attenuation::factor` evaluated an overflowing polynomial
/// denominator in `f64`: the kernels' `f32` denominator overflowed to +∞ and gave 0 where `shade`
/// gives the small true factor. Such lanes now go to the scalar path.
#[test]
fn an_overflowing_polynomial_denominator_matches_shade() {
    let lamp = PointLight::try_new(
        Vec3::ZERO,
        Attenuation::try_polynomial(0.0, 3.4e38, 1e38).unwrap(),
        LightColors::try_new(Vec3::ZERO, Vec3::splat(3e38), Vec3::ZERO).unwrap(),
    )
    .unwrap();
    let lights = [lamp];
    let material = Material::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO, 1.0).unwrap();
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::Z),
    };
    let p = Vec3::new(0.0, 0.0, -0.01);
    let want = phong::shade(&Lambert::default(), &material, &scene, p, Vec3::Z).total();
    assert!(
        want.y > 0.0,
        "the true factor is 2.9e-37, times 3e38: {want}"
    );
    assert_batch_in_range(Lambert::default().into(), &material, &scene, p, Vec3::Z);
}
