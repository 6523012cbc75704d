//! The matrix that carries normals through a model transform.

use glam::{Mat3, Vec3};

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
/// **Accuracy:** the cofactors and the determinant are computed in `f64` from the `f32` entries
/// (each product of two entries is exact there), so the result is the exact matrix rounded once,
/// and the sign of a nearly singular `M`'s determinant is right even where an `f32` determinant
/// gets it wrong (which would flip every normal).
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
/// Derivation: [docs/derivations.md](https://example.invalid/phong/docs/derivations.md#the-normal-matrix).
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
/// ```
#[must_use]
pub fn normal_matrix(m: Mat3) -> Mat3 {
    let w = |v: Vec3| [v.x as f64, v.y as f64, v.z as f64];
    let (a, b, c) = (w(m.x_axis), w(m.y_axis), w(m.z_axis));
    let cross = |p: [f64; 3], q: [f64; 3]| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let cols = [cross(b, c), cross(c, a), cross(a, b)];
    // det M = a · (b × c), from the f64 cofactors.
    let det = a[0] * cols[0][0] + a[1] * cols[0][1] + a[2] * cols[0][2];
    let sign = if det < 0.0 { -1.0 } else { 1.0 };
    let largest = cols
        .iter()
        .flatten()
        .fold(0.0f64, |acc, x| acc.max(x.abs()));
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
    let f = |col: [f64; 3]| {
        Vec3::new(
            (col[0] * sign * scale) as f32,
            (col[1] * sign * scale) as f32,
            (col[2] * sign * scale) as f32,
        )
    };
    Mat3::from_cols(f(cols[0]), f(cols[1]), f(cols[2]))
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
