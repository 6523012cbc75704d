//! The three cosines every lobe in the Phong family is built from.

use glam::Vec3;

/// The dot products between the unit normal `N`, light direction `L` and view direction `V` at a
/// point, computed once and shared by the diffuse and specular lobes.
///
/// ```text
/// n_dot_l = N·L,   n_dot_v = N·V,   l_dot_v = L·V
/// ```
///
/// From these alone, with unit vectors:
///
/// ```text
/// Phong:   R·V = 2 (N·L)(N·V) − L·V                    (R = 2(N·L)N − L)
/// Blinn:   (N·H)² = max(N·L + N·V, 0)² / (2 + 2 L·V)   (H = (L+V)/‖L+V‖)
/// ```
///
/// so no reflection or halfway vector is ever built (derivations in docs/derivations.md).
///
/// **Domain:** every direction points away from the surface (to the light, to the viewer) and is
/// unit, or the zero vector meaning "no such direction". The fields are public so batch code and
/// renderers with their own cosines can fill them directly.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Incidence {
    /// `N·L`, the cosine of the angle of incidence.
    pub n_dot_l: f32,
    /// `N·V`, the cosine of the viewing angle.
    pub n_dot_v: f32,
    /// `L·V`, the cosine between the light and the view direction.
    pub l_dot_v: f32,
}

impl Incidence {
    /// The cosines of unit `n`, `l`, `v` (debug builds assert unit length or zero).
    ///
    /// ```
    /// use glam::Vec3;
    /// let g = phong::Incidence::new(Vec3::Z, Vec3::Z, Vec3::X);
    /// assert_eq!((g.n_dot_l, g.n_dot_v, g.l_dot_v), (1.0, 0.0, 0.0));
    /// ```
    #[must_use]
    #[inline]
    pub fn new(n: Vec3, l: Vec3, v: Vec3) -> Self {
        debug_assert!(unit_or_zero(n), "Incidence::new: n must be unit, got {n}");
        debug_assert!(unit_or_zero(l), "Incidence::new: l must be unit, got {l}");
        debug_assert!(unit_or_zero(v), "Incidence::new: v must be unit, got {v}");
        Incidence {
            n_dot_l: n.dot(l),
            n_dot_v: n.dot(v),
            l_dot_v: l.dot(v),
        }
    }

    /// The cosines after normalising each vector with [`normalize_or_zero`](crate::normalize_or_zero).
    /// Total: a zero or non-finite vector contributes zero cosines.
    #[must_use]
    #[inline]
    pub fn from_unnormalized(n: Vec3, l: Vec3, v: Vec3) -> Self {
        use crate::normalize_or_zero as nz;
        Self::new(nz(n), nz(l), nz(v))
    }

    /// Phong's `R·V = 2(N·L)(N·V) − L·V`, clamped to `[−1, 1]` (rounding can push it past ±1).
    #[must_use]
    #[inline]
    pub fn r_dot_v(&self) -> f32 {
        (2.0 * self.n_dot_l * self.n_dot_v - self.l_dot_v).clamp(-1.0, 1.0)
    }

    /// Blinn's `(N·H)²` for the clamped cosine: `max(N·L + N·V, 0)² / (2 + 2 L·V)`, in `[0, 1]`.
    ///
    /// **Degenerate input:** at `L = −V` (where `2 + 2 L·V` falls below `1e-12`) the halfway vector
    /// does not exist and this returns 0, the same answer as [`halfway`](crate::halfway).
    #[must_use]
    #[inline]
    pub fn n_dot_h_squared(&self) -> f32 {
        let s = (self.n_dot_l + self.n_dot_v).max(0.0);
        let den = 2.0 + 2.0 * self.l_dot_v;
        if den > 1e-12 {
            (s * s / den).min(1.0)
        } else {
            0.0
        }
    }
}

fn unit_or_zero(v: Vec3) -> bool {
    let l2 = v.length_squared();
    l2 == 0.0 || (l2 - 1.0).abs() < 1e-3
}
