//! Blinn's halfway vector between the light and view directions.

use glam::Vec3;

use crate::normalize_or_zero;

/// The unit vector halfway between `L` and `V`, or `None` when `L = −V`.
///
/// ```text
/// H = (L + V) / ‖L + V‖
/// ```
///
/// **Domain:** `L` (to the light) and `V` (to the viewer) unit, pointing away from the surface.
/// `H` bisects them: `H·L = H·V`. In the plane of `N`, `L` and `V`, the angle between `N` and `H` is
/// half the angle between `R` and `V`.
///
/// Derivation of the bisection and half-angle properties:
/// docs/derivations.md, section "The halfway vector".
///
/// **Degenerate input:** when `L = −V` the sum is zero and every direction perpendicular to `L`
/// bisects them equally; there is no single answer, so this returns `None`. It also returns `None`
/// for non-finite input. The sum is normalised with [`normalize_or_zero`], so nearly opposite
/// directions still give a unit vector as long as `L + V` is not exactly zero.
///
/// ```
/// use glam::Vec3;
/// let h = phong::try_halfway(Vec3::X, Vec3::Y).unwrap();
/// assert!((h - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6);
/// assert_eq!(phong::try_halfway(Vec3::X, -Vec3::X), None);
/// ```
#[must_use]
#[inline]
pub fn try_halfway(l: Vec3, v: Vec3) -> Option<Vec3> {
    let h = normalize_or_zero(l + v);
    (h != Vec3::ZERO).then_some(h)
}

/// The halfway vector `H = (L + V)/‖L + V‖`, or the zero vector when `L = −V`.
///
/// The zero vector makes `N·H = 0`, so a Blinn-Phong lobe built from it is 0: with the light exactly
/// behind the viewer's line of sight there is no highlight. The batch and dot-product paths give the
/// same answer. See [`try_halfway`] for the domain.
///
/// ```
/// use glam::Vec3;
/// assert_eq!(phong::halfway_or_zero(Vec3::Z, -Vec3::Z), Vec3::ZERO);
/// assert_eq!(phong::halfway_or_zero(Vec3::Z, Vec3::Z), Vec3::Z);
/// ```
#[must_use]
#[inline]
pub fn halfway_or_zero(l: Vec3, v: Vec3) -> Vec3 {
    normalize_or_zero(l + v)
}
