//! The four terms of the Phong-family equation at one point, kept apart.

use core::ops::{Add, AddAssign, Mul};

use glam::Vec3;

use crate::math;

/// The four terms of the Phong-family equation at one point, kept apart.
///
/// **Domain:** every channel of every term finite and `≥ 0`: what [`shade`](crate::shade) and a
/// [`Shader`](crate::Shader) produce. The fields are public, so other values can be built in code,
/// but deserialising (feature `serde`) checks this rule and names the channel, e.g.
/// `terms.diffuse.y must be non-negative, got -1`.
///
/// Terms add (`+`, `+=`) and scale (`* k`) channel by channel, so a renderer can shade one light at
/// a time, or weight a bounce, and sum: both saturate at `f32::MAX`, so the results stay finite.
///
/// ```
/// use glam::Vec3;
/// use phong::Terms;
/// let a = Terms { diffuse: Vec3::splat(0.25), ..Terms::default() };
/// let mut sum = a + a;
/// sum += a * 2.0;
/// assert_eq!(sum.diffuse, Vec3::ONE);
/// assert_eq!(sum.total(), Vec3::ONE);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub struct Terms {
    /// `Ka ⊙ (Ia + Σ La·f)`
    pub ambient: Vec3,
    /// `Σ f · vis · Kd ⊙ Ld · diffuse lobe`
    pub diffuse: Vec3,
    /// `Σ f · vis · Ks ⊙ Ls · specular lobe`
    pub specular: Vec3,
    /// `Ke`
    pub emission: Vec3,
}

impl Terms {
    /// The sum of the four terms, saturated at `f32::MAX` per channel.
    ///
    /// ```text
    /// total = min(((ambient + emission) + diffuse) + specular, f32::MAX)
    /// ```
    ///
    /// Summed in that order: the specular term is the last that shading computes (it waits for
    /// the lobe's power), so it joins last, one addition from the end, which shortens the chain
    /// a vectorised loop over points waits on (DESIGN.md has the measurement). Every term is
    /// `≥ 0`, so the total saturates exactly when the exact sum passes `f32::MAX`, in any order;
    /// with no emission (most materials) it is `(ambient + diffuse) + specular` exactly, since
    /// adding 0 is exact.
    #[must_use]
    #[inline]
    pub fn total(&self) -> Vec3 {
        (self.ambient + self.emission + self.diffuse + self.specular).min(Vec3::splat(math::MAX))
    }

    fn map2(self, other: Terms, f: impl Fn(Vec3, Vec3) -> Vec3) -> Terms {
        Terms {
            ambient: f(self.ambient, other.ambient),
            diffuse: f(self.diffuse, other.diffuse),
            specular: f(self.specular, other.specular),
            emission: f(self.emission, other.emission),
        }
    }
}

/// Term by term, channel by channel, saturated at `f32::MAX`: `(a + b).min(f32::MAX)`.
impl Add for Terms {
    type Output = Terms;
    #[inline]
    fn add(self, rhs: Terms) -> Terms {
        self.map2(rhs, |a, b| (a + b).min(Vec3::splat(math::MAX)))
    }
}

/// `self = self + rhs` (see [`Add`]).
impl AddAssign for Terms {
    #[inline]
    fn add_assign(&mut self, rhs: Terms) {
        *self = *self + rhs;
    }
}

/// Every term times `k`, saturated at `f32::MAX`.
///
/// **Domain:** `k` finite and `≥ 0` (a weight: a bounce's reflectance, a blend factor); NaN and
/// negative `k` read as 0, so terms stay `≥ 0`.
impl Mul<f32> for Terms {
    type Output = Terms;
    #[inline]
    fn mul(self, k: f32) -> Terms {
        let k = math::clamp_or_lo(k, 0.0, math::MAX);
        self.map2(self, |a, _| (a * k).min(Vec3::splat(math::MAX)))
    }
}
