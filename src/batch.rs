//! Shading many points at once from structure-of-arrays slices, at SIMD speed.
//!
//! [`shade_batch`] computes, for every point `i`, the same colour as
//!
//! ```text
//! shade(model, material, scene, (px[i], py[i], pz[i]), (nx[i], ny[i], nz[i])).total()
//! ```
//!
//! 16 points at a time, with the instruction set chosen at run time (with `std` on x86_64:
//! AVX-512, AVX2 + FMA or SSE2 through `is_x86_feature_detected!`), or at compile time (NEON on
//! aarch64; without `std`, the build's target features). [`shade_batch_with_level`] forces a [`Level`], for tests and measurements.
//!
//! [`shade_gbuffer`] is the deferred renderer's form: a [`GBuffer`] with, optionally, a per-point
//! surface ([`SoaSurface`]: what a [`Surface`](crate::Surface) holds, from texture maps) and a
//! visibility per light and point (shadow maps), which scales the light's diffuse and specular
//! parts. It computes [`Shader::shade_surface`](crate::Shader::shade_surface) per point in the
//! same kernel, each lane with its own shininess. Where a light's visibility is 0 at all 16
//! points of a chunk (a shadow map's dark regions), or the light lies behind the surface at all
//! of them (`N·L ≤ 0`, as across a lit sphere's far side) and the model's gate zeroes the lobe
//! there (any gate but [`SpecularGate::None`](crate::SpecularGate::None)), the kernel adds that
//! light's ambient part and skips the rest, with the same result. Passing one slice for planes
//! that are equal ([`SoaSurface`]) saves their loads. A coverage mask
//! ([`GBuffer::with_coverage`]) leaves the background's pixels unread and unwritten. With many
//! lights, [`shade_gbuffer_tiled`] shades each tile of the image with only the lights that reach
//! it ([`TileCulling`]).
//!
//! ## What runs in the vector kernel
//!
//! - models: [`Lambert`](crate::Lambert), [`Phong`](crate::Phong),
//!   [`BlinnPhong`](crate::BlinnPhong) and [`Model`](crate::Model), every
//!   [`SpecularGate`](crate::SpecularGate), [`Normalization`](crate::Normalization) and
//!   [`PowStrategy`](crate::PowStrategy) (`Exact` calls `powf` per lane and so does not vectorise;
//!   `Auto` picks [`PowStrategy::cheapest_for_8bit`](crate::PowStrategy::cheapest_for_8bit));
//! - lights: every kind, any number, also through [`Light`](crate::Light).
//!   [`DirectionalLight`](crate::DirectionalLight)s and [`PointLight`](crate::PointLight)s with
//!   [`Attenuation::None`](crate::Attenuation::None) or
//!   [`Attenuation::Polynomial`](crate::Attenuation::Polynomial) take the fastest path, with the
//!   approximate inverse norms below. A [`SpotLight`](crate::SpotLight), or a point light with
//!   another falloff (inverse-square, Unreal, Frostbite), gets its direction and distance per lane
//!   by an exact square root and division and its factor by the scalar path's own formula, in the
//!   level's vector instructions, so its direction and falloff are [`shade`](crate::shade)'s, bit
//!   for bit; a spot cone's power `c^e` is [`PowStrategy::Auto`](crate::PowStrategy::Auto)'s
//!   for `e` (see "Accuracy"), where `shade` calls `powf`;
//! - both [`Viewer`](crate::Viewer)s.
//!
//! ## Saturation
//!
//! The colours are applied as [`shade`](crate::shade) applies them: per channel, the lights are
//! summed into three sums, each saturated at `f32::MAX` and only then multiplied by the material's
//! colour, and the total is saturated again:
//!
//! ```text
//! A = Ia + Σ f·La,   D = Σ f·d·Ld,   S = Σ min(f·w, MAX)·Ls        (d, w: diffuse, specular lobe)
//! I = min( min(Ka·min(A, MAX), MAX) + min(Kd·min(D, MAX), MAX) + min(Ks·min(S, MAX), MAX) + Ke, MAX )
//! ```
//!
//! Every weight `f·d` and `min(f·w, MAX)` is finite (a normalisation factor can be as large as
//! `f32::MAX`, which is why `f·w` is clamped; a falloff's factor can reach `f32::MAX` too, which
//! is why the kernel clamps that light's `N·L` at 1, as the exact cosine is) and every colour is
//! finite, so no product is `0·∞`:
//! overflow saturates and never turns into NaN. Each term is therefore
//! `min(K·min(exact sum, MAX), MAX)` up to rounding, the same in the kernel and in `shade`, also
//! in the overflow regime; only at the threshold itself can an ulp decide between a finite sum and
//! a saturated one. (When the colours, attenuation and normalisation of a call cannot bring any
//! sum within a factor 2 of `f32::MAX` at any point, the kernels sum the products `Ka⊙La`, … per
//! light instead, which keeps three accumulators rather than nine: the same values up to
//! rounding, at the speed of the unsaturated equation. With per-point surfaces, where that is
//! never done, a scene whose lights and ambient light are all grey (`Vec3::splat` colours, as in
//! LearnOpenGL's scenes) keeps one sum per term instead of three: every channel's sums are the
//! same operations on the same values, so the results are the same bits.)
//!
//! ## Accuracy
//!
//! The kernel forms its cosines from approximate inverse norms (error per [`Level`]'s table), so
//! it evaluates the equation at slightly different cosines. Precisely, with `N`, `L`, `V` the
//! exactly normalised vectors of the point (`L` and `V` from the `f32` differences
//! `P_light − p` and `eye − p`, as `shade` forms them):
//!
//! - every cosine `N·L`, `N·V`, `L·V` it uses is within `η = 2e-6` of the exact one (two inverse
//!   norms, relative error ≤ 3.5e-7 each, and the dot product's `3·2⁻²⁴`, about `1e-6`; the
//!   margin covers the rounding of `2(N·L)(N·V) − L·V` and `2 + 2 L·V`, which perturb a cosine by
//!   a few `2⁻²⁴`);
//! - a point light's attenuation factor is within `2e-6` relative of the exact one (the other
//!   falloffs are `shade`'s own, which are within that too);
//! - a spot light's cone factor `c^e` (`c` the cosine to its axis, the same bits as `shade`'s) is
//!   `shade`'s for `e = 0` and `e = 1`, and otherwise within
//!   [`PowStrategy::Auto`](crate::PowStrategy::Auto)'s `max_relative_error` for `e` relative to
//!   `max(c^e, 2⁻²⁴)` (`3.3e-5` for a whole `e ≤ 1024`, `2.2e-5` otherwise), as a lobe is;
//! - Blinn-Phong's `(N·H)²` is the cosine form `max(N·L + N·V, 0)² / (2 + 2 L·V)` of those
//!   cosines within `3·2⁻²⁴` relative;
//! - the lobe power is within the strategy's
//!   [`max_relative_error`](crate::PowStrategy::max_relative_error) (relative to
//!   `max(lobe, 2⁻²⁴)`);
//! - each of the three sums, and the total, rounds to within `(8 + 2·lights)·2⁻²⁴` relative (all
//!   their terms are `≥ 0`);
//! - where an intermediate value falls below `f32`'s normal range (`2⁻¹²⁶`), gradual underflow
//!   replaces the relative rounding by an absolute error of at most `2⁻¹⁵⁰` per operation, which
//!   the factors applied after it scale: per light, at most `32 · 2⁻¹⁵⁰ · max(f, 1)` times the sum
//!   over the three terms of `max(colour, 1) · max(reflectance, 1)` (and the normalisation factor
//!   for the specular term). With colours of order 1 this is below `1e-43`; it matters only for
//!   scenes whose colours span the whole `f32` range. `shade` has the same allowance.
//!
//! So each channel lies in the range the equation takes over those perturbations. To first order
//! that range is, per light, `f·Ks·Ls·k·gate` (`k` the normalisation factor) times the lobe's
//! change, plus `f·Kd·Ld·η` for the diffuse lobe. With `p` the exponent applied to the lobe's base
//! (`s` for Phong, `s/2` for Blinn-Phong) the lobe's relative change is
//!
//! ```text
//! Phong:        p · 5η / (R·V)                                      (R·V = 2(N·L)(N·V) − L·V)
//! Blinn-Phong:  p · ( 4η / (N·L + N·V) + 2η / (2 + 2 L·V) )        (base t² / (2 + 2 L·V))
//! ```
//!
//! plus the strategy's error. It grows with `p` and with the conditioning of the base: near a
//! zero base (where for `p < 1` the change is up to `(5η)^p` absolute rather than relative), and
//! for Blinn-Phong as `L → −V`, where `2 + 2 L·V` cancels. Where a cosine is within `η` of 0 the
//! step gate and the clamps may decide either way. Energy-normalised lobes scale all of it by `k`,
//! which exceeds 1. [`shade`](crate::shade) lies in the same range (its cosines are within a few
//! `2⁻²⁴`), so the two agree to the range's width. `tests/batch.rs` checks this range at every
//! level, on random and on adversarial input.
//!
//! Degenerate points (zero normal, viewer or light at the point, coordinates so large that a
//! squared norm leaves `[1e-30, 1e30]`) are shaded by [`shade`](crate::shade) itself, so their
//! documented results hold exactly. So are Blinn-Phong lanes with `2 + 2 L·V < 1e-2` (light and
//! viewer nearly opposite, e.g. a grazing glint), where `2η / (2 + 2 L·V)` above would exceed
//! `4e-4` (`shade` computes `(N·H)²` from `L + V`, whose error grows only as
//! `2⁻²⁴ / ‖L + V‖`). From finite input no NaN is produced.
//!
//! ## 8-bit output
//!
//! [`shade_batch_rgba8`] and [`shade_batch_xrgb8`] write a frame's pixels directly, as
//! `[r, g, b, 255]` or `0x00RRGGBB`: the kernel encodes each chunk's colours in its lanes with
//! [`linear_to_srgb8`](crate::linear_to_srgb8)'s table as it writes them. The levels are exactly
//! those of this module's `f32` output; no buffer and no allocation, so they work without `alloc`.
//!
//! ## The terms apart
//!
//! [`shade_gbuffer_terms`] writes each point's ambient, diffuse and specular terms into their own
//! slices ([`SoaTerms`]), for a renderer that treats them differently. The same kernel computes
//! them at every level; only the sum (and, for one material whose sums cannot overflow, the
//! folding of the products into that sum) is left out.
//!
//! ## Array-of-structs input
//!
//! [`shade_batch_aos`] and [`shade_batch_aos_rgba8`] take `&[Vec3]` positions and normals, the
//! layout a G-buffer or a mesh already has: 1024 points at a time are moved into stack arrays
//! for the kernel, so the results are [`shade_batch`]'s, bit for bit, without a copy of the
//! caller's arrays.
//!
//! ## One preparation, many calls
//!
//! Each free function prepares its model, material and scene for the kernel on every call. A
//! [`BatchShader`] holds that preparation, with the level, for as many calls as a renderer makes
//! (a frame's rows or tiles, one part per thread); its methods are the free functions without
//! their first three arguments, with the same results, bit for bit.
//!
//! ## Many cores
//!
//! Every point is shaded from its own inputs and the call's constants alone, so a batch split
//! into parts gives exactly the same bits as the whole, whatever the split. To use every core,
//! cut the nine slices at the same indices and shade the parts on threads; the output is then
//! identical to one serial call (tested at every level in tests/batch_parallel.rs; the speed-up
//! is measured in docs/performance.md, group `parallel_1m`, into `f32` and into 8-bit RGBA: the
//! same split works for every entry point, a frame's rows cut at the same indices). A recipe
//! rather than a `rayon` entry point: it needs no dependency, works with any thread pool, and a
//! renderer usually splits its frame (tiles, rows) already. With `std`:
//!
//! ```
//! use glam::Vec3;
//! use phong::{BatchShader, DirectionalLight, LightColors, Material, Phong, Scene, SoaRgb, SoaVec3, Viewer};
//!
//! let sun = DirectionalLight::try_new(Vec3::ONE, LightColors::try_new(Vec3::splat(0.1), Vec3::ONE, Vec3::ONE)?)?;
//! let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
//! let material = Material::try_from_color(Vec3::new(0.8, 0.3, 0.2), 32.0)?;
//! let model = Phong::default();
//! let n = 10_000;
//! let p: [Vec<f32>; 3] = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
//! let nn: [Vec<f32>; 3] = [(0..n).map(|i| (i as f32).sin()).collect(), vec![0.5; n], vec![1.0; n]];
//! let (mut r, mut g, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
//!
//! // Prepared once, shared by every thread; one part per thread, cut at the same indices in
//! // every slice.
//! let shader = BatchShader::new(&model, &material, &scene);
//! let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
//! let part = n.div_ceil(threads);
//! std::thread::scope(|s| {
//!     let outs = r.chunks_mut(part).zip(g.chunks_mut(part)).zip(b.chunks_mut(part));
//!     for (k, ((r, g), b)) in outs.enumerate() {
//!         let (lo, hi) = (k * part, (k * part + part).min(n));
//!         let positions = SoaVec3::new(&p[0][lo..hi], &p[1][lo..hi], &p[2][lo..hi]);
//!         let normals = SoaVec3::new(&nn[0][lo..hi], &nn[1][lo..hi], &nn[2][lo..hi]);
//!         let shader = &shader;
//!         s.spawn(move || shader.shade(positions, normals, SoaRgb::new(r, g, b)));
//!     }
//! });
//! let one = phong::shade(&model, &material, &scene, Vec3::ZERO, Vec3::new(nn[0][7], 0.5, 1.0));
//! assert!((r[7] - one.total().x).abs() < 1e-5);
//! # Ok::<(), phong::PhongError>(())
//! ```

mod aos;
mod batch_shader;
mod dispatch;
mod falloff_lanes;
mod gbuffer;
mod kernel;
mod level;
mod prepare;
mod simd;
mod sink;
mod soa;
mod srgb8_lanes;
mod tiled;

pub use aos::AosVec3;
pub use batch_shader::BatchShader;
pub use gbuffer::{
    GBuffer, SoaSurface, shade_gbuffer, shade_gbuffer_rgba8, shade_gbuffer_rgba8_with_level,
    shade_gbuffer_terms, shade_gbuffer_terms_with_level, shade_gbuffer_with_level,
    shade_gbuffer_xrgb8, shade_gbuffer_xrgb8_with_level,
};
pub use level::{Level, UnsupportedLevel};
pub use prepare::{BatchLight, BatchModel};
pub use soa::{SoaRgb, SoaTerms, SoaVec3};
pub use tiled::{TileCulling, shade_gbuffer_tiled, shade_gbuffer_tiled_with_level};

use glam::Vec3;

use crate::material::Material;
use crate::shade::Scene;

/// Shades every point of a structure-of-arrays batch: `out[i] = shade(…, p[i], n[i]).total()`.
///
/// ```text
/// I = Ke + Ka⊙(Ia + Σ f·La) + Σ f · ( Kd⊙Ld · diffuse(N·L) + Ks⊙Ls · gate(N·L) · lobe^s )
/// ```
///
/// **Domain:** any finite positions and normals (normals need not be unit; they are normalised per
/// point); model, material and scene as for [`shade`](crate::shade). Runs at the best
/// [`Level::detect`] finds.
///
/// **Returns** the number of points shaded: the length of the shortest of the nine slices (debug
/// builds assert they are equal). Outputs past it are untouched.
///
/// **Degenerate input:** as [`shade`](crate::shade): a zero normal gives ambient + emission only,
/// a light at the point adds ambient only, a viewer at the point gives no specular, `L = −V` gives
/// no Blinn-Phong specular; no NaN from finite input. **Error** against [`shade`](crate::shade):
/// see the module docs.
///
/// ```
/// use glam::Vec3;
/// use phong::{Attenuation, BlinnPhong, LightColors, Material, PointLight, PowStrategy, Scene};
/// use phong::{SoaRgb, SoaVec3, Viewer};
///
/// let light = PointLight::try_new(
///     Vec3::new(0.0, 2.0, 2.0),
///     Attenuation::try_polynomial(1.0, 0.09, 0.032)?,
///     LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5)?,
/// )?;
/// let scene = Scene { lights: &[light], ambient: Vec3::ZERO, viewer: Viewer::At(Vec3::Z * 3.0) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.31), 32.0)?;
/// let model = BlinnPhong { pow: PowStrategy::Auto, ..BlinnPhong::default() };
///
/// let (px, py, pz) = (vec![0.0; 100], vec![0.0; 100], vec![0.0; 100]);
/// let (nx, ny, nz) = (vec![0.0; 100], vec![0.0; 100], vec![1.0; 100]);
/// let (mut r, mut g, mut b) = (vec![0.0; 100], vec![0.0; 100], vec![0.0; 100]);
/// let n = phong::shade_batch(
///     &model,
///     &material,
///     &scene,
///     SoaVec3::new(&px, &py, &pz),
///     SoaVec3::new(&nx, &ny, &nz),
///     SoaRgb::new(&mut r, &mut g, &mut b),
/// );
/// assert_eq!(n, 100);
/// let one = phong::shade(&model, &material, &scene, Vec3::ZERO, Vec3::Z).total();
/// assert!((r[7] - one.x).abs() < 1e-5);
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_batch<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: SoaVec3<'_>,
    normals: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> usize {
    BatchShader::new(model, material, scene).shade(positions, normals, out)
}

/// [`shade_batch`] at a chosen instruction-set [`Level`].
///
/// **Returns** the number of points shaded, or [`UnsupportedLevel`] (having written nothing) when
/// this CPU or build cannot run `level`: asking for a missing instruction set is an error, never
/// undefined behaviour. Results agree with [`shade_batch`] at every level to the accuracy in
/// [`Level`]'s table.
///
/// ```
/// use phong::Level;
/// assert!(Level::Portable.is_supported());
/// assert!(Level::detect().is_supported());
/// ```
pub fn shade_batch_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: SoaVec3<'_>,
    normals: SoaVec3<'_>,
    out: SoaRgb<'_>,
) -> Result<usize, UnsupportedLevel> {
    Ok(BatchShader::with_level(level, model, material, scene)?.shade(positions, normals, out))
}

/// Shades a batch straight into an 8-bit RGBA frame: `out[i] = [r, g, b, 255]` with
/// `[r, g, b] = linear_to_srgb8(shade(…, p[i], n[i]).total())`.
///
/// The same kernel as [`shade_batch`] encodes each colour in its vector lanes before writing it,
/// with [`linear_to_srgb8`](crate::linear_to_srgb8)'s levels. At AVX-512 and AVX2 the lanes
/// compute `255·srgb(x)` to within `9e-4` levels, in fixed point, and round it. Where a lane lies
/// within `9.8e-4` of a rounding boundary, its channel takes that function's own table instead (as SSE2, NEON
/// and portable always do): per channel, one 32-bit entry for the value's bucket of `f32`s (its
/// exponent and top seven mantissa bits) holds the bucket's first level and where the one level
/// boundary it may hold lies, then one comparison. So every pixel is exactly
/// [`linear_to_srgb8`](crate::linear_to_srgb8) of the `f32` colour, at every level. No buffer,
/// no allocation. Alpha is 255.
///
/// **Domain:** as [`shade_batch`]. **Returns** the number of points shaded: the shortest of the
/// six input slices and `out` (debug builds assert they are equal); entries past it are untouched.
/// **Degenerate input:** as [`shade_batch`]; colours above 1 give 255, so no NaN reaches a
/// channel. The levels are those of [`shade_batch`]'s own `f32` output, bit for bit the same
/// encoding; against the scalar [`shade`](crate::shade) they differ by one level where the two
/// colours straddle a level boundary (the rate is in docs/accuracy.md for `f32` against `f64`).
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.0), 32.0)?;
/// let (px, py, pz) = ([0.0; 3], [0.0; 3], [0.0; 3]);
/// // Facing the sun, side-on, facing away.
/// let (nx, ny, nz) = ([0.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, -1.0]);
/// let mut frame = [[0u8; 4]; 3];
/// let n = phong::shade_batch_rgba8(
///     &Phong::default(),
///     &material,
///     &scene,
///     SoaVec3::new(&px, &py, &pz),
///     SoaVec3::new(&nx, &ny, &nz),
///     &mut frame,
/// );
/// assert_eq!(n, 3);
/// assert_eq!(frame[0], [255, 188, 0, 255]); // srgb(0.5) is level 188
/// assert_eq!(frame[2], [0, 0, 0, 255]);
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_batch_rgba8<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: SoaVec3<'_>,
    normals: SoaVec3<'_>,
    out: &mut [[u8; 4]],
) -> usize {
    BatchShader::new(model, material, scene).shade_rgba8(positions, normals, out)
}

/// Shades a batch straight into a `0x00RRGGBB` frame (the `u32` pixels that minifb and
/// softbuffer take): `out[i] = r << 16 | g << 8 | b` with `[r, g, b]` as in
/// [`shade_batch_rgba8`], the top byte 0.
///
/// **Domain, returns, degenerate input:** as [`shade_batch_rgba8`].
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, SoaVec3, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.0), 32.0)?;
/// let zeros = [0.0; 1];
/// let mut frame = [0u32; 1];
/// phong::shade_batch_xrgb8(
///     &Phong::default(),
///     &material,
///     &scene,
///     SoaVec3::new(&zeros, &zeros, &zeros),
///     SoaVec3::new(&zeros, &zeros, &[1.0]),
///     &mut frame,
/// );
/// assert_eq!(frame[0], 0x00ff_bc00);
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_batch_xrgb8<M: BatchModel, L: BatchLight>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: SoaVec3<'_>,
    normals: SoaVec3<'_>,
    out: &mut [u32],
) -> usize {
    BatchShader::new(model, material, scene).shade_xrgb8(positions, normals, out)
}

/// [`shade_batch_rgba8`] at a chosen [`Level`], for tests and measurements: the same pixels as
/// [`shade_batch_with_level`]'s output at that level, encoded.
///
/// **Domain and degenerate input:** as [`shade_batch_rgba8`]. **Returns** the number of points
/// shaded, or [`UnsupportedLevel`] (having written nothing) where this CPU or build cannot run
/// `level`.
///
/// ```
/// use phong::Level;
/// let mut frame = [[0u8; 4]; 0];
/// let scene = phong::Scene::<phong::PointLight> { lights: &[], ambient: glam::Vec3::ZERO, viewer: phong::Viewer::Infinite(glam::Vec3::Z) };
/// let m = phong::Material::try_from_color(glam::Vec3::ONE, 8.0)?;
/// let none = phong::SoaVec3::new(&[], &[], &[]);
/// let n = phong::shade_batch_rgba8_with_level(Level::Portable, &phong::Lambert::default(), &m, &scene, none, none, &mut frame);
/// assert_eq!(n, Ok(0));
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_batch_rgba8_with_level<M: BatchModel, L: BatchLight>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: SoaVec3<'_>,
    normals: SoaVec3<'_>,
    out: &mut [[u8; 4]],
) -> Result<usize, UnsupportedLevel> {
    Ok(
        BatchShader::with_level(level, model, material, scene)?
            .shade_rgba8(positions, normals, out),
    )
}

/// Shades array-of-structs input, the layout a G-buffer or a mesh keeps: `out[i] = shade(…,
/// positions[i], normals[i]).total()`, as [`shade_batch`] computes it. The elements are any
/// [`AosVec3`]: `Vec3`, `Vec3A`, `[f32; 3]`, or four-wide `Vec4` / `[f32; 4]` texels whose fourth
/// component is ignored.
///
/// The points are moved into structure-of-arrays form 1024 at a time on the stack (36 KiB with
/// the output, no allocation: mind a small thread stack), shaded by [`shade_batch`]'s kernel and
/// written back, so a caller needs no copy of its arrays. docs/performance.md measures it against
/// copying into and out of `Vec`s around one [`shade_batch`] call: slower at 4096 points (each
/// chunk pays the kernel's entry), faster over a frame of 2²⁰ points, where the copies leave the
/// cache.
///
/// **Domain:** as [`shade_batch`]. **Returns** the number of points shaded: the shortest of the
/// three slices (debug builds assert they are equal); entries past it are untouched.
/// **Degenerate input:** as [`shade_batch`]. The results are [`shade_batch`]'s, bit for bit.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::new(1.0, 0.5, 0.0), 32.0)?;
/// let positions = [Vec3::ZERO; 2];
/// let normals = [Vec3::Z, -Vec3::Z];
/// let mut out = [Vec3::NAN; 2];
/// let n = phong::shade_batch_aos(&Phong::default(), &material, &scene, &positions, &normals, &mut out);
/// assert_eq!(n, 2);
/// assert_eq!(out, [Vec3::new(1.0, 0.5, 0.0), Vec3::ZERO]);
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_batch_aos<M: BatchModel, L: BatchLight, P: AosVec3, N: AosVec3>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: &[P],
    normals: &[N],
    out: &mut [Vec3],
) -> usize {
    BatchShader::new(model, material, scene).shade_aos(positions, normals, out)
}

/// [`shade_batch_aos`] into an 8-bit RGBA frame: `out[i] = [r, g, b, 255]` as
/// [`shade_batch_rgba8`] writes it, from array-of-structs input (a G-buffer's positions and
/// normals).
///
/// **Domain, returns, degenerate input:** as [`shade_batch_aos`]; the levels are
/// [`linear_to_srgb8`](crate::linear_to_srgb8) of its output.
pub fn shade_batch_aos_rgba8<M: BatchModel, L: BatchLight, P: AosVec3, N: AosVec3>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: &[P],
    normals: &[N],
    out: &mut [[u8; 4]],
) -> usize {
    BatchShader::new(model, material, scene).shade_aos_rgba8(positions, normals, out)
}

/// Points per chunk of the array-of-structs entry points: a multiple of the kernel's 16 lanes, so
/// the chunks group the points into vectors as one whole call would. Each chunk pays the kernel's
/// entry. Measured at 4096 points from `&[Vec3]`: 273 Mpoints/s with 512-point chunks and 301
/// with 1024 (copying into `Vec`s around one `shade_batch` call: 305). At 1024 the buffers take
/// 36 KiB of stack.
const CHUNK: usize = 1024;

/// Shades `min` of the lengths chunk by chunk, transposing each into stack arrays: `shade(pos,
/// nor, out, rgb)` shades a chunk's points into its part of `out`, with three stack slices of the
/// chunk's length to use for linear colours; returns the count.
#[inline(always)]
fn chunked_aos<P: AosVec3, N: AosVec3, T>(
    positions: &[P],
    normals: &[N],
    out: &mut [T],
    shade: impl Fn(SoaVec3<'_>, SoaVec3<'_>, &mut [T], [&mut [f32]; 3]),
) -> usize {
    debug_assert!(
        positions.len() == normals.len() && out.len() == positions.len(),
        "shade_batch_aos*: positions, normals and the output must have the same length"
    );
    let n = positions.len().min(normals.len()).min(out.len());
    let mut soa = [[0.0f32; CHUNK]; 9];
    for (k, out) in out[..n].chunks_mut(CHUNK).enumerate() {
        let start = k * CHUNK;
        let len = out.len();
        let [px, py, pz, nx, ny, nz, r, g, b] = &mut soa;
        for (j, (p, q)) in positions[start..start + len]
            .iter()
            .zip(&normals[start..start + len])
            .enumerate()
        {
            [px[j], py[j], pz[j]] = p.xyz();
            [nx[j], ny[j], nz[j]] = q.xyz();
        }
        let pos = SoaVec3::new(&px[..len], &py[..len], &pz[..len]);
        let nor = SoaVec3::new(&nx[..len], &ny[..len], &nz[..len]);
        shade(pos, nor, out, [&mut r[..len], &mut g[..len], &mut b[..len]]);
    }
    n
}

/// The maximal runs of `true` in `coverage`, as index ranges, in order.
fn covered_runs(coverage: &[bool]) -> impl Iterator<Item = core::ops::Range<usize>> + '_ {
    let mut i = 0;
    core::iter::from_fn(move || {
        let start = i + coverage[i..].iter().position(|&c| c)?;
        let end = coverage[start..]
            .iter()
            .position(|&c| !c)
            .map_or(coverage.len(), |e| start + e);
        i = end;
        Some(start..end)
    })
}

/// Whether the six input slices and an output of `out_len` have one length.
fn same_lengths(positions: SoaVec3<'_>, normals: SoaVec3<'_>, out_len: usize) -> bool {
    let n = positions.x.len();
    [
        positions.y.len(),
        positions.z.len(),
        normals.x.len(),
        normals.y.len(),
        normals.z.len(),
        out_len,
    ]
    .iter()
    .all(|&m| m == n)
}
