//! Lambert's diffuse-only model.

use crate::incidence::Incidence;
use crate::model::ReflectionModel;
use crate::normalization::Normalization;

/// Lambert's model (1760): diffuse only, no specular work at all.
///
/// ```text
/// diffuse  = max(N·L, 0)          (or max(N·L, 0)/π when normalised)
/// specular = 0
/// ```
///
/// ```
/// use phong::{Incidence, Lambert, ReflectionModel};
/// let g = Incidence::from_cosines(0.5, 1.0, 0.5);
/// assert_eq!(Lambert::default().diffuse(&g), 0.5);
/// assert!(!Lambert::HAS_SPECULAR);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct Lambert {
    /// [`Normalization::None`] (the default) or normalised (`1/π`).
    pub normalization: Normalization,
}

impl ReflectionModel for Lambert {
    const HAS_SPECULAR: bool = false;

    #[inline]
    fn diffuse(&self, g: &Incidence) -> f32 {
        self.normalization.diffuse(g.n_dot_l)
    }

    /// Always 0.
    #[inline]
    fn specular(&self, _g: &Incidence, _shininess: f32) -> f32 {
        0.0
    }

    #[inline]
    fn resolve(&self) -> Option<crate::ResolvedModel> {
        Some((*self).into())
    }
}
