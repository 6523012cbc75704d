//! Conversions between glam (what `phong` takes and returns) and the math crates a user may come
//! from: nalgebra, cgmath, vek and ultraviolet. For each, the shortest forms that compile, into
//! glam and back out, for vectors, points, 3×3 and 4×4 matrices, each asserted; then a model
//! matrix, a point and a normal from that crate are shaded by `phong` and the normal matrix and the
//! colour go back out.
//!
//! None of these crates converts to glam with a single `.into()`: with the `mint` feature glam
//! implements `From<mint::Vector3<f32>> for Vec3`, the other crate `Into<mint::Vector3<f32>>`, and
//! Rust does not chain the two (`Vec3::from(v)` and `let g: Vec3 = v.into()` fail to compile, and
//! `Vec3::from(v.into())` is ambiguous). Two routes work:
//!
//! - **Fixed-size arrays**, which glam and all four crates convert to and from, with no feature:
//!   `Vec3::from_array(v.into())` (vek: `v.into_array()`), `Mat4::from_cols_array_2d(&m.into())`
//!   (column arrays; vek: `m.into_col_arrays()`), and back `Type::from(g.to_array())`,
//!   `Type::from(g.to_cols_array_2d())` (vek: `Mat4::from_col_arrays`).
//! - **mint** (`phong`'s `mint` feature): ultraviolet implements `From` both ways, so
//!   `Vec3::from(mint::Vector3::from(v))`; nalgebra, cgmath and vek implement only `Into<mint::…>`,
//!   so the mint type is named on a `let` first. Back out, `Type::from(mint::Vector3::from(g))`
//!   works for all four.
//!
//! The array forms are the shorter ones everywhere and need neither the feature nor a `mint`
//! dependency. A transposed matrix conversion would compile just as well, so the matrices here are
//! not symmetric and every conversion is checked against the other crate's own arithmetic.

use glam::{Mat3, Mat4, Vec3};
use phong::{Attenuation, BlinnPhong, LightColors, Material, PointLight, Scene, Shader, Viewer};

/// A vector and a point, no two components equal.
const V: [f32; 3] = [1.5, -2.0, 0.25];
const P: [f32; 3] = [0.5, 1.0, -3.0];

/// A model matrix in math notation (rows): non-uniform scale, shear and a translation. Not
/// symmetric, so a conversion that transposed it would change the results below.
const MODEL_ROWS: [[f32; 4]; 4] = [
    [2.0, 0.5, 0.0, 1.0],
    [0.0, 1.0, -0.3, 2.0],
    [0.2, 0.0, 3.0, -1.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The upper-left 3×3 of [`MODEL_ROWS`], the part a normal matrix is computed from.
const LINEAR_ROWS: [[f32; 3]; 3] = [[2.0, 0.5, 0.0], [0.0, 1.0, -0.3], [0.2, 0.0, 3.0]];

/// A surface normal and a tangent of the same surface (`N · T = 0`), and where the viewer is.
const NORMAL: [f32; 3] = [0.0, 0.6, 0.8];
const TANGENT: [f32; 3] = [1.0, 0.8, -0.6];
const EYE: [f32; 3] = [0.0, 1.0, 5.0];

fn glam_model() -> Mat4 {
    Mat4::from_cols_array_2d(&MODEL_ROWS).transpose()
}

/// `|a − b| ≤ 1e-5·(1 + |b|)` per component: the other crate's products may round in another order.
fn assert_close(a: Vec3, b: Vec3) {
    let tol = (Vec3::ONE + b.abs()) * 1e-5;
    assert!((a - b).abs().cmple(tol).all(), "{a} vs {b}");
}

/// `n` (in world space, from the normal matrix) is a normal of the model-transformed surface:
/// perpendicular to the transformed tangent `t`, and on the side of the transformed normal `m`.
fn assert_is_world_normal(n: Vec3, t: Vec3, m: Vec3) {
    let (n, t) = (n.normalize(), t.normalize());
    assert!(
        n.dot(t).abs() < 1e-6,
        "N·T = {} for N = {n}, T = {t}",
        n.dot(t)
    );
    assert!(n.dot(m) > 0.0, "the normal matrix flipped the normal: {n}");
}

/// What a renderer does with the converted values: moves a point and its normal to world space and
/// shades it with `phong`.
fn shade(model: Mat4, point: Vec3, normal: Vec3, eye: Vec3) -> Vec3 {
    let lamp = PointLight::try_new(
        Vec3::new(2.0, 3.0, 4.0),
        Attenuation::try_polynomial(1.0, 0.09, 0.032).unwrap(),
        LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.9, 0.6).unwrap(),
    )
    .unwrap();
    let material = Material::try_from_color(Vec3::new(0.2, 0.4, 0.9), 48.0).unwrap();
    let scene = Scene {
        lights: &[lamp],
        ambient: Vec3::ZERO,
        viewer: Viewer::At(eye),
    };
    let normal_matrix = phong::normal_matrix(Mat3::from_mat4(model));
    Shader::new(BlinnPhong::default(), &material, &scene)
        .shade(
            model.transform_point3(point),
            phong::transform_normal(normal_matrix, normal),
        )
        .total()
}

/// The colour every crate's round trip must give back exactly: the same inputs as glam values.
fn expected_colour() -> Vec3 {
    let [p, n, e] = [P, NORMAL, EYE].map(Vec3::from_array);
    let c = shade(glam_model(), p, n, e);
    assert!(c.z > c.x && c.x > 0.0, "a lit blue material: {c}");
    c
}

mod nalgebra_interop {
    use super::*;
    use nalgebra::{Matrix3, Matrix4, Point3, Vector3};

    #[test]
    fn vectors_and_points() {
        let (v, p, g) = (Vector3::from(V), Point3::from(P), Vec3::from_array(V));
        // Into glam, by arrays.
        assert_eq!(Vec3::from_array(v.into()), g);
        assert_eq!(Vec3::from_array(p.into()), Vec3::from_array(P));
        // Into glam, by mint: nalgebra implements `Into<mint::…>`, not `From`.
        let mv: mint::Vector3<f32> = v.into();
        let mp: mint::Point3<f32> = p.into();
        assert_eq!((Vec3::from(mv), Vec3::from(mp)), (g, Vec3::from_array(P)));
        // Back out.
        assert_eq!(Vector3::from(g.to_array()), v);
        assert_eq!(Point3::from(g.to_array()), Point3::from(V));
        assert_eq!(Vector3::from(mint::Vector3::from(g)), v);
        assert_eq!(Point3::from(mint::Point3::from(g)), Point3::from(V));
    }

    #[test]
    fn matrices() {
        let model = Matrix4::from_row_slice(MODEL_ROWS.as_flattened());
        let linear = Matrix3::from_row_slice(LINEAR_ROWS.as_flattened());
        // Into glam: nalgebra's nested arrays are columns, as glam's are.
        let g = Mat4::from_cols_array_2d(&model.into());
        assert_eq!(g, glam_model());
        assert_eq!(Mat3::from_cols_array_2d(&linear.into()), Mat3::from_mat4(g));
        let mm: mint::ColumnMatrix4<f32> = model.into();
        assert_eq!(Mat4::from(mm), g);
        // The same point moved by nalgebra and by glam.
        let moved = (model * Point3::from(P).to_homogeneous()).xyz();
        assert_close(
            Vec3::from_array(moved.into()),
            g.transform_point3(Vec3::from_array(P)),
        );
        // Back out: phong's normal matrix, used by nalgebra.
        let nm = phong::normal_matrix(Mat3::from_mat4(g));
        let normal_matrix = Matrix3::from(nm.to_cols_array_2d());
        assert_eq!(Matrix3::from(mint::ColumnMatrix3::from(nm)), normal_matrix);
        let [n, t, m] = [
            normal_matrix * Vector3::from(NORMAL),
            linear * Vector3::from(TANGENT),
            linear * Vector3::from(NORMAL),
        ]
        .map(|v| Vec3::from_array(v.into()));
        assert_is_world_normal(n, t, m);
        assert_eq!(Matrix4::from(g.to_cols_array_2d()), model);
        assert_eq!(Matrix4::from(mint::ColumnMatrix4::from(g)), model);
    }

    #[test]
    fn shading_round_trip() {
        let model = Matrix4::from_row_slice(MODEL_ROWS.as_flattened());
        let (p, n, eye) = (Point3::from(P), Vector3::from(NORMAL), Point3::from(EYE));
        let rgb = shade(
            Mat4::from_cols_array_2d(&model.into()),
            Vec3::from_array(p.into()),
            Vec3::from_array(n.into()),
            Vec3::from_array(eye.into()),
        );
        let colour = Vector3::from(rgb.to_array());
        assert_eq!(Vec3::from_array(colour.into()), expected_colour());
    }
}

mod cgmath_interop {
    use super::*;
    use cgmath::{Matrix, Matrix3, Matrix4, Point3, Transform, Vector3};

    #[test]
    fn vectors_and_points() {
        let (v, p, g) = (Vector3::from(V), Point3::from(P), Vec3::from_array(V));
        // Into glam, by arrays.
        assert_eq!(Vec3::from_array(v.into()), g);
        assert_eq!(Vec3::from_array(p.into()), Vec3::from_array(P));
        // Into glam, by mint: cgmath implements `Into<mint::…>`, not `From`.
        let mv: mint::Vector3<f32> = v.into();
        let mp: mint::Point3<f32> = p.into();
        assert_eq!((Vec3::from(mv), Vec3::from(mp)), (g, Vec3::from_array(P)));
        // Back out.
        assert_eq!(Vector3::from(g.to_array()), v);
        assert_eq!(Point3::from(g.to_array()), Point3::from(V));
        assert_eq!(Vector3::from(mint::Vector3::from(g)), v);
        assert_eq!(Point3::from(mint::Point3::from(g)), Point3::from(V));
    }

    #[test]
    fn matrices() {
        // cgmath's nested arrays are columns: the rows above, transposed.
        let model = Matrix4::from(MODEL_ROWS).transpose();
        let linear = Matrix3::from(LINEAR_ROWS).transpose();
        // Into glam.
        let g = Mat4::from_cols_array_2d(&model.into());
        assert_eq!(g, glam_model());
        assert_eq!(Mat3::from_cols_array_2d(&linear.into()), Mat3::from_mat4(g));
        let mm: mint::ColumnMatrix4<f32> = model.into();
        assert_eq!(Mat4::from(mm), g);
        // The same point moved by cgmath and by glam.
        let moved = model.transform_point(Point3::from(P));
        assert_close(
            Vec3::from_array(moved.into()),
            g.transform_point3(Vec3::from_array(P)),
        );
        // Back out: phong's normal matrix, used by cgmath.
        let nm = phong::normal_matrix(Mat3::from_mat4(g));
        let normal_matrix = Matrix3::from(nm.to_cols_array_2d());
        assert_eq!(Matrix3::from(mint::ColumnMatrix3::from(nm)), normal_matrix);
        let [n, t, m] = [
            normal_matrix * Vector3::from(NORMAL),
            linear * Vector3::from(TANGENT),
            linear * Vector3::from(NORMAL),
        ]
        .map(|v| Vec3::from_array(v.into()));
        assert_is_world_normal(n, t, m);
        assert_eq!(Matrix4::from(g.to_cols_array_2d()), model);
        assert_eq!(Matrix4::from(mint::ColumnMatrix4::from(g)), model);
    }

    #[test]
    fn shading_round_trip() {
        let model = Matrix4::from(MODEL_ROWS).transpose();
        let (p, n, eye) = (Point3::from(P), Vector3::from(NORMAL), Point3::from(EYE));
        let rgb = shade(
            Mat4::from_cols_array_2d(&model.into()),
            Vec3::from_array(p.into()),
            Vec3::from_array(n.into()),
            Vec3::from_array(eye.into()),
        );
        let colour = Vector3::from(rgb.to_array());
        assert_eq!(Vec3::from_array(colour.into()), expected_colour());
    }
}

mod vek_interop {
    use super::*;
    // vek's default matrices are row-major; it has no point type (positions are `Vec3`). Its
    // names are used with the crate path, since `use vek::*` and `use glam::*` both bring a `Vec3`.

    #[test]
    fn vectors() {
        let (v, g) = (vek::Vec3::from(V), Vec3::from_array(V));
        // Into glam, by arrays: vek has no `Into<[T; 3]>`, but `into_array`.
        assert_eq!(Vec3::from_array(v.into_array()), g);
        // Into glam, by mint: vek implements `Into<mint::…>`, not `From`.
        let mv: mint::Vector3<f32> = v.into();
        let mp: mint::Point3<f32> = v.into();
        assert_eq!((Vec3::from(mv), Vec3::from(mp)), (g, g));
        // Back out.
        assert_eq!(vek::Vec3::from(g.to_array()), v);
        assert_eq!(vek::Vec3::from(mint::Vector3::from(g)), v);
    }

    #[test]
    fn matrices() {
        let model = vek::Mat4::from_row_arrays(MODEL_ROWS);
        let linear = vek::Mat3::from_row_arrays(LINEAR_ROWS);
        // Into glam: row-major storage, so ask for columns.
        let g = Mat4::from_cols_array_2d(&model.into_col_arrays());
        assert_eq!(g, glam_model());
        assert_eq!(
            Mat3::from_cols_array_2d(&linear.into_col_arrays()),
            Mat3::from_mat4(g)
        );
        // By mint, either layout: vek converts its rows to mint's columns and glam back.
        let columns: mint::ColumnMatrix4<f32> = model.into();
        let rows: mint::RowMatrix4<f32> = model.into();
        assert_eq!((Mat4::from(columns), Mat4::from(rows)), (g, g));
        // The same point moved by vek and by glam.
        let moved = model.mul_point(vek::Vec3::from(P));
        assert_close(
            Vec3::from_array(moved.into_array()),
            g.transform_point3(Vec3::from_array(P)),
        );
        // Back out: phong's normal matrix, used by vek.
        let nm = phong::normal_matrix(Mat3::from_mat4(g));
        let normal_matrix = vek::Mat3::from_col_arrays(nm.to_cols_array_2d());
        assert_eq!(
            vek::Mat3::from(mint::ColumnMatrix3::from(nm)),
            normal_matrix
        );
        let [n, t, m] = [
            normal_matrix * vek::Vec3::from(NORMAL),
            linear * vek::Vec3::from(TANGENT),
            linear * vek::Vec3::from(NORMAL),
        ]
        .map(|v| Vec3::from_array(v.into_array()));
        assert_is_world_normal(n, t, m);
        assert_eq!(vek::Mat4::from_col_arrays(g.to_cols_array_2d()), model);
        assert_eq!(vek::Mat4::from(mint::ColumnMatrix4::from(g)), model);
    }

    #[test]
    fn shading_round_trip() {
        let model = vek::Mat4::from_row_arrays(MODEL_ROWS);
        let [p, n, eye] = [P, NORMAL, EYE].map(vek::Vec3::from);
        let rgb = shade(
            Mat4::from_cols_array_2d(&model.into_col_arrays()),
            Vec3::from_array(p.into_array()),
            Vec3::from_array(n.into_array()),
            Vec3::from_array(eye.into_array()),
        );
        let colour = vek::Vec3::from(rgb.to_array());
        assert_eq!(Vec3::from_array(colour.into_array()), expected_colour());
    }
}

mod ultraviolet_interop {
    use super::*;
    // ultraviolet has no point type: positions are `Vec3`, as in glam.

    #[test]
    fn vectors() {
        let (v, g) = (ultraviolet::Vec3::from(V), Vec3::from_array(V));
        // Into glam, by arrays.
        assert_eq!(Vec3::from_array(v.into()), g);
        // Into glam, by mint: ultraviolet implements `From` both ways, so no `let` is needed.
        assert_eq!(Vec3::from(mint::Vector3::from(v)), g);
        // Back out.
        assert_eq!(ultraviolet::Vec3::from(g.to_array()), v);
        assert_eq!(ultraviolet::Vec3::from(mint::Vector3::from(g)), v);
    }

    #[test]
    fn matrices() {
        // ultraviolet's nested arrays are columns: the rows above, transposed.
        let model = ultraviolet::Mat4::from(MODEL_ROWS).transposed();
        let linear = ultraviolet::Mat3::from(LINEAR_ROWS).transposed();
        // Into glam.
        let g = Mat4::from_cols_array_2d(&model.into());
        assert_eq!(g, glam_model());
        assert_eq!(Mat3::from_cols_array_2d(&linear.into()), Mat3::from_mat4(g));
        assert_eq!(Mat4::from(mint::ColumnMatrix4::from(model)), g);
        // The same point moved by ultraviolet and by glam.
        let moved = model.transform_point3(ultraviolet::Vec3::from(P));
        assert_close(
            Vec3::from_array(moved.into()),
            g.transform_point3(Vec3::from_array(P)),
        );
        // Back out: phong's normal matrix, used by ultraviolet.
        let nm = phong::normal_matrix(Mat3::from_mat4(g));
        let normal_matrix = ultraviolet::Mat3::from(nm.to_cols_array_2d());
        assert_eq!(
            ultraviolet::Mat3::from(mint::ColumnMatrix3::from(nm)),
            normal_matrix
        );
        let [n, t, m] = [
            normal_matrix * ultraviolet::Vec3::from(NORMAL),
            linear * ultraviolet::Vec3::from(TANGENT),
            linear * ultraviolet::Vec3::from(NORMAL),
        ]
        .map(|v| Vec3::from_array(v.into()));
        assert_is_world_normal(n, t, m);
        assert_eq!(ultraviolet::Mat4::from(g.to_cols_array_2d()), model);
        assert_eq!(ultraviolet::Mat4::from(mint::ColumnMatrix4::from(g)), model);
    }

    #[test]
    fn shading_round_trip() {
        let model = ultraviolet::Mat4::from(MODEL_ROWS).transposed();
        let [p, n, eye] = [P, NORMAL, EYE].map(ultraviolet::Vec3::from);
        let rgb = shade(
            Mat4::from_cols_array_2d(&model.into()),
            Vec3::from_array(p.into()),
            Vec3::from_array(n.into()),
            Vec3::from_array(eye.into()),
        );
        let colour = ultraviolet::Vec3::from(rgb.to_array());
        assert_eq!(Vec3::from_array(colour.into()), expected_colour());
    }
}

/// The glam side on its own: the shaded point is lit, and the world normal it used is one.
#[test]
fn the_reference_itself() {
    let g = glam_model();
    let nm = phong::normal_matrix(Mat3::from_mat4(g));
    let linear = Mat3::from_mat4(g);
    let [n, t] = [NORMAL, TANGENT].map(Vec3::from_array);
    assert_is_world_normal(nm * n, linear * t, linear * n);
    let _ = expected_colour();
}
