//! Promises of `Attenuation` that an outside fuzz campaign found false at the extremes, each with
//! its reproducer as a regression test and a property test that searches the part of the domain
//! where it broke:
//!
//! 1. the checked constructors reject exactly what their error says is out of range (subnormal
//!    radii and `ε` included);
//! 2. the unchecked polynomial constructor follows the crate's rule (NaN and negatives become 0,
//!    `+∞` saturates at `f32::MAX`) that its doc states;
//! 3. `factor` is finite, `≥ 0`, non-increasing in `d` and close to the exact formula for every
//!    valid form, radii and distances up to `f32::MAX` included (the window's `r + d` overflowed);
//! 4. a polynomial with a coefficient near `f32::MAX` keeps its representable factor (its `f32`
//!    denominator overflowed to `+∞`, giving 0);
//! 5. `cull_radius` keeps its contract at every scale: `+∞` exactly when the light never fades
//!    below the threshold, 0 when `factor(0)` is already below it, and otherwise safe
//!    (`factor(d) < t` for every larger `d`) and tight (exactly for the polynomial and
//!    inverse-square forms, to within the documented margin for the windowed ones). It failed in
//!    both directions: too small (unsafe) at thresholds near `factor(0)`, and far too large for
//!    huge radii, where bisecting `[0, r]` in halves cannot resolve a crossing near 100.

use phong::{Attenuation, PhongError};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// 1. Radius and ε: the error's interval is the accepted interval
// ---------------------------------------------------------------------------------------------

#[test]
fn subnormal_radius_is_rejected_with_the_interval_the_error_names() {
    // Reproducer: try_unreal(2e-39) was accepted while the error for 0 says the radius must lie
    // in [1.1754944e-38, f32::MAX].
    let e = Attenuation::try_unreal(2e-39).unwrap_err();
    assert_eq!(
        e,
        PhongError::OutOfRange {
            field: "attenuation.radius",
            value: 2e-39,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        }
    );
    assert!(matches!(
        Attenuation::try_frostbite(1e-45),
        Err(PhongError::OutOfRange {
            field: "attenuation.radius",
            ..
        })
    ));
    let literal = Attenuation::Frostbite {
        radius: 1.0,
        min_distance: f32::MIN_POSITIVE.next_down(),
    };
    assert!(matches!(
        literal.validated(),
        Err(PhongError::OutOfRange {
            field: "attenuation.min_distance",
            ..
        })
    ));
    // The ends of the interval are accepted.
    assert!(Attenuation::try_unreal(f32::MIN_POSITIVE).is_ok());
    assert!(Attenuation::try_unreal(f32::MAX).is_ok());
}

/// Any `f32` bit pattern: every class (subnormal, ±0, ±∞, NaN) is reached.
fn any_bits() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<u32>().prop_map(f32::from_bits),
        // The neighbourhood of the interval's ends, where an off-by-one would hide.
        (-4i32..4).prop_map(|k| f32::from_bits(f32::MIN_POSITIVE.to_bits().wrapping_add_signed(k))),
        (-4i32..1).prop_map(|k| f32::from_bits(f32::MAX.to_bits().wrapping_add_signed(k))),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// A radius or `ε` is accepted exactly when it lies in the interval that the `OutOfRange`
    /// error states, and every rejection of a non-negative finite value is that error.
    #[test]
    fn radius_and_min_distance_accepted_iff_in_the_stated_interval(v in any_bits()) {
        let inside = (f32::MIN_POSITIVE..=f32::MAX).contains(&v);
        let checks = [
            ("attenuation.radius", Attenuation::try_unreal(v)),
            ("attenuation.radius", Attenuation::try_frostbite(v)),
            (
                "attenuation.radius",
                Attenuation::Frostbite { radius: v, min_distance: 0.01 }.validated(),
            ),
            (
                "attenuation.min_distance",
                Attenuation::Frostbite { radius: 1.0, min_distance: v }.validated(),
            ),
            (
                "attenuation.min_distance",
                Attenuation::InverseSquare { power: 1.0, min_distance: v }.validated(),
            ),
            ("attenuation.radius", Attenuation::try_frostbite_with_min_distance(v, 0.01)),
            ("attenuation.min_distance", Attenuation::try_frostbite_with_min_distance(1.0, v)),
            ("attenuation.min_distance", Attenuation::try_inverse_square_with_min_distance(1.0, v)),
        ];
        for (name, r) in checks {
            match r {
                Ok(_) => prop_assert!(inside, "{name} = {v:e} accepted"),
                Err(PhongError::OutOfRange { field, min, max, .. }) => {
                    prop_assert_eq!(field, name);
                    prop_assert!(
                        !(min..=max).contains(&v),
                        "{v:e} rejected but in [{min:e}, {max:e}]"
                    );
                    prop_assert!(v.is_finite() && v >= 0.0);
                }
                // NonFinite or Negative: only for values outside [0, ∞), so never for one inside.
                Err(e) => prop_assert!(v.is_nan() || v.is_infinite() || v < 0.0, "{v:e}: {e:?}"),
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. The unchecked polynomial constructor: NaN and negatives → 0, +∞ → f32::MAX
// ---------------------------------------------------------------------------------------------

/// `Attenuation::polynomial(c, l, q)` in a release build, or `None` where the debug assertion
/// fired (debug builds assert the domain, as documented).
fn unchecked_polynomial(c: f32, l: f32, q: f32) -> Option<Attenuation> {
    std::panic::catch_unwind(|| Attenuation::polynomial(c, l, q)).ok()
}

/// An unchecked constructor, its checked twin's answer, and the release build's documented value.
type UncheckedCase = (
    fn(f32) -> Attenuation,
    Result<Attenuation, phong::PhongError>,
    Attenuation,
);

/// The documented release-build rule for one coefficient.
fn sanitised(x: f32) -> f32 {
    if x.is_nan() || x < 0.0 {
        0.0
    } else {
        x.min(f32::MAX)
    }
}

#[test]
fn unchecked_polynomial_saturates_infinity_as_documented() {
    // Reproducer: polynomial(0, 0, +∞) keeps f32::MAX (the crate-wide rule), while its doc said
    // non-finite coefficients become 0. The doc now states the rule; this pins the behaviour.
    let got = unchecked_polynomial(0.0, 0.0, f32::INFINITY);
    if cfg!(debug_assertions) {
        assert_eq!(got, None, "debug builds assert the domain");
    } else {
        let want = Attenuation::Polynomial {
            constant: 0.0,
            linear: 0.0,
            quadratic: f32::MAX,
        };
        assert_eq!(got, Some(want));
        let all = unchecked_polynomial(f32::NAN, -1.0, f32::NEG_INFINITY);
        let zero = Attenuation::Polynomial {
            constant: 0.0,
            linear: 0.0,
            quadratic: 0.0,
        };
        assert_eq!(all, Some(zero));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// Any coefficients: a debug build panics exactly when `try_polynomial` rejects them; a
    /// release build keeps valid ones bit for bit and sanitises the others by the documented rule.
    #[test]
    fn unchecked_polynomial_follows_the_crate_rule(
        c in any_bits(),
        l in any_bits(),
        q in any_bits(),
    ) {
        let checked = Attenuation::try_polynomial(c, l, q);
        match unchecked_polynomial(c, l, q) {
            None => prop_assert!(cfg!(debug_assertions) && checked.is_err()),
            Some(a) => {
                if let Ok(v) = checked {
                    prop_assert_eq!(a, v);
                }
                let want = Attenuation::Polynomial {
                    constant: sanitised(c),
                    linear: sanitised(l),
                    quadratic: sanitised(q),
                };
                prop_assert_eq!(a, want);
            }
        }
    }

    /// The other unchecked constructors, by the same rule for their own domains: a debug build
    /// panics exactly when the checked twin rejects the value; a release build keeps a valid one
    /// bit for bit (the checked twin's result) and otherwise clamps the power into `[0, f32::MAX]`
    /// (NaN → 0) and a radius into `[f32::MIN_POSITIVE, f32::MAX]` (NaN → the lower end).
    #[test]
    fn unchecked_constructors_follow_the_crate_rule(x in any_bits()) {
        let radius = |x: f32| {
            if x.is_nan() { f32::MIN_POSITIVE } else { x.clamp(f32::MIN_POSITIVE, f32::MAX) }
        };
        let eps = Attenuation::DEFAULT_MIN_DISTANCE;
        let cases: [UncheckedCase; 3] = [
            (
                Attenuation::inverse_square,
                Attenuation::try_inverse_square(x),
                Attenuation::InverseSquare { power: sanitised(x), min_distance: eps },
            ),
            (
                Attenuation::unreal,
                Attenuation::try_unreal(x),
                Attenuation::Unreal { radius: radius(x) },
            ),
            (
                Attenuation::frostbite,
                Attenuation::try_frostbite(x),
                Attenuation::Frostbite { radius: radius(x), min_distance: eps },
            ),
        ];
        for (unchecked, checked, want) in cases {
            match std::panic::catch_unwind(|| unchecked(x)).ok() {
                None => prop_assert!(cfg!(debug_assertions) && checked.is_err(), "{x:e}"),
                Some(a) => {
                    if let Ok(v) = checked {
                        prop_assert_eq!(a, v);
                    }
                    prop_assert_eq!(a, want);
                    prop_assert!(a.validated().is_ok(), "{a:?}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Shared strategies and the exact formula
// ---------------------------------------------------------------------------------------------

/// The unit roundoff of `f32`, `2⁻²⁴`: one correctly rounded operation is off by at most this
/// much relatively (for results in the normal range).
const U: f64 = 1.0 / (1u64 << 24) as f64;

/// Results below this are compared absolutely: subnormal results carry absolute rounding errors
/// (at most `2⁻¹⁵⁰` per operation) rather than relative ones, and Unreal's `d² + 1` overflows to
/// `+∞` (a factor of 0) only for `d > 1.8e19`, where the exact factor is below `1/d² < 2⁻¹²⁸`.
const TINY: f64 = f32::MIN_POSITIVE as f64;

/// A uniform `f64` in `[lo, hi]` on a grid of `2²⁴` steps (built from an integer: proptest's own
/// float ranges trip a debug assertion of theirs on rare draws).
fn uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (0u32..=1 << 24).prop_map(move |k| lo + (hi - lo) * (k as f64 / (1u32 << 24) as f64))
}

/// A positive `f32` spread evenly over the bit patterns of `[lo, hi]`: every binade is as likely
/// as every other, so `1e-30` and `1e30` come up as often as `1`.
fn log_f32(lo: f32, hi: f32) -> impl Strategy<Value = f32> {
    (lo.to_bits()..=hi.to_bits()).prop_map(f32::from_bits)
}

/// A polynomial coefficient or power: 0, ordinary, any magnitude up to `f32::MAX` (subnormal
/// included), and the values where the fuzz campaign found overflow.
fn coefficient() -> impl Strategy<Value = f32> {
    prop_oneof![
        2 => Just(0.0f32),
        2 => uniform(0.0, 4.0).prop_map(|x| x as f32),
        4 => log_f32(1e-45, f32::MAX),
        2 => log_f32(1e30, f32::MAX),
        1 => prop::sample::select(vec![1.0f32, f32::MAX, 3.4e38, 1e38, f32::MIN_POSITIVE, 1e-45]),
    ]
}

/// A valid radius or `ε`: `[f32::MIN_POSITIVE, f32::MAX]`, with huge and ordinary ones weighted up.
fn length() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => log_f32(f32::MIN_POSITIVE, f32::MAX),
        2 => log_f32(1e30, f32::MAX),
        2 => uniform(0.05, 100.0).prop_map(|x| x as f32),
        1 => prop::sample::select(vec![
            f32::MIN_POSITIVE,
            0.01,
            0.5,
            1.0,
            1e30,
            1e37,
            3e38,
            f32::MAX,
        ]),
    ]
}

/// Any form with valid parameters (what `validated()` accepts).
fn valid_form() -> impl Strategy<Value = Attenuation> {
    prop_oneof![
        1 => Just(Attenuation::None),
        3 => (coefficient(), coefficient(), coefficient()).prop_map(|(c, l, q)| {
            Attenuation::Polynomial { constant: c, linear: l, quadratic: q }
        }),
        2 => (coefficient(), prop_oneof![Just(0.01f32), length()])
            .prop_map(|(power, min_distance)| Attenuation::InverseSquare { power, min_distance }),
        3 => length().prop_map(|radius| Attenuation::Unreal { radius }),
        3 => (length(), prop_oneof![Just(0.01f32), length()])
            .prop_map(|(radius, min_distance)| Attenuation::Frostbite { radius, min_distance }),
    ]
    .prop_map(|a| a.validated().expect("the strategy builds valid forms"))
}

/// The length that sets the scale of a form's features: its radius, or `ε`, or 1.
fn scale(a: &Attenuation) -> f32 {
    match *a {
        Attenuation::Unreal { radius } | Attenuation::Frostbite { radius, .. } => radius,
        Attenuation::InverseSquare { min_distance, .. } => min_distance,
        _ => 1.0,
    }
}

/// A distance in `[0, f32::MAX]` for a feature of length `s`: anywhere (every binade), a fraction
/// of `s`, just below `s` (where the window vanishes), at `s`, or 0.
fn distance(s: f32) -> impl Strategy<Value = f32> {
    prop_oneof![
        3 => log_f32(1e-45, f32::MAX),
        3 => uniform(0.0, 1.5).prop_map(move |k| (s as f64 * k).min(f32::MAX as f64) as f32),
        2 => (1i32..40).prop_map(move |k| (s as f64 * (1.0 - 2f64.powi(-k))) as f32),
        1 => (0u32..64).prop_map(move |k| f32::from_bits(s.to_bits().saturating_sub(k))),
        1 => Just(s),
        1 => Just(0.0f32),
    ]
}

/// How the second distance of a pair is drawn.
#[derive(Clone, Copy, Debug)]
enum Second {
    /// Independently of the first.
    Anywhere(f32),
    /// This many ulps above the first.
    Ulps(u32),
    /// The first times `1 + δ`.
    Step(f64),
}

/// A valid form and two distances `d1 ≤ d2`: independent, or neighbours (one ulp, a few ulps, a
/// relative step) where rounding could reverse the order of the factors.
fn form_and_two_distances() -> impl Strategy<Value = (Attenuation, f32, f32)> {
    valid_form().prop_flat_map(|a| {
        let s = scale(&a);
        let second = prop_oneof![
            distance(s).prop_map(Second::Anywhere),
            (1u32..5).prop_map(Second::Ulps),
            (-23i32..-7).prop_map(|k| Second::Step(2f64.powi(k))),
        ];
        (Just(a), distance(s), second).prop_map(|(a, d1, second)| {
            let d2 = match second {
                Second::Anywhere(d) => d,
                Second::Ulps(k) => f32::from_bits((d1.to_bits() + k).min(f32::MAX.to_bits())),
                Second::Step(k) => (d1 as f64 * (1.0 + k)).min(f32::MAX as f64) as f32,
            };
            (a, d1.min(d2), d1.max(d2))
        })
    })
}

/// The exact factor (the formula in the table on `Attenuation`), in `f64`, saturated at
/// `f32::MAX` as the crate documents. The window is the direct `(1 − (d/r)⁴)²`, independent of
/// the crate's factored form: for `f32` arguments `d < r` it is `1 − x⁴ ≥ 2⁻²³`, so its `f64`
/// rounding (a few `2⁻⁵³` absolutely) is below `2⁻²⁸` relatively, far inside every tolerance here.
fn exact(a: &Attenuation, d: f32) -> f64 {
    let d = d as f64;
    let window = |r: f32| {
        let r = r as f64;
        if d < r {
            let x2 = (d / r) * (d / r);
            (1.0 - x2 * x2) * (1.0 - x2 * x2)
        } else {
            0.0
        }
    };
    let f = match *a {
        Attenuation::None => 1.0,
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => {
            let den = constant as f64 + linear as f64 * d + quadratic as f64 * d * d;
            1.0 / den.max(Attenuation::MIN_DENOMINATOR as f64)
        }
        Attenuation::InverseSquare {
            power,
            min_distance,
        } => power as f64 / d.max(min_distance as f64).powi(2),
        Attenuation::Unreal { radius } => window(radius) / (d * d + 1.0),
        Attenuation::Frostbite {
            radius,
            min_distance,
        } => window(radius) / d.max(min_distance as f64).powi(2),
    };
    f.min(f32::MAX as f64)
}

/// How far `factor` may be from [`exact`], relatively, by the number of roundings in its
/// evaluation:
/// - polynomial: 4 in the denominator and 1 in the division (5u); where the `f32` denominator
///   overflows, the evaluation on scaled operands: 4 roundings in its denominator, which is
///   deliberately raised by 12u (one more rounding), the reciprocal and the scaling back: 19u
///   below the exact factor at most (see `factor`). Bound 20u.
/// - inverse square: two divisions (the `max` is exact): 2u. Bound 4u.
/// - windowed: the window squared, 17u (see `window`), then `d² + 1` and the division (3u) or two
///   divisions (2u): 20u, plus below 1u for the `f64` reference's own rounding near `d = r`.
///   Bound 32u = 2⁻¹⁹, the margin `cull_radius` uses.
fn tolerance(a: &Attenuation) -> f64 {
    match a {
        Attenuation::None => 0.0,
        Attenuation::Polynomial { .. } => 20.0 * U,
        Attenuation::InverseSquare { .. } => 4.0 * U,
        _ => 32.0 * U,
    }
}

// ---------------------------------------------------------------------------------------------
// 3. factor: finite, ≥ 0, non-increasing and accurate over the whole f32 range
// ---------------------------------------------------------------------------------------------

#[test]
fn frostbite_with_a_huge_radius_vanishes_at_its_edge() {
    // Reproducer: (r + d)/r overflowed in the window, so the factor just inside r = 3e38 was
    // f32::MAX where the formula gives about 1e-77, and factor(0) = 1e4 < factor(3e38).
    let f = Attenuation::Frostbite {
        radius: 3e38,
        min_distance: 0.01,
    };
    let d = 2.999_999_8e38f32;
    let got = f.factor(d);
    assert_eq!(
        got,
        0.0,
        "factor({d:e}) = {got:e}; the exact value {:e} underflows",
        exact(&f, d)
    );
    assert_eq!(f.factor(0.0), 1e4);
    assert!(f.factor(3e38) <= f.factor(0.0));
    // Where the exact value is representable, factor keeps the window's relative precision: at
    // d = 0.9·r and 2⁻²⁰ below r the window itself, unscaled, is what Unreal at radius 1 gives.
    let u = Attenuation::Unreal { radius: 3e38 };
    for k in [0.5f64, 0.9, 1.0 - 2f64.powi(-20)] {
        let d = (3e38 * k) as f32;
        let (got, want) = (u.factor(d), exact(&u, d));
        assert!(
            got as f64 <= want + TINY,
            "Unreal 3e38 at {d:e}: {got:e} vs {want:e}"
        );
    }
    let one = Attenuation::Unreal {
        radius: 1.0 - 2f32.powi(-24),
    };
    let near = 1.0 - 2f32.powi(-23); // the window is about 2⁻⁴⁴ here
    let (got, want) = (one.factor(near) as f64, exact(&one, near));
    assert!((got - want).abs() <= 32.0 * U * want, "{got:e} vs {want:e}");
}

#[test]
fn no_factor_exceeds_its_value_at_the_light() {
    // Rounding lifted the window an ulp above 1 for about 1.5 % of small d/r, so Unreal at a
    // tiny radius and Frostbite below ε gave factor(d) > factor(0) (here: the first such case a
    // scan found). cull_radius returns 0 when factor(0) < t, which needs factor(d) ≤ factor(0).
    let u = Attenuation::Unreal {
        radius: 1.447_747e-8,
    };
    let d = 1.253_255_6e-10;
    assert!(
        u.factor(d) <= u.factor(0.0),
        "{} > {}",
        u.factor(d),
        u.factor(0.0)
    );
    let f = Attenuation::Frostbite {
        radius: 1.447_747e-8,
        min_distance: 0.01,
    };
    assert!(
        f.factor(d) <= f.factor(0.0),
        "{} > {}",
        f.factor(d),
        f.factor(0.0)
    );
}

#[test]
fn polynomial_with_a_huge_coefficient_keeps_its_factor() {
    // Reproducer: l + q·d overflowed to +∞ although the denominator d·(l + q·d) is 3.4e36, so
    // the factor was 0 instead of 2.9e-37.
    let p = Attenuation::Polynomial {
        constant: 0.0,
        linear: 3.4e38,
        quadratic: 1e38,
    };
    let (got, want) = (p.factor(0.01) as f64, exact(&p, 0.01));
    assert!(want > 2.9e-37 && want < 3e-37, "{want:e}");
    // The scaled path: at most 19u below the exact factor (see `tolerance`), never above it.
    assert!(
        got <= want && want - got <= 20.0 * U * want,
        "{got:e} vs {want:e}"
    );
    // The same near every overflow: of q·d, of l + q·d, of the product, of the sum.
    let cases = [
        (0.0, 0.0, f32::MAX, 2.0),
        (0.0, f32::MAX, 1e30, 20.0),
        (0.0, 1e30, 0.0, 1e9),
        (f32::MAX, 1.0, 0.0, 1e38),
    ];
    for (constant, linear, quadratic, d) in cases {
        let p = Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        };
        let (got, want) = (p.factor(d) as f64, exact(&p, d));
        assert!(got > 0.0, "{p:?} at {d:e}");
        assert!(
            (got - want).abs() <= 20.0 * U * want + TINY,
            "{p:?} at {d:e}: {got:e} vs {want:e}"
        );
    }
}

#[test]
fn polynomial_is_monotone_where_its_denominator_starts_to_overflow() {
    // The scaled path takes over at the first d whose f32 denominator overflows; there the factor
    // must not rise above the f32 path's value one ulp earlier (the scaled denominator is raised
    // by 12·2⁻²⁴ for that). Walk across the switch for coefficients that overflow in each place.
    let forms = [
        (0.0f32, 3.4e38f32, 1e38f32),
        (0.0, f32::MAX, f32::MAX),
        (0.0, 0.0, f32::MAX),
        (0.0, 3e38, 1.0),
        (3e38, 1.0, 0.0),
        (1.0, 1e20, 1e30),
        // Found by a random scan: without a raise of the overflowed denominator the factor rose
        // across the switch here by a few units in the last place (5.622784e-39 → 5.622786e-39,
        // 2.3121098e-38 → 2.31211e-38).
        (1.461_032_1e38, 3.287_677_4e38, 1.234_295_7e38),
        (3.813_231_2e37, 3.398_706_5e38, 2.737_18e37),
    ];
    for (constant, linear, quadratic) in forms {
        let p = Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        };
        // The first overflowing d, by bisection over the bit patterns (the f32 denominator is
        // monotone in d).
        let den = |d: f32| constant + d * (linear + quadratic * d);
        let (mut lo, mut hi) = (0u32, f32::MAX.to_bits());
        assert!(den(f32::MAX).is_infinite() && den(0.0).is_finite());
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if den(f32::from_bits(mid)).is_infinite() {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let mut prev = p.factor(f32::from_bits(lo.saturating_sub(64)));
        for bits in lo.saturating_sub(63)..=(hi + 64).min(f32::MAX.to_bits()) {
            let d = f32::from_bits(bits);
            let f = p.factor(d);
            assert!(f <= prev, "{p:?}: factor rises at {d:e}: {prev:e} -> {f:e}");
            prev = f;
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    /// Finite, `≥ 0`, at most `factor(0)`, and within [`tolerance`] of the exact formula
    /// (relatively, or absolutely below `f32::MIN_POSITIVE`).
    #[test]
    fn factor_is_finite_bounded_and_accurate(
        (a, d, _) in form_and_two_distances(),
    ) {
        let f = a.factor(d);
        prop_assert!(f.is_finite() && f >= 0.0, "{a:?}.factor({d:e}) = {f:e}");
        let f0 = a.factor(0.0);
        prop_assert!(f <= f0, "{a:?}.factor({d:e}) = {f:e} > factor(0) = {f0:e}");
        let want = exact(&a, d);
        let err = (f as f64 - want).abs();
        prop_assert!(
            err <= tolerance(&a) * want + TINY,
            "{a:?}.factor({d:e}) = {f:e}, exact {want:e}: relative error {:e}",
            err / want
        );
    }

    /// Non-increasing in `d`: exactly for the polynomial and inverse-square forms (every
    /// operation in their evaluation is monotone in `d`), and within rounding for the windowed
    /// ones. There each factor is within 21u of the exact, decreasing formula, plus at most
    /// `2⁻¹⁴⁹` absolutely from underflow, so
    /// `factor(d2) ≤ factor(d1)·(1 + 21u)/(1 − 21u) + 2·2⁻¹⁴⁹`, below the
    /// `factor(d1)·(1 + 2⁻¹⁸) + 2⁻¹⁴⁷` asserted (`2⁻¹⁸` = 64u).
    #[test]
    fn factor_is_non_increasing((a, d1, d2) in form_and_two_distances()) {
        let (f1, f2) = (a.factor(d1), a.factor(d2));
        let windowed = matches!(a, Attenuation::Unreal { .. } | Attenuation::Frostbite { .. });
        let slack = if windowed {
            f1 as f64 * 2f64.powi(-18) + 2f64.powi(-147)
        } else {
            0.0
        };
        prop_assert!(
            f2 as f64 <= f1 as f64 + slack,
            "{a:?}: factor({d1:e}) = {f1:e} < factor({d2:e}) = {f2:e}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 5. cull_radius: never cull, zero, or safe and tight
// ---------------------------------------------------------------------------------------------

/// The windowed forms' documented margin: `cull_radius` is tight to `t·(1 − 2⁻¹⁹) − 2⁻¹⁴⁹`.
fn windowed_floor(t: f32) -> f64 {
    t as f64 * (1.0 - 2f64.powi(-19)) - 2f64.powi(-149)
}

fn is_windowed(a: &Attenuation) -> bool {
    matches!(
        a,
        Attenuation::Unreal { .. } | Attenuation::Frostbite { .. }
    )
}

/// Checks the documented contract of `a.cull_radius(t)` at the points that decide it, with the
/// extra distances `more` (beyond the result) where the factor must also be below `t`.
fn check_cull_radius(a: &Attenuation, t: f32, more: &[f64]) -> Result<f32, String> {
    let r = a.cull_radius(t);
    let what = format!("{a:?}.cull_radius({t:e}) = {r:e}");
    let fail = |why: String| Err(format!("{what}: {why}"));
    if r.is_nan() || r < 0.0 {
        return fail("not in [0, +∞]".into());
    }
    // +∞ exactly for a non-positive or NaN threshold, or when the light never fades below t.
    let never = t.is_nan() || t <= 0.0 || a.factor(f32::MAX) >= t;
    if never != (r == f32::INFINITY) {
        return fail(format!("factor(f32::MAX) = {:e}", a.factor(f32::MAX)));
    }
    if never {
        return Ok(r);
    }
    if a.factor(0.0) < t && r != 0.0 {
        return fail(format!("factor(0) = {:e} < t, want 0", a.factor(0.0)));
    }
    // Safe: below t everywhere past r. The next ulps (where an ulp's wiggle of the windowed
    // product would show), a relative step, the given distances, and far out.
    let mut ds: Vec<f32> = (1..=64).map(|k| f32::from_bits(r.to_bits() + k)).collect();
    for k in [2f64.powi(-20), 1e-3, 1.0, 10.0, 1e10] {
        ds.push((r as f64 * (1.0 + k)).min(f32::MAX as f64) as f32);
    }
    ds.extend(more.iter().map(|&d| d.min(f32::MAX as f64) as f32));
    ds.push(f32::MAX);
    for d in ds.into_iter().filter(|&d| d > r) {
        if a.factor(d) >= t {
            return fail(format!("unsafe: factor({d:e}) = {:e} ≥ t", a.factor(d)));
        }
    }
    // Tight, where the factor reaches t at all.
    if a.factor(0.0) >= t {
        if is_windowed(a) {
            let radius = match *a {
                Attenuation::Unreal { radius } | Attenuation::Frostbite { radius, .. } => radius,
                _ => unreachable!(),
            };
            if r > radius {
                return fail(format!("beyond the radius {radius:e}"));
            }
            // The test's exact formula differs from the crate's f64 one by far less than 2⁻²⁷
            // relatively (see `exact`); allow that much.
            let floor = windowed_floor(t) * (1.0 - 2f64.powi(-27));
            if exact(a, r) < floor {
                return fail(format!(
                    "not tight: exact factor {:e} < {floor:e}",
                    exact(a, r)
                ));
            }
        } else if a.factor(r) < t {
            return fail(format!("not tight: factor(r) = {:e} < t", a.factor(r)));
        }
    }
    Ok(r)
}

#[test]
fn cull_radius_reproducers_are_safe_and_tight() {
    // Unreal r = 1 at t = 1 gave 7.45e-9, yet the f32 factor is 1 ≥ t up to about 2.4e-4 (the
    // window and d² + 1 round to 1 there).
    let u = Attenuation::Unreal { radius: 1.0 };
    let r = check_cull_radius(&u, 1.0, &[7.45e-9 * 1.001, 1e-4, 2e-4]).unwrap();
    assert!(r > 1e-4, "{r:e}");
    // Polynomial 1/(2 + d²) at t = 0.5 gave 0, yet factor(1e-5) = 0.5 = t. The f32 factor is
    // monotone, so the answer is exact: the last f32 at which 2 + d² still rounds to 2.
    let p = Attenuation::Polynomial {
        constant: 2.0,
        linear: 0.0,
        quadratic: 1.0,
    };
    assert_eq!(p.factor(1e-5), 0.5);
    let r = check_cull_radius(&p, 0.5, &[1e-5]).unwrap();
    assert!(
        p.factor(r) >= 0.5 && p.factor(r.next_up()) < 0.5 && r >= 1e-5,
        "{r:e}"
    );
    // Frostbite r = 0.5 at t = 1e4 = factor(0) gave 0.0061136, yet the f32 factor stays 1e4 to
    // 0.00616.
    let f = Attenuation::Frostbite {
        radius: 0.5,
        min_distance: 0.01,
    };
    assert_eq!(f.factor(0.0), 1e4);
    let r = check_cull_radius(&f, 1e4, &[0.006_113_6 * 1.000_01, 0.006_16]).unwrap();
    assert!(r >= 0.006_16, "{r:e}");
    // Huge radii: the factor crosses 1e-4 near d = 99.995 (Unreal: 1/(d² + 1) = 1e-4) and
    // d = 100 (Frostbite: 1/d²), whatever the radius; bisecting [0, r] in 80 halvings gave
    // 827,180 for r = 1e30, and radii near 1e37 were as loose.
    for radius in [1e30f32, 1e37, 3e38, f32::MAX] {
        for a in [
            Attenuation::try_unreal(radius).unwrap(),
            Attenuation::try_frostbite(radius).unwrap(),
        ] {
            let r = check_cull_radius(&a, 1e-4, &[101.0, 1e3, 827_180.0]).unwrap();
            let want = if matches!(a, Attenuation::Unreal { .. }) {
                9999f64.sqrt()
            } else {
                100.0
            };
            // Tight to the margin: where the factor ~ 1/d², 2⁻¹⁹ in t moves the root by 2⁻²⁰.
            assert!((r as f64 / want - 1.0).abs() < 2e-6, "{a:?}: {r} vs {want}");
        }
    }
}

#[test]
fn cull_radius_is_infinite_exactly_when_the_light_never_fades_below_t() {
    let inf = f32::INFINITY;
    let c_only = Attenuation::Polynomial {
        constant: 0.5,
        linear: 0.0,
        quadratic: 0.0,
    };
    // Tiny linear term: factor(f32::MAX) = 1/(1e-42·f32::MAX) ≈ 2.9e3, below factor(0) = 1e4.
    let tiny_l = Attenuation::Polynomial {
        constant: 0.0,
        linear: 1e-42,
        quadratic: 0.0,
    };
    // Huge power: factor(f32::MAX) = f32::MAX/f32::MAX/f32::MAX ≈ 2.9e-39.
    let huge_p = Attenuation::InverseSquare {
        power: f32::MAX,
        min_distance: 0.01,
    };
    let cases = [
        (Attenuation::None, 1.0, inf),
        (Attenuation::None, 1.0f32.next_up(), 0.0),
        (c_only, 2.0, inf),
        (c_only, 2.0f32.next_up(), 0.0),
        (tiny_l, 1e3, inf),
        (huge_p, 1e-39, inf),
        (Attenuation::try_unreal(3e38).unwrap(), 1e-45, 3e38),
    ];
    for (a, t, want) in cases {
        let r = check_cull_radius(&a, t, &[]).unwrap();
        if want == 3e38 {
            // Even the smallest threshold is met only inside the radius.
            assert!(r.is_finite() && r <= want, "{a:?} at {t:e}: {r:e}");
        } else {
            assert_eq!(r, want, "{a:?} at {t:e}");
        }
    }
    for t in [f32::NAN, 0.0, -0.0, -1.0, f32::NEG_INFINITY] {
        assert_eq!(Attenuation::try_unreal(1.0).unwrap().cull_radius(t), inf);
    }
    // And the light that fades: finite at every positive threshold.
    let huge_p_finite = check_cull_radius(&huge_p, 1e-37, &[]).unwrap();
    assert!(huge_p_finite.is_finite());
}

/// A threshold for `a`: anywhere, just at or around `factor(0)`, a fraction of it, the factor's
/// own value at a distance (so the crossing is exactly at an `f32`), or tiny.
fn threshold_for(a: Attenuation) -> impl Strategy<Value = f32> {
    let f0 = a.factor(0.0);
    prop_oneof![
        2 => log_f32(1e-45, f32::MAX),
        1 => Just(f0),
        1 => Just(f0.next_up()),
        1 => (0u32..4096).prop_map(move |k| f32::from_bits(f0.to_bits().saturating_sub(k))),
        2 => uniform(0.0, 150.0).prop_map(move |k| (f0 as f64 * 2f64.powf(-k)) as f32),
        3 => distance(scale(&a)).prop_map(move |d| a.factor(d)),
        1 => prop::sample::select(vec![1e-45f32, f32::MIN_POSITIVE, 1e-30, 1e-4, 1.0]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(5000))]

    /// The contract for random valid forms (huge and tiny radii, huge coefficients) and
    /// thresholds (at, above and far below `factor(0)`, and tiny), with safety also checked at
    /// random distances in `(R, 2R]`.
    #[test]
    fn cull_radius_keeps_its_contract(
        (a, t, ks) in valid_form().prop_flat_map(|a| {
            (Just(a), threshold_for(a), prop::collection::vec(uniform(0.0, 1.0), 4))
        }),
    ) {
        let r = a.cull_radius(t) as f64;
        let more: Vec<f64> = ks.iter().map(|k| r * (1.0 + k)).collect();
        if let Err(e) = check_cull_radius(&a, t, &more) {
            prop_assert!(false, "{}", e);
        }
    }
}
