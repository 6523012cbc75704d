//! What the kernel needs of a model and a light, flattened into per-call constants.

use glam::Vec3;

use crate::attenuation::Attenuation;
use crate::gate::SpecularGate;
use crate::light::{DirectionalLight, Light, LightSource, PointLight, SpotLight};
use crate::model::{Model, ReflectionModel};
use crate::normalization::Normalization;
use crate::pow::PowStrategy;
use crate::{BlinnPhong, Lambert, Phong};

/// The specular lobe's shape, resolved once per call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lobe {
    /// No specular work.
    None,
    /// `max(R·V, 0)^s`, `R·V = 2(N·L)(N·V) − L·V`.
    Phong,
    /// `((N·H)²)^(s/2)`, `(N·H)² = max(N·L + N·V, 0)² / (2 + 2 L·V)`.
    Blinn,
}

/// A model's constants for one shininess: the lobe, its gate, the two scale factors, the exponent
/// applied to the lobe's base and the pow strategy.
#[expect(
    unnameable_types,
    reason = "returned by the hidden, sealed BatchModel/BatchLight hooks: only this crate implements or calls them"
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneModel {
    pub(crate) lobe: Lobe,
    /// The gate; a normalised lobe is cosine-gated.
    pub(crate) gate: SpecularGate,
    /// 1, or `1/π` when normalised.
    pub(crate) diffuse_scale: f32,
    /// 1, or the normalisation factor.
    pub(crate) specular_scale: f32,
    /// `s` for Phong, `s/2` for Blinn-Phong's `(N·H)²`.
    pub(crate) exponent: f32,
    pub(crate) pow: PowStrategy,
    /// The model's normalisation, for a per-point shininess's specular scale.
    pub(crate) normalization: Normalization,
}

/// A light the kernel handles, with its colours.
#[expect(
    unnameable_types,
    reason = "returned by the hidden, sealed BatchModel/BatchLight hooks: only this crate implements or calls them"
)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LaneLight {
    /// A unit direction toward the light, factor 1.
    Directional(Vec3),
    /// A position and `1/max(c + l·d + q·d², MIN_DENOMINATOR)`.
    Point {
        /// Light position.
        position: Vec3,
        /// `c`, `l`, `q`.
        coefficients: [f32; 3],
    },
    /// A point light with any other falloff, or a spot light: its direction and distance by an
    /// exact square root and division and its falloff by `Attenuation::factor`'s operations, per
    /// lane, so they are the scalar path's bit for bit; a spot cone's power by
    /// `PowStrategy::Auto`'s plan for its exponent.
    Falloff {
        /// Light position.
        position: Vec3,
        /// The falloff.
        attenuation: Attenuation,
        /// The cone of a spot light.
        spot: Option<SpotLight>,
    },
    /// A light that adds ambient only (a directional light built with a zero direction).
    AmbientOnly,
}

pub(crate) mod sealed {
    /// Keeps the batch traits closed: the kernel knows every implementation.
    #[expect(
        unnameable_types,
        reason = "the sealed-trait pattern: nameable outside would unseal it"
    )]
    pub trait Sealed {}
}

/// One of the crate's own models, whose whole description the crate knows: [`Lambert`],
/// [`Phong`], [`BlinnPhong`] and [`Model`], with every gate, normalisation and [`PowStrategy`].
/// Sealed.
///
/// Every function that needs that description takes the model as `&M` with `M: BatchModel`: the
/// batch path, [`shading_rate`](crate::shading_rate)'s advisor and
/// [`GpuParams::new`](crate::gpu::GpuParams::new). ([`shade`](crate::shade()) takes any
/// [`ReflectionModel`] as `&M`; [`Shader::new`](crate::Shader::new) keeps its model and takes it
/// by value.)
pub trait BatchModel: ReflectionModel + Copy + Into<Model> + sealed::Sealed {
    /// The model's constants for the kernel at shininess `s`.
    #[doc(hidden)]
    fn lane_model(&self, s: f32) -> LaneModel;
}

/// A light type the batch path accepts. Sealed; implemented by every light kind, and every kind
/// runs in the vector kernel.
///
/// [`DirectionalLight`] and [`PointLight`] with [`Attenuation::None`] or
/// [`Attenuation::Polynomial`] run on the kernel's fastest path, in vector arithmetic. A
/// [`SpotLight`], or a point light with another falloff, gets its direction and distance per lane
/// by an exact square root and division and its factor by the scalar path's own formula, in
/// vector arithmetic at every level (a spot cone's power by `PowStrategy::Auto`'s plan for its
/// exponent: the module docs' "Accuracy").
pub trait BatchLight: LightSource + sealed::Sealed {
    /// The light's kernel form, or `None` when the kernel does not handle it.
    #[doc(hidden)]
    fn lane_light(&self) -> Option<LaneLight>;
}

impl sealed::Sealed for Lambert {}
impl sealed::Sealed for Phong {}
impl sealed::Sealed for BlinnPhong {}
impl sealed::Sealed for Model {}
impl sealed::Sealed for DirectionalLight {}
impl sealed::Sealed for PointLight {}
impl sealed::Sealed for SpotLight {}
impl sealed::Sealed for Light {}

fn diffuse_scale(n: Normalization) -> f32 {
    n.diffuse(1.0)
}

impl BatchModel for Lambert {
    fn lane_model(&self, _s: f32) -> LaneModel {
        LaneModel {
            lobe: Lobe::None,
            gate: SpecularGate::None,
            diffuse_scale: diffuse_scale(self.normalization),
            specular_scale: 0.0,
            exponent: 0.0,
            pow: PowStrategy::Exact,
            normalization: self.normalization,
        }
    }
}

/// Gate and scale of a lobe: a normalised lobe is cosine-gated and scaled by its factor.
fn gate_and_scale(g: SpecularGate, n: Normalization, factor: f32) -> (SpecularGate, f32) {
    if n.is_normalized() {
        (SpecularGate::Cosine, factor)
    } else {
        (g, 1.0)
    }
}

impl BatchModel for Phong {
    fn lane_model(&self, s: f32) -> LaneModel {
        let n = self.normalization;
        let (gate, specular_scale) = gate_and_scale(self.gate, n, n.phong_factor(s));
        LaneModel {
            lobe: Lobe::Phong,
            gate,
            diffuse_scale: diffuse_scale(n),
            specular_scale,
            exponent: s,
            pow: self.pow,
            normalization: n,
        }
    }
}

impl BatchModel for BlinnPhong {
    fn lane_model(&self, s: f32) -> LaneModel {
        let n = self.normalization;
        let (gate, specular_scale) = gate_and_scale(self.gate, n, n.blinn_factor(s));
        LaneModel {
            lobe: Lobe::Blinn,
            gate,
            diffuse_scale: diffuse_scale(n),
            specular_scale,
            exponent: 0.5 * s,
            pow: self.pow,
            normalization: n,
        }
    }
}

impl BatchModel for Model {
    fn lane_model(&self, s: f32) -> LaneModel {
        match self {
            Model::Lambert(m) => m.lane_model(s),
            Model::Phong(m) => m.lane_model(s),
            Model::BlinnPhong(m) => m.lane_model(s),
        }
    }
}

impl BatchLight for DirectionalLight {
    fn lane_light(&self) -> Option<LaneLight> {
        let d = self.direction();
        Some(if d == Vec3::ZERO {
            LaneLight::AmbientOnly
        } else {
            LaneLight::Directional(d)
        })
    }
}

impl BatchLight for PointLight {
    fn lane_light(&self) -> Option<LaneLight> {
        let coefficients = match self.attenuation() {
            Attenuation::None => [1.0, 0.0, 0.0],
            Attenuation::Polynomial {
                constant,
                linear,
                quadratic,
            } => [constant, linear, quadratic],
            attenuation => {
                return Some(LaneLight::Falloff {
                    position: self.position(),
                    attenuation,
                    spot: None,
                });
            }
        };
        Some(LaneLight::Point {
            position: self.position(),
            coefficients,
        })
    }
}

impl BatchLight for SpotLight {
    fn lane_light(&self) -> Option<LaneLight> {
        Some(LaneLight::Falloff {
            position: self.position(),
            attenuation: self.attenuation(),
            spot: Some(*self),
        })
    }
}

impl BatchLight for Light {
    fn lane_light(&self) -> Option<LaneLight> {
        match self {
            Light::Directional(l) => l.lane_light(),
            Light::Point(l) => l.lane_light(),
            Light::Spot(l) => l.lane_light(),
        }
    }
}
