//! Hand-computed values. Each expected number is worked out in the comment beside it; where the
//! f32 computation is exact (powers of two, exactly representable sums) the test asserts equality,
//! elsewhere it allows one or two ulps of the result (`ULP` below), never more.

use core::f32::consts::{FRAC_1_SQRT_2, PI};

use glam::{Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, Incidence, Lambert, LightColors, Material, Normalization, Phong,
    PointLight, PowStrategy, ReflectionModel, ResolvedModel, Scene, SpecularGate, SpotLight,
    Viewer,
};

/// Relative size of one f32 ulp at 1: `x` and a correctly rounded `y` differ by at most ULP·|y|.
const ULP: f32 = f32::EPSILON;

/// `got` within `ulps` ulps (relative to the larger magnitude) of `want`: approx's relative test
/// with no absolute slack, so an expected exact value must come out exact.
fn close(got: f32, want: f32, ulps: f32, what: &str) {
    assert!(
        approx::relative_eq!(got, want, epsilon = 0.0, max_relative = ulps * ULP),
        "{what}: got {got}, want {want} (±{ulps} ulp)"
    );
}

/// Every component within `ulps` ulps of the largest expected component (approx's absolute test
/// on glam vectors, with the tolerance scaled to the vector).
fn close_vec(got: Vec3, want: Vec3, ulps: f32, what: &str) {
    assert!(
        approx::abs_diff_eq!(got, want, epsilon = ulps * ULP * want.abs().max_element()),
        "{what}: got {got}, want {want} (±{ulps} ulp of the largest component)"
    );
}

// ---------------------------------------------------------------------------------------------
// Lobes
// ---------------------------------------------------------------------------------------------

#[test]
fn mirror_configuration_gives_exactly_one() {
    // V = R: R·V = 2(N·L)(N·V) − L·V = 2·0.8·0.8 − (−0.6·0.6 + 0.8·0.8) = 1.28 − 0.28 = 1, and
    // the clamp to [−1, 1] keeps rounding from leaving 1; 1^s = 1 exactly for every s.
    let (n, l) = (Vec3::Z, Vec3::new(0.6, 0.0, 0.8));
    let v = phong::reflect(n, l);
    let g = Incidence::new(n, l, v);
    for s in [0.0f32, 0.5, 1.0, 32.0, 256.0] {
        for pow in [PowStrategy::Exact, PowStrategy::Squaring] {
            let p = Phong {
                pow,
                ..Default::default()
            };
            assert_eq!(p.specular(&g, s), 1.0, "Phong mirror, s={s}, {pow:?}");
        }
    }
    // Blinn: H = N, (N·H)² = (0.8 + 0.8)²/(2 + 2·0.28) = 2.56/2.56 = 1 up to rounding.
    let b = BlinnPhong::default().specular(&g, 128.0);
    assert!((b - 1.0).abs() < 1e-5, "Blinn mirror: {b}");
    // Normal incidence, viewer on the axis: every cosine is exactly 1.
    let g = Incidence::new(Vec3::Z, Vec3::Z, Vec3::Z);
    assert_eq!(g.r_dot_v(), 1.0, "R·V on the axis");
    assert_eq!(g.n_dot_h_squared(), 1.0, "(N·H)² on the axis: 4/4");
    assert_eq!(
        BlinnPhong::default().specular(&g, 32.0),
        1.0,
        "Blinn on the axis"
    );
    assert_eq!(
        Phong::default().specular(&g, 32.0),
        1.0,
        "Phong on the axis"
    );
}

#[test]
fn light_at_45_degrees_gives_diffuse_sqrt2_over_2() {
    // N = Z, L = (1, 0, 1)/√2: N·L = cos 45° = √2/2 = 0.70710677 (f32).
    let l = Vec3::new(1.0, 0.0, 1.0).normalize();
    let g = Incidence::new(Vec3::Z, l, Vec3::Z);
    close(
        Lambert::default().diffuse(&g),
        FRAC_1_SQRT_2,
        1.0,
        "Lambert at 45°",
    );
    close(
        Phong::default().diffuse(&g),
        FRAC_1_SQRT_2,
        1.0,
        "Phong diffuse at 45°",
    );
    // Normalised: √2/2 / π = 0.22507908.
    let lam = Lambert {
        normalization: Normalization::Energy,
    };
    close(lam.diffuse(&g), FRAC_1_SQRT_2 / PI, 2.0, "Lambert/π at 45°");
    // Through shade: a white light at (3, 0, 3), white material, no attenuation:
    // diffuse = Kd·Ld·N·L = √2/2 in every channel.
    let light = PointLight::try_new(
        Vec3::new(3.0, 0.0, 3.0),
        Attenuation::None,
        LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    let m = Material::try_from_color(Vec3::ONE, 32.0).unwrap();
    let t = phong::shade(&Lambert::default(), &m, &scene, Vec3::ZERO, Vec3::Z);
    close_vec(
        t.diffuse,
        Vec3::splat(FRAC_1_SQRT_2),
        1.0,
        "shaded diffuse at 45°",
    );
    assert_eq!(t.specular, Vec3::ZERO, "Lambert has no specular");
}

#[test]
fn cosine_formulas() {
    // N·L = 0.5, N·V = 1, L·V = 0.5 (V = N, L at 60°):
    // R·V = 2·0.5·1 − 0.5 = 0.5; (N·H)² = (0.5 + 1)²/(2 + 2·0.5) = 2.25/3 = 0.75.
    let g = Incidence::from_cosines(0.5, 1.0, 0.5);
    assert_eq!(g.r_dot_v(), 0.5, "R·V");
    assert_eq!(g.n_dot_h_squared(), 0.75, "(N·H)²");
    // Phong with s = 1 is R·V; with s = 3 it is 0.125 (exact).
    assert_eq!(Phong::default().specular(&g, 1.0), 0.5, "Phong s=1");
    assert_eq!(Phong::default().specular(&g, 3.0), 0.125, "Phong s=3");
    // Blinn with s = 2 is (N·H)² = 0.75; with s = 4, 0.5625 (exact).
    assert_eq!(BlinnPhong::default().specular(&g, 2.0), 0.75, "Blinn s=2");
    close(
        BlinnPhong::default().specular(&g, 4.0),
        0.5625,
        1.0,
        "Blinn s=4",
    );
    // Gates at N·L = 0.5: step 1, cosine 0.5, none 1.
    let cos = Phong {
        gate: SpecularGate::Cosine,
        ..Default::default()
    };
    assert_eq!(cos.specular(&g, 1.0), 0.25, "cosine gate: 0.5 · 0.5");
    assert_eq!(SpecularGate::Step.weight(0.5), 1.0, "step gate");
    assert_eq!(SpecularGate::Step.weight(0.0), 0.0, "step gate at 0");
    assert_eq!(SpecularGate::None.weight(-0.5), 1.0, "no gate");
    // Incidence::new of axis vectors: (N·L, N·V, L·V) = (1, 0, 0).
    let g = Incidence::new(Vec3::Z, Vec3::Z, Vec3::X);
    assert_eq!(
        (g.n_dot_l, g.n_dot_v, g.l_dot_v),
        (1.0, 0.0, 0.0),
        "axis cosines"
    );
}

#[test]
fn pow_strategies() {
    // 0.5³ = 0.125 and 0.5³² = 2⁻³² exactly: powers of two, no rounding.
    for p in [PowStrategy::Exact, PowStrategy::Squaring] {
        assert_eq!(p.lobe(0.5, 3.0), 0.125, "{p:?}: 0.5³");
        assert_eq!(p.lobe(0.5, 32.0), 2f32.powi(-32), "{p:?}: 0.5³²");
        assert_eq!(p.lobe(0.25, 0.5), 0.5, "{p:?}: √0.25");
        assert_eq!(p.lobe(1.0, 1e4), 1.0, "{p:?}: 1^s");
        assert_eq!(p.lobe(0.0, 0.0), 0.0, "{p:?}: the documented 0^0 = 0");
        assert_eq!(p.lobe(0.3, 0.0), 1.0, "{p:?}: x^0 = 1 for x > 0");
        assert_eq!(
            p.lobe(-0.5, 2.0),
            0.0,
            "{p:?}: a negative cosine clamps to 0"
        );
        // 0.9f32 is 0.899999976, and 0.899999976^256 = 1.9323219e-12 (f64), 57 ulps below
        // 0.9^256 = 1.9323350e-12. Exact is powf (≤ 1 ulp, 2 allowed); Squaring's documented bound
        // is (s + log₂ s + 1)·2⁻²⁴ = 265·2⁻²⁴ relative = 132.5 ulps (of 2⁻²³).
        let ulps = if p == PowStrategy::Exact { 2.0 } else { 133.0 };
        close(p.lobe(0.9, 256.0), 1.932_322e-12, ulps, "0.9^256");
    }
}

#[test]
fn energy_normalisation_factors() {
    // The factors as a model resolves them (`ResolvedModel::specular_scale`, `diffuse`).
    let phong = |normalization| {
        ResolvedModel::from(Phong {
            normalization,
            ..Default::default()
        })
    };
    let blinn = |normalization| {
        ResolvedModel::from(BlinnPhong {
            normalization,
            ..Default::default()
        })
    };
    // Phong: (s + 2)/(2π): s = 0 → 1/π; s = 2 → 2/π.
    close(
        phong(Normalization::Energy).specular_scale(0.0),
        1.0 / PI,
        2.0,
        "Phong s=0",
    );
    close(
        phong(Normalization::Energy).specular_scale(2.0),
        2.0 / PI,
        2.0,
        "Phong s=2",
    );
    close(
        phong(Normalization::EnergyExact).specular_scale(2.0),
        2.0 / PI,
        2.0,
        "Phong exact = common",
    );
    assert_eq!(
        phong(Normalization::None).specular_scale(100.0),
        1.0,
        "classic Phong"
    );
    // Blinn common: (s + 8)/(8π): s = 8 → 2/π.
    close(
        blinn(Normalization::Energy).specular_scale(8.0),
        2.0 / PI,
        2.0,
        "Blinn s=8",
    );
    // Blinn exact: (s+2)(s+4)/(8π(2^(−s/2) + s)): s = 0 → 8/(8π·1) = 1/π;
    // s = 2 → 4·6/(8π(0.5 + 2)) = 24/(20π) = 1.2/π.
    close(
        blinn(Normalization::EnergyExact).specular_scale(0.0),
        1.0 / PI,
        2.0,
        "exact s=0",
    );
    close(
        blinn(Normalization::EnergyExact).specular_scale(2.0),
        1.2 / PI,
        3.0,
        "exact s=2",
    );
    assert_eq!(
        ResolvedModel::from(Lambert::default()).specular_scale(32.0),
        0.0,
        "no lobe"
    );
    // Diffuse: N·L/π.
    close(
        phong(Normalization::Energy).diffuse(1.0),
        1.0 / PI,
        1.0,
        "diffuse 1/π",
    );
    assert_eq!(
        phong(Normalization::None).diffuse(-1.0),
        0.0,
        "clamped diffuse"
    );
    // A normalised Phong at the mirror with N·L = 1: (s+2)/(2π)·1·1; s = 8 → 5/π.
    let g = Incidence::new(Vec3::Z, Vec3::Z, Vec3::Z);
    let p = Phong {
        normalization: Normalization::Energy,
        ..Default::default()
    };
    close(
        p.specular(&g, 8.0),
        5.0 / PI,
        2.0,
        "normalised Phong at the mirror",
    );
}

// ---------------------------------------------------------------------------------------------
// Geometry
// ---------------------------------------------------------------------------------------------

#[test]
fn reflect_halfway_and_face_forward() {
    // L at 45° in the xy plane mirrored about Y: (1, 1, 0)/√2 → (−1, 1, 0)/√2.
    let l = Vec3::new(1.0, 1.0, 0.0).normalize();
    let r = phong::reflect(Vec3::Y, l);
    close_vec(
        r,
        Vec3::new(-FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0),
        2.0,
        "reflect at 45°",
    );
    // Along the normal: R = L; perpendicular: R = −L (exact).
    assert_eq!(phong::reflect(Vec3::Z, Vec3::Z), Vec3::Z, "L = N");
    assert_eq!(phong::reflect(Vec3::Z, Vec3::X), -Vec3::X, "L ⟂ N");
    // The conformance vector "45_deg": GLSL reflect((√2/2, 0, −√2/2), Z) = (√2/2, 0, √2/2).
    let i = Vec3::new(FRAC_1_SQRT_2, 0.0, -FRAC_1_SQRT_2);
    assert_eq!(
        phong::reflect(Vec3::Z, -i),
        Vec3::new(FRAC_1_SQRT_2, 0.0, FRAC_1_SQRT_2),
        "GLSL reflect(i, n) = reflect(n, −i)"
    );
    // H of X and Y: (1, 1, 0)/√2.
    close_vec(
        phong::halfway_or_zero(Vec3::X, Vec3::Y),
        Vec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0),
        1.0,
        "halfway(X, Y)",
    );
    assert_eq!(
        phong::halfway_or_zero(Vec3::Z, Vec3::Z),
        Vec3::Z,
        "halfway(Z, Z)"
    );
    assert_eq!(phong::try_halfway(Vec3::X, -Vec3::X), None, "no halfway");
    // face_forward(N, V, Nref): N if Nref·V > 0, else −N (the tie goes to −N, as in GLSL).
    assert_eq!(
        phong::face_forward(Vec3::Z, Vec3::Z, Vec3::Z),
        Vec3::Z,
        "facing"
    );
    assert_eq!(
        phong::face_forward(Vec3::Z, -Vec3::Z, Vec3::Z),
        -Vec3::Z,
        "away"
    );
    assert_eq!(
        phong::face_forward(Vec3::Z, Vec3::X, Vec3::Z),
        -Vec3::Z,
        "tie"
    );
}

#[test]
fn triangle_values() {
    // Right triangle with legs 2 and 3: A = (2,0,0) × (0,3,0) = (0, 0, 6), area 3.
    let (a, b, c) = (
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 3.0, 0.0),
    );
    assert_eq!(
        phong::triangle_area_normal(a, b, c),
        Vec3::new(0.0, 0.0, 6.0),
        "A"
    );
    assert_eq!(phong::triangle_normal_or_zero(a, b, c), Vec3::Z, "N");
    assert_eq!(
        phong::triangle_normal_or_zero(a, c, b),
        -Vec3::Z,
        "clockwise"
    );
    // A 3-4-5 face tilted out of the xy plane: (1,0,0) × (0,4,3)... edges (1, 0, 0) and (0, 4, 3):
    // A = (0·3 − 0·4, 0·0 − 1·3, 1·4 − 0·0) = (0, −3, 4), ‖A‖ = 5, N = (0, −0.6, 0.8).
    let n = phong::triangle_normal_or_zero(a, Vec3::X, Vec3::new(0.0, 4.0, 3.0));
    close_vec(n, Vec3::new(0.0, -0.6, 0.8), 1.0, "3-4-5 normal");
    assert_eq!(
        phong::triangle_area_normal(a, Vec3::X, Vec3::new(0.0, 4.0, 3.0)),
        Vec3::new(0.0, -3.0, 4.0),
        "3-4-5 area vector"
    );
    // Vertex normals: two faces of equal area meeting at the x axis, normals −Z and −Y: the shared
    // vertices get (0, −1, −1)/√2, the others their face normal.
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    let mut out = [Vec3::ZERO; 4];
    phong::vertex_normals(&p, &[[0, 2, 1], [0, 1, 3]], &mut out);
    assert_eq!(out[2], -Vec3::Z, "vertex 2");
    assert_eq!(out[3], -Vec3::Y, "vertex 3");
    close_vec(
        out[0],
        Vec3::new(0.0, -FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
        1.0,
        "vertex 0",
    );
}

#[test]
fn normal_matrix_values() {
    // M = diag(2, 1, 1): cof = diag(1·1, 1·2, 2·1) = diag(1, 2, 2), det > 0.
    let m = Mat3::from_diagonal(Vec3::new(2.0, 1.0, 1.0));
    assert_eq!(
        phong::normal_matrix(m),
        Mat3::from_diagonal(Vec3::new(1.0, 2.0, 2.0)),
        "cof(diag(2,1,1))"
    );
    // The normal (1, 1, 0) → (1, 2, 0)/√5: tilted toward the squashed axis.
    let n = phong::transform_normal(phong::normal_matrix(m), Vec3::new(1.0, 1.0, 0.0));
    let s5 = 5f32.sqrt();
    close_vec(
        n,
        Vec3::new(1.0 / s5, 2.0 / s5, 0.0),
        2.0,
        "(1,1,0) under diag(2,1,1)",
    );
    // Mirror diag(−1, 1, 1): cof = diag(1, −1, −1), det = −1, so NM = diag(−1, 1, 1) = M⁻ᵀ.
    let mirror = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
    assert_eq!(phong::normal_matrix(mirror), mirror, "mirror: NM = M⁻ᵀ = M");
    // A rotation: NM = R (cof of a rotation is the rotation itself).
    let r = Mat3::from_rotation_z(0.5);
    let nm = phong::normal_matrix(r);
    for (a, b) in nm.to_cols_array().iter().zip(r.to_cols_array()) {
        assert!((a - b).abs() < 2e-7, "rotation: NM = R, {a} vs {b}");
    }
}

#[test]
fn normalize_and_length() {
    // 3-4-5 at every scale: powers of ten are not exact, so allow a couple of ulps.
    for s in [1e-30f32, 1.0, 1e30] {
        close(
            phong::length(Vec3::new(3.0 * s, 4.0 * s, 0.0)),
            5.0 * s,
            2.0,
            "length 3-4-5",
        );
    }
    assert_eq!(
        phong::length(Vec3::new(3.0, 4.0, 0.0)),
        5.0,
        "length 3-4-5 (exact)"
    );
    assert_eq!(
        phong::normalize_or_zero(Vec3::new(0.0, 2.0, 0.0)),
        Vec3::Y,
        "normalize (0, 2, 0)"
    );
    assert_eq!(
        phong::normalize_or_zero(Vec3::new(3e38, 0.0, 0.0)),
        Vec3::X,
        "normalize a huge axis vector"
    );
    close_vec(
        phong::normalize_or_zero(Vec3::new(3.0, 0.0, 4.0)),
        Vec3::new(0.6, 0.0, 0.8),
        1.0,
        "normalize (3, 0, 4)",
    );
}

// ---------------------------------------------------------------------------------------------
// Attenuation
// ---------------------------------------------------------------------------------------------

#[test]
fn attenuation_values() {
    // LearnOpenGL's range-50 entry (1, 0.09, 0.032):
    //   d = 0: 1/1 = 1;  d = 10: 1/(1 + 0.9 + 3.2) = 1/5.1 = 0.19607843;
    //   d = 50: 1/(1 + 4.5 + 80) = 1/85.5 = 0.011695906.
    let lo = Attenuation::polynomial(1.0, 0.09, 0.032);
    assert_eq!(lo.factor(0.0), 1.0, "LearnOpenGL at 0");
    close(lo.factor(10.0), 1.0 / 5.1, 3.0, "LearnOpenGL at 10");
    close(lo.factor(50.0), 1.0 / 85.5, 3.0, "LearnOpenGL at 50");
    // Pure quadratic: 1/d² — 0.25 at 2, 0.01 at 10; the floor 1e-4 caps it at 1e4 (d ≤ 0.01).
    let q = Attenuation::polynomial(0.0, 0.0, 1.0);
    assert_eq!(q.factor(2.0), 0.25, "1/2²");
    close(q.factor(10.0), 0.01, 1.0, "1/10²");
    assert_eq!(q.factor(0.0), 1e4, "capped at 1/MIN_DENOMINATOR");
    // Inverse square with power 3: 3/2² = 0.75; below ε = 0.01 it stays at 3/ε² = 3e4.
    let p = Attenuation::try_inverse_square(3.0).unwrap();
    assert_eq!(p.factor(2.0), 0.75, "3/2²");
    close(p.factor(0.005), 3e4, 2.0, "3/ε²");
    // Unreal, r = 10, d = 5: (1 − (1/2)⁴)²/(5² + 1) = (15/16)²/26 = 0.87890625/26 = 0.033804087.
    let u = Attenuation::try_unreal(10.0).unwrap();
    close(u.factor(5.0), 0.878_906_25 / 26.0, 1.0, "Unreal at r/2");
    assert_eq!(u.factor(0.0), 1.0, "Unreal at 0: 1/(0 + 1)");
    assert_eq!(u.factor(10.0), 0.0, "Unreal at r");
    assert_eq!(u.factor(11.0), 0.0, "Unreal past r");
    // Frostbite, r = 10, d = 5: (15/16)²/25 = 0.03515625 (= 9/256, exact).
    let f = Attenuation::try_frostbite(10.0).unwrap();
    assert_eq!(f.factor(5.0), 0.035_156_25, "Frostbite at r/2");
    assert_eq!(f.factor(10.0), 0.0, "Frostbite at r");
    assert_eq!(Attenuation::None.factor(1e30), 1.0, "no falloff");
}

#[test]
fn cull_radius_values() {
    // 1/d² < 0.01 beyond d = 10; 4/d² < 1 beyond d = 2; (1 + d)⁻¹ < 0.5 beyond d = 1.
    let q = Attenuation::polynomial(0.0, 0.0, 1.0);
    close(q.cull_radius(0.01), 10.0, 2.0, "quadratic");
    let p = Attenuation::try_inverse_square(4.0).unwrap();
    close(p.cull_radius(1.0), 2.0, 2.0, "inverse square");
    let lin = Attenuation::polynomial(1.0, 1.0, 0.0);
    close(lin.cull_radius(0.5), 1.0, 2.0, "linear");
    assert_eq!(
        Attenuation::None.cull_radius(0.01),
        f32::INFINITY,
        "None never culls"
    );
    // Windowed forms: never beyond the radius.
    let u = Attenuation::try_unreal(8.0).unwrap();
    let r = u.cull_radius(1e-9);
    assert!(
        r <= 8.0 && r > 7.9,
        "Unreal cull radius ≈ r for a tiny threshold: {r}"
    );
}

// ---------------------------------------------------------------------------------------------
// Lights and shading
// ---------------------------------------------------------------------------------------------

#[test]
fn light_colour_parametrisations() {
    let c = Vec3::new(1.0, 0.5, 0.25);
    // Strengths 0.1 / 1 / 0.5: La = 0.1C, Ld = C, Ls = 0.5C.
    let s = LightColors::try_from_strengths(c, 0.1, 1.0, 0.5).unwrap();
    assert_eq!(s.ambient(), c * 0.1, "La");
    assert_eq!(s.diffuse(), c, "Ld");
    assert_eq!(s.specular(), Vec3::new(0.5, 0.25, 0.125), "Ls");
    // Power 4: La = 0, Ld = Ls = 4C.
    let p = LightColors::try_from_power(c, 4.0).unwrap();
    assert_eq!(p.ambient(), Vec3::ZERO, "no ambient");
    assert_eq!(p.diffuse(), Vec3::new(4.0, 2.0, 1.0), "Ld = PC");
    assert_eq!(p.specular(), Vec3::new(4.0, 2.0, 1.0), "Ls = PC");
}

#[test]
fn spot_factor_values() {
    // Axis −Y, exponent 2, cutoff 1.2 rad (cos = 0.362).
    let spot = SpotLight::try_new(
        Vec3::new(0.0, 5.0, 0.0),
        -Vec3::Y,
        1.2,
        2.0,
        Attenuation::None,
        LightColors::BLACK,
    )
    .unwrap();
    // On the axis: (−L·D)² = 1.
    assert_eq!(spot.spot_factor(Vec3::Y), 1.0, "on the axis");
    // 60° off the axis: −L·D = cos 60° = 0.5 → 0.25.
    let l = Vec3::new(60f32.to_radians().sin(), 0.5, 0.0);
    close(spot.spot_factor(l), 0.25, 4.0, "60° off the axis");
    // 80° off the axis: cos 80° = 0.174 < cos 1.2 → outside the cone.
    let l = Vec3::new(80f32.to_radians().sin(), 80f32.to_radians().cos(), 0.0);
    assert_eq!(spot.spot_factor(l), 0.0, "outside the cone");
}

#[test]
fn shade_the_tutorial_configuration() {
    // LearnOpenGL: light and eye on the normal at (0, 0, 5), object colour (1, 0.5, 0.25), light
    // white with strengths 0.1/1/0.5, s = 32. diff = 1 and spec = 1, so
    // ambient = 0.1·C, diffuse = 1·C, specular = 0.5·C, total = 1.6·C = (1.6, 0.8, 0.4).
    let c = Vec3::new(1.0, 0.5, 0.25);
    let light = PointLight::try_new(
        Vec3::new(0.0, 0.0, 5.0),
        Attenuation::None,
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    let m = Material::try_from_color(c, 32.0).unwrap();
    let t = phong::shade(&Phong::learnopengl(), &m, &scene, Vec3::ZERO, Vec3::Z);
    close_vec(t.ambient, c * 0.1, 1.0, "ambient");
    assert_eq!(t.diffuse, c, "diffuse");
    assert_eq!(t.specular, c * 0.5, "specular");
    assert_eq!(t.emission, Vec3::ZERO, "emission");
    close_vec(t.total(), Vec3::new(1.6, 0.8, 0.4), 1.0, "total");

    // The same with LearnOpenGL attenuation at d = 5: f = 1/(1 + 0.45 + 0.8) = 1/2.25 = 4/9, which
    // scales all three terms; plus scene ambient 0.2 and emission (0, 0, 1):
    // ambient = C·(0.2 + 0.1·4/9), diffuse = C·4/9, specular = 0.5·C·4/9.
    let light = PointLight::try_new(
        Vec3::new(0.0, 0.0, 5.0),
        Attenuation::polynomial(1.0, 0.09, 0.032),
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5).unwrap(),
    )
    .unwrap();
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::splat(0.2),
        viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)),
    };
    let m = m.try_with_emission(Vec3::Z).unwrap();
    let t = phong::shade(&Phong::learnopengl(), &m, &scene, Vec3::ZERO, Vec3::Z);
    let f = 4.0 / 9.0;
    close_vec(t.ambient, c * (0.2 + 0.1 * f), 4.0, "attenuated ambient");
    close_vec(t.diffuse, c * f, 4.0, "attenuated diffuse");
    close_vec(t.specular, c * (0.5 * f), 4.0, "attenuated specular");
    assert_eq!(t.emission, Vec3::Z, "emission");

    // A textured override: Kd = Ka = texel (0.5, 0.2, 0.1), Ks = 0.3 — under the first light.
    let base = Material::try_from_color(Vec3::ONE, 8.0).unwrap();
    let tex = base.textured(Vec3::new(0.5, 0.2, 0.1), Vec3::splat(0.3));
    assert_eq!(tex.ambient(), Vec3::new(0.5, 0.2, 0.1), "textured Ka");
    assert_eq!(tex.diffuse(), Vec3::new(0.5, 0.2, 0.1), "textured Kd");
    assert_eq!(tex.specular(), Vec3::splat(0.3), "textured Ks");
    assert_eq!(tex.shininess(), 8.0, "shininess kept");
}

// ---------------------------------------------------------------------------------------------
// Colour
// ---------------------------------------------------------------------------------------------

#[test]
fn srgb_at_the_knee_and_beyond() {
    // The knee: encode(0.0031308) = 12.92 · 0.0031308 = 0.040449936; decode(0.04045) =
    // 0.04045/12.92 = 0.0031308049. The power segment meets it there (1.055·0.0031308^(1/2.4) −
    // 0.055 = 0.0404500 in f64): the two pieces agree to 1e-6, so just above the knee encode is
    // still 0.04045 to six digits.
    close(
        phong::srgb_encode(0.003_130_8),
        0.040_449_936,
        1.0,
        "encode at the knee",
    );
    close(
        phong::srgb_decode(0.040_45),
        0.003_130_805,
        1.0,
        "decode at the knee",
    );
    let above = phong::srgb_encode(0.003_130_8f32.next_up());
    assert!(
        (above - 0.040_45).abs() < 1e-6,
        "encode just above the knee: {above}"
    );
    // Endpoints and the middle: encode(1) = 1.055 − 0.055 = 1; encode(0.5) = 0.7353569;
    // decode(0.5) = ((0.5 + 0.055)/1.055)^2.4 = 0.21404114.
    assert_eq!(phong::srgb_encode(0.0), 0.0, "encode 0");
    close(phong::srgb_encode(1.0), 1.0, 2.0, "encode 1");
    close(phong::srgb_encode(0.5), 0.735_356_9, 2.0, "encode 0.5");
    close(phong::srgb_decode(0.5), 0.214_041_14, 2.0, "decode 0.5");
    // Gamma 2.2: 0.5^(1/2.2) = 0.72974005, 0.5^2.2 = 0.21763764.
    close(
        phong::gamma_encode(0.5, 2.2),
        0.729_740,
        2.0,
        "gamma encode",
    );
    close(
        phong::gamma_decode(0.5, 2.2),
        0.217_637_64,
        2.0,
        "gamma decode",
    );
    // 8 bits: round half up. 0.5 → 127.5 + 0.5 → 128; 0.7353569·255 = 187.5 + … → 188.
    assert_eq!(phong::quantize_u8(0.5), 128, "quantize 0.5");
    assert_eq!(phong::quantize_u8(1.0 / 255.0), 1, "quantize one step");
    assert_eq!(
        phong::linear_to_srgb8(Vec3::new(0.0, 0.5, 1.0)),
        [0, 188, 255],
        "linear → sRGB8"
    );
    assert_eq!(
        phong::saturate(Vec3::new(-0.5, 0.5, 1.5)),
        Vec3::new(0.0, 0.5, 1.0),
        "saturate"
    );
}
