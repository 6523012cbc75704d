//! A small software rasterizer for `phong`'s gallery and explorer. Not part of `phong`'s API.
//!
//! - [`Camera`]: a perspective camera; [`Mesh`]: icosphere, cube and plane with normals from
//!   [`phong::vertex_normals`]; [`Framebuffer`]: linear colour, depth and triangle ids.
//! - [`draw`]: near-plane clipping, a depth test and perspective-correct barycentric interpolation,
//!   shading per vertex (Gouraud), per pixel (Phong shading, deferred: every visible pixel once, at
//!   the end of the draw, through [`SurfaceShader::shade_many`]) or adaptively per triangle with
//!   [`phong::shading_rate::gouraud_within_tolerance`] ([`ShadingMode`]).
//! - [`PhongShader`]: [`phong::shade`] as a [`SurfaceShader`], and the batch path
//!   ([`phong::shade_gbuffer`]) for many points, with one term or all, texture maps, and light
//!   culling by [`phong::Attenuation::cull_radius`].
//! - [`Image`]: sRGB or raw 8-bit encoding, captions in a built-in 3×5 font, PNG output.

#![deny(missing_docs)]
// `!(x > 0.0)` is used on purpose: unlike `x <= 0.0` it is also true for NaN.
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    reason = "!(x > 0.0) is also true for NaN"
)]

mod camera;
mod framebuffer;
mod image;
mod mesh;
mod rasterize;
mod shader;
pub mod text;

pub use camera::Camera;
pub use framebuffer::Framebuffer;
pub use image::Image;
pub use mesh::Mesh;
pub use rasterize::{DrawStats, ShadingMode, SurfaceShader, draw, shade_each};
pub use shader::{MAX_LIGHTS, PhongShader, Term, Texture};
