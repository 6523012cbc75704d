//! Smooth per-vertex normals for an indexed triangle mesh.

use glam::Vec3;

use crate::{normalize_or_zero, triangle_area_normal};

/// Fills `normals[i]` with the area-weighted average of the face normals around vertex `i`.
///
/// ```text
/// n_i = normalize( Σ_{faces f ∋ i} A_f ),     A_f = (P1 − P0) × (P2 − P0)  (‖A_f‖ = 2·area)
/// ```
///
/// Summing the unnormalised area vectors weights each face by its area, so large faces dominate and
/// slivers barely count. The face vectors come from [`triangle_area_normal`], which is exact for
/// slivers.
///
/// **Domain:** `positions` finite; `triangles` index into `positions` with counter-clockwise winding.
/// `normals` should have `positions.len()` entries.
///
/// **Degenerate input:** a vertex used by no triangle, or whose faces cancel (e.g. a flat fan around
/// a fold), gets the zero vector. A triangle with an index out of range is skipped (debug builds
/// assert). Only the first `min(normals.len(), positions.len())` vertices are written.
///
/// ```
/// use glam::Vec3;
/// let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
/// let tris = [[0, 2, 1], [0, 1, 3]]; // two faces meeting at the x axis
/// let mut n = [Vec3::ZERO; 4];
/// phong::vertex_normals(&p, &tris, &mut n);
/// assert_eq!(n[2], -Vec3::Z);
/// assert!((n[0] - Vec3::new(0.0, -1.0, -1.0).normalize()).length() < 1e-6);
/// ```
pub fn vertex_normals(positions: &[Vec3], triangles: &[[u32; 3]], normals: &mut [Vec3]) {
    let n = normals.len().min(positions.len());
    let normals = &mut normals[..n];
    normals.fill(Vec3::ZERO);
    for t in triangles {
        let [i0, i1, i2] = t.map(|i| i as usize);
        let (Some(&p0), Some(&p1), Some(&p2)) =
            (positions.get(i0), positions.get(i1), positions.get(i2))
        else {
            debug_assert!(
                false,
                "vertex_normals: triangle {t:?} indexes past the positions"
            );
            continue;
        };
        let a = triangle_area_normal(p0, p1, p2);
        for i in [i0, i1, i2] {
            if let Some(slot) = normals.get_mut(i) {
                *slot += a;
            }
        }
    }
    for slot in normals.iter_mut() {
        *slot = normalize_or_zero(*slot);
    }
}
