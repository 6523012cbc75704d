//! Shading one point: every light's lobes, weighted by colours, summed into separate terms.

use glam::Vec3;

use crate::incidence::Incidence;
use crate::light::{LightSource, sanitize_colour};
use crate::material::Material;
use crate::math;
use crate::model::ReflectionModel;
use crate::normalize::sub_saturating;
use crate::normalize_or_zero;

/// Where the viewer is.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Viewer {
    /// A viewer at this point (a camera position): `V = normalize(eye − p)` per point.
    At(Vec3),
    /// A viewer infinitely far away in this direction (from the surface toward the viewer); `V` is
    /// the same everywhere (OpenGL's non-local viewer). Normalised on use.
    Infinite(Vec3),
}

/// The lights and global state a point is shaded under.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a, L> {
    /// The lights; any type implementing [`LightSource`], e.g. [`PointLight`](crate::PointLight)
    /// or the [`Light`](crate::Light) enum.
    pub lights: &'a [L],
    /// `Ia`, the scene's ambient light (OpenGL's light-model ambient), multiplied by `Ka`.
    /// Channels should be finite and `≥ 0`; NaN and negatives are read as 0.
    pub ambient: Vec3,
    /// Where the viewer is.
    pub viewer: Viewer,
}

/// The four terms of the Phong-family equation at one point, kept apart.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Terms {
    /// `Ka ⊙ (Ia + Σ La·f)`
    pub ambient: Vec3,
    /// `Σ f · Kd ⊙ Ld · diffuse lobe`
    pub diffuse: Vec3,
    /// `Σ f · Ks ⊙ Ls · specular lobe`
    pub specular: Vec3,
    /// `Ke`
    pub emission: Vec3,
}

impl Terms {
    /// The sum of the four terms, saturated at `f32::MAX` per channel.
    ///
    /// ```text
    /// total = ambient + diffuse + specular + emission
    /// ```
    #[must_use]
    #[inline]
    pub fn total(&self) -> Vec3 {
        (self.ambient + self.diffuse + self.specular + self.emission).min(Vec3::splat(math::MAX))
    }
}

/// Shades one surface point under every light of a scene: the Phong-family equation.
///
/// ```text
/// ambient  = Ka ⊙ (Ia + Σᵢ Laᵢ·fᵢ)
/// diffuse  = Σᵢ fᵢ · Kd ⊙ Ldᵢ · model.diffuse(gᵢ)
/// specular = Σᵢ fᵢ · Ks ⊙ Lsᵢ · model.specular(gᵢ, s)
/// emission = Ke
/// ```
///
/// with `fᵢ` light `i`'s attenuation × spot factor at the point and `gᵢ` the cosines of
/// `N = normalize(normal)`, `Lᵢ` and `V` ([`Incidence`]). Light `i`'s ambient part is attenuated like
/// its other parts, as in OpenGL and LearnOpenGL's multiple-lights chapter.
///
/// **Domain:** any finite `position` and `normal` (the normal need not be unit: it is normalised
/// here, over the whole `f32` range, as the notes' shaders do). Lights, material and scene as
/// documented on their types.
///
/// **Degenerate input** (no NaN, no panic, for finite input):
/// - a zero `normal`: no diffuse or specular (only ambient and emission);
/// - the point at a point light's position: that light adds ambient only (finite attenuation at
///   `d = 0`); at a spot light's position the direction to the light, and so the cone test, is
///   undefined, and the spot adds nothing ([`SpotLight::spot_factor`](crate::SpotLight::spot_factor)
///   is 0 for a zero `L`);
/// - the viewer at the point (or a zero infinite-viewer direction): no specular;
/// - `L = −V`: no Blinn-Phong specular (see [`BlinnPhong`](crate::BlinnPhong));
/// - overflow: each channel saturates at `f32::MAX`.
///
/// The compiler specialises this on `M` and `L`: [`Lambert`](crate::Lambert) does no specular work,
/// a [`DirectionalLight`](crate::DirectionalLight) no distance or attenuation work.
///
/// ```
/// use glam::Vec3;
/// use phong::{Attenuation, LightColors, Material, Phong, PointLight, Scene, Viewer};
///
/// let light = PointLight::try_new(
///     Vec3::new(0.0, 2.0, 2.0),
///     Attenuation::try_polynomial(1.0, 0.09, 0.032)?,
///     LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5)?,
/// )?;
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0)?;
/// let scene = Scene { lights: &[light], ambient: Vec3::ZERO, viewer: Viewer::At(Vec3::new(0.0, 0.0, 3.0)) };
/// let terms = phong::shade(&Phong::default(), &material, &scene, Vec3::ZERO, Vec3::Z);
/// assert!(terms.diffuse.x > 0.0 && terms.specular.x > 0.0);
/// let rgb = terms.total();
/// # Ok::<(), phong::PhongError>(())
/// ```
#[must_use]
#[inline]
pub fn shade<M: ReflectionModel, L: LightSource>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    position: Vec3,
    normal: Vec3,
) -> Terms {
    let sat = Vec3::splat(math::MAX);
    let n = normalize_or_zero(normal);
    let v = match scene.viewer {
        Viewer::At(eye) => normalize_or_zero(sub_saturating(eye, position)),
        Viewer::Infinite(dir) => normalize_or_zero(dir),
    };
    let s = material.shininess();
    let lit = n != Vec3::ZERO;
    let specular_on = M::HAS_SPECULAR && lit && v != Vec3::ZERO;

    let mut ambient_light = sanitize_colour(scene.ambient);
    let mut diffuse = Vec3::ZERO;
    let mut specular = Vec3::ZERO;
    for light in scene.lights {
        let sample = light.sample(position);
        let f = sample.factor;
        if f == 0.0 {
            continue;
        }
        let colors = light.colors();
        ambient_light += (colors.ambient() * f).min(sat);
        if !lit || sample.direction == Vec3::ZERO {
            continue;
        }
        let g = Incidence::new(n, sample.direction, v);
        // Scalar weights first: finite × finite never gives NaN, and every colour is ≥ 0, so the
        // sums below can overflow to +∞ (saturated at the end) but never produce NaN.
        let wd = math::min_or(f * model.diffuse(&g), math::MAX);
        diffuse += ((colors.diffuse() * material.diffuse()).min(sat) * wd).min(sat);
        if specular_on {
            let ws = math::min_or(f * model.specular(&g, s), math::MAX);
            specular += ((colors.specular() * material.specular()).min(sat) * ws).min(sat);
        }
    }
    Terms {
        ambient: (ambient_light.min(sat) * material.ambient()).min(sat),
        diffuse: diffuse.min(sat),
        specular: specular.min(sat),
        emission: material.emission(),
    }
}
