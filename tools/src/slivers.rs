//! The sliver study: an adversarial set of thin triangles, the candidate methods for their normal,
//! and the angular error of each against the exact normal of the `f32` vertices.

use glam::{DVec3, Vec3};

use crate::reference;
use crate::rng::Rng;

/// The two kinds of sliver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// One short edge: two long, nearly parallel edges meet at a sharp tip.
    Needle,
    /// No short edge: one angle close to 180°, the third vertex just off the longest edge.
    Cap,
}

/// One triangle of the set, with the parameters it was made from.
#[derive(Clone, Copy, Debug)]
pub struct Sliver {
    /// Which kind of sliver.
    pub shape: Shape,
    /// Height over longest edge.
    pub aspect: f64,
    /// Length of the longest edge.
    pub size: f64,
    /// Distance of the triangle from the origin.
    pub offset: f64,
    /// The vertices.
    pub p: [Vec3; 3],
}

/// The aspect ratios (height over longest edge) of the set.
pub const ASPECTS: [f64; 5] = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5];
/// The longest edges of the set.
pub const SIZES: [f64; 3] = [1e-2, 1e-1, 1.0];
/// The distances from the origin of the set.
pub const OFFSETS: [f64; 6] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5];
const PERMUTATIONS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// The adversarial set: every shape × aspect × size × offset, `per_cell` random orientations and
/// placements each, every one of the 6 vertex orders. Triangles whose `f32` vertices have exactly
/// zero area (the sliver was rounded flat) are left out and counted in the second return value.
pub fn sliver_set(rng: &mut Rng, per_cell: usize) -> (Vec<Sliver>, usize) {
    let mut out = Vec::new();
    let mut flat = 0;
    for shape in [Shape::Needle, Shape::Cap] {
        for aspect in ASPECTS {
            for size in SIZES {
                for offset in OFFSETS {
                    for _ in 0..per_cell {
                        let u = rng.unit_dvec3();
                        let w = rng.unit_dvec3().reject_from_normalized(u).normalize();
                        let h = aspect * size;
                        let (a, b, c) = match shape {
                            Shape::Needle => {
                                // Short edge from the tip B, leaning along u by up to ±h.
                                let b = size * u;
                                (DVec3::ZERO, b, b + h * w + rng.range(-h, h) * u)
                            }
                            Shape::Cap => (
                                DVec3::ZERO,
                                size * u,
                                rng.range(0.1, 0.9) * size * u + h * w,
                            ),
                        };
                        let o = offset * rng.unit_dvec3();
                        let q = [a, b, c].map(|x| (o + x).as_vec3());
                        if reference::triangle_area_normal(q[0], q[1], q[2]) == DVec3::ZERO {
                            flat += 6;
                            continue;
                        }
                        for perm in PERMUTATIONS {
                            out.push(Sliver {
                                shape,
                                aspect,
                                size,
                                offset,
                                p: perm.map(|i| q[i]),
                            });
                        }
                    }
                }
            }
        }
    }
    (out, flat)
}

/// A method for the (unnormalised) normal of a triangle.
pub struct Candidate {
    /// The method's name in the tables.
    pub name: &'static str,
    /// The method.
    pub run: fn(Vec3, Vec3, Vec3) -> Vec3,
}

/// Naive `f32`: `(P1 − P0) × (P2 − P0)`.
pub fn naive(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    (p1 - p0).cross(p2 - p0)
}

/// Pivoting: the cross product of the two edges leaving the vertex opposite the longest edge
/// (the two shorter edges), in the cyclic order that keeps the orientation.
pub fn pivot(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    let l0 = (p2 - p1).length_squared(); // opposite P0
    let l1 = (p0 - p2).length_squared(); // opposite P1
    let l2 = (p1 - p0).length_squared(); // opposite P2
    if l0 >= l1 && l0 >= l2 {
        (p1 - p0).cross(p2 - p0)
    } else if l1 >= l2 {
        (p2 - p1).cross(p0 - p1)
    } else {
        (p0 - p2).cross(p1 - p2)
    }
}

/// `a·b − c·d` by Kahan's algorithm: one FMA recovers the rounding error of `c·d` exactly.
pub fn kahan_diff_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let w = c * d;
    let e = (-c).mul_add(d, w);
    let f = a.mul_add(b, -w);
    f + e
}

/// The cross product of the `f32` edges with every component by Kahan's difference of products.
pub fn kahan(p0: Vec3, p1: Vec3, p2: Vec3) -> Vec3 {
    let (a, b) = (p1 - p0, p2 - p0);
    Vec3::new(
        kahan_diff_of_products(a.y, b.z, a.z, b.y),
        kahan_diff_of_products(a.z, b.x, a.x, b.z),
        kahan_diff_of_products(a.x, b.y, a.y, b.x),
    )
}

/// The candidates in table order; the crate's own function last.
pub fn candidates() -> [Candidate; 4] {
    [
        Candidate {
            name: "naive f32 (P1−P0)×(P2−P0)",
            run: naive,
        },
        Candidate {
            name: "pivot at the vertex opposite the longest edge",
            run: pivot,
        },
        Candidate {
            name: "Kahan FMA difference of products",
            run: kahan,
        },
        Candidate {
            name: "`phong::triangle_normal_or_zero` (exact area vector)",
            run: phong::triangle_normal_or_zero,
        },
    ]
}

/// The angle in radians between `got` and the exact normal of the triangle; `π` for a zero or
/// non-finite answer (the method lost the normal entirely).
pub fn angular_error(got: Vec3, t: &Sliver) -> f64 {
    let exact = reference::triangle_area_normal(t.p[0], t.p[1], t.p[2]);
    angle_between(got.as_dvec3(), exact)
}

/// The angle between two non-zero vectors, accurate for tiny angles.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    if !a.is_finite() || a == DVec3::ZERO || b == DVec3::ZERO {
        return core::f64::consts::PI;
    }
    let (a, b) = (a.normalize(), b.normalize());
    a.cross(b).length().atan2(a.dot(b))
}

/// Worst and median of a list of errors, and how many were total losses (`π`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Summary {
    /// The largest error.
    pub worst: f64,
    /// The median error.
    pub median: f64,
    /// The 99th percentile.
    pub p99: f64,
    /// Errors of `π` or more: the normal lost entirely.
    pub lost: usize,
    /// Errors summarised.
    pub n: usize,
}

/// The [`Summary`] of the errors `e`.
pub fn summarize(mut e: Vec<f64>) -> Summary {
    if e.is_empty() {
        return Summary::default();
    }
    e.sort_by(f64::total_cmp);
    let lost = e.iter().filter(|&&x| x >= core::f64::consts::PI).count();
    Summary {
        worst: e[e.len() - 1],
        median: e[e.len() / 2],
        p99: e[(e.len() * 99) / 100],
        lost,
        n: e.len(),
    }
}

/// Each candidate's summary over the triangles `filter` accepts.
pub fn study(set: &[Sliver], filter: impl Fn(&Sliver) -> bool) -> Vec<(&'static str, Summary)> {
    candidates()
        .iter()
        .map(|c| {
            let errs = set
                .iter()
                .filter(|t| filter(t))
                .map(|t| angular_error((c.run)(t.p[0], t.p[1], t.p[2]), t))
                .collect();
            (c.name, summarize(errs))
        })
        .collect()
}
