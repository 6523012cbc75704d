//! Using `phong` from a codebase built on nalgebra: its model matrix, points and normals in, the
//! normal matrix and the shaded colour back out.
//!
//! Run with `cargo run --example mint_interop --features mint`.
//!
//! `phong` takes glam types, and nalgebra's do not convert to them with a single `.into()`: with
//! the `mint` feature glam converts *from* mint types and nalgebra *into* them, and Rust does not
//! chain two conversions. What works:
//!
//! - fixed-size arrays, shortest and with no feature: `Vec3::from_array(v.into())`,
//!   `Mat4::from_cols_array_2d(&m.into())`, and back `Vector3::from(g.to_array())`;
//! - mint, with the mint type named: `let m: mint::Vector3<f32> = v.into(); Vec3::from(m)`, and
//!   back `Vector3::from(mint::Vector3::from(g))`.
//!
//! The same forms for cgmath, vek and ultraviolet are in README's `mint` section and are compiled
//! and checked in `tests/interop.rs`.

use nalgebra::{Matrix3, Matrix4, Point3, Vector3};
use phong::glam::{Mat3, Mat4, Vec3};
use phong::{BlinnPhong, LightColors, Material, PointLight, Scene, Shader, Viewer};

fn main() -> Result<(), phong::PhongError> {
    // The scene as the nalgebra side has it: an object stretched to twice its height and lifted.
    let model = Matrix4::new_translation(&Vector3::new(0.0, 0.5, 0.0))
        * Matrix4::new_nonuniform_scaling(&Vector3::new(1.0, 2.0, 1.0));
    let point = Point3::new(0.0, 0.25, 0.9);
    let normal = Vector3::new(0.0, 0.6, 0.8);
    let lamp = Point3::new(2.0, 3.0, 4.0);
    let eye = Point3::new(0.0, 1.0, 5.0);

    // In, by arrays: nalgebra's vectors and points become `[f32; 3]`, its matrices column arrays.
    let model = Mat4::from_cols_array_2d(&model.into());
    let position = model.transform_point3(Vec3::from_array(point.into()));
    // In, by mint: the mint type has to be named, since nalgebra implements only `Into<mint::…>`.
    let normal: mint::Vector3<f32> = normal.into();
    let normal_matrix = phong::normal_matrix(Mat3::from_mat4(model));
    let world_normal = phong::transform_normal(normal_matrix, Vec3::from(normal));

    let light = PointLight::try_new(
        Vec3::from_array(lamp.into()),
        phong::Attenuation::None,
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.9, 0.6)?,
    )?;
    let material = Material::try_from_color(Vec3::new(0.2, 0.4, 0.9), 48.0)?;
    let scene = Scene {
        lights: &[light],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(Vec3::from_array(eye.into())),
    };
    let rgb = Shader::new(BlinnPhong::default(), &material, &scene)
        .shade(position, world_normal)
        .total();

    // Out, back to nalgebra: the colour and the normal matrix (which nalgebra can apply itself).
    let colour = Vector3::from(rgb.to_array());
    let normal_matrix = Matrix3::from(normal_matrix.to_cols_array_2d());
    let world_normal = Vector3::from(mint::Vector3::from(world_normal));
    println!(
        "world position {position}, world normal ({:.4}, {:.4}, {:.4})",
        world_normal.x, world_normal.y, world_normal.z
    );
    println!("normal matrix from phong, |det M|·M⁻ᵀ (not normalised):{normal_matrix:.4}");
    println!(
        "shaded colour: ({:.4}, {:.4}, {:.4}), sRGB8 {:?}",
        colour.x,
        colour.y,
        colour.z,
        phong::linear_to_srgb8(rgb)
    );
    Ok(())
}
