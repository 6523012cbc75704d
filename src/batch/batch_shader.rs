//! The batch path's prepared form: a model, a material and a scene, reduced once for the kernel
//! at one instruction-set level, shading any number of batches.

use glam::Vec3;

use super::aos::AosVec3;
use super::gbuffer::{self, GBuffer};
use super::kernel;
use super::level::{Level, UnsupportedLevel};
use super::prepare::{self, BatchLight, BatchModel};
use super::sink::{Pixels8, Sink};
use super::soa::{SoaRgb, SoaTerms, SoaVec3};
use super::{chunked_aos, same_lengths};
use crate::material::Material;
use crate::shade::Scene;

/// A model, a material and a scene prepared once for the batch kernel, at one instruction-set
/// [`Level`]: the bundle every batch entry point takes, kept for as many calls as the caller
/// likes (a frame's tiles or rows, one part per thread: it is `Send` and `Sync` when the model
/// and lights are).
///
/// ```text
/// I = Ke + Ka⊙(Ia + Σ f·La) + Σ f·visⱼ · ( Kd⊙Ld · diffuse(N·L) + Ks⊙Ls · gate(N·L) · lobe^s )
/// ```
///
/// Each method is the free function of the same name without its first three arguments:
/// [`shade`](Self::shade) is [`shade_batch`](crate::shade_batch),
/// [`shade_gbuffer`](Self::shade_gbuffer) is [`shade_gbuffer`](crate::shade_gbuffer), and so on,
/// with the same domain, results (bit for bit), degenerate answers and error (the module docs of
/// `batch`). The free functions build one of these per call.
///
/// **Domain:** the model, material and scene of [`shade`](crate::shade); any finite positions
/// and normals (normals need not be unit). **Degenerate input:** as [`shade`](crate::shade), per
/// point; a scene whose lights the kernel cannot take (a light type from outside the crate) is
/// shaded point by point, with the same results.
///
/// ```
/// use glam::Vec3;
/// use phong::{BatchShader, DirectionalLight, LightColors, Material, Phong, Scene, SoaRgb, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.0), 32.0)?;
/// let model = Phong::default();
/// let shader = BatchShader::new(&model, &material, &scene);
///
/// // Two rows of a frame, one call each, one preparation.
/// let zeros = [0.0; 2];
/// let (nx, nz) = ([0.0, 1.0], [1.0, 0.0]); // facing the sun, side-on
/// let mut frame = [0u32; 4];
/// for row in frame.chunks_mut(2) {
///     let n = shader.shade_xrgb8(SoaVec3::new(&zeros, &zeros, &zeros), SoaVec3::new(&nx, &zeros, &nz), row);
///     assert_eq!(n, 2);
/// }
/// assert_eq!(frame, [0x00ff_bc00, 0, 0x00ff_bc00, 0]);
///
/// // The free function is the same call with the bundle unpacked.
/// let (mut r, mut g, mut b) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// let (p, n) = (SoaVec3::new(&zeros, &zeros, &zeros), SoaVec3::new(&nx, &zeros, &nz));
/// shader.shade(p, n, SoaRgb::new(&mut r, &mut g, &mut b));
/// let (mut r2, mut g2, mut b2) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// phong::shade_batch(&model, &material, &scene, p, n, SoaRgb::new(&mut r2, &mut g2, &mut b2));
/// assert_eq!((r, g, b), (r2, g2, b2));
/// # Ok::<(), phong::PhongError>(())
/// ```
pub struct BatchShader<'a, 's, M, L> {
    pub(super) level: Level,
    pub(super) model: &'a M,
    pub(super) material: &'a Material,
    pub(super) scene: &'a Scene<'s, L>,
    /// The kernel's constants, or `None` when some light is not a lane light (then every call is
    /// shaded point by point).
    kernel: Option<kernel::Setup<'a>>,
}

impl<M, L> core::fmt::Debug for BatchShader<'_, '_, M, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BatchShader")
            .field("level", &self.level)
            .field("kernel", &self.kernel.is_some())
            .finish_non_exhaustive()
    }
}

impl<'a, 's, M: BatchModel, L: BatchLight> BatchShader<'a, 's, M, L> {
    /// Prepares `model`, `material` and `scene` for the best [`Level`] this CPU runs
    /// ([`Level::detect`]).
    ///
    /// **Cost:** the model's resolution and one reduction per light (colour products,
    /// attenuation constants, the pow plan), the work each free function does per call.
    pub fn new(model: &'a M, material: &'a Material, scene: &'a Scene<'s, L>) -> Self {
        Self::at(Level::detect(), model, material, scene)
    }

    /// [`new`](Self::new) at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] where this
    /// CPU or build cannot run it: asking for a missing instruction set is an error, never
    /// undefined behaviour.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{BatchShader, Lambert, Level, Material, PointLight, Scene, Viewer};
    /// let scene = Scene::<PointLight> { lights: &[], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
    /// let m = Material::try_from_color(Vec3::ONE, 8.0)?;
    /// let model = Lambert::default();
    /// let shader = BatchShader::with_level(Level::Portable, &model, &m, &scene);
    /// assert_eq!(shader.map(|s| s.level()), Ok(Level::Portable));
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    pub fn with_level(
        level: Level,
        model: &'a M,
        material: &'a Material,
        scene: &'a Scene<'s, L>,
    ) -> Result<Self, UnsupportedLevel> {
        if !level.is_supported() {
            return Err(UnsupportedLevel(level));
        }
        Ok(Self::at(level, model, material, scene))
    }

    /// The instruction-set level the calls run at.
    pub fn level(&self) -> Level {
        self.level
    }

    /// The shader at `level`, which the caller has checked is supported.
    pub(super) fn at(
        level: Level,
        model: &'a M,
        material: &'a Material,
        scene: &'a Scene<'s, L>,
    ) -> Self {
        let kernel = scene
            .lights
            .iter()
            .all(|l| l.lane_light().is_some())
            .then(|| kernel::Setup::new(model, material, scene));
        BatchShader {
            level,
            model,
            material,
            scene,
            kernel,
        }
    }

    /// [`shade_batch`](crate::shade_batch) with this bundle: `out[i] = shade(…, p[i],
    /// n[i]).total()`; returns the number of points shaded, the shortest of the nine slices
    /// (debug builds assert they are equal).
    pub fn shade(&self, positions: SoaVec3<'_>, normals: SoaVec3<'_>, out: SoaRgb<'_>) -> usize {
        debug_assert!(
            same_lengths(positions, normals, out.r.len())
                && out.g.len() == out.r.len()
                && out.b.len() == out.r.len(),
            "shade_batch: the nine slices must have the same length"
        );
        self.shade_inputs(positions, normals, &kernel::PointInputs::default(), out)
    }

    /// [`shade_batch_rgba8`](crate::shade_batch_rgba8) with this bundle: `out[i] = [r, g, b,
    /// 255]`, `linear_to_srgb8` of [`shade`](Self::shade)'s colour, encoded in the kernel's lanes.
    pub fn shade_rgba8(
        &self,
        positions: SoaVec3<'_>,
        normals: SoaVec3<'_>,
        out: &mut [[u8; 4]],
    ) -> usize {
        self.pixels(positions, normals, Pixels8::Rgba(out))
    }

    /// [`shade_batch_xrgb8`](crate::shade_batch_xrgb8) with this bundle: `out[i] = r << 16 |
    /// g << 8 | b`, the levels of [`shade_rgba8`](Self::shade_rgba8), the top byte 0.
    pub fn shade_xrgb8(
        &self,
        positions: SoaVec3<'_>,
        normals: SoaVec3<'_>,
        out: &mut [u32],
    ) -> usize {
        self.pixels(positions, normals, Pixels8::Xrgb(out))
    }

    /// [`shade_batch_aos`](crate::shade_batch_aos) with this bundle: array-of-structs positions
    /// and normals ([`AosVec3`]), moved into structure-of-arrays form 1024 points at a time on
    /// the stack (36 KiB).
    pub fn shade_aos<P: AosVec3, N: AosVec3>(
        &self,
        positions: &[P],
        normals: &[N],
        out: &mut [Vec3],
    ) -> usize {
        chunked_aos(positions, normals, out, |pos, nor, out, [r, g, b]| {
            self.shade_inputs(
                pos,
                nor,
                &kernel::PointInputs::default(),
                SoaRgb::new(r, g, b),
            );
            for (j, o) in out.iter_mut().enumerate() {
                *o = Vec3::new(r[j], g[j], b[j]);
            }
        })
    }

    /// [`shade_batch_aos_rgba8`](crate::shade_batch_aos_rgba8) with this bundle:
    /// [`shade_aos`](Self::shade_aos) into an 8-bit RGBA frame, as
    /// [`shade_rgba8`](Self::shade_rgba8) encodes it.
    pub fn shade_aos_rgba8<P: AosVec3, N: AosVec3>(
        &self,
        positions: &[P],
        normals: &[N],
        out: &mut [[u8; 4]],
    ) -> usize {
        chunked_aos(positions, normals, out, |pos, nor, out, _| {
            let inputs = kernel::PointInputs::default();
            self.shade_inputs(pos, nor, &inputs, Pixels8::Rgba(out));
        })
    }

    /// [`shade_gbuffer`](crate::shade_gbuffer) with this bundle: per-point surfaces,
    /// visibilities, 8-bit albedo and the coverage mask as the [`GBuffer`] holds them, into
    /// linear `f32` colours.
    pub fn shade_gbuffer(&self, gbuffer: &GBuffer<'_>, out: SoaRgb<'_>) -> usize {
        gbuffer::run(self, gbuffer, out)
    }

    /// [`shade_gbuffer_rgba8`](crate::shade_gbuffer_rgba8) with this bundle: alpha 255 at every
    /// shaded point; uncovered pixels keep all four bytes.
    pub fn shade_gbuffer_rgba8(&self, gbuffer: &GBuffer<'_>, out: &mut [[u8; 4]]) -> usize {
        gbuffer::run(self, gbuffer, Pixels8::Rgba(out))
    }

    /// [`shade_gbuffer_xrgb8`](crate::shade_gbuffer_xrgb8) with this bundle: `0x00RRGGBB`
    /// pixels.
    pub fn shade_gbuffer_xrgb8(&self, gbuffer: &GBuffer<'_>, out: &mut [u32]) -> usize {
        gbuffer::run(self, gbuffer, Pixels8::Xrgb(out))
    }

    /// [`shade_gbuffer_terms`](crate::shade_gbuffer_terms) with this bundle: the ambient,
    /// diffuse and specular terms apart.
    pub fn shade_gbuffer_terms(&self, gbuffer: &GBuffer<'_>, out: SoaTerms<'_>) -> usize {
        gbuffer::run(self, gbuffer, out)
    }

    /// Shades the first `min(len, out.len())` points into an 8-bit frame, encoded in the kernel's
    /// lanes; returns the count.
    fn pixels(&self, positions: SoaVec3<'_>, normals: SoaVec3<'_>, mut out: Pixels8<'_>) -> usize {
        debug_assert!(
            same_lengths(positions, normals, out.len()),
            "shade_batch_*8: the six input slices and the output must have the same length"
        );
        let n = positions.len().min(normals.len()).min(out.len());
        self.shade_inputs(
            positions.range(0..n),
            normals.range(0..n),
            &kernel::PointInputs::default(),
            out.part(0..n),
        )
    }

    /// Points `run` of the slices and of `inputs`, into the same points of `out` (the others
    /// untouched); returns the run's length.
    pub(super) fn shade_range<O: Sink>(
        &self,
        pos: SoaVec3<'_>,
        nor: SoaVec3<'_>,
        inputs: &kernel::PointInputs<'_>,
        out: &mut O,
        run: core::ops::Range<usize>,
    ) -> usize {
        self.shade_inputs(
            pos.range(run.clone()),
            nor.range(run.clone()),
            &inputs.from(run.start),
            out.part(run),
        )
    }

    /// The points of a tile (`spans`' runs) of the slices and of `inputs`, into the same points
    /// of `out` (the others untouched), in one kernel call where the kernel runs: its preparation
    /// (each light's constants in every lane) is paid once a tile, not once a row.
    pub(super) fn shade_spans<O: Sink>(
        &self,
        pos: SoaVec3<'_>,
        nor: SoaVec3<'_>,
        inputs: &kernel::PointInputs<'_>,
        out: &mut O,
        spans: super::tiled::TileSpans<'_>,
    ) {
        if let Some(k) = self.kernel_for(inputs) {
            let len = out.len();
            self.run_kernel(k, pos, nor, inputs, out.part(0..len), Some(spans));
        } else {
            for span in spans.runs() {
                self.shade_range(pos, nor, inputs, out, span);
            }
        }
    }

    /// Shades the common prefix of the slices, with per-point inputs over at least as many
    /// points; returns its length. The kernel runs when it takes every light and, for per-point
    /// surfaces, when the model's pow strategy is `Auto` (the only plan it runs per lane) or
    /// there is no lobe; otherwise point by point.
    pub(super) fn shade_inputs<O: Sink>(
        &self,
        pos: SoaVec3<'_>,
        nor: SoaVec3<'_>,
        inputs: &kernel::PointInputs<'_>,
        out: O,
    ) -> usize {
        if let Some(k) = self.kernel_for(inputs) {
            self.run_kernel(k, pos, nor, inputs, out, None)
        } else {
            scalar(self.model, self.material, self.scene, pos, nor, inputs, out)
        }
    }

    /// The kernel's setup where the kernel runs these inputs (see [`shade_inputs`](Self::shade_inputs)).
    fn kernel_for(&self, inputs: &kernel::PointInputs<'_>) -> Option<&kernel::Setup<'a>> {
        self.kernel.as_ref().filter(|k| {
            !inputs.per_point_surface()
                || k.lm.pow == crate::PowStrategy::Auto
                || k.lm.lobe == prepare::Lobe::None
        })
    }

    /// One kernel call with setup `k` (from [`kernel_for`](Self::kernel_for)) over the slices, or
    /// over `spans`' runs of them.
    fn run_kernel<O: Sink>(
        &self,
        k: &kernel::Setup<'_>,
        pos: SoaVec3<'_>,
        nor: SoaVec3<'_>,
        inputs: &kernel::PointInputs<'_>,
        out: O,
        spans: Option<super::tiled::TileSpans<'_>>,
    ) -> usize {
        let call = kernel::CallOf {
            model: self.model,
            material: self.material,
            scene: self.scene,
        };
        let job = kernel::Job {
            setup: k,
            call: &call,
            pos,
            nor,
            inputs,
            out,
            spans,
        };
        super::dispatch::run_level(self.level, job)
    }
}

/// Point by point with [`shade`](crate::shade) (with per-point inputs, a [`Shader`]'s
/// `shade_surface`), for scenes the kernel does not handle.
///
/// [`Shader`]: crate::Shader
fn scalar<M: BatchModel, L: BatchLight, O: Sink>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    pos: SoaVec3<'_>,
    nor: SoaVec3<'_>,
    inputs: &kernel::PointInputs<'_>,
    mut out: O,
) -> usize {
    let n = pos.len().min(nor.len()).min(out.len());
    let shader = crate::Shader::new(model, material, scene);
    for i in 0..n {
        let (p, q) = (
            Vec3::new(pos.x[i], pos.y[i], pos.z[i]),
            Vec3::new(nor.x[i], nor.y[i], nor.z[i]),
        );
        let c = match (inputs.surface(i, 1), inputs.visibility) {
            (None, None) => crate::shade(model, material, scene, p, q),
            (surface, _) => {
                let surface = surface.map_or(crate::Surface::of(material), |s| crate::Surface {
                    ambient: Vec3::new(s[0][0], s[1][0], s[2][0]),
                    diffuse: Vec3::new(s[3][0], s[4][0], s[5][0]),
                    specular: Vec3::new(s[6][0], s[7][0], s[8][0]),
                    shininess: s[9][0],
                });
                let vis = crate::VisibilityFn(|j| inputs.visibility(j, i, 1)[0]);
                shader.shade_surface(p, q, &surface, vis)
            }
        };
        out.put(i, &c);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        Attenuation, BlinnPhong, DirectionalLight, Light, LightColors, Phong, PointLight,
        SoaSurface, Viewer,
    };

    /// A G-buffer of `len` points with per-point surfaces and visibilities, with adversarial
    /// points among them: zero and tiny normals, points at the light and at the viewer, huge
    /// coordinates, shininess 0 and 1, shadow factors 0, 1 and between.
    struct Buffer {
        cols: Vec<Vec<f32>>,
        vis: Vec<f32>,
    }

    impl Buffer {
        fn new(len: usize, lights: usize, at: Vec3, eye: Vec3) -> Self {
            let mut x = 0x9e37_79b9_u32;
            let mut next = move || {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                (x >> 8) as f32 / (1 << 24) as f32
            };
            let mut cols: Vec<Vec<f32>> = (0..16).map(|_| Vec::with_capacity(len)).collect();
            for i in 0..len {
                let mut p = Vec3::new(next(), next(), next()) * 4.0 - 2.0;
                let mut n = Vec3::new(next(), next(), next()) * 2.0 - 1.0;
                match i % 13 {
                    1 => n = Vec3::ZERO,
                    2 => n *= 1e-30,
                    3 => p = at,
                    4 => p = eye,
                    5 => p *= 1e30,
                    _ => {}
                }
                let s = match i % 7 {
                    1 => 0.0,
                    2 => 1.0,
                    _ => 2.0 + 126.0 * next(),
                };
                let row = [
                    p.x,
                    p.y,
                    p.z,
                    n.x,
                    n.y,
                    n.z,
                    next(),
                    next(),
                    next(),
                    next(),
                    next(),
                    next(),
                    next(),
                    next(),
                    next(),
                    s,
                ];
                for (c, v) in cols.iter_mut().zip(row) {
                    c.push(v);
                }
            }
            let vis = (0..len * lights)
                .map(|i| match i % 5 {
                    0 => 0.0,
                    1 => 1.0,
                    _ => next(),
                })
                .collect();
            Buffer { cols, vis }
        }

        fn soa(&self, at: usize) -> SoaVec3<'_> {
            SoaVec3::new(&self.cols[at], &self.cols[at + 1], &self.cols[at + 2])
        }

        fn gbuffer(&self) -> GBuffer<'_> {
            GBuffer::new(self.soa(0), self.soa(3))
                .with_surface(SoaSurface {
                    ambient: self.soa(6),
                    diffuse: self.soa(9),
                    specular: self.soa(12),
                    shininess: &self.cols[15],
                })
                .with_visibility(&self.vis)
        }
    }

    fn grey(a: f32, d: f32, s: f32) -> LightColors {
        LightColors::try_new(Vec3::splat(a), Vec3::splat(d), Vec3::splat(s)).unwrap()
    }

    /// `f32` and 8-bit output of `shader` with its setup's `grey` as prepared and forced off.
    fn both_ways<M: BatchModel, L: BatchLight>(
        mut shader: BatchShader<'_, '_, M, L>,
        g: &GBuffer<'_>,
    ) -> [(Vec<u32>, Vec<[u8; 4]>); 2] {
        assert!(
            shader.kernel.as_ref().unwrap().grey,
            "grey lights not seen as grey"
        );
        let len = g.positions.len();
        let run = |shader: &BatchShader<'_, '_, M, L>| {
            let (mut r, mut gr, mut b) = (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
            shader.shade_gbuffer(g, SoaRgb::new(&mut r, &mut gr, &mut b));
            let mut px = vec![[0u8; 4]; len];
            shader.shade_gbuffer_rgba8(g, &mut px);
            let bits = r.iter().chain(&gr).chain(&b).map(|v| v.to_bits()).collect();
            (bits, px)
        };
        let grey = run(&shader);
        shader.kernel.as_mut().unwrap().grey = false;
        [grey, run(&shader)]
    }

    /// The kernel's instance for grey lights keeps one sum per term where the general one keeps
    /// three: the same operations on the same values, so the same bits, at every level, for
    /// every light kind the kernel runs inline, with per-point surfaces and shadows, on
    /// adversarial points too.
    #[test]
    fn grey_lights_shade_the_same_bits_with_one_sum_per_term() {
        let at = Vec3::new(1.2, 1.0, 2.0);
        let eye = Vec3::new(0.0, 0.5, 4.0);
        let quadratic = Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap();
        let lights: [Light; 3] = [
            PointLight::try_new(at, quadratic, grey(0.1, 0.7, 1.0))
                .unwrap()
                .into(),
            DirectionalLight::try_new(Vec3::new(-1.0, 2.0, 0.5), grey(0.05, 0.4, 0.6))
                .unwrap()
                .into(),
            PointLight::try_new(-at, Attenuation::None, grey(0.0, 0.3, 0.3))
                .unwrap()
                .into(),
        ];
        let m = Material::try_from_color(Vec3::new(0.9, 0.5, 0.2), 24.0).unwrap();
        for count in [1, 3] {
            let buffer = Buffer::new(203, count, at, eye);
            let g = buffer.gbuffer();
            for ambient in [Vec3::ZERO, Vec3::splat(0.03)] {
                let scene = Scene {
                    lights: &lights[..count],
                    ambient,
                    viewer: Viewer::At(eye),
                };
                for level in Level::supported() {
                    let phong = Phong::default();
                    let [a, b] = both_ways(BatchShader::at(level, &phong, &m, &scene), &g);
                    assert!(a == b, "Phong at {level}, {count} lights: grey sums differ");
                    let blinn = BlinnPhong::default();
                    let [a, b] = both_ways(BatchShader::at(level, &blinn, &m, &scene), &g);
                    assert!(
                        a == b,
                        "Blinn-Phong at {level}, {count} lights: grey sums differ"
                    );
                }
            }
        }
    }

    /// Grey is seen only where every colour of every light, and the scene's ambient light, has
    /// three equal channels, and every light is prepared.
    #[test]
    fn only_grey_scenes_take_one_sum_per_term() {
        let m = Material::try_from_color(Vec3::ONE, 8.0).unwrap();
        let at = Vec3::Y;
        let point = |c: LightColors| PointLight::try_new(at, Attenuation::None, c).unwrap();
        let is_grey = |lights: &[PointLight], ambient: Vec3| {
            let scene = Scene {
                lights,
                ambient,
                viewer: Viewer::At(Vec3::Z),
            };
            kernel::Setup::new(&Phong::default(), &m, &scene).grey
        };
        let g = grey(0.1, 0.5, 1.0);
        assert!(is_grey(&[point(g)], Vec3::ZERO));
        assert!(is_grey(&[], Vec3::splat(0.2)));
        assert!(!is_grey(&[point(g)], Vec3::new(0.2, 0.2, 0.3)));
        let tinted = [
            LightColors::try_new(Vec3::new(0.1, 0.1, 0.2), Vec3::ONE, Vec3::ONE).unwrap(),
            LightColors::try_new(Vec3::ONE, Vec3::new(1.0, 0.5, 1.0), Vec3::ONE).unwrap(),
            LightColors::try_new(Vec3::ONE, Vec3::ONE, Vec3::new(1.0, 1.0, 0.9)).unwrap(),
        ];
        for c in tinted {
            assert!(!is_grey(&[point(g), point(c)], Vec3::ZERO), "{c:?}");
        }
        // More lights than the kernel prepares: the others are prepared per chunk.
        assert!(is_grey(&[point(g); kernel::PREPARED], Vec3::ZERO));
        assert!(!is_grey(&[point(g); kernel::PREPARED + 1], Vec3::ZERO));
    }
}
