//! Indexed triangle meshes and the shapes the gallery draws: icosphere, cube, plane.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

/// An indexed triangle mesh with per-vertex normals and texture coordinates.
///
/// Triangles wind counter-clockwise seen from outside; normals come from
/// [`phong::vertex_normals`] (area-weighted face normals), so a vertex shared by faces is smooth
/// and a vertex used by one face only (the cube's corners are split per face) is flat.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions in object space.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals in object space.
    pub normals: Vec<Vec3>,
    /// Texture coordinates, `[0, 1]²` over the shape.
    pub uvs: Vec<Vec2>,
    /// Vertex indices, three per triangle.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// A mesh from positions, texture coordinates and triangles, with normals from
    /// [`phong::vertex_normals`].
    #[must_use]
    pub fn new(positions: Vec<Vec3>, uvs: Vec<Vec2>, triangles: Vec<[u32; 3]>) -> Self {
        let mut normals = vec![Vec3::ZERO; positions.len()];
        phong::vertex_normals(&positions, &triangles, &mut normals);
        Mesh {
            positions,
            normals,
            uvs,
            triangles,
        }
    }

    /// A unit sphere from an icosahedron whose faces are split in four `subdivisions` times:
    /// `20·4ᵏ` triangles, no seams and no poles. `k = 1` or 2 is low-poly, 4 looks smooth.
    #[must_use]
    pub fn icosphere(subdivisions: u32) -> Self {
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let mut positions: Vec<Vec3> = [
            (-1.0, t, 0.0),
            (1.0, t, 0.0),
            (-1.0, -t, 0.0),
            (1.0, -t, 0.0),
            (0.0, -1.0, t),
            (0.0, 1.0, t),
            (0.0, -1.0, -t),
            (0.0, 1.0, -t),
            (t, 0.0, -1.0),
            (t, 0.0, 1.0),
            (-t, 0.0, -1.0),
            (-t, 0.0, 1.0),
        ]
        .iter()
        .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
        .collect();
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            let mut midpoint: HashMap<(u32, u32), u32> = HashMap::new();
            let mut mid = |a: u32, b: u32, positions: &mut Vec<Vec3>| -> u32 {
                let key = (a.min(b), a.max(b));
                *midpoint.entry(key).or_insert_with(|| {
                    let p = (positions[a as usize] + positions[b as usize]).normalize();
                    positions.push(p);
                    (positions.len() - 1) as u32
                })
            };
            let mut next = Vec::with_capacity(triangles.len() * 4);
            for [a, b, c] in triangles {
                let ab = mid(a, b, &mut positions);
                let bc = mid(b, c, &mut positions);
                let ca = mid(c, a, &mut positions);
                next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            triangles = next;
        }
        orient_outward(&positions, &mut triangles);
        let uvs = positions
            .iter()
            .map(|p| {
                Vec2::new(
                    0.5 + p.z.atan2(p.x) / std::f32::consts::TAU,
                    0.5 - p.y.asin() / std::f32::consts::PI,
                )
            })
            .collect();
        Mesh::new(positions, uvs, triangles)
    }

    /// The unit cube `[−½, ½]³`, two triangles per face and four vertices per face, so each face
    /// is flat (as in LearnOpenGL's lit cube, "Basic Lighting").
    #[must_use]
    pub fn cube() -> Self {
        let mut positions = Vec::new();
        let mut uvs = Vec::new();
        let mut triangles = Vec::new();
        for n in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            let u = if n.y.abs() > 0.5 {
                Vec3::X
            } else {
                Vec3::Y.cross(n)
            };
            let v = n.cross(u);
            let base = positions.len() as u32;
            for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                positions.push(0.5 * (n + su * u + sv * v));
                uvs.push(Vec2::new(0.5 + 0.5 * su, 0.5 - 0.5 * sv));
            }
            triangles.push([base, base + 1, base + 2]);
            triangles.push([base, base + 2, base + 3]);
        }
        Mesh::new(positions, uvs, triangles)
    }

    /// A square in the `y = 0` plane from `−half` to `half` in `x` and `z`, facing `+y`, split into
    /// `cells × cells` quads; `uv` runs over `[0, 1]²`.
    #[must_use]
    pub fn plane(half: f32, cells: u32) -> Self {
        let cells = cells.max(1);
        let k = cells + 1;
        let mut positions = Vec::new();
        let mut uvs = Vec::new();
        for j in 0..k {
            for i in 0..k {
                let (u, v) = (i as f32 / cells as f32, j as f32 / cells as f32);
                positions.push(Vec3::new(
                    (2.0 * u - 1.0) * half,
                    0.0,
                    (2.0 * v - 1.0) * half,
                ));
                uvs.push(Vec2::new(u, v));
            }
        }
        let mut triangles = Vec::new();
        for j in 0..cells {
            for i in 0..cells {
                let a = j * k + i;
                let (b, c, d) = (a + 1, a + k + 1, a + k);
                // Counter-clockwise seen from +y: (d − a) × (b − a) = z × x = +y.
                triangles.push([a, d, c]);
                triangles.push([a, c, b]);
            }
        }
        Mesh::new(positions, uvs, triangles)
    }
}

/// Flips any triangle of a closed convex mesh around the origin whose winding points inward.
fn orient_outward(positions: &[Vec3], triangles: &mut [[u32; 3]]) {
    for t in triangles.iter_mut() {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        if (b - a).cross(c - a).dot(a + b + c) < 0.0 {
            t.swap(1, 2);
        }
    }
}
