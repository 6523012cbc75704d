//! Totality: every public function of `phong`, fed random finite `f32` input (±0, subnormals,
//! values near `f32::MAX`, non-unit vectors where accepted), must not panic and must return finite
//! values inside its documented range.
//!
//! Fast functions get input inside their documented domain (debug builds assert it: `reflect`
//! and `Incidence::new` need unit vectors, the unchecked constructors valid fields); everything
//! outside it goes to the total or checked variant (`normalize_or_zero`, `try_*`, `shade`).

use crate::strategies;

use glam::{Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Incidence, Light, LightColors, LightSource,
    Material, Model, Normalization, Phong, PhongError, PointLight, ReflectionModel, ResolvedModel,
    Scene, SpotLight, Viewer,
};
use proptest::prelude::*;
use strategies::{gate, model, normalization, pow_strategy};

const CASES: u32 = 5000;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: CASES,
        ..ProptestConfig::default()
    }
}

// ---------------------------------------------------------------------------------------------
// Named strategies

/// Any finite `f32`, with the edges of the range over-represented.
fn finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => prop::num::f32::NORMAL | prop::num::f32::SUBNORMAL | prop::num::f32::ZERO,
        1 => prop::sample::select(vec![
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            1e-40,
            f32::MAX,
            -f32::MAX,
            3e38,
            -3e38,
            1e19,
            1e-19,
        ]),
        2 => -1e3f32..1e3,
    ]
}

fn non_negative() -> impl Strategy<Value = f32> {
    finite().prop_map(f32::abs)
}

fn finite_vec3() -> impl Strategy<Value = Vec3> {
    (finite(), finite(), finite()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A unit vector (or, now and then, the zero vector, which the fast functions also accept).
fn unit_vec3() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, 0u8..20).prop_map(|(x, y, z, k)| {
        if k == 0 {
            Vec3::ZERO
        } else {
            Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::Z)
        }
    })
}

/// A cosine in `[−1, 1]`, ends included.
fn cosine() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -1.0f32..=1.0,
        1 => prop::sample::select(vec![-1.0f32, -0.0, 0.0, 1.0, 1e-40, -1e-40]),
    ]
}

fn colour() -> impl Strategy<Value = Vec3> {
    (non_negative(), non_negative(), non_negative()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn shininess() -> impl Strategy<Value = f32> {
    prop_oneof![non_negative(), 0.0f32..1e4]
}

/// An attenuation with arbitrary finite fields (the factor must be robust to any of them).
fn any_attenuation() -> impl Strategy<Value = Attenuation> {
    (0u8..5, finite(), finite(), finite()).prop_map(|(k, a, b, c)| match k {
        0 => Attenuation::None,
        1 => Attenuation::Polynomial {
            constant: a,
            linear: b,
            quadratic: c,
        },
        2 => Attenuation::InverseSquare {
            power: a,
            min_distance: b,
        },
        3 => Attenuation::Unreal { radius: a },
        _ => Attenuation::Frostbite {
            radius: a,
            min_distance: b,
        },
    })
}

/// An attenuation that passes `validated()` (the documented domain).
fn valid_attenuation() -> impl Strategy<Value = Attenuation> {
    any_attenuation().prop_map(|a| match a {
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => Attenuation::Polynomial {
            constant: constant.abs(),
            linear: linear.abs(),
            quadratic: quadratic.abs(),
        },
        Attenuation::InverseSquare {
            power,
            min_distance,
        } => Attenuation::InverseSquare {
            power: power.abs(),
            min_distance: min_distance.abs().max(f32::MIN_POSITIVE),
        },
        Attenuation::Unreal { radius } => Attenuation::Unreal {
            radius: radius.abs().max(f32::MIN_POSITIVE),
        },
        Attenuation::Frostbite {
            radius,
            min_distance,
        } => Attenuation::Frostbite {
            radius: radius.abs().max(f32::MIN_POSITIVE),
            min_distance: min_distance.abs().max(f32::MIN_POSITIVE),
        },
        Attenuation::None => Attenuation::None,
    })
}

fn light_colors() -> impl Strategy<Value = LightColors> {
    (colour(), colour(), colour()).prop_map(|(a, d, s)| LightColors::try_new(a, d, s).unwrap())
}

/// A light of any kind from the checked constructors, with finite fields across the range.
fn light() -> impl Strategy<Value = Light> {
    (
        0u8..3,
        finite_vec3(),
        finite_vec3(),
        valid_attenuation(),
        light_colors(),
        0.0f32..=core::f32::consts::FRAC_PI_2,
        non_negative(),
    )
        .prop_map(|(k, p, d, a, c, cutoff, e)| {
            let d = if phong::try_normalize(d).is_some() {
                d
            } else {
                Vec3::Z
            };
            match k {
                0 => DirectionalLight::try_new(d, c).unwrap().into(),
                1 => PointLight::try_new(p, a, c).unwrap().into(),
                _ => SpotLight::try_new(p, d, cutoff, e, a, c).unwrap().into(),
            }
        })
}

fn material() -> impl Strategy<Value = Material> {
    (colour(), colour(), colour(), colour(), shininess()).prop_map(|(a, d, s, e, sh)| {
        Material::try_new(a, d, s, sh)
            .unwrap()
            .try_with_emission(e)
            .unwrap()
    })
}

fn finite3(v: Vec3) -> bool {
    v.is_finite()
}

fn unit_or_zero(v: Vec3) -> bool {
    v == Vec3::ZERO || (v.length() - 1.0).abs() < 1e-5
}

// ---------------------------------------------------------------------------------------------
// Geometry

proptest! {
    #![proptest_config(config())]

    #[test]
    fn normalize_and_length_are_total(v in finite_vec3()) {
        let n = phong::normalize_or_zero(v);
        prop_assert!(unit_or_zero(n), "normalize_or_zero({v}) = {n}");
        prop_assert_eq!(n == Vec3::ZERO, v == Vec3::ZERO, "zero only for zero: {} -> {}", v, n);
        prop_assert_eq!(phong::try_normalize(v).is_some(), n != Vec3::ZERO);
        let l = phong::length(v);
        prop_assert!(l.is_finite() && l >= 0.0, "length({v}) = {l}");
    }

    #[test]
    fn triangle_functions_are_total(a in finite_vec3(), b in finite_vec3(), c in finite_vec3()) {
        let area = phong::triangle_area_normal(a, b, c);
        prop_assert!(finite3(area), "area normal of {a}, {b}, {c} = {area}");
        let n = phong::triangle_normal_or_zero(a, b, c);
        prop_assert!(unit_or_zero(n), "triangle_normal = {n}");
        if let Some(t) = phong::try_triangle_normal(a, b, c) {
            prop_assert!(unit_or_zero(t) && t != Vec3::ZERO, "try_triangle_normal = {t}");
        }
    }

    #[test]
    fn reflect_is_total_on_its_domain(n in unit_vec3(), l in finite_vec3()) {
        // Domain: unit (or zero) n, any finite l: an overflowing 2(n·l)n saturates.
        let r = phong::reflect(n, l);
        prop_assert!(finite3(r), "reflect({n}, {l}) = {r}");
    }

    #[test]
    fn halfway_and_face_forward_are_total(l in finite_vec3(), v in finite_vec3(), n in finite_vec3(), r in finite_vec3()) {
        let h = phong::halfway_or_zero(l, v);
        prop_assert!(unit_or_zero(h), "halfway({l}, {v}) = {h}");
        prop_assert_eq!(phong::try_halfway(l, v).is_some(), h != Vec3::ZERO);
        let f = phong::face_forward(n, v, r);
        prop_assert!(f == n || f == -n, "face_forward returns ±n");
    }

    #[test]
    fn normal_matrix_is_total_within_its_documented_scale(
        cols in prop::array::uniform9(finite()),
        n in finite_vec3(),
    ) {
        // Documented: entries beyond about 1e19 overflow (products of two columns). Inside that
        // range the cofactor matrix is finite for every matrix, singular ones included.
        let m = Mat3::from_cols_array(&cols.map(|x| x.clamp(-1e19, 1e19)));
        let nm = phong::normal_matrix(m);
        prop_assert!(nm.is_finite(), "normal_matrix({m}) = {nm}");
        let t = phong::transform_normal(nm, n);
        prop_assert!(unit_or_zero(t), "transform_normal = {t}");
    }

    #[test]
    fn transform_normal_is_total_for_any_matrix(
        cols in prop::array::uniform9(finite()),
        n in finite_vec3(),
    ) {
        // Beyond the documented scale the matrix may overflow; transform_normal still answers
        // with a unit or zero vector.
        let m = Mat3::from_cols_array(&cols);
        let t = phong::transform_normal(phong::normal_matrix(m), n);
        prop_assert!(unit_or_zero(t), "transform_normal = {t}");
    }

    #[test]
    fn vertex_normals_are_total(
        pos in prop::collection::vec(finite_vec3(), 1..12),
        tris in prop::collection::vec((0usize..64, 0usize..64, 0usize..64), 0..20),
    ) {
        let k = pos.len();
        let tris: Vec<[u32; 3]> = tris.iter().map(|&(a, b, c)| [(a % k) as u32, (b % k) as u32, (c % k) as u32]).collect();
        let mut out = vec![Vec3::ONE; k];
        phong::vertex_normals(&pos, &tris, &mut out);
        for n in out {
            prop_assert!(unit_or_zero(n), "vertex normal {n}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Attenuation and lights

proptest! {
    #![proptest_config(config())]

    #[test]
    fn attenuation_factor_is_total_for_any_fields(a in any_attenuation(), d in finite()) {
        // Documented: "evaluated robustly for any field values (always finite and ≥ 0)".
        let f = a.factor(d);
        prop_assert!(f.is_finite() && f >= 0.0, "{a:?}.factor({d}) = {f}");
    }

    #[test]
    fn cull_radius_is_total(a in valid_attenuation(), t in finite()) {
        let r = a.cull_radius(t);
        prop_assert!(r >= 0.0, "{a:?}.cull_radius({t}) = {r}");
        // Documented: +∞ exactly when the light never fades below the threshold at any finite
        // distance, i.e. t ≤ 0 or factor(f32::MAX) ≥ t.
        let never = t <= 0.0 || a.factor(f32::MAX) >= t;
        prop_assert_eq!(r.is_infinite(), never, "{:?}.cull_radius({}) = {}", a, t, r);
    }

    #[test]
    fn checked_constructors_never_panic(
        a in finite(), b in finite(), c in finite(), v in finite_vec3(), w in finite_vec3(), e in finite(),
    ) {
        let _ = Attenuation::try_polynomial(a, b, c);
        let _ = Attenuation::try_inverse_square(a);
        let _ = Attenuation::try_unreal(a);
        let _ = Attenuation::try_frostbite(a);
        let _ = Attenuation::InverseSquare { power: a, min_distance: b }.validated();
        let _ = Attenuation::Frostbite { radius: a, min_distance: b }.validated();
        let _ = LightColors::try_new(v, w, v);
        let _ = LightColors::try_from_strengths(v, a, b, c);
        let _ = LightColors::try_from_power(v, a);
        let _ = DirectionalLight::try_new(v, LightColors::BLACK);
        let _ = PointLight::try_new(v, Attenuation::None, LightColors::BLACK);
        let _ = SpotLight::try_new(v, w, a, e, Attenuation::None, LightColors::BLACK);
        let m = Material::try_new(v, w, v, a);
        if let Ok(m) = m {
            let _ = m.try_with_emission(w);
            let _ = m.try_with_shininess(b);
            prop_assert!(m.shininess().is_finite());
        }
        let _ = Material::try_from_color(v, a);
    }

    #[test]
    fn lights_sample_finite_factors(light in light(), p in finite_vec3()) {
        let s = light.sample(p);
        prop_assert!(unit_or_zero(s.direction), "{light:?} at {p}: direction {}", s.direction);
        prop_assert!(s.factor.is_finite() && s.factor >= 0.0, "{light:?} at {p}: factor {}", s.factor);
        if let Light::Spot(spot) = light {
            let f = spot.spot_factor(s.direction);
            prop_assert!((0.0..=1.0).contains(&f), "spot factor {f}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Lobes and models

proptest! {
    #![proptest_config(config())]

    #[test]
    fn lobe_pieces_are_total(x in finite(), s in finite(), p in pow_strategy(), g in gate(), nz in normalization()) {
        // Domain of lobe: x ≤ 1 (a clamped cosine); s NaN or negative is documented as 0.
        let lobe = p.lobe(x.min(1.0), s);
        prop_assert!((0.0..=1.0).contains(&lobe), "{p:?}.lobe({x}, {s}) = {lobe}");
        let w = g.weight(x);
        prop_assert!(w.is_finite() && w >= 0.0, "{g:?}.weight({x}) = {w}");
        let phong = ResolvedModel::from(Phong { normalization: nz, ..Phong::default() });
        let blinn = ResolvedModel::from(BlinnPhong { normalization: nz, ..BlinnPhong::default() });
        let d = phong.diffuse(x);
        prop_assert!(d.is_finite() && d >= 0.0);
        let pf = phong.specular_scale(s);
        let bf = blinn.specular_scale(s);
        prop_assert!(pf.is_finite() && pf > 0.0, "{nz:?} Phong specular_scale({s}) = {pf}");
        prop_assert!(bf.is_finite() && bf > 0.0, "{nz:?} Blinn specular_scale({s}) = {bf}");
    }

    #[test]
    fn incidence_is_total(n in unit_vec3(), l in unit_vec3(), v in unit_vec3(), a in finite_vec3(), b in finite_vec3(), c in finite_vec3()) {
        for g in [Incidence::new(n, l, v), Incidence::from_unnormalized(a, b, c)] {
            let rv = g.r_dot_v();
            let nh = g.n_dot_h_squared();
            prop_assert!((-1.0..=1.0).contains(&rv), "r_dot_v = {rv} for {g:?}");
            prop_assert!((0.0..=1.0).contains(&nh), "n_dot_h_squared = {nh} for {g:?}");
        }
    }

    #[test]
    fn models_keep_their_contract(
        m in model(),
        nl in cosine(), nv in cosine(), lv in cosine(),
        s in shininess(),
    ) {
        // Contract of ReflectionModel: finite cosines in [−1, 1] and finite s ≥ 0 give finite
        // lobes ≥ 0; unnormalised lobes lie in [0, 1].
        let g = Incidence::from_cosines(nl, nv, lv);
        let d = m.diffuse(&g);
        let sp = m.specular(&g, s);
        prop_assert!(d.is_finite() && d >= 0.0, "{m:?} diffuse {d}");
        prop_assert!(sp.is_finite() && sp >= 0.0, "{m:?} specular({s}) {sp} for {g:?}");
        let normalized = match m {
            Model::Lambert(x) => x.normalization,
            Model::Phong(x) => x.normalization,
            Model::BlinnPhong(x) => x.normalization,
        } != Normalization::None;
        if !normalized {
            prop_assert!(d <= 1.0 && sp <= 1.0, "{m:?}: unnormalised lobes above 1: {d}, {sp}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Shading and colour

proptest! {
    #![proptest_config(config())]

    #[test]
    fn shade_is_total(
        m in model(),
        mat in material(),
        lights in prop::collection::vec(light(), 0..4),
        ambient in finite_vec3(),
        eye in finite_vec3(),
        infinite in any::<bool>(),
        p in finite_vec3(),
        n in finite_vec3(),
    ) {
        let scene = Scene {
            lights: &lights,
            ambient,
            viewer: if infinite { Viewer::Infinite(eye) } else { Viewer::At(eye) },
        };
        let t = phong::shade(&m, &mat, &scene, p, n);
        for (name, c) in [("ambient", t.ambient), ("diffuse", t.diffuse), ("specular", t.specular), ("emission", t.emission), ("total", t.total())] {
            prop_assert!(c.is_finite() && c.min_element() >= 0.0, "{name} = {c}");
        }
        let _ = phong::gpu::GpuParams::new(&m, scene.viewer, ambient, lights.len() as u32);
        for l in &lights {
            let g = phong::gpu::GpuLight::from(l);
            prop_assert!(g.position.iter().chain(&g.direction).chain(&g.attenuation).all(|x| x.is_finite()), "{g:?}");
        }
        let gm = phong::gpu::GpuMaterial::from(&mat);
        prop_assert!(gm.shininess.is_finite());
    }

    #[test]
    fn colour_functions_are_total(x in finite(), gamma in finite(), c in finite_vec3()) {
        // The whole finite range, `finite()`'s ±f32::MAX and ±3e38 included: below
        // −f32::MAX/12.92 the linear segment 12.92·x would overflow, and `srgb_encode` saturates.
        for (name, y) in [
            ("srgb_encode", phong::srgb_encode(x)),
            ("srgb_decode", phong::srgb_decode(x)),
            ("gamma_encode", phong::gamma_encode(x, gamma)),
            ("gamma_decode", phong::gamma_decode(x, gamma)),
        ] {
            prop_assert!(y.is_finite(), "{name}({x}, γ = {gamma}) = {y}");
        }
        prop_assert!(phong::gamma_encode(x, gamma) >= 0.0 && phong::gamma_decode(x, gamma) >= 0.0);
        if (0.0..=1.0).contains(&x) {
            let e = phong::srgb_encode(x);
            let d = phong::srgb_decode(x);
            prop_assert!((0.0..=1.0).contains(&e) && (0.0..=1.0).contains(&d), "sRGB maps [0,1] onto [0,1]: {e}, {d}");
        }
        let s = phong::saturate(c);
        prop_assert!(s.min_element() >= 0.0 && s.max_element() <= 1.0);
        let _ = phong::quantize_u8(x);
        let _ = phong::linear_to_srgb8(c);
    }
}

#[test]
fn srgb_encode_of_huge_negatives() {
    // The doc promises any finite x is accepted (negatives follow the linear segment, saturated
    // at −f32::MAX) and the crate promises no infinity from finite input, although 12.92·x
    // overflows for x < −f32::MAX/12.92 ≈ −2.6e37.
    for x in [-f32::MAX, -3e38, -f32::MAX / 12.0] {
        assert_eq!(phong::srgb_encode(x), -f32::MAX, "srgb_encode({x})");
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn unchecked_constructors_and_accessors_are_total_on_their_domain(
        c in colour(), d in colour(), e in colour(), s in shininess(), t in colour(), u in colour(),
        dir in unit_vec3(), p in finite_vec3(), a in valid_attenuation(),
    ) {
        // Unchecked constructors: valid fields (debug builds assert them).
        let m = Material::new(c, d, e, s).textured(t, u);
        for x in [m.ambient(), m.diffuse(), m.specular(), m.emission()] {
            prop_assert!(x.is_finite() && x.min_element() >= 0.0);
        }
        prop_assert!(m.shininess().is_finite() && m.shininess() >= 0.0);
        let colors = LightColors::new(c, d, e);
        let dir = if dir == Vec3::ZERO { Vec3::Z } else { dir };
        let sun = DirectionalLight::new(dir, colors);
        prop_assert!(unit_or_zero(sun.direction()));
        let point = PointLight::new(p, a, colors);
        prop_assert_eq!(point.position(), p);
        prop_assert_eq!(point.attenuation(), a);
        if let Attenuation::Polynomial { constant, linear, quadratic } = a {
            let q = Attenuation::polynomial(constant, linear, quadratic);
            prop_assert!(q.factor(1.0).is_finite());
        }
    }

    #[test]
    fn checked_constructors_report_errors_that_name_field_and_value(x in finite(), v in finite_vec3()) {
        // PhongError's promise: the message names the field and shows the offending value as it
        // is. Checked structurally here over random values: the message starts with the field,
        // and the number after "got " parses back to the carried value bit for bit (f32's
        // Display prints the shortest decimal that round-trips). The exact wording of every
        // variant is pinned by `phong_error_messages_are_exact` below.
        let errs = [
            Attenuation::try_polynomial(x, -1.0, 0.0).err(),
            Attenuation::try_unreal(-x.abs()).err(),
            Material::try_new(v, v, v, -1.0).err(),
            LightColors::try_new(Vec3::new(f32::NAN, 0.0, 0.0), v, v).err(),
            DirectionalLight::try_new(Vec3::ZERO, LightColors::BLACK).err(),
            SpotLight::try_new(v, Vec3::Z, 2.0, 1.0, Attenuation::None, LightColors::BLACK).err(),
        ];
        for e in errs.into_iter().flatten() {
            let msg = e.to_string();
            let (field, value) = match e {
                PhongError::NonFinite { field, value }
                | PhongError::Negative { field, value }
                | PhongError::OutOfRange { field, value, .. } => (field, Some(value)),
                PhongError::ZeroDirection { field } => (field, None),
                _ => unreachable!("a variant this test does not know: {e:?}"),
            };
            prop_assert!(msg.starts_with(field) && msg.len() > field.len(), "{msg:?} does not start with {field:?}");
            if let Some(value) = value {
                let shown = msg.rsplit_once("got ").map(|(_, t)| t);
                let back = shown.and_then(|t| t.parse::<f32>().ok());
                prop_assert!(
                    back.is_some_and(|b| b.to_bits() == value.to_bits() || (b.is_nan() && value.is_nan())),
                    "{msg:?} does not show {value:?}"
                );
            }
        }
    }
}

#[test]
fn phong_error_messages_are_exact() {
    // One error of each variant, from the checked constructor that reports it, with its exact
    // message: a user may show these as they are, so a change of wording is a change of API.
    let v = Vec3::ONE;
    let cases: [(Result<(), PhongError>, PhongError, &str); 4] = [
        (
            LightColors::try_new(v, Vec3::new(0.0, f32::INFINITY, 0.0), v).map(drop),
            PhongError::NonFinite {
                field: "light.diffuse.y",
                value: f32::INFINITY,
            },
            "light.diffuse.y must be finite, got inf",
        ),
        (
            Material::try_new(v, v, v, -2.5).map(drop),
            PhongError::Negative {
                field: "material.shininess",
                value: -2.5,
            },
            "material.shininess must be non-negative, got -2.5",
        ),
        (
            DirectionalLight::try_new(Vec3::ZERO, LightColors::BLACK).map(drop),
            PhongError::ZeroDirection {
                field: "light.direction",
            },
            "light.direction must be a non-zero direction",
        ),
        (
            SpotLight::try_new(
                Vec3::ZERO,
                Vec3::Z,
                2.0,
                1.0,
                Attenuation::None,
                LightColors::BLACK,
            )
            .map(drop),
            PhongError::OutOfRange {
                field: "light.cutoff",
                value: 2.0,
                min: 0.0,
                max: core::f32::consts::FRAC_PI_2,
            },
            "light.cutoff must lie in [0, 1.5707964], got 2",
        ),
    ];
    for (got, want, message) in cases {
        assert_eq!(got, Err(want));
        assert_eq!(want.to_string(), message, "{want:?}");
    }
    // NaN, the other non-finite value, prints as NaN.
    let nan = LightColors::try_new(Vec3::new(f32::NAN, 0.0, 0.0), v, v).unwrap_err();
    assert_eq!(nan.to_string(), "light.ambient.x must be finite, got NaN");
    // The batch API's one error names the level it cannot run.
    assert_eq!(
        phong::UnsupportedLevel(phong::Level::Avx512).to_string(),
        "batch level avx512 is not supported on this CPU or build"
    );
}
