//! The normal of a triangle, computed so that sliver triangles keep their digits.
//!
//! The naive `f32` cross product `(P1−P0)×(P2−P0)` subtracts nearly equal products when the two
//! edges are almost parallel (a sliver), and cancellation then leaves only a few correct bits. Here
//! the vertices are widened to `f64` first. The edge differences of `f32` inputs are then exact
//! (their exponents differ by far less than 29), each product of two such edges is exact in `f64`'s
//! 53-bit significand, and the cross product carries one rounding per component. The result is the
//! exact normal of the given `f32` vertices, rounded once to `f32`. docs/accuracy.md has the measured
//! error against the naive form on an adversarial sliver set; derivations are in
//! [docs/derivations.md](https://example.invalid/phong/docs/derivations.md#triangle-normal-and-area).

use glam::Vec3;

use crate::math;

/// An `f64` vector, just for this file (glam's `DVec3` would need its `f64` feature).
type D3 = [f64; 3];

#[inline]
fn widen_sub(p: Vec3, origin: Vec3) -> D3 {
    [
        p.x as f64 - origin.x as f64,
        p.y as f64 - origin.y as f64,
        p.z as f64 - origin.z as f64,
    ]
}

/// The doubled area vector in `f64`: `(P1 − P0) × (P2 − P0)`, exact up to one rounding per component.
#[inline]
fn area_normal_f64(p0: Vec3, p1: Vec3, p2: Vec3) -> D3 {
    let (e1, e2) = (widen_sub(p1, p0), widen_sub(p2, p0));
    [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ]
}

/// Narrows to `f32`, saturating components beyond `f32::MAX` (possible only for huge triangles).
#[inline]
fn narrow_saturating(v: D3) -> Vec3 {
    let m = f32::MAX as f64;
    let c = v.map(|x| x.clamp(-m, m) as f32);
    Vec3::from_array(c)
}

/// The area-weighted normal of triangle `P0 P1 P2`: its length is twice the area.
///
/// ```text
/// A = (P1 − P0) × (P2 − P0),     ‖A‖ = 2 · area,    direction: right-hand rule on P0 → P1 → P2
/// ```
///
/// **Domain:** any finite points; counter-clockwise winding (seen from the side the normal points to)
/// gives the outward normal. Computed in `f64` from the `f32` vertices, so sliver triangles keep
/// full accuracy: the result is the exact area vector of the given vertices, rounded once.
///
/// **Degenerate input:** a zero-area triangle (repeated or collinear vertices) gives the zero vector.
/// Components whose true value exceeds `f32::MAX` (vertices beyond about 1e19 apart) saturate to
/// `±f32::MAX`. Non-finite vertices give a non-finite result; use finite input.
///
/// This is the form to sum for area-weighted vertex normals ([`vertex_normals`](crate::vertex_normals)).
///
/// ```
/// use glam::Vec3;
/// let a = phong::triangle_area_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(a, Vec3::Z); // the unit right triangle: area 1/2, so ‖A‖ = 1
/// ```
#[must_use]
#[inline]
pub fn triangle_area_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    narrow_saturating(area_normal_f64(p0, p1, p2))
}

/// The unit normal of triangle `P0 P1 P2`, or `None` for a zero-area triangle.
///
/// ```text
/// N = A / ‖A‖,   A = (P1 − P0) × (P2 − P0)
/// ```
///
/// **Domain:** finite points. Accurate to about 1 ulp per component even for slivers with aspect
/// ratio 1e-5 placed 1e5 from the origin (measured in docs/accuracy.md), because the cross product
/// and the normalisation are done in `f64`.
///
/// **Degenerate input:** `None` when the vertices are collinear or repeated *exactly* (as `f32`
/// values), or when a vertex is not finite.
///
/// ```
/// use glam::Vec3;
/// let n = phong::try_triangle_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(n, Some(Vec3::Z));
/// assert_eq!(phong::try_triangle_normal(Vec3::ZERO, Vec3::X, 2.0 * Vec3::X), None);
/// ```
#[must_use]
#[inline]
pub fn try_triangle_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Option<Vec3> {
    let a = area_normal_f64(p0, p1, p2);
    let l2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    // f64 covers every product of two f32 edges: the squared length cannot overflow or underflow
    // to zero unless the area is exactly zero (or the input is not finite).
    if !(l2 > 0.0 && l2.is_finite()) {
        return None;
    }
    let inv = 1.0 / math::sqrt_f64(l2);
    Some(Vec3::from_array(a.map(|x| (x * inv) as f32)))
}

/// The unit normal of triangle `P0 P1 P2`, or the zero vector for a zero-area triangle.
///
/// ```text
/// N = (P1 − P0) × (P2 − P0) / ‖(P1 − P0) × (P2 − P0)‖
/// ```
///
/// The same as [`try_triangle_normal`] with `None` mapped to `Vec3::ZERO`, which the shading
/// functions treat as "no normal": such a point receives only ambient and emission.
///
/// GLSL's `normalize(cross(p1 − p0, p2 − p0))` computes the same formula in `f32`; it agrees with
/// this function to within its own cancellation error (see the conformance tests).
///
/// ```
/// use glam::Vec3;
/// // A needle 1e5 from the origin: naive f32 arithmetic loses most digits here.
/// let o = Vec3::splat(1e5);
/// let n = phong::triangle_normal(o, o + Vec3::new(1.0, 0.0, 0.0), o + Vec3::new(1.0, 1e-2, 0.0));
/// assert!((n - Vec3::Z).length() < 1e-6);
/// assert_eq!(phong::triangle_normal(o, o, o), Vec3::ZERO);
/// ```
#[must_use]
#[inline]
pub fn triangle_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    try_triangle_normal(p0, p1, p2).unwrap_or(Vec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn winding_flips_and_area_is_half_length() {
        let (a, b, c) = (
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(4.0, 0.0, 1.0),
            Vec3::new(-1.0, 5.0, 2.0),
        );
        assert_eq!(
            triangle_area_normal(a, b, c),
            -triangle_area_normal(a, c, b)
        );
        // Heron-free check: |AB × AC| computed by hand = |(−4,-11,17)|... use glam as the ruler.
        let expect = (b - a).cross(c - a);
        assert!((triangle_area_normal(a, b, c) - expect).length() < 1e-5);
    }

    #[test]
    fn huge_triangles_saturate_instead_of_overflowing() {
        let m = 1e30;
        let a = triangle_area_normal(Vec3::ZERO, Vec3::new(m, 0.0, 0.0), Vec3::new(0.0, m, 0.0));
        assert_eq!(a, Vec3::new(0.0, 0.0, f32::MAX));
        assert_eq!(
            triangle_normal(Vec3::ZERO, Vec3::new(m, 0.0, 0.0), Vec3::new(0.0, m, 0.0)),
            Vec3::Z
        );
    }
}
