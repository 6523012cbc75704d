//! The shading-rate advisor: a proven bound on how far Gouraud (per-vertex) shading of a triangle
//! can be from per-pixel shading, so a renderer can shade per vertex wherever that is invisible.
//!
//! **What is compared.** Inside a triangle with vertices `Pᵢ`, unit vertex normals `nᵢ` and
//! barycentric coordinates `b` (perspective-correct, so `b` are the coordinates of the surface
//! point itself), per-pixel ("Phong") shading evaluates the shaded value `F` at the point
//! `P(b) = Σ bᵢPᵢ` with the normal `normalize(Σ bᵢnᵢ)`; Gouraud shading evaluates `F` at the three
//! vertices and interpolates, `G(b) = Σ bᵢ F(Pᵢ)`. The advisor bounds `max_b |G(b) − F(b)|`.
//!
//! **How.** Along any straight unit-speed path in the triangle, every ingredient of `F` (the
//! cosines `N·L`, `N·V`, `L·V`, the distance to the light, the attenuation, the spot cone, the
//! lobe powers) gets a *jet*: an interval holding its values and bounds on its first and second
//! derivatives, propagated by the product and chain rules. If `F` has a Lipschitz gradient with
//! constant `M₂` (a bound on `|F''|`), Taylor's theorem around the pixel gives
//!
//! ```text
//! |G(b) − F(b)| ≤ ½ · M₂ · Σ bᵢ‖Pᵢ − P(b)‖² ≤ ½ · M₂ · r²
//! ```
//!
//! with `r` the radius of the triangle's smallest enclosing circle. Where `F` has a kink or a jump
//! inside the triangle (a terminator, Phong's cut-off at `s < 2`, a step gate, a spot cone edge), the
//! bound falls back to the width of `F`'s interval: `G` and `F` both lie in it. The result is the
//! smaller of the two, plus a rounding allowance, taken for the ambient, diffuse and specular parts
//! of each light apart. The rounding allowance is the evaluation's own: each jet also carries how
//! far an `f32` evaluation of its function can be from the exact value (every cosine off by an
//! absolute `η`, the distance by its rounding, the lobe power by its pow strategy's error), and
//! the intervals are widened by the same amounts, so both the Taylor and the width bound hold for
//! the computed shadings (see [`gouraud_error_bound`]). A directional light's diffuse part has an exact form,
//! `(Σ bᵢcᵢ)(1 − 1/‖Σ bᵢnᵢ‖)` plus a Jensen gap at the terminator, and gets the sharper bound
//! `max(B(1/μ − 1), AB/(A+B))` from it. The derivation with every constant is in
//! docs/derivations.md, section "Shading-rate bound".
//!
//! **Where the code is.** `jet.rs`: the jet type, its arithmetic and the cosines; `falloff.rs`:
//! the attenuation factor as a jet of the distance; `triangle.rs`: the triangle's geometry (its
//! enclosing circle, the spread of its normals, the cosines' rounding allowance);
//! `light_bound.rs`: one light's bound from those; this file: the public entry points, which sum
//! the lights.

use glam::Vec3;

use crate::BatchModel;
use crate::light::Light;
use crate::material::Material;
use crate::model::Model;
use crate::normalize_or_zero;
use crate::shade::Scene;

mod falloff;
mod jet;
mod light_bound;
mod triangle;

use light_bound::light_bound;
use triangle::{Triangle, distance_to_triangle, enclosing_radius_squared, normal_jet};

/// An upper bound on how far Gouraud (per-vertex) shading of a triangle can be from per-pixel
/// shading of the same lobes, anywhere inside the triangle, per colour channel of the linear
/// result of [`shade`](crate::shade).
///
/// ```text
/// bound ≥ max over the triangle of | Σ bᵢ·I(Pᵢ, nᵢ) − I(Σ bᵢPᵢ, normalize(Σ bᵢnᵢ)) |
///        (each channel of the linear colour I = shade(…).total())
///
/// per light and part:  min( width of the part's interval ,  ½ · M₂ · r² ) + rounding
/// directional diffuse:  Kd·Ld · max( B·(1/μ − 1) , AB/(A+B) )  if smaller
/// ```
///
/// `r` is the radius of the triangle's smallest enclosing circle and `M₂` a bound on the second
/// derivative of the light's contribution along any straight path in the triangle, built from the
/// spread of the normals (`κ = ‖∂n/∂P‖`, `μ = min ‖Σ bᵢnᵢ‖`), the distances to the light and the
/// viewer, the attenuation and spot factors and the lobe exponent; where the contribution has a kink
/// or a jump inside the triangle only the interval width is used. For a directional light's
/// diffuse part, `B` and `A` are the largest positive and negative vertex values of `N·L` and
/// `μ = min ‖Σ bᵢnᵢ‖`. The parts (the light's ambient, diffuse and specular) and the lights add
/// their bounds; the scene's ambient and the emission are constant and add nothing. Derivation in
/// docs/derivations.md, section "Shading-rate bound".
///
/// **Domain:** `positions` finite; `normals` the vertex normals the renderer interpolates (they
/// are normalised here, and per-pixel shading is assumed to interpolate these unit normals with
/// the same, perspective-correct, barycentric weights as Gouraud interpolates colours). The
/// material's constant colours are used: per-pixel texture lookups are not covered. Any of the
/// crate's models, gates, normalisations, pow strategies, lights and attenuation forms.
///
/// **Returns** a finite value `≥ 0` (saturated at `f32::MAX`). It bounds the difference of the
/// two shadings as [`shade`](crate::shade) computes them in `f32`, with the barycentric point and
/// the interpolated normal `Σ bᵢnᵢ` formed in `f32` too: besides the exact-arithmetic bound above
/// it allows, per light and part, for
///
/// - every cosine `shade` computes being off by up to
///   `η = (8 + 6/μ)·2⁻²⁴ + 3·2⁻²⁴·max‖Pᵢ‖·(1/d_light + 1/d_viewer)` (`d` the distance from the
///   triangle to a point light or an eye; the term is 0 for directions). This is an *absolute*
///   error: a cosine near 0 formed from terms near ±1, e.g. a grazing light, is off by a few
///   `2⁻²⁴` whatever its own size. The part's sensitivity to it is carried alongside its
///   derivatives;
/// - the distance to a point light being off by `3·2⁻²⁴·max‖Pᵢ‖ + 2·2⁻²⁴·d`;
/// - the model's pow strategy: its lobe is within
///   [`PowStrategy::max_relative_error`](crate::PowStrategy::max_relative_error) of `x^s`,
///   relative to `max(x^s, 2⁻²⁴)` (the approximate strategies' flush of tiny lobes to 0
///   included);
/// - `(32 + 4s)` ulps of the light's largest contribution for the products and sums.
///
/// **Degenerate input:** a zero-area triangle, normals that cancel inside the triangle, the light
/// or the eye on the triangle: the bound falls back to the interval width of each light's
/// contribution (still a bound, rarely small). A light that cannot reach the triangle (outside a
/// spot cone, beyond a windowed attenuation's radius, or below every point of it with a gated
/// model) gives 0.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::new(0.0, 0.0, 1.0), LightColors::try_from_strengths(Vec3::ONE, 0.0, 0.8, 0.5)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
/// let p = [Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.1, 0.0, 1.0), Vec3::new(0.0, 0.1, 1.0)];
/// // A flat triangle, a directional light and a distant viewer: N, L, V constant, so exact.
/// let flat = phong::shading_rate::gouraud_error_bound(&Phong::default(), &material, &scene, p, [Vec3::Z; 3]);
/// assert!(flat < 1e-3);
/// // The same triangle with normals spread by 45°, as on a very coarse sphere, under the highlight.
/// let curved = [Vec3::Z, Vec3::new(1.0, 0.0, 1.0).normalize(), Vec3::new(0.0, 1.0, 1.0).normalize()];
/// assert!(phong::shading_rate::gouraud_error_bound(&Phong::default(), &material, &scene, p, curved) > 0.1);
/// # Ok::<(), phong::PhongError>(())
/// ```
#[must_use]
pub fn gouraud_error_bound<M, L>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: [Vec3; 3],
    normals: [Vec3; 3],
) -> f32
where
    M: BatchModel,
    L: Copy + Into<Light>,
{
    let model: Model = (*model).into();
    let n = normals.map(normalize_or_zero);
    let tri = Triangle {
        p: positions,
        n,
        r2: enclosing_radius_squared(positions),
        mu: distance_to_triangle(Vec3::ZERO, n),
        normal: normal_jet(positions, n),
        pmax: positions
            .iter()
            .map(|q| crate::length(*q))
            .fold(0.0, f32::max),
    };
    // The constant terms are interpolated exactly but for rounding: a few ulps of their size.
    let constant = material.emission() + material.ambient() * scene.ambient.max(Vec3::ZERO);
    let mut total = 16.0 * f32::EPSILON * constant.max_element().max(0.0);
    for light in scene.lights {
        let light: Light = (*light).into();
        total += light_bound(&model, material, &light, scene.viewer, &tri);
    }
    if total.is_finite() { total } else { f32::MAX }
}

/// Whether Gouraud (per-vertex) shading of this triangle stays within `tolerance` of per-pixel
/// shading everywhere inside it, per channel of the linear colour: [`gouraud_error_bound`]` ≤
/// tolerance`.
///
/// ```text
/// gouraud_within_tolerance = gouraud_error_bound(…) ≤ tolerance
/// ```
///
/// A `true` answer is a guarantee (see the bound's domain); a `false` one only means the bound is
/// not small enough. Tolerances are in linear units; for 8-bit output, `2/255` keeps the two
/// shadings within two steps before encoding. **Degenerate input:** a NaN or negative tolerance
/// gives `false`.
///
/// ```
/// use glam::Vec3;
/// use phong::{BlinnPhong, DirectionalLight, LightColors, Material, Scene, Viewer};
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let m = Material::try_from_color(Vec3::ONE, 16.0)?;
/// let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
/// // Facing away from the light: nothing but (constant) ambient.
/// let away = [-Vec3::Z; 3];
/// assert!(phong::shading_rate::gouraud_within_tolerance(&BlinnPhong::default(), &m, &scene, p, away, 2.0 / 255.0));
/// # Ok::<(), phong::PhongError>(())
/// ```
#[must_use]
pub fn gouraud_within_tolerance<M, L>(
    model: &M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: [Vec3; 3],
    normals: [Vec3; 3],
    tolerance: f32,
) -> bool
where
    M: BatchModel,
    L: Copy + Into<Light>,
{
    tolerance >= 0.0 && gouraud_error_bound(model, material, scene, positions, normals) <= tolerance
}
