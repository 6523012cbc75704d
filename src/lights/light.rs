//! Light sources: directional, point and spot, and the colours they carry.
//!
//! Each kind is its own type implementing [`LightSource`], so shading code that is generic over the
//! light type compiles a scene of directional lights with no distance or attenuation code at all.
//! [`Light`] is the enum over all three, for scenes that mix them.

use glam::Vec3;

use crate::attenuation::{Attenuation, FlatAttenuation};
use crate::error::{self, PhongError};
use crate::math;
use crate::normalize::{
    Scaled, direction_and_distance, direction_and_distance_full_scaled,
    direction_and_distance_scaled,
};
use crate::pow::lobe_pow;

/// The three colours a light contributes: to the ambient, diffuse and specular terms.
///
/// ```text
/// ambient term  += La ⊙ Ka · f,   diffuse term += Ld ⊙ Kd · f · diffuse lobe,
/// specular term += Ls ⊙ Ks · f · specular lobe,      f = attenuation × spot factor
/// ```
///
/// **Domain:** every channel finite and `≥ 0` (checked by [`try_new`](Self::try_new)).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub struct LightColors {
    ambient: Vec3,
    diffuse: Vec3,
    specular: Vec3,
}

/// Maps NaN and negatives to 0 and saturates at `f32::MAX`: the release-build fallback of the
/// unchecked constructors.
#[inline]
pub(crate) fn sanitize_colour(c: Vec3) -> Vec3 {
    Vec3::new(
        math::clamp_or_lo(c.x, 0.0, math::MAX),
        math::clamp_or_lo(c.y, 0.0, math::MAX),
        math::clamp_or_lo(c.z, 0.0, math::MAX),
    )
}

impl LightColors {
    /// A light that contributes nothing.
    pub const BLACK: Self = LightColors {
        ambient: Vec3::ZERO,
        diffuse: Vec3::ZERO,
        specular: Vec3::ZERO,
    };

    /// Checked: every channel of the three colours finite and `≥ 0`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{LightColors, PhongError};
    /// let err = LightColors::try_new(Vec3::ZERO, Vec3::new(1.0, f32::NAN, 0.0), Vec3::ONE);
    /// assert!(matches!(err, Err(PhongError::NonFinite { field: "light.diffuse.y", .. })));
    /// ```
    pub fn try_new(ambient: Vec3, diffuse: Vec3, specular: Vec3) -> Result<Self, PhongError> {
        Ok(LightColors {
            ambient: error::colour(
                ["light.ambient.x", "light.ambient.y", "light.ambient.z"],
                ambient,
            )?,
            diffuse: error::colour(
                ["light.diffuse.x", "light.diffuse.y", "light.diffuse.z"],
                diffuse,
            )?,
            specular: error::colour(
                ["light.specular.x", "light.specular.y", "light.specular.z"],
                specular,
            )?,
        })
    }

    /// Unchecked: debug builds assert the domain; release builds map NaN and negative channels to 0.
    #[must_use]
    pub fn new(ambient: Vec3, diffuse: Vec3, specular: Vec3) -> Self {
        debug_assert!(
            Self::try_new(ambient, diffuse, specular).is_ok(),
            "LightColors::new: {:?}",
            Self::try_new(ambient, diffuse, specular)
        );
        LightColors {
            ambient: sanitize_colour(ambient),
            diffuse: sanitize_colour(diffuse),
            specular: sanitize_colour(specular),
        }
    }

    /// One light colour split by strengths, as in LearnOpenGL's basic-lighting shader.
    ///
    /// ```text
    /// La = ambient_strength · C,   Ld = diffuse_strength · C,   Ls = specular_strength · C
    /// ```
    ///
    /// Checked like [`try_new`](Self::try_new); a negative strength is reported on the colour it
    /// produces.
    ///
    /// ```
    /// use glam::Vec3;
    /// let c = phong::LightColors::try_from_strengths(Vec3::ONE, 0.1, 1.0, 0.5).unwrap();
    /// assert_eq!(c.ambient(), Vec3::splat(0.1));
    /// assert_eq!(c.specular(), Vec3::splat(0.5));
    /// ```
    pub fn try_from_strengths(
        color: Vec3,
        ambient_strength: f32,
        diffuse_strength: f32,
        specular_strength: f32,
    ) -> Result<Self, PhongError> {
        error::colour(["light.color.x", "light.color.y", "light.color.z"], color)?;
        error::non_negative("light.ambient_strength", ambient_strength)?;
        error::non_negative("light.diffuse_strength", diffuse_strength)?;
        error::non_negative("light.specular_strength", specular_strength)?;
        Self::try_new(
            color * ambient_strength,
            color * diffuse_strength,
            color * specular_strength,
        )
    }

    /// A light of colour `C` and power `P` (a multiplier), with no ambient part: the
    /// parametrisation of the Blinn-Phong shader on Wikipedia.
    ///
    /// ```text
    /// La = 0,   Ld = Ls = P · C
    /// ```
    ///
    /// **This is where that shader's power goes.** Its falloff `P·C / d²` is this light with
    /// [`Attenuation::try_inverse_square(1.0)`](Attenuation::try_inverse_square): the power is
    /// applied once, here, and the attenuation's own `power` stays 1. Putting `P` in both applies
    /// it twice.
    ///
    /// Checked: `C` and `P` finite and `≥ 0`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Attenuation, LightColors, LightSource, PointLight};
    /// // Wikipedia's Blinn-Phong shader: lightColor = white, lightPower = 40.
    /// let lamp = PointLight::try_new(
    ///     Vec3::new(0.0, 2.0, 0.0),
    ///     Attenuation::try_inverse_square(1.0)?,
    ///     LightColors::try_from_power(Vec3::ONE, 40.0)?,
    /// )?;
    /// let s = lamp.sample(Vec3::ZERO);
    /// assert_eq!(lamp.colors().diffuse() * s.factor, Vec3::splat(40.0 / 4.0)); // P·C / d²
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    pub fn try_from_power(color: Vec3, power: f32) -> Result<Self, PhongError> {
        error::colour(["light.color.x", "light.color.y", "light.color.z"], color)?;
        error::non_negative("light.power", power)?;
        Self::try_new(Vec3::ZERO, color * power, color * power)
    }

    /// `La`, the colour added to the ambient term.
    #[must_use]
    #[inline]
    pub fn ambient(&self) -> Vec3 {
        self.ambient
    }
    /// `Ld`, the colour of the diffuse term.
    #[must_use]
    #[inline]
    pub fn diffuse(&self) -> Vec3 {
        self.diffuse
    }
    /// `Ls`, the colour of the specular term.
    #[must_use]
    #[inline]
    pub fn specular(&self) -> Vec3 {
        self.specular
    }
}

/// A light's three colours by name, for construction that cannot be misordered (see
/// [`MaterialParams`](crate::MaterialParams)). Checked by `LightColors::try_from`, with the checks of
/// [`LightColors::try_new`]; `Default` is black.
///
/// ```
/// use glam::Vec3;
/// use phong::{LightColors, LightColorsParams};
/// let lamp = LightColors::try_from(LightColorsParams {
///     diffuse: Vec3::splat(0.8),
///     specular: Vec3::ONE,
///     ..LightColorsParams::default()
/// })?;
/// assert_eq!(lamp.ambient(), Vec3::ZERO);
/// # Ok::<(), phong::PhongError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightColorsParams {
    /// `La`, finite and `≥ 0` per channel.
    pub ambient: Vec3,
    /// `Ld`, finite and `≥ 0` per channel.
    pub diffuse: Vec3,
    /// `Ls`, finite and `≥ 0` per channel.
    pub specular: Vec3,
}

impl TryFrom<LightColorsParams> for LightColors {
    type Error = PhongError;
    /// [`LightColors::try_new`] of the named colours.
    fn try_from(p: LightColorsParams) -> Result<Self, PhongError> {
        LightColors::try_new(p.ambient, p.diffuse, p.specular)
    }
}

/// What a light delivers at one surface point: where it comes from and how strongly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the point to the light, or the zero vector when the point is at the
    /// light's position (no direction exists; diffuse and specular are then 0).
    pub direction: Vec3,
    /// Attenuation × spot factor: finite and `≥ 0`.
    pub factor: f32,
}

/// A light that can be sampled at a surface point. Implemented by every light kind.
pub trait LightSource {
    /// The light's ambient, diffuse and specular colours.
    fn colors(&self) -> &LightColors;

    /// The direction to the light and the attenuation × spot factor at point `p`.
    ///
    /// **Domain:** any finite `p`. **Returns** a unit or zero direction and a finite factor `≥ 0`.
    fn sample(&self, p: Vec3) -> LightSample;

    /// An upper bound of [`sample`](Self::sample)`(p).factor` over every point `p`, or `+∞` when
    /// none is known (the default).
    ///
    /// [`Shader`](crate::Shader) uses it once, when prepared: when the bounds show that no sum
    /// of the shading equation can come near `f32::MAX`, it skips the per-point saturation.
    ///
    /// **Contract:** like [`sample`](Self::sample)'s finite factor, this is a promise the
    /// implementation makes: `sample(p).factor ≤ max_factor()` for every `p`. A light type outside
    /// this crate can leave the default (its points are then saturated, as always); a bound that
    /// is too small voids the no-overflow guarantee for scenes with colours near `f32::MAX`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Attenuation, LightColors, LightSource, PointLight};
    /// let lamp = PointLight::try_new(Vec3::Y, Attenuation::polynomial(1.0, 0.09, 0.032), LightColors::BLACK)?;
    /// assert_eq!(lamp.max_factor(), 1.0); // the factor at the light itself
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    #[inline]
    fn max_factor(&self) -> f32 {
        f32::INFINITY
    }

    /// The light as [`FlatLight`]'s one formula, for [`Shader`](crate::Shader)'s one-light path;
    /// `None` (the default, and every light outside this crate) keeps [`sample`](Self::sample).
    #[doc(hidden)]
    #[inline]
    fn flat(&self) -> Option<FlatLight> {
        None
    }

    /// [`sample`](Self::sample), and the offset to the light before its normalisation, times a
    /// power of two, with its squared length: what [`Shader`](crate::Shader)'s Phong lobe reads
    /// under [`PowStrategy::Auto`](crate::PowStrategy::Auto), `(R·V)²` from the vectors as they
    /// are, so that it does not wait for the unit direction. The default (every light outside
    /// this crate, and a directional light) gives the unit direction and 1.
    #[doc(hidden)]
    #[inline(always)]
    fn sample_scaled(&self, p: Vec3) -> (LightSample, Vec3, f32) {
        let sample = self.sample(p);
        (sample, sample.direction, 1.0)
    }
}

/// A directional or point light with its falloff as one formula, so a shading loop evaluates it
/// with no branch on its kind (see [`LightSource::flat`]). Only this crate builds one.
#[doc(hidden)]
#[expect(
    unnameable_types,
    reason = "returned by the hidden LightSource::flat hook, which only this crate's lights implement"
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatLight {
    /// A point light's position, or a directional light's unit direction.
    pub(crate) origin: Vec3,
    /// Whether `origin` is a position.
    pub(crate) point: bool,
    pub(crate) attenuation: FlatAttenuation,
}

impl FlatLight {
    /// [`LightSource::sample_scaled`] by the one formula, with the full-range direction and
    /// distance (no range test): the same direction and factor as `sample`, bit for bit wherever
    /// the squared distance neither under- nor overflows `f32` ([`FlatAttenuation`] is
    /// `Attenuation::factor`'s own evaluation), and the offset to the light [`Scaled`] (the unit
    /// direction and 1 for a directional light).
    #[inline(always)]
    pub(crate) fn sample_scaled(&self, p: Vec3) -> (LightSample, Scaled) {
        if self.point {
            let (direction, d, w) = direction_and_distance_full_scaled(self.origin, p);
            let sample = LightSample {
                direction,
                factor: self.attenuation.factor(d),
            };
            (sample, w)
        } else {
            let sample = LightSample {
                direction: self.origin,
                factor: 1.0,
            };
            (sample, Scaled::unit(self.origin))
        }
    }
}

/// A light infinitely far away: one direction everywhere, no attenuation.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub struct DirectionalLight {
    direction: Vec3,
    colors: LightColors,
}

impl DirectionalLight {
    /// Checked: `direction` (from the surface *toward* the light) finite and non-zero; it is
    /// normalised.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{DirectionalLight, LightColors, PhongError};
    /// let sun = DirectionalLight::try_new(Vec3::new(0.0, 2.0, 0.0), LightColors::BLACK).unwrap();
    /// assert_eq!(sun.direction(), Vec3::Y);
    /// assert_eq!(
    ///     DirectionalLight::try_new(Vec3::ZERO, LightColors::BLACK),
    ///     Err(PhongError::ZeroDirection { field: "light.direction" })
    /// );
    /// ```
    pub fn try_new(direction: Vec3, colors: LightColors) -> Result<Self, PhongError> {
        Ok(DirectionalLight {
            direction: error::direction("light.direction", direction)?,
            colors,
        })
    }

    /// Unchecked: `direction` is normalised; a zero or non-finite direction (debug builds assert)
    /// becomes the zero vector, which lights nothing but the ambient term.
    #[must_use]
    pub fn new(direction: Vec3, colors: LightColors) -> Self {
        debug_assert!(
            Self::try_new(direction, colors).is_ok(),
            "DirectionalLight::new: bad direction {direction}"
        );
        DirectionalLight {
            direction: crate::normalize_or_zero(direction),
            colors,
        }
    }

    /// The unit direction toward the light.
    #[must_use]
    #[inline]
    pub fn direction(&self) -> Vec3 {
        self.direction
    }
}

impl LightSource for DirectionalLight {
    #[inline]
    fn flat(&self) -> Option<FlatLight> {
        Some(FlatLight {
            origin: self.direction,
            point: false,
            attenuation: Attenuation::None.flat(),
        })
    }
    #[inline]
    fn colors(&self) -> &LightColors {
        &self.colors
    }
    /// 1: a directional light does not fade.
    #[inline]
    fn max_factor(&self) -> f32 {
        1.0
    }
    /// `L` = the light's direction, factor 1: no distance, no attenuation work.
    #[inline(always)]
    fn sample(&self, _p: Vec3) -> LightSample {
        LightSample {
            direction: self.direction,
            factor: 1.0,
        }
    }
}

/// A light at a point, shining equally in all directions, fading with [`Attenuation`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub struct PointLight {
    position: Vec3,
    attenuation: Attenuation,
    colors: LightColors,
}

impl PointLight {
    /// Checked: a finite position and a valid attenuation ([`Attenuation::validated`]).
    pub fn try_new(
        position: Vec3,
        attenuation: Attenuation,
        colors: LightColors,
    ) -> Result<Self, PhongError> {
        finite_point("light.position", position)?;
        Ok(PointLight {
            position,
            attenuation: attenuation.validated()?,
            colors,
        })
    }

    /// Unchecked (debug builds assert what [`try_new`](Self::try_new) checks).
    #[must_use]
    pub fn new(position: Vec3, attenuation: Attenuation, colors: LightColors) -> Self {
        debug_assert!(
            Self::try_new(position, attenuation, colors).is_ok(),
            "PointLight::new: {:?}",
            Self::try_new(position, attenuation, colors)
        );
        PointLight {
            position,
            attenuation,
            colors,
        }
    }

    /// The light's position.
    #[must_use]
    #[inline]
    pub fn position(&self) -> Vec3 {
        self.position
    }
    /// The light's falloff.
    #[must_use]
    #[inline]
    pub fn attenuation(&self) -> Attenuation {
        self.attenuation
    }
}

impl LightSource for PointLight {
    #[inline]
    fn flat(&self) -> Option<FlatLight> {
        Some(FlatLight {
            origin: self.position,
            point: true,
            attenuation: self.attenuation.flat(),
        })
    }
    #[inline]
    fn colors(&self) -> &LightColors {
        &self.colors
    }
    /// The attenuation at distance 0, where every form is largest.
    #[inline]
    fn max_factor(&self) -> f32 {
        self.attenuation.factor(0.0)
    }
    /// `L = normalize(P_light − p)`, factor = attenuation(‖P_light − p‖).
    #[inline(always)]
    fn sample(&self, p: Vec3) -> LightSample {
        let (direction, d) = direction_and_distance(self.position, p);
        LightSample {
            direction,
            factor: self.attenuation.factor_of_length(d),
        }
    }
    /// The same sample, with the offset by [`direction_and_distance_scaled`] (whose common range
    /// is narrower).
    #[inline(always)]
    fn sample_scaled(&self, p: Vec3) -> (LightSample, Vec3, f32) {
        let (direction, d, w) = direction_and_distance_scaled(self.position, p);
        let sample = LightSample {
            direction,
            factor: self.attenuation.factor_of_length(d),
        };
        (sample, w.w, w.ww)
    }
}

/// A spot light's cone: its half-angle and the exponent that concentrates light toward its axis.
///
/// ```text
/// spot(c) = c^e   if c ≥ cos(cutoff)        c = −L·D, the cosine between the axis and the point
///         = 0     otherwise
/// spot(c) = 1     for every c when cutoff = π (OpenGL's `GL_SPOT_CUTOFF = 180`: not a spot)
/// ```
///
/// Named fields, so the two angles-and-numbers a spot takes cannot be swapped silently:
/// `SpotCone { cutoff: 0.5, exponent: 8.0 }`, or [`SpotCone::degrees`] with
/// [`with_exponent`](Self::with_exponent).
///
/// **Domain:** `cutoff` in radians, in `[0, π/2]` or exactly `π` ([`SpotCone::NONE`]); `exponent`
/// finite and `≥ 0` (`GL_SPOT_EXPONENT`). [`SpotLight::try_with_cone`] checks both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// The cone's half-angle in radians (`GL_SPOT_CUTOFF`, which OpenGL gives in degrees).
    pub cutoff: f32,
    /// The spot exponent `e` (`GL_SPOT_EXPONENT`); 0 lights the whole cone evenly.
    pub exponent: f32,
}

impl SpotCone {
    /// No cone: `cutoff = π`, OpenGL's `GL_SPOT_CUTOFF = 180`, the spot factor is 1 in every
    /// direction and the light acts as a point light.
    pub const NONE: SpotCone = SpotCone {
        cutoff: core::f32::consts::PI,
        exponent: 0.0,
    };

    /// A cone of half-angle `cutoff_degrees`, exponent 0, as OpenGL's `glLightf(GL_SPOT_CUTOFF, …)`
    /// takes it. `180` gives [`SpotCone::NONE`] exactly (the `f32` conversion of 180° would round to
    /// a value just off `π`).
    ///
    /// ```
    /// use phong::SpotCone;
    /// assert_eq!(SpotCone::degrees(180.0), SpotCone::NONE);
    /// assert_eq!(SpotCone::degrees(90.0).cutoff, core::f32::consts::FRAC_PI_2);
    /// let cone = SpotCone::degrees(30.0).with_exponent(8.0);
    /// assert_eq!(cone.exponent, 8.0);
    /// ```
    #[must_use]
    pub fn degrees(cutoff_degrees: f32) -> Self {
        let cutoff = match cutoff_degrees {
            180.0 => core::f32::consts::PI,
            90.0 => core::f32::consts::FRAC_PI_2,
            d => d.to_radians(),
        };
        SpotCone {
            cutoff,
            exponent: 0.0,
        }
    }

    /// The same cone with spot exponent `e` (`spot(c) = c^e` inside the cone). Unchecked here:
    /// [`SpotLight::try_with_cone`] rejects a negative or non-finite `e`.
    #[must_use]
    pub fn with_exponent(self, exponent: f32) -> Self {
        SpotCone { exponent, ..self }
    }

    /// Whether this is OpenGL's "not a spot" (`cutoff = π`).
    #[must_use]
    #[inline]
    pub fn is_none(&self) -> bool {
        self.cutoff == core::f32::consts::PI
    }
}

/// A point light restricted to a cone: OpenGL's fixed-function spot light.
///
/// ```text
/// spot = (−L·D)^e   if −L·D ≥ cos(cutoff)
///      = 0          otherwise
/// spot = 1          if cutoff = π (OpenGL's 180°: not a spot)
/// ```
///
/// `D` is the unit axis the spot shines along (from the light outward), `L` the direction from the
/// surface to the light, `e` the exponent (`GL_SPOT_EXPONENT`) and `cutoff` the half-angle of the cone
/// (`GL_SPOT_CUTOFF`, in radians here, in `[0, π/2]` or exactly `π`); see [`SpotCone`]. Derivation:
/// docs/derivations.md, section "The spot factor".
///
/// A spot light is a [`PointLight`] (position, falloff, colours: [`point`](Self::point)) with a
/// cone; it keeps one, so the point light's checks, getters and sampling are the spot's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// Position, falloff and colours.
    point: PointLight,
    axis: Vec3,
    cutoff: f32,
    // Derived from `cutoff` (serde does not store it).
    cos_cutoff: f32,
    exponent: f32,
}

impl SpotLight {
    /// Checked, with the cone's two numbers positional: `cutoff` (radians) then `exponent`. Prefer
    /// [`try_with_cone`](Self::try_with_cone), whose named [`SpotCone`] cannot be misordered.
    ///
    /// Checks: finite position, non-zero axis, `cutoff ∈ [0, π/2]` radians or exactly `π` (not a
    /// spot), exponent finite `≥ 0`, valid attenuation.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Attenuation, LightColors, LightSource, PhongError, SpotLight};
    /// let spot = SpotLight::try_new(
    ///     Vec3::new(0.0, 5.0, 0.0), -Vec3::Y, 0.5, 2.0, Attenuation::None, LightColors::BLACK,
    /// ).unwrap();
    /// assert_eq!(spot.sample(Vec3::ZERO).factor, 1.0);          // on the axis
    /// assert_eq!(spot.sample(Vec3::new(9.0, 0.0, 0.0)).factor, 0.0); // outside the cone
    /// assert!(matches!(
    ///     SpotLight::try_new(Vec3::ZERO, Vec3::X, 2.0, 1.0, Attenuation::None, LightColors::BLACK),
    ///     Err(PhongError::OutOfRange { field: "light.cutoff", .. })
    /// ));
    /// ```
    pub fn try_new(
        position: Vec3,
        axis: Vec3,
        cutoff: f32,
        exponent: f32,
        attenuation: Attenuation,
        colors: LightColors,
    ) -> Result<Self, PhongError> {
        Self::try_with_cone(
            position,
            axis,
            SpotCone { cutoff, exponent },
            attenuation,
            colors,
        )
    }

    /// Checked, with a named cone: finite position, non-zero axis (normalised here), `cone.cutoff`
    /// in `[0, π/2]` radians or exactly `π` ([`SpotCone::NONE`]), `cone.exponent` finite and `≥ 0`,
    /// valid attenuation. Errors name the field (`light.cutoff`, `light.exponent`, …).
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Attenuation, LightColors, LightSource, SpotCone, SpotLight};
    /// let lamp = SpotLight::try_with_cone(
    ///     Vec3::new(0.0, 5.0, 0.0), -Vec3::Y, SpotCone::degrees(30.0).with_exponent(4.0),
    ///     Attenuation::None, LightColors::BLACK,
    /// )?;
    /// assert_eq!(lamp.sample(Vec3::ZERO).factor, 1.0);
    /// // OpenGL's 180°: no cone, the light reaches behind itself too.
    /// let bulb = SpotLight::try_with_cone(
    ///     Vec3::ZERO, Vec3::X, SpotCone::degrees(180.0), Attenuation::None, LightColors::BLACK,
    /// )?;
    /// assert_eq!(bulb.sample(Vec3::new(-3.0, 0.0, 0.0)).factor, 1.0);
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    pub fn try_with_cone(
        position: Vec3,
        axis: Vec3,
        cone: SpotCone,
        attenuation: Attenuation,
        colors: LightColors,
    ) -> Result<Self, PhongError> {
        // The spot's own checks between the position's and the falloff's, in the fields' order.
        finite_point("light.position", position)?;
        let axis = error::direction("light.axis", axis)?;
        let SpotCone { cutoff, exponent } = cone;
        let half_pi = core::f32::consts::FRAC_PI_2;
        if !cutoff.is_finite() {
            return Err(PhongError::NonFinite {
                field: "light.cutoff",
                value: cutoff,
            });
        }
        if !(0.0..=half_pi).contains(&cutoff) && !cone.is_none() {
            return Err(PhongError::OutOfRange {
                field: "light.cutoff",
                value: cutoff,
                min: 0.0,
                max: half_pi,
            });
        }
        let exponent = error::non_negative("light.exponent", exponent)?;
        Ok(SpotLight {
            point: PointLight::try_new(position, attenuation, colors)?,
            axis,
            cutoff,
            cos_cutoff: cos_cutoff(cutoff),
            exponent,
        })
    }

    /// Unchecked: debug builds assert what [`try_with_cone`](Self::try_with_cone) checks. Release
    /// builds sanitise: a NaN cutoff reads as 0 and any other is clamped to `[0, π/2]` unless it is
    /// `≥ π` (then no cone); a NaN or negative exponent reads as 0 and `+∞` saturates at
    /// `f32::MAX`; a zero or non-finite axis gives a light that reaches no point (spot factor 0);
    /// the position and attenuation are kept as given, as [`PointLight::new`] does (shading is
    /// total for any of them).
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{Attenuation, LightColors, LightSource, SpotCone, SpotLight};
    /// let spot = SpotLight::new(Vec3::Y, -Vec3::Y, SpotCone { cutoff: 0.3, exponent: 1.0 },
    ///     Attenuation::None, LightColors::BLACK);
    /// assert_eq!(spot.sample(Vec3::ZERO).factor, 1.0);
    /// ```
    #[must_use]
    pub fn new(
        position: Vec3,
        axis: Vec3,
        cone: SpotCone,
        attenuation: Attenuation,
        colors: LightColors,
    ) -> Self {
        debug_assert!(
            Self::try_with_cone(position, axis, cone, attenuation, colors).is_ok(),
            "SpotLight::new: {:?}",
            Self::try_with_cone(position, axis, cone, attenuation, colors)
        );
        let pi = core::f32::consts::PI;
        let cutoff = if cone.cutoff >= pi {
            pi
        } else {
            math::clamp_or_lo(cone.cutoff, 0.0, core::f32::consts::FRAC_PI_2)
        };
        let axis = crate::normalize_or_zero(axis);
        SpotLight {
            // Checked by the assertion above (as `PointLight::new` would assert it).
            point: PointLight {
                position,
                attenuation,
                colors,
            },
            axis,
            cutoff,
            // A zero axis has no cone: `−L·D = 0` must never pass, so the threshold is above 1.
            cos_cutoff: if axis == Vec3::ZERO {
                2.0
            } else {
                cos_cutoff(cutoff)
            },
            exponent: math::clamp_or_lo(cone.exponent, 0.0, math::MAX),
        }
    }

    /// The cone: cutoff (radians) and exponent.
    #[must_use]
    #[inline]
    pub fn cone(&self) -> SpotCone {
        SpotCone {
            cutoff: self.cutoff,
            exponent: self.exponent,
        }
    }

    /// The light without its cone: position, falloff and colours.
    #[must_use]
    #[inline]
    pub fn point(&self) -> &PointLight {
        &self.point
    }
    /// The light's position (its [`point`](Self::point)'s).
    #[must_use]
    #[inline]
    pub fn position(&self) -> Vec3 {
        self.point.position()
    }
    /// The unit axis of the cone.
    #[must_use]
    #[inline]
    pub fn axis(&self) -> Vec3 {
        self.axis
    }
    /// The cone's half-angle in radians, in `[0, π/2]`, or `π` for no cone.
    #[must_use]
    #[inline]
    pub fn cutoff(&self) -> f32 {
        self.cutoff
    }
    /// `cos(cutoff)`, clamped to `≥ 0` for a cone (`cos(π/2)` rounds below 0 in `f32`); `−1` for no
    /// cone.
    #[must_use]
    #[inline]
    pub fn cos_cutoff(&self) -> f32 {
        self.cos_cutoff
    }
    /// The spot exponent `e`.
    #[must_use]
    #[inline]
    pub fn exponent(&self) -> f32 {
        self.exponent
    }
    /// The light's falloff (its [`point`](Self::point)'s).
    #[must_use]
    #[inline]
    pub fn attenuation(&self) -> Attenuation {
        self.point.attenuation()
    }

    /// The cone factor for unit `L` (from surface to light), in `[0, 1]`; 0 for a zero `L`; 1 for
    /// every non-zero `L` when there is no cone (`cutoff = π`).
    #[must_use]
    #[inline]
    pub fn spot_factor(&self, l: Vec3) -> f32 {
        let c = -l.dot(self.axis);
        if l == Vec3::ZERO || c < self.cos_cutoff {
            0.0
        } else if self.cos_cutoff < 0.0 {
            1.0
        } else {
            lobe_pow(c.min(1.0), self.exponent)
        }
    }
}

impl SpotLight {
    /// The point light's sample with its factor times [`SpotLight::spot_factor`].
    #[inline(always)]
    fn in_cone(&self, sample: LightSample) -> LightSample {
        let LightSample { direction, factor } = sample;
        let spot = self.spot_factor(direction);
        let factor = if spot > 0.0 {
            (factor * spot).min(math::MAX)
        } else {
            0.0
        };
        LightSample { direction, factor }
    }
}

impl LightSource for SpotLight {
    #[inline]
    fn colors(&self) -> &LightColors {
        self.point.colors()
    }
    /// The point light's (the spot factor is at most 1).
    #[inline]
    fn max_factor(&self) -> f32 {
        self.point.max_factor()
    }
    /// The [`PointLight`]'s sample, its factor times [`SpotLight::spot_factor`].
    #[inline]
    fn sample(&self, p: Vec3) -> LightSample {
        self.in_cone(self.point.sample(p))
    }
    #[inline]
    fn sample_scaled(&self, p: Vec3) -> (LightSample, Vec3, f32) {
        let (sample, w, ww) = self.point.sample_scaled(p);
        (self.in_cone(sample), w, ww)
    }
}

/// Any light kind, for scenes that mix them. Costs one match per light and point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Light {
    /// See [`DirectionalLight`].
    Directional(DirectionalLight),
    /// See [`PointLight`].
    Point(PointLight),
    /// See [`SpotLight`].
    Spot(SpotLight),
}

impl From<DirectionalLight> for Light {
    fn from(l: DirectionalLight) -> Self {
        Light::Directional(l)
    }
}
impl From<PointLight> for Light {
    fn from(l: PointLight) -> Self {
        Light::Point(l)
    }
}
impl From<SpotLight> for Light {
    fn from(l: SpotLight) -> Self {
        Light::Spot(l)
    }
}

impl LightSource for Light {
    #[inline]
    fn colors(&self) -> &LightColors {
        match self {
            Light::Directional(l) => l.colors(),
            Light::Point(l) => l.colors(),
            Light::Spot(l) => l.colors(),
        }
    }
    #[inline]
    fn max_factor(&self) -> f32 {
        match self {
            Light::Directional(l) => l.max_factor(),
            Light::Point(l) => l.max_factor(),
            Light::Spot(l) => l.max_factor(),
        }
    }
    #[inline]
    fn sample(&self, p: Vec3) -> LightSample {
        match self {
            Light::Directional(l) => l.sample(p),
            Light::Point(l) => l.sample(p),
            Light::Spot(l) => l.sample(p),
        }
    }
    #[inline]
    fn sample_scaled(&self, p: Vec3) -> (LightSample, Vec3, f32) {
        match self {
            Light::Directional(l) => l.sample_scaled(p),
            Light::Point(l) => l.sample_scaled(p),
            Light::Spot(l) => l.sample_scaled(p),
        }
    }
    #[inline]
    fn flat(&self) -> Option<FlatLight> {
        match self {
            Light::Directional(l) => l.flat(),
            Light::Point(l) => l.flat(),
            Light::Spot(l) => l.flat(),
        }
    }
}

/// `cos(cutoff)` for a cone, kept `≥ 0` (`cos(π/2)` rounds to `−4.4e-8` in `f32`, and the cone must
/// not reach behind the light); `−1` for no cone (`cutoff = π`), which every cosine passes.
fn cos_cutoff(cutoff: f32) -> f32 {
    if cutoff == core::f32::consts::PI {
        -1.0
    } else {
        math::cos(cutoff).max(0.0)
    }
}

fn finite_point(field: &'static str, p: Vec3) -> Result<Vec3, PhongError> {
    for value in p.to_array() {
        if !value.is_finite() {
            return Err(PhongError::NonFinite { field, value });
        }
    }
    Ok(p)
}
