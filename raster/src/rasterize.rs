//! Drawing a mesh: near-plane clipping, a depth test, perspective-correct barycentric
//! interpolation, and three shading rates.

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use crate::{Camera, Framebuffer, Mesh};

/// Where the lighting equation is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadingMode {
    /// Gouraud: shade each vertex, interpolate the colours.
    PerVertex,
    /// Phong shading: interpolate the normal, renormalise it, shade each pixel.
    PerPixel,
    /// Per vertex where [`SurfaceShader::per_vertex_ok`] says the difference is within its
    /// tolerance, per pixel elsewhere; decided once per triangle.
    Adaptive,
}

/// What a pixel's colour is, given the interpolated surface attributes (in world space).
pub trait SurfaceShader {
    /// The linear colour at `position` with (not necessarily unit) `normal` and texture
    /// coordinate `uv`.
    fn shade(&self, position: Vec3, normal: Vec3, uv: Vec2) -> Vec3;

    /// Whether per-vertex shading of this triangle is close enough to per-pixel shading. Used by
    /// [`ShadingMode::Adaptive`]; the default says no.
    fn per_vertex_ok(&self, _positions: [Vec3; 3], _normals: [Vec3; 3]) -> bool {
        false
    }
}

/// What one [`draw`] call did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawStats {
    /// Front-facing triangles (the ones sent to the rasterizer).
    pub triangles: usize,
    /// Of those, the ones shaded per vertex.
    pub per_vertex: usize,
    /// Pixels written (after the depth test).
    pub pixels: usize,
    /// Calls to [`SurfaceShader::shade`].
    pub shader_calls: usize,
}

impl std::ops::AddAssign for DrawStats {
    fn add_assign(&mut self, o: DrawStats) {
        self.triangles += o.triangles;
        self.per_vertex += o.per_vertex;
        self.pixels += o.pixels;
        self.shader_calls += o.shader_calls;
    }
}

/// A vertex after clipping: clip-space position and barycentric coordinates in the original
/// triangle.
#[derive(Clone, Copy)]
struct ClipVertex {
    clip: Vec4,
    bary: Vec3,
}

/// Draws `mesh`, placed in the world by `model`, into `fb` as seen by `camera`.
///
/// Positions go to world space with `model`, normals with [`phong::normal_matrix`] of its upper
/// 3×3 and [`phong::transform_normal`]. Back faces (seen from the eye) are skipped. Triangles are
/// clipped against the near plane; attributes are interpolated with perspective-correct
/// barycentric coordinates, so a pixel's weights are those of the surface point it shows.
pub fn draw<S: SurfaceShader>(
    fb: &mut Framebuffer,
    camera: &Camera,
    mesh: &Mesh,
    model: Mat4,
    shader: &S,
    mode: ShadingMode,
) -> DrawStats {
    let mut stats = DrawStats::default();
    let vp = camera.view_projection(fb.width as f32 / fb.height as f32);
    let nm = phong::normal_matrix(Mat3::from_mat4(model));
    let world: Vec<Vec3> = mesh
        .positions
        .iter()
        .map(|p| model.transform_point3(*p))
        .collect();
    let normals: Vec<Vec3> = mesh
        .normals
        .iter()
        .map(|n| phong::transform_normal(nm, *n))
        .collect();
    let clip: Vec<Vec4> = world.iter().map(|p| vp * p.extend(1.0)).collect();
    let uv = |i: usize| mesh.uvs.get(i).copied().unwrap_or(Vec2::ZERO);
    // Per-vertex colours are shared by the triangles around a vertex.
    let mut vertex_colour: Vec<Option<Vec3>> = vec![None; world.len()];

    for (t_index, tri) in mesh.triangles.iter().enumerate() {
        let idx = tri.map(|i| i as usize);
        let p = idx.map(|i| world[i]);
        let n = idx.map(|i| normals[i]);
        let facing = (p[1] - p[0]).cross(p[2] - p[0]).dot(camera.eye - p[0]);
        if !(facing > 0.0) {
            continue;
        }
        stats.triangles += 1;
        let per_vertex = match mode {
            ShadingMode::PerVertex => true,
            ShadingMode::PerPixel => false,
            ShadingMode::Adaptive => shader.per_vertex_ok(p, n),
        };
        let colours = if per_vertex {
            stats.per_vertex += 1;
            idx.map(|i| {
                *vertex_colour[i].get_or_insert_with(|| {
                    stats.shader_calls += 1;
                    shader.shade(world[i], normals[i], uv(i))
                })
            })
        } else {
            [Vec3::ZERO; 3]
        };
        let uvs = idx.map(uv);
        let poly = clip_near([
            ClipVertex {
                clip: clip[idx[0]],
                bary: Vec3::X,
            },
            ClipVertex {
                clip: clip[idx[1]],
                bary: Vec3::Y,
            },
            ClipVertex {
                clip: clip[idx[2]],
                bary: Vec3::Z,
            },
        ]);
        for k in 1..poly.len().saturating_sub(1) {
            let sub = [poly[0], poly[k], poly[k + 1]];
            let before = stats.pixels;
            raster_triangle(fb, &sub, t_index as u32 + 1, &mut stats, |b| {
                if per_vertex {
                    colours[0] * b.x + colours[1] * b.y + colours[2] * b.z
                } else {
                    let q = p[0] * b.x + p[1] * b.y + p[2] * b.z;
                    let m = n[0] * b.x + n[1] * b.y + n[2] * b.z;
                    let t = uvs[0] * b.x + uvs[1] * b.y + uvs[2] * b.z;
                    shader.shade(q, m, t)
                }
            });
            if !per_vertex {
                stats.shader_calls += stats.pixels - before;
            }
        }
    }
    stats
}

/// Sutherland–Hodgman against the near plane `z ≥ 0` (glam's depth range): up to 4 vertices.
fn clip_near(v: [ClipVertex; 3]) -> Vec<ClipVertex> {
    let mut out = Vec::with_capacity(4);
    for i in 0..3 {
        let (a, b) = (v[i], v[(i + 1) % 3]);
        let (da, db) = (a.clip.z, b.clip.z);
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push(ClipVertex {
                clip: a.clip + (b.clip - a.clip) * t,
                bary: a.bary + (b.bary - a.bary) * t,
            });
        }
    }
    out
}

/// Fills one clipped triangle: pixel centres inside all three edges, nearer than the stored
/// depth. `colour` gets the perspective-correct barycentric coordinates in the original
/// triangle.
fn raster_triangle(
    fb: &mut Framebuffer,
    v: &[ClipVertex; 3],
    id: u32,
    stats: &mut DrawStats,
    mut colour: impl FnMut(Vec3) -> Vec3,
) {
    let (w, h) = (fb.width as f32, fb.height as f32);
    let screen = v.map(|c| {
        let inv_w = 1.0 / c.clip.w;
        Vec3::new(
            (c.clip.x * inv_w * 0.5 + 0.5) * w,
            (0.5 - c.clip.y * inv_w * 0.5) * h,
            c.clip.z * inv_w,
        )
    });
    let inv_w = v.map(|c| 1.0 / c.clip.w);
    let edge = |a: Vec3, b: Vec3, x: f32, y: f32| (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
    let area = edge(screen[0], screen[1], screen[2].x, screen[2].y);
    if !(area.abs() > 1e-12) || !area.is_finite() {
        return;
    }
    let min_x = screen.iter().map(|s| s.x).fold(f32::INFINITY, f32::min);
    let max_x = screen.iter().map(|s| s.x).fold(f32::NEG_INFINITY, f32::max);
    let min_y = screen.iter().map(|s| s.y).fold(f32::INFINITY, f32::min);
    let max_y = screen.iter().map(|s| s.y).fold(f32::NEG_INFINITY, f32::max);
    let x0 = (min_x - 0.5).ceil().max(0.0) as usize;
    let y0 = (min_y - 0.5).ceil().max(0.0) as usize;
    let x1 = ((max_x - 0.5).floor().min(w - 1.0)).max(-1.0);
    let y1 = ((max_y - 0.5).floor().min(h - 1.0)).max(-1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return;
    }
    let (x1, y1) = (x1 as usize, y1 as usize);
    for y in y0..=y1 {
        let py = y as f32 + 0.5;
        for x in x0..=x1 {
            let px = x as f32 + 0.5;
            let l0 = edge(screen[1], screen[2], px, py) / area;
            let l1 = edge(screen[2], screen[0], px, py) / area;
            let l2 = 1.0 - l0 - l1;
            if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                continue;
            }
            let z = l0 * screen[0].z + l1 * screen[1].z + l2 * screen[2].z;
            let i = y * fb.width + x;
            if !(z < fb.depth[i]) || z > 1.0 {
                continue;
            }
            let (a, b, c) = (l0 * inv_w[0], l1 * inv_w[1], l2 * inv_w[2]);
            let s = a + b + c;
            let bary = (v[0].bary * a + v[1].bary * b + v[2].bary * c) / s;
            fb.depth[i] = z;
            fb.triangle[i] = id;
            fb.color[i] = colour(bary);
            stats.pixels += 1;
        }
    }
}
