//! Blinn's modification: the lobe around the normal, measured with the halfway vector.

use crate::gate::SpecularGate;
use crate::incidence::Incidence;
use crate::model::ReflectionModel;
use crate::normalization::Normalization;
use crate::pow::PowStrategy;

/// The Blinn-Phong model (Blinn 1977): the specular lobe measured between `N` and the halfway
/// vector `H = (L+V)/‖L+V‖`.
///
/// ```text
/// diffuse  = max(N·L, 0)
/// specular = gate(N·L) · max(N·H, 0)^s = gate(N·L) · ((N·H)²)^(s/2),
/// (N·H)²   = max(N·L + N·V, 0)² / (2 + 2 L·V)
/// ```
///
/// The squared form needs one divide and no square root, and raising `(N·H)²` to `s/2` is the same
/// number. With `N`, `L`, `V` coplanar the angle between `N` and `H` is half the angle between `R`
/// and `V`, so Blinn-Phong with about `4s` tracks Phong with `s` near the highlight (the "2–4×"
/// rule of LearnOpenGL's Advanced Lighting chapter; derivation and measured error in
/// docs/derivations.md, section "The 4× exponent rule").
///
/// **Domain:** the cosines of unit `N`, `L`, `V` (see [`Incidence`]); `s ≥ 0`.
///
/// **Degenerate cases:** at `L = −V` there is no halfway vector and the lobe is 0 (see
/// [`Incidence::n_dot_h_squared`]); nor is there one when `L` or `V` is missing (the zero vector in
/// [`Incidence::new`]), and without a normal `N·H` is 0: a missing `N`, `L` or `V` gives specular 0
/// (and a missing `N` or `L` diffuse 0). `0^0` is 0 (see [`PowStrategy`]). Unlike Phong there is no
/// hard cut-off at low shininess: `N·H > 0` whenever `L` and `V` are both above the surface.
///
/// ```
/// use glam::Vec3;
/// use phong::{BlinnPhong, Incidence, ReflectionModel};
/// let (n, l) = (Vec3::Z, Vec3::new(0.6, 0.0, 0.8));
/// let g = Incidence::new(n, l, phong::reflect(n, l)); // H = N exactly
/// assert!((BlinnPhong::default().specular(&g, 128.0) - 1.0).abs() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct BlinnPhong {
    /// How the specular lobe behaves when `N·L ≤ 0`.
    pub gate: SpecularGate,
    /// Classic (default) or energy-normalised lobes.
    pub normalization: Normalization,
    /// How `((N·H)²)^(s/2)` is evaluated.
    pub pow: PowStrategy,
}

impl BlinnPhong {
    /// Configured like LearnOpenGL's Advanced Lighting shader: no gate (the highlight is not cut
    /// where `N·L ≤ 0`), classic lobes, the default pow strategy. The counterpart of
    /// [`Phong::learnopengl`](crate::Phong::learnopengl).
    ///
    /// ```
    /// use phong::{BlinnPhong, SpecularGate};
    /// assert_eq!(BlinnPhong::learnopengl().gate, SpecularGate::None);
    /// ```
    #[must_use]
    pub fn learnopengl() -> Self {
        BlinnPhong {
            gate: SpecularGate::None,
            ..BlinnPhong::default()
        }
    }
}

impl ReflectionModel for BlinnPhong {
    #[inline]
    fn diffuse(&self, g: &Incidence) -> f32 {
        self.normalization.diffuse(g.n_dot_l)
    }

    #[inline]
    fn specular(&self, g: &Incidence, s: f32) -> f32 {
        let lobe = self.pow.lobe(g.n_dot_h_squared(), 0.5 * s);
        if self.normalization.is_normalized() {
            self.normalization.blinn_factor(s) * lobe * crate::math::max_or(g.n_dot_l, 0.0)
        } else {
            lobe * self.gate.weight(g.n_dot_l)
        }
    }

    #[inline]
    fn resolve(&self) -> Option<crate::ResolvedModel> {
        Some((*self).into())
    }
}
