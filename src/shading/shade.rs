//! Shading one point: every light's lobes, weighted by colours, summed into separate terms.

use glam::Vec3;

use crate::light::LightSource;
use crate::material::Material;
use crate::model::ReflectionModel;
use crate::shader::Shader;
use crate::terms::Terms;

/// Where the viewer is.
///
/// **Domain:** every coordinate finite. `At(eye)` may be any finite point (at the shaded point
/// itself `V` is the zero vector: no specular there); `Infinite(d)` any finite `d` of any length (a
/// zero `d` means no viewer direction and so no specular). Deserialising (feature `serde`) checks
/// this and names the coordinate, e.g. `viewer.position.x must be finite, got inf`
/// (`viewer.direction.*` for `Infinite`); a direction is kept as written, not normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self")
)]
pub enum Viewer {
    /// A viewer at this point (a camera position): `V = normalize(eye − p)` per point.
    At(Vec3),
    /// A viewer infinitely far away in this direction (from the surface toward the viewer); `V` is
    /// the same everywhere (OpenGL's non-local viewer). Normalised on use.
    Infinite(Vec3),
}

impl Viewer {
    /// The viewer of a ray tracer's hit: infinitely far back along the ray, so `V = −ray_direction`.
    ///
    /// ```text
    /// along_ray(d) = Infinite(−d)
    /// ```
    ///
    /// A ray tracer knows, at each hit, the direction the ray travelled (from the eye or the
    /// previous bounce toward the surface); the direction to the viewer is its opposite, the same
    /// for every light. **Domain:** any finite `d`, any length; a zero `d` means no viewer direction
    /// and so no specular.
    ///
    /// ```
    /// use glam::Vec3;
    /// assert_eq!(phong::Viewer::along_ray(Vec3::new(0.0, 0.0, -2.0)), phong::Viewer::Infinite(Vec3::new(0.0, 0.0, 2.0)));
    /// ```
    #[must_use]
    #[inline]
    pub fn along_ray(ray_direction: Vec3) -> Self {
        Viewer::Infinite(-ray_direction)
    }
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
/// `N = normalize(normal)`, `Lᵢ` and `V` ([`Incidence`](crate::Incidence)). Light `i`'s ambient part is attenuated like
/// its other parts, as in OpenGL and LearnOpenGL's multiple-lights chapter.
///
/// **Domain:** any finite `position` and `normal` (the normal need not be unit: it is normalised
/// here as LearnOpenGL's shaders do, but over the whole `f32` range). Lights, material and scene as
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
/// **Changes of coordinates.** The terms read positions only through the differences
/// `P_light − p` and `eye − p`, so moving the whole scene changes no bit wherever those
/// differences come out the same (always, when the coordinates and the move lie on a grid whose
/// sums are exact). A mirror image (one coordinate negated in every point, normal, light
/// position and direction, and the viewer) changes no bit either. Without falloff
/// ([`Attenuation::None`](crate::Attenuation::None), directional lights) the terms depend on
/// directions only, and a change of units by a power of two changes no bit: positions (the
/// point, the lights, a viewer at a point) × `2ᵏ` and the normal × `2ʲ` give the same terms,
/// from scales where squared lengths underflow `f32` to scales where they overflow, as long as
/// every coordinate and every difference of two stays a normal `f32`; the normalisations divide
/// the factor out exactly (`√(4ᵏx) = 2ᵏ√x`, or a power-of-two rescaling of their own). All three
/// hold for [`Shader`]'s `shade`, `shade_visible` and `shade_surface` in both of its forms, and
/// the first two for the batch and G-buffer entry points at every level
/// (tests/change_of_coordinates.rs).
///
/// The compiler specialises this on `M` and `L`: [`Lambert`](crate::Lambert) does no specular work,
/// a [`DirectionalLight`](crate::DirectionalLight) no distance or attenuation work. This is
/// `Shader::new(model, material, scene).shade(position, normal)`: to shade many points under one
/// material build the [`Shader`] once; for shadows and per-point materials see its
/// [`shade_visible`](Shader::shade_visible) and [`shade_surface`](Shader::shade_surface).
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
    Shader::for_one_point(model, material, scene).shade(position, normal)
}
