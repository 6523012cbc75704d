//! Using `phong` from a codebase that does not use glam.
//!
//! Run with `cargo run --example mint_interop --features mint`.
//!
//! Many math crates (nalgebra, cgmath, vek, ultraviolet, …) convert their vectors to and from the
//! `mint` interchange types. With phong's `mint` feature, glam's `Vec3` converts from
//! `mint::Vector3<f32>` and `mint::Point3<f32>` too, so such a codebase hands its vectors in with
//! `.into()` and writes no conversion code of its own. Here the "other library" is a tiny vector type
//! standing in for any of them.

use phong::glam::Vec3;
use phong::{BlinnPhong, LightColors, Material, PointLight, Scene, Viewer};

/// Another library's vector type. Like the real ones, it converts to `mint` types.
#[derive(Clone, Copy, Debug)]
struct OtherVec {
    x: f32,
    y: f32,
    z: f32,
}

impl From<OtherVec> for mint::Vector3<f32> {
    fn from(v: OtherVec) -> Self {
        mint::Vector3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// The same conversion through the mint type that every participating crate shares.
fn to_glam(v: OtherVec) -> Vec3 {
    mint::Vector3::from(v).into()
}

fn main() -> Result<(), phong::PhongError> {
    let light_at = OtherVec {
        x: 2.0,
        y: 3.0,
        z: 4.0,
    };
    let eye = OtherVec {
        x: 0.0,
        y: 0.0,
        z: 5.0,
    };
    let point = OtherVec {
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    let normal = OtherVec {
        x: 0.0,
        y: 0.0,
        z: 1.0,
    };

    let light = PointLight::try_new(
        to_glam(light_at),
        phong::Attenuation::None,
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.9, 0.6)?,
    )?;
    let material = Material::try_from_color(Vec3::new(0.2, 0.4, 0.9), 48.0)?;
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(to_glam(eye)),
    };
    let rgb = phong::shade(
        &BlinnPhong::default(),
        &material,
        &scene,
        to_glam(point),
        to_glam(normal),
    )
    .total();
    // And back out to the other library's world through mint.
    let out: mint::Vector3<f32> = rgb.into();
    println!(
        "shaded colour: ({:.4}, {:.4}, {:.4})  sRGB8 {:?}",
        out.x,
        out.y,
        out.z,
        phong::linear_to_srgb8(rgb)
    );
    Ok(())
}
