//! A perspective camera: where the eye is, what it looks at, and how wide it sees.

use glam::camera::rh::{proj, view};
use glam::{Mat4, Vec3};

/// A right-handed perspective camera (`y` up), with depth mapped to `[0, 1]` between the near and
/// far planes (glam's right-handed DirectX-convention projection).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye position (the viewer of [`phong::Viewer::At`]).
    pub eye: Vec3,
    /// The point the camera looks at.
    pub target: Vec3,
    /// The up direction (need not be perpendicular to the view direction).
    pub up: Vec3,
    /// Vertical field of view in radians.
    pub fov_y: f32,
    /// Distance to the near clipping plane, `> 0`.
    pub near: f32,
    /// Distance to the far clipping plane, `> near`.
    pub far: f32,
}

impl Camera {
    /// A camera at `eye` looking at `target`, `y` up, 35° vertical field of view.
    #[must_use]
    pub fn look_at(eye: Vec3, target: Vec3) -> Self {
        Camera {
            eye,
            target,
            up: Vec3::Y,
            fov_y: 35f32.to_radians(),
            near: 0.05,
            far: 200.0,
        }
    }

    /// The same camera with another vertical field of view (in degrees).
    #[must_use]
    pub fn with_fov_degrees(self, fov: f32) -> Self {
        Camera {
            fov_y: fov.to_radians(),
            ..self
        }
    }

    /// World → clip space for an image of the given aspect ratio (width / height).
    #[must_use]
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        proj::directx::perspective(self.fov_y, aspect, self.near, self.far)
            * view::look_at_mat4(self.eye, self.target, self.up)
    }

    /// The pixel (x right, y down, pixel centres at `+0.5`) a world point projects to, or `None`
    /// behind the near plane.
    #[must_use]
    pub fn project(&self, p: Vec3, width: usize, height: usize) -> Option<(f32, f32)> {
        let c = self.view_projection(width as f32 / height as f32) * p.extend(1.0);
        if c.z < 0.0 || c.w <= 0.0 {
            return None;
        }
        let (x, y) = (c.x / c.w, c.y / c.w);
        Some((
            (x * 0.5 + 0.5) * width as f32,
            (0.5 - y * 0.5) * height as f32,
        ))
    }
}
