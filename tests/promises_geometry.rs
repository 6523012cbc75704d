//! The geometry's exactness promises at the extremes of the `f32` range, checked against an
//! independent exact reference.
//!
//! - `normal_matrix`: `sign(det M)` is the exact sign (with `sign(0) = +1`) and every entry is the
//!   exact entry of `sign(det M)·2ᵏ·cof(M)` rounded to nearest.
//! - `triangle_area_normal`: each component is the exact one rounded to nearest (saturated);
//!   `try_triangle_normal` is within 0.5 + 2⁻¹⁴ ulp of the exact unit normal, `None` exactly for a
//!   zero area.
//! - `reflect`: finite for every finite `L` (saturating), and the `f32` formula where that is finite.
//! - `face_forward`: decides by the exact sign of `Nref·V`.
//!
//! The reference ([`exact::Fixed`]) is plain fixed-point integer arithmetic, a different algorithm
//! from the crate's expansions: every `f32` is an integer times a power of two, so sums of their
//! products are exact as wide integers, and rounding them is bit manipulation.

use crate::strategies;

use glam::{DVec3, Mat3, Vec3};
use proptest::prelude::*;
use strategies::unit_vec3;

use exact::Fixed;

/// Exact sums of products of `f32`, as fixed-point integers.
mod exact {
    /// The value is `Σ limbs[k] · 2^(32k − BASE)`. Products of up to three `f32` are multiples of
    /// 2⁻⁴⁴⁷ and below 2⁴⁰⁰, so 2⁻⁴⁶⁰ … 2⁵⁶⁴ holds every sum the tests build.
    const BASE: i64 = 460;
    const LIMBS: usize = 32;

    /// A signed fixed-point number with unnormalised 32-bit limbs (held in `i128`, so a few dozen
    /// additions cannot overflow them).
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct Fixed([i128; LIMBS]);

    /// `x = ±m · 2^e` with `m < 2²⁴`.
    fn parts(x: f32) -> (bool, u128, i64) {
        assert!(x.is_finite(), "finite input only: {x}");
        let b = x.to_bits();
        let neg = b >> 31 == 1;
        let field = ((b >> 23) & 0xff) as i64;
        let frac = (b & 0x7f_ffff) as u128;
        if field == 0 {
            (neg, frac, -149)
        } else {
            (neg, frac | 1 << 23, field - 150)
        }
    }

    impl Fixed {
        pub(crate) fn zero() -> Self {
            Fixed([0; LIMBS])
        }

        /// `Σ sign · Π factors` over the given terms.
        pub(crate) fn sum(terms: &[(i32, &[f32])]) -> Self {
            let mut s = Fixed::zero();
            for &(sign, factors) in terms {
                s.add(sign < 0, factors);
            }
            s
        }

        /// Adds `±Π factors`, exactly.
        pub(crate) fn add(&mut self, negate: bool, factors: &[f32]) {
            let (mut m, mut e, mut neg) = (1u128, 0i64, negate);
            for &f in factors {
                let (n, fm, fe) = parts(f);
                m *= fm;
                e += fe;
                neg ^= n;
            }
            if m == 0 {
                return;
            }
            let shift = e + BASE;
            assert!(shift >= 0, "below the fixed-point range");
            let (mut k, r) = ((shift / 32) as usize, shift % 32);
            let mut x = m << r; // m < 2⁷², so x < 2¹⁰⁴
            while x != 0 {
                let piece = (x & 0xffff_ffff) as i128;
                self.0[k] += if neg { -piece } else { piece };
                x >>= 32;
                k += 1;
            }
        }

        /// Limbs carried into [0, 2³²), except the top one, which keeps the sign.
        fn carried(mut l: [i128; LIMBS]) -> [i128; LIMBS] {
            for k in 0..LIMBS - 1 {
                let carry = l[k] >> 32;
                l[k] -= carry << 32;
                l[k + 1] += carry;
            }
            l
        }

        /// The sign (−1, 0, 1) and the magnitude's bits.
        fn sign_magnitude(&self) -> (i64, [u64; LIMBS]) {
            let c = Self::carried(self.0);
            let negative = c[LIMBS - 1] < 0;
            let c = if negative {
                Self::carried(self.0.map(|x| -x))
            } else {
                c
            };
            assert_eq!(c[LIMBS - 1], 0, "outside the fixed-point range");
            let mag = c.map(|x| x as u64);
            let sign = if negative {
                -1
            } else if mag.iter().any(|&x| x != 0) {
                1
            } else {
                0
            };
            (sign, mag)
        }

        pub(crate) fn sign(&self) -> i64 {
            self.sign_magnitude().0
        }

        /// `value · 2^scale` rounded to nearest, ties to even, with `precision` significant bits
        /// and no bit below 2^emin; the result is returned exactly, as an `f64`.
        fn round(&self, scale: i64, precision: i64, emin: i64) -> f64 {
            let (sign, mag) = self.sign_magnitude();
            if sign == 0 {
                return 0.0;
            }
            let bit = |i: i64| -> u64 {
                if i < 0 {
                    0
                } else {
                    (mag[(i / 32) as usize] >> (i % 32)) & 1
                }
            };
            let top = (0..LIMBS as i64 * 32).rev().find(|&i| bit(i) == 1).unwrap();
            // Bit i of the magnitude weighs 2^(i − BASE + scale).
            let lsb = (top - (precision - 1)).max(emin + BASE - scale);
            let mut m: u64 = 0;
            for i in (lsb..=top).rev() {
                m = (m << 1) | bit(i);
            }
            let half = bit(lsb - 1) == 1;
            let sticky = (0..lsb - 1).any(|i| bit(i) == 1);
            if half && (sticky || m & 1 == 1) {
                m += 1;
            }
            let e = lsb - BASE + scale;
            sign as f64 * m as f64 * 2f64.powi(e as i32)
        }

        /// The value rounded to the nearest `f32` (∞ beyond its range).
        pub(crate) fn to_f32(self) -> f32 {
            self.scaled_to_f32(0)
        }

        /// `value · 2^scale` rounded to the nearest `f32`.
        pub(crate) fn scaled_to_f32(&self, scale: i64) -> f32 {
            self.round(scale, 24, -149) as f32
        }

        /// The value rounded to the nearest `f64`.
        pub(crate) fn to_f64(self) -> f64 {
            self.round(0, 53, -1074)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Exact references

/// The exact components of the doubled area vector `P0×P1 + P1×P2 + P2×P0`.
fn exact_area(p: [Vec3; 3]) -> [Fixed; 3] {
    let c = p.map(|q| q.to_array());
    // Component i is the determinant of the projection on coordinates (u, v).
    [(1, 2), (2, 0), (0, 1)].map(|(u, v)| {
        let mut s = Fixed::zero();
        for k in 0..3 {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            s.add(false, &[a[u], b[v]]);
            s.add(true, &[a[v], b[u]]);
        }
        s
    })
}

/// The exact cofactor matrix `[b×c, c×a, a×b]`, column by column.
fn exact_cofactors(m: Mat3) -> [[Fixed; 3]; 3] {
    let (a, b, c) = (
        m.x_axis.to_array(),
        m.y_axis.to_array(),
        m.z_axis.to_array(),
    );
    let cross = |p: [f32; 3], q: [f32; 3]| {
        [(1, 2), (2, 0), (0, 1)]
            .map(|(i, j)| Fixed::sum(&[(1, &[p[i], q[j]]), (-1, &[p[j], q[i]])]))
    };
    [cross(b, c), cross(c, a), cross(a, b)]
}

/// The exact sign of `det M`.
fn exact_det_sign(m: Mat3) -> i64 {
    let (a, b, c) = (
        m.x_axis.to_array(),
        m.y_axis.to_array(),
        m.z_axis.to_array(),
    );
    let mut s = Fixed::zero();
    for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
        s.add(false, &[a[i], b[j], c[k]]);
        s.add(true, &[a[i], b[k], c[j]]);
    }
    s.sign()
}

/// The spacing of `f32` values at `|x|`, for `x` given in `f64`.
fn f32_spacing(x: f64) -> f64 {
    let e = ((x.abs().to_bits() >> 52) & 0x7ff) as i32 - 1023;
    2f64.powi(e.max(-126) - 23)
}

/// Asserts the promise of `normal_matrix`: exact sign, and each entry the exact scaled entry rounded
/// to nearest. The power of two is read off the largest entry, where the result has 24 bits.
fn check_normal_matrix(m: Mat3) -> Result<(), TestCaseError> {
    let nm = phong::normal_matrix(m);
    let cof = exact_cofactors(m);
    let sign = if exact_det_sign(m) < 0 { -1.0f32 } else { 1.0 };
    let got = [nm.x_axis, nm.y_axis, nm.z_axis].map(|c| c.to_array());
    let (mut big, mut at) = (0.0f64, (0, 0));
    for (j, col) in cof.iter().enumerate() {
        for (i, x) in col.iter().enumerate() {
            if x.to_f64().abs() > big {
                big = x.to_f64().abs();
                at = (j, i);
            }
        }
    }
    if big == 0.0 {
        prop_assert_eq!(nm, Mat3::ZERO, "zero cofactors for {}", m);
        return Ok(());
    }
    let ratio = got[at.0][at.1] as f64 / cof[at.0][at.1].to_f64();
    prop_assert!(
        ratio * sign as f64 > 0.0,
        "normal_matrix({m}) is flipped: exact det sign {sign}, got {nm}"
    );
    let k = ratio.abs().log2().round() as i64;
    for j in 0..3 {
        for i in 0..3 {
            let want = sign * cof[j][i].scaled_to_f32(k);
            prop_assert_eq!(
                got[j][i],
                want,
                "normal_matrix({}) column {} row {}: got {}, exact·2^{} rounds to {}",
                m,
                j,
                i,
                got[j][i],
                k,
                want
            );
        }
    }
    Ok(())
}

/// Asserts the promises of the triangle functions for one triangle.
fn check_triangle(p0: Vec3, p1: Vec3, p2: Vec3) -> Result<(), TestCaseError> {
    let exact = exact_area([p0, p1, p2]);
    let what = format!("P0 = {p0:?}, P1 = {p1:?}, P2 = {p2:?}");
    // The area vector: the exact one, rounded to nearest, saturated.
    let want = Vec3::from_array(exact.map(|x| x.to_f32().clamp(-f32::MAX, f32::MAX)));
    let got = phong::triangle_area_normal(p0, p1, p2);
    prop_assert_eq!(got, want, "area vector of {}", what);
    // The unit normal: None exactly for a zero area.
    let zero = exact.iter().all(|x| x.sign() == 0);
    let n = phong::try_triangle_normal(p0, p1, p2);
    prop_assert_eq!(n.is_none(), zero, "None iff zero area: {}", what);
    prop_assert_eq!(
        phong::triangle_normal_or_zero(p0, p1, p2),
        n.unwrap_or(Vec3::ZERO),
        "triangle_normal vs try_triangle_normal: {}",
        what
    );
    let Some(n) = n else { return Ok(()) };
    // Reference: the exact components rounded to f64 (relative error 2⁻⁵³ each), normalised in
    // f64 (a few more roundings): within about 2⁻⁵⁰·⁵ relative, 2⁻²⁶·⁵ ulp of f32. The promise is
    // 0.5 + 2⁻¹⁴ ulp; the reference's own error adds 2⁻²⁴ of slack.
    let a = DVec3::from_array(exact.map(|x| x.to_f64()));
    let r = a / a.length();
    for i in 0..3 {
        let (g, w) = (n[i] as f64, r[i]);
        let ulps = (g - w).abs() / f32_spacing(w);
        prop_assert!(
            ulps <= 0.5 + 2f64.powi(-14) + 2f64.powi(-24),
            "unit normal component {} off by {} ulp: got {}, exact {}: {}",
            i,
            ulps,
            g,
            w,
            what
        );
        // The exact sign; zero only where the exact component is zero or below f32's range.
        let s = exact[i].sign();
        let sign_ok = if g == 0.0 {
            s == 0 || w.abs() <= 2f64.powi(-149)
        } else {
            s != 0 && (g > 0.0) == (s > 0)
        };
        prop_assert!(
            sign_ok,
            "unit normal component {} has the wrong sign: got {}, exact sign {}: {}",
            i,
            g,
            s,
            what
        );
    }
    Ok(())
}

/// The exact sign of `a·b`.
fn exact_dot_sign(a: Vec3, b: Vec3) -> i64 {
    Fixed::sum(&[(1, &[a.x, b.x]), (1, &[a.y, b.y]), (1, &[a.z, b.z])]).sign()
}

// ---------------------------------------------------------------------------------------------
// Strategies

/// 2^e as an `f32` (through `f64`, so subnormal powers come out exact).
fn pow2(e: i32) -> f32 {
    2f64.powi(e) as f32
}

/// Any finite `f32`, its exponent uniform over the whole range (subnormals included), with zeros
/// and small integers mixed in.
fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => (any::<bool>(), 0u32..(1 << 23), 0u32..255).prop_map(|(s, m, e)| {
            f32::from_bits((s as u32) << 31 | e << 23 | m)
        }),
        1 => Just(0.0f32),
        1 => (-8i32..=8).prop_map(|i| i as f32),
    ]
}

fn wild_vec3() -> impl Strategy<Value = Vec3> {
    (wild(), wild(), wild()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// `±m · 2^e`: a full 24-bit significand at an exponent in `exps`.
fn scaled(exps: core::ops::Range<i32>) -> impl Strategy<Value = f32> {
    (any::<bool>(), (1u32 << 23)..(1 << 24), exps).prop_map(|(s, m, e)| {
        let x = m as f64 * 2f64.powi(e - 23);
        (if s { -x } else { x }) as f32
    })
}

/// A vector of `O(1)` components times `2^e` for one `e` in `exps`.
fn vec_at(exps: core::ops::Range<i32>) -> impl Strategy<Value = Vec3> {
    (scaled(-3..1), scaled(-3..1), scaled(-3..1), exps)
        .prop_map(|(x, y, z, e)| Vec3::new(x, y, z) * pow2(e))
}

/// An exactly singular matrix of small integers scaled by powers of two: column `dep` is an integer
/// combination of the other two, and rows and columns are then scaled by independent powers of two
/// (which keeps the determinant zero and every entry exact).
fn integer_singular_matrix() -> impl Strategy<Value = Mat3> {
    (
        prop::array::uniform6(-(1i32 << 20)..=(1 << 20)),
        (-7i32..=7, -7i32..=7),
        prop::array::uniform3(-20i32..=20),
        prop::array::uniform3(-20i32..=20),
        0usize..3,
    )
        .prop_map(|(ints, (alpha, beta), rows, cols, dep)| {
            let c0 = [ints[0], ints[1], ints[2]];
            let c1 = [ints[3], ints[4], ints[5]];
            // |c2| ≤ 14 · 2^20 < 2^24: exact in f32.
            let c2 = [0, 1, 2].map(|i| alpha * c0[i] + beta * c1[i]);
            let mut cs = [c0, c1, c2];
            cs.swap(2, dep);
            let entry = |j: usize, i: usize| cs[j][i] as f32 * pow2(rows[i] + cols[j]);
            Mat3::from_cols_array(&[
                entry(0, 0),
                entry(0, 1),
                entry(0, 2),
                entry(1, 0),
                entry(1, 1),
                entry(1, 2),
                entry(2, 0),
                entry(2, 1),
                entry(2, 2),
            ])
        })
}

/// Columns `a, b, 2^j·a` with arbitrary 24-bit entries, like the fuzzed case, in any order, and
/// transposed half the time (a dependent row instead).
fn scaled_column_matrix() -> impl Strategy<Value = Mat3> {
    (
        vec_at(-30..30),
        vec_at(-30..30),
        -10i32..=10,
        0usize..3,
        any::<bool>(),
    )
        .prop_map(|(a, b, j, dep, transpose)| {
            let mut cs = [a, b, a * pow2(j)];
            cs.swap(2, dep);
            let m = Mat3::from_cols(cs[0], cs[1], cs[2]);
            if transpose { m.transpose() } else { m }
        })
}

/// An exactly singular matrix.
fn singular_matrix() -> impl Strategy<Value = Mat3> {
    prop_oneof![integer_singular_matrix(), scaled_column_matrix()]
}

/// A matrix one ulp away from singular: one entry of a singular matrix moved to a neighbour.
fn nearly_singular_matrix() -> impl Strategy<Value = Mat3> {
    (singular_matrix(), 0usize..9, any::<bool>()).prop_map(|(m, at, up)| {
        let mut e = m.to_cols_array();
        e[at] = if up {
            e[at].next_up()
        } else {
            e[at].next_down()
        };
        Mat3::from_cols_array(&e)
    })
}

// ---------------------------------------------------------------------------------------------
// normal_matrix

#[test]
fn normal_matrix_of_the_fuzzed_singular_matrix_is_not_flipped() {
    // The third column is twice the first: det M = 0 exactly, so sign(0) = +1. From rounded
    // cofactors the determinant came out −8.9e-16 and the whole matrix flipped.
    let m = Mat3::from_cols(
        Vec3::new(3.550105, 0.7529144, 0.15172768),
        Vec3::new(8.9, 0.0, 2.0),
        Vec3::new(7.10021, 1.5058289, 0.30345535),
    );
    assert_eq!(exact_det_sign(m), 0, "setup: exactly singular");
    check_normal_matrix(m).unwrap();
    let n = phong::transform_normal(phong::normal_matrix(m), Vec3::Z);
    // +cof(M)·Z = a × b, normalised: (0.168, −0.642, −0.748).
    let want = m.x_axis.as_dvec3().cross(m.y_axis.as_dvec3()).normalize();
    assert!(
        (n.as_dvec3() - want).length() < 1e-6,
        "transform_normal(Z) = {n}, want {want}"
    );
    assert!(n.x > 0.0 && n.y < 0.0 && n.z < 0.0, "{n}");
}

#[test]
fn normal_matrix_of_a_nearly_singular_matrix_has_the_exact_sign() {
    // Exact det −2e-9 (f32 1e19 and 2e-28 are not exact, so "about"); plain f64 evaluation got 0.
    let m = Mat3::from_cols(
        Vec3::new(-1e19, 0.0, 1e19),
        Vec3::new(0.0, 1.0, 2e-28),
        Vec3::new(-0.5, -1.0, 0.5),
    );
    assert_eq!(exact_det_sign(m), -1, "setup: det < 0");
    check_normal_matrix(m).unwrap();
    // det < 0: the normal matrix is −cof(M), so X goes to −(b × c) = −(0.5, −1e-28, 0.5) direction.
    let n = phong::transform_normal(phong::normal_matrix(m), Vec3::X);
    let want = -Vec3::new(1.0, 0.0, 1.0).normalize();
    assert!((n - want).length() < 1e-6, "transform_normal(X) = {n}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn normal_matrix_of_singular_matrices_is_exact(m in singular_matrix()) {
        prop_assert_eq!(exact_det_sign(m), 0, "setup: singular {}", m);
        check_normal_matrix(m)?;
    }

    #[test]
    fn normal_matrix_one_ulp_from_singular_is_exact(m in nearly_singular_matrix()) {
        check_normal_matrix(m)?;
    }

    #[test]
    fn normal_matrix_of_entries_over_the_whole_range_is_exact(e in prop::array::uniform9(wild())) {
        check_normal_matrix(Mat3::from_cols_array(&e))?;
    }
}

// ---------------------------------------------------------------------------------------------
// Triangles

#[test]
fn triangle_reproducers_are_exact() {
    let v = Vec3::new;
    let cases = [
        // The exact A is (0, 0, +3e-18); edges rounded in f64 gave −1.39e-17: the wrong side.
        (v(-0.5, -0.2, 0.0), v(0.0, 0.0, 0.0), v(6e-17, 3e-17, 0.0)),
        // Exact A_z = −8.56e-21; f64 edges gave 0.
        (
            v(-2.5680957, 4.16813, 0.0),
            v(0.0, 5e-21, 0.0),
            v(-0.8560319, 1.3893766, 0.0),
        ),
        // Exact A = (1, 0, 0); f64 edges gave None.
        (v(0.0, 1.0, 1e25), v(0.0, 0.0, 1.0), v(0.0, 0.0, 0.0)),
        // A sliver whose f64 direction was off by 1e-5.
        (
            v(-1.2054324, 3.9623203, -0.3220172),
            v(1.2054324, -3.9623203, 0.3220172),
            v(0.0, 0.0, 9e-13),
        ),
    ];
    for (a, b, c) in cases {
        check_triangle(a, b, c).unwrap();
        check_triangle(b, c, a).unwrap();
        check_triangle(a, c, b).unwrap();
    }
    let z = phong::triangle_area_normal(cases[0].0, cases[0].1, cases[0].2).z;
    assert!(z > 0.0 && (z / 3e-18 - 1.0).abs() < 1e-6, "A_z = {z:e}");
    let z = phong::triangle_area_normal(cases[1].0, cases[1].1, cases[1].2).z;
    assert!(z < 0.0 && (z / -8.56e-21 - 1.0).abs() < 1e-3, "A_z = {z:e}");
    assert_eq!(
        phong::try_triangle_normal(cases[2].0, cases[2].1, cases[2].2),
        Some(Vec3::X)
    );
}

#[test]
fn area_vector_ties_are_broken_by_the_exact_value() {
    // A_z = x1·y2 − y1·x2 + y0·(x2 − x1) with x0 = 0:
    //     = (1 + 2⁻²⁴ − 2⁻⁴⁷) + 2⁻⁴⁷ ∓ 2⁻⁸⁰·2⁻²³ = 1 + 2⁻²⁴ ± 2⁻¹⁰³,
    // just off the midpoint between 1 and 1 + 2⁻²³, by far less than an f64 ulp.
    let (x1, y2) = (1.0f32.next_up(), 1.0 - pow2(-24));
    let (y1, x2) = (-pow2(-47), 1.0);
    for (y0, want) in [(-pow2(-80), 1.0f32.next_up()), (pow2(-80), 1.0), (0.0, 1.0)] {
        let p = [
            Vec3::new(0.0, y0, 0.0),
            Vec3::new(x1, y1, 0.0),
            Vec3::new(x2, y2, 0.0),
        ];
        check_triangle(p[0], p[1], p[2]).unwrap();
        let z = phong::triangle_area_normal(p[0], p[1], p[2]).z;
        assert_eq!(z, want, "y0 = {y0:e}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn triangles_over_the_whole_range_are_exact(p in prop::array::uniform3(wild_vec3())) {
        check_triangle(p[0], p[1], p[2])?;
    }

    #[test]
    fn triangles_with_vertices_of_different_magnitudes_are_exact(
        p in prop::array::uniform3(vec_at(-100..60)),
    ) {
        check_triangle(p[0], p[1], p[2])?;
    }

    #[test]
    fn slivers_are_exact(
        p0 in vec_at(-10..10),
        p1 in vec_at(-10..10),
        t in 0.0f32..1.0,
        dir in unit_vec3(),
        h in -140i32..0,
    ) {
        // A point on the segment P0P1 (rounded to f32), pushed off it by 2^h.
        let p2 = p0 + t * (p1 - p0) + dir * pow2(h);
        check_triangle(p0, p1, p2)?;
        check_triangle(p2, p0, p1)?;
    }

    #[test]
    fn exactly_collinear_triangles_have_no_normal(
        q in vec_at(-60..60),
        k in prop::array::uniform3(-20i32..20),
        (y, z) in (wild(), wild()),
        xs in prop::array::uniform3(wild()),
    ) {
        // Points 2^k·Q on a line through the origin, and points on a line parallel to the x axis.
        let on_ray = k.map(|k| q * pow2(k));
        check_triangle(on_ray[0], on_ray[1], on_ray[2])?;
        prop_assert_eq!(phong::try_triangle_normal(on_ray[0], on_ray[1], on_ray[2]), None);
        let on_line = xs.map(|x| Vec3::new(x, y, z));
        check_triangle(on_line[0], on_line[1], on_line[2])?;
        prop_assert_eq!(
            phong::triangle_area_normal(on_line[0], on_line[1], on_line[2]),
            Vec3::ZERO
        );
    }
}

// ---------------------------------------------------------------------------------------------
// reflect

#[test]
fn reflect_of_a_huge_l_is_finite() {
    // 2(N·L) = 6e38 overflows f32; R = L exactly (L is along N).
    let r = phong::reflect(Vec3::X, Vec3::new(3e38, 0.0, 0.0));
    assert_eq!(r, Vec3::new(3e38, 0.0, 0.0));
    // N at 45° in the xy plane, L = (MAX, MAX, MAX): R ≈ (MAX, MAX, −MAX), where the x and y
    // components sit at the edge of the range (saturated or just below), and R_z = −L_z exactly.
    let n = Vec3::new(1.0, 1.0, 0.0).normalize();
    let r = phong::reflect(n, Vec3::new(f32::MAX, f32::MAX, f32::MAX));
    assert!(r.is_finite(), "{r}");
    assert_eq!(r.z, -f32::MAX, "the z component is −L_z: {r}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5000))]

    #[test]
    fn reflect_is_finite_and_accurate_for_every_finite_l(n in unit_vec3(), l in wild_vec3()) {
        let r = phong::reflect(n, l);
        prop_assert!(r.is_finite(), "reflect({}, {}) = {}", n, l, r);
        // Reference: R in f64 from the same f32 N and L (products exact, a few roundings of 2⁻⁵³),
        // saturated like the crate. The f32 path errs by at most 9U·‖L‖ per component for
        // ‖N‖ ≈ 1 (tests/properties.rs derives it; U = 2⁻²⁴), the f64 path by one final rounding.
        // Underflow adds at most a few units of 2⁻¹⁴⁹. Bound: 10U‖L‖ + 2⁻¹⁴⁵.
        let (nd, ld) = (n.as_dvec3(), l.as_dvec3());
        let want = (2.0 * nd.dot(ld) * nd - ld).clamp(DVec3::splat(-f32::MAX as f64), DVec3::splat(f32::MAX as f64));
        let tol = 10.0 * 2f64.powi(-24) * ld.length() + 2f64.powi(-145);
        let err = (r.as_dvec3() - want).abs().max_element();
        prop_assert!(err <= tol, "reflect({}, {}) = {}, want {}: error {:e} > {:e}", n, l, r, want, err, tol);
    }
}

// ---------------------------------------------------------------------------------------------
// face_forward

#[test]
fn face_forward_decides_overflowing_dot_products() {
    // Nref·V = 2.7e63 − 2.4e57 > 0; the f32 dot product is NaN (∞ − ∞ would not even arise: the
    // first product alone overflows).
    let (v, n_ref) = (Vec3::new(-3e38, 0.0, 6e32), Vec3::new(-9e24, 0.0, -4e24));
    assert_eq!(exact_dot_sign(n_ref, v), 1);
    assert_eq!(phong::face_forward(Vec3::Z, v, n_ref), Vec3::Z);
    // Underflow: 1e-30 · 1e-30 is zero in f32, positive exactly.
    let tiny = Vec3::Z * 1e-30;
    assert_eq!(phong::face_forward(Vec3::Z, tiny, tiny), Vec3::Z);
    // An exact tie (a·b − b·a) goes to −N, however large the terms.
    let (a, b) = (3e38f32, -7e37f32);
    let tie = phong::face_forward(Vec3::Z, Vec3::new(b, -a, 1.0), Vec3::new(a, b, 0.0));
    assert_eq!(tie, -Vec3::Z);
}

fn expected_face_forward(n: Vec3, v: Vec3, n_ref: Vec3) -> Vec3 {
    if exact_dot_sign(n_ref, v) > 0 { n } else { -n }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5000))]

    #[test]
    fn face_forward_uses_the_exact_sign(v in wild_vec3(), n_ref in wild_vec3()) {
        let n = Vec3::new(0.6, 0.0, 0.8);
        prop_assert_eq!(phong::face_forward(n, v, n_ref), expected_face_forward(n, v, n_ref), "V = {}, Nref = {}", v, n_ref);
    }

    #[test]
    fn face_forward_near_the_tie_uses_the_exact_sign(
        (a, b) in (scaled(-60..60), scaled(-60..60)),
        (c, w) in (wild(), wild()),
        j in -40i32..40,
        order in 0usize..3,
        nudge in 0usize..4,
    ) {
        // Nref = (a, c, b), V = (2^j·b, w, −2^j·a): two products that cancel exactly around a third,
        // c·w, of any size, which a rounded sum of the three loses. Then the coordinates are
        // rotated (so the small product sits at any position), and one component of V may be
        // moved by one ulp, leaving an exact dot product far below its terms.
        let s = pow2(j);
        let mut n_ref = [a, c, b];
        let mut v = [b * s, w, -a * s];
        n_ref.rotate_left(order);
        v.rotate_left(order);
        if nudge < 3 {
            v[nudge] = if j % 2 == 0 { v[nudge].next_up() } else { v[nudge].next_down() };
        }
        let (n_ref, v) = (Vec3::from_array(n_ref), Vec3::from_array(v));
        let n = Vec3::Y;
        prop_assert_eq!(
            phong::face_forward(n, v, n_ref),
            expected_face_forward(n, v, n_ref),
            "V = {}, Nref = {}", v, n_ref
        );
    }
}

#[test]
fn the_reference_is_exact() {
    // (2^24 − 1)² − (2^24 − 1)(2^24 − 2) = 2^24 − 1 in integers, far below the products.
    let (a, b) = (16_777_215.0f32, 16_777_214.0f32);
    let s = Fixed::sum(&[(1, &[a, a]), (-1, &[a, b])]);
    assert_eq!(s.to_f64(), 16_777_215.0);
    // 1 + 2^-24 (a tie between two f32) plus or minus 2^-60 rounds away from or onto 1.
    let one_tie = |sign: i32| {
        Fixed::sum(&[
            (1, &[1.0]),
            (1, &[pow2(-24)]),
            (sign, &[pow2(-30), pow2(-30)]),
        ])
        .to_f32()
    };
    assert_eq!(one_tie(1), 1.0f32.next_up());
    assert_eq!(one_tie(-1), 1.0);
    assert_eq!(Fixed::sum(&[(1, &[1.0]), (1, &[pow2(-24)])]).to_f32(), 1.0);
    // Subnormals and the top of the range.
    assert_eq!(
        Fixed::sum(&[(1, &[f32::from_bits(1)])]).to_f32(),
        f32::from_bits(1)
    );
    assert_eq!(
        Fixed::sum(&[(-1, &[f32::MAX, 2.0])]).to_f32(),
        f32::NEG_INFINITY
    );
    assert_eq!(exact_det_sign(Mat3::IDENTITY), 1);
    assert_eq!(exact_det_sign(-Mat3::IDENTITY), -1);
}
