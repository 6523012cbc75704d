//! The attenuation factor as a jet of the distance to the light, for every falloff form.

use super::jet::Jet;
use crate::Attenuation;

/// The attenuation factor as a jet of the distance `d ∈ [d0, d1]` (with `|d'| ≤ 1`,
/// `|d''| ≤ 1/d0`), whose computed value may be off by up to `eta` (the interval `[d0, d1]`
/// includes that allowance).
pub(super) fn attenuation_jet(a: &Attenuation, d0: f32, d1: f32, eta: f32) -> Jet {
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
pub(super) fn windowed(dist: Jet, radius: f32, d0: f32, d1: f32, g: Jet, lo: f32, hi: f32) -> Jet {
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
