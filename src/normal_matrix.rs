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
/// **Domain:** any finite `Mat3`; for a 4×4 model matrix pass `Mat3::from_mat4(model)`. The result
/// is *not* normalised: transform a normal with it, then renormalise, or use
/// [`transform_normal`]. It works for rotations, non-uniform scale, shear and mirroring.
///
/// **Degenerate input:** for a singular `M` (e.g. a scale of 0 along one axis, which flattens the
/// object) the cofactor matrix still maps normals to the normals of the flattened surface, and to
/// zero where no normal exists. Scale: entries are products of two entries of `M`, so matrices
/// whose entries are all beyond about 1e19 overflow, and those whose entries are all below about
/// 1e-19 underflow to zero (then [`transform_normal`] returns the zero vector). Scale such a
/// matrix by a power of two first: the normal matrix of `c·M` is `c²` times that of `M`, the same
/// directions.
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
#[inline]
pub fn normal_matrix(m: Mat3) -> Mat3 {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    let cof = Mat3::from_cols(b.cross(c), c.cross(a), a.cross(b));
    // det M = a · (b × c)
    if a.dot(cof.x_axis) < 0.0 { -cof } else { cof }
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
