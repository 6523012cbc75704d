//! Promises of `Attenuation` that an outside fuzz campaign found false at the extremes, each with
//! its reproducer as a regression test and a property test that searches the part of the domain
//! where it broke:
//!
//! 1. the checked constructors reject exactly what their error says is out of range (subnormal
//!    radii and `ε` included);

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
                    prop_assert!(!(min..=max).contains(&v), "{v:e} rejected but in [{min:e}, {max:e}]");
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
    fn unchecked_polynomial_follows_the_crate_rule(c in any_bits(), l in any_bits(), q in any_bits()) {
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
}
