//! The `ReflectionModel` trait: one question, how strong are the two lobes at a point.

use crate::incidence::Incidence;
use crate::resolved_model::ResolvedModel;
use crate::{BlinnPhong, Lambert, Phong};

/// A reflection model of the Phong family: the diffuse and specular lobes at a point.
///
/// A lobe is a **scalar** weight. Colours are applied once by [`shade`](crate::shade):
///
/// ```text
/// I = Ka⊙(Ia + Σ La·f) + Σ f · ( Kd⊙Ld · diffuse(g) + Ks⊙Ls · specular(g, s) ) + Ke
/// ```
///
/// so a model is a few flops and a batch kernel can specialise on it. `g` holds the cosines
/// `N·L`, `N·V`, `L·V` of unit vectors pointing away from the surface; `s` is the shininess.
///
/// **Contract** for implementations: from any finite `g` with cosines in `[−1, 1]` and any finite
/// `s ≥ 0`, both lobes are finite and `≥ 0`; unnormalised lobes lie in `[0, 1]`.
pub trait ReflectionModel {
    /// `false` for models without a specular lobe; shading then skips all specular work.
    const HAS_SPECULAR: bool = true;

    /// The diffuse lobe; Lambert's `max(N·L, 0)` unless the model is energy-normalised.
    fn diffuse(&self, g: &Incidence) -> f32;

    /// The specular lobe for shininess `s`, including this model's gate.
    fn specular(&self, g: &Incidence, shininess: f32) -> f32;

    /// The model's resolved description, for the crate's own models; `None` (the default) for
    /// models defined elsewhere.
    ///
    /// [`shade`](crate::shade) and [`Shader`](crate::Shader) evaluate a model that resolves with
    /// straight-line code on cosines formed once per light; a model that returns `None` is
    /// evaluated through [`diffuse`](Self::diffuse) and [`specular`](Self::specular) on an
    /// [`Incidence`], which gives the same numbers for the built-in models at a higher cost. A
    /// model outside this crate must keep the default.
    #[inline]
    fn resolve(&self) -> Option<ResolvedModel> {
        None
    }
}

/// A reflection model chosen at run time (from a UI or a scene file).
///
/// Costs one `match` per lobe; use the concrete types when the model is known at compile time.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Model {
    /// See [`Lambert`].
    Lambert(Lambert),
    /// See [`Phong`].
    Phong(Phong),
    /// See [`BlinnPhong`].
    BlinnPhong(BlinnPhong),
}

impl ReflectionModel for Model {
    #[inline]
    fn diffuse(&self, g: &Incidence) -> f32 {
        match self {
            Model::Lambert(m) => m.diffuse(g),
            Model::Phong(m) => m.diffuse(g),
            Model::BlinnPhong(m) => m.diffuse(g),
        }
    }
    #[inline]
    fn specular(&self, g: &Incidence, shininess: f32) -> f32 {
        match self {
            Model::Lambert(m) => m.specular(g, shininess),
            Model::Phong(m) => m.specular(g, shininess),
            Model::BlinnPhong(m) => m.specular(g, shininess),
        }
    }
    #[inline]
    fn resolve(&self) -> Option<ResolvedModel> {
        Some((*self).into())
    }
}

/// A reference to a model is the model: this lets [`Shader::new`](crate::Shader::new) take a model
/// by value or by reference.
impl<M: ReflectionModel + ?Sized> ReflectionModel for &M {
    const HAS_SPECULAR: bool = M::HAS_SPECULAR;
    #[inline(always)]
    fn diffuse(&self, g: &Incidence) -> f32 {
        (**self).diffuse(g)
    }
    #[inline(always)]
    fn specular(&self, g: &Incidence, shininess: f32) -> f32 {
        (**self).specular(g, shininess)
    }
    #[inline(always)]
    fn resolve(&self) -> Option<ResolvedModel> {
        (**self).resolve()
    }
}

impl From<Lambert> for Model {
    fn from(m: Lambert) -> Self {
        Model::Lambert(m)
    }
}
impl From<Phong> for Model {
    fn from(m: Phong) -> Self {
        Model::Phong(m)
    }
}
impl From<BlinnPhong> for Model {
    fn from(m: BlinnPhong) -> Self {
        Model::BlinnPhong(m)
    }
}
