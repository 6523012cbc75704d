//! The mirror direction of the light about the normal.

use glam::Vec3;

/// The direction `L` mirrored about `N`: Phong's reflection vector.
///
/// ```text
/// R = 2 (N·L) N − L
/// ```
///
/// **Conventions:** `L` points *from the surface to the light*, as every direction in this crate.
/// GLSL's `reflect(I, N)` and glam's [`Vec3::reflect`] take the *incident* direction `I = −L`
/// (pointing toward the surface) and return `I − 2 (N·I) N`, which is the same vector:
/// `reflect(n, l) == (-l).reflect(n)` wherever glam's result is finite, and GLSL's `reflect(-lightDir, norm)` from the tutorials is
/// this `R`.
///
/// **Domain:** `N` unit (debug builds assert it). `L` need not be unit: the map is linear in `L`,
/// so ‖R‖ = ‖L‖ and the angle to `N` is kept (`R·N = L·N`). Any finite `L` is accepted, up to
/// `f32::MAX` per component.
///
/// **Accuracy and range:** computed in `f32` (a few ulps of ‖L‖ per component, as GLSL does it).
/// Where that overflows (`2(N·L)` beyond `f32::MAX`, only for components of `L` above about 1e38)
/// the result is computed again in `f64` instead of returning ∞ or NaN; components whose exact value
/// exceeds `f32::MAX` (possible only when ‖L‖ does) saturate to `±f32::MAX`. So the result is
/// finite for every finite input.
///
/// **Degenerate input:** a zero `L` gives the zero vector. A non-unit `N` gives `L` reflected and
/// scaled wrongly; use [`normalize_or_zero`](crate::normalize_or_zero) first. A zero `N` gives `−L`.
///
/// Derivation (projection and Householder forms): docs/derivations.md, section "The reflect
/// vector".
///
/// ```
/// use glam::Vec3;
/// let n = Vec3::Y;
/// let l = Vec3::new(1.0, 1.0, 0.0).normalize();
/// let r = phong::reflect(n, l);
/// assert!((r - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-6);
/// assert_eq!(r, (-l).reflect(n)); // glam's incident-direction form
/// // Huge L: 2(N·L) overflows f32, yet R is the exact mirror image.
/// assert_eq!(phong::reflect(Vec3::X, Vec3::new(3e38, 0.0, 0.0)), Vec3::new(3e38, 0.0, 0.0));
/// ```
#[must_use]
#[inline]
pub fn reflect(n: Vec3, l: Vec3) -> Vec3 {
    debug_assert!(
        n == Vec3::ZERO || (n.length_squared() - 1.0).abs() < 1e-3,
        "reflect: n must be unit, got {n}"
    );
    let r = 2.0 * n.dot(l) * n - l;
    // An overflow anywhere above leaves an ∞ or NaN in r (∞ propagates through every later step),
    // so a finite r is the plain f32 result.
    if r.is_finite() { r } else { reflect_wide(n, l) }
}

/// [`reflect`] in `f64`, for the rare `L` whose `f32` evaluation overflows.
///
/// With ‖N‖ ≈ 1, `|N·L| ≤ ‖L‖ ≤ √3·f32::MAX`, far inside `f64`'s range, so nothing overflows here;
/// the result is narrowed with saturation.
#[cold]
#[inline(never)]
fn reflect_wide(n: Vec3, l: Vec3) -> Vec3 {
    let (n, l) = (n.to_array().map(f64::from), l.to_array().map(f64::from));
    let d = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    let m = f32::MAX as f64;
    let r = |i: usize| (2.0 * d * n[i] - l[i]).clamp(-m, m) as f32;
    Vec3::new(r(0), r(1), r(2))
}
