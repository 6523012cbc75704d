//! The reflectances of one surface point: a material that changes per pixel.

use glam::Vec3;

use crate::material::Material;

/// The per-point part of a material: what texture maps change at every pixel.
///
/// ```text
/// Ka = ambient,  Kd = diffuse,  Ks = specular,  s = shininess      (Ke stays the material's)
/// ```
///
/// Build it per shaded point from texels and hand it to
/// [`Shader::shade_surface`](crate::Shader::shade_surface); nothing is validated in the hot loop.
///
/// **Domain:** colour channels finite and `≥ 0`, shininess finite and `≥ 0` (debug builds assert
/// this when shading). Release builds shade a sanitised copy, by the rule of [`Material::new`]:
/// NaN and negatives read as 0, and values above `f32::MAX` (`+∞`) as `f32::MAX`.
///
/// ```
/// use glam::Vec3;
/// use phong::Surface;
/// // LearnOpenGL's lighting maps: the diffuse texel also colours the ambient term; an
/// // ambient-occlusion texel darkens the ambient term only.
/// let s = Surface::textured(Vec3::new(0.5, 0.3, 0.2), Vec3::splat(0.8), 32.0).with_occlusion(0.5);
/// assert_eq!(s.ambient, Vec3::new(0.25, 0.15, 0.1));
/// assert_eq!(s.diffuse, Vec3::new(0.5, 0.3, 0.2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// `Ka`, the ambient reflectance.
    pub ambient: Vec3,
    /// `Kd`, the diffuse reflectance (a diffuse-map texel, in linear colour).
    pub diffuse: Vec3,
    /// `Ks`, the specular reflectance (a specular-map texel, or a strength times a colour).
    pub specular: Vec3,
    /// `s`, the shininess (a gloss-map value). May change per point.
    pub shininess: f32,
}

impl Surface {
    /// A textured point as in LearnOpenGL's lighting-maps chapter: the diffuse texel is both
    /// `Ka` and `Kd`.
    ///
    /// ```text
    /// Ka = Kd = diffuse_texel,   Ks = specular_texel,   s = shininess
    /// ```
    #[must_use]
    #[inline]
    pub fn textured(diffuse_texel: Vec3, specular_texel: Vec3, shininess: f32) -> Self {
        Surface {
            ambient: diffuse_texel,
            diffuse: diffuse_texel,
            specular: specular_texel,
            shininess,
        }
    }

    /// The same point with its ambient reflectance scaled by an ambient-occlusion factor `ao`
    /// (1 open, 0 fully occluded): `Ka ← ao · Ka`.
    ///
    /// **Domain:** `ao ∈ [0, 1]`; NaN and negatives give 0.
    #[must_use]
    #[inline]
    pub fn with_occlusion(self, ao: f32) -> Self {
        debug_assert!(
            (0.0..=1.0).contains(&ao),
            "Surface::with_occlusion: ao = {ao}"
        );
        Surface {
            ambient: self.ambient * crate::math::clamp_or_lo(ao, 0.0, 1.0),
            ..self
        }
    }

    /// The reflectances and shininess of a [`Material`] (its emission is not part of a surface).
    #[must_use]
    #[inline]
    pub fn of(material: &Material) -> Self {
        Surface {
            ambient: material.ambient(),
            diffuse: material.diffuse(),
            specular: material.specular(),
            shininess: material.shininess(),
        }
    }

    /// Whether every field is in the documented domain.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        let colour = |c: Vec3| c.is_finite() && c.min_element() >= 0.0;
        colour(self.ambient)
            && colour(self.diffuse)
            && colour(self.specular)
            && self.shininess.is_finite()
            && self.shininess >= 0.0
    }
}
