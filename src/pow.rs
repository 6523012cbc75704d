//! Raising a lobe's cosine to the shininess: the specular exponent, and strategies for it.
//!
//! Every strategy computes the *lobe power*
//!
//! ```text
//! lobe_pow(x, s) = x^s   for x ∈ (0, 1], s ≥ 0
//!                = 0     for x ≤ 0            (also when s = 0: see below)
//! ```
//!
//! **`0^0`.** At `s = 0` this takes the limit `s → 0⁺` pointwise: 1 where the clamped cosine is
//! positive and 0 where it is zero. This keeps the lobe continuous in the shininess (a material at
//! `s = 10⁻⁶` and one at `s = 0` look the same) and agrees with what Mesa computes at run time for
//! `pow(0, 0)`. IEEE `powf(0, 0) = 1` would instead light the whole back half of a Phong lobe at
//! `s = 0`.

use crate::math;

/// How the specular exponent `x^s` is evaluated.
///
/// Each strategy's maximum relative error against an `f64` reference is measured in
/// docs/accuracy.md and guarded by a test.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PowStrategy {
    /// `powf` from `std` or `libm`: correctly rounded to within 1 ulp, but a scalar call that
    /// blocks vectorisation.
    #[default]
    Exact,
    /// Repeated squaring when `s` is a whole number in `[0, 65536]` (e.g. `x³² = x` squared 5
    /// times). Each squaring doubles the relative error carried so far, so the result is within
    /// about `s·2⁻²⁴` relative of `x^s`: the same effect as perturbing `x` by one ulp, which is
    /// already the precision of any computed cosine. Other `s` fall back to [`Exact`](Self::Exact).
    Squaring,
}

impl PowStrategy {
    /// The lobe power `x^s` with this strategy (formula and `0^0` rule in the module docs).
    ///
    /// **Domain:** `x ≤ 1` (a clamped cosine), `s ≥ 0` finite. **Returns** a value in `[0, 1]`;
    /// `x ≤ 0` or NaN gives 0; `s` NaN or negative is treated as 0.
    ///
    /// ```
    /// use phong::PowStrategy;
    /// assert_eq!(PowStrategy::Squaring.lobe(0.5, 3.0), 0.125);
    /// assert_eq!(PowStrategy::Exact.lobe(0.0, 0.0), 0.0);
    /// assert_eq!(PowStrategy::Exact.lobe(0.3, 0.0), 1.0);
    /// ```
    #[must_use]
    #[inline]
    pub fn lobe(self, x: f32, s: f32) -> f32 {
        match self {
            PowStrategy::Exact => lobe_pow(x, s),
            PowStrategy::Squaring => lobe_pow_squaring(x, s),
        }
    }
}

/// `x^s` by [`PowStrategy::Exact`]; see the module docs for the domain and the `0^0` rule.
#[inline]
pub(crate) fn lobe_pow(x: f32, s: f32) -> f32 {
    if x > 0.0 {
        // x ∈ (0, 1] and s ≥ 0 keep powf in [0, 1]; the clamp absorbs x slightly above 1 and a
        // NaN or negative s.
        math::clamp_or_lo(math::powf(x.min(1.0), s.max(0.0)), 0.0, 1.0)
    } else {
        0.0
    }
}

#[inline]
fn lobe_pow_squaring(x: f32, s: f32) -> f32 {
    if !(x > 0.0) {
        return 0.0;
    }
    if !(0.0..=65536.0).contains(&s) || s != (s as u32) as f32 {
        return lobe_pow(x, s);
    }
    let mut e = s as u32;
    let mut base = x.min(1.0);
    let mut acc = 1.0f32;
    while e > 0 {
        if e & 1 == 1 {
            acc *= base;
        }
        base *= base;
        e >>= 1;
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squaring_matches_exact_on_integers() {
        for s in [1.0f32, 2.0, 5.0, 32.0, 100.0, 256.0] {
            for x in [0.1f32, 0.5, 0.9, 0.999, 1.0] {
                let a = PowStrategy::Squaring.lobe(x, s) as f64;
                let b = (x as f64).powf(s as f64);
                // Squaring doubles the carried relative error: e_k ≤ (2^k − 1)·u plus one rounding
                // per multiply into the accumulator, so ≤ (s + log2 s + 1)·u with u = 2^-24.
                let tol = (s as f64 + (s as f64).log2() + 1.0) * 2f64.powi(-24);
                assert!((a - b).abs() <= tol * b + 1e-38, "x={x} s={s}: {a} vs {b}");
            }
        }
    }
}
