//! How a light's intensity falls off with distance, and where it becomes negligible.
//!
//! Every form is finite at `d = 0` and for every finite or infinite `d ≥ 0`, and non-increasing in
//! `d` (for the documented, non-negative parameters; the windowed forms within rounding, see
//! [`Attenuation::factor`]). [`Attenuation::cull_radius`] gives a distance beyond which the
//! factor stays below a threshold, so a renderer can skip lights that cannot change a pixel. Derivations: docs/derivations.md, section "Attenuation".

use crate::error::{self, PhongError};
use crate::math;

/// A distance-falloff form for point and spot lights.
///
/// | variant | factor at distance `d` |
/// |---|---|
/// | `None` | `1` |
/// | `Polynomial` | `1 / max(c + l·d + q·d², MIN_DENOMINATOR)` (OpenGL, LearnOpenGL) |
/// | `InverseSquare` | `P / max(d², ε²)` (the power `P` is a multiplier) |
/// | `Unreal` | `saturate(1 − (d/r)⁴)² / (d² + 1)` (Karis 2013) |
/// | `Frostbite` | `saturate(1 − (d/r)⁴)² / max(d², ε²)` (Lagarde & de Rousiers 2014) |
///
/// **Domain:** coefficients and power finite and `≥ 0`; radius and `ε` finite and at least
/// `f32::MIN_POSITIVE` (positive, not subnormal). The `try_*` constructors and
/// [`validated`](Attenuation::validated) check this and name the bad field. The factor is
/// evaluated robustly for any field values (it is always finite and `≥ 0`), but monotonicity and
/// the promises of [`cull_radius`] assume the documented domain.
///
/// [`cull_radius`]: Attenuation::cull_radius
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self", deny_unknown_fields)
)]
pub enum Attenuation {
    /// No falloff: the factor is 1 at every distance (the light never fades). The default.
    #[default]
    None,
    /// `1 / (constant + linear·d + quadratic·d²)`, the OpenGL fixed-function and LearnOpenGL form.
    Polynomial {
        /// `c`, the constant term (LearnOpenGL uses 1, which also caps the factor at 1).
        constant: f32,
        /// `l`, the linear term.
        linear: f32,
        /// `q`, the quadratic term; `c = l = 0, q = 1` is the inverse-square law.
        quadratic: f32,
    },
    /// `P / max(d², ε²)`: the inverse-square law scaled by a light power.
    InverseSquare {
        /// `P`, a multiplier (not an exponent). To reproduce the Blinn-Phong shader on Wikipedia,
        /// leave this at 1 and give its light power to
        /// [`LightColors::try_from_power`](crate::LightColors::try_from_power), so it is applied once.
        power: f32,
        /// `ε`, the distance below which the factor stops growing (default 0.01, one centimetre in
        /// metres, as Frostbite uses).
        min_distance: f32,
    },
    /// `saturate(1 − (d/r)⁴)² / (d² + 1)`: inverse-square with a window that reaches 0 at `r`.
    Unreal {
        /// `r`, where the light ends.
        radius: f32,
    },
    /// `saturate(1 − (d/r)⁴)² / max(d², ε²)`: Frostbite's windowed inverse-square.
    Frostbite {
        /// `r`, where the light ends.
        radius: f32,
        /// `ε`, the distance below which the factor stops growing (default 0.01).
        min_distance: f32,
    },
}

/// The windowing function `saturate(1 − (d/r)⁴)²`; 0 for `d ≥ r` (and for `r ≤ 0` or NaN), 1 for
/// `r = +∞` (the limit).
///
/// Factored as `1 − x⁴ = ((r − d)/r)·(1 + x)·(1 + x²)` with `x = d/r ∈ [0, 1)`: `r − d` is exact
/// when `d` is near `r` (Sterbenz), so the window keeps its relative precision where it goes to
/// zero, where the direct `1 − x⁴` would cancel. The other two factors lie in `[1, 2)` and cannot
/// cancel; `1 + x` stands for `(r + d)/r`, whose `r + d` overflows to `+∞` for `r, d` near
/// `f32::MAX` (giving `f32::MAX` where the window is near 0). Every intermediate is at most 2, so
/// nothing overflows for any `0 ≤ d < r ≤ f32::MAX`.
///
/// Relative error at most 8 roundings before the square (17 after it): 2 in `(r − d)/r`, 2 in
/// `1 + x`, 3 in `1 + x²` (each weighted by at most 1), 2 products. The product is capped at 1,
/// the exact window's maximum: rounding near `d = 0` otherwise lifts it an ulp above 1 (for about
/// 1.5 % of small `d/r`), and the factor would then exceed its value at `d = 0`.
#[inline(always)]
fn window(d: f32, r: f32) -> f32 {
    if d < r {
        let x = d / r; // in [0, 1): finite because r > d ≥ 0
        let w = ((r - d) / r) * (1.0 + x) * (1.0 + x * x);
        // NaN only for r = +∞ (∞/∞), whose limit is 1.
        let w = math::min_or(w, 1.0);
        w * w
    } else {
        0.0
    }
}

/// [`window`]'s operations in any [`FactorArith`], every one computed and the result selected
/// where `d < r` (the batch kernel's falloff test checks the two against each other bit for bit;
/// `window` keeps its branch, which the scalar paths were tuned with).
#[inline(always)]
fn window_in<A: FactorArith>(a: A, d: A::V, r: A::V) -> A::V {
    let one = a.splat(1.0);
    let x = a.div(d, r); // in [0, 1) where kept: finite because r > d ≥ 0
    let w = a.mul(
        a.mul(a.div(a.sub(r, d), r), a.add(one, x)),
        a.add(one, a.mul(x, x)),
    );
    // NaN only for r = +∞ (∞/∞), whose limit is 1.
    let w = a.min_or(w, one);
    a.select_lt(d, r, a.mul(w, w), a.splat(0.0))
}

/// The arithmetic [`FlatAttenuation::factor_in`] is written in: `f32` for one value
/// ([`OneValue`]), and the batch kernel's sixteen lanes, so that both evaluate the falloff by one
/// source, operation for operation (each operation is IEEE-exact in both: no fused multiply-add).
pub(crate) trait FactorArith: Copy {
    /// One value, or one per lane.
    type V: Copy;
    /// `x` (in every lane).
    fn splat(self, x: f32) -> Self::V;
    /// `a + b`.
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a − b`.
    fn sub(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a · b`, not fused with what follows.
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    /// `a / b`.
    fn div(self, a: Self::V, b: Self::V) -> Self::V;
    /// `x > lo ? x : lo` (`lo` for NaN), as [`math::max_or`].
    fn max_or(self, x: Self::V, lo: Self::V) -> Self::V;
    /// `x < hi ? x : hi` (`hi` for NaN), as [`math::min_or`].
    fn min_or(self, x: Self::V, hi: Self::V) -> Self::V;
    /// `a < b ? x : y`.
    fn select_lt(self, a: Self::V, b: Self::V, x: Self::V, y: Self::V) -> Self::V;
}

/// [`FactorArith`] on one `f32`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OneValue;

impl FactorArith for OneValue {
    type V = f32;
    #[inline(always)]
    fn splat(self, x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn add(self, a: f32, b: f32) -> f32 {
        a + b
    }
    #[inline(always)]
    fn sub(self, a: f32, b: f32) -> f32 {
        a - b
    }
    #[inline(always)]
    fn mul(self, a: f32, b: f32) -> f32 {
        a * b
    }
    #[inline(always)]
    fn div(self, a: f32, b: f32) -> f32 {
        a / b
    }
    #[inline(always)]
    fn max_or(self, x: f32, lo: f32) -> f32 {
        math::max_or(x, lo)
    }
    #[inline(always)]
    fn min_or(self, x: f32, hi: f32) -> f32 {
        math::min_or(x, hi)
    }
    #[inline(always)]
    fn select_lt(self, a: f32, b: f32, x: f32, y: f32) -> f32 {
        if a < b { x } else { y }
    }
}

/// `2⁻³²`, exact in `f32`: the scale of the distance and of `l` in [`overflowed_reciprocal`].
const TWO_POW_M32: f32 = f32::from_bits((127 - 32) << 23);

/// `2⁻⁶⁴`, exact in `f32`: the scale of `c`, and of the reciprocal back.
const TWO_POW_M64: f32 = f32::from_bits((127 - 64) << 23);

/// `1 + 12·2⁻²⁴`: how far [`overflowed_reciprocal`] raises its scaled denominator (see there).
const RAISE: f32 = 1.0 + 12.0 / (1u32 << 24) as f32;

/// The polynomial's coefficients rescaled for [`overflowed_reciprocal`]: `c·2⁻⁶⁴` and `l·2⁻³²`,
/// each exact, or 0 where it would be subnormal (`c < 2⁻⁶²`, `l < 2⁻⁹⁴`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct OverflowScale {
    c: f32,
    l: f32,
}

impl OverflowScale {
    #[inline(always)]
    fn new(constant: f32, linear: f32) -> Self {
        let c = constant * TWO_POW_M64;
        let l = linear * TWO_POW_M32;
        Self {
            c: if c >= f32::MIN_POSITIVE { c } else { 0.0 },
            l: if l >= f32::MIN_POSITIVE { l } else { 0.0 },
        }
    }
}

/// `2⁶⁴ / (c + d·(l + q·d))`, raised by [`RAISE`], for a polynomial whose `f32` denominator
/// overflowed: the same Horner form on operands scaled into range, in `f32`, with `ds = d·2⁻³²`.
/// Times `2⁻⁶⁴` (one rounding) it is the factor.
///
/// **Why it cannot overflow or lose the answer.** Where the `f32` denominator overflows, the exact
/// one is at least `2¹⁰⁰` (each way of overflowing needs `l + q·d ≳ 2¹²⁸` with `d ≳ 2⁻²⁵`, or
/// `d·(l + q·d)` or the sum `≳ 2¹²⁸`), so `ds ≥ 2⁻⁵⁷` is normal and exact, and the scaled
/// denominator, `2⁻⁶⁴` times the exact one, is at least `2³⁶`. A coefficient flushed to 0 by
/// [`OverflowScale`] contributed less than `2⁻⁶⁰` of it, an underflow in `q·ds` less than
/// `2⁻⁹⁰`. An intermediate that overflows means an exact denominator above `2¹⁹²`, whose factor
/// rounds to 0, as `1/∞` does.
///
/// **No subnormal operand where it did not overflow.** A vectorised loop evaluates this for every
/// point and discards it where the denominator was finite; for distances and coefficients of
/// ordinary size every intermediate is then a normal number (`2⁻³²` and `2⁻⁶⁴` are far from the
/// subnormal range), where a subnormal one would cost a microcode assist per instruction on many
/// x86 cores.
///
/// **Monotone across the switch.** The `f32` path's denominator `D₁` at any smaller distance is
/// at most 4 roundings above the exact one, plus absolute underflow errors below `2⁻²⁰`, which
/// are below `2⁻¹²⁰` of it here: `D₁ ≤ den·(1 + 4.01·2⁻²⁴)`. This evaluation is at least
/// `den·2⁻⁶⁴·(1 − 4.01·2⁻²⁴)` (4 roundings); raised by `12·2⁻²⁴` (one more rounding), and with
/// the reciprocal's own rounding, the factor stays below the exact `1/D₁`, so after the final
/// rounding it is at most the `f32` path's `1/D₁`: the factor is non-increasing in `d`, which
/// [`Attenuation::cull_radius`]'s bisection relies on. The price is a relative error of at most
/// `19·2⁻²⁴` below the exact factor, plus `2⁻¹⁵⁰` where the factor is subnormal.
#[inline(always)]
fn overflowed_reciprocal(k: OverflowScale, quadratic: f32, ds: f32) -> f32 {
    overflowed_reciprocal_in(OneValue, k, quadratic, ds)
}

/// [`overflowed_reciprocal`] in any [`FactorArith`].
#[inline(always)]
fn overflowed_reciprocal_in<A: FactorArith>(
    a: A,
    k: OverflowScale,
    quadratic: f32,
    ds: A::V,
) -> A::V {
    let den = a.add(
        a.splat(k.c),
        a.mul(ds, a.add(a.splat(k.l), a.mul(a.splat(quadratic), ds))),
    );
    a.div(a.splat(1.0), a.mul(den, a.splat(RAISE)))
}

/// The polynomial factor where its `f32` denominator `c + d·(l + q·d)` overflowed (for a finite
/// `d ≥ 0` and coefficients in `[0, f32::MAX]`): [`overflowed_reciprocal`] scaled back.
///
/// Out of line and cold, so the common path of [`Attenuation::factor`] keeps one comparison.
#[cold]
#[inline(never)]
fn polynomial_overflowed(constant: f32, linear: f32, quadratic: f32, d: f32) -> f32 {
    let k = OverflowScale::new(constant, linear);
    let f = overflowed_reciprocal(k, quadratic, d * TWO_POW_M32) * TWO_POW_M64;
    // ∞ coefficients (outside the domain) give 1/∞ = 0; NaN cannot arise from a finite d.
    math::clamp_or_lo(f, 0.0, math::MAX)
}

/// [`window`] in `f64`, the same factored form (no cancellation near `d = r`), for the root
/// search of the cull radius.
fn window_f64(d: f64, r: f64) -> f64 {
    if d < r {
        let x = d / r;
        let w = ((r - d) / r) * (1.0 + x) * (1.0 + x * x);
        let w = if w < 1.0 { w } else { 1.0 };
        w * w
    } else {
        0.0
    }
}

/// Every [`Attenuation`] form as one formula, so a shading loop evaluates a falloff it does not
/// know at compile time without branching on the form (a branch that, run for every lane of a
/// vectorised loop, would stop the compiler vectorising it):
///
/// ```text
/// dd     = max(d, min_d)
/// factor = power · window(d, r) / max(c + dd·(l + q·dd), floor)      (the rational forms)
///        = power · window(d, r) / dd / dd                            (the inverse-square forms)
/// window(d, ∞) = 1
/// ```
///
/// | form | `c, l, q` | `power` | `min_d` | `r` |
/// |---|---|---|---|---|
/// | `None` | 1, 0, 0 | 1 | 0 | ∞ |
/// | `Polynomial` | its coefficients | 1 | 0 | ∞ |
/// | `InverseSquare` | – | `P` | `max(ε, f32::MIN_POSITIVE)` | ∞ |
/// | `Unreal` | 1, 0, 1 | 1 | 0 | `r` |
/// | `Frostbite` | – | 1 | `max(ε, f32::MIN_POSITIVE)` | `r` |
///
/// These are [`Attenuation::factor`]'s own operations in its own order, so the result is the same,
/// bit for bit, including the scaled evaluation of an overflowing polynomial denominator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FlatAttenuation {
    c: f32,
    l: f32,
    q: f32,
    power: f32,
    min_d: f32,
    floor: f32,
    radius: f32,
    /// Divide by `dd` twice (the inverse-square forms) instead of by `max(den, floor)`.
    twice: bool,
    /// Where the denominator counts as overflowed: `f32::MAX` for the polynomial forms (above it
    /// means ∞, evaluated scaled into range as `factor` does), ∞ for the others (never).
    overflow_above: f32,
    /// The coefficients for that evaluation.
    scaled: OverflowScale,
}

impl FlatAttenuation {
    /// The factor at distance `d ∈ [0, f32::MAX]` (the crate's lengths are: the caller passes one,
    /// and debug builds assert it). Never NaN and never negative (every numerator is finite and
    /// `≥ 0`, every denominator positive), so only the saturation at `f32::MAX` is applied.
    #[inline(always)]
    pub(crate) fn factor(&self, d: f32) -> f32 {
        debug_assert!(
            (0.0..=math::MAX).contains(&d),
            "a flat factor's distance must lie in [0, f32::MAX], got {d}"
        );
        self.factor_in(OneValue, d)
    }

    /// [`factor`](Self::factor) in any [`FactorArith`]: the batch kernel evaluates it on sixteen
    /// lanes, with the same operations in the same order, so its factors are the scalar path's,
    /// bit for bit (tested at every level in the kernel's tests).
    #[inline(always)]
    pub(crate) fn factor_in<A: FactorArith>(&self, a: A, d: A::V) -> A::V {
        let dd = a.max_or(d, a.splat(self.min_d));
        let den = a.add(
            a.splat(self.c),
            a.mul(dd, a.add(a.splat(self.l), a.mul(a.splat(self.q), dd))),
        );
        // `radius` is the same at every point: in a vectorised loop this stays a branch, and the
        // window runs only for the windowed forms.
        let w = if self.radius < f32::INFINITY {
            window_in(a, d, a.splat(self.radius))
        } else {
            a.splat(1.0)
        };
        // The inverse-square forms divide twice by `dd`, as `factor` does: `dd²` underflows for
        // `dd` below 1e-19 and overflows above 1.8e19, while `P/dd/dd` is still representable.
        // The second division is chosen on the form alone, outside the per-point choice below,
        // so that it too stays a branch.
        let divisor = if self.twice {
            dd
        } else {
            a.max_or(den, a.splat(self.floor))
        };
        let q = a.div(a.mul(a.splat(self.power), w), divisor);
        let q = if self.twice { a.div(q, dd) } else { q };
        // As `polynomial_overflowed` (the polynomial forms: power 1, no window). A vectorised
        // loop computes both and selects; see `overflowed_reciprocal` for why that is cheap.
        let wide = a.mul(
            overflowed_reciprocal_in(a, self.scaled, self.q, a.mul(dd, a.splat(TWO_POW_M32))),
            a.splat(TWO_POW_M64),
        );
        let f = a.select_lt(a.splat(self.overflow_above), den, wide, q);
        a.min_or(f, a.splat(math::MAX))
    }
}

impl Attenuation {
    /// The smallest denominator the polynomial form divides by, so its factor never exceeds 1e4
    /// (the same cap as the inverse-square forms at `P = 1`, `ε = 0.01`).
    pub const MIN_DENOMINATOR: f32 = 1e-4;

    /// This falloff as [`FlatAttenuation`]'s one formula.
    #[inline]
    pub(crate) fn flat(&self) -> FlatAttenuation {
        let form = |c, l, q, power, min_d: f32, radius, twice| FlatAttenuation {
            c,
            l,
            q,
            power,
            min_d,
            floor: Self::MIN_DENOMINATOR,
            radius,
            twice,
            overflow_above: if matches!(self, Attenuation::None | Attenuation::Polynomial { .. }) {
                math::MAX
            } else {
                f32::INFINITY
            },
            scaled: OverflowScale::new(c, l),
        };
        let inf = f32::INFINITY;
        let eps = |e: f32| e.max(f32::MIN_POSITIVE);
        match *self {
            Attenuation::None => form(1.0, 0.0, 0.0, 1.0, 0.0, inf, false),
            Attenuation::Polynomial {
                constant,
                linear,
                quadratic,
            } => form(constant, linear, quadratic, 1.0, 0.0, inf, false),
            Attenuation::InverseSquare {
                power,
                min_distance,
            } => form(0.0, 0.0, 1.0, power, eps(min_distance), inf, true),
            Attenuation::Unreal { radius } => form(1.0, 0.0, 1.0, 1.0, 0.0, radius, false),
            Attenuation::Frostbite {
                radius,
                min_distance,
            } => form(0.0, 0.0, 1.0, 1.0, eps(min_distance), radius, true),
        }
    }

    /// The default `ε` of the inverse-square forms: 0.01 (a centimetre when units are metres).
    pub const DEFAULT_MIN_DISTANCE: f32 = 0.01;

    /// The polynomial form `1/(c + l·d + q·d²)`, without checks.
    ///
    /// **Domain:** every coefficient finite and `≥ 0`; debug builds assert it. Release builds apply
    /// the crate's rule for unchecked constructors to each coefficient: NaN and negatives (`−∞`
    /// included) become 0, and `+∞` (an overflowed coefficient) saturates at `f32::MAX`. Use
    /// [`try_polynomial`](Self::try_polynomial) to reject such values instead.
    ///
    /// ```
    /// use phong::Attenuation;
    /// // LearnOpenGL's table entry for a range of about 50 units.
    /// let a = Attenuation::polynomial(1.0, 0.09, 0.032);
    /// assert_eq!(a.factor(0.0), 1.0);
    /// ```
    #[must_use]
    pub fn polynomial(constant: f32, linear: f32, quadratic: f32) -> Self {
        debug_assert!(
            Self::try_polynomial(constant, linear, quadratic).is_ok(),
            "Attenuation::polynomial: coefficients must be finite and >= 0"
        );
        let s = |x: f32| math::clamp_or_lo(x, 0.0, math::MAX);
        Attenuation::Polynomial {
            constant: s(constant),
            linear: s(linear),
            quadratic: s(quadratic),
        }
    }

    /// `P / max(d², ε²)` with the default `ε` ([`Self::DEFAULT_MIN_DISTANCE`]), without checks.
    ///
    /// **Domain:** `P` finite and `≥ 0`; debug builds assert it. Release builds apply the crate's
    /// rule for unchecked constructors: NaN and negatives become 0, `+∞` saturates at `f32::MAX`.
    /// Use [`try_inverse_square`](Self::try_inverse_square) to reject such values instead.
    ///
    /// ```
    /// use phong::Attenuation;
    /// assert_eq!(Attenuation::inverse_square(4.0).factor(2.0), 1.0);
    /// ```
    #[must_use]
    pub fn inverse_square(power: f32) -> Self {
        debug_assert!(
            Self::try_inverse_square(power).is_ok(),
            "Attenuation::inverse_square: power must be finite and >= 0"
        );
        Attenuation::InverseSquare {
            power: math::clamp_or_lo(power, 0.0, math::MAX),
            min_distance: Self::DEFAULT_MIN_DISTANCE,
        }
    }

    /// The Unreal windowed form `saturate(1 − (d/r)⁴)² / (d² + 1)` with radius `r`, without checks.
    ///
    /// **Domain:** `r` in `[f32::MIN_POSITIVE, f32::MAX]`; debug builds assert it. Release builds
    /// clamp `r` into that range, with NaN read as the lower end (a light whose window closes at
    /// once, the nearest valid thing to a zero radius). Use [`try_unreal`](Self::try_unreal) to
    /// reject such values instead.
    ///
    /// ```
    /// use phong::Attenuation;
    /// let a = Attenuation::unreal(10.0);
    /// assert_eq!(a.factor(10.0), 0.0); // nothing at or past the radius
    /// assert_eq!(a, Attenuation::try_unreal(10.0).unwrap());
    /// ```
    #[must_use]
    pub fn unreal(radius: f32) -> Self {
        debug_assert!(
            Self::try_unreal(radius).is_ok(),
            "Attenuation::unreal: radius must lie in [f32::MIN_POSITIVE, f32::MAX]"
        );
        Attenuation::Unreal {
            radius: math::clamp_or_lo(radius, f32::MIN_POSITIVE, math::MAX),
        }
    }

    /// The Frostbite windowed form `saturate(1 − (d/r)⁴)² / max(d², ε²)` with radius `r` and the
    /// default `ε` ([`Self::DEFAULT_MIN_DISTANCE`]), without checks.
    ///
    /// **Domain and release behaviour:** as [`unreal`](Self::unreal). Use
    /// [`try_frostbite`](Self::try_frostbite) to reject bad radii instead.
    ///
    /// ```
    /// use phong::Attenuation;
    /// let a = Attenuation::frostbite(10.0);
    /// assert_eq!(a.factor(10.0), 0.0);
    /// assert_eq!(a, Attenuation::try_frostbite(10.0).unwrap());
    /// ```
    #[must_use]
    pub fn frostbite(radius: f32) -> Self {
        debug_assert!(
            Self::try_frostbite(radius).is_ok(),
            "Attenuation::frostbite: radius must lie in [f32::MIN_POSITIVE, f32::MAX]"
        );
        Attenuation::Frostbite {
            radius: math::clamp_or_lo(radius, f32::MIN_POSITIVE, math::MAX),
            min_distance: Self::DEFAULT_MIN_DISTANCE,
        }
    }

    /// The polynomial form, checked: every coefficient finite and `≥ 0`.
    ///
    /// ```
    /// use phong::{Attenuation, PhongError};
    /// assert!(matches!(
    ///     Attenuation::try_polynomial(1.0, -0.1, 0.0),
    ///     Err(PhongError::Negative { field: "attenuation.linear", .. })
    /// ));
    /// ```
    pub fn try_polynomial(constant: f32, linear: f32, quadratic: f32) -> Result<Self, PhongError> {
        Ok(Attenuation::Polynomial {
            constant: error::non_negative("attenuation.constant", constant)?,
            linear: error::non_negative("attenuation.linear", linear)?,
            quadratic: error::non_negative("attenuation.quadratic", quadratic)?,
        })
    }

    /// `P / max(d², ε²)` with the default `ε` ([`Self::DEFAULT_MIN_DISTANCE`]), checked: `P` finite
    /// and `≥ 0`.
    pub fn try_inverse_square(power: f32) -> Result<Self, PhongError> {
        Ok(Attenuation::InverseSquare {
            power: error::non_negative("attenuation.power", power)?,
            min_distance: Self::DEFAULT_MIN_DISTANCE,
        })
    }

    /// `P / max(d², ε²)` with a chosen `ε`, checked: `P` finite and `≥ 0`,
    /// `ε` in `[f32::MIN_POSITIVE, f32::MAX]`.
    ///
    /// ```
    /// use phong::Attenuation;
    /// let a = Attenuation::try_inverse_square_with_min_distance(1.0, 0.5)?;
    /// assert_eq!(a.factor(0.0), 4.0); // 1 / 0.5²: the factor stops growing inside ε
    /// # Ok::<(), phong::PhongError>(())
    /// ```
    pub fn try_inverse_square_with_min_distance(
        power: f32,
        min_distance: f32,
    ) -> Result<Self, PhongError> {
        Attenuation::InverseSquare {
            power,
            min_distance,
        }
        .validated()
    }

    /// The Unreal windowed form with radius `r`, checked: `r` in `[f32::MIN_POSITIVE, f32::MAX]`
    /// (finite, positive and not subnormal).
    ///
    /// **Errors:** [`PhongError::NonFinite`] for NaN or ±∞, [`PhongError::Negative`] below 0, and
    /// [`PhongError::OutOfRange`] for 0 and subnormal radii.
    ///
    /// ```
    /// use phong::{Attenuation, PhongError};
    /// assert!(Attenuation::try_unreal(10.0).is_ok());
    /// assert!(matches!(
    ///     Attenuation::try_unreal(2e-39), // subnormal
    ///     Err(PhongError::OutOfRange { field: "attenuation.radius", .. })
    /// ));
    /// ```
    pub fn try_unreal(radius: f32) -> Result<Self, PhongError> {
        Ok(Attenuation::Unreal {
            radius: positive("attenuation.radius", radius)?,
        })
    }

    /// The Frostbite windowed form with radius `r` and the default `ε`, checked: `r` in
    /// `[f32::MIN_POSITIVE, f32::MAX]`, with the errors of [`try_unreal`](Self::try_unreal).
    pub fn try_frostbite(radius: f32) -> Result<Self, PhongError> {
        Ok(Attenuation::Frostbite {
            radius: positive("attenuation.radius", radius)?,
            min_distance: Self::DEFAULT_MIN_DISTANCE,
        })
    }

    /// `saturate(1 − (d/r)⁴)² / max(d², ε²)` (Frostbite's windowed form) with a chosen `ε`,
    /// checked: `r` and `ε` in `[f32::MIN_POSITIVE, f32::MAX]`; otherwise the error names the field.
    pub fn try_frostbite_with_min_distance(
        radius: f32,
        min_distance: f32,
    ) -> Result<Self, PhongError> {
        Attenuation::Frostbite {
            radius,
            min_distance,
        }
        .validated()
    }

    /// Checks the fields of any variant, as the `try_*` constructors do; returns `self` if valid:
    /// coefficients and power finite and `≥ 0`, radius and `ε` in `[f32::MIN_POSITIVE, f32::MAX]`.
    ///
    /// Use it after building a variant literally, or after deserialising one.
    pub fn validated(self) -> Result<Self, PhongError> {
        match self {
            Attenuation::None => Ok(self),
            Attenuation::Polynomial {
                constant,
                linear,
                quadratic,
            } => Self::try_polynomial(constant, linear, quadratic),
            Attenuation::InverseSquare {
                power,
                min_distance,
            } => {
                error::non_negative("attenuation.power", power)?;
                positive("attenuation.min_distance", min_distance)?;
                Ok(self)
            }
            Attenuation::Unreal { radius } => Self::try_unreal(radius),
            Attenuation::Frostbite {
                radius,
                min_distance,
            } => {
                positive("attenuation.radius", radius)?;
                positive("attenuation.min_distance", min_distance)?;
                Ok(self)
            }
        }
    }

    /// The factor at distance `d` from the light.
    ///
    /// The formula of each form is in the table on [`Attenuation`].
    ///
    /// **Domain:** `d ≥ 0`; any `f32` is accepted: negative `d` and NaN are treated as 0, `+∞` as the
    /// limit. **Returns** a finite value in `[0, f32::MAX]`, also at `d = 0` (where the inverse-square
    /// forms give `P/ε²` and the polynomial at most `1/MIN_DENOMINATOR`).
    ///
    /// **Accuracy:** against the exact formula, at most 5 roundings (`5·2⁻²⁴` relatively) for the
    /// polynomial, 2 for the inverse-square and 20 for the windowed forms, with results below
    /// `f32::MIN_POSITIVE` only absolutely accurate (subnormal). A polynomial whose `f32`
    /// denominator overflows (a coefficient near `f32::MAX`, or a distance near it) is evaluated
    /// out of line on operands scaled into range, to within `19·2⁻²⁴` below the exact factor
    /// (plus `2⁻¹⁵⁰` where it is subnormal), instead of giving 0.
    ///
    /// **Monotone:** for valid parameters the factor never exceeds `factor(0)`, and is
    /// non-increasing in `d`: exactly for `None`, the polynomial and the inverse-square forms
    /// (every operation of their evaluation is monotone in `d`), and within rounding for the
    /// windowed forms, whose `f32` product of a decreasing and an increasing term can rise by an
    /// ulp: `factor(d₂) ≤ factor(d₁)·(1 + 2⁻¹⁸) + 2⁻¹⁴⁷` for `d₁ ≤ d₂`.
    ///
    /// ```
    /// use phong::Attenuation;
    /// let q = Attenuation::polynomial(0.0, 0.0, 1.0);
    /// assert_eq!(q.factor(2.0), 0.25); // inverse-square law
    /// assert_eq!(q.factor(0.0), 1e4);  // finite at the light
    /// let u = Attenuation::try_unreal(10.0).unwrap();
    /// assert_eq!(u.factor(10.0), 0.0);
    /// ```
    #[must_use]
    #[inline(always)]
    pub fn factor(&self, d: f32) -> f32 {
        self.factor_of_length(math::clamp_or_lo(d, 0.0, math::MAX))
    }

    /// [`factor`](Self::factor) at a distance `d ∈ [0, f32::MAX]` that the crate computed (a
    /// saturated length, never NaN), without `factor`'s clamp of `d`: what a light's
    /// [`sample`](crate::LightSource::sample) calls, once per light and point. Debug builds
    /// assert the domain.
    #[inline(always)]
    pub(crate) fn factor_of_length(&self, d: f32) -> f32 {
        debug_assert!(
            (0.0..=math::MAX).contains(&d),
            "a light's distance must lie in [0, f32::MAX], got {d}"
        );
        match *self {
            Attenuation::None => 1.0,
            Attenuation::Polynomial {
                constant,
                linear,
                quadratic,
            } => {
                // Horner form: no ∞·0 for any finite d, so no NaN; the denominator is at least
                // MIN_DENOMINATOR, so the factor is finite.
                let den = constant + d * (linear + quadratic * d);
                if den == f32::INFINITY {
                    // A coefficient near f32::MAX: 1/∞ = 0 would lose a representable factor.
                    return polynomial_overflowed(constant, linear, quadratic, d);
                }
                // `max_or` maps every `den` (NaN from coefficients outside the domain included) to
                // at least MIN_DENOMINATOR, so the quotient lies in (0, 1e4]: no clamp needed.
                1.0 / math::max_or(den, Self::MIN_DENOMINATOR)
            }
            // The other forms run out of line, so shading loops inline only the common two.
            _ => self.factor_other(d),
        }
    }

    /// [`factor`](Self::factor) for the inverse-square and windowed forms, `d` already clamped.
    #[inline(never)]
    fn factor_other(&self, d: f32) -> f32 {
        let f = match *self {
            Attenuation::None => 1.0,
            Attenuation::Polynomial { .. } => self.factor(d),
            Attenuation::InverseSquare {
                power,
                min_distance,
            } => {
                // Divide twice: dd² overflows for dd > 1.8e19 while P/dd² is still representable.
                let dd = d.max(min_distance).max(f32::MIN_POSITIVE);
                power / dd / dd
            }
            Attenuation::Unreal { radius } => window(d, radius) / (d * d + 1.0),
            Attenuation::Frostbite {
                radius,
                min_distance,
            } => {
                let dd = d.max(min_distance).max(f32::MIN_POSITIVE);
                window(d, radius) / dd / dd
            }
        };
        math::clamp_or_lo(f, 0.0, math::MAX)
    }

    /// The distance beyond which [`factor`](Self::factor) stays below `threshold`: lights farther
    /// than this from a point can be skipped.
    ///
    /// **Promise (safe):** for valid parameters, `factor(d) < threshold` for every `d` greater
    /// than the result, checked against this crate's own `f32` [`factor`](Self::factor), so a
    /// renderer that culls with it never drops a light it would have shaded at `≥ threshold`.
    ///
    /// **Returns**, never NaN:
    /// - `f32::INFINITY` ("never cull") for a NaN or non-positive threshold, and exactly when
    ///   `factor(f32::MAX) ≥ t`: the light does not fade below `t` at any finite distance (`None`
    ///   with `t ≤ 1`, a polynomial with `l = q = 0` and `1/c ≥ t`, or coefficients, power and
    ///   threshold so extreme that, say, `1/(l·f32::MAX) ≥ t`).
    /// - `0` when `factor(0) < t`: the factor never exceeds `factor(0)`, so it is below `t`
    ///   everywhere.
    /// - otherwise a finite `R`, found by bisection over the ordered bit patterns of the `f32`
    ///   distances in `[0, f32::MAX]` (at most 31 steps, so exact at every scale: no tolerance,
    ///   and no loss for huge radii):
    ///   - `Polynomial`, `InverseSquare`: their `f32` factor is non-increasing, so `R` is the
    ///     largest `f32` with `factor(R) ≥ t`, which is exactly tight:
    ///     `factor(R) ≥ t > factor(R.next_up())`.
    ///   - `Unreal`, `Frostbite`: the `f32` product of a decreasing and an increasing term can rise
    ///     by an ulp, so `R` is the larger of that bisection's result and the largest `f32` below
    ///     the radius where the exact formula (in `f64`) is at least `t·(1 − 2⁻¹⁹) − 2⁻¹⁴⁹`.
    ///     `2⁻¹⁹` bounds the relative error of the `f32` factor (20 roundings of `2⁻²⁴`, see
    ///     [`factor`](Self::factor)) and `2⁻¹⁴⁹` its absolute error where it is subnormal, so past
    ///     that distance the `f32` factor is below `t`. `R ≤ radius`, and `R` is tight in the sense
    ///     that the exact factor at `R` is at least `t·(1 − 2⁻¹⁹) − 2⁻¹⁴⁹`: where the factor is
    ///     flat (`t` near `factor(0)`) `R` can lie well past the crossing of `t` itself.
    ///
    /// What it approximates, the exact crossing `inf { r ≥ 0 : factor(d) < t for every d > r }`:
    ///
    /// | form | exact cull radius |
    /// |---|---|
    /// | `None` | `+∞` for `t ≤ 1`, else 0 |
    /// | `Polynomial` | the positive root of `c + l·d + q·d² = 1/t` |
    /// | `InverseSquare` | `√(P/t)` |
    /// | `Unreal`, `Frostbite` | `min(r, root of factor(d) = t)` (a degree-8 polynomial) |
    ///
    /// A pick of `t` for 8-bit output is half a step of the brightest colour the light can add:
    /// `t = 0.5 / (255 · max colour)`.
    ///
    /// ```
    /// use phong::Attenuation;
    /// let q = Attenuation::polynomial(0.0, 0.0, 1.0);
    /// let r = q.cull_radius(0.01);
    /// assert_eq!(r, 10.0); // 1/d² ≥ 0.01 up to d = 10 in f32, and not one ulp further
    /// assert!(q.factor(r) >= 0.01 && q.factor(r.next_up()) < 0.01);
    /// assert_eq!(Attenuation::None.cull_radius(0.01), f32::INFINITY);
    /// let f = Attenuation::try_frostbite(5.0).unwrap();
    /// assert!(f.cull_radius(1e-9) <= 5.0);
    /// ```
    #[must_use]
    pub fn cull_radius(&self, threshold: f32) -> f32 {
        let t = threshold;
        if !(t > 0.0) {
            return f32::INFINITY;
        }
        if !(self.factor(0.0) >= t) {
            return 0.0;
        }
        if self.factor(f32::MAX) >= t {
            return f32::INFINITY;
        }
        // factor(0) ≥ t > factor(f32::MAX): the bisection's invariant holds at both ends, and its
        // result R has factor(R) ≥ t > factor(R.next_up()) whether or not factor is monotone.
        let last = last_f32_where(f32::MAX, |d| self.factor(d) >= t);
        match *self {
            Attenuation::Unreal { radius } | Attenuation::Frostbite { radius, .. } => {
                last.max(self.windowed_crossing(t, radius))
            }
            _ => last,
        }
    }

    /// For the windowed forms: the largest `f32` below `radius` where the exact factor, in `f64`,
    /// is at least `t·(1 − CULL_MARGIN) − 2⁻¹⁴⁹`; 0 if there is none, or if `radius` is not in
    /// `(0, f32::MAX]`. Past it the `f32` factor is below `t` (see [`Attenuation::cull_radius`]).
    fn windowed_crossing(&self, t: f32, radius: f32) -> f32 {
        if !(radius > 0.0 && radius <= f32::MAX) {
            return 0.0;
        }
        let r = radius as f64;
        // The exact formula with the same clamps as factor_other; the factored window has no
        // cancellation near d = r, and every f64 intermediate lies in [2⁻²⁵², 2²⁵⁶].
        let exact = |d: f64| -> f64 {
            match *self {
                Attenuation::Unreal { .. } => window_f64(d, r) / (d * d + 1.0),
                Attenuation::Frostbite { min_distance, .. } => {
                    let dd = d.max(min_distance as f64).max(f32::MIN_POSITIVE as f64);
                    window_f64(d, r) / (dd * dd)
                }
                _ => 0.0,
            }
        };
        let target = t as f64 * (1.0 - CULL_MARGIN) - SUBNORMAL_ERROR;
        last_f32_where(radius, |d| exact(d as f64) >= target)
    }
}

/// The relative error the windowed factors' `f32` evaluation may have, with room: 20 roundings of
/// `2⁻²⁴` (17 in the squared window, 3 in `/(d² + 1)`, see [`window`]) and their second-order
/// terms are below `21·2⁻²⁴`; `2⁻¹⁹ = 32·2⁻²⁴`, and the `f64` formula it is compared with is
/// accurate to a few `2⁻⁵³`. So where the exact factor is below `t·(1 − 2⁻¹⁹)`, the `f32` one is
/// below `t`.
const CULL_MARGIN: f64 = 1.0 / (1u32 << 19) as f64;

/// The absolute error the windowed factors' `f32` evaluation may add where results are subnormal:
/// the final rounding (at most `2⁻¹⁵⁰`), and for Frostbite a subnormal first quotient `w/dd`
/// (another `2⁻¹⁵⁰`, divided by `dd > 2⁷⁸`, since `w ≥ 2⁻⁴⁸` when it is not 0). `2⁻¹⁴⁹` bounds
/// their sum.
const SUBNORMAL_ERROR: f64 = f32::MIN_POSITIVE as f64 / (1u32 << 23) as f64;

/// The largest `f32` `d` in `[0, hi)` with `pred(d)`, by bisection over the ordered bit patterns
/// of the non-negative `f32`s (at most 31 steps for `hi ≤ f32::MAX`), assuming `pred(hi)` is
/// false (it is never evaluated); 0 if `pred(0)` is false. The result `d` always has `pred(d)`
/// and `!pred(d.next_up())` (or `d.next_up() = hi`); if `pred` is true on an initial segment of
/// the distances and false after it, `d` is the segment's end.
fn last_f32_where(hi: f32, pred: impl Fn(f32) -> bool) -> f32 {
    if !pred(0.0) {
        return 0.0;
    }
    let (mut lo, mut hi) = (0u32, hi.to_bits());
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if pred(f32::from_bits(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    f32::from_bits(lo)
}

/// Checks a radius or `ε`: finite and at least `f32::MIN_POSITIVE`, the interval its error names.
///
/// Subnormal values are rejected with the zero: the error says the value must lie in
/// `[f32::MIN_POSITIVE, f32::MAX]`, and accepting `2e-39` would contradict that message.
fn positive(field: &'static str, value: f32) -> Result<f32, PhongError> {
    let v = error::non_negative(field, value)?;
    if v < f32::MIN_POSITIVE {
        Err(PhongError::OutOfRange {
            field,
            value,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        })
    } else {
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flat form is `factor` itself, operation for operation, for every form and every
    /// distance: near 0, around each radius and minimum distance, and out to `f32::MAX` (where the
    /// polynomial denominator overflows and both take the scaled evaluation).
    #[test]
    fn flat_form_is_the_factor_bit_for_bit() {
        let forms = [
            Attenuation::None,
            Attenuation::polynomial(1.0, 0.09, 0.032),
            Attenuation::polynomial(0.0, 0.0, 2.0),
            Attenuation::polynomial(1.0, f32::MAX, 2.0),
            Attenuation::polynomial(0.0, 3.0, f32::MAX),
            Attenuation::try_inverse_square(3.0).unwrap(),
            Attenuation::try_inverse_square_with_min_distance(4.4e-26, 3.6e-23).unwrap(),
            Attenuation::try_unreal(8.0).unwrap(),
            Attenuation::try_unreal(5.6e-38).unwrap(),
            Attenuation::try_unreal(f32::MAX).unwrap(),
            Attenuation::try_frostbite(8.0).unwrap(),
        ];
        let mut ds = vec![
            0.0f32, 1e-45, 1e-38, 1e-20, 0.01, 0.5, 1.0, 7.999, 8.0, 8.001, 1e19, 1e20,
        ];
        ds.extend([1e30, 1e38, f32::MAX]);
        ds.extend((0..2000).map(|k| k as f32 * 0.005));
        for a in forms {
            let flat = a.flat();
            for &d in &ds {
                assert_eq!(
                    flat.factor(d).to_bits(),
                    a.factor(d).to_bits(),
                    "{a:?} at d = {d}"
                );
            }
        }
    }

    #[test]
    fn cull_radius_is_where_the_factor_crosses() {
        let forms = [
            Attenuation::polynomial(1.0, 0.09, 0.032),
            Attenuation::polynomial(0.0, 0.0, 2.0),
            Attenuation::try_inverse_square(3.0).unwrap(),
            Attenuation::try_unreal(8.0).unwrap(),
            Attenuation::try_frostbite(8.0).unwrap(),
        ];
        for a in forms {
            for t in [1e-3f32, 0.01, 0.1] {
                let r = a.cull_radius(t);
                assert!(r.is_finite(), "{a:?} t={t}");
                assert!(a.factor(r * 1.0001 + 1e-6) < t, "{a:?} t={t} r={r}");
                assert!(a.factor(r * 0.999) >= t, "{a:?} t={t} r={r}: not tight");
            }
        }
    }
}
