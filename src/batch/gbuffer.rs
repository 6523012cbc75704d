//! Deferred shading from a G-buffer: per-point surfaces and per-light shadows in the batch kernel.

use super::batch_shader::BatchShader;
use super::covered_runs;
use super::kernel::PointInputs;
use super::level::{Level, UnsupportedLevel};
use super::prepare::{BatchLight, BatchModel};
use super::sink::Sink;
use super::soa::{SoaRgb, SoaTerms, SoaVec3};
use crate::material::Material;
use crate::shade::Scene;

/// A G-buffer's per-point surface as structure-of-arrays slices: at point `i`, the
/// [`Surface`](crate::Surface) with these reflectances and this shininess (texture maps, resolved
/// per pixel).
///
/// A textured renderer in LearnOpenGL's style passes its diffuse texels as both `ambient` and
/// `diffuse` (see [`Surface::textured`](crate::Surface::textured)), or the diffuse texels times an
/// ambient-occlusion factor as `ambient`. Pass one slice where values are shared: the kernel
/// loads a plane once when `ambient` and `diffuse` are the same slices, or the three `specular`
/// slices are one (a grey strength map), and gives the same bits as separate copies.
///
/// **Domain:** as [`Surface`](crate::Surface): finite reflectances `≥ 0` and shininess `≥ 0`.
/// Nothing is validated per point: release builds sanitise (NaN and negatives read as 0, `+∞`
/// as `f32::MAX`), debug builds assert where the scalar path runs.
#[derive(Clone, Copy, Debug)]
pub struct SoaSurface<'a> {
    /// `Ka` per point.
    pub ambient: SoaVec3<'a>,
    /// `Kd` per point.
    pub diffuse: SoaVec3<'a>,
    /// `Ks` per point.
    pub specular: SoaVec3<'a>,
    /// `s` per point.
    pub shininess: &'a [f32],
}

impl<'a> SoaSurface<'a> {
    /// The length of the shortest of the ten slices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.ambient
            .len()
            .min(self.diffuse.len())
            .min(self.specular.len())
            .min(self.shininess.len())
    }

    /// Whether the shortest slice is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn slices(self) -> [&'a [f32]; 10] {
        let (a, d, s) = (self.ambient, self.diffuse, self.specular);
        [a.x, a.y, a.z, d.x, d.y, d.z, s.x, s.y, s.z, self.shininess]
    }
}

/// What a deferred renderer has per pixel: positions and normals, and optionally a per-point
/// surface, 8-bit sRGB albedo texels ([`with_albedo_srgb8`](Self::with_albedo_srgb8)),
/// per-light visibilities (shadow factors) and a coverage mask.
///
/// **Coverage:** with [`with_coverage`](Self::with_coverage), only the points whose mask value is
/// `true` are read and shaded; at the others (the background) every input is left unread, so it
/// may hold anything, and the output is left untouched (8-bit outputs included: their alpha too).
/// Each run of covered points is shaded by one kernel call, so a frame's spans cost what a
/// G-buffer of their length would.
///
/// **Visibility layout:** light-major, `visibility[j * stride + i]` for light `j` at point `i`,
/// where `stride = positions.x.len()`: one plane of the G-buffer per light, in the order of
/// `scene.lights`. Each value is clamped to `[0, 1]` (NaN reads as 0) and scales the light's
/// diffuse and specular parts, not its ambient part, as
/// [`Shader::shade_visible`](crate::Shader::shade_visible) does.
///
/// ```
/// use phong::{GBuffer, SoaVec3};
/// let (x, z, one) = ([0.0; 4], [0.0; 4], [1.0; 4]);
/// let g = GBuffer::new(SoaVec3::new(&x, &x, &z), SoaVec3::new(&x, &x, &one));
/// assert_eq!(g.len(), 4);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct GBuffer<'a> {
    /// The points, in the same space as the scene's lights and viewer.
    pub positions: SoaVec3<'a>,
    /// The surface normals (any length; normalised per point).
    pub normals: SoaVec3<'a>,
    /// Per-point reflectances and shininess; `None`: the call's material at every point.
    pub surface: Option<SoaSurface<'a>>,
    /// Per-light, per-point visibility (see the type's docs); `None`: every light unshadowed.
    pub visibility: Option<&'a [f32]>,
    /// Which points to shade (see the type's docs); `None`: every point.
    pub coverage: Option<&'a [bool]>,
    /// Per-point 8-bit sRGB texels (see [`with_albedo_srgb8`](Self::with_albedo_srgb8)); `None`:
    /// none.
    pub albedo: Option<&'a [[u8; 4]]>,
}

impl<'a> GBuffer<'a> {
    /// Positions and normals only: the call's material at every point, no shadows.
    #[must_use]
    pub fn new(positions: SoaVec3<'a>, normals: SoaVec3<'a>) -> Self {
        GBuffer {
            positions,
            normals,
            surface: None,
            visibility: None,
            coverage: None,
            albedo: None,
        }
    }

    /// The same G-buffer with a per-point surface.
    #[must_use]
    pub fn with_surface(self, surface: SoaSurface<'a>) -> Self {
        GBuffer {
            surface: Some(surface),
            ..self
        }
    }

    /// The same G-buffer with per-light visibilities (layout in the type's docs).
    #[must_use]
    pub fn with_visibility(self, visibility: &'a [f32]) -> Self {
        GBuffer {
            visibility: Some(visibility),
            ..self
        }
    }

    /// The same G-buffer shading only the points where `coverage` is `true` (see the type's
    /// docs).
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{DirectionalLight, GBuffer, LightColors, Material, Phong, Scene, SoaRgb, SoaVec3, Viewer};
    ///
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
    /// // The middle pixel is background: its inputs are never read, its output never written.
    /// let (zero, nz) = ([0.0; 3], [1.0, f32::NAN, 1.0]);
    /// let g = GBuffer::new(SoaVec3::new(&zero, &zero, &zero), SoaVec3::new(&zero, &zero, &nz))
    ///     .with_coverage(&[true, false, true]);
    /// let mut frame = [[9u8; 4]; 3];
    /// assert_eq!(phong::shade_gbuffer_rgba8(&Phong::default(), &material, &scene, &g, &mut frame), 3);
    /// assert_eq!(frame, [[255, 255, 255, 255], [9; 4], [255, 255, 255, 255]]);
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    pub fn with_coverage(self, coverage: &'a [bool]) -> Self {
        GBuffer {
            coverage: Some(coverage),
            ..self
        }
    }

    /// The same G-buffer with a texture's 8-bit sRGB texels per point, as a renderer keeps them
    /// (`[r, g, b, a]`, alpha ignored): each is decoded in the kernel by
    /// [`srgb8_to_linear`](crate::srgb8_to_linear) (a table, no `powf`) and multiplies the
    /// point's ambient and diffuse reflectances, the surface's where there is one (so its
    /// `ambient` can carry an occlusion factor), else the material's. With a white material this
    /// is LearnOpenGL's `texture(material.diffuse, uv)` for both terms.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{DirectionalLight, GBuffer, LightColors, Material, Phong, Scene, SoaRgb, SoaVec3, Viewer};
    ///
    /// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
    /// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let white = Material::try_from_color(Vec3::ONE, 32.0)?;
    /// let (zero, one) = ([0.0; 1], [1.0; 1]);
    /// let texel = [[188, 255, 0, 255]]; // sRGB 188 is about 0.5 linear
    /// let g = GBuffer::new(SoaVec3::new(&zero, &zero, &zero), SoaVec3::new(&zero, &zero, &one))
    ///     .with_albedo_srgb8(&texel);
    /// let mut frame = [[0u8; 4]; 1];
    /// phong::shade_gbuffer_rgba8(&Phong::default(), &white, &scene, &g, &mut frame);
    /// assert_eq!(frame[0], [188, 255, 0, 255]); // lit head-on: the texel itself
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[must_use]
    pub fn with_albedo_srgb8(self, albedo: &'a [[u8; 4]]) -> Self {
        GBuffer {
            albedo: Some(albedo),
            ..self
        }
    }

    /// The number of points: the shortest of the position, normal, surface, albedo and coverage
    /// slices.
    #[must_use]
    pub fn len(&self) -> usize {
        let n = self.positions.len().min(self.normals.len());
        let n = self.surface.map_or(n, |s| n.min(s.len()));
        let n = self.albedo.map_or(n, |a| n.min(a.len()));
        self.coverage.map_or(n, |c| n.min(c.len()))
    }

    /// Whether there are no points.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The first `n` positions and normals (`n` at most [`len`](Self::len)).
    pub(super) fn prefix(&self, n: usize) -> (SoaVec3<'a>, SoaVec3<'a>) {
        let (p, q) = (self.positions, self.normals);
        (
            SoaVec3::new(&p.x[..n], &p.y[..n], &p.z[..n]),
            SoaVec3::new(&q.x[..n], &q.y[..n], &q.z[..n]),
        )
    }

    /// The kernel's view of the per-point inputs, and how many points can be shaded: 0 when the
    /// visibility slice is too short for `lights` planes.
    pub(super) fn inputs(&self, lights: usize, material: &Material) -> (PointInputs<'a>, usize) {
        let stride = self.positions.x.len();
        let n = self.len();
        let short = self
            .visibility
            .is_some_and(|v| v.len() < lights.saturating_mul(stride));
        debug_assert!(
            !short,
            "GBuffer: visibility needs {lights} × {stride} values (one plane per light)"
        );
        let (ka, kd, ks) = (material.ambient(), material.diffuse(), material.specular());
        let inputs = PointInputs::new(
            self.surface.map(|s| s.slices()),
            self.albedo,
            [
                ka.x,
                ka.y,
                ka.z,
                kd.x,
                kd.y,
                kd.z,
                ks.x,
                ks.y,
                ks.z,
                material.shininess(),
            ],
            self.visibility.map(|v| (v, stride)),
        );
        (inputs, if short { 0 } else { n })
    }
}

/// Shades a G-buffer: `out[i] = Shader::shade_surface(p[i], n[i], surface[i], vis[i]).total()`
/// (with [`shade`](crate::shade)'s material where `surface` is `None`, every light unshadowed
/// where `visibility` is `None`), by the batch kernel.
///
/// ```text
/// I = Ke + Ka⊙(Ia + Σ f·La) + Σ f·visⱼ · ( Kd⊙Ld · diffuse(N·L) + Ks⊙Ls · gate(N·L) · lobe^s )
/// ```
///
/// with `Ka, Kd, Ks, s` the point's surface, `Ke` the material's emission. Each lane of the
/// kernel has its own shininess: under [`PowStrategy::Auto`](crate::PowStrategy::Auto) (the
/// default) every lane's power is the degree-7 polynomial's, whole exponents included, as
/// [`Shader::shade_surface`](crate::Shader::shade_surface) computes it; a model with another pow
/// strategy and a per-point surface is shaded point by point.
///
/// **Domain:** as [`shade_batch`](crate::shade_batch), and as [`GBuffer`] and [`SoaSurface`]
/// describe. **Returns** the number of points shaded: the shortest of the G-buffer's slices and
/// `out` (0 when the visibility slice is too short; debug builds assert both); outputs past it
/// are untouched. **Degenerate input:** as [`shade_batch`](crate::shade_batch), per point: the
/// lanes the kernel cannot do exactly go to the scalar path with their own surface and
/// visibilities. **Error** against the scalar path: as [`shade_batch`](crate::shade_batch)'s.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, GBuffer, LightColors, Material, Phong, Scene, SoaRgb, SoaSurface, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
/// let (zero, one) = ([0.0; 2], [1.0; 2]);
/// // Two texels: red and green; the second point is half in shadow.
/// let (red, green, shininess) = ([1.0, 0.0], [0.0, 1.0], [8.0, 40.5]);
/// let texels = SoaVec3::new(&red, &green, &zero);
/// let surface = SoaSurface { ambient: texels, diffuse: texels, specular: SoaVec3::new(&zero, &zero, &zero), shininess: &shininess };
/// let visibility = [1.0, 0.5];
/// let g = GBuffer::new(SoaVec3::new(&zero, &zero, &zero), SoaVec3::new(&zero, &zero, &one))
///     .with_surface(surface)
///     .with_visibility(&visibility);
/// let (mut r, mut gr, mut b) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// let n = phong::shade_gbuffer(&Phong::default(), &material, &scene, &g, SoaRgb::new(&mut r, &mut gr, &mut b));
/// assert_eq!(n, 2);
/// assert_eq!((r, gr), ([1.0, 0.0], [0.0, 0.5]));
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_gbuffer<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: SoaRgb<'_>,
) -> usize {
    BatchShader::new(model, material, scene).shade_gbuffer(gbuffer, out)
}

/// [`shade_gbuffer`] at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] (nothing
/// written) when this CPU or build cannot run it.
pub fn shade_gbuffer_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: SoaRgb<'_>,
) -> Result<usize, UnsupportedLevel> {
    Ok(BatchShader::with_level(level, model, material, scene)?.shade_gbuffer(gbuffer, out))
}

/// [`shade_gbuffer`] straight into an 8-bit RGBA frame: `out[i] = [r, g, b, 255]` with
/// `[r, g, b] = linear_to_srgb8` of [`shade_gbuffer`]'s colour, encoded in the kernel as
/// [`shade_batch_rgba8`](crate::shade_batch_rgba8) encodes them. Alpha is 255 at every shaded
/// point; with a coverage mask, uncovered pixels keep all four bytes.
///
/// **Domain, returns, degenerate input:** as [`shade_gbuffer`], with `out` in place of the
/// three output slices; the levels are those of [`shade_gbuffer`]'s `f32` output, bit for bit.
pub fn shade_gbuffer_rgba8<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: &mut [[u8; 4]],
) -> usize {
    BatchShader::new(model, material, scene).shade_gbuffer_rgba8(gbuffer, out)
}

/// [`shade_gbuffer_rgba8`] at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] (nothing
/// written) when this CPU or build cannot run it.
pub fn shade_gbuffer_rgba8_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: &mut [[u8; 4]],
) -> Result<usize, UnsupportedLevel> {
    Ok(BatchShader::with_level(level, model, material, scene)?.shade_gbuffer_rgba8(gbuffer, out))
}

/// [`shade_gbuffer`] straight into a `0x00RRGGBB` frame (what minifb and softbuffer take):
/// `out[i]` holds `linear_to_srgb8` of [`shade_gbuffer`]'s colour, encoded in the kernel
/// as [`shade_batch_xrgb8`](crate::shade_batch_xrgb8) encodes them; the top byte is 0.
///
/// **Domain, returns, degenerate input:** as [`shade_gbuffer`], with `out` in place of the
/// three output slices; the levels are those of [`shade_gbuffer`]'s `f32` output, bit for bit.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, GBuffer, LightColors, Material, Phong, Scene, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.0), 32.0)?;
/// let (zero, one) = ([0.0; 1], [1.0; 1]);
/// let g = GBuffer::new(SoaVec3::new(&zero, &zero, &zero), SoaVec3::new(&zero, &zero, &one));
/// let mut frame = [0u32; 1];
/// phong::shade_gbuffer_xrgb8(&Phong::default(), &material, &scene, &g, &mut frame);
/// assert_eq!(frame[0], 0x00ff_bc00);
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_gbuffer_xrgb8<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: &mut [u32],
) -> usize {
    BatchShader::new(model, material, scene).shade_gbuffer_xrgb8(gbuffer, out)
}

/// [`shade_gbuffer_xrgb8`] at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] (nothing
/// written) when this CPU or build cannot run it.
pub fn shade_gbuffer_xrgb8_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: &mut [u32],
) -> Result<usize, UnsupportedLevel> {
    Ok(BatchShader::with_level(level, model, material, scene)?.shade_gbuffer_xrgb8(gbuffer, out))
}

/// [`shade_gbuffer`] writing each term apart: `out.ambient`, `out.diffuse` and `out.specular`
/// receive point `i`'s [`Terms`](crate::Terms) as the scalar path computes them (see
/// [`SoaTerms`]), for renderers that treat the terms differently (a bloom pass on the specular
/// term, ambient occlusion applied to the ambient term, a debug view of one term).
///
/// The terms come from the same kernel as [`shade_gbuffer`] at every level, never folded (the
/// total colour may fold the products of the light and material colours into one sum, which
/// rounds differently), so the sum `ambient + diffuse + specular + emission` equals
/// [`shade_gbuffer`]'s colour up to that rounding (a few ulps), and each term equals the scalar
/// path's up to the batch's stated error (the module docs of `batch`). Per-point surfaces,
/// visibilities, the 8-bit albedo and the coverage mask work as in [`shade_gbuffer`].
///
/// **Domain, returns, degenerate input:** as [`shade_gbuffer`], with the nine output slices in
/// place of three; the material's emission is not written.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, GBuffer, LightColors, Material, Phong, Scene, SoaRgb, SoaTerms, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::splat(0.25), Vec3::ONE, Vec3::ONE)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
/// let (zero, one) = ([0.0; 1], [1.0; 1]);
/// let g = GBuffer::new(SoaVec3::new(&zero, &zero, &zero), SoaVec3::new(&zero, &zero, &one));
/// let mut t = [[0.0f32; 1]; 9];
/// let [ar, ag, ab, dr, dg, db, sr, sg, sb] = &mut t;
/// let out = SoaTerms::new(SoaRgb::new(ar, ag, ab), SoaRgb::new(dr, dg, db), SoaRgb::new(sr, sg, sb));
/// phong::shade_gbuffer_terms(&Phong::default(), &material, &scene, &g, out);
/// // Facing the light and the viewer: ambient 0.25, diffuse 1, and the highlight's peak, 1.
/// assert_eq!((t[0][0], t[3][0], t[6][0]), (0.25, 1.0, 1.0));
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_gbuffer_terms<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: SoaTerms<'_>,
) -> usize {
    BatchShader::new(model, material, scene).shade_gbuffer_terms(gbuffer, out)
}

/// [`shade_gbuffer_terms`] at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] (nothing
/// written) when this CPU or build cannot run it.
pub fn shade_gbuffer_terms_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    out: SoaTerms<'_>,
) -> Result<usize, UnsupportedLevel> {
    Ok(BatchShader::with_level(level, model, material, scene)?.shade_gbuffer_terms(gbuffer, out))
}

/// Shades `gbuffer` with `shader` into `out`: its covered runs only, when it has a coverage mask.
pub(super) fn run<M: BatchModel, L: BatchLight, O: Sink>(
    shader: &BatchShader<'_, '_, M, L>,
    gbuffer: &GBuffer<'_>,
    mut out: O,
) -> usize {
    let (inputs, n) = gbuffer.inputs(shader.scene.lights.len(), shader.material);
    debug_assert!(
        out.len() == n,
        "shade_gbuffer: the output must have the G-buffer's length"
    );
    let n = n.min(out.len());
    let (pos, nor) = gbuffer.prefix(n);
    let Some(coverage) = gbuffer.coverage else {
        return shader.shade_inputs(pos, nor, &inputs, out.part(0..n));
    };
    for run in covered_runs(&coverage[..n]) {
        shader.shade_range(pos, nor, &inputs, &mut out, run);
    }
    n
}
