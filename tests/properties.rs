//! Property tests of the identities the crate's formulas rest on.
//!
//! Every check is evaluated in `f64` on the `f32` values the crate returns, so the test's own
//! rounding (about 2⁻⁵³) is negligible next to the crate's. Tolerances are written as multiples of
//! the `f32` unit roundoff `U = 2⁻²⁴` times a condition number of the input; each comment gives the
//! error bound the multiple comes from. "Unit" input vectors are rounded once from `f64`, so
//! `|‖v‖² − 1| ≤ 3U` (written `η` below).

use crate::strategies;

use core::f64::consts::PI;

use glam::{DMat3, DVec3, Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Incidence, Light, LightColors, Material, Model,
    Phong, PointLight, ReflectionModel, Scene, SpecularGate, SpotLight, Terms, Viewer,
};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use strategies::*;

/// Unit roundoff of `f32`: every correctly rounded operation has relative error at most `U`.
const U: f64 = f32::EPSILON as f64 / 2.0;

fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// The angle between two vectors, well conditioned everywhere (unlike `acos` near 0 and π).
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

// ---------------------------------------------------------------------------------------------
// Reflection
// ---------------------------------------------------------------------------------------------

// Error model of `reflect(n, l) = 2(n·l)n − l` in f32 with |n|, |l| ≈ 1: the dot product carries
// ≤ 3U relative error of Σ|nᵢlᵢ| ≤ 1, the product with nᵢ one more U, the subtraction U·|rᵢ|. So the
// computed R is the exact R(n, l) of the given f32 vectors plus δ with ‖δ‖ ≤ 2·4U + U = 9U. The
// given n is not exactly unit (|n|² = 1 + η): exact R(n, l)·n = (n·l)(1 + 2η).
proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn reflect_keeps_the_angle_to_n(n in unit_vec3(), l in unit_vec3()) {
        let r = phong::reflect(n, l);
        // |R·N − L·N| ≤ ‖δ‖ + 2|η| ≤ 9U + 6U = 15U; 16U.
        let err = (d(r).dot(d(n)) - d(l).dot(d(n))).abs();
        prop_assert!(err <= 16.0 * U, "R·N − L·N = {err:e} for n={n} l={l} r={r}");
    }

    #[test]
    fn reflect_keeps_unit_length(n in unit_vec3(), l in unit_vec3()) {
        let r = phong::reflect(n, l);
        // Exact ‖R‖² = ‖l‖² + 4(n·l)²η, so |‖R‖ − 1| ≤ η/2 + 2η + ‖δ‖ ≤ 1.5U + 6U + 9U; 18U.
        let err = (d(r).length() - 1.0).abs();
        prop_assert!(err <= 18.0 * U, "‖R‖ − 1 = {err:e} for n={n} l={l} r={r}");
    }

    #[test]
    fn reflect_stays_in_the_plane_of_l_and_n(n in unit_vec3(), l in unit_vec3()) {
        let r = phong::reflect(n, l);
        // The exact R is a combination of n and l, so R·(n × l) = 0; only δ remains:
        // |δ·(n × l)| ≤ 9U ‖n × l‖ (the f64 cross product of f32 values is exact to 2⁻⁵³); 10U.
        let c = d(n).cross(d(l));
        let triple = d(r).dot(c).abs();
        prop_assert!(
            triple <= 10.0 * U * c.length() + 1e-300,
            "R·(N×L) = {triple:e}, ‖N×L‖ = {} for n={n} l={l}", c.length()
        );
    }

    #[test]
    fn reflecting_twice_gives_l_back(n in unit_vec3(), l in unit_vec3()) {
        let back = phong::reflect(n, phong::reflect(n, l));
        // With H = 2nnᵀ − I, H² = I + 4η nnᵀ (≤ 12U); the first δ passes through H (≤ 9U(1+2η)),
        // the second reflection adds its own ≤ 9U: 30U in all; 32U.
        let err = (d(back) - d(l)).length();
        prop_assert!(err <= 32.0 * U, "‖R(R(L)) − L‖ = {err:e} for n={n} l={l}");
    }

    #[test]
    fn reflect_equals_the_householder_form(n in unit_vec3(), l in unit_vec3()) {
        let r = phong::reflect(n, l);
        // (I − 2NNᵀ)(−L) built as a matrix in f64 from the same f32 n: exact R(n, l) to ~2⁻⁵⁰,
        // so only δ remains; 10U.
        let nd = d(n);
        let house = DMat3::IDENTITY
            - 2.0 * DMat3::from_cols(nd * nd.x, nd * nd.y, nd * nd.z);
        let expect = house * (-d(l));
        let err = (d(r) - expect).length();
        prop_assert!(err <= 10.0 * U, "‖R − (I−2NNᵀ)(−L)‖ = {err:e} for n={n} l={l}");
        // The documented identity with glam's incident-direction form holds bit for bit: both
        // compute fl(2·fl(n·l)·nᵢ − lᵢ), and negating l negates the dot product exactly.
        prop_assert_eq!(r, (-l).reflect(n), "reflect(n, l) vs (−l).reflect(n)");
    }
}

// ---------------------------------------------------------------------------------------------
// Halfway vector
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn halfway_bisects_l_and_v(l in unit_vec3(), v in unit_vec3()) {
        let s = l + v;
        prop_assume!(s != Vec3::ZERO);
        let h = phong::halfway_or_zero(l, v);
        let sum = d(l) + d(v);
        // Exactly, H·(L − V) = (‖L‖² − ‖V‖²)/‖L + V‖ ≤ 6U/‖L+V‖ for the given f32 vectors. The
        // computed H: the sum rounds each component by U of ‖L+V‖ (so no cancellation blow-up)
        // and normalising adds ≤ 5U: ‖δH‖ ≤ 7U, times ‖L − V‖ ≤ 2: 14U. Bound: 16U + 8U/‖L+V‖.
        let err = d(h).dot(d(l) - d(v)).abs();
        let tol = 16.0 * U + 8.0 * U / sum.length();
        prop_assert!(err <= tol, "H·L − H·V = {err:e} > {tol:e} for l={l} v={v} h={h}");
        prop_assert!(
            (d(h).length() - 1.0).abs() <= 8.0 * U,
            "H must be unit: ‖H‖ = {} for l={l} v={v}", d(h).length()
        );
    }

    #[test]
    fn halfway_is_n_when_v_is_the_mirror_direction((n, l) in normal_and_light()) {
        let v = phong::reflect(n, l);
        let h = phong::halfway_or_zero(l, v);
        let nl = d(n).dot(d(l));
        // L + R = 2(N·L)N + δ with ‖δ‖ ≤ 9U (reflect) + U (the sum): the direction error is
        // ≤ 10U/(2 N·L); normalising adds ≤ 5U, and N itself is unit only to 1.5U. Bound:
        // 5U/(N·L) + 8U (N·L ≥ 1e-3 here, so the bound stays below 5e-4).
        let err = (d(h) - d(n)).length();
        let tol = 5.0 * U / nl + 8.0 * U;
        prop_assert!(err <= tol, "‖H − N‖ = {err:e} > {tol:e} for n={n} l={l} (N·L = {nl})");
    }

    #[test]
    fn in_plane_angle_to_h_is_half_the_angle_between_r_and_v(
        (n, l, v, tl, tv) in coplanar_nlv()
    ) {
        let r = phong::reflect(n, l);
        let h = phong::halfway_or_zero(l, v);
        let lhs = angle(d(n), d(h));
        let rhs = angle(d(r), d(v)) / 2.0;
        // The generating angles predict both sides: |θl + θv| / 2.
        let predicted = (tl + tv).abs() / 2.0;
        // An angle moves by at most the direction error of its vectors (angle(b, b') ≥ its
        // change). N, L, V carry ≤ 1U each from rounding; R ≤ 9U + 3U (non-unit n); H ≤ 7U plus a
        // tilt ≤ 3U/‖L+V‖ from ‖L‖ ≠ ‖V‖. So |lhs − rhs| ≤ 8U + 3U/‖L+V‖ + (12U + U)/2 ≤ 15U +
        // 3U/‖L+V‖; with ‖L+V‖ ≥ 2 sin 0.01 this is at most ~1e-5. Bound: 16U + 4U/‖L+V‖.
        let tol = 16.0 * U + 4.0 * U / (d(l) + d(v)).length();
        prop_assert!(
            (lhs - rhs).abs() <= tol,
            "angle(N,H) = {lhs} vs angle(R,V)/2 = {rhs} (tol {tol:e}) for θl={tl} θv={tv}"
        );
        prop_assert!(
            (lhs - predicted).abs() <= tol,
            "angle(N,H) = {lhs} vs |θl+θv|/2 = {predicted} (tol {tol:e})"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The cosine forms used by the lobes agree with the vector forms
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn r_dot_v_from_cosines_equals_the_reflected_vector(
        n in unit_vec3(), l in unit_vec3(), v in unit_vec3()
    ) {
        // R·V = (2(N·L)N − L)·V = 2(N·L)(N·V) − L·V holds exactly for any N, unit or not, so only
        // rounding separates the two: the cosine form carries ≤ 18U (three dot products of ≤ 3U,
        // two products, the difference), the vector form ≤ 9U (reflect) on ‖V‖ ≈ 1; clamping to
        // [−1, 1] only moves the cosine form closer. Bound: 32U.
        let g = Incidence::new(n, l, v);
        let vector = d(phong::reflect(n, l)).dot(d(v));
        let err = (g.r_dot_v() as f64 - vector).abs();
        prop_assert!(
            err <= 32.0 * U,
            "R·V: cosines {} vs vector {vector} (err {err:e}) for n={n} l={l} v={v}", g.r_dot_v()
        );
    }

    #[test]
    fn n_dot_h_squared_from_cosines_equals_the_halfway_vector(
        n in unit_vec3(), l in unit_vec3(), v in unit_vec3()
    ) {
        // (N·H)² = (N·L + N·V)²/(2 + 2L·V) with H = (L+V)/‖L+V‖ and ‖L+V‖² = 2 + 2L·V for unit
        // L, V. The cosine form rounds the numerator's base by ≤ 7U and the denominator
        // den = 2 + 2L·V by ≤ 7U absolute, and the inputs are unit only to 3U each (≤ 6U on
        // ‖L+V‖²); the vector form is accurate to ≤ 16U. So the two differ by at most
        // 16U + 14U/√den + 13U/den: the condition grows as L approaches −V (den → 0), where the
        // cancellation in 2 + 2L·V leaves few digits. Bound: 32U + 16U/√den + 16U/den, with den
        // taken exactly (in f64) from the vectors.
        let g = Incidence::new(n, l, v);
        let h = phong::halfway_or_zero(l, v);
        let vector = d(n).dot(d(h)).max(0.0).powi(2);
        let den = (d(l) + d(v)).length_squared();
        let tol = 32.0 * U + 16.0 * U / den.sqrt() + 16.0 * U / den;
        let err = (g.n_dot_h_squared() as f64 - vector).abs();
        prop_assert!(
            err <= tol,
            "(N·H)²: cosines {} vs vector {vector} (err {err:e} > {tol:e}, ‖L+V‖² = {den:e})",
            g.n_dot_h_squared()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Blinn-Phong with 4s tracks Phong with s near the highlight
// ---------------------------------------------------------------------------------------------

/// `(s, θl, δ)`: shininess, the in-plane angle of `L` from `N`, and the in-plane offset `δ` of `V`
/// from the mirror direction `R`, kept where the Phong lobe is at least e⁻⁶ (sδ²/2 ≤ 6) and
/// `|δ| ≤ 0.5`.
fn near_highlight() -> impl Strategy<Value = (f32, f64, f64)> {
    (8.0f32..=256.0, -1.0f64..=1.0, -1.0f64..=1.0).prop_map(|(s, tl, x)| {
        let max_delta = (12.0 / s as f64).sqrt().min(0.5);
        (s, tl, x * max_delta)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    // Why 4 and how close. With θ = angle(R, V), Phong's lobe is cos^s θ; in the plane of N, L, V,
    // angle(N, H) = θ/2 (checked above), so Blinn-Phong with exponent 4s is cos^{4s}(θ/2). From
    // ln cos x = −x²/2 − x⁴/12 − x⁶/45 − …:
    //     Phong  = exp(−sθ²/2 − sθ⁴/12 − sθ⁶/45 − …)
    //     Blinn  = exp(−sθ²/2 − sθ⁴/48 − sθ⁶/720 − …)
    // The second-order terms (the Gaussian exp(−sθ²/2) that sets the highlight's width) are
    // identical, so the two lobes agree to second order; their log-ratio is
    //     D = ln(Blinn/Phong) = s(θ⁴/16 + θ⁶/48 + …),
    // a fourth-order error. All coefficients of D are positive, and for θ ≤ 0.5 the tail after
    // θ⁴/16 is below θ²·(θ⁴/16) (at θ = 0.5 the whole series is 1.091 × sθ⁴/16), so
    //     exp(sθ⁴/16) − 1 ≤ Blinn/Phong − 1 ≤ exp(sθ⁴/16 · (1 + θ²)) − 1.
    // Near the highlight (sθ²/2 ≤ 6) this is sθ⁴/16 ≤ 2.25/s: 4 % at s = 64, 1 % at s = 256.
    //
    // Out of that plane the ratio is not 4: if V leaves R by δ perpendicular to the plane of
    // incidence, H ∝ L + V tilts from N by only δ/(2 cos θᵢ) (θᵢ = angle(N, L)), so the matching
    // Blinn exponent is 4s·cos²θᵢ. That is why this property keeps N, L, V coplanar.
    //
    // Rounding on top: Phong's R·V = 2(N·L)(N·V) − L·V carries ≤ 30U absolute (three dot products,
    // two products, the difference, and the non-unit inputs), and cos θ ≥ cos 0.5 = 0.877, so
    // the lobe carries ≤ 35·s·U relative; Blinn's (N·H)² carries ≤ 50U relative (N·L + N·V ≥ 0.7
    // and 2 + 2L·V ≥ 0.5 here) raised to 2s: ≤ 100·s·U. Allowance: (P + B)·(100·s + 4)·U.
    #[test]
    fn blinn_with_four_times_the_exponent_tracks_phong(
        (s, tl, delta) in near_highlight(),
        n in unit_vec3(),
        phi in 0.0f64..(2.0 * PI),
    ) {
        let nd = d(n);
        let (t, b) = basis(nd);
        let u = t * phi.cos() + b * phi.sin();
        let at = |theta: f64| (nd * theta.cos() + u * theta.sin()).normalize().as_vec3();
        // L at θl, its mirror R at −θl, V at −θl + δ: angle(R, V) = |δ|.
        let (l, v) = (at(tl), at(-tl + delta));
        let g = Incidence::new(n, l, v);
        let p = Phong::default().specular(&g, s) as f64;
        let bl = BlinnPhong::default().specular(&g, 4.0 * s) as f64;
        let (sd, th) = (s as f64, delta.abs());
        let lead = sd * th.powi(4) / 16.0;
        let rounding = (p + bl) * (100.0 * sd + 4.0) * U;
        let lo = p * lead.exp_m1() - rounding;
        let hi = p * (lead * (1.0 + th * th)).exp_m1() + rounding;
        let diff = bl - p;
        prop_assert!(
            lo <= diff && diff <= hi,
            "Blinn(4s) − Phong(s) = {diff:e} outside [{lo:e}, {hi:e}]: s={s} θ={th} P={p} B={bl}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Triangle normals
// ---------------------------------------------------------------------------------------------

/// `(P1 − P0) × (P2 − P0)` in f64. Differences of f32 coordinates in [−1e3, 1e3] are exact in f64
/// (their exponents differ by far less than 29 except for values below ~1e-6, which proptest's
/// uniform ranges practically never produce; even then the error is 2⁻⁵³ relative), products of
/// two such edges are exact, so each component is correctly rounded in f64.
fn area_vector_f64(p0: Vec3, p1: Vec3, p2: Vec3) -> DVec3 {
    (d(p1) - d(p0)).cross(d(p2) - d(p0))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn triangle_normal_is_perpendicular_to_both_edges((p0, p1, p2) in triangle()) {
        let n = phong::triangle_normal_or_zero(p0, p1, p2);
        prop_assume!(n != Vec3::ZERO);
        // n is the f64 unit normal (exact to 2⁻⁵²) rounded once per component: ‖n − n̂‖ ≤ U.
        // So |n·e| ≤ U‖e‖ plus the 2⁻⁵² of the f64 check; 2U‖e‖.
        for (name, e) in [("P1−P0", d(p1) - d(p0)), ("P2−P0", d(p2) - d(p0))] {
            let dot = d(n).dot(e).abs();
            prop_assert!(
                dot <= 2.0 * U * e.length(),
                "N·({name}) = {dot:e} > 2U‖e‖ = {:e} for {p0} {p1} {p2} (n={n})",
                2.0 * U * e.length()
            );
        }
        prop_assert!(
            (d(n).length() - 1.0).abs() <= 2.0 * U,
            "triangle_normal must be unit, ‖n‖ = {}", d(n).length()
        );
    }

    #[test]
    fn area_normal_length_is_twice_the_area((p0, p1, p2) in triangle()) {
        let a = phong::triangle_area_normal(p0, p1, p2);
        let twice_area = area_vector_f64(p0, p1, p2).length();
        // Each f32 component is the f64 one rounded once (relative U), so the length is within
        // U·‖A‖ of the f64 length; 2U.
        let err = (d(a).length() - twice_area).abs();
        prop_assert!(
            err <= 2.0 * U * twice_area,
            "‖A‖ = {} vs 2·area = {twice_area} for {p0} {p1} {p2}", d(a).length()
        );
    }

    #[test]
    fn swapping_the_winding_flips_the_normal((p0, p1, p2) in triangle()) {
        // Swapping P1 and P2 swaps the two edges; every cross-product component a·b − c·d becomes
        // c·d − a·b, which rounds to exactly the negation. So the flip is bit-exact.
        let a = phong::triangle_area_normal(p0, p1, p2);
        prop_assert_eq!(phong::triangle_area_normal(p0, p2, p1), -a, "area normal, swap P1/P2");
        let n = phong::triangle_normal_or_zero(p0, p1, p2);
        prop_assert_eq!(phong::triangle_normal_or_zero(p0, p2, p1), -n, "unit normal, swap P1/P2");
        // Swapping P0 and P1 changes the origin vertex, so the f64 edges differ; both results are
        // the same exact vector rounded (f64, then f32), so each component is within one f32 ulp
        // (≤ 2U·|x|) of the other.
        let b = phong::triangle_area_normal(p1, p0, p2);
        for i in 0..3 {
            let (x, y) = (a[i] as f64, -(b[i] as f64));
            prop_assert!(
                (x - y).abs() <= 2.0 * U * x.abs().max(y.abs()),
                "component {i}: {x} vs flipped {y} for {p0} {p1} {p2}"
            );
        }
    }

    #[test]
    fn translation_leaves_the_normal_unchanged((p0, p1, p2) in triangle(), t in translation()) {
        let (q0, q1, q2) = (p0 + t, p1 + t, p2 + t);
        let a = d(phong::triangle_area_normal(p0, p1, p2));
        let b = d(phong::triangle_area_normal(q0, q1, q2));
        // The translated vertices are rounded: each coordinate moves by ≤ U·M, M the largest
        // coordinate magnitude, so each edge moves by ‖δe‖ ≤ 2√3·U·M. Then ‖δA‖ ≤ ‖δe₁‖‖e₂‖ +
        // ‖e₁‖‖δe₂‖ (+ second order), and each f32 result rounds once more (U‖A‖ each). Bound:
        // 4U·M·(‖e₁‖ + ‖e₂‖) + 2U‖A‖ (4 > 2√3 absorbs the second-order term).
        let m = [p0, p1, p2, q0, q1, q2]
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0f32, f32::max) as f64;
        let (e1, e2) = ((d(p1) - d(p0)).length(), (d(p2) - d(p0)).length());
        let tol = 4.0 * U * m * (e1 + e2) + 2.0 * U * a.length();
        let err = (a - b).length();
        prop_assert!(err <= tol, "‖A(P+t) − A(P)‖ = {err:e} > {tol:e} for t={t}");
        if a.length() > tol {
            // Unit normals: a perturbation ε of A turns its direction by ≤ 2ε/‖A‖.
            let n = d(phong::triangle_normal_or_zero(p0, p1, p2));
            let m2 = d(phong::triangle_normal_or_zero(q0, q1, q2));
            let dir_tol = 2.0 * tol / a.length() + 2.0 * U;
            prop_assert!(
                (n - m2).length() <= dir_tol,
                "unit normal moved by {:e} > {dir_tol:e} under t={t}", (n - m2).length()
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Lobes
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn lobes_are_in_range_and_dark_below_the_horizon(
        model in model(),
        n in unit_vec3(),
        l in unit_vec3(),
        v in unit_vec3(),
        s in shininess(),
    ) {
        let g = Incidence::new(n, l, v);
        let (kd, ks) = (model.diffuse(&g), model.specular(&g, s));
        prop_assert!(kd.is_finite() && kd >= 0.0, "diffuse {kd} for {model:?} {g:?}");
        prop_assert!(ks.is_finite() && ks >= 0.0, "specular {ks} for {model:?} {g:?} s={s}");
        let (normalization, gate) = match model {
            Model::Lambert(m) => (m.normalization, SpecularGate::Step),
            Model::Phong(m) => (m.normalization, m.gate),
            Model::BlinnPhong(m) => (m.normalization, m.gate),
        };
        if normalization == phong::Normalization::None {
            prop_assert!(kd <= 1.0, "classic diffuse {kd} > 1 for {model:?} {g:?}");
            prop_assert!(ks <= 1.0, "classic specular {ks} > 1 for {model:?} {g:?} s={s}");
        }
        if g.n_dot_l <= 0.0 {
            prop_assert_eq!(kd, 0.0, "diffuse below the horizon, {:?} {:?}", model, g);
            // The step gate, the cosine gate and every normalised lobe (which carry max(N·L, 0))
            // are exactly 0 here; only the "none" gate lets the back-face halo through.
            if gate != SpecularGate::None || normalization != phong::Normalization::None {
                prop_assert_eq!(ks, 0.0, "specular below the horizon, {:?} {:?} s={}", model, g, s);
            }
        }
    }

    #[test]
    fn step_gate_darkens_every_light_below_the_horizon(
        n in unit_vec3(),
        v in unit_vec3(),
        s in shininess(),
        c in 0.0f64..=1.0,
        phi in 0.0f64..(2.0 * PI),
    ) {
        // L in the lower hemisphere of N (N·L = −c ≤ 0).
        let (t, b) = basis(d(n));
        let r = (1.0 - c * c).sqrt();
        let l = (-d(n) * c + t * (r * phi.cos()) + b * (r * phi.sin())).normalize().as_vec3();
        let g = Incidence::new(n, l, v);
        prop_assume!(g.n_dot_l <= 0.0);
        let phong = Phong::default();
        let blinn = BlinnPhong::default();
        prop_assert_eq!(phong.diffuse(&g), 0.0, "Phong diffuse, {:?}", g);
        prop_assert_eq!(phong.specular(&g, s), 0.0, "Phong specular, {:?} s={}", g, s);
        prop_assert_eq!(blinn.diffuse(&g), 0.0, "Blinn diffuse, {:?}", g);
        prop_assert_eq!(blinn.specular(&g, s), 0.0, "Blinn specular, {:?} s={}", g, s);
    }
}

// ---------------------------------------------------------------------------------------------
// Attenuation
// ---------------------------------------------------------------------------------------------

fn distance() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        0.0f32..=1.0,
        0.0f32..=1e3,
        0.0f32..=1e30,
        Just(f32::MAX),
        Just(f32::INFINITY),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    // Every form is a chain of operations each monotone in d (d/r, x², 1 − x⁴, w², c + d(l + qd)
    // with non-negative coefficients, max, and a quotient whose numerator falls and denominator
    // grows), and correct rounding is itself monotone; so the computed factor is exactly
    // non-increasing, with no tolerance.
    #[test]
    fn attenuation_is_non_increasing_in_distance(a in attenuation(), d1 in distance(), d2 in distance()) {
        let (near, far) = if d1 <= d2 { (d1, d2) } else { (d2, d1) };
        let (f_near, f_far) = (a.factor(near), a.factor(far));
        prop_assert!(f_near.is_finite() && f_near >= 0.0, "{a:?}.factor({near}) = {f_near}");
        prop_assert!(f_far.is_finite() && f_far >= 0.0, "{a:?}.factor({far}) = {f_far}");
        prop_assert!(
            f_far <= f_near,
            "{a:?}: factor({far}) = {f_far} > factor({near}) = {f_near}"
        );
    }

    // For c = l = 0 the Horner form gives fl(2d·fl(q·2d)) = 4·fl(d·fl(q·d)): scaling by powers of
    // two is exact away from overflow and subnormals, and 1/(4x) rounds to exactly fl(1/x)/4. So
    // factor(2d) = factor(d)/4 holds bit for bit wherever the floor MIN_DENOMINATOR is not active.
    #[test]
    fn pure_quadratic_follows_the_inverse_square_law(q in 1e-3f32..=1e3, dist in 1e-2f32..=1e3) {
        let a = Attenuation::try_polynomial(0.0, 0.0, q).unwrap();
        let den = dist * (q * dist);
        prop_assume!(den >= Attenuation::MIN_DENOMINATOR);
        prop_assert_eq!(
            a.factor(2.0 * dist),
            a.factor(dist) / 4.0,
            "q={} d={}: factor(2d) vs factor(d)/4", q, dist
        );
    }

    // The same for P / max(d², ε²) once d ≥ ε.
    #[test]
    fn inverse_square_form_follows_the_inverse_square_law(p in 0.0f32..=1e3, dist in 1e-2f32..=1e3) {
        let a = Attenuation::try_inverse_square(p).unwrap();
        prop_assume!(dist >= Attenuation::DEFAULT_MIN_DISTANCE);
        prop_assert_eq!(
            a.factor(2.0 * dist),
            a.factor(dist) / 4.0,
            "P={} d={}: factor(2d) vs factor(d)/4", p, dist
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Superposition
// ---------------------------------------------------------------------------------------------

fn light_colors() -> impl Strategy<Value = LightColors> {
    (color(), color(), color()).prop_map(|(a, d, s)| LightColors::try_new(a, d, s).unwrap())
}

fn light() -> impl Strategy<Value = Light> {
    prop_oneof![
        (unit_vec3(), light_colors())
            .prop_map(|(dir, c)| DirectionalLight::try_new(dir, c).unwrap().into()),
        (point(), attenuation(), light_colors())
            .prop_map(|(p, a, c)| PointLight::try_new(p, a, c).unwrap().into()),
        (
            point(),
            unit_vec3(),
            0.0f32..=core::f32::consts::FRAC_PI_2,
            0.0f32..=64.0,
            attenuation(),
            light_colors()
        )
            .prop_map(|(p, axis, cutoff, e, a, c)| {
                SpotLight::try_new(p, axis, cutoff, e, a, c).unwrap().into()
            }),
    ]
}

fn material() -> impl Strategy<Value = Material> {
    (color(), color(), color(), color(), shininess()).prop_map(|(ka, kd, ks, ke, s)| {
        Material::try_new(ka, kd, ks, s)
            .unwrap()
            .try_with_emission(ke)
            .unwrap()
    })
}

fn viewer() -> impl Strategy<Value = Viewer> {
    prop_oneof![
        point().prop_map(Viewer::At),
        unit_vec3().prop_map(Viewer::Infinite)
    ]
}

fn shade_with(
    model: &Model,
    m: &Material,
    lights: &[Light],
    ia: Vec3,
    viewer: Viewer,
    p: Vec3,
    n: Vec3,
) -> Terms {
    let scene = Scene {
        lights,
        ambient: ia,
        viewer,
    };
    phong::shade(model, m, &scene, p, n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn shading_superposes_over_lights(
        model in model(),
        m in material(),
        a in light(),
        b in light(),
        ia in color(),
        viewer in viewer(),
        p in point(),
        n in unit_vec3(),
    ) {
        let ab = shade_with(&model, &m, &[a, b], ia, viewer, p, n);
        let ta = shade_with(&model, &m, &[a], ia, viewer, p, n);
        let tb = shade_with(&model, &m, &[b], ia, viewer, p, n);
        // shade sums the light-weighted colours x_i = Ld_i·w_i and applies the material once:
        // diffuse = fl(Kd·fl(x_A + x_B)), while the one-light results add as
        // fl(fl(Kd·x_A) + fl(Kd·x_B)). Both are Kd·(x_A + x_B) within two roundings (all terms are
        // ≥ 0, so no cancellation): they differ by at most 4U of the sum, per channel. Where a
        // result is subnormal a rounding is absolute instead, at most half the spacing `2⁻¹⁴⁹`:
        // four of them add up to at most 2 spacings.
        let subnormal = 2.0 * f64::from(f32::from_bits(1));
        for (what, got, a_, b_) in [
            ("diffuse", ab.diffuse, ta.diffuse, tb.diffuse),
            ("specular", ab.specular, ta.specular, tb.specular),
        ] {
            for i in 0..3 {
                let sum = d(a_)[i] + d(b_)[i];
                let err = (d(got)[i] - sum).abs();
                prop_assert!(
                    err <= 4.0 * U * sum + subnormal,
                    "{what} superposition, channel {i}: {} vs A + B = {}", got[i], sum
                );
            }
        }
        prop_assert_eq!(ab.emission, m.emission(), "emission is Ke, counted once");
        // Ambient: Ka⊙(Ia + f_A·La_A + f_B·La_B). Each one-light result also carries the scene
        // ambient Ka⊙Ia, so A + B counts it twice: subtract it once. The three results round
        // their sums and products differently: ≤ 2 roundings in each sum and 1 in each product,
        // each ≤ U of the magnitude S = Ka⊙(Ia + f_A La_A + f_B La_B), plus the test's own
        // additions: 8U·S per channel.
        let ka_ia = m.ambient() * ia;
        let expect = d(ta.ambient) + d(tb.ambient) - d(ka_ia);
        let scale = d(ta.ambient) + d(tb.ambient);
        for i in 0..3 {
            let err = (d(ab.ambient)[i] - expect[i]).abs();
            prop_assert!(
                err <= 8.0 * U * scale[i],
                "ambient channel {i}: {} vs A + B − Ka⊙Ia = {}", ab.ambient[i], expect[i]
            );
        }
        // The totals, with Ka⊙Ia and Ke each counted once: the ambient error above plus one
        // rounding per term in each total: 16U of the sum of the magnitudes.
        let expect_total = d(ta.total()) + d(tb.total()) - d(ka_ia) - d(m.emission());
        let mag = d(ta.total()) + d(tb.total());
        for i in 0..3 {
            let err = (d(ab.total())[i] - expect_total[i]).abs();
            prop_assert!(
                err <= 16.0 * U * mag[i],
                "total channel {i}: {} vs A + B − Ka⊙Ia − Ke = {}", ab.total()[i], expect_total[i]
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Normal matrix
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn normal_matrix_keeps_normals_perpendicular_to_tangents(
        m in invertible_mat3(),
        n in unit_vec3(),
        phi in 0.0f64..(2.0 * PI),
    ) {
        // A unit tangent: a direction in the plane perpendicular to n.
        let (t, b) = basis(d(n));
        let tangent = (t * phi.cos() + b * phi.sin()).as_vec3();
        let nm = phong::normal_matrix(m);
        let n2 = phong::transform_normal(nm, n);
        let t2 = m * tangent;
        // Error bound. Each cofactor column is an f32 cross product of two columns of M, with
        // error ≤ 2√2·U·‖a‖‖b‖; over the matrix ‖E‖_F ≤ 2U‖M‖_F². The product with n adds
        // ≤ 3U‖cof‖_F ≤ 3U‖M‖_F². So NM·n is off by ≤ 5U‖M‖_F², a direction error of
        // 5U‖M‖_F²/‖cof·n‖ (the condition, computed here in f64), plus ≤ 4U from normalising.
        // M·t is off by ≤ 3U‖M‖_F, and t ⟂ n only to 2U, which shows up as ≤ 2U‖M‖_F after the
        // transform. Bound: ‖t'‖(5U‖M‖_F²/‖cof·n‖ + 4U) + 6U‖M‖_F.
        let md = m.as_dmat3();
        let mf = (md.x_axis.length_squared() + md.y_axis.length_squared() + md.z_axis.length_squared()).sqrt();
        let cof = DMat3::from_cols(
            md.y_axis.cross(md.z_axis),
            md.z_axis.cross(md.x_axis),
            md.x_axis.cross(md.y_axis),
        );
        let cof_n = (cof * d(n)).length();
        let t2_len = d(t2).length();
        let tol = t2_len * (5.0 * U * mf * mf / cof_n + 4.0 * U) + 6.0 * U * mf;
        let dot = d(n2).dot(d(t2)).abs();
        prop_assert!(
            dot <= tol,
            "N'·T' = {dot:e} > {tol:e} for det {} m={m:?} n={n}", m.determinant()
        );
        prop_assert!((d(n2).length() - 1.0).abs() <= 4.0 * U, "N' must be unit: {n2}");
        // The sign factor makes N' point like the inverse transpose, also for det M < 0.
        let it = (md.inverse().transpose() * d(n)).normalize();
        prop_assert!(
            d(n2).dot(it) > 0.0,
            "N' = {n2} points away from M⁻ᵀn = {it} (det {})", m.determinant()
        );
    }
}

#[test]
fn invertible_strategy_covers_mirrors() {
    // Guard on the strategy itself: the normal-matrix property must see negative determinants.
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = invertible_mat3();
    let (mut neg, mut pos) = (0, 0);
    for _ in 0..200 {
        let m: Mat3 = strategy.new_tree(&mut runner).unwrap().current();
        if m.determinant() < 0.0 {
            neg += 1;
        } else {
            pos += 1;
        }
    }
    assert!(
        neg > 20 && pos > 20,
        "expected both signs of det M, got {neg} negative, {pos} positive"
    );
}
