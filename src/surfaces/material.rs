//! Surface reflectances and shininess.

use glam::Vec3;

use crate::error::{self, PhongError};
use crate::light::sanitize_colour;
use crate::math;

/// How a surface reflects: ambient, diffuse and specular reflectance, emission, and shininess.
///
/// ```text
/// I = Ka⊙(Ia + Σ La·f) + Σ f·(Kd⊙Ld·diffuse + Ks⊙Ls·specular(s)) + Ke
/// ```
///
/// **Domain:** every colour channel finite and `≥ 0`; shininess `s` finite and `≥ 0` (`s < 1` is
/// allowed: it gives the broad lobes where Phong's cut-off shows). Checked by
/// [`try_new`](Self::try_new), which names the bad field.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub struct Material {
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
    emission: Vec3,
    shininess: f32,
}

impl Material {
    /// Checked: colours finite and `≥ 0`, shininess finite and `≥ 0`. No emission.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Material, PhongError};
    /// let m = Material::try_new(Vec3::splat(0.1), Vec3::splat(0.7), Vec3::ONE, 32.0).unwrap();
    /// assert_eq!(m.shininess(), 32.0);
    /// assert_eq!(
    ///     Material::try_new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, -1.0),
    ///     Err(PhongError::Negative { field: "material.shininess", value: -1.0 })
    /// );
    /// ```
    pub fn try_new(
        ambient: Vec3,
        diffuse: Vec3,
        specular: Vec3,
        shininess: f32,
    ) -> Result<Self, PhongError> {
        Ok(Material {
            ambient: error::colour(
                [
                    "material.ambient.x",
                    "material.ambient.y",
                    "material.ambient.z",
                ],
                ambient,
            )?,
            diffuse: error::colour(
                [
                    "material.diffuse.x",
                    "material.diffuse.y",
                    "material.diffuse.z",
                ],
                diffuse,
            )?,
            specular: error::colour(
                [
                    "material.specular.x",
                    "material.specular.y",
                    "material.specular.z",
                ],
                specular,
            )?,
            emission: Vec3::ZERO,
            shininess: error::non_negative("material.shininess", shininess)?,
        })
    }

    /// Unchecked: debug builds assert the domain; release builds map NaN and negative values to 0.
    #[must_use]
    pub fn new(ambient: Vec3, diffuse: Vec3, specular: Vec3, shininess: f32) -> Self {
        debug_assert!(
            Self::try_new(ambient, diffuse, specular, shininess).is_ok(),
            "Material::new: {:?}",
            Self::try_new(ambient, diffuse, specular, shininess)
        );
        Material {
            ambient: sanitize_colour(ambient),
            diffuse: sanitize_colour(diffuse),
            specular: sanitize_colour(specular),
            emission: Vec3::ZERO,
            shininess: math::clamp_or_lo(shininess, 0.0, math::MAX),
        }
    }

    /// One object colour for ambient, diffuse and specular, as in LearnOpenGL's basic-lighting
    /// shader (where the light carries the strengths). Checked.
    ///
    /// ```text
    /// Ka = Kd = Ks = C
    /// ```
    pub fn try_from_color(color: Vec3, shininess: f32) -> Result<Self, PhongError> {
        Self::try_new(color, color, color, shininess)
    }

    /// The same material with emission `Ke`, checked (finite, `≥ 0`).
    pub fn try_with_emission(self, emission: Vec3) -> Result<Self, PhongError> {
        Ok(Material {
            emission: error::colour(
                [
                    "material.emission.x",
                    "material.emission.y",
                    "material.emission.z",
                ],
                emission,
            )?,
            ..self
        })
    }

    /// The same material with shininess `s`, checked (finite, `≥ 0`).
    pub fn try_with_shininess(self, shininess: f32) -> Result<Self, PhongError> {
        Ok(Material {
            shininess: error::non_negative("material.shininess", shininess)?,
            ..self
        })
    }

    /// The material at one texel of a diffuse map and a specular map: the per-point override for
    /// texture-mapped surfaces.
    ///
    /// ```text
    /// Ka' = Kd' = diffuse_texel,   Ks' = specular_texel,   Ke, s unchanged
    /// ```
    ///
    /// As in LearnOpenGL's lighting-maps chapter, the diffuse map also colours the ambient term.
    /// Cheap (a copy), so call it per shaded point. **Domain:** texels finite and `≥ 0` (debug builds
    /// assert; release builds map NaN and negatives to 0).
    ///
    /// ```
    /// use glam::Vec3;
    /// let m = phong::Material::try_from_color(Vec3::ONE, 8.0).unwrap();
    /// let t = m.textured(Vec3::new(0.5, 0.2, 0.1), Vec3::splat(0.3));
    /// assert_eq!(t.ambient(), Vec3::new(0.5, 0.2, 0.1));
    /// assert_eq!(t.specular(), Vec3::splat(0.3));
    /// ```
    #[must_use]
    #[inline]
    pub fn textured(&self, diffuse_texel: Vec3, specular_texel: Vec3) -> Material {
        debug_assert!(
            diffuse_texel.is_finite() && diffuse_texel.min_element() >= 0.0,
            "Material::textured: diffuse texel {diffuse_texel}"
        );
        debug_assert!(
            specular_texel.is_finite() && specular_texel.min_element() >= 0.0,
            "Material::textured: specular texel {specular_texel}"
        );
        let d = sanitize_colour(diffuse_texel);
        Material {
            ambient: d,
            diffuse: d,
            specular: sanitize_colour(specular_texel),
            ..*self
        }
    }

    /// `Ka`, the ambient reflectance.
    #[must_use]
    #[inline]
    pub fn ambient(&self) -> Vec3 {
        self.ambient
    }
    /// `Kd`, the diffuse reflectance.
    #[must_use]
    #[inline]
    pub fn diffuse(&self) -> Vec3 {
        self.diffuse
    }
    /// `Ks`, the specular reflectance.
    #[must_use]
    #[inline]
    pub fn specular(&self) -> Vec3 {
        self.specular
    }
    /// `Ke`, the emitted colour.
    #[must_use]
    #[inline]
    pub fn emission(&self) -> Vec3 {
        self.emission
    }
    /// `s`, the shininess (specular exponent).
    #[must_use]
    #[inline]
    pub fn shininess(&self) -> f32 {
        self.shininess
    }
}

/// A material's fields by name, for construction that cannot be misordered: three colours in a row
/// in [`Material::try_new`] swap silently, named fields do not. Checked by `Material::try_from`
/// (the same checks as [`Material::try_new`], naming the bad field); `Default` is black with
/// shininess 0, so a literal can name only what it sets.
///
/// ```
/// use glam::Vec3;
/// use phong::{Material, MaterialParams};
/// let brass = Material::try_from(MaterialParams {
///     ambient: Vec3::new(0.33, 0.22, 0.03),
///     diffuse: Vec3::new(0.78, 0.57, 0.11),
///     specular: Vec3::new(0.99, 0.94, 0.81),
///     shininess: 27.9,
///     ..MaterialParams::default()
/// })?;
/// assert_eq!(brass.shininess(), 27.9);
/// assert!(Material::try_from(MaterialParams { shininess: -1.0, ..MaterialParams::default() }).is_err());
/// # Ok::<(), phong::PhongError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MaterialParams {
    /// `Ka`, finite and `≥ 0` per channel.
    pub ambient: Vec3,
    /// `Kd`, finite and `≥ 0` per channel.
    pub diffuse: Vec3,
    /// `Ks`, finite and `≥ 0` per channel.
    pub specular: Vec3,
    /// `Ke`, finite and `≥ 0` per channel.
    pub emission: Vec3,
    /// `s`, finite and `≥ 0`.
    pub shininess: f32,
}

impl TryFrom<MaterialParams> for Material {
    type Error = PhongError;
    /// [`Material::try_new`] with the emission: the first bad field is reported.
    fn try_from(p: MaterialParams) -> Result<Self, PhongError> {
        Material::try_new(p.ambient, p.diffuse, p.specular, p.shininess)?
            .try_with_emission(p.emission)
    }
}

impl From<Material> for MaterialParams {
    fn from(m: Material) -> Self {
        MaterialParams {
            ambient: m.ambient(),
            diffuse: m.diffuse(),
            specular: m.specular(),
            emission: m.emission(),
            shininess: m.shininess(),
        }
    }
}
