//! The meshes, the transforms and the clipping the pictures rest on.

use glam::{Mat4, Vec2, Vec3};
use raster::{Camera, Framebuffer, Mesh, ShadingMode, SurfaceShader, draw};

/// Every triangle winds counter-clockwise seen from outside (its area normal agrees with its
/// vertex normals), and every normal is unit.
fn check_orientation(name: &str, mesh: &Mesh) {
    for n in &mesh.normals {
        assert!(
            (n.length() - 1.0).abs() < 1e-5,
            "{name}: normal {n} not unit"
        );
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let face = (b - a).cross(c - a);
        for i in t {
            assert!(
                face.dot(mesh.normals[*i as usize]) > 0.0,
                "{name}: triangle {t:?} winds against its normals"
            );
        }
    }
}

#[test]
fn meshes_wind_outward_with_unit_normals() {
    for k in 0..4 {
        let s = Mesh::icosphere(k);
        assert_eq!(
            s.triangles.len(),
            20 * 4usize.pow(k),
            "faces of icosphere({k})"
        );
        // Euler: V − E + F = 2 with E = 3F/2.
        assert_eq!(
            s.positions.len() + s.triangles.len() - 3 * s.triangles.len() / 2,
            2,
            "icosphere({k}) is closed without duplicated vertices"
        );
        for p in &s.positions {
            assert!(
                (p.length() - 1.0).abs() < 1e-5,
                "vertex {p} off the unit sphere"
            );
        }
        check_orientation("icosphere", &s);
    }
    check_orientation("cube", &Mesh::cube());
    let plane = Mesh::plane(2.0, 3);
    check_orientation("plane", &plane);
    assert!(
        plane.normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6),
        "the plane faces +y"
    );
}

/// Outputs the interpolated normal, mapped to `[0, 1]`.
struct NormalShader;

impl SurfaceShader for NormalShader {
    fn shade(&self, _p: Vec3, n: Vec3, _uv: Vec2) -> Vec3 {
        n.normalize_or_zero() * 0.5 + Vec3::splat(0.5)
    }
}

#[test]
fn normals_follow_the_normal_matrix_under_non_uniform_scale() {
    // A unit sphere squashed to an ellipsoid: at the pixel where the surface faces the camera
    // the transformed normal must point at the camera too.
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO);
    let mesh = Mesh::icosphere(4);
    let model = Mat4::from_scale(Vec3::new(2.0, 0.7, 1.0)) * Mat4::from_rotation_y(0.3);
    let mut fb = Framebuffer::new(64, 64, Vec3::ZERO);
    draw(
        &mut fb,
        &camera,
        &mesh,
        model,
        &NormalShader,
        ShadingMode::PerPixel,
    );
    let n = fb.at(32, 32) * 2.0 - Vec3::ONE;
    assert!(
        n.dot(Vec3::Z) > 0.99,
        "centre normal {n}, expected about +z"
    );
    // Half-way to the right edge of the ellipsoid the normal leans right, much less than the
    // position does (the surface is flattened along x).
    let right = fb.at(40, 32) * 2.0 - Vec3::ONE;
    assert!(
        right.x > 0.05 && right.x < 0.5,
        "normal {right} should lean a little to +x"
    );
}

#[test]
fn a_plane_through_the_camera_is_clipped_not_lost() {
    // The floor runs under and behind the eye: its triangles cross the near plane.
    let camera = Camera::look_at(Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 0.0, -3.0));
    let floor = Mesh::plane(20.0, 1);
    let mut fb = Framebuffer::new(48, 48, Vec3::ZERO);
    let stats = draw(
        &mut fb,
        &camera,
        &floor,
        Mat4::IDENTITY,
        &NormalShader,
        ShadingMode::PerPixel,
    );
    assert_eq!(stats.triangles, 2, "both floor triangles face the eye");
    // The lower half of the view sees the floor, all the way down to the bottom row.
    for y in 30..48 {
        for x in 0..48 {
            assert!(fb.covered(x, y), "pixel ({x}, {y}) should show the floor");
            let c = fb.at(x, y);
            assert!((c - Vec3::new(0.5, 1.0, 0.5)).length() < 1e-4, "normal {c}");
        }
    }
    // The upper rows see the sky above the horizon.
    assert!(!fb.covered(24, 2), "sky above the horizon");
}
