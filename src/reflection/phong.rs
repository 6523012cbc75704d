//! Phong's model: the specular lobe around the mirror direction.

use crate::gate::SpecularGate;
use crate::incidence::Incidence;
use crate::model::ReflectionModel;
use crate::normalization::Normalization;
use crate::pow::PowStrategy;

/// Phong's reflection model (Phong 1975): a lobe around the mirror direction `R`.
///
/// ```text
/// diffuse  = max(N·L, 0)
/// specular = gate(N·L) · max(R·V, 0)^s,     R·V = 2(N·L)(N·V) − L·V  (= reflect(N, L)·V)
/// ```
///
/// **Domain:** the cosines of unit `N`, `L`, `V` (see [`Incidence`]); `s ≥ 0`.
///
/// **Degenerate cases:** `R·V` is clamped to `[−1, 1]` before the power, so rounding never gives a
/// negative base or a lobe above 1; `0^0` is 0 (see [`PowStrategy`]). A missing `N`, `L` or `V`
/// (the zero vector in [`Incidence::new`]) makes `R·V` 0 and so the lobe 0, and a missing `N` or `L`
/// the diffuse lobe 0 as well. For `s < 1` the lobe is
/// cut off sharply where `R·V` reaches 0 (the edge LearnOpenGL's "Advanced Lighting" chapter shows
/// at shininess 1): that is the model,
/// not a bug; [`BlinnPhong`](crate::BlinnPhong) has no such edge.
///
/// ```
/// use glam::Vec3;
/// use phong::{Incidence, Phong, ReflectionModel};
/// // The mirror configuration: V = R gives exactly 1.
/// let (n, l) = (Vec3::Z, Vec3::new(0.6, 0.0, 0.8));
/// let v = phong::reflect(n, l);
/// let g = Incidence::new(n, l, v);
/// assert_eq!(Phong::default().specular(&g, 32.0), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct Phong {
    /// How the specular lobe behaves when `N·L ≤ 0`.
    pub gate: SpecularGate,
    /// Classic (default) or energy-normalised lobes.
    pub normalization: Normalization,
    /// How `max(R·V, 0)^s` is evaluated.
    pub pow: PowStrategy,
}

impl Phong {
    /// Configured like LearnOpenGL's basic-lighting shader: no gate (the highlight is not cut where
    /// `N·L ≤ 0`), classic lobes, the default pow strategy. See also
    /// [`BlinnPhong::learnopengl`](crate::BlinnPhong::learnopengl).
    #[must_use]
    pub fn learnopengl() -> Self {
        Phong {
            gate: SpecularGate::None,
            ..Phong::default()
        }
    }
}

impl ReflectionModel for Phong {
    #[inline]
    fn diffuse(&self, g: &Incidence) -> f32 {
        self.normalization.diffuse(g.n_dot_l)
    }

    #[inline]
    fn specular(&self, g: &Incidence, s: f32) -> f32 {
        let lobe = self.pow.lobe(g.r_dot_v(), s);
        if self.normalization.is_normalized() {
            self.normalization.phong_factor(s) * lobe * crate::math::max_or(g.n_dot_l, 0.0)
        } else {
            lobe * self.gate.weight(g.n_dot_l)
        }
    }

    #[inline]
    fn resolve(&self) -> Option<crate::ResolvedModel> {
        Some((*self).into())
    }
}
