//! Guards every bound in docs/accuracy.md: the same measurements as
//! `cargo run --release -p phong-tools --bin accuracy`, on a smaller sample (the first samples of the same
//! seeded streams), asserted against bounds stated once, here, each with the number the full run
//! measured and why the bound is what it is. A regression in any `f32` function fails this test.

use phong_tools::{measure, reference, rng, slivers};

use glam::{DVec3, Vec3};
use phong::{BlinnPhong, Incidence, ReflectionModel};

/// Samples per row here; the example uses 100 000.
const N: usize = 3000;

/// Which statistic of a row a bound applies to.
#[derive(Clone, Copy, Debug)]
enum Metric {
    Ulp,
    Rel,
    Abs,
}

/// A bound on one row: `function`, the start of its domain text, the metric and the limit, and
/// the justification (with the value measured on the full run of the example).
struct Bound(&'static str, &'static str, Metric, f64, &'static str);

use Metric::{Abs, Rel, Ulp};

const BOUNDS: &[Bound] = &[
    // Geometry
    Bound(
        "normalize_or_zero",
        "random directions",
        Ulp,
        4.0,
        "measured 2.49 ulp: the rescale is exact, then one sqrt, one divide, one multiply",
    ),
    Bound(
        "normalize_or_zero",
        "components of independent",
        Ulp,
        4.0,
        "measured 2.43 ulp over the whole f32 range: the doc's \"exact to a few ulps\"",
    ),
    Bound(
        "length",
        "random directions",
        Ulp,
        2.0,
        "measured 1.34 ulp: sum of squares and sqrt",
    ),
    Bound(
        "length",
        "components of independent",
        Ulp,
        2.0,
        "measured 1.08 ulp (saturating at f32::MAX as documented)",
    ),
    Bound(
        "triangle_area_normal",
        "random triangles",
        Ulp,
        1.0,
        "measured 0.500 ulp: exact f64 products, one rounding to f32",
    ),
    Bound(
        "triangle_area_normal",
        "sliver set",
        Ulp,
        1.0,
        "measured 0.500 ulp on slivers: the doc's exact-then-rounded-once claim",
    ),
    Bound(
        "triangle_normal_or_zero",
        "random triangles",
        Ulp,
        1.0,
        "measured 0.500 ulp: the doc's \"about 1 ulp per component\"",
    ),
    Bound(
        "triangle_normal_or_zero",
        "sliver set",
        Ulp,
        1.0,
        "measured 0.500 ulp on slivers 1e5 from the origin, aspect 1e-5",
    ),
    Bound(
        "reflect",
        "unit N, L in",
        Ulp,
        6.0,
        "measured 3.62 ulp (of the largest component): a dot product and a fused-free 2(N·L)N − L",
    ),
    Bound(
        "reflect",
        "unit N, L grazing",
        Ulp,
        6.0,
        "measured 2.02 ulp",
    ),
    Bound(
        "halfway_or_zero",
        "unit L, V uniform",
        Ulp,
        4.0,
        "measured 2.60 ulp: one add, then normalize_or_zero",
    ),
    Bound(
        "halfway_or_zero",
        "V = −L turned",
        Ulp,
        4.0,
        "measured 2.53 ulp down to δ = 1e-7: L + V is exact (Sterbenz)",
    ),
    Bound(
        "face_forward",
        "random N, V, Nref",
        Abs,
        0.0,
        "measured 0: away from the tie the sign decision is exact",
    ),
    Bound(
        "face_forward",
        "V within",
        Abs,
        0.0,
        "measured 0: face_forward returns exactly N or −N, on the exact sign of Nref·V, so any \
         error is a flip (2); an f32 dot product flips 179 of the first 3000 samples here. The \
         f64 reference's sign is exact except within 2⁻⁵² of the tie (relative to Σ|Nref_i·V_i|), \
         far inside the 1e-9 rad the samples keep from it before V is rounded to f32",
    ),
    Bound(
        "normal_matrix",
        "random matrices",
        Ulp,
        2.0,
        "measured 0.500 ulp: f64 cofactors of f32 entries are exact up to one rounding, then one rounding to f32",
    ),
    Bound(
        "transform_normal",
        "random matrices",
        Ulp,
        300.0,
        "measured 73 ulp: the f32 matrix-vector product of an ill-conditioned normal matrix; error follows the condition number",
    ),
    Bound(
        "normal_matrix",
        "near-singular",
        Rel,
        2e-7,
        "measured 5.88e-8 with f64 cofactors and det (was 2.00: an f32 det of the wrong sign flipped the matrix)",
    ),
    Bound(
        "transform_normal",
        "near-singular",
        Rel,
        5e-4,
        "measured 1.06e-4: the f32 product NM·n of a near-singular normal matrix (was 2.00 from the sign flip)",
    ),
    // Attenuation
    Bound(
        "Attenuation::factor — Polynomial",
        "d in",
        Ulp,
        6.0,
        "measured 3.12 ulp: Horner form, one divide",
    ),
    Bound(
        "Attenuation::factor — Polynomial",
        "d = 0",
        Ulp,
        6.0,
        "measured 3.10 ulp, d from 0 to 1e30",
    ),
    Bound(
        "Attenuation::factor — InverseSquare",
        "d in",
        Ulp,
        3.0,
        "measured 1.40 ulp",
    ),
    Bound(
        "Attenuation::factor — InverseSquare",
        "d = 0",
        Ulp,
        3.0,
        "measured 1.42 ulp (where the true factor is ≥ 1e-30)",
    ),
    Bound(
        "Attenuation::factor — Unreal",
        "d in",
        Rel,
        1e-3,
        "measured 2.75e-4: 1 − (d/r)⁴ cancels as d → r, where the factor is tiny",
    ),
    Bound(
        "Attenuation::factor — Unreal",
        "d = 0",
        Rel,
        1e-3,
        "measured 3.50e-5: the same window cancellation",
    ),
    Bound(
        "Attenuation::factor — Frostbite",
        "d in",
        Rel,
        5e-3,
        "measured 1.82e-3: the window cancellation near d = r",
    ),
    Bound(
        "Attenuation::factor — Frostbite",
        "d = 0",
        Rel,
        5e-3,
        "measured 2.58e-5",
    ),
    // cull_radius promises safety and tightness against the crate's own f32 factor (exact for the
    // polynomial and inverse-square forms, to a margin t·2⁻¹⁹ for the windowed ones), not the
    // exact crossing measured here. It differs from that crossing by the f32 factor's relative
    // error (or the margin) divided by the elasticity |d·f'/f| at the crossing, plus the final
    // ulp; where the factor is flat (t near factor(0)) that elasticity goes to 0.
    Bound(
        "Attenuation::cull_radius — Polynomial",
        "threshold in",
        Ulp,
        8.0,
        "measured 2.57 ulp: the factor's 5 roundings over an elasticity ≥ 0.85 (1/t ≥ 10, c ≤ 1.5), plus the last ulp",
    ),
    Bound(
        "Attenuation::cull_radius — Polynomial",
        "threshold log",
        Rel,
        1e-3,
        "measured 1.43e-4 (t = 1.709 near factor(0) = 1/c = 1.71): the f32 factor's rounding where it is flat moves the crossing",
    ),
    Bound(
        "Attenuation::cull_radius — InverseSquare",
        "threshold in",
        Ulp,
        2.0,
        "measured 1.10 ulp: P/d/d's 2 roundings over the elasticity 2, plus the last ulp",
    ),
    Bound(
        "Attenuation::cull_radius — InverseSquare",
        "threshold log",
        Ulp,
        2.0,
        "measured 1.11 ulp",
    ),
    Bound(
        "Attenuation::cull_radius — Unreal",
        "threshold in",
        Rel,
        1.5e-6,
        "measured 1.06e-6: the margin 2⁻¹⁹ over the elasticity ≥ 1.8 (t ≤ 0.1 puts the crossing at d ≥ 3), plus the last ulp",
    ),
    Bound(
        "Attenuation::cull_radius — Unreal",
        "threshold log",
        Rel,
        1e-2,
        "measured 1.43e-3 (t = 0.99934 near factor(0) = 1): where f ≈ 1 − d² the margin moves the root by about 2⁻²⁰/(1 − t) relatively",
    ),
    Bound(
        "Attenuation::cull_radius — Frostbite",
        "threshold in",
        Rel,
        1.2e-6,
        "measured 9.54e-7: the margin 2⁻¹⁹ over the elasticity ≥ 2 (the 1/d² law), plus the last ulp",
    ),
    Bound(
        "Attenuation::cull_radius — Frostbite",
        "threshold log",
        Rel,
        1.2e-6,
        "measured 9.54e-7: as above; no sampled t came within 2⁻¹⁹ of factor(0) = 1/ε², where the flat top would move it",
    ),
    Bound(
        "SpotLight::spot_factor",
        "random axis",
        Ulp,
        64.0,
        "measured 30.8 ulp: the cosine's rounding raised to the exponent",
    ),
    // The adversarial spot row has two bounds: Rel catches a point inside the cone left dark
    // (relative error 1), Abs a point outside it lit (error (cos cutoff)^e, up to 1).
    Bound(
        "SpotLight::spot_factor",
        "exponent in",
        Rel,
        2.4e-3,
        "measured 6.71e-4. Within 2⁻²² of the edge either side counts (measure::SPOT_EDGE_BAND: \
         the f32 cosine's own error); elsewhere that error δ becomes e·δ/c relative in c^e, at \
         most 1e4·2⁻²²/cos(0.05) = 2.39e-3 (plus powf's ulp), as a base below 0.993 with e = 1e4 \
         falls under the 1e-30 floor",
    ),
    Bound(
        "SpotLight::spot_factor",
        "exponent in",
        Abs,
        2.4e-3,
        "measured 2.10e-5. The same band; elsewhere δ ≤ 2⁻²² moves c^e by e·c^(e−1)·δ ≤ e·δ ≤ \
         1e4·2⁻²² = 2.4e-3 for e ≥ 1 (for e < 1, c ≥ cos 1.5 bounds it by δ/0.07 = 3.4e-6)",
    ),
    // The batch kernel's spot factor: its own pow for c^e (the batch module's "Accuracy": 3.3e-5
    // relative to max(c^e, 2^-24), the rows' floor), on top of the scalar rows' cosine error and
    // N·L within 2e-6 of 1.
    Bound(
        "shade_batch spot factor (Lambert, N·L ≈ 1)",
        "random axis",
        Rel,
        4e-5,
        "measured 4.55e-6: the pow plan's 3.3e-5 (2.2e-5 for a non-whole e), plus the cosine's \
         rounding raised to e ≤ 8 (the scalar row: 1.97e-6) and N·L's 2e-6",
    ),
    Bound(
        "shade_batch spot factor (Lambert, N·L ≈ 1)",
        "exponent in",
        Rel,
        2.5e-3,
        "measured 5.72e-4: the scalar row's bound for the cosine's error raised to e ≤ 1e4 \
         (2.39e-3, plus powf's ulp), plus the pow plan's 3.3e-5 and N·L's 2e-6",
    ),
    Bound(
        "shade_batch spot factor (Lambert, N·L ≈ 1)",
        "exponent in",
        Abs,
        2.5e-3,
        "measured 2.94e-5: the scalar row's 2.4e-3, plus the pow plan's 3.3e-5 of a factor ≤ 1",
    ),
    // Lobes, ordinary: abs error from the f32 cosines (about 1e-7) times s.
    Bound(
        "Incidence::r_dot_v",
        "unit N;",
        Abs,
        1e-6,
        "measured 3.23e-7: 2(N·L)(N·V) − L·V from three rounded cosines",
    ),
    Bound(
        "Incidence::n_dot_h_squared",
        "unit N;",
        Abs,
        1e-4,
        "measured 2.97e-5: the denominator 2 + 2L·V cancels when L, V are nearly opposite",
    ),
    Bound("Phong specular", "unit N;", Abs, 1e-4, "measured 1.87e-5"),
    Bound(
        "BlinnPhong specular",
        "unit N;",
        Abs,
        1e-3,
        "measured 2.79e-4 (12× the vector form's 2.28e-5: the (N·H)² cancellation)",
    ),
    Bound(
        "Phong specular, Energy",
        "unit N;",
        Abs,
        2e-3,
        "measured 5.03e-4 on lobes up to (s+2)/2π ≈ 41",
    ),
    Bound(
        "BlinnPhong specular, Energy",
        "unit N;",
        Abs,
        1e-3,
        "measured 2.02e-4",
    ),
    Bound(
        "BlinnPhong specular, EnergyExact",
        "unit N;",
        Abs,
        1e-3,
        "measured 2.00e-4",
    ),
    Bound(
        "Phong specular, PowStrategy::Squaring",
        "unit N;",
        Abs,
        1e-4,
        "measured 2.16e-5",
    ),
    Bound(
        "Lambert diffuse",
        "unit N;",
        Abs,
        2e-7,
        "measured 9.82e-8: one rounded dot product",
    ),
    Bound(
        "vector form: lobe(N·halfway(L,V), s)",
        "unit N;",
        Abs,
        1e-4,
        "measured 2.28e-5",
    ),
    // Lobes at grazing angles.
    Bound(
        "Incidence::r_dot_v",
        "L, V grazing",
        Abs,
        1e-6,
        "measured 1.26e-7",
    ),
    Bound(
        "Incidence::n_dot_h_squared",
        "L, V grazing",
        Abs,
        1e-6,
        "measured 2.88e-7 with (N·H)² from L + V (was 0.202 with the cosine form): a few ulps of a value ≤ 1",
    ),
    Bound(
        "Phong specular",
        "L, V grazing",
        Abs,
        1e-3,
        "measured 2.71e-4 with s up to 1e4",
    ),
    Bound(
        "BlinnPhong specular",
        "L, V grazing",
        Abs,
        1e-4,
        "measured 2.98e-5 with s up to 1e4 (was 0.612 with the cosine form)",
    ),
    Bound(
        "Phong specular, Energy",
        "L, V grazing",
        Abs,
        1e-2,
        "measured 1.94e-3 on lobes up to ≈ 1600",
    ),
    Bound(
        "BlinnPhong specular, Energy",
        "L, V grazing",
        Abs,
        1e-3,
        "measured 2.64e-4 on lobes scaled by up to (s+8)/8π ≈ 398 and damped by N·L (was 0.0352)",
    ),
    Bound(
        "BlinnPhong specular, EnergyExact",
        "L, V grazing",
        Abs,
        1e-3,
        "measured 2.64e-4 (was 0.0352)",
    ),
    Bound(
        "Phong specular, PowStrategy::Squaring",
        "L, V grazing",
        Abs,
        1e-3,
        "measured 2.71e-4",
    ),
    Bound(
        "Lambert diffuse",
        "L, V grazing",
        Abs,
        2e-7,
        "measured 6.12e-8",
    ),
    Bound(
        "vector form: lobe(N·halfway(L,V), s)",
        "L, V grazing",
        Abs,
        1e-4,
        "measured 1.89e-5",
    ),
    Bound(
        "Incidence::r_dot_v",
        "L grazing, V within",
        Abs,
        1e-6,
        "measured 1.34e-7",
    ),
    Bound(
        "Incidence::n_dot_h_squared",
        "L grazing, V within",
        Abs,
        1e-6,
        "measured 3.65e-7 (was 1.00 with the cosine form)",
    ),
    Bound(
        "Phong specular",
        "L grazing, V within",
        Abs,
        3e-3,
        "measured 8.98e-4: s up to 1e4 at the peak, s·1e-7",
    ),
    Bound(
        "BlinnPhong specular",
        "L grazing, V within",
        Abs,
        5e-3,
        "measured 1.40e-3: s up to 1e4 at the peak, s·1e-7 as for Phong (was 1.00)",
    ),
    Bound(
        "Phong specular, Energy",
        "L grazing, V within",
        Abs,
        0.3,
        "measured 0.0814 on lobes up to ≈ 1600",
    ),
    Bound(
        "BlinnPhong specular, Energy",
        "L grazing, V within",
        Abs,
        0.1,
        "measured 0.0325 on lobes up to ≈ 398 (was 3.28)",
    ),
    Bound(
        "BlinnPhong specular, EnergyExact",
        "L grazing, V within",
        Abs,
        0.1,
        "measured 0.0325 (was 3.28)",
    ),
    Bound(
        "Phong specular, PowStrategy::Squaring",
        "L grazing, V within",
        Abs,
        3e-3,
        "measured 8.98e-4",
    ),
    Bound(
        "Lambert diffuse",
        "L grazing, V within",
        Abs,
        2e-7,
        "measured 6.77e-8",
    ),
    Bound(
        "vector form: lobe(N·halfway(L,V), s)",
        "L grazing, V within",
        Abs,
        5e-3,
        "measured 1.27e-3: s up to 1e4 at the peak",
    ),
    Bound(
        "Incidence::r_dot_v",
        "L, V nearly opposite",
        Abs,
        1e-6,
        "measured 3.81e-7",
    ),
    Bound(
        "Incidence::n_dot_h_squared",
        "L, V nearly opposite",
        Abs,
        1e-6,
        "measured 3.15e-7 (was 1.00 with the cosine form)",
    ),
    Bound(
        "Phong specular",
        "L, V nearly opposite",
        Abs,
        1e-3,
        "measured 3.24e-4",
    ),
    Bound(
        "BlinnPhong specular",
        "L, V nearly opposite",
        Abs,
        3e-4,
        "measured 7.40e-5 (was 1.00)",
    ),
    Bound(
        "Phong specular, Energy",
        "L, V nearly opposite",
        Abs,
        1e-2,
        "measured 3.23e-3",
    ),
    Bound(
        "BlinnPhong specular, Energy",
        "L, V nearly opposite",
        Abs,
        1.5e-3,
        "measured 3.76e-4 (was 105)",
    ),
    Bound(
        "BlinnPhong specular, EnergyExact",
        "L, V nearly opposite",
        Abs,
        1.5e-3,
        "measured 3.76e-4 (was 105)",
    ),
    Bound(
        "Phong specular, PowStrategy::Squaring",
        "L, V nearly opposite",
        Abs,
        1e-3,
        "measured 3.24e-4",
    ),
    Bound(
        "Lambert diffuse",
        "L, V nearly opposite",
        Abs,
        2e-7,
        "measured 9.94e-8",
    ),
    Bound(
        "vector form: lobe(N·halfway(L,V), s)",
        "L, V nearly opposite",
        Abs,
        1e-3,
        "measured 1.64e-4",
    ),
    // Factors and pow.
    Bound(
        "ResolvedModel::specular_scale, Phong, Energy",
        "s in",
        Ulp,
        3.0,
        "measured 1.79 ulp",
    ),
    Bound(
        "ResolvedModel::specular_scale, Blinn-Phong, Energy",
        "s in",
        Ulp,
        3.0,
        "measured 1.80 ulp",
    ),
    Bound(
        "ResolvedModel::specular_scale, Blinn-Phong, EnergyExact",
        "s in",
        Ulp,
        6.0,
        "measured 3.81 ulp: powf, two divides",
    ),
    Bound(
        "PowStrategy::Exact.lobe",
        "s in",
        Ulp,
        1.0,
        "measured 0.601 ulp: powf",
    ),
    Bound(
        "PowStrategy::Squaring.lobe (integer s)",
        "s in",
        Rel,
        1.2e-3,
        "measured 1.80e-4; the doc's s·2⁻²⁴ is 6.0e-4 at s = 1e4, plus log2(s) roundings",
    ),
    Bound(
        "ResolvedModel::diffuse, Energy (1/π)",
        "s in",
        Ulp,
        2.0,
        "measured 1.18 ulp",
    ),
    // Colour.
    Bound("srgb_encode", "x uniform", Ulp, 4.0, "measured 2.88 ulp"),
    Bound(
        "srgb_decode",
        "x uniform",
        Ulp,
        8.0,
        "measured 6.49 ulp: the base's two roundings raised to 2.4",
    ),
    Bound("gamma_encode", "x uniform", Ulp, 2.0, "measured 1.30 ulp"),
    Bound("gamma_decode", "x uniform", Ulp, 1.0, "measured 0.501 ulp"),
    Bound(
        "srgb_encode",
        "x log-uniform",
        Ulp,
        10.0,
        "measured 7.33 ulp",
    ),
    Bound(
        "srgb_decode",
        "x log-uniform",
        Ulp,
        20.0,
        "measured 13.5 ulp for x up to 1e3",
    ),
    Bound(
        "gamma_encode",
        "x log-uniform",
        Ulp,
        100.0,
        "measured 57.5 ulp: 1/γ rounded to f32, times |ln x| ≈ 69 at x = 1e-30",
    ),
    Bound(
        "gamma_decode",
        "x log-uniform",
        Ulp,
        1.0,
        "measured 0.501 ulp",
    ),
    Bound(
        "linear_to_srgb8 (levels)",
        "linear channels",
        Abs,
        1.0,
        "measured 1 level, only where f32 lands on the other side of a rounding boundary",
    ),
];

fn value(s: &measure::Stats, m: Metric) -> f64 {
    match m {
        Ulp => s.max_ulp,
        Rel => s.max_rel,
        Abs => s.max_abs,
    }
}

#[test]
fn every_row_stays_within_its_bound() {
    let rows = measure::rows(N);
    let mut failures = Vec::new();
    for r in rows.iter().filter(|r| !r.function.starts_with("naive")) {
        let bounds: Vec<&Bound> = BOUNDS
            .iter()
            .filter(|b| b.0 == r.function && r.domain.starts_with(b.1))
            .collect();
        assert!(
            !bounds.is_empty(),
            "no bound for row `{}`: add one to BOUNDS",
            r.key()
        );
        assert!(r.stats.n > 0, "row `{}` measured nothing", r.key());
        assert_eq!(
            r.stats.non_finite,
            0,
            "row `{}`: non-finite output for finite input ({})",
            r.key(),
            r.stats.worst
        );
        for b in bounds {
            let v = value(&r.stats, b.2);
            if v > b.3 {
                failures.push(format!(
                    "{}: {:?} {v:e} > bound {:e} ({}); worst input {}",
                    r.key(),
                    b.2,
                    b.3,
                    b.4,
                    r.stats.worst
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "bounds exceeded:\n{}",
        failures.join("\n")
    );
}

#[test]
fn every_bound_names_a_measured_row() {
    let rows = measure::rows(50);
    for b in BOUNDS {
        assert!(
            rows.iter()
                .any(|r| r.function == b.0 && r.domain.starts_with(b.1)),
            "bound `{} | {}` matches no row",
            b.0,
            b.1
        );
    }
}

#[test]
fn naive_rows_show_the_failures_the_docs_describe() {
    let rows = measure::rows(N);
    let get = |f: &str, d: &str| {
        rows.iter()
            .find(|r| r.function == f && r.domain.starts_with(d))
            .unwrap_or_else(|| panic!("no row {f} | {d}"))
    };
    // glam's normalize over the whole range: overflow and underflow of v·v.
    let naive = get("naive: v.normalize()", "components of independent");
    assert!(
        naive.stats.non_finite > 0,
        "naive normalize should give NaN/∞ on tiny vectors"
    );
    // Naive slivers lose digits; the crate keeps them.
    let naive = get("naive: normalize((P1−P0)×(P2−P0))", "sliver set");
    let ours = get("triangle_normal_or_zero", "sliver set");
    assert!(
        naive.stats.max_rel > 1000.0 * ours.stats.max_rel,
        "naive sliver normal {} vs ours {}",
        naive.stats.max_rel,
        ours.stats.max_rel
    );
}

#[test]
fn sliver_study_meets_the_10x_target_and_one_ulp() {
    let mut rng = rng::Rng::new(60);
    let (set, _) = slivers::sliver_set(&mut rng, 2);
    for shape in [
        None,
        Some(slivers::Shape::Needle),
        Some(slivers::Shape::Cap),
    ] {
        let res = slivers::study(&set, |t| shape.is_none_or(|s| t.shape == s));
        let naive = res[0].1;
        let ours = res[3].1;
        // Measured on the full set: phong 4.44e-8 rad (0.75 u) against naive 0.0355 rad.
        assert!(
            ours.worst < 2.0 * 2f64.powi(-24),
            "{shape:?}: triangle_normal worst {} rad is above 2 u",
            ours.worst
        );
        assert!(
            naive.worst >= 10.0 * ours.worst,
            "{shape:?}: target ≥ 10× smaller worst case: naive {} vs phong {}",
            naive.worst,
            ours.worst
        );
        assert_eq!(ours.lost, 0, "{shape:?}: triangle_normal lost a normal");
    }
    // The doc's "about 1 ulp per component": measured 0.500 on the full set.
    for t in &set {
        let got = phong::triangle_normal_or_zero(t.p[0], t.p[1], t.p[2]).as_dvec3();
        let want = reference::triangle_normal(t.p[0], t.p[1], t.p[2]);
        for i in 0..3 {
            let ulps = (got[i] - want[i]).abs() / measure::ulp_f32(want[i]);
            assert!(ulps <= 1.0, "{:?}: component {i} off by {ulps} ulp", t.p);
        }
    }
}

#[test]
fn shading_matches_the_reference_in_8bit_srgb() {
    // Full run: typical 0.0010 % of channels differ (6 of 600 000), hard 0.0007 %, by 1 level.
    for (seed, hard, per_point) in [
        (50, false, false),
        (51, true, false),
        (50, false, true),
        (51, true, true),
    ] {
        let s = measure::measure_shading(4000, seed, hard, per_point);
        assert_eq!(s.stats.non_finite, 0, "hard = {hard}: non-finite shading");
        assert!(
            s.fraction() <= 1e-3,
            "hard = {hard}, per point = {per_point}: {} % of 8-bit channels differ",
            100.0 * s.fraction()
        );
        assert!(
            s.srgb8_max_levels <= 1,
            "hard = {hard}: an 8-bit channel is off by {} levels",
            s.srgb8_max_levels
        );
        // Full run (200 000 scenes each): max rel 6.5e-4 (typical), 1.2e-3 (hard, where s up to
        // 1e4 turns the f32 cosines' 1e-7 into 1e-3). Bound 5e-3.
        assert!(
            s.stats.max_rel < 5e-3,
            "hard = {hard}: max rel {}",
            s.stats.max_rel
        );
    }
}

#[test]
fn halfway_is_exact_to_the_tie_and_zero_at_it() {
    let mut rng = rng::Rng::new(70);
    for k in 1..=7 {
        let delta = 10f64.powi(-k);
        for _ in 0..200 {
            let l = rng.unit_vec3();
            let v = rng.at_angle(-l, delta);
            let want = reference::halfway(l.as_dvec3(), v.as_dvec3());
            if want == DVec3::ZERO {
                continue;
            }
            let e = slivers::angle_between(phong::halfway_or_zero(l, v).as_dvec3(), want);
            // Full run: at most 6.1e-8 rad at every δ.
            assert!(e < 2e-7, "δ = {delta}: halfway off by {e} rad");
        }
    }
    let l = Vec3::new(0.6, 0.0, 0.8);
    assert_eq!(
        phong::halfway_or_zero(l, -l),
        Vec3::ZERO,
        "the documented zero at L = −V"
    );
}

#[test]
fn four_times_rule_error_is_as_documented() {
    // docs/derivations.md cites these: max |Blinn(4s) − Phong(s)| ≈ e⁻²/s in the plane of
    // incidence (measured 0.00873 at s = 16 against 0.00846, 0.00213 at s = 64 against 0.00211).
    for s in [16.0, 64.0, 256.0, 1024.0] {
        let (m, p) = measure::four_times_rule_in_plane(s);
        assert!(
            (m - p).abs() <= 0.05 * p,
            "s = {s}: measured {m}, second-order prediction {p}"
        );
    }
    // Out of the plane the matching ratio is 4 cos²θi (measured 3.01 at 30°, 1.01 at 60°).
    for deg in [0.0f64, 30.0, 45.0, 60.0] {
        let t = deg.to_radians();
        let ratio = measure::matching_ratio(64.0, t, false);
        let want = 4.0 * t.cos().powi(2);
        assert!(
            (ratio - want).abs() < 0.05,
            "θi = {deg}°: ratio {ratio}, want {want}"
        );
        let in_plane = measure::matching_ratio(64.0, t, true);
        assert!(
            (in_plane - 4.0).abs() < 0.05,
            "θi = {deg}°: in-plane ratio {in_plane}"
        );
    }
}

#[test]
fn blinn_lobe_at_opposite_grazing_directions_keeps_the_highlight() {
    // Found by the first measurement run: with N = Z and L, V at ε above the plane on opposite
    // sides, H = N exactly and the true lobe is 1, but the cosine form
    // (N·H)² = (N·L + N·V)² / (2 + 2 L·V) has a denominator below f32 resolution and gave 0.
    // Incidence::new now computes (N·H)² from L + V; the lobe must be 1 to a few ulps × s.
    for eps in [1e-2f64, 1e-4, 1e-6] {
        let l = DVec3::new(eps.cos(), 0.0, eps.sin()).as_vec3();
        let v = DVec3::new(-eps.cos(), 0.0, eps.sin()).as_vec3();
        let got = BlinnPhong::default().specular(&Incidence::new(Vec3::Z, l, v), 32.0);
        // (N·H)² is within 2 ulps of 1, and raising to s/2 = 16 multiplies that by 16.
        assert!(
            (got - 1.0).abs() < 16.0 * 2.0 * f32::EPSILON,
            "ε = {eps:e}: Blinn-Phong lobe {got}, want 1"
        );
        // The cosine form still fails here, which is why it is not used when vectors exist.
        let g = Incidence::new(Vec3::Z, l, v);
        let cos_form = BlinnPhong::default().specular(
            &Incidence::from_cosines(g.n_dot_l, g.n_dot_v, g.l_dot_v),
            32.0,
        );
        assert!(
            (0.0..=1.0).contains(&cos_form),
            "cosine form in range: {cos_form}"
        );
    }
}
