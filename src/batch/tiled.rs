//! Many lights over a G-buffer: each tile of the image shaded with only the lights that reach it.

use glam::Vec3;

use super::batch_shader::BatchShader;
use super::covered_runs;
use super::gbuffer::GBuffer;
use super::level::{Level, UnsupportedLevel};
use super::prepare::{BatchLight, BatchModel, LaneLight};
use super::soa::SoaRgb;
use crate::attenuation::Attenuation;
use crate::material::Material;
use crate::shade::Scene;

/// How [`shade_gbuffer_tiled`] cuts the G-buffer into tiles and which lights it drops per tile.
///
/// The G-buffer is an image of `width` pixels per row, rows one after another (point
/// `y · width + x`); a tile is `tile × tile` pixels (smaller at the right and bottom edges).
///
/// **Threshold:** a point or spot light is left out of a tile when its attenuation factor at the
/// tile's nearest point (the distance from the light to the box around the tile's covered
/// positions) is below `threshold`: every factor is non-increasing in the distance, so at every
/// point of the tile the light's factor is below `threshold` too (to the rounding of that
/// distance). Directional lights are never left out. A light left out changes a channel of a
/// point by less than
///
/// ```text
/// threshold · ( Ka·La + Kd·Ld·diffuse scale + Ks·Ls·specular scale )
/// ```
///
/// (the scales are 1 for classic lobes; see [`Normalization`](crate::Normalization)), so for 8-bit
/// output with colours of order 1 a threshold of `0.5 / 255` over the number of lights that may
/// be dropped at once keeps every pixel within half a level. `threshold ≤ 0` (or NaN) keeps
/// every light: the output is then [`shade_gbuffer`](crate::shade_gbuffer)'s, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileCulling {
    /// Pixels per row of the G-buffer.
    pub width: usize,
    /// The side of a tile in pixels (16 or 32 are typical).
    pub tile: usize,
    /// The attenuation factor below which a light is left out of a tile.
    pub threshold: f32,
}

/// A tile's points in a G-buffer of `width` points a row: per row `y` of `rows`, the points
/// `y·width + columns`, clipped to the first `n`, and of those only the covered ones.
#[derive(Clone)]
pub(crate) struct TileSpans<'a> {
    pub(crate) rows: core::ops::Range<usize>,
    pub(crate) width: usize,
    pub(crate) columns: core::ops::Range<usize>,
    pub(crate) n: usize,
    pub(crate) coverage: Option<&'a [bool]>,
}

impl<'a> TileSpans<'a> {
    /// The runs of points, in increasing order.
    pub(crate) fn runs(self) -> impl Iterator<Item = core::ops::Range<usize>> + 'a {
        let TileSpans {
            rows,
            width,
            columns,
            n,
            coverage,
        } = self;
        rows.flat_map(move |y| {
            let row = y * width;
            let span = (row + columns.start).min(n)..(row + columns.end).min(n);
            let (whole, covered) = match coverage {
                Some(c) => (
                    None,
                    Some(
                        covered_runs(&c[span.clone()])
                            .map(move |r| span.start + r.start..span.start + r.end),
                    ),
                ),
                None => (Some(span), None),
            };
            whole.into_iter().chain(covered.into_iter().flatten())
        })
    }
}

/// [`shade_gbuffer`](crate::shade_gbuffer) for scenes with many lights: per tile of the image
/// (see [`TileCulling`]), the lights whose factor cannot reach `culling.threshold` anywhere in
/// the tile are left out, as tiled deferred renderers cull lights per screen tile.
///
/// ```text
/// out[i] = shade_gbuffer of point i with the lights that reach i's tile
/// ```
///
/// **Domain:** as [`shade_gbuffer`](crate::shade_gbuffer); `scratch` holds each tile's light list
/// and needs at least `scene.lights.len()` entries (no allocation: the call works without
/// `alloc`). **Returns** the number of points shaded, as `shade_gbuffer`. **Falls back** to
/// shading every light at every point (no culling) when `scratch` is too short (debug builds
/// assert), when `culling.width` or `culling.tile` is 0, or when the G-buffer has per-light
/// visibility planes (their layout follows `scene.lights`, not a tile's list). The coverage mask
/// is honoured: uncovered points are neither read nor written, and they do not widen a tile's
/// box. **Error** against `shade_gbuffer`: the bound in [`TileCulling`]'s docs per light left
/// out, plus the rounding of a sum over fewer lights.
///
/// ```
/// use glam::Vec3;
/// use phong::{Attenuation, GBuffer, LightColors, Material, Phong, PointLight, Scene, SoaRgb, SoaVec3, TileCulling, Viewer};
///
/// let lamp = |x: f32| PointLight::try_new(Vec3::new(x, 0.0, 0.5), Attenuation::try_inverse_square(1.0).unwrap(),
///     LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO).unwrap()).unwrap();
/// let lights = [lamp(0.0), lamp(100.0)]; // the second is far from every pixel
/// let scene = Scene { lights: &lights, ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
/// // A 4 × 2 image on the plane z = 0, facing the lamps.
/// let xs = [0.0, 1.0, 2.0, 3.0, 0.0, 1.0, 2.0, 3.0];
/// let ys = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
/// let (zero, one) = ([0.0; 8], [1.0; 8]);
/// let g = GBuffer::new(SoaVec3::new(&xs, &ys, &zero), SoaVec3::new(&zero, &zero, &one));
/// let culling = TileCulling { width: 4, tile: 2, threshold: 1e-3 };
/// let mut scratch = lights;
/// let (mut r, mut gr, mut b) = ([0.0; 8], [0.0; 8], [0.0; 8]);
/// let n = phong::shade_gbuffer_tiled(&Phong::default(), &material, &scene, &g, culling,
///     &mut scratch, SoaRgb::new(&mut r, &mut gr, &mut b));
/// assert_eq!(n, 8);
/// assert!((r[0] - 4.0).abs() < 1e-5); // 1/0.5² from the near lamp; the far one adds < 1e-4
/// # Ok::<(), phong::PhongError>(())
/// ```
pub fn shade_gbuffer_tiled<M: BatchModel, L: BatchLight + Copy>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    culling: TileCulling,
    scratch: &mut [L],
    out: SoaRgb<'_>,
) -> usize {
    tiled(
        Level::detect(),
        model,
        material,
        scene,
        gbuffer,
        culling,
        scratch,
        out,
    )
}

/// [`shade_gbuffer_tiled`] at a chosen instruction-set [`Level`]; [`UnsupportedLevel`] (nothing
/// written) when this CPU or build cannot run it.
#[expect(
    clippy::too_many_arguments,
    reason = "shade_gbuffer_tiled's arguments and the level, in the order of the other _with_level functions"
)]
pub fn shade_gbuffer_tiled_with_level<M: BatchModel, L: BatchLight + Copy>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    culling: TileCulling,
    scratch: &mut [L],
    out: SoaRgb<'_>,
) -> Result<usize, UnsupportedLevel> {
    if !level.is_supported() {
        return Err(UnsupportedLevel(level));
    }
    Ok(tiled(
        level, model, material, scene, gbuffer, culling, scratch, out,
    ))
}

/// Whether `light` can reach `threshold` anywhere in the box `[lo, hi]`: directional and
/// ambient-only lights always; a point or spot light when its factor at the box's nearest point
/// is at least `threshold` (the spot cone, at most 1, is not used to cull).
fn reaches<L: BatchLight>(light: &L, lo: Vec3, hi: Vec3, threshold: f32) -> bool {
    let (position, attenuation) = match light.lane_light() {
        Some(LaneLight::Point {
            position,
            coefficients: [constant, linear, quadratic],
        }) => (
            position,
            Attenuation::Polynomial {
                constant,
                linear,
                quadratic,
            },
        ),
        Some(LaneLight::Falloff {
            position,
            attenuation,
            ..
        }) => (position, attenuation),
        _ => return true,
    };
    let nearest = position.clamp(lo, hi);
    // `!(x < t)`: a NaN threshold keeps the light.
    !(attenuation.factor(crate::length(nearest - position)) < threshold)
}

#[expect(
    clippy::too_many_arguments,
    reason = "shade_gbuffer_tiled_with_level's arguments, passed on"
)]
fn tiled<M: BatchModel, L: BatchLight + Copy>(
    level: Level,
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    gbuffer: &GBuffer<'_>,
    culling: TileCulling,
    scratch: &mut [L],
    mut out: SoaRgb<'_>,
) -> usize {
    let lights = scene.lights.len();
    debug_assert!(
        scratch.len() >= lights,
        "shade_gbuffer_tiled: scratch needs one entry per light ({lights})"
    );
    let TileCulling {
        width,
        tile,
        threshold,
    } = culling;
    if scratch.len() < lights || width == 0 || tile == 0 || gbuffer.visibility.is_some() {
        let shader = BatchShader::at(level, model, material, scene);
        return super::gbuffer::run(&shader, gbuffer, out);
    }
    let (inputs, n) = gbuffer.inputs(lights, material);
    debug_assert!(
        out.len() == n,
        "shade_gbuffer_tiled: the output must have the G-buffer's length"
    );
    let n = n.min(out.len());
    let (pos, nor) = gbuffer.prefix(n);
    let covered = |i: usize| gbuffer.coverage.is_none_or(|c| c[i]);
    let rows = n.div_ceil(width);
    // A row holds at most `n` points, and every sum below stays at most `n + width` (no overflow
    // for any `width` and `tile`).
    for ty in (0..rows).step_by(tile) {
        for tx in (0..width.min(n)).step_by(tile) {
            // The tile's row spans, clipped to the image and to the points there are.
            let spans = (ty..rows.min(ty.saturating_add(tile))).map(|y| {
                let row = y * width;
                (row + tx).min(n)..(row + width.min(tx.saturating_add(tile))).min(n)
            });
            let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
            for span in spans.clone() {
                for i in span.filter(|&i| covered(i)) {
                    let p = Vec3::new(pos.x[i], pos.y[i], pos.z[i]);
                    (lo, hi) = (lo.min(p), hi.max(p));
                }
            }
            if !(lo.x <= hi.x) {
                continue; // nothing covered
            }
            let mut k = 0;
            for light in scene.lights {
                if reaches(light, lo, hi, threshold) {
                    scratch[k] = *light;
                    k += 1;
                }
            }
            let tile_scene = Scene {
                lights: &scratch[..k],
                ..*scene
            };
            let shading = BatchShader::at(level, model, material, &tile_scene);
            // The tile's rows (or their covered runs) in one kernel call.
            let tile_spans = TileSpans {
                rows: ty..rows.min(ty.saturating_add(tile)),
                width,
                columns: tx..width.min(tx.saturating_add(tile)),
                n,
                coverage: gbuffer.coverage,
            };
            shading.shade_spans(pos, nor, &inputs, &mut out, tile_spans);
        }
    }
    n
}
