//! Exact sums of floating-point numbers: Shewchuk's expansion arithmetic.
//!
//! An *expansion* is an unevaluated sum of `f64` components that represents a value exactly: adding
//! a number keeps the rounding error of each addition as a component instead of dropping it
//! (Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", Discrete & Computational Geometry 18). The geometry uses it where it promises an
//! exact sign or a correctly rounded value of a short sum of products of `f32` inputs: the sign of
//! a determinant ([`normal_matrix`](crate::normal_matrix)), the area vector of a triangle
//! ([`triangle_area_normal`](crate::triangle_area_normal)) and the sign of a dot product
//! ([`face_forward`](crate::face_forward)).
//!
//! The inputs are exact by construction: a product of two `f32` fits an `f64` significand
//! (24 + 24 ≤ 53 bits), and a product of three splits into two exact `f64` terms
//! ([`product3`]). Every such product lies between 2⁻⁴⁴⁷ and 2³⁸⁴ in magnitude, far inside the
//! normal `f64` range, so no step here overflows or underflows for finite `f32` input.
//!
//! These routines run only where a cheap floating-point filter cannot certify the answer, so they
//! favour plainness over speed.

/// `a + b = s + e` exactly, with `s = fl(a + b)` (Knuth's TwoSum; no precondition on `a`, `b`).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a·b·c` exactly, as the sum of two `f64`.
///
/// `a·b` is exact in `f64` (48 significant bits). Veltkamp's split cuts it into two halves of at
/// most 26 bits each, and each half times the 24-bit `c` fits 53 bits, so both products are exact.
#[inline]
pub(crate) fn product3(a: f32, b: f32, c: f32) -> [f64; 2] {
    let ab = a as f64 * b as f64;
    // 2^27 + 1 splits a 53-bit significand into 26 + 26 bits (Dekker 1971).
    let t = 134_217_729.0 * ab;
    let hi = t - (t - ab);
    let lo = ab - hi;
    [hi * c as f64, lo * c as f64]
}

/// An exact sum of at most `N` components, nonoverlapping and in increasing order of magnitude.
///
/// The value is the sum of `c[..len]`. `len ≥ 1`; the only zero component is a lone zero, which
/// means the value is zero. Because the components do not overlap, the largest one carries the sign
/// of the whole sum.
#[derive(Clone, Copy)]
pub(crate) struct Expansion<const N: usize> {
    c: [f64; N],
    len: usize,
}

impl<const N: usize> Expansion<N> {
    /// The exact sum of `terms` (Shewchuk's Grow-Expansion with zero elimination, once per term).
    pub(crate) fn sum(terms: [f64; N]) -> Self {
        let mut e = Expansion {
            c: [0.0; N],
            len: 0,
        };
        for t in terms {
            e.grow(t);
        }
        e
    }

    /// Adds `b` exactly. Each call lengthens the expansion by at most one component, and
    /// [`sum`](Self::sum) calls it at most `N` times, so it never writes past the array.
    fn grow(&mut self, b: f64) {
        let mut q = b;
        let mut out = 0;
        for i in 0..self.len {
            let (s, e) = two_sum(q, self.c[i]);
            if e != 0.0 {
                // out ≤ i: the write never overtakes the read.
                self.c[out] = e;
                out += 1;
            }
            q = s;
        }
        if q != 0.0 || out == 0 {
            self.c[out] = q;
            out += 1;
        }
        self.len = out;
    }

    /// The largest component: its sign is the sign of the sum.
    #[inline]
    fn largest(&self) -> f64 {
        self.c[self.len.max(1) - 1]
    }

    /// The sign of the sum: `1.0`, `-1.0`, or `0.0` when the sum is exactly zero (and NaN for
    /// non-finite terms).
    pub(crate) fn sign(&self) -> f64 {
        let top = self.largest();
        if top > 0.0 {
            1.0
        } else if top < 0.0 {
            -1.0
        } else {
            top
        }
    }

    /// The sum as `top + t`, where `|t| < ulp(top)` and `t` has the sign of `below` (zero when `t`
    /// is): Shewchuk's Compress, whose largest output component approximates the sum with an error
    /// smaller than its own ulp (Shewchuk 1997, Theorem 23).
    pub(crate) fn approximate(mut self) -> Approx {
        self.compress();
        let below = if self.len >= 2 {
            self.c[self.len - 2]
        } else {
            0.0
        };
        Approx {
            top: self.largest(),
            below,
        }
    }

    /// Shewchuk's Compress, in place: a top-down pass of exact sums, then a bottom-up one. Uses
    /// TwoSum where Shewchuk uses FastTwoSum: the same result, with no precondition to check.
    fn compress(&mut self) {
        let n = self.len;
        if n < 2 {
            return;
        }
        let mut bottom = n - 1;
        let mut q = self.c[bottom];
        for i in (0..n - 1).rev() {
            let (s, e) = two_sum(q, self.c[i]);
            if e != 0.0 {
                // bottom > i here (it starts above i and falls at most as fast), so bottom ≥ 1.
                self.c[bottom] = s;
                bottom -= 1;
                q = e;
            } else {
                q = s;
            }
        }
        let mut top = 0;
        for i in bottom + 1..n {
            let (s, e) = two_sum(self.c[i], q);
            if e != 0.0 {
                // top < i: the write never overtakes the read.
                self.c[top] = e;
                top += 1;
            }
            q = s;
        }
        self.c[top] = q;
        self.len = top + 1;
    }
}

/// An exact value written as `top + t` with `|t| < ulp(top)` and `t` of the sign of `below`
/// (`below = 0` when `t = 0`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Approx {
    /// The value to within one ulp of itself: relative error below 2⁻⁵².
    pub(crate) top: f64,
    /// A number with the sign of the remainder `value − top` (zero when the remainder is zero).
    pub(crate) below: f64,
}

impl Approx {
    /// The value rounded to the nearest `f32` (ties to even), saturated to `±f32::MAX`.
    ///
    /// Rounding `top` to `f32` gives the right answer unless `top` lies exactly halfway between two
    /// `f32` values, because no other `f32` rounding boundary lies strictly within one `f64` ulp of
    /// `top` (the boundaries have 25 significant bits). At a halfway point the sign of the
    /// remainder decides.
    pub(crate) fn round_to_f32(self) -> f32 {
        let Approx { top, below } = self;
        let max = f32::MAX as f64;
        // Beyond f32::MAX the sum is above the last rounding boundary below f32::MAX (it is within
        // one f64 ulp of top), so it rounds to f32::MAX or to infinity: both saturate.
        if top >= max {
            return f32::MAX;
        }
        if top <= -max {
            return -f32::MAX;
        }
        let r = top as f32;
        let back = r as f64;
        if back == top {
            return r;
        }
        let other = if top > back {
            r.next_up()
        } else {
            r.next_down()
        };
        // Exact: two neighbouring f32 values sum and halve without rounding in f64.
        let halfway = 0.5 * (back + other as f64);
        if top != halfway || below == 0.0 {
            // Not a tie, or an exact tie, which the cast already sent to the even neighbour.
            return r;
        }
        // A tie for top, not for the value: the remainder says which side of it the value lies.
        if (below > 0.0) == (top > back) {
            other
        } else {
            r
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_are_exact_and_signed() {
        // 1 + 2^-80 − 1 is 2^-80, which plain f64 addition loses.
        let e = Expansion::sum([1.0, 2f64.powi(-80), -1.0]);
        assert_eq!(e.sign(), 1.0);
        assert_eq!(e.approximate().top, 2f64.powi(-80));
        let z = Expansion::sum([3.0, -1.5, -1.5, 0.0]);
        assert_eq!(z.sign(), 0.0);
        let a = z.approximate();
        assert_eq!((a.top, a.below), (0.0, 0.0));
    }

    #[test]
    fn product3_is_exact() {
        let (a, b, c) = (16_777_215.0f32, 16_777_213.0f32, 16_777_211.0f32);
        let [hi, lo] = product3(a, b, c);
        // (2^24 − 1)(2^24 − 3)(2^24 − 5) in integers, split the same way.
        let exact: i128 = 16_777_215 * 16_777_213 * 16_777_211;
        assert_eq!(hi as i128 + lo as i128, exact);
    }

    #[test]
    fn rounding_to_f32_breaks_ties_by_the_remainder() {
        // 1 + 2^-24 is halfway between 1 and 1 + 2^-23.
        let tie = 1.0 + 2f64.powi(-24);
        let up = Approx {
            top: tie,
            below: 2f64.powi(-80),
        };
        let down = Approx {
            top: tie,
            below: -2f64.powi(-80),
        };
        let exact = Approx {
            top: tie,
            below: 0.0,
        };
        assert_eq!(up.round_to_f32(), 1.0f32.next_up());
        assert_eq!(down.round_to_f32(), 1.0);
        assert_eq!(exact.round_to_f32(), 1.0, "ties to even");
        let huge = Approx {
            top: 1e300,
            below: 0.0,
        };
        assert_eq!(huge.round_to_f32(), f32::MAX);
    }
}
