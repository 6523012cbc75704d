//! The normal of a triangle, computed so that sliver triangles keep their digits.
//!
//! The naive `f32` cross product `(P1−P0)×(P2−P0)` subtracts nearly equal products when the two
//! edges are almost parallel (a sliver), and cancellation then leaves only a few correct bits.
//! Widening to `f64` first helps only while the edge differences are exact, that is while the
//! coordinates of the vertices lie within about 2²⁹ of each other. Here each component of the area
//! vector is the 2×2 determinant of one coordinate-plane projection of the triangle (Shewchuk's
//! `orient2d`): an `f64` estimate with a rigorous error bound decides the common case, and exact
//! expansion arithmetic (Shewchuk 1997) the rest, so the result is exact for every finite input:
//! the exact area vector of the given `f32` vertices, rounded once. docs/accuracy.md has the
//! measured error against the naive form on an adversarial sliver set; the derivation is in
//! docs/derivations.md, section "Triangle normal and area".

use glam::Vec3;

use crate::expansion::{Approx, Expansion};
use crate::math;

/// One component of the area vector: the triangle projected on a coordinate plane `(u, v)`.
///
/// `A_x` is the projection on `(y, z)`, `A_y` on `(z, x)`, `A_z` on `(x, y)`, each the determinant
///
/// ```text
/// (u1 − u0)(v2 − v0) − (v1 − v0)(u2 − u0)  =  u0·v1 − v0·u1 + u1·v2 − v1·u2 + u2·v0 − v2·u0
/// ```
#[derive(Clone, Copy)]
struct Projection {
    u: [f32; 3],
    v: [f32; 3],
}

/// 2⁻⁵⁰ = 8ε (ε = 2⁻⁵³): bounds the error of [`Projection::estimate`] relative to `|l| + |r|`.
const EST_ERR: f64 = 1.0 / 1_125_899_906_842_624.0;

/// 2⁻⁴⁰: the relative error [`Projection::to_f64`] accepts from the estimate.
const UNIT_REL: f64 = 1.0 / 1_099_511_627_776.0;

impl Projection {
    #[inline]
    fn of(p: [Vec3; 3], u: usize, v: usize) -> Self {
        Projection {
            u: p.map(|q| q.to_array()[u]),
            v: p.map(|q| q.to_array()[v]),
        }
    }

    /// The determinant from `f64` edges, with a bound on its error.
    ///
    /// The edge differences and the two products each round once (relative error ≤ ε = 2⁻⁵³), so
    /// each computed product is within (3ε + O(ε²)) of itself of the exact one, and the final
    /// difference rounds once more: `|d − exact| ≤ (4ε + O(ε²))(|l| + |r|)`, with `l`, `r` the
    /// computed products (Shewchuk's `orient2d` filter bounds the sign the same way). The returned
    /// bound is twice that, which also covers its own rounding. Every non-zero quantity here is at least 2⁻²⁹⁸ (a product of two `f32`), far
    /// above `f64`'s underflow, so the bound holds for every finite input; a zero bound means both
    /// products are exactly zero and so is the determinant.
    #[inline]
    fn estimate(&self) -> (f64, f64) {
        let (u, v) = (self.u.map(f64::from), self.v.map(f64::from));
        let l = (u[1] - u[0]) * (v[2] - v[0]);
        let r = (v[1] - v[0]) * (u[2] - u[0]);
        (l - r, EST_ERR * (l.abs() + r.abs()))
    }

    /// The exact determinant: six exact products summed by expansion arithmetic.
    #[cold]
    #[inline(never)]
    fn exact(&self) -> Approx {
        let (u, v) = (self.u.map(f64::from), self.v.map(f64::from));
        Expansion::sum([
            u[0] * v[1],
            -(v[0] * u[1]),
            u[1] * v[2],
            -(v[1] * u[2]),
            u[2] * v[0],
            -(v[2] * u[0]),
        ])
        .approximate()
    }

    /// The determinant in `f64` with relative error at most 2⁻⁴⁰: the exact sign, and zero exactly
    /// when the determinant is.
    #[inline]
    fn to_f64(self) -> f64 {
        let (d, err) = self.estimate();
        if err <= UNIT_REL * d.abs() {
            d
        } else {
            self.exact().top
        }
    }

    /// The determinant rounded to the nearest `f32` (ties to even), saturated to `±f32::MAX`.
    #[inline]
    fn to_f32(self) -> f32 {
        let (d, err) = self.estimate();
        certainly_rounds_to(d, err).unwrap_or_else(|| self.exact().round_to_f32())
    }
}

/// `RN32(d)` if every value within `err` of `d` rounds to the same `f32`, else `None`.
///
/// The values that round to `r` fill an interval reaching at least half the gap below `|r|` on both
/// sides (the gap above is never smaller), so the answer is certain when `|d − r| + err` stays
/// below that half-gap, a power of two: rounding the sum cannot cross it.
#[inline]
fn certainly_rounds_to(d: f64, err: f64) -> Option<f32> {
    if !(d.abs() <= f32::MAX as f64) {
        return None; // saturation or non-finite input: the exact path decides
    }
    let r = d as f32;
    let a = math::abs(r);
    let gap = if a == 0.0 {
        f32::from_bits(1) as f64
    } else {
        a as f64 - a.next_down() as f64
    };
    // |d − r| is exact (Sterbenz), so only the sum with err rounds.
    ((d - r as f64).abs() + err < 0.5 * gap).then_some(r)
}

/// The three projections whose determinants are `A_x`, `A_y`, `A_z`.
#[inline]
fn projections(p0: Vec3, p1: Vec3, p2: Vec3) -> [Projection; 3] {
    let p = [p0, p1, p2];
    [
        Projection::of(p, 1, 2),
        Projection::of(p, 2, 0),
        Projection::of(p, 0, 1),
    ]
}

/// The area-weighted normal of triangle `P0 P1 P2`: its length is twice the area.
///
/// ```text
/// A = (P1 − P0) × (P2 − P0) = P0×P1 + P1×P2 + P2×P0,   ‖A‖ = 2 · area,
/// direction: right-hand rule on P0 → P1 → P2
/// ```
///
/// **Domain:** any finite points; counter-clockwise winding (seen from the side the normal points to)
/// gives the outward normal.
///
/// **Accuracy:** each component is the exact component of the area vector of the given `f32`
/// vertices, rounded to the nearest `f32` (ties to even). This holds for every finite input,
/// vertices of wildly different magnitudes and slivers included: in particular the sign of every
/// component is exact, and a component is zero only when its exact value is zero or too small for
/// `f32` (at most 2⁻¹⁵⁰ in magnitude).
///
/// **Degenerate input:** a zero-area triangle (repeated or collinear vertices, exactly, as `f32`
/// values) gives the zero vector. Components whose exact value exceeds `f32::MAX` (vertices beyond
/// about 1e19 apart) saturate to `±f32::MAX`. A non-finite coordinate makes the components it enters
/// meaningless (NaN, or saturated); use finite input.
///
/// This is the form to sum for area-weighted vertex normals ([`vertex_normals`](crate::vertex_normals)).
///
/// ```
/// use glam::Vec3;
/// let a = phong::triangle_area_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(a, Vec3::Z); // the unit right triangle: area 1/2, so ‖A‖ = 1
/// // Vertices 17 orders of magnitude apart: the exact A is (0, 0, 3e-18), not −1.39e-17.
/// let t = phong::triangle_area_normal(
///     Vec3::new(-0.5, -0.2, 0.0), Vec3::ZERO, Vec3::new(6e-17, 3e-17, 0.0));
/// assert!(t.z > 0.0);
/// ```
#[must_use]
#[inline]
pub fn triangle_area_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    Vec3::from_array(projections(p0, p1, p2).map(Projection::to_f32))
}

/// The unit normal of triangle `P0 P1 P2`, or `None` for a zero-area triangle.
///
/// ```text
/// N = A / ‖A‖,   A = (P1 − P0) × (P2 − P0)
/// ```
///
/// **Domain:** finite points.
///
/// **Accuracy:** each component is within 0.5 + 2⁻¹⁴ ulp of the exact unit normal of the given
/// `f32` vertices (so nearly always the exact normal rounded to nearest), with the exact sign, for
/// every finite input: slivers, vertices of wildly different magnitudes, huge and subnormal
/// triangles. The components of `A` are found in `f64` to a relative error of 2⁻⁴⁰ (exactly where
/// needed, as in [`triangle_area_normal`]) and normalised in `f64`, whose range holds every
/// product of two `f32`.
///
/// **Degenerate input:** `None` exactly when the vertices are collinear or repeated (as `f32`
/// values; an exact test, no tolerance), or when a vertex is not finite.
///
/// ```
/// use glam::Vec3;
/// let n = phong::try_triangle_normal(Vec3::ZERO, Vec3::X, Vec3::Y);
/// assert_eq!(n, Some(Vec3::Z));
/// assert_eq!(phong::try_triangle_normal(Vec3::ZERO, Vec3::X, 2.0 * Vec3::X), None);
/// // 1e25 away along z, yet a real triangle: its area vector is exactly (1, 0, 0).
/// let far = Vec3::new(0.0, 1.0, 1e25);
/// assert_eq!(phong::try_triangle_normal(far, Vec3::Z, Vec3::ZERO), Some(Vec3::X));
/// ```
#[must_use]
#[inline]
pub fn try_triangle_normal(p0: Vec3, p1: Vec3, p2: Vec3) -> Option<Vec3> {
    let a = projections(p0, p1, p2).map(Projection::to_f64);
    let l2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    // Each non-zero component lies in [2⁻²⁹⁸, 2²⁶⁰], so l2 cannot overflow, and is zero only when
    // the exact area is (or NaN/∞ when the input is not finite).
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
/// let n = phong::triangle_normal_or_zero(o, o + Vec3::new(1.0, 0.0, 0.0), o + Vec3::new(1.0, 1e-2, 0.0));
/// assert!((n - Vec3::Z).length() < 1e-6);
/// assert_eq!(phong::triangle_normal_or_zero(o, o, o), Vec3::ZERO);
/// ```
#[must_use]
#[inline]
pub fn triangle_normal_or_zero(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
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
            triangle_normal_or_zero(Vec3::ZERO, Vec3::new(m, 0.0, 0.0), Vec3::new(0.0, m, 0.0)),
            Vec3::Z
        );
    }
}
