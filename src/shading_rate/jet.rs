//! Jets: an interval of a function's values on the triangle with bounds on its first and second
//! derivatives along any unit-speed path, and the rounding allowance of its `f32` evaluation;
//! their arithmetic (the product and chain rules) and the cosines built from them.

use crate::math;
use crate::pow::PowStrategy;

/// `2/√3`: the largest `|N''|` per `|m'|²/|m|²` for `N = m/|m|` with `m'' = 0`.
pub(super) const TWO_OVER_SQRT3: f32 = 1.154_700_5;

/// Absolute slack added to intervals computed from `f32` vertex values (at least; the cosines get
/// their rounding allowance `η` when it is larger).
pub(super) const ROUND_ABS: f32 = 1e-6;

/// `f32`'s unit roundoff, `2⁻²⁴`.
pub(super) const U: f32 = f32::EPSILON * 0.5;

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
pub(super) struct Jet {
    pub(super) lo: f32,
    pub(super) hi: f32,
    pub(super) d1: f32,
    pub(super) d2: f32,
    pub(super) s1: f32,
}

/// `a·b` with `0·∞ = 0`: a factor that is exactly zero kills an unknown derivative bound.
#[inline]
pub(super) fn mulz(a: f32, b: f32) -> f32 {
    if a == 0.0 || b == 0.0 { 0.0 } else { a * b }
}

impl Jet {
    pub(super) const ZERO: Jet = Jet::constant(0.0);

    pub(super) const fn constant(x: f32) -> Jet {
        Jet {
            lo: x,
            hi: x,
            d1: 0.0,
            d2: 0.0,
            s1: 0.0,
        }
    }

    /// Only the interval is known.
    pub(super) fn rough(lo: f32, hi: f32) -> Jet {
        Jet {
            lo,
            hi,
            d1: f32::INFINITY,
            d2: f32::INFINITY,
            s1: f32::INFINITY,
        }
    }

    pub(super) fn is_zero(&self) -> bool {
        self.lo == 0.0 && self.hi == 0.0 && self.d1 == 0.0 && self.d2 == 0.0 && self.s1 == 0.0
    }

    pub(super) fn abs_max(&self) -> f32 {
        math::abs(self.lo).max(math::abs(self.hi))
    }

    pub(super) fn add(self, o: Jet) -> Jet {
        Jet {
            lo: self.lo + o.lo,
            hi: self.hi + o.hi,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
            s1: self.s1 + o.s1,
        }
    }

    pub(super) fn sub(self, o: Jet) -> Jet {
        Jet {
            lo: self.lo - o.hi,
            hi: self.hi - o.lo,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
            s1: self.s1 + o.s1,
        }
    }

    /// Scaling by `k ≥ 0`.
    pub(super) fn scale(self, k: f32) -> Jet {
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
    pub(super) fn mul(self, o: Jet) -> Jet {
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
    pub(super) fn compose(self, lo: f32, hi: f32, p1: f32, p2: f32) -> Jet {
        Jet {
            lo,
            hi,
            d1: mulz(p1, self.d1),
            d2: mulz(p2, mulz(self.d1, self.d1)) + mulz(p1, self.d2),
            s1: mulz(p1, self.s1),
        }
    }

    /// `max(x, 0)`: the identity, zero, or a kink (which is still 1-Lipschitz).
    pub(super) fn positive_part(self) -> Jet {
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
    pub(super) fn step(self) -> Jet {
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
    pub(super) fn lobe_pow(self, s: f32, pow: PowStrategy) -> Jet {
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
    pub(super) fn around(
        values: [f32; 3],
        d1: f32,
        d2: f32,
        r2: f32,
        lo: f32,
        hi: f32,
        eta: f32,
    ) -> Jet {
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
pub(super) struct UnitJet {
    pub(super) a: f32,
    pub(super) b: f32,
}

impl UnitJet {
    pub(super) const FIXED: UnitJet = UnitJet { a: 0.0, b: 0.0 };

    /// `X = (Q − P)/‖Q − P‖` toward a fixed point `Q` at least `d` from the triangle.
    pub(super) fn toward_point(d: f32) -> UnitJet {
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
pub(super) struct NormalJet {
    /// `κ/μ ≥ |N'|`.
    pub(super) a: f32,
    /// `κ²/μ²`: the part of `|N''·X|` proportional to `|N·X|`.
    pub(super) k2: f32,
    /// `2·ρ·κ/μ²`: the rest of `|N''·X|`.
    pub(super) cross: f32,
}

/// The cosine `N·X` as a jet, from its vertex values (`nᵢ·Xᵢ`).
///
/// `(N·X)'' = N''·X + 2N'·X' + N·X''` and, since `m'' = 0`,
/// `N''·X = −(‖m'⊥‖²/‖m‖²)(N·X) − 2(‖m‖'/‖m‖)(N'·X)`.
pub(super) fn normal_cosine(values: [f32; 3], n: &NormalJet, x: UnitJet, r2: f32, eta: f32) -> Jet {
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
pub(super) fn plain_cosine(values: [f32; 3], x: UnitJet, y: UnitJet, r2: f32, eta: f32) -> Jet {
    let d1 = x.a + y.a;
    let d2 = x.b + 2.0 * mulz(x.a, y.a) + y.b;
    Jet::around(values, d1, d2, r2, -1.0, 1.0, eta)
}
