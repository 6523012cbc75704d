//! Energy normalisation: scaling the lobes so a material reflects no more light than it receives.

use core::f32::consts::PI;

use crate::math;

/// Whether, and how, the diffuse and specular lobes are energy-normalised.
///
/// The classic Phong-family lobes are not normalised: raising the shininess narrows the highlight
/// *and* darkens it, and `Kd + Ks ≤ 1` does not keep reflected energy below incident energy. The
/// normalised variants turn each lobe into a BRDF times `cos θ = N·L`:
///
/// ```text
/// diffuse  = max(N·L, 0) / π                                     (Lambert's 1/π)
/// Phong    = (s + 2)/(2π) · (R·V)^s · max(N·L, 0)                (Lewis 1994)
/// Blinn    = (s + 8)/(8π) · (N·H)^s · max(N·L, 0)                (Energy: Akenine-Möller et al.)
/// Blinn    = (s + 2)(s + 4) / (8π (2^(−s/2) + s)) · (N·H)^s · max(N·L, 0)   (EnergyExact)
/// ```
///
/// The normalised diffuse carries `1/π`, as a Lambertian BRDF must. Because the `N·L` factor is part
/// of the normalised specular, a normalised model gates specular by the cosine whatever its
/// [`SpecularGate`](crate::SpecularGate) says. For Phong, `Energy` and `EnergyExact` are the same
/// factor: `(s+2)/(2π)` already makes the cosine-weighted lobe integrate to 1 at normal incidence.
/// Derivations: docs/derivations.md, section "Energy normalisation". A model's factors are read
/// through its [`ResolvedModel`](crate::ResolvedModel): `diffuse` and `specular_scale`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Normalization {
    /// The classic lobes, as in OpenGL and LearnOpenGL. The default.
    #[default]
    None,
    /// The common normalisation factors: `(s+2)/2π` for Phong, `(s+8)/8π` for Blinn-Phong.
    Energy,
    /// The exact factor for Blinn-Phong; the same as [`Energy`](Self::Energy) for Phong and Lambert.
    EnergyExact,
}

impl Normalization {
    /// The diffuse lobe `max(N·L, 0)`, divided by `π` when normalised.
    #[must_use]
    #[inline]
    pub(crate) fn diffuse(self, n_dot_l: f32) -> f32 {
        let c = math::max_or(n_dot_l, 0.0);
        match self {
            Normalization::None => c,
            _ => c * (1.0 / PI),
        }
    }

    /// Phong's factor: 1, or `(s+2)/(2π)` when normalised. Finite for every finite `s ≥ 0`.
    #[must_use]
    #[inline]
    pub(crate) fn phong_factor(self, s: f32) -> f32 {
        match self {
            Normalization::None => 1.0,
            _ => ((s.max(0.0) + 2.0) * (1.0 / (2.0 * PI))).min(math::MAX),
        }
    }

    /// Blinn-Phong's factor: 1, `(s+8)/(8π)`, or `(s+2)(s+4) / (8π(2^(−s/2) + s))` (public as
    /// [`ResolvedModel::specular_scale`](crate::ResolvedModel::specular_scale)).
    #[must_use]
    #[inline]
    pub(crate) fn blinn_factor(self, s: f32) -> f32 {
        let s = s.max(0.0);
        match self {
            Normalization::None => 1.0,
            Normalization::Energy => ((s + 8.0) * (1.0 / (8.0 * PI))).min(math::MAX),
            Normalization::EnergyExact => {
                // Split so (s+2)(s+4) cannot overflow for huge s.
                let a = (s + 2.0) * (1.0 / (8.0 * PI));
                let b = (s + 4.0) / (math::powf(2.0, -0.5 * s) + s);
                (a * b).min(math::MAX)
            }
        }
    }

    /// Whether the lobes are normalised (and so cosine-gated).
    #[must_use]
    #[inline]
    pub(crate) fn is_normalized(self) -> bool {
        self != Normalization::None
    }
}
