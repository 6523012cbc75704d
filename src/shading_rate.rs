//! The shading-rate advisor: a proven bound on how far Gouraud (per-vertex) shading of a triangle
//! can be from per-pixel shading, so a renderer can shade per vertex wherever that is invisible.
//!
//! **What is compared.** Inside a triangle with vertices `Pᵢ`, unit vertex normals `nᵢ` and
//! barycentric coordinates `b` (perspective-correct, so `b` are the coordinates of the surface
//! point itself), per-pixel ("Phong") shading evaluates the shaded value `F` at the point
//! `P(b) = Σ bᵢPᵢ` with the normal `normalize(Σ bᵢnᵢ)`; Gouraud shading evaluates `F` at the three
//! vertices and interpolates, `G(b) = Σ bᵢ F(Pᵢ)`. The advisor bounds `max_b |G(b) − F(b)|`.
//!
//! **How.** Along any straight unit-speed path in the triangle, every ingredient of `F` (the
//! cosines `N·L`, `N·V`, `L·V`, the distance to the light, the attenuation, the spot cone, the
//! lobe powers) gets a *jet*: an interval holding its values and bounds on its first and second
//! derivatives, propagated by the product and chain rules. If `F` has a Lipschitz gradient with
//! constant `M₂` (a bound on `|F''|`), Taylor's theorem around the pixel gives
//!
//! ```text
//! |G(b) − F(b)| ≤ ½ · M₂ · Σ bᵢ‖Pᵢ − P(b)‖² ≤ ½ · M₂ · r²
//! ```
//!
//! with `r` the radius of the triangle's smallest enclosing circle. Where `F` has a kink or a jump
//! inside the triangle (a terminator, Phong's cut-off at `s < 2`, a step gate, a spot cone edge), the
//! bound falls back to the width of `F`'s interval: `G` and `F` both lie in it. The result is the
//! smaller of the two, plus a rounding allowance, taken for the ambient, diffuse and specular parts
//! of each light apart. The rounding allowance is the evaluation's own: each jet also carries how
//! far an `f32` evaluation of its function can be from the exact value (every cosine off by an
//! absolute `η`, the distance by its rounding, the lobe power by its pow strategy's error), and
//! the intervals are widened by the same amounts, so both the Taylor and the width bound hold for
//! the computed shadings (see [`gouraud_error_bound`]). A directional light's diffuse part has an exact form,
//! `(Σ bᵢcᵢ)(1 − 1/‖Σ bᵢnᵢ‖)` plus a Jensen gap at the terminator, and gets the sharper bound
//! `max(B(1/μ − 1), AB/(A+B))` from it. The derivation with every constant is in
//! docs/derivations.md, section "Shading-rate bound".

use glam::{DVec3, Vec3};

use crate::light::{Light, LightSource};
use crate::material::Material;
use crate::math;
use crate::model::Model;
use crate::normalization::Normalization;
use crate::normalize_or_zero;
use crate::pow::PowStrategy;
use crate::shade::{Scene, Viewer};
use crate::{Attenuation, SpecularGate};

/// `2/√3`: the largest `|N''|` per `|m'|²/|m|²` for `N = m/|m|` with `m'' = 0`.
const TWO_OVER_SQRT3: f32 = 1.154_700_5;

/// Absolute slack added to intervals computed from `f32` vertex values (at least; the cosines get
/// their rounding allowance `η` when it is larger).
const ROUND_ABS: f32 = 1e-6;

/// `f32`'s unit roundoff, `2⁻²⁴`.
const U: f32 = f32::EPSILON * 0.5;

/// Bounds on a scalar function on the triangle: its values lie in `[lo, hi]`, and along any
/// straight unit-speed path inside the triangle `|F'| ≤ d1` and `F'` is Lipschitz with constant
/// `d2`. `d2 = ∞` means "no such constant": only the interval is known.
///
/// `s1` bounds how far an `f32` evaluation of the function at one point can be from its exact
/// value there, from its inputs' rounding: every cosine off by up to its allowance `η`, the
/// distance to the light by up to its allowance, the lobe power by its strategy's error. The
/// interval already contains those perturbed values (its inputs' intervals are widened by the
/// allowances), so only the Taylor bound needs `s1` added.
#[derive(Clone, Copy, Debug)]
struct Jet {
    lo: f32,
    hi: f32,
    d1: f32,
    d2: f32,
    s1: f32,
}

/// `a·b` with `0·∞ = 0`: a factor that is exactly zero kills an unknown derivative bound.
#[inline]
fn mulz(a: f32, b: f32) -> f32 {
    if a == 0.0 || b == 0.0 { 0.0 } else { a * b }
}

impl Jet {
    const ZERO: Jet = Jet::constant(0.0);

    const fn constant(x: f32) -> Jet {
        Jet {
            lo: x,
            hi: x,
            d1: 0.0,
            d2: 0.0,
            s1: 0.0,
        }
    }

    /// Only the interval is known.
    fn rough(lo: f32, hi: f32) -> Jet {
        Jet {
            lo,
            hi,
            d1: f32::INFINITY,
            d2: f32::INFINITY,
            s1: f32::INFINITY,
        }
    }

    fn is_zero(&self) -> bool {
        self.lo == 0.0 && self.hi == 0.0 && self.d1 == 0.0 && self.d2 == 0.0 && self.s1 == 0.0
    }

    fn abs_max(&self) -> f32 {
        math::abs(self.lo).max(math::abs(self.hi))
    }

    fn add(self, o: Jet) -> Jet {
        Jet {
            lo: self.lo + o.lo,
            hi: self.hi + o.hi,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
            s1: self.s1 + o.s1,
        }
    }

    fn sub(self, o: Jet) -> Jet {
        Jet {
            lo: self.lo - o.hi,
            hi: self.hi - o.lo,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
            s1: self.s1 + o.s1,
        }
    }

    /// Scaling by `k ≥ 0`.
    fn scale(self, k: f32) -> Jet {
        if k == 0.0 {
            return Jet::ZERO;
        }
        Jet {
            lo: self.lo * k,
            hi: self.hi * k,
            d1: self.d1 * k,
            d2: self.d2 * k,
            s1: self.s1 * k,
        }
    }

    /// `(fg)' = f'g + fg'`, `(fg)'' = f''g + 2f'g' + fg''`; the perturbations the same way as the
    /// first derivative (the intervals already hold the perturbed values).
    fn mul(self, o: Jet) -> Jet {
        if self.is_zero() || o.is_zero() {
            return Jet::ZERO;
        }
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        let (a, b) = (self.abs_max(), o.abs_max());
        Jet {
            lo: p[0].min(p[1]).min(p[2]).min(p[3]),
            hi: p[0].max(p[1]).max(p[2]).max(p[3]),
            d1: mulz(a, o.d1) + mulz(b, self.d1),
            d2: mulz(a, o.d2) + 2.0 * mulz(self.d1, o.d1) + mulz(b, self.d2),
            s1: mulz(a, o.s1) + mulz(b, self.s1),
        }
    }

    /// `φ∘self` for `φ` with `|φ'| ≤ p1` and `|φ''| ≤ p2` (or `φ'` Lipschitz with `p2`) on
    /// `[self.lo, self.hi]`, whose values there lie in `[lo, hi]`.
    fn compose(self, lo: f32, hi: f32, p1: f32, p2: f32) -> Jet {
        Jet {
            lo,
            hi,
            d1: mulz(p1, self.d1),
            d2: mulz(p2, mulz(self.d1, self.d1)) + mulz(p1, self.d2),
            s1: mulz(p1, self.s1),
        }
    }

    /// `max(x, 0)`: the identity, zero, or a kink (which is still 1-Lipschitz).
    fn positive_part(self) -> Jet {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            Jet::ZERO
        } else {
            Jet {
                s1: self.s1,
                ..Jet::rough(0.0, self.hi)
            }
        }
    }

    /// `[x > 0]`.
    fn step(self) -> Jet {
        if self.lo > 0.0 {
            Jet::constant(1.0)
        } else if self.hi <= 0.0 {
            Jet::ZERO
        } else {
            Jet::rough(0.0, 1.0)
        }
    }

    /// The lobe power `max(x, 0)^s` with the crate's `0^0 = 0` rule, for `x ≤ 1`, `s ≥ 0`, as
    /// `pow` computes it: the exact power's jet, its interval widened and its `s1` increased by
    /// the strategy's error (`max_relative_error` relative to `max(x^s, 2⁻²⁴)`).
    fn lobe_pow(self, s: f32, pow: PowStrategy) -> Jet {
        let hi = self.hi.min(1.0);
        if hi <= 0.0 {
            // Every strategy gives exactly 0 for a base ≤ 0.
            return Jet::ZERO;
        }
        if s == 0.0 {
            // x^0 is exactly 1 for x > 0 with every strategy.
            return if self.lo > 0.0 {
                Jet::constant(1.0)
            } else {
                Jet::rough(0.0, 1.0)
            };
        }
        let top = math::powf(hi, s);
        let exact = if self.lo > 0.0 {
            // x^(s−1) and x^(s−2) are monotone in x: their sup over [lo, hi] is at an end.
            let lo = self.lo;
            let p1 = s * math::powf(lo, s - 1.0).max(math::powf(hi, s - 1.0));
            let p2 = s * math::abs(s - 1.0) * math::powf(lo, s - 2.0).max(math::powf(hi, s - 2.0));
            self.compose(math::powf(lo, s), top, p1, p2)
        } else if s >= 2.0 {
            // Crossing 0: max(x,0)^s is C¹ with a Lipschitz derivative for s ≥ 2.
            let p1 = s * math::powf(hi, s - 1.0);
            let p2 = s * (s - 1.0) * math::powf(hi, s - 2.0);
            self.compose(0.0, top, p1, p2)
        } else if s >= 1.0 {
            // Crossing 0 with a kink: Lipschitz still, with constant s·hi^(s−1).
            Jet {
                s1: mulz(s * math::powf(hi, s - 1.0), self.s1),
                ..Jet::rough(0.0, top)
            }
        } else {
            Jet::rough(0.0, top)
        };
        let eps = pow.max_relative_error();
        let floor = PowStrategy::ERROR_FLOOR;
        Jet {
            lo: (exact.lo - eps * exact.lo.max(floor)).max(0.0),
            hi: (exact.hi + eps * exact.hi.max(floor)).min(1.0),
            s1: exact.s1 + eps * exact.hi.max(floor),
            ..exact
        }
    }

    /// The half-width of the interval around the vertex values that holds a function with this
    /// `d2`: the interpolation error bound `½·d2·r²`, plus the values' rounding allowance `eta`.
    fn around(values: [f32; 3], d1: f32, d2: f32, r2: f32, lo: f32, hi: f32, eta: f32) -> Jet {
        let min = values[0].min(values[1]).min(values[2]);
        let max = values[0].max(values[1]).max(values[2]);
        let delta = 0.5 * mulz(d2, r2) + ROUND_ABS.max(eta);
        if !delta.is_finite() || !d1.is_finite() {
            return Jet::rough(lo, hi);
        }
        Jet {
            lo: (min - delta).max(lo),
            hi: (max + delta).min(hi),
            d1,
            d2,
            s1: eta,
        }
    }
}

/// Bounds on a unit-vector field `X(P)` along unit-speed paths: `|X'| ≤ a`, `|X''| ≤ b`.
#[derive(Clone, Copy, Debug)]
struct UnitJet {
    a: f32,
    b: f32,
}

impl UnitJet {
    const FIXED: UnitJet = UnitJet { a: 0.0, b: 0.0 };

    /// `X = (Q − P)/‖Q − P‖` toward a fixed point `Q` at least `d` from the triangle.
    fn toward_point(d: f32) -> UnitJet {
        if d > 0.0 {
            UnitJet {
                a: 1.0 / d,
                b: TWO_OVER_SQRT3 / (d * d),
            }
        } else {
            UnitJet {
                a: f32::INFINITY,
                b: f32::INFINITY,
            }
        }
    }
}

/// What the interpolated normal `N = m/‖m‖`, `m = Σ bᵢnᵢ`, can do on the triangle.
#[derive(Clone, Copy, Debug)]
struct NormalJet {
    /// `κ/μ ≥ |N'|`.
    a: f32,
    /// `κ²/μ²`: the part of `|N''·X|` proportional to `|N·X|`.
    k2: f32,
    /// `2·ρ·κ/μ²`: the rest of `|N''·X|`.
    cross: f32,
}

/// The cosine `N·X` as a jet, from its vertex values (`nᵢ·Xᵢ`).
///
/// `(N·X)'' = N''·X + 2N'·X' + N·X''` and, since `m'' = 0`,
/// `N''·X = −(‖m'⊥‖²/‖m‖²)(N·X) − 2(‖m‖'/‖m‖)(N'·X)`.
fn normal_cosine(values: [f32; 3], n: &NormalJet, x: UnitJet, r2: f32, eta: f32) -> Jet {
    let d1 = n.a + x.a;
    let mut c = 1.0f32;
    let mut jet = Jet::rough(-1.0, 1.0);
    // The bound on |N·X| refines d2, which refines the interval: two rounds.
    for _ in 0..2 {
        let d2 = n.k2 * c + n.cross + 2.0 * mulz(n.a, x.a) + x.b;
        jet = Jet::around(values, d1, d2, r2, -1.0, 1.0, eta);
        c = jet.abs_max().min(1.0);
    }
    jet
}

/// The cosine `X·Y` of two unit fields.
fn plain_cosine(values: [f32; 3], x: UnitJet, y: UnitJet, r2: f32, eta: f32) -> Jet {
    let d1 = x.a + y.a;
    let d2 = x.b + 2.0 * mulz(x.a, y.a) + y.b;
    Jet::around(values, d1, d2, r2, -1.0, 1.0, eta)
}

/// The attenuation factor as a jet of the distance `d ∈ [d0, d1]` (with `|d'| ≤ 1`,
/// `|d''| ≤ 1/d0`), whose computed value may be off by up to `eta` (the interval `[d0, d1]`
/// includes that allowance).
fn attenuation_jet(a: &Attenuation, d0: f32, d1: f32, eta: f32) -> Jet {
    let range_hi = a.factor(d0);
    let range_lo = a.factor(d1);
    let dist = Jet {
        lo: d0,
        hi: d1,
        d1: 1.0,
        d2: if d0 > 0.0 { 1.0 / d0 } else { f32::INFINITY },
        s1: eta,
    };
    let rough = Jet::rough(range_lo, range_hi);
    match *a {
        Attenuation::None => Jet::constant(1.0),
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => {
            let den0 = constant + d0 * (linear + quadratic * d0);
            if !(den0 >= Attenuation::MIN_DENOMINATOR) {
                return rough;
            }
            // |f'| = (l + 2qd)/den², |f''| ≤ 2(l + 2qd)²/den³ + 2q/den²; numerators grow and
            // denominators grow with d.
            let num = linear + 2.0 * quadratic * d1;
            let p1 = num / (den0 * den0);
            let p2 = 2.0 * num * num / (den0 * den0 * den0) + 2.0 * quadratic / (den0 * den0);
            dist.compose(range_lo, range_hi, p1, p2)
        }
        Attenuation::InverseSquare {
            power,
            min_distance,
        } => {
            if !(d0 >= min_distance && d0 > 0.0) {
                return rough;
            }
            let p1 = 2.0 * power / (d0 * d0 * d0);
            let p2 = 6.0 * power / (d0 * d0 * d0 * d0);
            dist.compose(range_lo, range_hi, p1, p2)
        }
        Attenuation::Unreal { radius } => {
            let g = Jet {
                lo: 1.0 / (d1 * d1 + 1.0),
                hi: 1.0 / (d0 * d0 + 1.0),
                d1: 2.0 * d1 / ((d0 * d0 + 1.0) * (d0 * d0 + 1.0)),
                d2: (6.0 * d1 * d1).max(2.0)
                    / ((d0 * d0 + 1.0) * (d0 * d0 + 1.0) * (d0 * d0 + 1.0)),
                s1: 0.0,
            };
            windowed(dist, radius, d0, d1, g, range_lo, range_hi)
        }
        Attenuation::Frostbite {
            radius,
            min_distance,
        } => {
            if !(d0 >= min_distance && d0 > 0.0) {
                return rough;
            }
            let g = Jet {
                lo: 1.0 / (d1 * d1),
                hi: 1.0 / (d0 * d0),
                d1: 2.0 / (d0 * d0 * d0),
                d2: 6.0 / (d0 * d0 * d0 * d0),
                s1: 0.0,
            };
            windowed(dist, radius, d0, d1, g, range_lo, range_hi)
        }
    }
}

/// `window(d)·g(d)` with `window = saturate(1 − (d/r)⁴)²`, which is C¹ with a Lipschitz
/// derivative: `|w'| ≤ 8x³/r`, `|w''| ≤ (24x² + 32x⁶)/r²` for `x = d/r ≤ 1`.
fn windowed(dist: Jet, radius: f32, d0: f32, d1: f32, g: Jet, lo: f32, hi: f32) -> Jet {
    if !(radius > 0.0) {
        return Jet::rough(lo, hi);
    }
    if d0 >= radius {
        return Jet::ZERO;
    }
    let x = (d1 / radius).min(1.0);
    let w = Jet {
        lo: 0.0,
        hi: 1.0,
        d1: 8.0 * x * x * x / radius,
        d2: (24.0 * x * x + 32.0 * x * x * x * x * x * x) / (radius * radius),
        s1: 0.0,
    };
    // g's bounds are with respect to d; chain through d(P) before multiplying.
    let g = dist.compose(g.lo, g.hi, g.d1, g.d2);
    let w = dist.compose(0.0, 1.0, w.d1, w.d2);
    let mut f = w.mul(g);
    f.lo = f.lo.max(lo);
    f.hi = f.hi.min(hi);
    f
}

/// The distance from `p` to triangle `abc` (Ericson, *Real-Time Collision Detection*, 5.1.5).
/// Degenerate triangles whose interior case divides by zero give 0 (a safe lower bound).
fn distance_to_triangle(p: Vec3, [a, b, c]: [Vec3; 3]) -> f32 {
    let (p, a, b, c) = (p.as_dvec3(), a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let len = |v: DVec3| math::sqrt_f64(v.length_squared());
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    let d = if d1 <= 0.0 && d2 <= 0.0 {
        len(ap)
    } else {
        let bp = p - b;
        let (d3, d4) = (ab.dot(bp), ac.dot(bp));
        let cp = p - c;
        let (d5, d6) = (ab.dot(cp), ac.dot(cp));
        let vc = d1 * d4 - d3 * d2;
        let vb = d5 * d2 - d1 * d6;
        let va = d3 * d6 - d5 * d4;
        if d3 >= 0.0 && d4 <= d3 {
            len(bp)
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            len(ap - ab * (d1 / (d1 - d3)))
        } else if d6 >= 0.0 && d5 <= d6 {
            len(cp)
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            len(ap - ac * (d2 / (d2 - d6)))
        } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
            len(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))
        } else {
            let den = va + vb + vc;
            if den == 0.0 || !den.is_finite() {
                return 0.0;
            }
            len(ap - ab * (vb / den) - ac * (vc / den))
        }
    };
    // Round down: the bound needs a lower estimate.
    let d = (d * (1.0 - 1e-6) - 1e-9).max(0.0);
    if d.is_finite() { d as f32 } else { 0.0 }
}

/// The squared radius of the smallest circle enclosing the triangle: the largest value of
/// `Σ bᵢ‖Pᵢ − P(b)‖²` over the triangle.
fn enclosing_radius_squared([a, b, c]: [Vec3; 3]) -> f32 {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let (ab, bc, ca) = (
        (b - a).length_squared(),
        (c - b).length_squared(),
        (a - c).length_squared(),
    );
    let r2 = if bc >= ab + ca {
        bc / 4.0
    } else if ca >= ab + bc {
        ca / 4.0
    } else if ab >= bc + ca {
        ab / 4.0
    } else {
        // Acute: the circumradius, R² = ab·bc·ca / (4‖(B−A)×(C−A)‖²).
        let k = (b - a).cross(c - a).length_squared();
        if k > 0.0 {
            ab * bc * ca / (4.0 * k)
        } else {
            ab.max(bc).max(ca) / 4.0
        }
    };
    ((r2 * (1.0 + 1e-6)) as f32).min(f32::MAX)
}

/// `κ`, `μ` and `ρ` of the interpolated normal (see [`NormalJet`]); `None` when the triangle has
/// no area or its normals cancel somewhere inside it.
fn normal_jet(p: [Vec3; 3], n: [Vec3; 3]) -> Option<NormalJet> {
    // μ = min ‖Σ bᵢnᵢ‖: the distance from the origin to the triangle of the normals.
    let mu = distance_to_triangle(Vec3::ZERO, n);
    if !(mu > 1e-4) {
        return None;
    }
    let (p0, p1, p2) = (p[0].as_dvec3(), p[1].as_dvec3(), p[2].as_dvec3());
    let (e1, e2) = (p1 - p0, p2 - p0);
    let (q1, q2) = (
        n[1].as_dvec3() - n[0].as_dvec3(),
        n[2].as_dvec3() - n[0].as_dvec3(),
    );
    let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let det = g11 * g22 - g12 * g12;
    if !(det > 1e-30 * g11 * g22) || !det.is_finite() {
        return None;
    }
    // An orthonormal basis of the plane, and J t = Σ qₖ xₖ with x = G⁻¹ [e1·t, e2·t].
    let t1 = e1 * (1.0 / math::sqrt_f64(g11));
    let t2 = e2 - t1 * e2.dot(t1);
    let t2 = t2 * (1.0 / math::sqrt_f64(t2.length_squared()));
    let jt = |t: DVec3| {
        let (r1, r2) = (e1.dot(t), e2.dot(t));
        let x1 = (g22 * r1 - g12 * r2) / det;
        let x2 = (g11 * r2 - g12 * r1) / det;
        q1 * x1 + q2 * x2
    };
    let (j1, j2) = (jt(t1), jt(t2));
    // κ = largest singular value of [j1 j2].
    let (a, b, c) = (j1.dot(j1), j1.dot(j2), j2.dot(j2));
    let half_tr = 0.5 * (a + c);
    let disc = math::sqrt_f64((0.25 * (a - c) * (a - c) + b * b).max(0.0));
    let kappa = math::sqrt_f64((half_tr + disc).max(0.0)) * (1.0 + 1e-6);
    // ρ ≥ |‖m‖'| = |N·m'|: σᵢ = ‖Jᵀnᵢ‖ restricted to the plane, divided by μ.
    let sigma = n
        .iter()
        .map(|ni| {
            let ni = ni.as_dvec3();
            math::sqrt_f64(ni.dot(j1) * ni.dot(j1) + ni.dot(j2) * ni.dot(j2))
        })
        .fold(0.0f64, f64::max)
        * (1.0 + 1e-6);
    let mu = mu as f64;
    let rho = sigma / mu;
    let out = NormalJet {
        a: (kappa / mu) as f32,
        k2: (kappa * kappa / (mu * mu)) as f32,
        cross: (2.0 * rho * kappa / (mu * mu)) as f32,
    };
    (out.a.is_finite() && out.k2.is_finite() && out.cross.is_finite()).then_some(out)
}

/// One triangle's geometry, shared by the lights.
struct Triangle {
    p: [Vec3; 3],
    /// Unit vertex normals.
    n: [Vec3; 3],
    /// Squared radius of the smallest enclosing circle.
    r2: f32,
    /// `μ = min ‖Σ bᵢnᵢ‖` over the triangle.
    mu: f32,
    normal: Option<NormalJet>,
    /// The largest vertex coordinate magnitude `max ‖Pᵢ‖`: a point `Σ bᵢPᵢ` computed in `f32` is
    /// within `3·2⁻²⁴` of it of the exact one.
    pmax: f32,
}

/// The rounding allowance of a cosine computed by `shade` at a point of the triangle, with the
/// light and the viewer at least `d_light` and `d_viewer` away (`∞` for directions):
///
/// ```text
/// η = (8 + 6/μ)·u + 3u·max‖Pᵢ‖·(1/d_light + 1/d_viewer),      u = 2⁻²⁴
/// ```
///
/// The interpolated normal `Σ bᵢnᵢ` is rounded by `3u` of `Σ bᵢ‖nᵢ‖ = 1`, which turns its
/// direction by up to `3√3·u/μ`; normalising it and the light and view directions adds `2u` each,
/// and the dot product `3u`. The point itself is off by `3u·max‖Pᵢ‖`, which turns a direction
/// toward a point `d` away by that over `d`.
fn cosine_allowance(tri: &Triangle, d_light: f32, d_viewer: f32) -> f32 {
    let normal = if tri.mu > 0.0 {
        6.0 / tri.mu
    } else {
        f32::INFINITY
    };
    let position = 3.0 * U * tri.pmax * (1.0 / d_light + 1.0 / d_viewer);
    (8.0 + normal) * U + position
}

/// The bound for one light; see [`gouraud_error_bound`].
fn light_bound(
    model: &Model,
    material: &Material,
    light: &Light,
    viewer: Viewer,
    tri: &Triangle,
) -> f32 {
    let (p, n, r2, normal) = (tri.p, tri.n, tri.r2, tri.normal.as_ref());
    let colors = light.colors();
    let wa = (colors.ambient() * material.ambient()).max_element();
    let wd = (colors.diffuse() * material.diffuse()).max_element();
    let ws = (colors.specular() * material.specular()).max_element();
    let s = material.shininess();
    let d_viewer = match viewer {
        Viewer::At(eye) => distance_to_triangle(eye, p),
        Viewer::Infinite(_) => f32::INFINITY,
    };
    // A point light's distance, as `shade` computes it, is off by the point's rounding and its
    // own (the square root of a rounded sum of squares: 2u relative).
    let distance_allowance = |d1: f32| 3.0 * U * tri.pmax + 2.0 * U * d1;

    // The attenuation × spot factor f, the light direction's jet and the cosines' allowance.
    let (factor, l_jet, l_at, eta) = match light {
        Light::Directional(d) => (
            Jet::constant(1.0),
            UnitJet::FIXED,
            [d.direction(); 3],
            cosine_allowance(tri, f32::INFINITY, d_viewer),
        ),
        Light::Point(pl) => {
            let d0 = distance_to_triangle(pl.position(), p);
            let d1 = p
                .map(|q| crate::length(pl.position() - q))
                .into_iter()
                .fold(0.0, f32::max);
            let e = distance_allowance(d1);
            let f = attenuation_jet(
                &pl.attenuation(),
                (d0 - e).max(0.0),
                d1 * (1.0 + 1e-6) + e,
                e,
            );
            (
                f,
                UnitJet::toward_point(d0),
                p.map(|q| light.sample(q).direction),
                cosine_allowance(tri, d0, d_viewer),
            )
        }
        Light::Spot(sl) => {
            let d0 = distance_to_triangle(sl.position(), p);
            let d1 = p
                .map(|q| crate::length(sl.position() - q))
                .into_iter()
                .fold(0.0, f32::max);
            let e = distance_allowance(d1);
            let f = attenuation_jet(
                &sl.attenuation(),
                (d0 - e).max(0.0),
                d1 * (1.0 + 1e-6) + e,
                e,
            );
            let lj = UnitJet::toward_point(d0);
            let eta = cosine_allowance(tri, d0, d_viewer);
            let dirs = p.map(|q| normalize_or_zero(sl.position() - q));
            // q = −L·D has |q'| ≤ |L'|, |q''| ≤ |L''|.
            let q = Jet::around(
                dirs.map(|l| -l.dot(sl.axis())),
                lj.a,
                lj.b,
                r2,
                -1.0,
                1.0,
                eta,
            );
            let e = sl.exponent();
            let spot = if sl.cone().is_none() {
                // OpenGL's 180° cutoff: the factor is 1 in every direction.
                Jet::constant(1.0)
            } else if q.hi < sl.cos_cutoff() {
                Jet::ZERO
            } else if q.lo >= sl.cos_cutoff() && q.lo > 0.0 {
                // The spot factor's power is `powf` (PowStrategy::Exact).
                q.lobe_pow(e, PowStrategy::Exact)
            } else {
                Jet::rough(
                    0.0,
                    if e == 0.0 {
                        1.0
                    } else {
                        math::powf(q.hi.clamp(0.0, 1.0), e)
                    },
                )
            };
            (f.mul(spot), lj, dirs, eta)
        }
    };
    if factor.is_zero() {
        return 0.0;
    }
    let ambient = factor.scale(wa);
    let no_direction = l_at.iter().all(|l| *l == Vec3::ZERO);
    if no_direction || matches!(light, Light::Directional(_)) && l_at[0] == Vec3::ZERO {
        return finish(ambient, r2, s);
    }
    let Some(nj) = normal else {
        // No smooth normal: only the interval of the whole contribution.
        let (dmax, smax) = lobe_maxima(model, s);
        let total = factor.mul(Jet::rough(wa, wa + wd * dmax + ws * smax));
        return finish(total, r2, s);
    };

    let c1 = normal_cosine(
        [n[0].dot(l_at[0]), n[1].dot(l_at[1]), n[2].dot(l_at[2])],
        nj,
        l_jet,
        r2,
        eta,
    );
    let diffuse = c1.positive_part();
    let (gate, normalization, pow, has_specular, blinn) = match model {
        Model::Lambert(m) => (
            SpecularGate::Step,
            m.normalization,
            PowStrategy::Exact,
            false,
            false,
        ),
        Model::Phong(m) => (m.gate, m.normalization, m.pow, true, false),
        Model::BlinnPhong(m) => (m.gate, m.normalization, m.pow, true, true),
    };
    let wd = if normalization.is_normalized() {
        wd * (1.0 / core::f32::consts::PI)
    } else {
        wd
    };
    // The parts are bounded apart: the error of a sum is at most the sum of the errors, and
    // min(width, Taylor) taken per part is never larger than taken for the sum.
    let mut total = finish(factor.scale(wa), r2, 0.0);
    let diffuse_jet = finish(factor.mul(diffuse.scale(wd)), r2, 0.0);
    total += match light {
        Light::Directional(_) => {
            // The exact-arithmetic bound, plus each evaluation's cosine off by up to η (the
            // diffuse lobe is 1-Lipschitz in it) and the products' rounding.
            let c = [n[0].dot(l_at[0]), n[1].dot(l_at[1]), n[2].dot(l_at[2])];
            let sharp =
                wd * (directional_diffuse_error(c, tri.mu) + 2.0 * eta) + 32.0 * f32::EPSILON * wd;
            sharp.min(diffuse_jet)
        }
        _ => diffuse_jet,
    };

    let v_at = match viewer {
        Viewer::At(eye) => p.map(|q| normalize_or_zero(eye - q)),
        Viewer::Infinite(dir) => [normalize_or_zero(dir); 3],
    };
    let v_jet = match viewer {
        Viewer::At(eye) => UnitJet::toward_point(distance_to_triangle(eye, p)),
        Viewer::Infinite(_) => UnitJet::FIXED,
    };
    if has_specular && ws > 0.0 && v_at.iter().any(|v| *v != Vec3::ZERO) {
        let c2 = normal_cosine(
            [n[0].dot(v_at[0]), n[1].dot(v_at[1]), n[2].dot(v_at[2])],
            nj,
            v_jet,
            r2,
            eta,
        );
        let c3 = plain_cosine(
            [
                l_at[0].dot(v_at[0]),
                l_at[1].dot(v_at[1]),
                l_at[2].dot(v_at[2]),
            ],
            l_jet,
            v_jet,
            r2,
            eta,
        );
        let lobe = if blinn {
            // N·H = (N·L + N·V) / √(2 + 2 L·V); g(x) = (2 + 2x)^(−1/2) is decreasing and convex.
            let base = 2.0 + 2.0 * c3.lo;
            if base > 1e-6 {
                let g_hi = 1.0 / math::sqrt(base);
                let g_lo = 1.0 / math::sqrt(2.0 + 2.0 * c3.hi.max(c3.lo));
                let p1 = g_hi * g_hi * g_hi;
                let p2 = 3.0 * p1 * g_hi * g_hi;
                let g = c3.compose(g_lo, g_hi, p1, p2);
                let mut nh = c1.add(c2).mul(g);
                nh.lo = nh.lo.max(-1.0);
                nh.hi = nh.hi.min(1.0);
                nh.lobe_pow(s, pow)
            } else {
                Jet::rough(0.0, 1.0)
            }
        } else {
            // R·V = 2(N·L)(N·V) − L·V.
            let mut rv = c1.mul(c2).scale(2.0).sub(c3);
            rv.lo = rv.lo.max(-1.0);
            rv.hi = rv.hi.min(1.0);
            rv.lobe_pow(s, pow)
        };
        let specular = if normalization.is_normalized() {
            let k = if blinn {
                normalization.blinn_factor(s)
            } else {
                normalization.phong_factor(s)
            };
            lobe.mul(c1.positive_part()).scale(k)
        } else {
            match gate {
                SpecularGate::Step => lobe.mul(c1.step()),
                SpecularGate::Cosine => lobe.mul(c1.positive_part()),
                SpecularGate::None => lobe,
            }
        };
        total += finish(factor.mul(specular.scale(ws)), r2, s);
    }
    total
}

/// The exact Gouraud error of a directional light's diffuse lobe, bounded: with `L` constant,
/// `m·L = Σ bᵢcᵢ` is affine in `b`, so with `a = m·L`
///
/// ```text
/// G − F = Σ bᵢ max(cᵢ, 0) − max(a, 0)/‖m‖
///       = [Σ bᵢ max(cᵢ, 0) − max(a, 0)]  +  max(a, 0)·(1 − 1/‖m‖)
/// ```
///
/// The first bracket is the Jensen gap of `max(x, 0)` for `cᵢ ∈ [−A, B]`, in `[0, AB/(A+B)]`; the
/// second is in `[−B(1/μ − 1), 0]`. Their sum is at most the larger of the two in magnitude.
fn directional_diffuse_error(c: [f32; 3], mu: f32) -> f32 {
    let b = c[0].max(c[1]).max(c[2]).max(0.0);
    let a = (-c[0]).max(-c[1]).max(-c[2]).max(0.0);
    if b == 0.0 {
        return 0.0;
    }
    if !(mu > 1e-6) {
        return 1.0;
    }
    let shrink = b * (1.0 / mu - 1.0);
    let jensen = if a > 0.0 { a * b / (a + b) } else { 0.0 };
    shrink.max(jensen).min(1.0)
}

/// The largest diffuse and specular lobes a model can produce at shininess `s`.
fn lobe_maxima(model: &Model, s: f32) -> (f32, f32) {
    let (norm, spec, blinn) = match model {
        Model::Lambert(m) => (m.normalization, false, false),
        Model::Phong(m) => (m.normalization, true, false),
        Model::BlinnPhong(m) => (m.normalization, true, true),
    };
    let d = if norm == Normalization::None {
        1.0
    } else {
        1.0 / core::f32::consts::PI
    };
    let sp = match (spec, blinn) {
        (false, _) => 0.0,
        (true, true) => norm.blinn_factor(s),
        (true, false) => norm.phong_factor(s),
    };
    (d, sp)
}

/// `min(interval width, ½·d2·r²)` plus the rounding allowance.
fn finish(f: Jet, r2: f32, s: f32) -> f32 {
    // Both shadings' values lie in the interval, perturbed inputs included; or: the exact values
    // differ by at most ½·d2·r², and each computed value is within s1 of its exact one (the
    // Gouraud value interpolates three computed values, so it is within s1 too).
    let width = (f.hi - f.lo).max(0.0);
    let taylor = 0.5 * mulz(f.d2, r2) + 2.0 * f.s1;
    let b = if taylor.is_finite() {
        width.min(taylor)
    } else {
        width
    };
    // f32 evaluation of both shadings: a few ulps per operation of the products and sums,
    // amplified by the power s.
    let rounding = f.abs_max() * (32.0 + 4.0 * s) * f32::EPSILON;
    let out = b + rounding;
    if out.is_finite() { out } else { f32::MAX }
}

/// An upper bound on how far Gouraud (per-vertex) shading of a triangle can be from per-pixel
/// shading of the same lobes, anywhere inside the triangle, per colour channel of the linear
/// result of [`shade`](crate::shade).
///
/// ```text
/// bound ≥ max over the triangle of | Σ bᵢ·I(Pᵢ, nᵢ) − I(Σ bᵢPᵢ, normalize(Σ bᵢnᵢ)) |
///        (each channel of the linear colour I = shade(…).total())
///
/// per light and part:  min( width of the part's interval ,  ½ · M₂ · r² ) + rounding
/// directional diffuse:  Kd·Ld · max( B·(1/μ − 1) , AB/(A+B) )  if smaller
/// ```
///
/// `r` is the radius of the triangle's smallest enclosing circle and `M₂` a bound on the second
/// derivative of the light's contribution along any straight path in the triangle, built from the
/// spread of the normals (`κ = ‖∂n/∂P‖`, `μ = min ‖Σ bᵢnᵢ‖`), the distances to the light and the
/// viewer, the attenuation and spot factors and the lobe exponent; where the contribution has a kink
/// or a jump inside the triangle only the interval width is used. For a directional light's
/// diffuse part, `B` and `A` are the largest positive and negative vertex values of `N·L` and
/// `μ = min ‖Σ bᵢnᵢ‖`. The parts (the light's ambient, diffuse and specular) and the lights add
/// their bounds; the scene's ambient and the emission are constant and add nothing. Derivation in
/// docs/derivations.md, section "Shading-rate bound".
///
/// **Domain:** `positions` finite; `normals` the vertex normals the renderer interpolates (they
/// are normalised here, and per-pixel shading is assumed to interpolate these unit normals with
/// the same, perspective-correct, barycentric weights as Gouraud interpolates colours). The
/// material's constant colours are used: per-pixel texture lookups are not covered. Any of the
/// crate's models, gates, normalisations, pow strategies, lights and attenuation forms.
///
/// **Returns** a finite value `≥ 0` (saturated at `f32::MAX`). It bounds the difference of the
/// two shadings as [`shade`](crate::shade) computes them in `f32`, with the barycentric point and
/// the interpolated normal `Σ bᵢnᵢ` formed in `f32` too: besides the exact-arithmetic bound above
/// it allows, per light and part, for
///
/// - every cosine `shade` computes being off by up to
///   `η = (8 + 6/μ)·2⁻²⁴ + 3·2⁻²⁴·max‖Pᵢ‖·(1/d_light + 1/d_viewer)` (`d` the distance from the
///   triangle to a point light or an eye; the term is 0 for directions). This is an *absolute*
///   error: a cosine near 0 formed from terms near ±1, e.g. a grazing light, is off by a few
///   `2⁻²⁴` whatever its own size. The part's sensitivity to it is carried alongside its
///   derivatives;
/// - the distance to a point light being off by `3·2⁻²⁴·max‖Pᵢ‖ + 2·2⁻²⁴·d`;
/// - the model's pow strategy: its lobe is within
///   [`PowStrategy::max_relative_error`](crate::PowStrategy::max_relative_error) of `x^s`,
///   relative to `max(x^s, 2⁻²⁴)` (the approximate strategies' flush of tiny lobes to 0
///   included);
/// - `(32 + 4s)` ulps of the light's largest contribution for the products and sums.
///
/// **Degenerate input:** a zero-area triangle, normals that cancel inside the triangle, the light
/// or the eye on the triangle: the bound falls back to the interval width of each light's
/// contribution (still a bound, rarely small). A light that cannot reach the triangle (outside a
/// spot cone, beyond a windowed attenuation's radius, or below every point of it with a gated
/// model) gives 0.
///
/// ```
/// use glam::Vec3;
/// use phong::{DirectionalLight, LightColors, Material, Phong, Scene, Viewer};
///
/// let sun = DirectionalLight::try_new(Vec3::new(0.0, 0.0, 1.0), LightColors::try_from_strengths(Vec3::ONE, 0.0, 0.8, 0.5)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let material = Material::try_from_color(Vec3::ONE, 32.0)?;
/// let p = [Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.1, 0.0, 1.0), Vec3::new(0.0, 0.1, 1.0)];
/// // A flat triangle, a directional light and a distant viewer: N, L, V constant, so exact.
/// let flat = phong::shading_rate::gouraud_error_bound(Phong::default(), &material, &scene, p, [Vec3::Z; 3]);
/// assert!(flat < 1e-3);
/// // The same triangle with normals spread by 45°, as on a very coarse sphere, under the highlight.
/// let curved = [Vec3::Z, Vec3::new(1.0, 0.0, 1.0).normalize(), Vec3::new(0.0, 1.0, 1.0).normalize()];
/// assert!(phong::shading_rate::gouraud_error_bound(Phong::default(), &material, &scene, p, curved) > 0.1);
/// # Ok::<(), phong::PhongError>(())
/// ```
#[must_use]
pub fn gouraud_error_bound<M, L>(
    model: M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: [Vec3; 3],
    normals: [Vec3; 3],
) -> f32
where
    M: Into<Model>,
    L: Copy + Into<Light>,
{
    let model = model.into();
    let n = normals.map(normalize_or_zero);
    let tri = Triangle {
        p: positions,
        n,
        r2: enclosing_radius_squared(positions),
        mu: distance_to_triangle(Vec3::ZERO, n),
        normal: normal_jet(positions, n),
        pmax: positions
            .iter()
            .map(|q| crate::length(*q))
            .fold(0.0, f32::max),
    };
    // The constant terms are interpolated exactly but for rounding: a few ulps of their size.
    let constant = material.emission() + material.ambient() * scene.ambient.max(Vec3::ZERO);
    let mut total = 16.0 * f32::EPSILON * constant.max_element().max(0.0);
    for light in scene.lights {
        let light: Light = (*light).into();
        total += light_bound(&model, material, &light, scene.viewer, &tri);
    }
    if total.is_finite() { total } else { f32::MAX }
}

/// Whether Gouraud (per-vertex) shading of this triangle stays within `tolerance` of per-pixel
/// shading everywhere inside it, per channel of the linear colour: [`gouraud_error_bound`]` ≤
/// tolerance`.
///
/// ```text
/// gouraud_within_tolerance = gouraud_error_bound(…) ≤ tolerance
/// ```
///
/// A `true` answer is a guarantee (see the bound's domain); a `false` one only means the bound is
/// not small enough. Tolerances are in linear units; for 8-bit output, `2/255` keeps the two
/// shadings within two steps before encoding. **Degenerate input:** a NaN or negative tolerance
/// gives `false`.
///
/// ```
/// use glam::Vec3;
/// use phong::{BlinnPhong, DirectionalLight, LightColors, Material, Scene, Viewer};
/// let sun = DirectionalLight::try_new(Vec3::Z, LightColors::try_from_strengths(Vec3::ONE, 0.1, 0.8, 0.5)?)?;
/// let scene = Scene { lights: &[sun], ambient: Vec3::ZERO, viewer: Viewer::Infinite(Vec3::Z) };
/// let m = Material::try_from_color(Vec3::ONE, 16.0)?;
/// let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
/// // Facing away from the light: nothing but (constant) ambient.
/// let away = [-Vec3::Z; 3];
/// assert!(phong::shading_rate::gouraud_within_tolerance(BlinnPhong::default(), &m, &scene, p, away, 2.0 / 255.0));
/// # Ok::<(), phong::PhongError>(())
/// ```
#[must_use]
pub fn gouraud_within_tolerance<M, L>(
    model: M,
    material: &Material,
    scene: &Scene<'_, L>,
    positions: [Vec3; 3],
    normals: [Vec3; 3],
    tolerance: f32,
) -> bool
where
    M: Into<Model>,
    L: Copy + Into<Light>,
{
    tolerance >= 0.0 && gouraud_error_bound(model, material, scene, positions, normals) <= tolerance
}
