//! Turning a normal toward the viewer.

use glam::Vec3;

use crate::expansion::Expansion;

/// `N` if the reference normal faces the viewer, otherwise `−N`.
///
/// ```text
/// face_forward(N, V, Nref) =  N   if Nref·V > 0
///                          = −N   otherwise
/// ```
///
/// **Conventions:** `V` points from the surface to the viewer. GLSL's `faceforward(N, I, Nref)` takes
/// the incident direction `I = −V` and returns `N` when `Nref·I < 0`; so
/// `faceforward(N, I, Nref) == face_forward(N, −I, Nref)`, including the tie `Nref·V = 0`, which both
/// map to `−N`, wherever GLSL's `f32` dot product has the sign of the exact one.
///
/// **Domain:** any finite vectors; none needs to be unit (only the sign of `Nref·V` is used).
///
/// **Accuracy:** the decision uses the exact sign of `Nref·V` for the given `f32` vectors, at every
/// magnitude: an `f32` dot product would overflow (to ∞ or NaN) for components beyond about 1e19,
/// underflow to zero below about 1e-19, and round to the wrong sign within a few ulps of the tie.
/// Each product of two `f32` is exact in `f64`; their sum is decided by an `f64` estimate with an
/// error bound, and by exact expansion arithmetic (Shewchuk 1997) in the rare cases it cannot
/// settle.
///
/// **Degenerate input:** `−N` when `Nref·V` is exactly zero: a zero `V` or `Nref` (as GLSL does), or
/// `V` exactly perpendicular to `Nref`. Non-finite input follows the sign of the `f64` dot product
/// (`−N` when it is NaN).
///
/// Two-sided lighting uses `face_forward(n, v, n)`: the normal flipped to the viewer's side.
///
/// ```
/// use glam::Vec3;
/// assert_eq!(phong::face_forward(Vec3::Z, -Vec3::Z, Vec3::Z), -Vec3::Z);
/// assert_eq!(phong::face_forward(Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
/// // Nref·V = 2.7e63 − 2.4e57 > 0, far beyond f32 (where the dot product is NaN).
/// let (v, n_ref) = (Vec3::new(-3e38, 0.0, 6e32), Vec3::new(-9e24, 0.0, -4e24));
/// assert_eq!(phong::face_forward(Vec3::Z, v, n_ref), Vec3::Z);
/// // 1e-30 · 1e-30 underflows f32, but not the decision.
/// assert_eq!(phong::face_forward(Vec3::Z, Vec3::Z * 1e-30, Vec3::Z * 1e-30), Vec3::Z);
/// ```
#[must_use]
#[inline]
pub fn face_forward(n: Vec3, v: Vec3, n_ref: Vec3) -> Vec3 {
    if dot_is_positive(n_ref, v) { n } else { -n }
}

/// 2⁻⁵¹ = 4ε (ε = 2⁻⁵³): bounds the error of the `f64` sum of three exact products relative to the
/// sum of their magnitudes (two roundings: 2ε; the rest covers the rounding of the bound itself).
const DOT_ERR: f64 = 1.0 / 2_251_799_813_685_248.0;

/// Whether the exact `a·b` is positive.
#[inline]
fn dot_is_positive(a: Vec3, b: Vec3) -> bool {
    // Exact: 24-bit significands multiply into 48 bits, and every non-zero product of two f32
    // lies in [2⁻²⁹⁸, 2²⁵⁶], inside f64's normal range.
    let p = [
        a.x as f64 * b.x as f64,
        a.y as f64 * b.y as f64,
        a.z as f64 * b.z as f64,
    ];
    let s = p[0] + p[1] + p[2];
    let bound = DOT_ERR * (p[0].abs() + p[1].abs() + p[2].abs());
    if s > bound {
        true
    } else if s < -bound || bound == 0.0 {
        // A zero bound means every product is exactly zero, and so is the dot product.
        false
    } else {
        exact_sum_is_positive(p)
    }
}

/// The sign of `p0 + p1 + p2` by exact expansion arithmetic, for estimates too close to zero.
#[cold]
#[inline(never)]
fn exact_sum_is_positive(p: [f64; 3]) -> bool {
    if !(p[0].is_finite() && p[1].is_finite() && p[2].is_finite()) {
        // Not finite input: the f64 sum's sign, as documented (false for NaN).
        return p[0] + p[1] + p[2] > 0.0;
    }
    Expansion::sum(p).sign() > 0.0
}
