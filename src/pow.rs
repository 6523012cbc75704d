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
//! `s = 0`. Derivation: [docs/derivations.md](https://example.invalid/phong/docs/derivations.md#the-00-rule).
//!
//! ## Strategies and their measured error
//!
//! | strategy | method | max relative error vs f64 (`x^s ≥ 2⁻²⁴`, `s ≤ 512`) |
//! |---|---|---|
//! | [`Exact`](PowStrategy::Exact) | `powf` | 1e-7 |
//! | [`Squaring`](PowStrategy::Squaring) | repeated squaring (integer `s`; else `Exact`) | 2e-5 |
//! | [`Poly3`](PowStrategy::Poly3) | `exp2(s·log2 x)`, degree 3 / 3 | 6e-2 |
//! | [`Poly5`](PowStrategy::Poly5) | `exp2(s·log2 x)`, degree 5 / 4 | 1.2e-3 |
//! | [`Poly7`](PowStrategy::Poly7) | `exp2(s·log2 x)`, degree 7 / 5 | 3e-5 |
//! | [`SplitPoly3`](PowStrategy::SplitPoly3) | `x^⌊s⌋` by squaring × `Poly3` of `x^{s−⌊s⌋}` | 8e-4 |
//! | [`SplitPoly5`](PowStrategy::SplitPoly5) | `x^⌊s⌋` by squaring × `Poly5` of `x^{s−⌊s⌋}` | 2e-5 |
//!
//! The bounds are measured by the `strategy_error_bounds` test (a grid of `x ∈ (0, 1]` and `s`
//! in `[0, 512]`) and enforced there. The polynomial strategies flush results below `2⁻¹⁰⁰` to 0
//! (no subnormals, which are slow); below `2⁻²⁴` their *absolute* error is what matters and it is
//! under `2⁻²⁴`. [`PowStrategy::cheapest_for_8bit`] picks a strategy per exponent; its 8-bit
//! sRGB mismatch rates are in docs/performance.md.
//!
//! ## How the polynomials were fitted
//!
//! `log2 x = e + log2 m` with `m ∈ [√½, √2)`, and `log2 m ≈ t·P(t)`, `t = m − 1` (exact at
//! `x = 1`, so the highlight peak is exactly 1). `2^y = 2^r · Q(f)` with `r = round(y)`,
//! `f ∈ [−½, ½]` and `Q(f) = 1 + f·R(f)`. `P` and `R` minimise the maximum *relative* error of
//! `t·P(t)` and `Q` on 20 001 equally spaced points: weighted least squares iterated by Lawson's
//! algorithm (400 rounds of reweighting by the residual), in numpy, f64, then rounded to f32. The
//! fitted relative errors of the pieces (before f32 rounding):
//!
//! | degree | log2 | exp2 |
//! |---|---|---|
//! | 3 | 2.6e-3 | 1.0e-4 |
//! | 4 | | 2.8e-6 |
//! | 5 | 5.0e-5 | 9.1e-8 |
//! | 7 | 1.1e-6 | |

use crate::math;

/// How the specular exponent `x^s` is evaluated.
///
/// Each strategy's maximum relative error against an `f64` reference is in the module docs' table
/// and guarded by a test. All return 0 for `x ≤ 0` and 1 at `x = 1` exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PowStrategy {
    /// `powf` from `std` or `libm`: correctly rounded to within 1 ulp, but a scalar call that
    /// blocks vectorisation. Max relative error 1e-7.
    #[default]
    Exact,
    /// Repeated squaring when `s` is a whole number in `[0, 65536]` (e.g. `x³² = x` squared 5
    /// times). Each squaring doubles the relative error carried so far, so the result is within
    /// about `s·2⁻²⁴` relative of `x^s`: the same effect as perturbing `x` by one ulp, which is
    /// already the precision of any computed cosine. Other `s` fall back to [`Exact`](Self::Exact).
    /// Max relative error 2e-5 (at `s ≤ 512`).
    Squaring,
    /// `exp2(s · log2 x)` with a degree-3 `log2` and a degree-3 `exp2` polynomial. Max relative
    /// error 6e-2: visibly wrong in 8 bits; here for the chart.
    Poly3,
    /// `exp2(s · log2 x)` with polynomials of degree 5 (`log2`) and 4 (`exp2`). Max relative error
    /// 1.2e-3.
    Poly5,
    /// `exp2(s · log2 x)` with polynomials of degree 7 (`log2`) and 5 (`exp2`). Max relative error
    /// 3e-5.
    Poly7,
    /// `x^⌊s⌋` by repeated squaring times `x^{s−⌊s⌋}` by [`Poly3`](Self::Poly3): the polynomial's
    /// error is scaled by the fractional exponent only. Max relative error 8e-4.
    SplitPoly3,
    /// `x^⌊s⌋` by repeated squaring times `x^{s−⌊s⌋}` by [`Poly5`](Self::Poly5). Max relative error
    /// 2e-5.
    SplitPoly5,
    /// [`PowStrategy::cheapest_for_8bit`] of the exponent, chosen per call: the error is the
    /// chosen strategy's (at most 3e-5 relative). (Resolving it to `powf` in scalar code was
    /// tried: fewer instructions, but slower in the criterion benches, 5% for Phong.)
    Auto,
}

// Coefficients of P (log2 m ≈ t·P(t), t = m − 1, m ∈ [√½, √2)), lowest order first; fitted as
// described in the module docs.
pub(crate) const LOG2_3: [f32; 3] = [1.4441768, -0.7511287, 0.4496072];
pub(crate) const LOG2_5: [f32; 5] = [1.4426463, -0.720555, 0.4853064, -0.39089188, 0.25475195];
pub(crate) const LOG2_7: [f32; 7] = [
    1.4426965,
    -0.7213636,
    0.48062676,
    -0.35937157,
    0.29569963,
    -0.269321,
    0.17162517,
];
// Coefficients of R (2^f ≈ 1 + f·R(f), f ∈ [−½, ½]), lowest order first.
pub(crate) const EXP2_3: [f32; 3] = [0.6932829, 0.24221076, 0.055008747];
pub(crate) const EXP2_4: [f32; 4] = [0.6931242, 0.24024099, 0.055906415, 0.009582836];
// The first coefficient is fitted, not ln 2 typed in (it happens to round near it).
#[allow(clippy::approx_constant)]
pub(crate) const EXP2_5: [f32; 5] = [0.693147, 0.24022242, 0.05550734, 0.009671513, 0.0013264715];

/// The largest exponent repeated squaring handles; larger ones use the fallback.
const MAX_SQUARING: f32 = 65536.0;

/// Below `2^FLUSH_EXP2` the polynomial strategies return 0.
const FLUSH_EXP2: f32 = -100.0;

impl PowStrategy {
    /// Every concrete strategy (all but [`Auto`](Self::Auto)), cheapest-looking last.
    pub const ALL: [PowStrategy; 7] = [
        PowStrategy::Exact,
        PowStrategy::Squaring,
        PowStrategy::Poly3,
        PowStrategy::Poly5,
        PowStrategy::Poly7,
        PowStrategy::SplitPoly3,
        PowStrategy::SplitPoly5,
    ];

    /// A short name for tables and charts (`"exact"`, `"squaring"`, `"poly5"`, …).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            PowStrategy::Exact => "exact",
            PowStrategy::Squaring => "squaring",
            PowStrategy::Poly3 => "poly3",
            PowStrategy::Poly5 => "poly5",
            PowStrategy::Poly7 => "poly7",
            PowStrategy::SplitPoly3 => "split3",
            PowStrategy::SplitPoly5 => "split5",
            PowStrategy::Auto => "auto",
        }
    }

    /// The cheapest strategy whose 8-bit sRGB output matches an `f64` reference as often as the
    /// exact `f32` path does, for the exponent `s` actually applied to the lobe's base (`s` for
    /// Phong's `R·V`, `s/2` for Blinn-Phong's `(N·H)²`).
    ///
    /// ```text
    /// s whole, ≤ 65536   → Squaring     (log2 s multiplies, rounding error only)
    /// otherwise          → Poly7
    /// ```
    ///
    /// **Criterion**, measured in docs/performance.md and enforced by the `auto_choice_is_8bit_exact`
    /// test: on random scenes the chosen strategy's rate of 8-bit channels that differ from the
    /// `f64` reference is at most the exact `f32` path's own rate plus 5 per million.
    ///
    /// **Domain:** any `s`; NaN and negative are treated as 0 (→ `Squaring`).
    ///
    /// ```
    /// use phong::PowStrategy;
    /// assert_eq!(PowStrategy::cheapest_for_8bit(32.0), PowStrategy::Squaring);
    /// assert_ne!(PowStrategy::cheapest_for_8bit(10.25), PowStrategy::Squaring);
    /// ```
    #[must_use]
    pub fn cheapest_for_8bit(s: f32) -> PowStrategy {
        let s = math::clamp_or_lo(s, 0.0, math::MAX);
        if s <= MAX_SQUARING && s == (s as u32) as f32 {
            PowStrategy::Squaring
        } else {
            PowStrategy::Poly7
        }
    }

    /// `Auto` resolved for exponent `s`; every other strategy unchanged.
    #[must_use]
    #[inline]
    pub fn resolve(self, s: f32) -> PowStrategy {
        match self {
            PowStrategy::Auto => Self::cheapest_for_8bit(s),
            other => other,
        }
    }

    /// The lobe power `x^s` with this strategy (formula and `0^0` rule in the module docs).
    ///
    /// **Domain:** `x ≤ 1` (a clamped cosine), `s ≥ 0` finite. **Returns** a value in `[0, 1]`;
    /// `x ≤ 0` or NaN gives 0; `s` NaN or negative is treated as 0. Error: the table in the module
    /// docs.
    ///
    /// ```
    /// use phong::PowStrategy;
    /// assert_eq!(PowStrategy::Squaring.lobe(0.5, 3.0), 0.125);
    /// assert_eq!(PowStrategy::Exact.lobe(0.0, 0.0), 0.0);
    /// assert_eq!(PowStrategy::Exact.lobe(0.3, 0.0), 1.0);
    /// assert_eq!(PowStrategy::Poly7.lobe(1.0, 20.5), 1.0);
    /// assert!((PowStrategy::Poly7.lobe(0.9, 20.5) - 0.9f32.powf(20.5)).abs() < 1e-5);
    /// ```
    #[must_use]
    #[inline(always)]
    pub fn lobe(self, x: f32, s: f32) -> f32 {
        match self.resolve(s) {
            PowStrategy::Exact => lobe_pow(x, s),
            PowStrategy::Squaring => lobe_pow_squaring(x, s),
            other => {
                if !(x > 0.0) {
                    return 0.0;
                }
                let x = x.min(1.0);
                let s = math::clamp_or_lo(s, 0.0, math::MAX);
                other.plan(s).eval(x)
            }
        }
    }

    /// The per-call plan of this strategy for exponent `s` (`s` finite, `≥ 0`). `Auto` is
    /// resolved here.
    #[inline]
    pub(crate) fn plan(self, s: f32) -> PowPlan {
        let s = math::clamp_or_lo(s, 0.0, math::MAX);
        let whole = s <= MAX_SQUARING && s == (s as u32) as f32;
        let split = |poly: Poly| {
            if s <= MAX_SQUARING {
                let n = s as u32;
                PowPlan::Split {
                    n,
                    frac: s - n as f32,
                    poly,
                }
            } else {
                PowPlan::Poly { s, poly }
            }
        };
        match self.resolve(s) {
            PowStrategy::Exact => PowPlan::Exact { s },
            PowStrategy::Squaring if whole => PowPlan::Squaring { n: s as u32 },
            PowStrategy::Squaring => PowPlan::Exact { s },
            PowStrategy::Poly3 => PowPlan::Poly { s, poly: Poly::P3 },
            PowStrategy::Poly5 => PowPlan::Poly { s, poly: Poly::P5 },
            PowStrategy::Poly7 => PowPlan::Poly { s, poly: Poly::P7 },
            PowStrategy::SplitPoly3 => split(Poly::P3),
            PowStrategy::SplitPoly5 | PowStrategy::Auto => split(Poly::P5),
        }
    }
}

/// Which pair of polynomials.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Poly {
    P3,
    P5,
    P7,
}

/// A strategy resolved for one exponent: what a batch kernel runs per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PowPlan {
    /// `powf(x, s)`.
    Exact { s: f32 },
    /// `x^n` by squaring.
    Squaring { n: u32 },
    /// `exp2(s·log2 x)`.
    Poly { s: f32, poly: Poly },
    /// `x^n · exp2(frac·log2 x)`.
    Split { n: u32, frac: f32, poly: Poly },
}

impl PowPlan {
    /// `x^s` for `x ∈ (0, 1]` (callers handle `x ≤ 0`).
    ///
    /// Only what [`PowStrategy::Auto`] picks (squaring, the degree-7 polynomial) is inlined into
    /// the caller: the other plans run out of line, so a shading loop stays small enough to keep
    /// its values in registers.
    #[inline(always)]
    pub(crate) fn eval(self, x: f32) -> f32 {
        match self {
            PowPlan::Squaring { n } => pow_u32(x, n),
            PowPlan::Poly { s, poly: Poly::P7 } => poly_pow(Poly::P7, x, s),
            other => other.eval_out_of_line(x),
        }
    }

    #[inline(never)]
    fn eval_out_of_line(self, x: f32) -> f32 {
        match self {
            PowPlan::Exact { s } => lobe_pow(x, s),
            PowPlan::Squaring { n } => pow_u32(x, n),
            PowPlan::Poly { s, poly } => poly_pow(poly, x, s),
            PowPlan::Split { n, frac, poly } => pow_u32(x, n) * poly_pow(poly, x, frac),
        }
    }
}

/// `x^n` by repeated squaring (`x^0 = 1`).
#[inline(always)]
pub(crate) fn pow_u32(x: f32, n: u32) -> f32 {
    let mut e = n;
    let mut base = x;
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

/// `Σ c[k] t^k` by Horner's rule.
#[inline(always)]
fn horner<const N: usize>(t: f32, c: &[f32; N]) -> f32 {
    let mut acc = 0.0f32;
    let mut k = N;
    while k > 0 {
        k -= 1;
        acc = acc * t + c[k];
    }
    acc
}

/// `log2 x` for `x ∈ (0, 1]`, subnormals included; branch-free so it vectorises. `x = 1` gives 0
/// exactly. For `x = 0` it returns a finite value about −151 (callers select 0).
#[inline(always)]
pub(crate) fn log2_poly<const N: usize>(x: f32, c: &[f32; N]) -> f32 {
    let sub = x < f32::MIN_POSITIVE;
    let xs = if sub { x * 16_777_216.0 } else { x }; // 2^24: exact
    let bits = xs.to_bits() as i32;
    // Exponent e such that m = x·2^-e ∈ [√½, √2): offset by the bits of √½.
    let e = bits.wrapping_sub(0x3f35_04f3) >> 23;
    let m = f32::from_bits(bits.wrapping_sub(e.wrapping_shl(23)) as u32);
    let t = m - 1.0;
    let e = e as f32 - if sub { 24.0 } else { 0.0 };
    e + t * horner(t, c)
}

/// `2^y` for `y ∈ [−100, 0]` (callers select 0 below), branch-free; `y = 0` gives 1 exactly.
#[inline(always)]
pub(crate) fn exp2_poly<const N: usize>(y: f32, c: &[f32; N]) -> f32 {
    // Not `clamp`: `max` also maps NaN to the lower bound.
    #[allow(clippy::manual_clamp)]
    let y = y.max(FLUSH_EXP2).min(0.0);
    // Round to nearest with the 1.5·2^23 trick (|y| ≤ 100 ≪ 2^22): the integer lands in the low
    // mantissa bits of `big`, so no float-to-int conversion (which does not vectorise) is needed.
    let big = y + 12_582_912.0;
    let r = big - 12_582_912.0;
    let ri = (big.to_bits() as i32).wrapping_sub(0x4b40_0000);
    let f = y - r;
    let q = 1.0 + f * horner(f, c);
    let scale = f32::from_bits((ri.wrapping_add(127) as u32) << 23);
    q * scale
}

/// `x^s` by `exp2(s·log2 x)` for `x ∈ (0, 1]`; 0 where the result is below `2^-100`.
#[inline(always)]
pub(crate) fn poly_pow(poly: Poly, x: f32, s: f32) -> f32 {
    let y = match poly {
        Poly::P3 => s * log2_poly(x, &LOG2_3),
        Poly::P5 => s * log2_poly(x, &LOG2_5),
        Poly::P7 => s * log2_poly(x, &LOG2_7),
    };
    let p = match poly {
        Poly::P3 => exp2_poly(y, &EXP2_3),
        Poly::P5 => exp2_poly(y, &EXP2_4),
        Poly::P7 => exp2_poly(y, &EXP2_5),
    };
    if y >= FLUSH_EXP2 { p } else { 0.0 }
}

/// `x^s` by [`PowStrategy::Exact`]; see the module docs for the domain and the `0^0` rule.
#[inline]
pub(crate) fn lobe_pow(x: f32, s: f32) -> f32 {
    if x > 0.0 {
        // x ∈ (0, 1] and s ≥ 0 keep powf in [0, 1]; the clamp absorbs x slightly above 1 and a
        // NaN or negative s.
        math::clamp_or_lo(
            math::powf(math::min_or(x, 1.0), math::max_or(s, 0.0)),
            0.0,
            1.0,
        )
    } else {
        0.0
    }
}

#[inline]
fn lobe_pow_squaring(x: f32, s: f32) -> f32 {
    if !(0.0..=MAX_SQUARING).contains(&s) || s != (s as u32) as f32 {
        return lobe_pow(x, s);
    }
    // Branch-free in `x`: about half of all shaded points have a base ≤ 0, and a branch on it
    // mispredicts. `max` maps NaN to 0.
    #[allow(clippy::manual_clamp)]
    let r = pow_u32(x.max(0.0).min(1.0), s as u32);
    if x > 0.0 { r } else { 0.0 }
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

#[cfg(test)]
mod error_bounds {
    use super::*;

    /// The documented bound of each strategy (module docs' table).
    fn bound(p: PowStrategy) -> f64 {
        match p {
            PowStrategy::Exact => 1e-7,
            PowStrategy::Squaring => 2e-5,
            PowStrategy::Poly3 => 6e-2,
            PowStrategy::Poly5 => 1.2e-3,
            PowStrategy::Poly7 => 3e-5,
            PowStrategy::SplitPoly3 => 8e-4,
            PowStrategy::SplitPoly5 => 2e-5,
            PowStrategy::Auto => 3e-5,
        }
    }

    fn grid() -> impl Iterator<Item = f32> {
        let coarse = (1..=20_000).map(|k| k as f32 / 20_000.0);
        let near_one = (1..=2_000).map(|k| 1.0 - k as f32 * f32::EPSILON * 0.5);
        let tiny = (0..60).map(|k| 2f32.powi(-k));
        coarse.chain(near_one).chain(tiny)
    }

    const EXPONENTS: [f32; 16] = [
        0.0, 0.5, 1.0, 2.5, 7.0, 10.25, 16.0, 16.5, 20.5, 32.0, 64.0, 100.7, 128.0, 256.0, 511.3,
        512.0,
    ];

    #[test]
    fn strategy_error_bounds() {
        let mut report = std::string::String::new();
        let mut failed = false;
        for p in PowStrategy::ALL {
            let mut worst = (0.0f64, 0.0f32, 0.0f32);
            let mut worst_abs = 0.0f64;
            for s in EXPONENTS {
                for x in grid() {
                    let got = p.lobe(x, s) as f64;
                    let want = (x as f64).powf(s as f64);
                    let abs = (got - want).abs();
                    if want >= 2f64.powi(-24) {
                        let rel = abs / want;
                        if rel > worst.0 {
                            worst = (rel, x, s);
                        }
                    } else if abs > worst_abs {
                        worst_abs = abs;
                    }
                }
            }
            report += &std::format!(
                "{:>9}: max rel {:.2e} at x={} s={}; abs below 2^-24 {:.1e}\n",
                p.name(),
                worst.0,
                worst.1,
                worst.2,
                worst_abs
            );
            failed |= worst.0 > bound(p) || worst_abs > 2f64.powi(-24);
        }
        std::println!("{report}");
        assert!(
            !failed,
            "a strategy exceeds its documented bound:\n{report}"
        );
    }
}
