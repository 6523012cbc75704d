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
/// `reflect(n, l) == (-l).reflect(n)`, and GLSL's `reflect(-lightDir, norm)` from the tutorials is
/// this `R`.
///
/// **Domain:** `N` unit (debug builds assert it). `L` need not be unit: the map is linear in `L`,
/// so ‖R‖ = ‖L‖ and the angle to `N` is kept (`R·N = L·N`).
///
/// **Degenerate input:** a zero `L` gives the zero vector. A non-unit `N` gives `L` reflected and
/// scaled wrongly; use [`normalize_or_zero`](crate::normalize_or_zero) first. A zero `N` gives `−L`.
///
/// Derivation (projection and Householder forms):
/// [docs/derivations.md](https://example.invalid/phong/docs/derivations.md#the-reflect-vector).
///
/// ```
/// use glam::Vec3;
/// let n = Vec3::Y;
/// let l = Vec3::new(1.0, 1.0, 0.0).normalize();
/// let r = phong::reflect(n, l);
/// assert!((r - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-6);
/// assert_eq!(r, (-l).reflect(n)); // glam's incident-direction form
/// ```
#[must_use]
#[inline]
pub fn reflect(n: Vec3, l: Vec3) -> Vec3 {
    debug_assert!(
        n == Vec3::ZERO || (n.length_squared() - 1.0).abs() < 1e-3,
        "reflect: n must be unit, got {n}"
    );
    2.0 * n.dot(l) * n - l
}
