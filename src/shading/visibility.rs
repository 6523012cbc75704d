//! How much of each light reaches a point: the shadow input of shading.

/// The fraction of each light that reaches the shaded point: 1 lit, 0 in shadow, in between for
/// soft shadows or percentage-closer filtering.
///
/// ```text
/// diffuseᵢ  ← visᵢ · diffuseᵢ,   specularᵢ ← visᵢ · specularᵢ,   ambientᵢ unchanged
/// ```
///
/// As in OpenGL and LearnOpenGL's shadow-mapping chapter, a shadow removes a light's diffuse and
/// specular parts and leaves its ambient part alone. [`Shader`](crate::Shader) asks for light `i`'s
/// visibility exactly once per shaded point, in the order of the scene's lights.
///
/// **Domain:** each value in `[0, 1]` (debug builds assert it); release builds clamp to `[0, 1]` and
/// read NaN as 0.
///
/// Implemented for a slice or array parallel to the scene's lights (a missing entry reads as 1,
/// lit), for [`Unshadowed`], and for a closure wrapped in [`VisibilityFn`] (e.g. one that traces a
/// shadow ray).
///
/// ```
/// use phong::Visibility;
/// let mut v: &[f32] = &[1.0, 0.0];
/// assert_eq!((v.visibility(0), v.visibility(1), v.visibility(2)), (1.0, 0.0, 1.0));
/// ```
pub trait Visibility {
    /// The visibility of light `index` at the point being shaded.
    fn visibility(&mut self, index: usize) -> f32;
}

/// Every light fully visible: no shadows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Unshadowed;

impl Visibility for Unshadowed {
    #[inline(always)]
    fn visibility(&mut self, _index: usize) -> f32 {
        1.0
    }
}

impl Visibility for &[f32] {
    #[inline(always)]
    fn visibility(&mut self, index: usize) -> f32 {
        self.get(index).copied().unwrap_or(1.0)
    }
}

impl<const N: usize> Visibility for [f32; N] {
    #[inline(always)]
    fn visibility(&mut self, index: usize) -> f32 {
        self.get(index).copied().unwrap_or(1.0)
    }
}

impl<const N: usize> Visibility for &[f32; N] {
    #[inline(always)]
    fn visibility(&mut self, index: usize) -> f32 {
        self.get(index).copied().unwrap_or(1.0)
    }
}

/// A closure `FnMut(light index) -> visibility` as a [`Visibility`], for renderers that compute
/// shadows on demand (a shadow ray, a shadow-map lookup).
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Shader, Viewer, VisibilityFn};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ONE)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 8.0)?;
/// let shader = Shader::new(Phong::default(), &material, &scene);
/// let mut rays = 0;
/// let lit = shader.shade_visible(Vec3::ZERO, Vec3::Z, VisibilityFn(|_light| { rays += 1; 0.0 }));
/// assert_eq!((lit.diffuse, lit.specular, rays), (Vec3::ZERO, Vec3::ZERO, 1));
/// # Ok::<(), phong::PhongError>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct VisibilityFn<F>(pub F);

impl<F: FnMut(usize) -> f32> Visibility for VisibilityFn<F> {
    #[inline(always)]
    fn visibility(&mut self, index: usize) -> f32 {
        (self.0)(index)
    }
}
