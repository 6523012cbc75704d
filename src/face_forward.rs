//! Turning a normal toward the viewer.

use glam::Vec3;

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
/// map to `−N`.
///
/// **Domain:** any vectors; none needs to be unit (only the sign of `Nref·V` is used).
/// **Degenerate input:** a zero `V` or `Nref` gives `−N`, as GLSL does; so do vectors so small
/// (below about 1e-19 per component) that `Nref·V` underflows to zero.
///
/// Two-sided lighting uses `face_forward(n, v, n)`: the normal flipped to the viewer's side.
///
/// ```
/// use glam::Vec3;
/// assert_eq!(phong::face_forward(Vec3::Z, -Vec3::Z, Vec3::Z), -Vec3::Z);
/// assert_eq!(phong::face_forward(Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
/// ```
#[must_use]
#[inline]
pub fn face_forward(n: Vec3, v: Vec3, n_ref: Vec3) -> Vec3 {
    if n_ref.dot(v) > 0.0 { n } else { -n }
}
