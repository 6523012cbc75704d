//! Drawing a mesh: near-plane clipping, a depth test, perspective-correct barycentric
//! interpolation, and three shading rates. Per-pixel shading is deferred: the rasterizer keeps
//! each visible pixel's interpolated position, normal and texture coordinate (a G-buffer), and
//! shades them all at once at the end of the draw, through [`SurfaceShader::shade_many`].

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use crate::{Camera, Framebuffer, Mesh};

/// Where the lighting equation is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShadingMode {
    /// Gouraud: shade each vertex, interpolate the colours.
    PerVertex,
    /// Phong shading: interpolate the normal, renormalise it, shade each pixel (deferred: every
    /// visible pixel of a draw is shaded once, after the depth test).
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

    /// `out[i] = shade(positions[i], normals[i], uvs[i])` for every `i`: what [`draw`] calls once
    /// per draw with the visible pixels of its per-pixel triangles. The default shades one point
    /// at a time; a shader with a batch path (the crate's [`PhongShader`](crate::PhongShader))
    /// overrides it. The four slices have the same length.
    fn shade_many(&self, positions: &[Vec3], normals: &[Vec3], uvs: &[Vec2], out: &mut [Vec3]) {
        shade_each(self, positions, normals, uvs, out);
    }
}

/// [`SurfaceShader::shade_many`] one point at a time.
pub fn shade_each<S: SurfaceShader + ?Sized>(
    shader: &S,
    positions: &[Vec3],
    normals: &[Vec3],
    uvs: &[Vec2],
    out: &mut [Vec3],
) {
    debug_assert!(
        positions.len() == out.len() && normals.len() == out.len() && uvs.len() == out.len(),
        "shade_many: slices of different lengths"
    );
    for (((o, p), n), t) in out.iter_mut().zip(positions).zip(normals).zip(uvs) {
        *o = shader.shade(*p, *n, *t);
    }
}

/// The per-pixel fragments of one draw that passed the depth test when they were drawn: the
/// pixel, the triangle and the interpolated attributes. A fragment is still visible at the end of
/// the draw when its pixel still shows its triangle.
#[derive(Default)]
struct Deferred {
    fragments: Vec<Fragment>,
}

/// One per-pixel fragment: where it is, which triangle drew it, and what the shader gets.
#[derive(Clone, Copy)]
struct Fragment {
    pixel: u32,
    triangle: u32,
    position: Vec3,
    normal: Vec3,
    uv: Vec2,
}

std::thread_local! {
    /// The fragment list, kept from one draw to the next on each thread.
    static SCRATCH: std::cell::Cell<Vec<Fragment>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Fragments shaded per [`SurfaceShader::shade_many`] call, gathered in stack arrays.
const CHUNK: usize = 1024;

impl Deferred {
    /// Shades the fragments still visible (one per pixel: a triangle covers a pixel once, and a
    /// later fragment at the same pixel replaced the triangle id), `CHUNK` at a time, and writes
    /// their colours. Returns how many were shaded.
    fn resolve<S: SurfaceShader + ?Sized>(&self, fb: &mut Framebuffer, shader: &S) -> usize {
        let mut pixel = [0usize; CHUNK];
        let mut position = [Vec3::ZERO; CHUNK];
        let mut normal = [Vec3::ZERO; CHUNK];
        let mut uv = [Vec2::ZERO; CHUNK];
        let mut colour = [Vec3::ZERO; CHUNK];
        let mut shaded = 0;
        let mut live = self
            .fragments
            .iter()
            .filter(|f| fb.triangle[f.pixel as usize] == f.triangle)
            .peekable();
        while live.peek().is_some() {
            let mut k = 0;
            for f in live.by_ref().take(CHUNK) {
                pixel[k] = f.pixel as usize;
                (position[k], normal[k], uv[k]) = (f.position, f.normal, f.uv);
                k += 1;
            }
            shader.shade_many(&position[..k], &normal[..k], &uv[..k], &mut colour[..k]);
            for (&i, &c) in pixel[..k].iter().zip(&colour[..k]) {
                fb.color[i] = c;
            }
            shaded += k;
        }
        shaded
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
    /// Points shaded: vertices of per-vertex triangles, and the pixels of per-pixel triangles
    /// still visible at the end of the draw (each shaded once, through
    /// [`SurfaceShader::shade_many`]).
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
    // The fragment list of the previous draw on this thread, emptied: its memory is already
    // mapped, where a new list of a frame's size would fault its pages in at every draw.
    let mut deferred = Deferred {
        fragments: SCRATCH.with(|s| s.take()),
    };
    deferred.fragments.clear();

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
        let id = t_index as u32 + 1;
        let uvs = idx.map(uv);
        for k in 1..poly.len().saturating_sub(1) {
            let sub = [poly[0], poly[k], poly[k + 1]];
            raster_triangle(fb, &sub, id, &mut stats, |i, b| {
                if per_vertex {
                    Some(colours[0] * b.x + colours[1] * b.y + colours[2] * b.z)
                } else {
                    deferred.fragments.push(Fragment {
                        pixel: i as u32,
                        triangle: id,
                        position: p[0] * b.x + p[1] * b.y + p[2] * b.z,
                        normal: n[0] * b.x + n[1] * b.y + n[2] * b.z,
                        uv: uvs[0] * b.x + uvs[1] * b.y + uvs[2] * b.z,
                    });
                    None
                }
            });
        }
    }
    let shaded = deferred.resolve(fb, shader);
    stats.shader_calls += shaded;
    SCRATCH.with(|s| s.replace(deferred.fragments));
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
/// depth. `colour` gets the pixel's index and the perspective-correct barycentric coordinates in
/// the original triangle, and returns the colour to store now, or `None` when the pixel is shaded
/// later (deferred).
fn raster_triangle(
    fb: &mut Framebuffer,
    v: &[ClipVertex; 3],
    id: u32,
    stats: &mut DrawStats,
    mut colour: impl FnMut(usize, Vec3) -> Option<Vec3>,
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
            if let Some(c) = colour(i, bary) {
                fb.color[i] = c;
            }
            stats.pixels += 1;
        }
    }
}
