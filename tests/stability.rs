//! Degenerate inputs. From finite input nothing may panic or return NaN/∞ (except the documented
//! "never cull" infinity of `Attenuation::cull_radius`), and where a function documents its answer
//! for a degenerate case, that answer is asserted, not just finiteness.
//!
//! Tests run with debug assertions on, so every call here also stays inside the documented domain
//! of the fast functions (`reflect` with a unit or zero `n`, `Incidence::new` with unit or zero
//! vectors); the total functions (`shade`, `normalize_or_zero`, the triangle functions,
//! `Incidence::from_unnormalized`) get the raw degenerate input.

use core::f32::consts::FRAC_PI_2;

use glam::{Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Incidence, Lambert, Light, LightColors, Material,
    Model, Normalization, Phong, PhongError, PointLight, PowStrategy, ReflectionModel, Scene,
    SpecularGate, SpotLight, Terms, Viewer,
};

const SHININESSES: [f32; 6] = [0.0, 0.5, 1.0, 32.0, 256.0, 1e4];

fn all_models() -> Vec<Model> {
    let mut out = Vec::new();
    for normalization in [
        Normalization::None,
        Normalization::Energy,
        Normalization::EnergyExact,
    ] {
        out.push(Model::Lambert(Lambert { normalization }));
        for gate in [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None] {
            for pow in [PowStrategy::Exact, PowStrategy::Squaring] {
                out.push(Model::Phong(Phong {
                    gate,
                    normalization,
                    pow,
                }));
                out.push(Model::BlinnPhong(BlinnPhong {
                    gate,
                    normalization,
                    pow,
                }));
            }
        }
    }
    out
}

fn assert_vec_finite(v: Vec3, what: &str) {
    assert!(v.is_finite(), "{what}: not finite: {v}");
}

fn assert_unit_or_zero(v: Vec3, what: &str) {
    assert_vec_finite(v, what);
    let l = v.length();
    assert!(
        v == Vec3::ZERO || (l - 1.0).abs() < 1e-6,
        "{what}: neither unit nor zero: {v} (length {l})"
    );
}

fn assert_terms_ok(t: &Terms, what: &str) {
    for (name, v) in [
        ("ambient", t.ambient),
        ("diffuse", t.diffuse),
        ("specular", t.specular),
        ("emission", t.emission),
        ("total", t.total()),
    ] {
        assert!(
            v.is_finite() && v.min_element() >= 0.0,
            "{what}: {name} = {v} must be finite and ≥ 0"
        );
    }
}

/// Every lobe of every model is finite and ≥ 0 (and ≤ 1 when classic) for the cosines `g`.
fn assert_lobes_ok(g: &Incidence, what: &str) {
    for m in all_models() {
        for s in SHININESSES {
            let (kd, ks) = (m.diffuse(g), m.specular(g, s));
            assert!(
                kd.is_finite() && kd >= 0.0,
                "{what}: diffuse {kd} for {m:?}, {g:?}"
            );
            assert!(
                ks.is_finite() && ks >= 0.0,
                "{what}: specular {ks} for {m:?}, s={s}, {g:?}"
            );
        }
    }
}

fn white() -> LightColors {
    LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5).unwrap()
}

fn plastic(s: f32) -> Material {
    Material::try_from_color(Vec3::new(1.0, 0.5, 0.25), s).unwrap()
}

fn shade_one<M: ReflectionModel>(
    model: &M,
    light: Light,
    viewer: Viewer,
    p: Vec3,
    n: Vec3,
    s: f32,
) -> Terms {
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer,
    };
    let free = phong::shade(model, &plastic(s), &scene, p, n);
    // The prepared shader's one-light path (straight-line, full-range normalisation) on the same
    // degenerate input: as total as the light loop, and the same answer. The two normalisations
    // differ only where a squared component is subnormal inside the common range: a relative
    // error below about 1e-8 in a direction, which the lobe's exponent multiplies by at most
    // `s`; the rest is a few roundings (1e-6), and 1e-35 absolute covers subnormal outputs.
    let one = phong::Shader::new(model, &plastic(s), &scene).shade(p, n);
    assert_terms_ok(&one, "Shader (one light)");
    let tol = |b: Vec3| b.abs() * (1e-6 + 1e-8 * s.max(1.0)) + Vec3::splat(1e-35);
    for (a, b) in [
        (one.ambient, free.ambient),
        (one.diffuse, free.diffuse),
        (one.specular, free.specular),
    ] {
        assert!(
            (a - b).abs().cmple(tol(b)).all(),
            "one-light path {a} vs light loop {b} at p = {p}, n = {n}, s = {s}"
        );
    }
    free
}

fn point_light(p: Vec3, a: Attenuation) -> Light {
    PointLight::try_new(p, a, white()).unwrap().into()
}

// ---------------------------------------------------------------------------------------------
// Triangles
// ---------------------------------------------------------------------------------------------

#[test]
fn zero_area_triangles_have_no_normal() {
    let p = Vec3::new(1.5, -2.0, 3.25);
    let cases = [
        ("all three equal", p, p, p),
        ("two equal", p, p, Vec3::ONE),
        ("exactly collinear", Vec3::ZERO, Vec3::ONE, Vec3::splat(2.0)),
        ("collinear on an axis", Vec3::ZERO, Vec3::X, 3.0 * Vec3::X),
        ("origin", Vec3::ZERO, Vec3::ZERO, Vec3::ZERO),
        (
            "repeated near f32::MAX",
            Vec3::splat(3e38),
            Vec3::splat(3e38),
            Vec3::splat(-3e38),
        ),
        (
            "repeated subnormal",
            Vec3::splat(1e-40),
            Vec3::splat(1e-40),
            Vec3::ZERO,
        ),
    ];
    for (what, a, b, c) in cases {
        // Documented: the zero vector / None for exactly collinear or repeated vertices.
        assert_eq!(
            phong::triangle_area_normal(a, b, c),
            Vec3::ZERO,
            "{what}: area normal"
        );
        assert_eq!(
            phong::triangle_normal_or_zero(a, b, c),
            Vec3::ZERO,
            "{what}: unit normal"
        );
        assert_eq!(
            phong::try_triangle_normal(a, b, c),
            None,
            "{what}: try_triangle_normal"
        );
    }
}

#[test]
fn sliver_triangles_keep_their_normal() {
    // The conformance edge case: a 1e-7 sliver. In f64 the area vector is (0, 0, 1e-7) exactly.
    let n = phong::triangle_normal_or_zero(Vec3::ZERO, Vec3::X, Vec3::new(2.0, 1e-7, 0.0));
    assert_eq!(n, Vec3::Z, "sliver 1e-7 must give +Z");
    // Needles far from the origin, where the naive f32 cross product loses most digits. The f64
    // edges are exact, so the normal is the exact one: +Z in the xy plane.
    for offset in [1e3f32, 1e5, 1e7] {
        let o = Vec3::new(offset, -offset, offset);
        let h = offset * f32::EPSILON * 4.0; // a few ulps of the offset: the thinnest sliver
        let (p1, p2) = (o + Vec3::new(1.0, 0.0, 0.0), o + Vec3::new(2.0, h, 0.0));
        let n = phong::triangle_normal_or_zero(o, p1, p2);
        assert!(
            (n - Vec3::Z).length() < 1e-6,
            "needle at {offset}, height {h}: {n}"
        );
        assert_eq!(
            phong::triangle_normal_or_zero(o, p2, p1),
            -n,
            "needle at {offset}: winding"
        );
    }
    // Collinear in exact arithmetic but not in f32: (3, 3, 3 + ulp) is a real, if tiny, triangle.
    let third = Vec3::new(3.0, 3.0, 3.0f32.next_up());
    let n = phong::triangle_normal_or_zero(Vec3::ZERO, Vec3::ONE, third);
    assert_unit_or_zero(n, "f32-rounded collinear");
    assert!(n != Vec3::ZERO, "a non-zero f32 area must give a normal");
    assert!(n.dot(Vec3::ONE).abs() < 1e-6, "normal ⟂ the long edge: {n}");
}

#[test]
fn huge_tiny_and_subnormal_triangles() {
    // Vertices near ±3e38: the edges (6e38) overflow f32 but not f64. The area vector saturates at
    // f32::MAX (documented) and the unit normal is exact.
    let (a, b, c) = (
        Vec3::new(-3e38, -3e38, 0.0),
        Vec3::new(3e38, -3e38, 0.0),
        Vec3::new(-3e38, 3e38, 0.0),
    );
    assert_eq!(
        phong::triangle_area_normal(a, b, c),
        Vec3::new(0.0, 0.0, f32::MAX),
        "huge triangle: saturated area normal"
    );
    assert_eq!(
        phong::triangle_normal_or_zero(a, b, c),
        Vec3::Z,
        "huge triangle: unit normal"
    );
    assert_eq!(
        phong::triangle_normal_or_zero(a, c, b),
        -Vec3::Z,
        "huge triangle: flipped"
    );
    // Subnormal vertices: the area (1e-80) underflows f32, but f64 keeps it, so the unit normal is
    // still exact; the area normal is finite (it rounds to zero in f32).
    for s in [1e-20f32, 1e-38, 1e-40, 1e-44] {
        let (a, b, c) = (Vec3::ZERO, Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, s, 0.0));
        assert_eq!(
            phong::triangle_normal_or_zero(a, b, c),
            Vec3::Z,
            "tiny triangle of size {s}"
        );
        assert_vec_finite(phong::triangle_area_normal(a, b, c), "tiny area normal");
    }
    // Mixed scales: a huge offset with a unit-size triangle; and the smallest subnormal step.
    let o = Vec3::splat(1e30);
    let n = phong::triangle_normal_or_zero(
        o,
        o + Vec3::new(1e23, 0.0, 0.0),
        o + Vec3::new(0.0, 1e23, 0.0),
    );
    assert_unit_or_zero(n, "1e23 triangle at 1e30");
    let tiny = f32::from_bits(1);
    let n = phong::triangle_normal_or_zero(
        Vec3::ZERO,
        Vec3::new(tiny, 0.0, 0.0),
        Vec3::new(0.0, tiny, 0.0),
    );
    assert_eq!(n, Vec3::Z, "triangle with sides of the smallest subnormal");
}

#[test]
fn vertex_normals_of_degenerate_meshes() {
    // A vertex used by no face, a zero-area face, and two faces that cancel: documented zero.
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(7.0, 7.0, 7.0)];
    let tris = [[0, 1, 2], [0, 2, 1], [0, 0, 1]];
    let mut n = [Vec3::ONE; 4];
    phong::vertex_normals(&p, &tris, &mut n);
    for (i, v) in n.iter().enumerate() {
        assert_eq!(*v, Vec3::ZERO, "vertex {i}: cancelling or unused faces");
    }
}

// ---------------------------------------------------------------------------------------------
// L = −V
// ---------------------------------------------------------------------------------------------

#[test]
fn light_opposite_the_viewer() {
    let l = Vec3::new(2.0, 1.0, 3.0).normalize();
    let v = -l;
    // Documented: no halfway vector.
    assert_eq!(phong::halfway_or_zero(l, v), Vec3::ZERO, "halfway(L, −L)");
    assert_eq!(phong::try_halfway(l, v), None, "try_halfway(L, −L)");
    for n in [Vec3::Z, l, -l, Vec3::X] {
        let g = Incidence::new(n, l, v);
        // Documented: (N·H)² = 0 and so no Blinn-Phong lobe, under every gate and normalisation.
        assert_eq!(g.n_dot_h_squared(), 0.0, "(N·H)² at L = −V, n={n}");
        for m in all_models() {
            if let Model::BlinnPhong(b) = m {
                for s in SHININESSES {
                    assert_eq!(
                        b.specular(&g, s),
                        0.0,
                        "Blinn lobe at L = −V: {b:?} s={s} n={n}"
                    );
                }
            }
        }
        assert_lobes_ok(&g, "L = −V");
    }
    // Through shade: a point light and a local viewer on opposite sides of the point, and a
    // directional light with the infinite viewer opposite it. Documented: no Blinn-Phong specular.
    let p = Vec3::new(0.5, -0.25, 1.0);
    let off = Vec3::new(2.0, 1.0, 3.0);
    for (light, viewer) in [
        (point_light(p + off, Attenuation::None), Viewer::At(p - off)),
        (
            DirectionalLight::try_new(off, white()).unwrap().into(),
            Viewer::Infinite(-off),
        ),
    ] {
        for s in SHININESSES {
            let blinn = BlinnPhong {
                gate: SpecularGate::None,
                ..Default::default()
            };
            let t = shade_one(&blinn, light, viewer, p, Vec3::Z, s);
            assert_terms_ok(&t, "shade at L = −V");
            assert_eq!(t.specular, Vec3::ZERO, "Blinn specular at L = −V, s={s}");
            assert!(t.diffuse.x > 0.0, "the light is above the surface: {t:?}");
            let t = shade_one(&Phong::learnopengl(), light, viewer, p, Vec3::Z, s);
            assert_terms_ok(&t, "Phong shade at L = −V");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Zero and tiny vectors
// ---------------------------------------------------------------------------------------------

#[test]
fn zero_and_tiny_vectors_normalise() {
    assert_eq!(phong::normalize_or_zero(Vec3::ZERO), Vec3::ZERO, "zero");
    assert_eq!(phong::try_normalize(Vec3::ZERO), None, "try zero");
    assert_eq!(phong::length(Vec3::ZERO), 0.0, "length of zero");
    let smallest = f32::from_bits(1); // 1.4e-45
    for s in [1e-20f32, 1e-30, 1e-38, 1e-40, smallest] {
        // Axis vectors: the power-of-two rescaling is exact, so the answer is exactly the axis.
        for (axis, what) in [(Vec3::X, "x"), (-Vec3::Y, "−y"), (Vec3::Z, "z")] {
            assert_eq!(
                phong::normalize_or_zero(axis * s),
                axis,
                "normalize({what} · {s:e})"
            );
        }
        // A diagonal: unit to a few ulps, pointing along (1, 1, 1).
        let n = phong::normalize_or_zero(Vec3::splat(s));
        assert!(
            (n - Vec3::splat(1.0 / 3f32.sqrt())).length() < 1e-6,
            "normalize(({s:e}, {s:e}, {s:e})) = {n}"
        );
    }
    // length: 5e-20 and, for subnormals, the value to the few bits they carry.
    let l = phong::length(Vec3::new(3e-20, 4e-20, 0.0));
    assert!(
        (l / 5e-20 - 1.0).abs() < 1e-6,
        "length((3,4,0)·1e-20) = {l:e}"
    );
    let l = phong::length(Vec3::new(3e-40, 4e-40, 0.0));
    assert!(
        (l / 5e-40 - 1.0).abs() < 1e-4,
        "length((3,4,0)·1e-40) = {l:e}"
    );
}

#[test]
fn zero_and_tiny_vectors_in_the_geometry() {
    let l = Vec3::new(0.6, 0.0, 0.8);
    // Documented: a zero L reflects to zero; a zero N gives −L.
    assert_eq!(
        phong::reflect(Vec3::Z, Vec3::ZERO),
        Vec3::ZERO,
        "reflect(n, 0)"
    );
    assert_eq!(phong::reflect(Vec3::ZERO, l), -l, "reflect(0, l)");
    // reflect is linear in L: a tiny L gives a tiny R, no NaN.
    let r = phong::reflect(Vec3::Z, l * 1e-40);
    assert_vec_finite(r, "reflect of a subnormal L");
    // Documented: a zero V or Nref gives −N.
    assert_eq!(
        phong::face_forward(Vec3::Z, Vec3::ZERO, Vec3::Z),
        -Vec3::Z,
        "face_forward, V = 0"
    );
    assert_eq!(
        phong::face_forward(Vec3::Z, Vec3::Z, Vec3::ZERO),
        -Vec3::Z,
        "face_forward, Nref = 0"
    );
    // Tiny vectors: the sign of Nref·V is decided exactly, so agreeing vectors keep N however
    // small their product.
    assert_eq!(
        phong::face_forward(Vec3::Z, Vec3::Z * 1e-20, Vec3::Z * 1e-20),
        Vec3::Z,
        "face_forward with a subnormal Nref·V"
    );
    let f = phong::face_forward(Vec3::Z, Vec3::Z * 1e-30, Vec3::Z * 1e-30);
    assert!(
        f == Vec3::Z || f == -Vec3::Z,
        "face_forward returns ±N: {f}"
    );
    // halfway of zero vectors: zero, documented as "no halfway vector".
    assert_eq!(
        phong::halfway_or_zero(Vec3::ZERO, Vec3::ZERO),
        Vec3::ZERO,
        "halfway(0, 0)"
    );
    assert_eq!(
        phong::halfway_or_zero(Vec3::Z, Vec3::ZERO),
        Vec3::Z,
        "halfway(Z, 0) = Z (normalised sum)"
    );
    // Incidence: a zero vector contributes zero cosines; tiny vectors are normalised exactly.
    let g = Incidence::from_unnormalized(Vec3::ZERO, l, Vec3::Z);
    assert_eq!(
        (g.n_dot_l, g.n_dot_v),
        (0.0, 0.0),
        "zero normal: zero cosines"
    );
    assert_lobes_ok(&g, "zero normal");
    let g = Incidence::from_unnormalized(Vec3::Z * 1e-40, l * 1e-30, Vec3::Z * 1e-20);
    assert_eq!(g.n_dot_v, 1.0, "tiny N and V normalise exactly to Z: {g:?}");
    assert!((g.n_dot_l - 0.8).abs() < 1e-6, "tiny L normalises: {g:?}");
    assert!((g.l_dot_v - 0.8).abs() < 1e-6, "tiny L normalises: {g:?}");
    let g = Incidence::from_unnormalized(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    assert_eq!(g, Incidence::default(), "all zero");
    assert_lobes_ok(&g, "all-zero incidence");
    // Directions for lights: zero is rejected by name; a subnormal direction still normalises.
    assert_eq!(
        DirectionalLight::try_new(Vec3::ZERO, white()),
        Err(PhongError::ZeroDirection {
            field: "light.direction"
        }),
        "zero light direction"
    );
    let sun = DirectionalLight::try_new(Vec3::new(0.0, 1e-40, 0.0), white()).unwrap();
    assert_eq!(sun.direction(), Vec3::Y, "subnormal light direction");
}

#[test]
fn shading_with_zero_and_tiny_normals() {
    let light = point_light(Vec3::new(0.0, 0.0, 5.0), Attenuation::None);
    let viewer = Viewer::At(Vec3::new(1.0, 0.0, 5.0));
    let reference = shade_one(
        &Phong::learnopengl(),
        light,
        viewer,
        Vec3::ZERO,
        Vec3::Z,
        32.0,
    );
    assert_terms_ok(&reference, "unit normal");
    // Documented: a zero normal gives only ambient and emission.
    let t = shade_one(
        &Phong::learnopengl(),
        light,
        viewer,
        Vec3::ZERO,
        Vec3::ZERO,
        32.0,
    );
    assert_terms_ok(&t, "zero normal");
    assert_eq!(t.diffuse, Vec3::ZERO, "zero normal: no diffuse");
    assert_eq!(t.specular, Vec3::ZERO, "zero normal: no specular");
    assert_eq!(
        t.ambient, reference.ambient,
        "zero normal: ambient unchanged"
    );
    // Documented: the normal is normalised over the whole f32 range, so tiny, subnormal and huge
    // axis normals are exactly +Z (Mesa gives 0 for 1e-20 and 1e20: subnormal flush, overflow).
    for scale in [1e-20f32, 1e-40, f32::from_bits(1), 1e20, f32::MAX] {
        let t = shade_one(
            &Phong::learnopengl(),
            light,
            viewer,
            Vec3::ZERO,
            Vec3::Z * scale,
            32.0,
        );
        assert_eq!(t, reference, "normal Z · {scale:e} must shade like Z");
    }
}

// ---------------------------------------------------------------------------------------------
// Grazing angles
// ---------------------------------------------------------------------------------------------

#[test]
fn grazing_light() {
    let n = Vec3::Z;
    for c in [1e-7f32, -1e-7] {
        let l = Vec3::new(1.0, 0.0, c).normalize();
        let v = phong::reflect(n, l); // the mirror direction, also grazing
        let g = Incidence::new(n, l, v);
        assert_eq!(g.n_dot_l, c, "N·L of the grazing light");
        assert_lobes_ok(&g, "grazing");
        let phong_step = Phong::default();
        let phong_cos = Phong {
            gate: SpecularGate::Cosine,
            ..Default::default()
        };
        let phong_none = Phong::learnopengl();
        if c > 0.0 {
            // Just above the horizon: the diffuse lobe is N·L; the mirror highlight is full under
            // the step gate and scaled by N·L under the cosine gate.
            assert_eq!(phong_step.diffuse(&g), c, "diffuse at N·L = {c}");
            assert_eq!(
                phong_step.specular(&g, 32.0),
                1.0,
                "step-gated mirror at N·L = {c}"
            );
            assert_eq!(
                phong_cos.specular(&g, 32.0),
                c,
                "cosine-gated mirror at N·L = {c}"
            );
            // Blinn-Phong here is only required to be finite: in f32, L·V rounds to exactly −1, so
            // the cosine formula cannot see the highlight (see the ignored test below).
        } else {
            // Just below: no diffuse; the step and cosine gates cut the highlight; the "none" gate
            // keeps Phong's back-face halo (R = V gives 1), as LearnOpenGL's shader does.
            assert_eq!(phong_step.diffuse(&g), 0.0, "diffuse at N·L = {c}");
            assert_eq!(phong_step.specular(&g, 32.0), 0.0, "step gate at N·L = {c}");
            assert_eq!(
                phong_cos.specular(&g, 32.0),
                0.0,
                "cosine gate at N·L = {c}"
            );
            assert_eq!(
                phong_none.specular(&g, 32.0),
                1.0,
                "no gate: the halo at N·L = {c}"
            );
            // Blinn's lobe is max(N·H, 0): with both L and V below, H is below too.
            let blinn_none = BlinnPhong {
                gate: SpecularGate::None,
                ..Default::default()
            };
            assert_eq!(
                blinn_none.specular(&g, 32.0),
                0.0,
                "Blinn, no gate, H below, N·L = {c}"
            );
        }
    }
    // Through shade: a light 1e7 away along the surface (N·L ≈ ±1e-7).
    for z in [1.0f32, -1.0] {
        let light = point_light(Vec3::new(1e7, 0.0, z), Attenuation::None);
        for m in all_models() {
            let t = shade_one(
                &m,
                light,
                Viewer::At(Vec3::new(-1e7, 0.0, z)),
                Vec3::ZERO,
                Vec3::Z,
                32.0,
            );
            assert_terms_ok(&t, "grazing shade");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Shininess 0, 0.5, 1
// ---------------------------------------------------------------------------------------------

#[test]
fn zero_to_the_zero_is_zero() {
    // Documented 0^0 = 0 (the limit s → 0⁺ of a clamped cosine of zero), for both strategies.
    for p in [PowStrategy::Exact, PowStrategy::Squaring] {
        assert_eq!(p.lobe(0.0, 0.0), 0.0, "{p:?}: 0^0");
        assert_eq!(p.lobe(-0.0, 0.0), 0.0, "{p:?}: (−0)^0");
        assert_eq!(p.lobe(-0.5, 0.0), 0.0, "{p:?}: (−0.5)^0 (clamped base 0)");
        assert_eq!(
            p.lobe(f32::from_bits(1), 0.0),
            1.0,
            "{p:?}: (smallest subnormal)^0"
        );
        assert_eq!(p.lobe(0.3, 0.0), 1.0, "{p:?}: 0.3^0");
        assert_eq!(p.lobe(1.0, 0.0), 1.0, "{p:?}: 1^0");
        // Documented: NaN or negative s is treated as 0, NaN x as 0.
        assert_eq!(p.lobe(0.3, f32::NAN), 1.0, "{p:?}: NaN exponent");
        assert_eq!(p.lobe(0.3, -2.0), 1.0, "{p:?}: negative exponent");
        assert_eq!(p.lobe(f32::NAN, 2.0), 0.0, "{p:?}: NaN base");
    }
}

#[test]
fn low_shininess_phong_cut_off_and_blinn_fall_off() {
    let n = Vec3::Z;
    let l = Vec3::new(-1.0, 0.0, 1.0).normalize(); // 45°, R = (1, 0, 1)/√2
    // V above the surface but more than 90° from R: R·V < 0.
    let v_cut = Vec3::new(-1.0, 0.0, 0.2).normalize();
    let g_cut = Incidence::new(n, l, v_cut);
    assert!(
        g_cut.r_dot_v() < 0.0,
        "setup: R·V < 0, got {}",
        g_cut.r_dot_v()
    );
    assert!(
        g_cut.n_dot_l > 0.0 && g_cut.n_dot_v > 0.0,
        "setup: L and V above"
    );
    for s in [0.0f32, 0.5, 1.0] {
        // Phong: the documented hard cut-off at R·V = 0, even with L and V above the surface.
        assert_eq!(
            Phong::default().specular(&g_cut, s),
            0.0,
            "Phong cut-off, s={s}"
        );
        // Blinn-Phong: N·H > 0 whenever L and V are above the surface — no edge.
        let b = BlinnPhong::default().specular(&g_cut, s);
        assert!(b > 0.0 && b <= 1.0, "Blinn has no cut-off, s={s}: {b}");
        if s == 0.0 {
            assert_eq!(b, 1.0, "Blinn at s = 0 is 1 wherever N·H > 0");
        }
        assert_lobes_ok(&g_cut, "low shininess");
    }
    // At R·V = 0 exactly (light overhead, viewer on the horizon) the clamped base is 0, so Phong
    // gives 0 for every s, including s = 0 (0^0 = 0).
    let g = Incidence::from_cosines(1.0, 0.0, 0.0);
    assert_eq!(g.r_dot_v(), 0.0, "setup: R·V = 0");
    for s in [0.0f32, 0.5, 1.0] {
        assert_eq!(
            Phong::default().specular(&g, s),
            0.0,
            "Phong at R·V = 0, s={s}"
        );
    }
    // Continuity of the two lobes across Phong's edge, for s = 0.5: Phong jumps from √ε to 0 over
    // an ε-step of R·V (infinite slope); Blinn moves by O(ε).
    let eps = 1e-6f32;
    let just_in = Incidence::from_cosines(0.6, 0.6, 2.0 * 0.36 - eps);
    let just_out = Incidence::from_cosines(0.6, 0.6, 2.0 * 0.36 + eps);
    let (p_in, p_out) = (
        Phong::default().specular(&just_in, 0.5),
        Phong::default().specular(&just_out, 0.5),
    );
    assert_eq!(p_out, 0.0, "Phong just past the edge");
    assert!(p_in > 5e-4, "Phong just inside the edge is ≈ √ε: {p_in}");
    let (b_in, b_out) = (
        BlinnPhong::default().specular(&just_in, 0.5),
        BlinnPhong::default().specular(&just_out, 0.5),
    );
    assert!(
        (b_in - b_out).abs() < 1e-5,
        "Blinn is smooth there: {b_in} vs {b_out}"
    );
    // Materials accept these shininesses and shade finitely.
    for s in [0.0f32, 0.5, 1.0] {
        let light = point_light(Vec3::new(-3.0, 0.0, 3.0), Attenuation::None);
        for m in all_models() {
            let t = shade_one(
                &m,
                light,
                Viewer::At(Vec3::new(-5.0, 0.0, 1.0)),
                Vec3::ZERO,
                Vec3::Z,
                s,
            );
            assert_terms_ok(&t, "low shininess shade");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Distances
// ---------------------------------------------------------------------------------------------

fn forms() -> [(Attenuation, &'static str); 7] {
    [
        (Attenuation::None, "none"),
        (
            Attenuation::polynomial(1.0, 0.09, 0.032),
            "LearnOpenGL polynomial",
        ),
        (Attenuation::polynomial(0.0, 0.0, 1.0), "pure quadratic"),
        (
            Attenuation::polynomial(0.0, 0.0, 0.0),
            "all-zero polynomial",
        ),
        (
            Attenuation::try_inverse_square(2.0).unwrap(),
            "inverse square, P = 2",
        ),
        (Attenuation::try_unreal(10.0).unwrap(), "Unreal r = 10"),
        (
            Attenuation::try_frostbite(10.0).unwrap(),
            "Frostbite r = 10",
        ),
    ]
}

#[test]
fn attenuation_at_zero_distance_is_finite_and_documented() {
    let eps2 = Attenuation::DEFAULT_MIN_DISTANCE * Attenuation::DEFAULT_MIN_DISTANCE;
    let expected = [
        1.0,
        1.0,                                // 1/c
        1.0 / Attenuation::MIN_DENOMINATOR, // documented cap 1e4
        1.0 / Attenuation::MIN_DENOMINATOR, // all zero: also the cap
        2.0 / eps2,                         // P/ε²
        1.0,                                // window(0)/(0 + 1)
        1.0 / eps2,                         // window(0)/ε²
    ];
    for ((a, what), want) in forms().into_iter().zip(expected) {
        for d in [0.0f32, -0.0, -1.0, f32::NAN, -f32::MAX] {
            // Documented: negative d and NaN are treated as 0.
            let f = a.factor(d);
            assert!(
                (f - want).abs() <= 1e-6 * want,
                "{what}: factor({d}) = {f}, want {want}"
            );
        }
    }
    assert_eq!(
        Attenuation::polynomial(0.0, 0.0, 1.0).factor(0.0),
        1e4,
        "the doc example: finite at the light"
    );
}

#[test]
fn attenuation_at_huge_distances() {
    for (a, what) in forms() {
        for d in [1e19f32, 1e30, f32::MAX, f32::INFINITY] {
            let f = a.factor(d);
            assert!(f.is_finite() && f >= 0.0, "{what}: factor({d:e}) = {f}");
            match a {
                Attenuation::None => assert_eq!(f, 1.0, "{what} never fades"),
                Attenuation::Polynomial {
                    linear, quadratic, ..
                } if linear > 0.0 || quadratic > 0.0 => {
                    assert!(f < 1e-30, "{what}: factor({d:e}) = {f} must vanish")
                }
                Attenuation::Unreal { .. } | Attenuation::Frostbite { .. } => {
                    assert_eq!(f, 0.0, "{what}: beyond the radius")
                }
                Attenuation::InverseSquare { .. } => {
                    assert!(f < 1e-30, "{what}: factor({d:e}) = {f}")
                }
                _ => {}
            }
        }
    }
    // Cull radii: finite, or the documented "never cull" infinity.
    for (a, what) in forms() {
        for t in [1e-30f32, 1e-3, 0.5, 1.0, 2.0, 1e30] {
            let r = a.cull_radius(t);
            assert!(!r.is_nan() && r >= 0.0, "{what}: cull_radius({t}) = {r}");
        }
        assert_eq!(
            a.cull_radius(0.0),
            f32::INFINITY,
            "{what}: t = 0 never culls"
        );
        assert_eq!(
            a.cull_radius(-1.0),
            f32::INFINITY,
            "{what}: t < 0 never culls"
        );
        assert_eq!(
            a.cull_radius(f32::NAN),
            f32::INFINITY,
            "{what}: NaN t never culls"
        );
    }
    assert_eq!(
        Attenuation::None.cull_radius(1.0),
        f32::INFINITY,
        "None at t = 1"
    );
    assert_eq!(Attenuation::None.cull_radius(1.5), 0.0, "None above 1");
    let r = Attenuation::polynomial(0.0, 0.0, 1.0).cull_radius(1e-38);
    assert!(r.is_finite(), "pure quadratic at a tiny threshold: {r}");
}

#[test]
fn light_at_the_shaded_point() {
    let p = Vec3::new(1.0, 2.0, 3.0);
    for (a, what) in forms() {
        // Documented: the light adds ambient only, with the finite factor at d = 0.
        let light = point_light(p, a);
        for m in all_models() {
            let t = shade_one(&m, light, Viewer::At(p + Vec3::Z), p, Vec3::Z, 32.0);
            assert_terms_ok(&t, what);
            assert_eq!(t.diffuse, Vec3::ZERO, "{what}: no diffuse at d = 0");
            assert_eq!(t.specular, Vec3::ZERO, "{what}: no specular at d = 0");
            let want =
                plastic(32.0).ambient() * (Vec3::splat(0.05) + white().ambient() * a.factor(0.0));
            assert!(
                (t.ambient - want).abs().max_element() <= 1e-6 * want.max_element(),
                "{what}: ambient {} vs Ka⊙(Ia + La·f(0)) = {want}",
                t.ambient
            );
        }
    }
    // A spot light at the point: no direction, so its cone factor is 0 (documented on
    // spot_factor) and it contributes nothing, not even ambient.
    let spot = SpotLight::try_new(p, -Vec3::Z, 0.5, 2.0, Attenuation::None, white()).unwrap();
    assert_eq!(spot.spot_factor(Vec3::ZERO), 0.0, "spot factor of a zero L");
    let t = shade_one(
        &Phong::default(),
        spot.into(),
        Viewer::At(p + Vec3::Z),
        p,
        Vec3::Z,
        32.0,
    );
    assert_terms_ok(&t, "spot at the point");
    assert_eq!(
        t.diffuse + t.specular,
        Vec3::ZERO,
        "spot at the point: no direct light"
    );
    // The viewer at the point: documented no specular. Also a zero infinite-viewer direction.
    let light = point_light(p + Vec3::new(0.0, 0.0, 5.0), Attenuation::None);
    for viewer in [Viewer::At(p), Viewer::Infinite(Vec3::ZERO)] {
        for m in all_models() {
            let t = shade_one(&m, light, viewer, p, Vec3::Z, 32.0);
            assert_terms_ok(&t, "viewer at the point");
            assert_eq!(t.specular, Vec3::ZERO, "{viewer:?}: no specular for {m:?}");
        }
    }
}

#[test]
fn lights_at_huge_distances() {
    // Opposite corners of the f32 range: the difference overflows and is saturated; the direction
    // stays (1, 1, 1)/√3 and the distance saturates at f32::MAX.
    let p = Vec3::splat(-3e38);
    let n = Vec3::ONE; // un-normalised on purpose: shade normalises
    let light = point_light(Vec3::splat(3e38), Attenuation::None);
    let t = shade_one(
        &Phong::default(),
        light,
        Viewer::At(Vec3::splat(3e38)),
        p,
        n,
        32.0,
    );
    assert_terms_ok(&t, "corner to corner");
    // N = L = V: diffuse = Kd·Ld·1, specular = Ks·Ls·1.
    let want_d = plastic(32.0).diffuse() * white().diffuse();
    assert!(
        (t.diffuse - want_d).abs().max_element() < 1e-6,
        "corner-to-corner diffuse {} vs {want_d}",
        t.diffuse
    );
    for (a, what) in forms() {
        for pos in [
            Vec3::new(1e30, 0.0, 1e30),
            Vec3::new(f32::MAX, f32::MAX, f32::MAX),
        ] {
            let light = point_light(pos, a);
            for m in all_models() {
                let t = shade_one(
                    &m,
                    light,
                    Viewer::At(Vec3::new(0.0, 0.0, 1.0)),
                    Vec3::ZERO,
                    Vec3::Z,
                    32.0,
                );
                assert_terms_ok(&t, what);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Singular and mirrored model matrices
// ---------------------------------------------------------------------------------------------

#[test]
fn singular_model_matrices() {
    let normals = [
        Vec3::X,
        Vec3::Y,
        Vec3::Z,
        Vec3::new(0.3, -0.2, 0.9),
        Vec3::ZERO,
    ];
    // Documented: a flattening transform maps normals to the flat surface's normal, and to zero
    // where no normal exists.
    let flat = phong::normal_matrix(Mat3::from_diagonal(Vec3::new(1.0, 1.0, 0.0)));
    assert_eq!(
        phong::transform_normal(flat, Vec3::new(0.3, 0.2, 0.9)),
        Vec3::Z,
        "flattened z"
    );
    assert_eq!(
        phong::transform_normal(flat, Vec3::new(0.3, 0.2, -0.9)),
        -Vec3::Z,
        "flattened −z"
    );
    assert_eq!(
        phong::transform_normal(flat, Vec3::X),
        Vec3::ZERO,
        "no normal for x"
    );
    for (m, what) in [
        (Mat3::ZERO, "zero matrix"),
        (Mat3::from_cols(Vec3::X, Vec3::X, Vec3::X), "rank 1"),
        (
            Mat3::from_diagonal(Vec3::new(1.0, 0.0, 0.0)),
            "rank 1 diagonal",
        ),
        (
            Mat3::from_cols(Vec3::X, Vec3::Y, Vec3::X + Vec3::Y),
            "rank 2, dependent columns",
        ),
    ] {
        let nm = phong::normal_matrix(m);
        assert!(nm.is_finite(), "{what}: normal matrix {nm:?}");
        for n in normals {
            let t = phong::transform_normal(nm, n);
            assert_unit_or_zero(t, what);
            if m.x_axis.cross(m.y_axis) == Vec3::ZERO
                && m.y_axis.cross(m.z_axis) == Vec3::ZERO
                && m.z_axis.cross(m.x_axis) == Vec3::ZERO
            {
                assert_eq!(t, Vec3::ZERO, "{what}: rank ≤ 1 leaves no normal for {n}");
            }
        }
    }
}

#[test]
fn mirrored_model_matrices() {
    let mirrors = [
        Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0)),
        Mat3::from_diagonal(Vec3::new(-2.0, 0.5, 3.0)),
        Mat3::from_diagonal(Vec3::splat(-1.0)),
        Mat3::from_cols(
            Vec3::new(1.0, 0.5, 0.0),
            Vec3::new(0.0, -2.0, 0.3),
            Vec3::new(0.2, 0.0, 3.0),
        ),
    ];
    for m in mirrors {
        assert!(m.determinant() < 0.0, "setup: det < 0 for {m:?}");
        let nm = phong::normal_matrix(m);
        let it = m.inverse().transpose();
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(0.3, -0.2, 0.9).normalize(),
        ] {
            // Documented: the same direction as the inverse transpose, not its opposite.
            let a = phong::transform_normal(nm, n);
            let b = (it * n).normalize();
            assert!((a - b).length() < 1e-5, "{m:?}, n={n}: {a} vs M⁻ᵀn = {b}");
        }
    }
    let mirror = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
    assert_eq!(
        phong::normal_matrix(mirror) * Vec3::X,
        mirror.inverse().transpose() * Vec3::X,
        "the doc example"
    );
}

#[test]
fn extreme_scale_model_matrices() {
    // Entries beyond ~1e19 overflow the cofactors (documented); transform_normal then returns the
    // documented zero vector for a non-finite NM·n. Nothing may be NaN.
    for s in [1e-20f32, 1e-15, 1e15, 1e19, 1e20, 1e30, f32::MAX] {
        let nm = phong::normal_matrix(Mat3::from_diagonal(Vec3::new(s, s, -s)));
        for n in [Vec3::X, Vec3::new(0.3, -0.2, 0.9)] {
            let t = phong::transform_normal(nm, n);
            assert_unit_or_zero(t, "extreme scale");
        }
    }
    // Cofactors of 1e-20 scale are 1e-40 (subnormal): normalising still recovers the direction.
    let nm = phong::normal_matrix(Mat3::from_diagonal(Vec3::splat(1e-20)));
    let n = Vec3::new(0.3, -0.2, 0.9);
    let t = phong::transform_normal(nm, n);
    assert!((t - n.normalize()).length() < 1e-3, "1e-20 scale: {t}");
}

// ---------------------------------------------------------------------------------------------
// Huge, tiny and subnormal coordinates
// ---------------------------------------------------------------------------------------------

#[test]
fn shading_at_extreme_coordinates() {
    let coords = [
        Vec3::ZERO,
        Vec3::splat(3e38),
        Vec3::splat(-3e38),
        Vec3::new(3e38, -3e38, 3e38),
        Vec3::new(f32::MAX, -f32::MAX, 0.0),
        Vec3::splat(1e-20),
        Vec3::splat(1e-40),
        Vec3::new(f32::from_bits(1), 0.0, -f32::from_bits(1)),
        Vec3::new(1e20, 1.0, -1e-20),
    ];
    let normals = [
        Vec3::Z,
        Vec3::splat(3e38),
        Vec3::splat(-1e-40),
        Vec3::new(1e-20, 0.0, 1e-20),
    ];
    let kinds = |pos: Vec3| -> [Light; 4] {
        [
            point_light(pos, Attenuation::polynomial(1.0, 0.09, 0.032)),
            point_light(pos, Attenuation::try_inverse_square(1.0).unwrap()),
            DirectionalLight::try_new(pos + Vec3::Z, white())
                .unwrap()
                .into(),
            SpotLight::try_new(pos, Vec3::ONE, FRAC_PI_2, 8.0, Attenuation::None, white())
                .unwrap()
                .into(),
        ]
    };
    let models = [
        Model::Phong(Phong::learnopengl()),
        Model::BlinnPhong(BlinnPhong::default()),
        Model::Phong(Phong {
            normalization: Normalization::Energy,
            ..Default::default()
        }),
    ];
    let mut checked = 0;
    for &p in &coords {
        for &lp in &coords {
            for light in kinds(lp) {
                for &eye in &[coords[1], coords[2], coords[5]] {
                    for &n in &normals {
                        for m in &models {
                            let t = shade_one(m, light, Viewer::At(eye), p, n, 32.0);
                            assert_terms_ok(&t, &format!("p={p} light={lp} eye={eye} n={n} {m:?}"));
                            checked += 1;
                        }
                    }
                }
            }
        }
    }
    assert_eq!(
        checked,
        9 * 9 * 4 * 3 * 4 * 3,
        "every combination was shaded"
    );
}

#[test]
fn colours_and_encodings_at_extremes() {
    for x in [
        0.0f32,
        -0.0,
        f32::from_bits(1),
        1e-40,
        -1.0,
        1.0,
        1e30,
        f32::MAX,
        -1e30,
        f32::NAN,
    ] {
        let e = phong::srgb_encode(x);
        let d = phong::srgb_decode(x);
        let ge = phong::gamma_encode(x, 2.2);
        let gd = phong::gamma_decode(x, 2.2);
        for (name, y) in [
            ("srgb_encode", e),
            ("srgb_decode", d),
            ("gamma_encode", ge),
            ("gamma_decode", gd),
        ] {
            if x.is_finite() && x >= 0.0 {
                assert!(y.is_finite() && y >= 0.0, "{name}({x}) = {y}");
            } else if x.is_nan() {
                // Documented: NaN gives 0.
                assert_eq!(y, 0.0, "{name}(NaN)");
            } else {
                // Negative input: srgb follows its linear segment, gamma clamps to 0.
                assert!(y.is_finite() && y <= 0.0, "{name}({x}) = {y}");
            }
        }
        let q = phong::linear_to_srgb8(Vec3::splat(x));
        let want = if x.is_nan() || x <= 0.0 {
            0
        } else if x >= 1.0 {
            255
        } else {
            q[0]
        };
        assert_eq!(q[0], want, "linear_to_srgb8({x})");
    }
    assert_eq!(
        phong::saturate(Vec3::new(f32::NAN, -1.0, 2.0)),
        Vec3::new(0.0, 0.0, 1.0),
        "saturate"
    );
    // Documented: a non-positive or NaN γ returns x clamped to ≥ 0, unencoded.
    assert_eq!(phong::gamma_encode(0.5, 0.0), 0.5, "γ = 0");
    assert_eq!(phong::gamma_encode(0.5, f32::NAN), 0.5, "γ = NaN");
    assert_eq!(
        phong::gamma_decode(-0.5, -2.0),
        0.0,
        "γ < 0, negative input"
    );
}

#[test]
fn checked_constructors_reject_bad_parameters_by_name() {
    assert!(
        matches!(
            Material::try_new(
                Vec3::ZERO,
                Vec3::new(0.0, f32::INFINITY, 0.0),
                Vec3::ZERO,
                1.0
            ),
            Err(PhongError::NonFinite {
                field: "material.diffuse.y",
                ..
            })
        ),
        "infinite diffuse"
    );
    assert!(
        matches!(
            Material::try_new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, f32::NAN),
            Err(PhongError::NonFinite {
                field: "material.shininess",
                ..
            })
        ),
        "NaN shininess"
    );
    assert!(
        matches!(
            Attenuation::try_polynomial(1.0, 0.0, -1e-30),
            Err(PhongError::Negative {
                field: "attenuation.quadratic",
                ..
            })
        ),
        "negative quadratic"
    );
    assert!(
        matches!(
            Attenuation::try_unreal(0.0),
            Err(PhongError::OutOfRange {
                field: "attenuation.radius",
                ..
            })
        ),
        "zero radius"
    );
    assert!(
        matches!(
            SpotLight::try_new(Vec3::ZERO, Vec3::X, -0.1, 1.0, Attenuation::None, white()),
            Err(PhongError::OutOfRange {
                field: "light.cutoff",
                ..
            })
        ),
        "negative cutoff"
    );
    assert!(
        matches!(
            PointLight::try_new(Vec3::new(f32::NAN, 0.0, 0.0), Attenuation::None, white()),
            Err(PhongError::NonFinite {
                field: "light.position",
                ..
            })
        ),
        "NaN position"
    );
    assert!(
        matches!(
            PointLight::try_new(
                Vec3::ZERO,
                Attenuation::InverseSquare {
                    power: 1.0,
                    min_distance: 0.0
                },
                white()
            ),
            Err(PhongError::OutOfRange {
                field: "attenuation.min_distance",
                ..
            })
        ),
        "zero min_distance"
    );
    // A cutoff of exactly π/2 is allowed: cos rounds to −4e-8 and is clamped to 0 (documented in
    // the source), so the cone never reaches behind the light.
    let spot = SpotLight::try_new(
        Vec3::ZERO,
        Vec3::X,
        FRAC_PI_2,
        1.0,
        Attenuation::None,
        white(),
    )
    .unwrap();
    assert_eq!(spot.cos_cutoff(), 0.0, "cos(π/2) clamps to 0");
    assert_eq!(
        spot.spot_factor(-Vec3::Y),
        0.0,
        "at 90° from the axis, the factor is 0^1"
    );
}

// ---------------------------------------------------------------------------------------------
// Found by these tests and since fixed in the crate; kept as regression tests.
// ---------------------------------------------------------------------------------------------

#[test]
fn srgb_encode_of_the_most_negative_float_is_finite() {
    for x in [-f32::MAX, -3e38, -1e38] {
        let y = phong::srgb_encode(x);
        assert!(
            y.is_finite(),
            "srgb_encode({x:e}) = {y}: expected a finite value (e.g. saturated)"
        );
    }
}

#[test]
fn blinn_sees_the_grazing_mirror_highlight() {
    // Measured on the foundation commit (s = 32, V = R, θ = elevation of L above the surface):
    //   θ = 1e-2: 0.99682 (should be 1: 2 + 2L·V ≈ 4θ² loses U/(2θ²) relatively, times s/2),
    //   θ = 3e-4: 0.0111, θ ≤ 1e-4: 0 — while halfway(L, V) = N in every case.
    let n = Vec3::Z;
    for theta in [3e-4f32, 1e-4, 1e-5, 1e-7] {
        let l = Vec3::new(theta.cos(), 0.0, theta.sin());
        let v = phong::reflect(n, l);
        // The vector path: L + V = (0, 0, 2 sin θ) ≠ 0, so H exists and is N.
        let h = phong::halfway_or_zero(l, v);
        assert_eq!(
            h,
            Vec3::Z,
            "setup: the halfway vector is N at θ = {theta:e}"
        );
        let g = Incidence::new(n, l, v);
        let blinn = BlinnPhong::default().specular(&g, 32.0);
        assert!(
            blinn > 0.5,
            "Blinn-Phong at a grazing mirror, θ = {theta:e}: got {blinn}, but (N·H)^32 = {} \
             ({g:?})",
            n.dot(h).powf(32.0)
        );
    }
}

#[test]
fn constant_polynomial_never_culls() {
    for c in [1.0f32, 0.5, 1e-3] {
        let a = Attenuation::polynomial(c, 0.0, 0.0);
        let t = 0.5 * a.factor(0.0);
        assert_eq!(
            a.cull_radius(t),
            f32::INFINITY,
            "polynomial({c}, 0, 0).cull_radius({t}): the factor never fades below t"
        );
    }
}
