//! One triangle's geometry: its distance to a point, its smallest enclosing circle, the spread
//! of its interpolated normals, and the rounding allowance of the cosines shaded on it.

use super::jet::{NormalJet, U};
use crate::math;
use glam::DVec3;
use glam::Vec3;

/// The distance from `p` to triangle `abc` (Ericson, *Real-Time Collision Detection*, 5.1.5).
/// Degenerate triangles whose interior case divides by zero give 0 (a safe lower bound).
pub(super) fn distance_to_triangle(p: Vec3, [a, b, c]: [Vec3; 3]) -> f32 {
    let (p, a, b, c) = (p.as_dvec3(), a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let len = |v: DVec3| math::sqrt_f64(v.length_squared());
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    let d = if d1 <= 0.0 && d2 <= 0.0 {
        len(ap)
    } else {
        let bp = p - b;
        let (d3, d4) = (ab.dot(bp), ac.dot(bp));
        let cp = p - c;
        let (d5, d6) = (ab.dot(cp), ac.dot(cp));
        let vc = d1 * d4 - d3 * d2;
        let vb = d5 * d2 - d1 * d6;
        let va = d3 * d6 - d5 * d4;
        if d3 >= 0.0 && d4 <= d3 {
            len(bp)
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            len(ap - ab * (d1 / (d1 - d3)))
        } else if d6 >= 0.0 && d5 <= d6 {
            len(cp)
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            len(ap - ac * (d2 / (d2 - d6)))
        } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            len(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))
        } else {
            let den = va + vb + vc;
            if den == 0.0 || !den.is_finite() {
                return 0.0;
            }
            len(ap - ab * (vb / den) - ac * (vc / den))
        }
    };
    // Round down: the bound needs a lower estimate.
    let d = (d * (1.0 - 1e-6) - 1e-9).max(0.0);
    if d.is_finite() { d as f32 } else { 0.0 }
}

/// The squared radius of the smallest circle enclosing the triangle: the largest value of
/// `Σ bᵢ‖Pᵢ − P(b)‖²` over the triangle.
pub(super) fn enclosing_radius_squared([a, b, c]: [Vec3; 3]) -> f32 {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let (ab, bc, ca) = (
        (b - a).length_squared(),
        (c - b).length_squared(),
        (a - c).length_squared(),
    );
    let r2 = if bc >= ab + ca {
        bc / 4.0
    } else if ca >= ab + bc {
        ca / 4.0
    } else if ab >= bc + ca {
        ab / 4.0
    } else {
        // Acute: the circumradius, R² = ab·bc·ca / (4‖(B−A)×(C−A)‖²).
        let k = (b - a).cross(c - a).length_squared();
        if k > 0.0 {
            ab * bc * ca / (4.0 * k)
        } else {
            ab.max(bc).max(ca) / 4.0
        }
    };
    ((r2 * (1.0 + 1e-6)) as f32).min(f32::MAX)
}

/// `κ`, `μ` and `ρ` of the interpolated normal (see [`NormalJet`]); `None` when the triangle has
/// no area or its normals cancel somewhere inside it.
pub(super) fn normal_jet(p: [Vec3; 3], n: [Vec3; 3]) -> Option<NormalJet> {
    // μ = min ‖Σ bᵢnᵢ‖: the distance from the origin to the triangle of the normals.
    let mu = distance_to_triangle(Vec3::ZERO, n);
    if !(mu > 1e-4) {
        return None;
    }
    let (p0, p1, p2) = (p[0].as_dvec3(), p[1].as_dvec3(), p[2].as_dvec3());
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (q1, q2) = (
        n[1].as_dvec3() - n[0].as_dvec3(),
        n[2].as_dvec3() - n[0].as_dvec3(),
    );
    let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let det = g11 * g22 - g12 * g12;
    if !(det > 1e-30 * g11 * g22) || !det.is_finite() {
        return None;
    }
    // An orthonormal basis of the plane, and J t = Σ qₖ xₖ with x = G⁻¹ [e1·t, e2·t].
    let t1 = e1 * (1.0 / math::sqrt_f64(g11));
    let t2 = e2 - t1 * e2.dot(t1);
    let t2 = t2 * (1.0 / math::sqrt_f64(t2.length_squared()));
    let jt = |t: DVec3| {
        let (r1, r2) = (e1.dot(t), e2.dot(t));
        let x1 = (g22 * r1 - g12 * r2) / det;
        let x2 = (g11 * r2 - g12 * r1) / det;
        q1 * x1 + q2 * x2
    };
    let (j1, j2) = (jt(t1), jt(t2));
    // κ = largest singular value of [j1 j2].
    let (a, b, c) = (j1.dot(j1), j1.dot(j2), j2.dot(j2));
    let half_tr = 0.5 * (a + c);
    let disc = math::sqrt_f64((0.25 * (a - c) * (a - c) + b * b).max(0.0));
    let kappa = math::sqrt_f64((half_tr + disc).max(0.0)) * (1.0 + 1e-6);
    // ρ ≥ |‖m‖'| = |N·m'|: σᵢ = ‖Jᵀnᵢ‖ restricted to the plane, divided by μ.
    let sigma = n
        .iter()
        .map(|ni| {
            let ni = ni.as_dvec3();
            math::sqrt_f64(ni.dot(j1) * ni.dot(j1) + ni.dot(j2) * ni.dot(j2))
        })
        .fold(0.0f64, f64::max)
        * (1.0 + 1e-6);
    let mu = mu as f64;
    let rho = sigma / mu;
    let out = NormalJet {
        a: (kappa / mu) as f32,
        k2: (kappa * kappa / (mu * mu)) as f32,
        cross: (2.0 * rho * kappa / (mu * mu)) as f32,
    };
    (out.a.is_finite() && out.k2.is_finite() && out.cross.is_finite()).then_some(out)
}

/// One triangle's geometry, shared by the lights.
pub(super) struct Triangle {
    pub(super) p: [Vec3; 3],
    /// Unit vertex normals.
    pub(super) n: [Vec3; 3],
    /// Squared radius of the smallest enclosing circle.
    pub(super) r2: f32,
    /// `μ = min ‖Σ bᵢnᵢ‖` over the triangle.
    pub(super) mu: f32,
    pub(super) normal: Option<NormalJet>,
    /// The largest vertex coordinate magnitude `max ‖Pᵢ‖`: a point `Σ bᵢPᵢ` computed in `f32` is
    /// within `3·2⁻²⁴` of it of the exact one.
    pub(super) pmax: f32,
}

/// The rounding allowance of a cosine computed by `shade` at a point of the triangle, with the
/// light and the viewer at least `d_light` and `d_viewer` away (`∞` for directions):
///
/// ```text
/// η = (8 + 6/μ)·u + 3u·max‖Pᵢ‖·(1/d_light + 1/d_viewer),      u = 2⁻²⁴
/// ```
///
/// The interpolated normal `Σ bᵢnᵢ` is rounded by `3u` of `Σ bᵢ‖nᵢ‖ = 1`, which turns its
/// direction by up to `3√3·u/μ`; normalising it and the light and view directions adds `2u` each,
/// and the dot product `3u`. The point itself is off by `3u·max‖Pᵢ‖`, which turns a direction
/// toward a point `d` away by that over `d`.
pub(super) fn cosine_allowance(tri: &Triangle, d_light: f32, d_viewer: f32) -> f32 {
    let normal = if tri.mu > 0.0 {
        6.0 / tri.mu
    } else {
        f32::INFINITY
    };
    let position = 3.0 * U * tri.pmax * (1.0 / d_light + 1.0 / d_viewer);
    (8.0 + normal) * U + position
}
