//! The stability matrix: one row per classic failure mode of Phong-family code.
//!
//! Each row runs the naive formula (plain glam/`f32`, as a shader or a first implementation would
//! write it) and the `phong` function on the same input, and states what each does as a check on
//! the measured values. `tests/stability_matrix.rs` asserts every check; the `accuracy` tool
//! prints the same rows, with the values it measured, into docs/stability.md.

use glam::{Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, Incidence, LightColors, Material, Phong, PointLight, PowStrategy,
    ReflectionModel, Scene, Viewer,
};

/// One side of a row: what runs, and what it is claimed to do.
pub struct Side {
    /// The code, as shown in the table.
    pub code: &'static str,
    /// Runs it; the values shown in the table.
    pub run: fn() -> Vec<f32>,
    /// What the values show, in words.
    pub claim: &'static str,
    /// The claim as a check on the values.
    pub check: fn(&[f32]) -> bool,
}

/// One row of the matrix.
pub struct Case {
    /// The failure mode.
    pub mode: &'static str,
    /// The input, in words.
    pub input: &'static str,
    /// What the naive formula does.
    pub naive: Side,
    /// What `phong` does.
    pub phong: Side,
}

fn any_nan(x: &[f32]) -> bool {
    x.iter().any(|v| v.is_nan())
}
fn all_finite(x: &[f32]) -> bool {
    x.iter().all(|v| v.is_finite())
}
fn any_non_finite(x: &[f32]) -> bool {
    !all_finite(x)
}
fn v(x: Vec3) -> Vec<f32> {
    x.to_array().to_vec()
}
fn close(a: &[f32], b: &[f32], tol: f32) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// The naive Phong lobe of GLSL: `pow(max(dot(reflect(-l, n), v), 0), s)`.
fn naive_phong_lobe(n: Vec3, l: Vec3, v: Vec3, s: f32) -> f32 {
    (-l).reflect(n).dot(v).max(0.0).powf(s)
}

/// Unit `N`, `L`, `V` in the xz-plane with `R·V = sin(t)` for a small signed `t`: `L` at 60° from
/// `N`, `V` rotated from `R` by `π/2 − t` away from it (so `V` stays above the surface).
fn around_cut_off(t: f32) -> (Vec3, Vec3, Vec3) {
    let n = Vec3::Z;
    let a = 60f32.to_radians();
    let l = Vec3::new(a.sin(), 0.0, a.cos());
    // R is at −60°; V at −60° + (90° − t) = 30° − t, which is above the surface for small t.
    let b = (30f32).to_radians() - t;
    let v = Vec3::new(b.sin(), 0.0, b.cos());
    (n, l, v)
}

/// The light and viewer both below the surface, `V` on the mirror direction: `R·V = 1`.
fn below_surface() -> (Vec3, Vec3, Vec3) {
    let n = Vec3::Z;
    let l = Vec3::new(0.6, 0.0, -0.8);
    let v = (-l).reflect(n); // R = (−0.6, 0, −0.8)
    (n, l, v)
}

/// A unit pair whose `f32` reflection has `R·V` just above 1 (found by a fixed search).
fn r_dot_v_above_one() -> (Vec3, Vec3, Vec3) {
    let n = Vec3::Z;
    for i in 1..10_000 {
        let a = i as f32 * 1.0e-4;
        let l = Vec3::new(a.sin(), 0.3 * a.cos(), a.cos()).normalize();
        let r = (-l).reflect(n);
        let v = r.normalize();
        if r.dot(v) > 1.0 {
            return (n, l, v);
        }
    }
    unreachable!("some angle rounds R·V above 1")
}

/// A unit pair whose `f32` `R·V` is a tiny negative number although `V ⟂ R` exactly.
fn r_dot_v_tiny_negative() -> (Vec3, Vec3, Vec3) {
    let n = Vec3::Z;
    for i in 1..10_000 {
        let a = i as f32 * 1.0e-4;
        let l = Vec3::new(a.sin(), 0.0, a.cos());
        let r = (-l).reflect(n);
        // Perpendicular to R in the xz-plane, above the surface.
        let v = Vec3::new(r.z, 0.0, -r.x).normalize();
        let v = if v.z < 0.0 { -v } else { v };
        let d = r.dot(v);
        if d < 0.0 && d > -1e-6 {
            return (n, l, v);
        }
    }
    unreachable!("some angle rounds R·V below 0")
}

fn learnopengl_scene_light(at: Vec3, attenuation: Attenuation) -> PointLight {
    PointLight::new(
        at,
        attenuation,
        LightColors::new(Vec3::splat(0.1), Vec3::ONE, Vec3::splat(0.5)),
    )
}

fn plastic() -> Material {
    Material::new(Vec3::splat(0.1), Vec3::splat(0.7), Vec3::ONE, 32.0)
}

/// Every row, in table order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            mode: "Phong's cut-off at shininess < 1",
            input: "s = 0.5, R·V = sin(±1e-3) (V crossing the plane ⟂ R), N·L, N·V > 0",
            naive: Side {
                code: "pow(max(dot(reflect(-l, n), v), 0), s)",
                run: || {
                    let (n, l, v1) = around_cut_off(1e-3);
                    let (_, _, v2) = around_cut_off(-1e-3);
                    vec![
                        naive_phong_lobe(n, l, v1, 0.5),
                        naive_phong_lobe(n, l, v2, 0.5),
                    ]
                },
                claim: "jumps from ≈ 0.032 to 0 across R·V = 0: a visible edge",
                check: |x| x[0] > 0.03 && x[1] == 0.0,
            },
            phong: Side {
                code: "Phong::default() vs BlinnPhong::default(), same s",
                run: || {
                    let (n, l, v1) = around_cut_off(1e-3);
                    let (_, _, v2) = around_cut_off(-1e-3);
                    let p = Phong::default();
                    let b = BlinnPhong::default();
                    let g1 = Incidence::new(n, l, v1);
                    let g2 = Incidence::new(n, l, v2);
                    vec![
                        p.specular(&g1, 0.5),
                        p.specular(&g2, 0.5),
                        b.specular(&g1, 0.5),
                        b.specular(&g2, 0.5),
                    ]
                },
                claim: "Phong keeps the edge (it is the model, documented); Blinn-Phong is \
                        continuous there (≈ 0.84 on both sides)",
                check: |x| x[0] > 0.03 && x[1] == 0.0 && x[2] > 0.8 && (x[2] - x[3]).abs() < 1e-3,
            },
        },
        Case {
            mode: "back-face specular halo (no N·L gate)",
            input: "L and V below the surface, V = R: N = Z, L = (0.6, 0, −0.8)",
            naive: Side {
                code: "pow(max(dot(reflect(-l, n), v), 0), 32)",
                run: || {
                    let (n, l, v) = below_surface();
                    vec![naive_phong_lobe(n, l, v, 32.0)]
                },
                claim: "1: a full highlight on an unlit face",
                check: |x| x[0] > 0.99,
            },
            phong: Side {
                code: "Phong::default().specular (step gate), and shade(..) specular",
                run: || {
                    let (n, l, v) = below_surface();
                    let g = Incidence::new(n, l, v);
                    let light = learnopengl_scene_light(l * 3.0, Attenuation::None);
                    let scene = Scene {
                        lights: &[light],
                        ambient: Vec3::ZERO,
                        viewer: Viewer::At(v * 3.0),
                    };
                    let t = phong::shade(&Phong::default(), &plastic(), &scene, Vec3::ZERO, n);
                    vec![
                        Phong::default().specular(&g, 32.0),
                        t.specular.x,
                        Phong::learnopengl().specular(&g, 32.0),
                    ]
                },
                claim: "0 (the halo needs the opt-in `Phong::learnopengl()`, which gives 1)",
                check: |x| x[0] == 0.0 && x[1] == 0.0 && x[2] > 0.99,
            },
        },
        Case {
            mode: "pow(0, 0)",
            input: "s = 0, R·V = −0.5 (clamped base 0)",
            naive: Side {
                code: "pow(max(r_dot_v, 0), 0)",
                run: || vec![(-0.5f32).max(0.0).powf(0.0)],
                claim: "1: at s = 0 the whole back half of the lobe is lit",
                check: |x| x[0] == 1.0,
            },
            phong: Side {
                code: "PowStrategy::Exact.lobe(0, 0), Phong specular at R·V = −0.5, s = 0",
                run: || {
                    let g = Incidence::from_cosines(0.5, 0.0, 0.5);
                    vec![
                        PowStrategy::Exact.lobe(0.0, 0.0),
                        PowStrategy::Squaring.lobe(0.0, 0.0),
                        Phong::default().specular(&g, 0.0),
                    ]
                },
                claim: "0, the limit s → 0⁺ (and what Mesa's GLSL pow computes at run time; its fixed-function path gives 1)",
                check: |x| x.iter().all(|&y| y == 0.0),
            },
        },
        Case {
            mode: "pow base above 1 from rounding",
            input: "V = normalize(R) with f32 R·V rounding to 1 + 1.2e-7, s = 10⁴",
            naive: Side {
                code: "pow(max(dot(r, v), 0), s)",
                run: || {
                    let (n, l, v) = r_dot_v_above_one();
                    let rv = (-l).reflect(n).dot(v);
                    vec![rv, naive_phong_lobe(n, l, v, 1e4)]
                },
                claim: "R·V > 1 and a lobe above 1 (1.0012): energy from nowhere",
                check: |x| x[0] > 1.0 && x[1] > 1.0,
            },
            phong: Side {
                code: "Phong::default().specular(&Incidence::new(n, l, v), s)",
                run: || {
                    let (n, l, v) = r_dot_v_above_one();
                    let g = Incidence::new(n, l, v);
                    vec![g.r_dot_v(), Phong::default().specular(&g, 1e4)]
                },
                claim: "R·V clamped to [−1, 1]; lobe ≤ 1",
                check: |x| x[0] <= 1.0 && x[1] <= 1.0 && x[1] >= 0.0,
            },
        },
        Case {
            mode: "negative pow base from rounding",
            input: "V ⟂ R exactly, f32 R·V rounds to a tiny negative number, s = 0.5",
            naive: Side {
                code: "pow(dot(r, v), s)  (no max)",
                run: || {
                    let (n, l, v) = r_dot_v_tiny_negative();
                    let rv = (-l).reflect(n).dot(v);
                    vec![rv, rv.powf(0.5)]
                },
                claim: "NaN",
                check: |x| x[0] < 0.0 && x[1].is_nan(),
            },
            phong: Side {
                code: "Phong::default().specular(..)",
                run: || {
                    let (n, l, v) = r_dot_v_tiny_negative();
                    vec![Phong::default().specular(&Incidence::new(n, l, v), 0.5)]
                },
                claim: "0",
                check: |x| x[0] == 0.0,
            },
        },
        Case {
            mode: "normalize(0)",
            input: "v = (0, 0, 0)",
            naive: Side {
                code: "v.normalize()  (GLSL normalize, v / length(v))",
                run: || v(Vec3::ZERO.normalize()),
                claim: "NaN",
                check: any_nan,
            },
            phong: Side {
                code: "normalize_or_zero(v), try_normalize(v)",
                run: || {
                    let mut x = v(phong::normalize_or_zero(Vec3::ZERO));
                    x.push(phong::try_normalize(Vec3::ZERO).is_none() as u8 as f32);
                    x
                },
                claim: "the zero vector; `None`",
                check: |x| x == [0.0, 0.0, 0.0, 1.0],
            },
        },
        Case {
            mode: "normalize of huge and tiny vectors",
            input: "v = (1e20, 0, 0) and v = (1e-25, 0, 0)",
            naive: Side {
                code: "v.normalize()",
                run: || {
                    let mut x = v(Vec3::new(1e20, 0.0, 0.0).normalize());
                    x.extend(v(Vec3::new(1e-25, 0.0, 0.0).normalize()));
                    x
                },
                claim: "zero vector for 1e20 (v·v overflows), NaN/∞ for 1e-25 (v·v underflows)",
                check: |x| x[..3] == [0.0, 0.0, 0.0] && any_non_finite(&x[3..]),
            },
            phong: Side {
                code: "normalize_or_zero(v)",
                run: || {
                    let mut x = v(phong::normalize_or_zero(Vec3::new(1e20, 0.0, 0.0)));
                    x.extend(v(phong::normalize_or_zero(Vec3::new(1e-25, 0.0, 0.0))));
                    x
                },
                claim: "(1, 0, 0) both times",
                check: |x| x == [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            },
        },
        Case {
            mode: "degenerate triangle",
            input: "collinear vertices (0,0,0), (1,1,1), (2,2,2)",
            naive: Side {
                code: "normalize(cross(p1 − p0, p2 − p0))",
                run: || {
                    let (a, b, c) = (Vec3::ZERO, Vec3::ONE, Vec3::splat(2.0));
                    v((b - a).cross(c - a).normalize())
                },
                claim: "NaN",
                check: any_nan,
            },
            phong: Side {
                code: "triangle_normal, try_triangle_normal, triangle_area_normal",
                run: || {
                    let (a, b, c) = (Vec3::ZERO, Vec3::ONE, Vec3::splat(2.0));
                    let mut x = v(phong::triangle_normal_or_zero(a, b, c));
                    x.push(phong::try_triangle_normal(a, b, c).is_none() as u8 as f32);
                    x.extend(v(phong::triangle_area_normal(a, b, c)));
                    x
                },
                claim: "the zero vector; `None`; a zero area vector",
                check: |x| x == [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
            },
        },
        Case {
            mode: "sliver triangle far from the origin",
            input: "needle of aspect 1e-4, length 1, at (100, 100, 100)",
            naive: Side {
                code: "normalize(cross(p1 − p0, p2 − p0)), angle to the exact normal (rad)",
                run: || {
                    let (a, b, c) = sliver();
                    let n = (b - a).cross(c - a).normalize();
                    vec![angle_to_exact(n, a, b, c)]
                },
                claim: "an error of 1e-4 rad or more",
                check: |x| x[0] > 1e-4,
            },
            phong: Side {
                code: "triangle_normal_or_zero(p0, p1, p2), angle to the exact normal (rad)",
                run: || {
                    let (a, b, c) = sliver();
                    vec![angle_to_exact(
                        phong::triangle_normal_or_zero(a, b, c),
                        a,
                        b,
                        c,
                    )]
                },
                claim: "below 1e-6 rad (a few f32 ulps)",
                check: |x| x[0] < 1e-6,
            },
        },
        Case {
            mode: "L = −V (no halfway vector)",
            input: "L = (0.6, 0, 0.8), V = −L",
            naive: Side {
                code: "h = normalize(l + v); pow(max(dot(n, h), 0), 32)",
                run: || {
                    let l = Vec3::new(0.6, 0.0, 0.8);
                    let h = (l + -l).normalize();
                    let mut x = v(h);
                    x.push(Vec3::Z.dot(h).max(0.0).powf(32.0));
                    x
                },
                claim: "H is NaN; the lobe is 0 only because `max(NaN, 0)` happens to give 0",
                check: |x| any_nan(&x[..3]),
            },
            phong: Side {
                code: "halfway_or_zero, try_halfway, BlinnPhong::default().specular",
                run: || {
                    let l = Vec3::new(0.6, 0.0, 0.8);
                    let mut x = v(phong::halfway_or_zero(l, -l));
                    x.push(phong::try_halfway(l, -l).is_none() as u8 as f32);
                    x.push(BlinnPhong::default().specular(&Incidence::new(Vec3::Z, l, -l), 32.0));
                    x
                },
                claim: "the zero vector; `None`; lobe 0 (documented)",
                check: |x| x == [0.0, 0.0, 0.0, 1.0, 0.0],
            },
        },
        Case {
            mode: "attenuation at d = 0",
            input: "the point at the light: d = 0, inverse-square law",
            naive: Side {
                code: "1 / (d·d), and 1/(c + l·d + q·d²) with c = l = 0, q = 1; then × 0 (a lobe)",
                run: || {
                    let d = 0.0f32;
                    let f = 1.0 / (d * d);
                    vec![f, 1.0 / (0.0 + 0.0 * d + 1.0 * d * d), f * 0.0]
                },
                claim: "+∞, and NaN once multiplied by a zero lobe",
                check: |x| x[0].is_infinite() && x[1].is_infinite() && x[2].is_nan(),
            },
            phong: Side {
                code: "Attenuation::factor(0) for polynomial(0,0,1) / inverse-square, and shade",
                run: || {
                    let q = Attenuation::polynomial(0.0, 0.0, 1.0);
                    let i = Attenuation::try_inverse_square(1.0).unwrap();
                    let light = learnopengl_scene_light(Vec3::ZERO, q);
                    let scene = Scene {
                        lights: &[light],
                        ambient: Vec3::ZERO,
                        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
                    };
                    let t =
                        phong::shade(&Phong::default(), &plastic(), &scene, Vec3::ZERO, Vec3::Z);
                    let mut x = vec![q.factor(0.0), i.factor(0.0)];
                    x.extend(v(t.total()));
                    x
                },
                claim: "1e4 (capped), and shading adds only the light's ambient part: finite",
                check: |x| x[0] == 1e4 && x[1] == 1e4 && all_finite(x),
            },
        },
        Case {
            mode: "singular model matrix",
            input: "M = diag(1, 1, 0) (flattens z), normal (0.3, 0.2, 0.9)",
            naive: Side {
                code: "normalize(transpose(inverse(M)) · n)",
                run: || {
                    let m = Mat3::from_diagonal(Vec3::new(1.0, 1.0, 0.0));
                    v((m.inverse().transpose() * Vec3::new(0.3, 0.2, 0.9)).normalize())
                },
                claim: "non-finite (1/det = ∞)",
                check: any_non_finite,
            },
            phong: Side {
                code: "transform_normal(normal_matrix(M), n)",
                run: || {
                    let m = Mat3::from_diagonal(Vec3::new(1.0, 1.0, 0.0));
                    v(phong::transform_normal(
                        phong::normal_matrix(m),
                        Vec3::new(0.3, 0.2, 0.9),
                    ))
                },
                claim: "(0, 0, 1): the normal of the flattened surface",
                check: |x| x == [0.0, 0.0, 1.0],
            },
        },
        Case {
            mode: "mirrored model matrix",
            input: "M = diag(−1, 1, 1), normal (1, 0, 0)",
            naive: Side {
                code: "adjugate (cofactor) matrix without the sign of det, then normalize",
                run: || {
                    let m = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
                    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
                    let cof = Mat3::from_cols(b.cross(c), c.cross(a), a.cross(b));
                    let n = (cof * Vec3::X).normalize();
                    let it = (m.inverse().transpose() * Vec3::X).normalize();
                    vec![n.dot(it)]
                },
                claim: "points inward: cosine −1 with the inverse-transpose normal",
                check: |x| x[0] == -1.0,
            },
            phong: Side {
                code: "transform_normal(normal_matrix(M), n), cosine with the inverse transpose",
                run: || {
                    let m = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
                    let n = phong::transform_normal(phong::normal_matrix(m), Vec3::X);
                    let it = (m.inverse().transpose() * Vec3::X).normalize();
                    vec![n.dot(it)]
                },
                claim: "cosine +1: the sign(det) correction",
                check: |x| x[0] == 1.0,
            },
        },
        Case {
            mode: "subnormal input",
            input: "normal (1e-40, −1e-40, 0) (subnormal components)",
            naive: Side {
                code: "normalize(n)",
                run: || v(Vec3::new(1e-40, -1e-40, 0.0).normalize()),
                claim: "non-finite (n·n underflows to 0)",
                check: any_non_finite,
            },
            phong: Side {
                code: "normalize_or_zero(n)",
                run: || v(phong::normalize_or_zero(Vec3::new(1e-40, -1e-40, 0.0))),
                claim: "(0.7071, −0.7071, 0): the exact direction",
                check: |x| {
                    let h = core::f32::consts::FRAC_1_SQRT_2;
                    close(x, &[h, -h, 0.0], 1e-6)
                },
            },
        },
        Case {
            mode: "light very far away",
            input: "point light at (1e25, 1e25, 1e25), point at the origin, N = normalize(1,1,1)",
            naive: Side {
                code: "l = normalize(light − p); max(dot(n, l), 0)",
                run: || {
                    let l = Vec3::splat(1e25).normalize();
                    vec![Vec3::ONE.normalize().dot(l).max(0.0)]
                },
                claim: "0: the light direction collapses to the zero vector (overflow)",
                check: |x| x[0] == 0.0,
            },
            phong: Side {
                code: "shade with Attenuation::None: diffuse term",
                run: || {
                    let light = PointLight::new(
                        Vec3::splat(1e25),
                        Attenuation::None,
                        LightColors::new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO),
                    );
                    let m = Material::new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO, 1.0);
                    let scene = Scene {
                        lights: &[light],
                        ambient: Vec3::ZERO,
                        viewer: Viewer::At(Vec3::Z),
                    };
                    let t = phong::shade(&Phong::default(), &m, &scene, Vec3::ZERO, Vec3::ONE);
                    vec![t.diffuse.x]
                },
                claim: "1: the light is straight along N",
                check: |x| (x[0] - 1.0).abs() < 1e-6,
            },
        },
        Case {
            mode: "∞ and NaN input",
            input: "normal (∞, 0, 0) or (NaN, 0, 0); position (NaN, 0, 0)",
            naive: Side {
                code: "normalize(n); max(dot(n, l), 0) · colour",
                run: || {
                    let a = Vec3::new(f32::INFINITY, 0.0, 0.0).normalize();
                    let b = Vec3::new(f32::NAN, 0.0, 0.0).normalize();
                    let mut x = v(a);
                    x.extend(v(b));
                    x
                },
                claim: "NaN",
                check: any_nan,
            },
            phong: Side {
                code: "normalize_or_zero(n); shade(.., position, n) total",
                run: || {
                    let mut x = v(phong::normalize_or_zero(Vec3::new(f32::INFINITY, 0.0, 0.0)));
                    let light =
                        learnopengl_scene_light(Vec3::new(1.0, 2.0, 3.0), Attenuation::None);
                    let scene = Scene {
                        lights: &[light],
                        ambient: Vec3::ZERO,
                        viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)),
                    };
                    let m = plastic();
                    for (p, n) in [
                        (Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0)),
                        (Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0)),
                        (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Z),
                    ] {
                        x.extend(v(phong::shade(&Phong::default(), &m, &scene, p, n).total()));
                    }
                    x
                },
                claim: "the zero vector; finite colours (ambient only for a non-finite normal)",
                check: |x| x[..3] == [0.0, 0.0, 0.0] && all_finite(x),
            },
        },
    ]
}

/// A needle of aspect ratio 1e-4 and length 1 placed 1e4 from the origin on every axis.
fn sliver() -> (Vec3, Vec3, Vec3) {
    let o = Vec3::splat(100.0);
    let u = Vec3::new(0.48, -0.6, 0.64);
    let w = Vec3::new(0.8, 0.6, 0.0);
    (o, o + u, o + u + 1e-4 * w)
}

/// The angle between `n` and the exact normal of the `f32` triangle, in `f64` radians.
fn angle_to_exact(n: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let e1 = b.as_dvec3() - a.as_dvec3();
    let e2 = c.as_dvec3() - a.as_dvec3();
    // The edges are exact; the plain f64 cross product is accurate to ~1e-12 rad here, far below
    // the differences this row shows.
    let exact = e1.cross(e2);
    let n = n.as_dvec3();
    n.cross(exact).length().atan2(n.dot(exact)) as f32
}

/// docs/stability.md: every row run, checked, and printed with its measured values.
pub fn markdown() -> String {
    use std::fmt::Write as _;
    let mut o = String::new();
    o.push_str(
        "# Stability matrix\n\n\
         Generated by `cargo run --release -p phong-tools --bin accuracy`; do not edit by hand. One row per \
         classic failure mode of Phong-family code. *Naive* is the plain glam/GLSL formula, run on \
         the input shown; *phong* is the crate on the same input. The values are what this run \
         measured; `tests/stability_matrix.rs` asserts each claim on the same code \
         (`tools/src/stability_cases.rs`), so the table cannot drift from the tests.\n\n",
    );
    o.push_str("| failure mode | input | naive code | naive: measured | naive: what it means | `phong` | phong: measured | phong: what it means |\n");
    o.push_str("|---|---|---|---|---|---|---|---|\n");
    for c in cases() {
        let nv = (c.naive.run)();
        let pv = (c.phong.run)();
        assert!(
            (c.naive.check)(&nv),
            "{}: naive claim does not hold: {nv:?}",
            c.mode
        );
        assert!(
            (c.phong.check)(&pv),
            "{}: phong claim does not hold: {pv:?}",
            c.mode
        );
        let _ = writeln!(
            o,
            "| {} | {} | `{}` | {} | {} | `{}` | {} | {} |",
            c.mode,
            c.input,
            c.naive.code,
            values(&nv),
            c.naive.claim,
            c.phong.code,
            values(&pv),
            c.phong.claim
        );
    }
    o.push('\n');
    o
}

/// The measured values, to 7 decimals: enough to show each claim, and stable across
/// platforms whose `powf` differs in the last bit (the staleness test compares the text).
fn values(x: &[f32]) -> String {
    let parts: Vec<String> = x
        .iter()
        .map(|&v| {
            if v == 0.0 || !v.is_finite() {
                format!("{v:?}")
            } else if (1e-3..1e4).contains(&v.abs()) {
                let s = format!("{v:.7}");
                let s = s.trim_end_matches('0');
                s.strip_suffix('.')
                    .map_or(s.to_string(), |t| format!("{t}.0"))
            } else {
                format!("{v:.5e}")
            }
        })
        .collect();
    format!("[{}]", parts.join(", "))
}
