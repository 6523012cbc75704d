//! The matrix that carries normals through a model transform.

use glam::{Mat3, Vec3};

use crate::expansion::{Approx, Expansion, product3, two_sum};
use crate::normalize_or_zero;

/// The normal matrix of a linear map `M`: its cofactor matrix with the sign of `det M`.
///
/// ```text
/// normal_matrix(M) = sign(det M) · cof(M),      cof(M) = det(M) · M⁻ᵀ = [ b×c  c×a  a×b ]
/// ```
///
/// where `a`, `b`, `c` are the columns of `M` and `sign(0) = +1`. Tangents transform by `M`; normals
/// must transform by `M⁻ᵀ` (up to scale) to stay perpendicular to them. The cofactor form needs no
/// inverse, so it stays defined when `M` is singular, and the sign factor makes a mirroring transform
/// (`det M < 0`) give the same direction as the inverse transpose, `|det M| · M⁻ᵀ`.
///
/// **Accuracy:** `sign(det M)` is the exact sign of the determinant of the given `f32` entries, for
/// every finite `M`: an exactly singular `M` gets `+1`, and a nearly singular one the right sign
/// however close it is (a wrong sign would flip every normal). It is decided from an `f64`
/// estimate with a rigorous error bound, and by exact expansion arithmetic (Shewchuk 1997) when the
/// estimate is too close to zero to tell. Each entry of the result is the exact entry of
/// `sign(det M) · cof(M)` (times the power of two below, if any) rounded to the nearest `f32`.
///
/// **Domain:** any finite `Mat3`; for a 4×4 model matrix pass `Mat3::from_mat4(model)`. The result
/// is *not* normalised: transform a normal with it, then renormalise, or use
/// [`transform_normal`]. It works for rotations, non-uniform scale, shear and mirroring.
///
/// **Degenerate input:** for a singular `M` (e.g. a scale of 0 along one axis, which flattens the
/// object) the cofactor matrix still maps normals to the normals of the flattened surface, and to
/// zero where no normal exists. **Scale:** when the exact cofactor matrix would overflow `f32`
/// (entries beyond about 1e19) or underflow it (entries all below about 1e-19), the result is that
/// matrix times a power of two chosen to bring its largest entry near 1: the same normal
/// directions, always finite.
///
/// Derivation: docs/derivations.md, section "The normal matrix".
///
/// ```
/// use glam::{Mat3, Vec3};
/// // Non-uniform scale: a 45° normal must tilt toward the squashed axis.
/// let m = Mat3::from_diagonal(Vec3::new(2.0, 1.0, 1.0));
/// let n = phong::transform_normal(phong::normal_matrix(m), Vec3::new(1.0, 1.0, 0.0));
/// let t = m * Vec3::new(1.0, -1.0, 0.0); // a tangent, carried by M
/// assert!(n.dot(t).abs() < 1e-6);
/// // Mirroring keeps the inverse-transpose direction.
/// let mirror = Mat3::from_diagonal(Vec3::new(-1.0, 1.0, 1.0));
/// assert_eq!(phong::normal_matrix(mirror) * Vec3::X, mirror.inverse().transpose() * Vec3::X);
/// // Exactly singular (the third column is twice the first): sign(0) = +1, never a flip.
/// let a = Vec3::new(3.550105, 0.7529144, 0.15172768);
/// let flat = Mat3::from_cols(a, Vec3::new(8.9, 0.0, 2.0), 2.0 * a);
/// assert_eq!(phong::normal_matrix(flat) * Vec3::Z, flat.x_axis.cross(flat.y_axis));
/// ```
#[must_use]
pub fn normal_matrix(m: Mat3) -> Mat3 {
    let (a, b, c) = (
        m.x_axis.to_array(),
        m.y_axis.to_array(),
        m.z_axis.to_array(),
    );
    let cols = [cross(b, c), cross(c, a), cross(a, b)];
    let sign = det_sign(a, b, c, &cols[0]);
    let largest = cols
        .iter()
        .flatten()
        .fold(0.0f64, |acc, x| acc.max(x.top.abs()));
    // Inside [2^-100, 2^100] every entry that matters fits f32 as it is; outside, rescale by a
    // power of two (exact) so the largest entry is about 1.
    let scale = if largest > 0.0 && largest.is_finite() && !(1e-30..=1e30).contains(&largest) {
        // 2^-e from the exponent field (no log2/powi: they need std). Products of f32 entries
        // lie in about [1e-90, 1e77], far inside f64's normal range, so e ∈ [-300, 300].
        let e = ((largest.to_bits() >> 52) & 0x7ff) as i64 - 1023;
        f64::from_bits(((1023 - e) as u64) << 52)
    } else {
        1.0
    };
    // ±2^k is exact on both parts (they stay far inside f64's normal range), so each entry is
    // still the exact value, rounded to f32 once.
    let k = sign * scale;
    let f = |col: [Approx; 3]| {
        Vec3::from_array(col.map(|x| {
            Approx {
                top: x.top * k,
                below: x.below * k,
            }
            .round_to_f32()
        }))
    };
    Mat3::from_cols(f(cols[0]), f(cols[1]), f(cols[2]))
}

/// `p × q` of `f32` vectors, each component kept exactly as `s + e`: its two products are exact in
/// `f64`, and TwoSum keeps the rounding error of their difference.
#[inline]
fn cross(p: [f32; 3], q: [f32; 3]) -> [Approx; 3] {
    let d = |i: usize, j: usize| {
        let (s, e) = two_sum(p[i] as f64 * q[j] as f64, -(p[j] as f64 * q[i] as f64));
        Approx { top: s, below: e }
    };
    [d(1, 2), d(2, 0), d(0, 1)]
}

/// The exact sign of `det M = a · (b × c)` with `sign(0) = +1`, given `b × c`.
#[inline]
fn det_sign(a: [f32; 3], b: [f32; 3], c: [f32; 3], bxc: &[Approx; 3]) -> f64 {
    let w = |x: f32| x as f64;
    let det = w(a[0]) * bxc[0].top + w(a[1]) * bxc[1].top + w(a[2]) * bxc[2].top;
    // Error bound: each cofactor is one rounding of an exact difference (≤ ε·(|p| + |q|)), then one
    // product and two sums, so |det − exact| ≤ 4ε·perm + O(ε²) with ε = 2⁻⁵³ and perm the
    // determinant with every term made positive. 8ε = 2⁻⁵⁰ also covers the rounding of perm.
    let pq = |i: usize, j: usize, k: usize| {
        w(a[i]).abs() * ((w(b[j]) * w(c[k])).abs() + (w(b[k]) * w(c[j])).abs())
    };
    let perm = pq(0, 1, 2) + pq(1, 2, 0) + pq(2, 0, 1);
    let bound = perm * DET_ERR;
    if det > bound {
        1.0
    } else if det < -bound {
        -1.0
    } else {
        exact_det_sign(a, b, c)
    }
}

/// 2⁻⁵⁰: the relative error bound of the `f64` determinant estimate (see [`det_sign`]).
const DET_ERR: f64 = 1.0 / 1_125_899_906_842_624.0;

/// The sign of `det M` by exact expansion arithmetic, for estimates too close to zero to tell.
#[cold]
#[inline(never)]
fn exact_det_sign(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> f64 {
    let plus = |i: usize, j: usize, k: usize| product3(a[i], b[j], c[k]);
    let minus = |i: usize, j: usize, k: usize| product3(a[i], b[j], c[k]).map(|x| -x);
    let [t0, t1] = plus(0, 1, 2);
    let [t2, t3] = minus(0, 2, 1);
    let [t4, t5] = plus(1, 2, 0);
    let [t6, t7] = minus(1, 0, 2);
    let [t8, t9] = plus(2, 0, 1);
    let [t10, t11] = minus(2, 1, 0);
    let det = Expansion::sum([t0, t1, t2, t3, t4, t5, t6, t7, t8, t9, t10, t11]);
    if det.sign() < 0.0 { -1.0 } else { 1.0 }
}

/// A normal carried through a normal matrix and renormalised: `normalize(NM · n)`.
///
/// ```text
/// transform_normal(NM, n) = NM·n / ‖NM·n‖
/// ```
///
/// **Domain:** `normal_matrix` from [`normal_matrix`]; `n` any vector. **Degenerate input:** the zero
/// vector when `NM·n` is zero (a singular transform that collapses this normal) or not finite.
///
/// ```
/// use glam::{Mat3, Vec3};
/// let nm = phong::normal_matrix(Mat3::from_rotation_z(1.0));
/// let n = phong::transform_normal(nm, Vec3::X);
/// assert!((n - Mat3::from_rotation_z(1.0) * Vec3::X).length() < 1e-6);
/// ```
#[must_use]
#[inline]
pub fn transform_normal(normal_matrix: Mat3, n: Vec3) -> Vec3 {
    normalize_or_zero(normal_matrix * n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn singular_flattening_keeps_the_flat_normal() {
        let flat = Mat3::from_diagonal(Vec3::new(1.0, 1.0, 0.0));
        let nm = normal_matrix(flat);
        assert_eq!(transform_normal(nm, Vec3::new(0.3, 0.2, 0.9)), Vec3::Z);
        assert_eq!(transform_normal(nm, Vec3::X), Vec3::ZERO);
    }

    #[test]
    fn nearly_singular_sign_comes_from_the_exact_determinant() {
        // f32 evaluates this determinant as +9.3e-10; the exact value is −2.76e-11.
        let m = Mat3::from_cols(
            Vec3::new(1.5689448, 3.7082431, 2.1678677),
            Vec3::new(657.62506, -215.00084, -693.1232),
            Vec3::new(-2.2198046e-6, -3.0442056e-6, -1.0733529e-6),
        );
        let nm = normal_matrix(m);
        let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
        // sign(det)·cof(M)·x must point like −(b×c) here, because det < 0.
        let naive_cof_x = b.cross(c);
        assert!((nm * Vec3::X).dot(naive_cof_x) < 0.0, "flipped: {nm}");
        let _ = a;
    }

    #[test]
    fn extreme_scales_stay_finite_and_keep_directions() {
        for s in [1e-30f32, 1e-20, 1e20, 1e30, 1e38] {
            let m = Mat3::from_diagonal(Vec3::new(2.0 * s, s, s));
            let n = transform_normal(normal_matrix(m), Vec3::new(1.0, 1.0, 0.0));
            let want = Vec3::new(1.0, 2.0, 0.0).normalize();
            assert!((n - want).length() < 1e-6, "scale {s}: {n}");
        }
    }

    #[test]
    fn matches_inverse_transpose_direction() {
        let m = Mat3::from_cols(
            Vec3::new(1.0, 0.5, 0.0),
            Vec3::new(0.0, -2.0, 0.3),
            Vec3::new(0.2, 0.0, 3.0),
        );
        let it = m.inverse().transpose();
        for n in [Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE] {
            let a = transform_normal(normal_matrix(m), n);
            let b = (it * n).normalize();
            assert!((a - b).length() < 1e-5, "{a} vs {b}");
        }
    }
}
