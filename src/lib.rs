//! # phong
//!
//! The Phong family of local reflection models — Lambert, Phong and Blinn-Phong — and the geometry
//! under them, as small, total, `no_std` functions on [glam] vectors.
//!
//! ## Conventions
//!
//! - **Directions point away from the surface:** `L` from the point to the light, `V` from the point
//!   to the viewer, `N` the outward normal. (GLSL's and glam's `reflect(I, N)` take the *incident*
//!   direction `I = −L`; see [`reflect`].)
//! - **Vectors are unit** unless a name or doc says otherwise. Fast functions document this and
//!   `debug_assert!` it; total functions ([`shade`], [`normalize_or_zero`], [`triangle_normal_or_zero`], …)
//!   accept anything finite.
//! - **Colours are linear** RGB, each channel `≥ 0`; encode for display with [`srgb_encode`].
//! - **Units:** distances in whatever unit the scene uses; the attenuation constants (`ε = 0.01`)
//!   assume metres.
//!
//! ## Symbols
//!
//! | symbol | meaning | in code |
//! |---|---|---|
//! | `N` | unit surface normal | `n` |
//! | `L` | unit direction to the light | `l`, [`LightSample::direction`] |
//! | `V` | unit direction to the viewer | `v` |
//! | `R` | mirror of `L` about `N`: `2(N·L)N − L` | [`reflect`] |
//! | `H` | halfway vector `(L+V)/‖L+V‖` | [`halfway_or_zero`] |
//! | `s` | shininess (specular exponent) | [`Material::shininess`] |
//! | `Ka, Kd, Ks, Ke` | ambient, diffuse, specular reflectance; emission | [`Material`] |
//! | `Ia` | scene ambient light | [`Scene::ambient`] |
//! | `La, Ld, Ls` | a light's ambient, diffuse, specular colour | [`LightColors`] |
//! | `f` | attenuation × spot factor | [`Attenuation::factor`], [`SpotLight::spot_factor`] |
//! | `d` | distance from the point to the light | |
//!
//! The equation [`shade`] evaluates (Phong 1975; Blinn 1977):
//!
//! ```text
//! I = Ke + Ka⊙(Ia + Σ f·La) + Σ f · ( Kd⊙Ld · max(N·L, 0) + Ks⊙Ls · gate(N·L) · lobe^s )
//! lobe = max(R·V, 0)  (Phong)   or   max(N·H, 0)  (Blinn-Phong)
//! ```
//!
//! ## Totality
//!
//! From finite input no function here panics (in release builds) or returns NaN. Each documents what
//! it returns on degenerate input: a zero-area triangle, `L = −V`, a zero normal, a light at the
//! point (`d = 0`), a singular model matrix. Infinity is returned only where documented to mean
//! something ([`Attenuation::cull_radius`]: "never fades below the threshold"). Bad parameters are
//! rejected by checked constructors (`try_*`) with a [`PhongError`] naming the field.
//!
//! ## Quick start
//!
//! ```
//! use glam::Vec3;
//! use phong::{BlinnPhong, DirectionalLight, LightColors, Material, Scene, Viewer};
//!
//! let sun = DirectionalLight::try_new(
//!     Vec3::new(1.0, 1.0, 1.0),
//!     LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5)?,
//! )?;
//! let red_plastic = Material::try_from_color(Vec3::new(0.8, 0.1, 0.1), 64.0)?;
//! let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::At(Vec3::new(0.0, 0.0, 5.0)) };
//! let rgb = phong::shade(&BlinnPhong::default(), &red_plastic, &scene, Vec3::ZERO, Vec3::Z).total();
//! let pixel = phong::linear_to_srgb8(rgb);
//! # Ok::<(), phong::PhongError>(())
//! ```
//!
//! ## Features
//!
//! - `std` (default): float functions from the platform's libm through `std`; the batch API picks
//!   its SIMD level at run time.
//! - `libm`: pure-Rust float functions for `no_std` targets (the batch API's SIMD level is then the
//!   build's target features). With both on, `std` wins.
//! - `serde`: `Serialize`/`Deserialize` for every parameter type (lights, attenuation forms,
//!   materials, models, gates, normalisations, pow strategies, viewers) and the shaded [`Terms`].
//!   Deserialising validates exactly like the `try_*` constructors, so a bad file is an error
//!   naming the field, never an invalid value.
//! - `mint`: glam's conversions between its vectors and matrices and the `mint` types. Another
//!   math crate's vector does not convert with one `.into()` (Rust does not chain its `Into<mint>`
//!   and glam's `From<mint>`); the README's `mint` section gives the shortest conversion per crate.
//!
//! One of `std` and `libm` is required. Derivations of every formula are in `docs/derivations.md`;
//! measured accuracy in `docs/accuracy.md`.

#![cfg_attr(not(feature = "std"), no_std)]
#![deny(missing_docs)]
#![deny(unsafe_code)]
// `!(x > 0.0)` is used on purpose: unlike `x <= 0.0` it is also true for NaN.
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    reason = "!(x > 0.0) is also true for NaN"
)]
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!(
    "phong needs a source of float functions: enable the `std` feature (the default) or, for \
     no_std targets, the `libm` feature"
);

// Layers, each using only the ones before it (and `error`, `math`, which every layer uses):
// geometry (vectors, normals) → reflection (models, cosines, pow) → lights (falloffs; a spot cone
// takes reflection's pow) → surfaces (materials) → shading (one point) → batch (many points).
// `colour`, `gpu` and `shading_rate` sit beside them.
pub mod batch;
mod colour;
mod error;
mod geometry;
pub mod gpu;
mod lights;
mod math;
mod reflection;
#[cfg(feature = "serde")]
mod serde_validation;
mod shading;
pub mod shading_rate;
mod surfaces;

// The layers' modules by their own names, so `crate::pow`, `crate::light`, … name them.
use colour::{color, srgb8, srgb8_to_linear};
use geometry::{
    expansion, face_forward, halfway, normal_matrix, normalize, reflect, triangle, vertex_normals,
};
use lights::{attenuation, light};
use reflection::{
    blinn_phong, gate, incidence, lambert, model, normalization, phong, pow, resolved_model,
};
use shading::{lobe_pow, shade, shader, terms, visibility};
use surfaces::{material, surface};

pub use attenuation::Attenuation;
pub use batch::{
    AosVec3, BatchLight, BatchModel, BatchShader, GBuffer, Level, SoaRgb, SoaSurface, SoaTerms,
    SoaVec3, TileCulling, UnsupportedLevel, shade_batch, shade_batch_aos, shade_batch_aos_rgba8,
    shade_batch_rgba8, shade_batch_rgba8_with_level, shade_batch_with_level, shade_batch_xrgb8,
    shade_gbuffer, shade_gbuffer_rgba8, shade_gbuffer_rgba8_with_level, shade_gbuffer_terms,
    shade_gbuffer_terms_with_level, shade_gbuffer_tiled, shade_gbuffer_tiled_with_level,
    shade_gbuffer_with_level, shade_gbuffer_xrgb8, shade_gbuffer_xrgb8_with_level,
};
pub use blinn_phong::BlinnPhong;
pub use color::{
    gamma_decode, gamma_encode, linear_to_srgb8, quantize_u8, saturate, srgb_decode, srgb_encode,
};
pub use error::PhongError;
pub use face_forward::face_forward;
pub use gate::SpecularGate;
pub use halfway::{halfway_or_zero, try_halfway};
pub use incidence::Incidence;
pub use lambert::Lambert;
pub use light::{
    DirectionalLight, Light, LightColors, LightColorsParams, LightSample, LightSource, PointLight,
    SpotCone, SpotLight,
};
pub use material::{Material, MaterialParams};
pub use model::{Model, ReflectionModel};
pub use normal_matrix::{normal_matrix, transform_normal};
pub use normalization::Normalization;
pub use normalize::{length, normalize_or_zero, try_normalize};
pub use phong::Phong;
pub use pow::PowStrategy;
pub use reflect::reflect;
pub use resolved_model::ResolvedModel;
pub use shade::{Scene, Viewer, shade};
pub use shader::Shader;
pub use srgb8_to_linear::srgb8_to_linear;
pub use surface::Surface;
pub use terms::Terms;
pub use triangle::{triangle_area_normal, triangle_normal_or_zero, try_triangle_normal};
pub use vertex_normals::vertex_normals;
pub use visibility::{Unshadowed, Visibility, VisibilityFn};

// The README's Rust examples compile and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// Re-export of the glam version this crate's API uses, so users can name `phong::glam::Vec3`
/// without a version mismatch.
pub use glam;
