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
//! `s = 10⁻⁶` and one at `s = 0` look the same) and agrees with what Mesa's GLSL `pow(0, 0)`
//! computes at run time. It is a choice, not a universal convention: IEEE `powf(0, 0) = 1`, and
//! Mesa's fixed-function lighting (OpenGL 2.1's `GL_SHININESS` path) also gives 1 there, which
//! lights the whole back half of a Phong lobe at `s = 0`. Derivation: docs/derivations.md, section "The 0^0 rule".
//!
//! ## Strategies and their error bounds
//!
//! **Relative error**, as used here: for `x ∈ (0, 1]` and `s ≥ 0` (both `f32`), with `x^s` the
//! exact real power of those two numbers,
//!
//! ```text
//! err(x, s) = |lobe(x, s) − x^s| / max(x^s, FLOOR),      FLOOR = PowStrategy::ERROR_FLOOR = 2⁻²⁴
//! ```
//!
//! so it is the ordinary relative error where `x^s ≥ 2⁻²⁴` and an *absolute* error, in units of
//! `2⁻²⁴`, below: a lobe that small is below the resolution of any colour it multiplies (one 8-bit
//! step is about `2⁻⁸`), and the polynomial strategies' flush of lobes below `2⁻¹⁰⁰` to 0 (no
//! subnormals, which are slow), or a subnormal rounded up, is then an error of at most `2⁻¹⁰⁰`,
//! far inside the floor. Repeated squaring flushes for the same reason: a base whose power is
//! below `2⁻⁶⁰` is read as 0, so that no square or product of the ladder is subnormal; that is
//! an error of at most `2⁻⁶⁰`, as far inside.
//! [`PowStrategy::max_relative_error`] is the bound on `err` over that whole domain, every finite
//! `s ≥ 0` included, and it holds for the batch kernels' evaluation of each strategy too:
//!
//! ```text
//! |lobe(x, s) − x^s| ≤ max_relative_error() · max(x^s, 2⁻²⁴)
//! ```
//!
//! | strategy | method | `max_relative_error()` |
//! |---|---|---|
//! | [`Exact`](PowStrategy::Exact) | `powf` | 1.2e-7 |
//! | [`Squaring`](PowStrategy::Squaring) | repeated squaring (whole `s ≤ 1024`; else `Exact`) | 3.3e-5 |
//! | [`Poly3`](PowStrategy::Poly3) | `exp2(s·log2 x)`, degree 3 / 3 | 4.6e-2 |
//! | [`Poly5`](PowStrategy::Poly5) | `exp2(s·log2 x)`, degree 5 / 4 | 8.8e-4 |
//! | [`Poly7`](PowStrategy::Poly7) | `exp2(s·log2 x)`, degree 7 / 5 | 2.2e-5 |
//! | [`SplitPoly3`](PowStrategy::SplitPoly3) | `x^⌊s⌋` by squaring × `Poly3` of `x^{s−⌊s⌋}` (`s ≤ 1024`; else `Poly5`) | 1.1e-3 |
//! | [`SplitPoly5`](PowStrategy::SplitPoly5) | `x^⌊s⌋` by squaring × `Poly5` of `x^{s−⌊s⌋}` (`s ≤ 1024`; else `Poly7`) | 3.3e-5 |
//! | [`Auto`](PowStrategy::Auto) | `Squaring` or `Poly7` | 3.3e-5 |
//!
//! The numbers are [`PowStrategy::max_relative_error`]'s (a test checks this table against it).
//! `Exact`'s is one ulp (`2⁻²³`), what `powf` promises with `std` and `libm` alike (measured:
//! 0.53 ulp). The others were measured: a random search with `x^s` log-uniform from 1 down to
//! `2⁻¹⁴⁰` and `s` from 0 to `f32::MAX` (steps of 1/400 below 1; every whole `s`, `s + ½` and
//! `s + 0.999` up to 4096; log-spaced above), then every `f32` `x` with `x^s ≥ 2⁻³²` at the
//! worst exponents found; the largest `err` seen, plus about 5%, is the bound. The worst cases
//! sit where `x^s` is near `2⁻²⁴`, because the polynomials' error in `log2 x` is multiplied by
//! `|log2 x^s|`, and repeated squaring's error grows with the exponent:
//!
//! | strategy | measured max | at `x` | at `s` |
//! |---|---|---|---|
//! | `Exact` | 6.3e-8 | 0.9920426 | 2082.236 |
//! | `Squaring` | 3.07e-5 | 0.9846978 | 1024 |
//! | `Poly3` | 4.342e-2 | 0.7071067 | 48 |
//! | `Poly5` | 8.371e-4 | 0.9430845 | 283.87845 |
//! | `Poly7` | 2.081e-5 | 0.9777624 | 739.41705 |
//! | `SplitPoly3` | 9.82e-4 | 1.6858787e-7 | 0.99323314 |
//! | `SplitPoly5` | 3.10e-5 | 0.9857256 | 1021.9777 |
//!
//! The `strategy_error_bounds` test re-runs the worst cases and a grid over the whole domain and
//! enforces the bound; tests in the batch kernels do the same for their own evaluation (which
//! rounds differently: Estrin's scheme and fused multiply-adds for AVX-512). Repeated squaring's error grows with the exponent (each squaring doubles
//! the relative error carried so far: about `s·2⁻²⁵` near `x = 1`), which is why it stops at
//! 1024; past that `Squaring` is `powf` and the split strategies evaluate the whole power with the
//! next larger polynomial, whose error is within theirs. [`PowStrategy::cheapest_for_8bit`] picks
//! a strategy per exponent; its 8-bit sRGB mismatch rates are in docs/performance.md.
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
/// Each strategy's error bound is [`max_relative_error`](Self::max_relative_error) (defined, with
/// the table of values and how they were measured, in the module docs) and guarded by a test.
/// All return 0 for `x ≤ 0` and 1 at `x = 1` exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PowStrategy {
    /// `powf` from `std` or `libm`: correctly rounded to within 1 ulp, but a scalar call that
    /// blocks vectorisation.
    Exact,
    /// Repeated squaring when `s` is a whole number in `[0, 1024]` (e.g. `x³² = x` squared 5
    /// times). Each squaring doubles the relative error carried so far, so the result is within
    /// about `s·2⁻²⁴` relative of `x^s`: the same effect as perturbing `x` by one ulp, which is
    /// already the precision of any computed cosine. Other `s` fall back to [`Exact`](Self::Exact)
    /// (past 1024 the squarings' error would outgrow the stated bound).
    Squaring,
    /// `exp2(s · log2 x)` with a degree-3 `log2` and a degree-3 `exp2` polynomial: visibly wrong
    /// in 8 bits; here for the chart.
    Poly3,
    /// `exp2(s · log2 x)` with polynomials of degree 5 (`log2`) and 4 (`exp2`).
    Poly5,
    /// `exp2(s · log2 x)` with polynomials of degree 7 (`log2`) and 5 (`exp2`).
    Poly7,
    /// `x^⌊s⌋` by repeated squaring times `x^{s−⌊s⌋}` by [`Poly3`](Self::Poly3): the polynomial's
    /// error is scaled by the fractional exponent only. For `s > 1024` the whole power by
    /// [`Poly5`](Self::Poly5) (see the module docs).
    SplitPoly3,
    /// `x^⌊s⌋` by repeated squaring times `x^{s−⌊s⌋}` by [`Poly5`](Self::Poly5). For `s > 1024`
    /// the whole power by [`Poly7`](Self::Poly7).
    SplitPoly5,
    /// The default: the cheapest strategy that keeps 8-bit sRGB output as exact as `powf`, chosen
    /// per exponent: [`PowStrategy::cheapest_for_8bit`], squaring for a whole exponent up to 1024
    /// and [`Poly7`](Self::Poly7) otherwise. The same everywhere (batch kernels, [`Shader`],
    /// [`shade`]), bit for bit; no `powf` call, so a loop over points stays vectorisable. The
    /// error is the chosen strategy's. An exponent given per point
    /// ([`Shader::shade_surface`](crate::Shader::shade_surface), a G-buffer's shininess) always
    /// takes `Poly7`: a choice per point would run both forms at every point of a vectorised loop.
    ///
    /// [`Shader`]: crate::Shader
    /// [`shade`]: crate::shade()
    #[default]
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
#[allow(clippy::approx_constant, reason = "a fitted coefficient, not ln 2")]
pub(crate) const EXP2_5: [f32; 5] = [0.693147, 0.24022242, 0.05550734, 0.009671513, 0.0013264715];

/// The largest exponent repeated squaring handles; larger ones use the fallback. Its error grows
/// about as `s·2⁻²⁵`: 3.1e-5 here.
const MAX_SQUARING: f32 = 1024.0;

/// Below `2^FLUSH_EXP2` the polynomial strategies return 0.
const FLUSH_EXP2: f32 = -100.0;

impl PowStrategy {
    /// Every concrete strategy (all but [`Auto`](Self::Auto)), cheapest-looking last. A slice, not
    /// an array: the enum is `#[non_exhaustive]`, and a strategy added later lengthens it without
    /// changing its type.
    pub const ALL: &'static [PowStrategy] = &[
        PowStrategy::Exact,
        PowStrategy::Squaring,
        PowStrategy::Poly3,
        PowStrategy::Poly5,
        PowStrategy::Poly7,
        PowStrategy::SplitPoly3,
        PowStrategy::SplitPoly5,
    ];

    /// The floor under the relative error: below a lobe of `2⁻²⁴` the error bound
    /// [`max_relative_error`](Self::max_relative_error) is absolute, in units of this floor.
    pub const ERROR_FLOOR: f32 = 1.0 / 16_777_216.0;

    /// The bound on this strategy's error, for every `x ∈ (0, 1]` and every finite `s ≥ 0`:
    ///
    /// ```text
    /// |lobe(x, s) − x^s| ≤ max_relative_error() · max(x^s, ERROR_FLOOR)      (x^s exact)
    /// ```
    ///
    /// The values, and how they were measured, are in the module docs' table. For
    /// [`Auto`](Self::Auto) it is the larger of the two strategies it chooses between.
    ///
    /// ```
    /// use phong::PowStrategy;
    /// let (x, s) = (0.95f32, 20.5f32);
    /// let want = (x as f64).powf(s as f64);
    /// for &p in PowStrategy::ALL {
    ///     let bound = p.max_relative_error() as f64 * want.max(PowStrategy::ERROR_FLOOR as f64);
    ///     assert!((p.lobe(x, s) as f64 - want).abs() <= bound, "{p:?}");
    /// }
    /// ```
    #[must_use]
    pub const fn max_relative_error(self) -> f32 {
        match self {
            PowStrategy::Exact => 1.2e-7,
            PowStrategy::Squaring => 3.3e-5,
            PowStrategy::Poly3 => 4.6e-2,
            PowStrategy::Poly5 => 8.8e-4,
            PowStrategy::Poly7 => 2.2e-5,
            PowStrategy::SplitPoly3 => 1.1e-3,
            PowStrategy::SplitPoly5 => 3.3e-5,
            PowStrategy::Auto => 3.3e-5,
        }
    }

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
    /// s whole, ≤ 1024    → Squaring     (log2 s multiplies, rounding error only)
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
    /// `x ≤ 0` or NaN gives 0; `s` NaN or negative is treated as 0. Error: at most
    /// [`max_relative_error`](Self::max_relative_error) relative to `max(x^s, 2⁻²⁴)`.
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
    /// resolved here: its plan is the plan of the concrete strategy
    /// [`cheapest_for_8bit`](Self::cheapest_for_8bit) picks, which is never `Auto`.
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
                // Past the squaring limit: the whole power by the next larger polynomial, whose
                // error (see the module docs' table) is within the split strategy's.
                let poly = match poly {
                    Poly::P3 => Poly::P5,
                    _ => Poly::P7,
                };
                PowPlan::Poly { s, poly }
            }
        };
        match self {
            PowStrategy::Exact => PowPlan::Exact { s },
            PowStrategy::Squaring if whole => PowPlan::Squaring { n: s as u32 },
            PowStrategy::Squaring => PowPlan::Exact { s },
            PowStrategy::Poly3 => PowPlan::Poly { s, poly: Poly::P3 },
            PowStrategy::Poly5 => PowPlan::Poly { s, poly: Poly::P5 },
            PowStrategy::Poly7 => PowPlan::Poly { s, poly: Poly::P7 },
            PowStrategy::SplitPoly3 => split(Poly::P3),
            PowStrategy::SplitPoly5 => split(Poly::P5),
            PowStrategy::Auto => Self::cheapest_for_8bit(s).plan(s),
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

/// The least base [`pow_u32`] squares for an exponent `n`: `2^(−120/2^b)` for `n`'s bit length `b`
/// (`2^(b−1) ≤ n < 2^b`, `b ≤ 11`; 0 for `n = 0`, and `b = 11`'s for any larger `n`). Below it
/// the base reads as 0.
///
/// **Why.** Squaring a small base runs into subnormal numbers (`0.06^32` is one), and x86 cores
/// take a microcode assist for each product with a subnormal result: on this crate's development
/// machine (AMD Zen 4), a probe of the vectorised Phong loop at `s = 32` ran about 4% faster with
/// this flush than without (DESIGN.md). A base below this floor has `xⁿ < x^(2^(b−1)) ≤ 2⁻⁶⁰`, far
/// below the error floor of every pow strategy (`2⁻²⁴`, [`PowStrategy::ERROR_FLOOR`]); a base at or
/// above it keeps every value of the ladder, each at least `x^(2^b) ≥ 2⁻¹²⁰`, a normal number.
#[inline(always)]
pub(crate) fn squaring_floor(n: u32) -> f32 {
    // The powers as f32 bits, b = 0..=11 (2⁻⁶⁰, 2⁻³⁰, 2⁻¹⁵, 2⁻⁷·⁵, …, 2^(−120/2048)), each
    // rounded to nearest.
    const FLOOR_BITS: [u32; 12] = [
        0,
        0x2180_0000,
        0x3080_0000,
        0x3800_0000,
        0x3bb5_04f3,
        0x3d98_37f0,
        0x3e8b_95c2,
        0x3f05_aac3,
        0x3f38_fbaf,
        0x3f59_9d16,
        0x3f6c_0719,
        0x3f75_cfa4,
    ];
    let b = 32 - n.leading_zeros();
    f32::from_bits(FLOOR_BITS[b.min(11) as usize])
}

/// `x` where it is at least [`squaring_floor`]`(n)`, else 0 (NaN included).
#[inline(always)]
fn flush_for_squaring(x: f32, n: u32) -> f32 {
    if x >= squaring_floor(n) { x } else { 0.0 }
}

/// `x^n` by repeated squaring (`x^0 = 1`), a base below [`squaring_floor`] read as 0 (its power
/// is below `2⁻⁶⁰`).
///
/// `n = 2^z·m` with `m` odd: `x^(2^z)` by `z` squarings behind five well-predicted tests, with no
/// loop (for a power of two such as 32 or 64, the common shininesses, that is all), then the
/// binary ladder on the bits above `z`. The ladder itself (one squaring per bit) would square the
/// same way and form `1·x^(2^z)` at bit `z`, which is exact, so the result is the ladder's, bit
/// for bit; the loop runs only over the bits above `z` (`48 = 3·2⁴`: one pass instead of six).
#[inline(always)]
pub(crate) fn pow_u32(x: f32, n: u32) -> f32 {
    if n == 0 {
        return 1.0;
    }
    let x = flush_for_squaring(x, n);
    let z = n.trailing_zeros();
    let mut base = squarings(x, z);
    let mut acc = base;
    // `(n >> z) >> 1`: a shift by `z + 1 = 32` would overflow.
    let mut e = (n >> z) >> 1;
    while e > 0 {
        base *= base;
        if e & 1 == 1 {
            acc *= base;
        }
        e >>= 1;
    }
    acc
}

/// `x^(2^k)`: `k` squarings, unrolled by the bits of `k` (`k < 32`).
#[inline(always)]
fn squarings(x: f32, k: u32) -> f32 {
    let mut y = x;
    if k & 16 != 0 {
        for _ in 0..16 {
            y *= y;
        }
    }
    squarings_below_16(y, k & 15)
}

/// [`squarings`] for `k < 16`.
#[inline(always)]
fn squarings_below_16(x: f32, k: u32) -> f32 {
    let mut y = x;
    if k & 8 != 0 {
        for _ in 0..8 {
            y *= y;
        }
    }
    if k & 4 != 0 {
        y *= y;
        y *= y;
        y *= y;
        y *= y;
    }
    if k & 2 != 0 {
        y *= y;
        y *= y;
    }
    if k & 1 != 0 {
        y *= y;
    }
    y
}

/// `x^n` for `n ≤ 1024` (the squaring plans' limit) by [`pow_u32`]'s steps in a form of fixed
/// length: the same flush of tiny bases ([`squaring_floor`]), then with `n = 2^z·m`, `m` odd, the
/// `z ≤ 10` squarings behind four tests on `z`, then a ladder of nine steps over the bits of
/// `m ≤ 1023` above its lowest, each bit selecting one squaring and one product (so the same
/// result, bit for bit). Debug builds assert `n ≤ 1024`.
///
/// No loop: a shading loop that evaluates it per point stays straight-line code, which the
/// compiler can vectorise across points. Every test is on `n` alone, the same for every point of
/// a material, so the code generator keeps each one a branch. Starting the ladder at `x^(2^z)`
/// takes the product `1·x^(2^z)` (exact, so the bits do not change) off the chain: for the common
/// powers of two (`n = 32`) the chain is the squarings alone (`scalar` probe, Phong at s = 32:
/// 35.0 → 34.4 cycles a point).
#[inline(always)]
pub(crate) fn pow_u32_fixed(x: f32, n: u32) -> f32 {
    debug_assert!(n <= 1024, "pow_u32_fixed: exponent {n} above 1024");
    let x = flush_for_squaring(x, n);
    // `& 15`: `n ≤ 1024` has at most 10 trailing zeros, so the test on 16 squarings is left out;
    // `n = 0` has 32 and reads as 0 (no squaring, and 1 at the end).
    let z = n.trailing_zeros() & 15;
    let mut base = squarings_below_16(x, z);
    let mut acc = base;
    // At most 9 bits: `m ≤ 1023`.
    let e = (n >> z) >> 1;
    let mut k = 0;
    while k < 9 {
        // No squaring past the top bit: each select has a single product on one side, which the
        // code generator turns into a branch on `n` when `n` is the same for every point.
        let square = base * base;
        base = if e >> k != 0 { square } else { base };
        let times = acc * base;
        acc = if (e >> k) & 1 == 1 { times } else { acc };
        k += 1;
    }
    if n == 0 { 1.0 } else { acc }
}

/// [`PowStrategy::Auto`]'s `x^s` for `x ∈ [0, 1]` from [`auto_split`]'s `(n, f)`: `x^n` by
/// squaring when `f = 0` (a whole `s ≤ 1024`), else the degree-7 polynomial's `x^f` (then
/// `n = 0`). Bit for bit the `Squaring` or `Poly7` plan that `Auto` picks. One point at a time:
/// the branch on `f` is taken the same way for every point of a material.
#[inline(always)]
pub(crate) fn auto_pow(x: f32, n: u32, f: f32) -> f32 {
    auto_pow_by(pow_u32, x, n, f)
}

/// [`auto_pow`] for code the compiler vectorises across points. The same result, bit for bit.
///
/// `SHARED`: `f` is the same at every point (one material for the whole loop). Both forms are
/// computed, the fixed-length ladder [`pow_u32_fixed`] and the polynomial, before one is selected
/// by `f`. The select keeps a scalar condition in the vectorised loop, which the code generator
/// turns into a branch; with the polynomial ending in a division ([`poly_pow_div`]) and its
/// constants `k` read from a prepared shader ([`PolyConsts`]), it moves the polynomial into that
/// branch, and a whole exponent skips it.
///
/// Otherwise the exponent is a point's own, and its plan never squares (`n = 0`, see
/// `auto_split_per_point`): the polynomial alone, ending in the cheaper product. Running the
/// ladder beside it for every point, as a per-lane choice would, cost a fifth of the
/// instructions of a textured fragment's shading.
#[inline(always)]
pub(crate) fn auto_pow_fixed<const SHARED: bool>(
    x: f32,
    n: u32,
    f: f32,
    k: &PolyConsts<7, 5>,
) -> f32 {
    if !SHARED {
        debug_assert_eq!(n, 0, "a per-point exponent's plan never squares");
        return if f != 0.0 {
            poly_pow_in::<7, 5, false>(x, f, k)
        } else {
            1.0
        };
    }
    let ladder = pow_u32_fixed(x, n);
    let poly = poly_pow_div(x, f, k);
    if f != 0.0 { poly } else { ladder }
}

/// `Auto`'s choice between the polynomial and a squaring `ladder` for `x^n`.
#[inline(always)]
fn auto_pow_by(ladder: impl Fn(f32, u32) -> f32, x: f32, n: u32, f: f32) -> f32 {
    if f != 0.0 {
        poly_pow(Poly::P7, x, f)
    } else {
        ladder(x, n)
    }
}

/// The `(n, f)` of [`auto_pow`] for a shininess `s ≥ 0` (NaN read as 0): what
/// [`PowStrategy::Auto`] plans, squaring for a whole `s ≤ 1024` and the degree-7 polynomial
/// otherwise.
#[inline(always)]
pub(crate) fn auto_split(s: f32) -> (u32, f32) {
    let s = math::clamp_or_lo(s, 0.0, math::MAX);
    // The nearest integer by the 1.5·2^23 trick (exact below 2^22): a float-to-integer `as`
    // saturates, which costs a dozen instructions per lane where a loop is vectorised. `s` is
    // whole exactly when it equals its nearest integer.
    let big = math::min_or(s, MAX_SQUARING) + 12_582_912.0;
    let n = big.to_bits().wrapping_sub(0x4b40_0000);
    if s <= MAX_SQUARING && s == big - 12_582_912.0 {
        (n, 0.0)
    } else {
        (0, s)
    }
}

/// `Auto`'s `(n, f)` for an exponent `e ∈ [0, f32::MAX]` (sanitised by the caller) that is a
/// point's own (a shininess per texel): `(0, e)`, the polynomial at every exponent, whole ones
/// included. With one exponent for many points the choice between squaring and the polynomial is
/// made once ([`auto_split`]); with one per point it would be made at every point, and where the
/// compiler vectorises the caller's loop both forms would run for every point. The polynomial's
/// error at a whole exponent is its error anywhere else (the `Poly7` rows of the pow-strategy
/// table in docs/performance.md).
#[inline(always)]
pub(crate) fn auto_split_per_point(e: f32) -> (u32, f32) {
    debug_assert!(
        (0.0..=math::MAX).contains(&e),
        "auto_split_per_point: exponent {e}"
    );
    (0, e)
}

/// `Σ c[k] t^k` by Estrin's scheme (`N ≤ 8`).
#[inline(always)]
fn horner<const N: usize>(t: f32, c: &[f32; N]) -> f32 {
    const { assert!(N <= 8, "horner: at most 8 coefficients") };
    estrin(t, c)
}

/// `Σ c[k] t^k` by Estrin's scheme for a slice of at most 8 coefficients whose length is known
/// once inlined: pairs `c[k] + c[k+1]·t`, then combined with `t²`, `t⁴`: depth `log2` of the
/// length.
#[inline(always)]
fn estrin(t: f32, c: &[f32]) -> f32 {
    let n = c.len();
    debug_assert!(n <= 8, "estrin: at most 8 coefficients");
    // A missing odd coefficient leaves its pair `c[k]` alone rather than adding `0·t` (which
    // the compiler must keep: it is −0 or NaN for some `t`), and a missing pair adds nothing.
    let pair = |k: usize| {
        if k + 1 < n { c[k] + c[k + 1] * t } else { c[k] }
    };
    let t2 = t * t;
    let lo = if n > 2 {
        pair(0) + pair(2) * t2
    } else {
        pair(0)
    };
    if n <= 4 {
        return lo;
    }
    let hi = if n > 6 {
        pair(4) + pair(6) * t2
    } else {
        pair(4)
    };
    lo + hi * (t2 * t2)
}

/// The floating-point constants of a polynomial `x^s`: the `log2` and `exp2` coefficients and the
/// few others its evaluation uses.
///
/// A value, not only constants in the code, so that a shading loop can read them from a prepared
/// shader ([`PolyConsts::opaque`]): the compiler then keeps them in registers. Written into the
/// instructions as constants they are loaded from memory, and the code generator's hoisting of
/// those loads out of a loop strips the instructions' "raises no FP exception" flag, which keeps
/// them from being moved into a branch that skips them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PolyConsts<const L: usize, const E: usize> {
    log2: [f32; L],
    exp2: [f32; E],
    /// `2^24`, the scale that makes every `x ≤ 1` a normal number.
    two_24: f32,
    one: f32,
    /// `1.5·2^23`, for rounding to an integer.
    round: f32,
    flush: f32,
}

impl<const L: usize, const E: usize> PolyConsts<L, E> {
    const fn new(log2: [f32; L], exp2: [f32; E]) -> Self {
        PolyConsts {
            log2,
            exp2,
            two_24: 16_777_216.0,
            one: 1.0,
            round: 12_582_912.0,
            flush: FLUSH_EXP2,
        }
    }

    /// The same values, hidden from the optimiser (see the type's docs); for a shader to keep.
    #[inline]
    pub(crate) fn opaque(self) -> Self {
        core::hint::black_box(self)
    }
}

/// [`Poly::P3`]'s constants.
const P3_CONSTS: PolyConsts<3, 3> = PolyConsts::new(LOG2_3, EXP2_3);
/// [`Poly::P5`]'s constants.
const P5_CONSTS: PolyConsts<5, 4> = PolyConsts::new(LOG2_5, EXP2_4);
/// [`Poly::P7`]'s constants.
pub(crate) const P7_CONSTS: PolyConsts<7, 5> = PolyConsts::new(LOG2_7, EXP2_5);

/// `log2 x` for `x ∈ (0, 1]`, subnormals included; branch-free so it vectorises. `x = 1` gives 0
/// exactly. For `x = 0` it returns a finite value about −151 (callers select 0).
#[inline(always)]
fn log2_poly<const L: usize, const E: usize>(x: f32, k: &PolyConsts<L, E>) -> f32 {
    // Every `x ≤ 1` times `2^24` is a normal number, exactly, with the same significand: scaling
    // every `x` (and taking 24 from the exponent) gives the bits that scaling only the subnormal
    // ones gave, without the compare and the two selects.
    log2_of_scaled(x * k.two_24, k)
}

/// [`log2_poly`] of `x` given as `xs = 2^24·x`, for `xs ∈ [2^−125, 2^24]` (so that it is normal):
/// the same bits, for a caller that has folded the scale into an earlier product (Phong's squared
/// base, [`crate::resolved_model::ResolvedModel::phong_base_squared`]).
#[inline(always)]
fn log2_of_scaled<const L: usize, const E: usize>(xs: f32, k: &PolyConsts<L, E>) -> f32 {
    let bits = xs.to_bits() as i32;
    // Exponent e such that m = x·2^(24−e) ∈ [√½, √2): offset by the bits of √½.
    let e = bits.wrapping_sub(0x3f35_04f3) >> 23;
    let m = f32::from_bits(bits.wrapping_sub(e.wrapping_shl(23)) as u32);
    let t = m - k.one;
    e.wrapping_sub(24) as f32 + t * horner(t, &k.log2)
}

/// `2^y = q·2^r` for `y ≤ 0` (below −100 the flush bound stands in for it; callers flush) as `(q, r)`: `r = round(y)` and
/// `q = 2^(y − r)` near 1. Branch-free; `y = 0` gives `(1, 0)` exactly.
#[inline(always)]
fn exp2_parts<const L: usize, const E: usize>(y: f32, k: &PolyConsts<L, E>) -> (f32, i32) {
    // The machine's `max`, which also maps NaN to the lower bound (`f32::max`'s NaN rule costs a
    // test and a blend per lane where a loop is vectorised). No `min(y, 0)`: `y = s·log2 x` with
    // `s ≥ 0` and `x ≤ 1` is never above 0 (`log2_poly` gives 0 at 1 and less below).
    exp2_parts_unfloored(math::max_or(y, k.flush), k)
}

/// [`exp2_parts`] without the floor: for `y ≥ −100` the same `(q, r)`; for a lower or infinite
/// `y`, values that the caller must discard by a select on `y` alone, never use in arithmetic
/// (`q` may then be NaN: `−∞ − (−∞)`). Two cycles off the chain from the base to the power,
/// which in a loop over points is what a point costs.
#[inline(always)]
fn exp2_parts_unfloored<const L: usize, const E: usize>(
    y: f32,
    k: &PolyConsts<L, E>,
) -> (f32, i32) {
    // Round to nearest with the 1.5·2^23 trick (|y| ≤ 100 ≪ 2^22): the integer lands in the low
    // mantissa bits of `big`, so no float-to-int conversion (which does not vectorise) is needed.
    let big = y + k.round;
    let r = big - k.round;
    let ri = (big.to_bits() as i32).wrapping_sub(0x4b40_0000);
    let f = y - r;
    // `1 + f·R(f)` as one polynomial with the 1 as its constant coefficient: Estrin's pairs
    // start with `1 + c₀·f`, which takes two operations (a product and a sum) off the chain
    // from `f` to `q` that `1 + f·R(f)` added after `R`.
    let mut c = [0.0f32; 8];
    c[0] = k.one;
    c[1..=E].copy_from_slice(&k.exp2);
    (estrin(f, &c[..=E]), ri)
}

/// `x^s` by `exp2(s·log2 x)` for `x ∈ (0, 1]`; 0 where the result is below `2^-100`.
#[inline(always)]
pub(crate) fn poly_pow(poly: Poly, x: f32, s: f32) -> f32 {
    match poly {
        Poly::P3 => poly_pow_with(x, s, &P3_CONSTS),
        Poly::P5 => poly_pow_with(x, s, &P5_CONSTS),
        Poly::P7 => poly_pow_with(x, s, &P7_CONSTS),
    }
}

/// [`poly_pow`] with its constants `k`.
#[inline(always)]
fn poly_pow_with<const L: usize, const E: usize>(x: f32, s: f32, k: &PolyConsts<L, E>) -> f32 {
    poly_pow_in::<L, E, true>(x, s, k)
}

/// [`poly_pow_with`], with `exp2`'s floor at `−100` where `FLOOR` says so; without it, the
/// same result, from a chain two cycles shorter (see [`exp2_parts_unfloored`]). The
/// vectorised per-point loop takes the shorter chain (`fragment` probe: 45.7 → 45.3 cycles a
/// fragment); a point shaded one at a time was slower without the floor (88.0 → 89.6).
#[inline(always)]
fn poly_pow_in<const L: usize, const E: usize, const FLOOR: bool>(
    x: f32,
    s: f32,
    k: &PolyConsts<L, E>,
) -> f32 {
    exp2_flushed::<L, E, FLOOR>(s * log2_poly(x, k), k)
}

/// `2^y` for `y = s·log2 x ≤ 0`, 0 below the flush bound: the end of [`poly_pow_in`] and
/// [`poly_pow_of_scaled`], with `exp2`'s floor where `FLOOR` says so.
#[inline(always)]
fn exp2_flushed<const L: usize, const E: usize, const FLOOR: bool>(
    y: f32,
    k: &PolyConsts<L, E>,
) -> f32 {
    let (q, ri) = if FLOOR {
        exp2_parts(y, k)
    } else {
        exp2_parts_unfloored(y, k)
    };
    // `q·2^r` by adding `r` to `q`'s exponent field: exact, as the product is, since
    // `q ∈ (0.7, 1.5)` and `r ≥ −100` keep the result normal, and one integer addition where the
    // product waited for the scale's bits and then multiplied. Without the floor, a `y` below
    // −100 makes these bits garbage, which the select below discards.
    let p = f32::from_bits(q.to_bits().wrapping_add((ri as u32) << 23));
    if y >= k.flush { p } else { 0.0 }
}

/// `min(x, 1)^s` for `x` given as `xs = 2^24·x ≥ 0`, with `Poly7`: [`poly_pow_in`]'s bits for
/// `min(x, 1)` (`FLOOR` as there), since [`log2_of_scaled`] gives [`log2_poly`]'s. An `xs` below
/// `2^−125` gives a value the caller must select away (as `poly_pow_in` does for `x = 0`).
#[inline(always)]
pub(crate) fn poly_pow_of_scaled<const FLOOR: bool>(xs: f32, s: f32, k: &PolyConsts<7, 5>) -> f32 {
    exp2_flushed::<7, 5, FLOOR>(s * log2_of_scaled(math::min_or(xs, k.two_24), k), k)
}

/// [`poly_pow_with`] ending in a division, for a caller that selects it by a condition the same
/// at every point (see [`auto_pow_fixed`]): `q·2^r` as `q / 2^−r`, which is exact here
/// (`q ∈ (0.7, 1.5)` and `r ≥ −100` keep the result normal), so the bits are the product's; the
/// flush is a division by `+∞` (`q > 0`, so `+0`, the selected 0's bits). A division costs more
/// than the product when it runs, but as the result's last operation it lets the code generator
/// move the whole evaluation behind the branch that the caller's select becomes.
#[inline(always)]
fn poly_pow_div<const L: usize, const E: usize>(x: f32, s: f32, k: &PolyConsts<L, E>) -> f32 {
    let y = s * log2_poly(x, k);
    let (q, ri) = exp2_parts(y, k);
    let inv_scale = f32::from_bits((127i32.wrapping_sub(ri) as u32) << 23);
    q / if y >= k.flush {
        inv_scale
    } else {
        f32::INFINITY
    }
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
    #[allow(clippy::manual_clamp, reason = "max also maps NaN to 0")]
    let r = pow_u32(x.max(0.0).min(1.0), s as u32);
    if x > 0.0 { r } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x^s` from `2^24·x` has `poly_pow_in`'s bits for `x`, at every exponent of `x` (subnormals
    /// included), with and without `exp2`'s floor, and `x` above 1 is read as 1.
    #[test]
    fn the_power_of_the_scaled_base_is_the_power_of_the_base() {
        let k = P7_CONSTS;
        let mut checked = 0;
        for e in 0u32..=127 {
            for mantissa in [0u32, 1, 0x12_3457, 0x40_0000, 0x7f_ffff] {
                let x = f32::from_bits(e << 23 | mantissa);
                if x == 0.0 || x > 1.0 {
                    continue;
                }
                let xs = x * 16_777_216.0;
                for s in [0.0f32, 0.25, 1.0, 3.5, 16.125, 64.0, 500.0] {
                    let want = poly_pow_in::<7, 5, true>(x, s, &k);
                    assert_eq!(
                        poly_pow_of_scaled::<true>(xs, s, &k).to_bits(),
                        want.to_bits()
                    );
                    assert_eq!(
                        poly_pow_of_scaled::<false>(xs, s, &k).to_bits(),
                        want.to_bits()
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 3000, "{checked}");
        for s in [0.5f32, 7.0] {
            let one = poly_pow_in::<7, 5, true>(1.0, s, &k);
            assert_eq!(poly_pow_of_scaled::<true>(3e7, s, &k), one);
            assert_eq!(one, 1.0);
        }
    }

    /// `x^n` by the binary ladder: one squaring per bit of `n`, one product per set bit (the
    /// reference for [`pow_u32`]).
    fn pow_u32_ladder(x: f32, n: u32) -> f32 {
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

    /// The exponents and bases the ladder tests run over: every power of two, every `n < 2048`
    /// that the fixed ladder covers, and bases across `[0, 1]`.
    const BASES: [f32; 10] = [0.0, 1e-30, 0.05, 0.3, 0.5, 0.7, 0.9, 0.999, 0.99999, 1.0];

    /// The polynomial power at exponent 0 is exactly 1 for every base in `[0, 1]` (zero,
    /// subnormals and 1 included), as `auto_pow_fixed`'s shortcut for a point's exponent 0 gives;
    /// and the subnormal bases, scaled with every other by `2^24`, keep their logarithm (`x^0.5`
    /// of `2^-140` is `2^-70`).
    #[test]
    fn the_polynomial_power_at_exponent_zero_is_one() {
        let tiny = [
            f32::from_bits(1),
            f32::from_bits(0x0040_0000),
            f32::MIN_POSITIVE,
        ];
        for &x in BASES.iter().chain(&tiny) {
            for poly in [Poly::P3, Poly::P5, Poly::P7] {
                assert_eq!(
                    poly_pow(poly, x, 0.0).to_bits(),
                    1.0f32.to_bits(),
                    "x = {x:e}"
                );
            }
            assert_eq!(
                auto_pow_fixed::<false>(x, 0, 0.0, &P7_CONSTS).to_bits(),
                1.0f32.to_bits()
            );
        }
        // 2^-140 (subnormal) and 2^-70.
        let (x, want) = (f32::from_bits(1 << 9), f32::from_bits((127 - 70) << 23));
        let half = poly_pow(Poly::P7, x, 0.5);
        assert!((half / want - 1.0).abs() < 1e-5, "{half:e}");
    }

    /// The trailing-zero shortcut multiplies in the ladder's order (the ladder's first product
    /// into the accumulator is `1 · x^(2^z)`, which is exact), so the two agree bit for bit: for
    /// every power of two, every `n < 4096` and a spread of larger exponents.
    #[test]
    fn trailing_zero_shortcut_equals_the_ladder() {
        let powers = (0..32).map(|k| 1u32 << k);
        let large = (0..32)
            .map(|k| (3u32 << k) | 1)
            .chain([u32::MAX, 48 << 20, 0x8000_0001]);
        for n in (0..4096).chain(powers).chain(large) {
            for &x in &BASES {
                // The plain ladder of the base as `pow_u32` flushes it (`squaring_floor`).
                let (a, b) = (pow_u32(x, n), pow_u32_ladder(flush_for_squaring(x, n), n));
                assert_eq!(a.to_bits(), b.to_bits(), "x = {x}, n = {n}");
            }
        }
        assert_eq!(pow_u32(0.9, 0), 1.0);
        assert_eq!(pow_u32(0.5, 3), 0.125);
    }

    /// The fixed-length ladder is the same ladder with its steps past the top bit skipped, over
    /// its whole domain (`n ≤ 1024`), at the bases above and just either side of each floor.
    #[test]
    fn fixed_ladder_equals_the_ladder() {
        for n in 0..=1024 {
            let t = squaring_floor(n);
            let near = [
                t,
                f32::from_bits(t.to_bits().saturating_sub(1)),
                t.next_up(),
            ];
            for &x in BASES.iter().chain(&near) {
                let (a, b) = (pow_u32_fixed(x, n), pow_u32(x, n));
                assert_eq!(a.to_bits(), b.to_bits(), "x = {x}, n = {n}");
            }
        }
    }

    /// Each floor is `2^(−120/2^b)` rounded to nearest, for the bit length `b` of `n`, and does
    /// what `squaring_floor` promises: below it the exact power is under `2⁻⁶⁰` (so reading it
    /// as 0 is an error far inside `ERROR_FLOOR`), and from it up every square and product the
    /// ladder forms is a normal number. Checked for every `n ≤ 1024` at the floor itself, on a
    /// grid above it and at the float just below it.
    #[test]
    fn the_squaring_floor_keeps_the_ladder_normal_and_drops_only_tiny_powers() {
        for b in 1..=11u32 {
            let want = 2f64.powf(-120.0 / f64::from(1u32 << b)) as f32;
            assert_eq!(squaring_floor(1 << (b - 1)), want, "b = {b}");
            assert_eq!(squaring_floor((1 << b) - 1), want, "b = {b}");
        }
        assert_eq!(squaring_floor(0), 0.0);
        for n in 1..=1024u32 {
            let t = squaring_floor(n);
            // Just below the floor: the power is tiny and reads as 0.
            let below = f32::from_bits(t.to_bits() - 1);
            assert!(f64::from(below).powi(n as i32) < 2f64.powi(-60), "n = {n}");
            assert_eq!(pow_u32(below, n), 0.0, "n = {n}");
            // From the floor up: every value of the ladder (the squarings of x and the partial
            // products, each at least xⁿ) is normal, and so is the result.
            for k in 0..=64 {
                let x = t + (1.0 - t) * k as f32 / 64.0;
                let exact = f64::from(x).powi(n as i32);
                assert!(exact >= 2f64.powi(-121), "n = {n}, x = {x}: {exact:e}");
                let got = pow_u32(x, n);
                assert!(got >= f32::MIN_POSITIVE, "n = {n}, x = {x}: {got:e}");
            }
        }
    }

    /// `Auto` point by point is bit for bit the plan `Auto` picks: `Squaring` or `Poly7`.
    #[test]
    fn auto_pow_is_the_auto_plan() {
        for s in [
            0.0f32, 1.0, 2.0, 20.5, 32.0, 64.0, 127.3, 1024.0, 1024.5, 1500.0, 4096.0,
        ] {
            let (n, f) = auto_split(s);
            for &x in &BASES[1..] {
                let want = PowStrategy::Auto.plan(s).eval(x);
                for got in [
                    auto_pow(x, n, f),
                    auto_pow_fixed::<true>(x, n, f, &P7_CONSTS),
                ] {
                    assert_eq!(got.to_bits(), want.to_bits(), "x = {x}, s = {s}");
                }
                // A point's own exponent: Poly7 at every exponent, whole ones included (1 at 0).
                let (pn, pf) = auto_split_per_point(s);
                let want = if s == 0.0 {
                    1.0
                } else {
                    PowStrategy::Poly7.plan(s).eval(x)
                };
                let got = auto_pow_fixed::<false>(x, pn, pf, &P7_CONSTS);
                assert_eq!(got.to_bits(), want.to_bits(), "per point: x = {x}, s = {s}");
                assert_eq!(
                    auto_pow(x, pn, pf).to_bits(),
                    want.to_bits(),
                    "x = {x}, s = {s}"
                );
            }
        }
    }

    /// Without `exp2`'s floor the polynomial gives the floored result, bit for bit, wherever
    /// `y = s·log2 x` lies far below `−100` or is `−∞` (an exponent near `f32::MAX` at a
    /// subnormal base), where `(q, r)` are garbage or NaN and only the select on `y` keeps them
    /// out.
    #[test]
    fn the_unfloored_power_is_the_floored_one() {
        let bases = [
            f32::from_bits(1),
            1e-40,
            f32::MIN_POSITIVE,
            1e-30,
            1e-5,
            0.3,
            0.5,
            0.999,
            1.0 - f32::EPSILON / 2.0,
            1.0,
        ];
        let exponents = [
            0.25f32,
            1.0,
            20.5,
            127.9,
            1e3,
            3e4,
            4.2e6,
            1e7,
            1e10,
            1e30,
            3e36,
            f32::MAX,
        ];
        for &x in &bases {
            for &e in &exponents {
                let want = poly_pow_with(x, e, &P7_CONSTS);
                let got = poly_pow_in::<7, 5, false>(x, e, &P7_CONSTS);
                assert_eq!(got.to_bits(), want.to_bits(), "x = {x:e}, s = {e:e}");
                assert!((0.0..=1.0).contains(&got), "x = {x:e}, s = {e:e}: {got}");
            }
        }
    }

    #[test]
    fn squaring_matches_exact_on_integers() {
        for s in [1.0f32, 2.0, 5.0, 32.0, 100.0, 256.0] {
            for x in [0.1f32, 0.5, 0.9, 0.999, 1.0] {
                let a = PowStrategy::Squaring.lobe(x, s) as f64;
                let b = (x as f64).powf(s as f64);
                // Squaring doubles the carried relative error: e_k ≤ (2^k − 1)·u plus one rounding
                // per multiply into the accumulator, so ≤ (s + log2 s + 1)·u with u = 2^-24.
                let tol = (s as f64 + (s as f64).log2() + 1.0) * 2f64.powi(-24);
                // Plus the flush of a base whose power is below 2^-60 (`squaring_floor`).
                assert!(
                    (a - b).abs() <= tol * b + 2f64.powi(-60),
                    "x={x} s={s}: {a} vs {b}"
                );
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod error_bounds {
    use super::*;

    /// `err(x, s)` of the module docs for a computed lobe `got`: the error relative to
    /// `max(x^s, 2⁻²⁴)`, against the exact power computed in `f64` (whose own error, about 2⁻⁵³
    /// relative, is negligible here).
    pub(crate) fn err(got: f32, x: f32, s: f32) -> f64 {
        let want = (x as f64).powf(s as f64);
        (got as f64 - want).abs() / want.max(PowStrategy::ERROR_FLOOR as f64)
    }

    /// `x` on a uniform grid, near 1 ulp by ulp, at powers of two down to the subnormals, and
    /// where `x^s` runs log-uniformly from 1 down to 2⁻⁴⁰ (where the worst cases are).
    fn grid(s: f32) -> impl Iterator<Item = f32> {
        let coarse = (1..=4_000).map(|k| k as f32 / 4_000.0);
        let near_one = (1..=500).map(|k| 1.0 - k as f32 * f32::EPSILON * 0.5);
        // 2⁰ down to 2⁻¹⁴⁹ by exact halving (`powi` would overflow 2¹⁴⁹ on the way).
        let tiny = core::iter::successors(Some(1.0f32), |x| Some(x * 0.5)).take_while(|x| *x > 0.0);
        let log = (0..=4_000).map(move |k| {
            let y = -40.0 * k as f64 / 4_000.0;
            if s > 0.0 {
                (2f64.powf(y / s as f64) as f32).max(f32::MIN_POSITIVE)
            } else {
                1.0
            }
        });
        coarse.chain(near_one).chain(tiny).chain(log)
    }

    /// Exponents: fine steps below 1, small whole and half values, fractions, the squaring limit
    /// and both sides of it, and huge ones.
    fn exponents() -> impl Iterator<Item = f32> {
        let below_one = (0..=40).map(|k| k as f32 / 40.0);
        let listed = [
            0.993,
            1.0,
            1.5,
            2.5,
            7.0,
            10.25,
            16.0,
            16.5,
            20.5,
            32.0,
            48.0,
            64.0,
            100.7,
            128.0,
            256.0,
            283.87845,
            511.3,
            512.0,
            739.41705,
            1000.5,
            1021.9777,
            1023.0,
            1024.0,
            1024.5,
            1025.0,
            4096.0,
            65536.0,
            1e6,
            1e12,
            1e30,
            f32::MAX,
        ];
        below_one.chain(listed)
    }

    /// The worst cases the search behind the module docs' table found, one per strategy: every
    /// `x` within 2000 ulps of each is checked at its exponent. (Poly3's is one ulp below `√½`,
    /// where `log2`'s reduction switches exponent: a measured point, not the constant.)
    #[allow(clippy::approx_constant, reason = "a measured point, not the constant")]
    const WORST: [(PowStrategy, f32, f32); 7] = [
        (PowStrategy::Exact, 0.9920426, 2082.236),
        (PowStrategy::Squaring, 0.9846978, 1024.0),
        (PowStrategy::Poly3, 0.7071067, 48.0),
        (PowStrategy::Poly5, 0.9430845, 283.87845),
        (PowStrategy::Poly7, 0.9777624, 739.41705),
        (PowStrategy::SplitPoly3, 1.6858787e-7, 0.99323314),
        (PowStrategy::SplitPoly5, 0.9857256, 1021.9777),
    ];

    /// The worst `(err, x, s)` of one implementation of strategy `p` over the test domain: the
    /// grid for every exponent, and the neighbourhoods of the recorded worst cases. `eval(s, xs)`
    /// computes the lobe of 16 bases at once (a batch kernel's width).
    pub(crate) fn worst_over_domain(
        p: PowStrategy,
        mut eval: impl FnMut(f32, &[f32; 16]) -> [f32; 16],
    ) -> (f64, f32, f32) {
        let mut worst = (0.0f64, 0.0f32, 0.0f32);
        let mut run = |s: f32, xs: &mut dyn Iterator<Item = f32>| loop {
            let mut buf = [1.0f32; 16];
            let mut n = 0;
            for (slot, x) in buf.iter_mut().zip(&mut *xs) {
                *slot = x;
                n += 1;
            }
            let got = eval(s, &buf);
            for i in 0..n {
                let e = err(got[i], buf[i], s);
                if e > worst.0 {
                    worst = (e, buf[i], s);
                }
            }
            if n < 16 {
                break;
            }
        };
        for s in exponents() {
            run(s, &mut grid(s));
        }
        for (q, x0, s) in WORST {
            if q == p || p == PowStrategy::Auto {
                let mut near = (-2000i32..=2000)
                    .map(|k| f32::from_bits(x0.to_bits().wrapping_add_signed(k)))
                    .filter(|x| *x > 0.0 && *x <= 1.0);
                run(s, &mut near);
            }
        }
        worst
    }

    #[test]
    fn strategy_error_bounds() {
        let mut report = std::string::String::new();
        let mut failed = false;
        for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let worst = worst_over_domain(p, |s, xs| xs.map(|x| p.lobe(x, s)));
            let bound = p.max_relative_error() as f64;
            report += &std::format!(
                "{:>9}: max err {:.3e} at x={:e} s={:e} (bound {bound:.1e})\n",
                p.name(),
                worst.0,
                worst.1,
                worst.2,
            );
            failed |= worst.0 > bound;
        }
        std::println!("{report}");
        assert!(
            !failed,
            "a strategy exceeds its documented bound:\n{report}"
        );
    }

    #[test]
    fn auto_plans_what_cheapest_for_8bit_documents() {
        // `Auto` has no plan of its own: squaring for a whole exponent up to 1024, the degree-7
        // polynomial otherwise, NaN and negative exponents read as 0.
        for s in exponents().chain([-1.0, f32::NAN, -0.0, 2.0, 10.25]) {
            let c = math::clamp_or_lo(s, 0.0, math::MAX);
            let want = if c <= MAX_SQUARING && c == (c as u32) as f32 {
                PowPlan::Squaring { n: c as u32 }
            } else {
                PowPlan::Poly {
                    s: c,
                    poly: Poly::P7,
                }
            };
            assert_eq!(PowStrategy::Auto.plan(s), want, "s = {s}");
        }
    }

    #[test]
    fn the_module_docs_table_quotes_max_relative_error() {
        // The table in the module docs is written by hand; this keeps it equal to the one source,
        // `max_relative_error`.
        let src = include_str!("pow.rs");
        for p in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
            let variant = std::format!("{p:?}");
            let row = src
                .lines()
                .find(|l| l.starts_with("//! | [`") && l.contains(&std::format!("[`{variant}`]")))
                .unwrap_or_else(|| panic!("no table row for {variant}"));
            let cell = row.trim_end_matches('|').rsplit('|').next().unwrap().trim();
            let quoted: f32 = cell
                .parse()
                .unwrap_or_else(|_| panic!("{variant}: {cell:?}"));
            assert_eq!(
                quoted,
                p.max_relative_error(),
                "{variant}: the table says {cell}"
            );
        }
    }
}
