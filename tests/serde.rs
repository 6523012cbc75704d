//! The `serde` feature: round trips through JSON, and rejection of invalid files with the field named.
#![cfg(feature = "serde")]

use glam::Vec3;
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Light, LightColors, Material, Model, Normalization,
    Phong, PointLight, PowStrategy, SpecularGate, SpotLight, Terms, Viewer,
};

fn round_trip<T>(value: &T) -> T
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + core::fmt::Debug,
{
    let json = serde_json::to_string(value).expect("serialises");
    let back: T = serde_json::from_str(&json).expect("deserialises what it wrote");
    assert_eq!(&back, value, "round trip through {json}");
    back
}

fn colors() -> LightColors {
    LightColors::try_from_strengths(Vec3::new(1.0, 0.9, 0.8), 0.1, 0.8, 0.5).unwrap()
}

#[test]
fn every_parameter_type_round_trips() {
    let m = Material::try_new(Vec3::splat(0.1), Vec3::new(0.7, 0.2, 0.1), Vec3::ONE, 20.5)
        .unwrap()
        .try_with_emission(Vec3::new(0.0, 0.01, 0.0))
        .unwrap();
    round_trip(&m);
    round_trip(&colors());
    for a in [
        Attenuation::None,
        Attenuation::polynomial(1.0, 0.09, 0.032),
        Attenuation::try_inverse_square(40.0).unwrap(),
        Attenuation::try_unreal(12.0).unwrap(),
        Attenuation::try_frostbite(12.0).unwrap(),
    ] {
        round_trip(&a);
    }
    let lights: Vec<Light> = vec![
        DirectionalLight::try_new(Vec3::new(1.0, 2.0, 3.0), colors())
            .unwrap()
            .into(),
        PointLight::try_new(
            Vec3::new(0.0, 3.0, 1.0),
            Attenuation::polynomial(1.0, 0.0, 0.1),
            colors(),
        )
        .unwrap()
        .into(),
        SpotLight::try_new(
            Vec3::Y * 4.0,
            -Vec3::Y,
            0.4,
            8.0,
            Attenuation::None,
            colors(),
        )
        .unwrap()
        .into(),
    ];
    let back = round_trip(&lights);
    // The spot's derived cosine is recomputed, not read from the file.
    let Light::Spot(spot) = back[2] else {
        panic!("variant kept")
    };
    assert_eq!(
        spot.cos_cutoff(),
        0.4f32.cos(),
        "cos(cutoff) recomputed on load"
    );
    for model in [
        Model::Lambert(Default::default()),
        Model::Phong(Phong::learnopengl()),
        Model::BlinnPhong(BlinnPhong {
            gate: SpecularGate::Cosine,
            normalization: Normalization::EnergyExact,
            pow: PowStrategy::Squaring,
        }),
    ] {
        round_trip(&model);
    }
    round_trip(&Viewer::At(Vec3::new(0.0, 1.0, 5.0)));
    round_trip(&Viewer::Infinite(Vec3::new(0.0, 3.0, 4.0)));
    round_trip(&Terms {
        ambient: Vec3::new(0.0, 1e-40, f32::MAX),
        diffuse: Vec3::splat(0.5),
        specular: Vec3::new(2.0, 0.0, 0.25),
        emission: Vec3::ZERO,
    });
}

#[test]
fn a_material_reads_from_a_hand_written_file() {
    let json = r#"{ "ambient": [0.1, 0.1, 0.1], "diffuse": [0.8, 0.2, 0.2],
                    "specular": [0.5, 0.5, 0.5], "emission": [0, 0, 0], "shininess": 32 }"#;
    let m: Material = serde_json::from_str(json).unwrap();
    assert_eq!(m.diffuse(), Vec3::new(0.8, 0.2, 0.2));
    assert_eq!(m.shininess(), 32.0);
}

fn rejection<T: serde::de::DeserializeOwned + core::fmt::Debug>(json: &str) -> String {
    serde_json::from_str::<T>(json)
        .expect_err("an invalid file must not load")
        .to_string()
}

#[test]
fn invalid_files_are_rejected_naming_the_field() {
    let e = rejection::<Material>(
        r#"{ "ambient": [0,0,0], "diffuse": [1,1,1], "specular": [1,1,1],
             "emission": [0,0,0], "shininess": -2 }"#,
    );
    assert!(
        e.contains("material.shininess must be non-negative, got -2"),
        "{e}"
    );

    let e = rejection::<Material>(
        r#"{ "ambient": [0,0,0], "diffuse": [1,-0.5,1], "specular": [1,1,1],
             "emission": [0,0,0], "shininess": 8 }"#,
    );
    assert!(e.contains("material.diffuse.y"), "{e}");

    // 1e39 does not fit an f32: it parses as +inf, which must be reported, not kept.
    let e = rejection::<LightColors>(
        r#"{ "ambient": [0,0,0], "diffuse": [1e39,0,0], "specular": [0,0,0] }"#,
    );
    assert!(e.contains("light.diffuse.x must be finite"), "{e}");

    let e = rejection::<Attenuation>(
        r#"{ "Polynomial": { "constant": 1, "linear": -0.1, "quadratic": 0 } }"#,
    );
    assert!(e.contains("attenuation.linear"), "{e}");

    let e = rejection::<Attenuation>(r#"{ "Unreal": { "radius": 0 } }"#);
    assert!(e.contains("attenuation.radius"), "{e}");

    let e = rejection::<DirectionalLight>(
        r#"{ "direction": [0,0,0], "colors": { "ambient": [0,0,0], "diffuse": [1,1,1], "specular": [1,1,1] } }"#,
    );
    assert!(
        e.contains("light.direction must be a non-zero direction"),
        "{e}"
    );

    let e = rejection::<SpotLight>(
        r#"{ "position": [0,0,0], "axis": [0,-1,0], "cutoff": 2.0, "exponent": 1,
             "attenuation": "None",
             "colors": { "ambient": [0,0,0], "diffuse": [1,1,1], "specular": [1,1,1] } }"#,
    );
    assert!(e.contains("light.cutoff must lie in"), "{e}");
}

/// Fuzz reproducer: `1e39` does not fit an `f32`, serde_json reads it as `+∞`, and a plainly derived
/// `Viewer` used to keep that. The check names the coordinate.
#[test]
fn a_viewer_at_infinity_is_rejected() {
    let e = rejection::<Viewer>(r#"{"At":[1e39,0,0]}"#);
    assert!(
        e.contains("viewer.position.x must be finite, got inf"),
        "{e}"
    );
    let e = rejection::<Viewer>(r#"{"At":[0,0,-1e39]}"#);
    assert!(
        e.contains("viewer.position.z must be finite, got -inf"),
        "{e}"
    );
    let e = rejection::<Viewer>(r#"{"Infinite":[0,1e39,1]}"#);
    assert!(
        e.contains("viewer.direction.y must be finite, got inf"),
        "{e}"
    );

    // The largest f32, subnormals and any length of direction are in the domain, kept as written.
    let v: Viewer = serde_json::from_str(r#"{"At":[3.4028235e38,-1e-40,0]}"#).unwrap();
    assert_eq!(v, Viewer::At(Vec3::new(f32::MAX, -1e-40, 0.0)));
    let v: Viewer = serde_json::from_str(r#"{"Infinite":[0,0,-7]}"#).unwrap();
    assert_eq!(
        v,
        Viewer::Infinite(Vec3::new(0.0, 0.0, -7.0)),
        "not normalised"
    );
    // A zero direction is the documented "no viewer direction", not an error.
    let v: Viewer = serde_json::from_str(r#"{"Infinite":[0,0,0]}"#).unwrap();
    assert_eq!(v, Viewer::Infinite(Vec3::ZERO));
}

fn terms_json(ambient: &str, diffuse: &str, specular: &str, emission: &str) -> String {
    format!(
        r#"{{"ambient":{ambient},"diffuse":{diffuse},"specular":{specular},"emission":{emission}}}"#
    )
}

/// Fuzz reproducer: `Terms` used to load with non-finite and negative channels, outside the range
/// `shade` produces (finite, `≥ 0`), which is the rule documented on the type.
#[test]
fn terms_outside_the_range_shade_produces_are_rejected() {
    let ok = "[0,0.5,1]";
    let e = rejection::<Terms>(&terms_json(ok, "[1,-1,0]", ok, ok));
    assert!(
        e.contains("terms.diffuse.y must be non-negative, got -1"),
        "{e}"
    );
    let e = rejection::<Terms>(&terms_json(ok, ok, ok, "[0,0,1e39]"));
    assert!(
        e.contains("terms.emission.z must be finite, got inf"),
        "{e}"
    );
    let e = rejection::<Terms>(&terms_json("[-1e39,0,0]", ok, ok, ok));
    assert!(
        e.contains("terms.ambient.x must be finite, got -inf"),
        "{e}"
    );
    let e = rejection::<Terms>(&terms_json(ok, ok, "[0,-1e-40,0]", ok));
    assert!(e.contains("terms.specular.y must be non-negative"), "{e}");

    // Zero (either sign), subnormal and the largest f32 are all in range.
    let t: Terms =
        serde_json::from_str(&terms_json("[0,-0,1e-40]", ok, "[3.4028235e38,2,3]", ok)).unwrap();
    assert_eq!(t.ambient, Vec3::new(0.0, 0.0, 1e-40));
    assert_eq!(t.specular.x, f32::MAX);
    assert!(
        t.ambient.y == 0.0 && t.ambient.y.is_sign_negative(),
        "-0 kept"
    );
}

/// The message of an unknown key names it: serde's "unknown field `key`".
fn assert_unknown_field<T: serde::de::DeserializeOwned + core::fmt::Debug>(json: &str, key: &str) {
    let e = rejection::<T>(json);
    assert!(
        e.contains(&format!("unknown field `{key}`")),
        "{} with `{key}`: {e}",
        core::any::type_name::<T>()
    );
}

const COLORS: &str = r#"{"ambient":[0,0,0],"diffuse":[1,1,1],"specular":[1,1,1]}"#;

/// Fuzz reproducer: a misspelt key used to be ignored, so `"shinyness": -5` loaded a material with
/// no complaint (and, had `shininess` a default, with that default).
#[test]
fn a_misspelt_material_key_is_rejected() {
    assert_unknown_field::<Material>(
        r#"{ "ambient": [0,0,0], "diffuse": [1,1,1], "specular": [1,1,1],
             "emission": [0,0,0], "shininess": 8, "shinyness": -5 }"#,
        "shinyness",
    );
}

#[test]
fn every_struct_like_type_rejects_an_unknown_field() {
    assert_unknown_field::<LightColors>(
        r#"{"ambient":[0,0,0],"diffuse":[1,1,1],"specular":[1,1,1],"emissive":[0,0,0]}"#,
        "emissive",
    );
    // Each struct variant of Attenuation.
    assert_unknown_field::<Attenuation>(
        r#"{"Polynomial":{"constant":1,"linear":0,"quadratic":0.1,"cubic":0}}"#,
        "cubic",
    );
    assert_unknown_field::<Attenuation>(
        r#"{"InverseSquare":{"power":10,"min_distance":0.01,"radius":5}}"#,
        "radius",
    );
    assert_unknown_field::<Attenuation>(r#"{"Unreal":{"radius":5,"raduis":6}}"#, "raduis");
    assert_unknown_field::<Attenuation>(
        r#"{"Frostbite":{"radius":5,"min_distance":0.01,"max_distance":9}}"#,
        "max_distance",
    );
    assert_unknown_field::<DirectionalLight>(
        &format!(r#"{{"direction":[0,1,0],"colors":{COLORS},"intensity":2}}"#),
        "intensity",
    );
    assert_unknown_field::<PointLight>(
        &format!(r#"{{"position":[0,1,0],"attenuation":"None","colors":{COLORS},"range":10}}"#),
        "range",
    );
    // A spot's cos(cutoff) is derived, never read: a file carrying one (perhaps disagreeing with
    // the cutoff) is rejected rather than silently recomputed.
    assert_unknown_field::<SpotLight>(
        &format!(
            r#"{{"position":[0,4,0],"axis":[0,-1,0],"cutoff":0.4,"cos_cutoff":0.5,"exponent":8,
                 "attenuation":"None","colors":{COLORS}}}"#
        ),
        "cos_cutoff",
    );
    // Inside the enum the inner type's own check runs.
    assert_unknown_field::<Light>(
        &format!(r#"{{"Directional":{{"direction":[0,1,0],"colors":{COLORS},"dir":[1,0,0]}}}}"#),
        "dir",
    );
    // Unknown keys in a nested LightColors are caught too.
    assert_unknown_field::<PointLight>(
        r#"{"position":[0,1,0],"attenuation":"None",
            "colors":{"ambient":[0,0,0],"diffuse":[1,1,1],"specular":[1,1,1],"diffuse_":[0,0,0]}}"#,
        "diffuse_",
    );
    assert_unknown_field::<Terms>(
        r#"{"ambient":[0,0,0],"diffuse":[0,0,0],"specular":[0,0,0],"emission":[0,0,0],"total":[0,0,0]}"#,
        "total",
    );
    assert_unknown_field::<phong::Lambert>(r#"{"normalization":"Energy","gate":"Step"}"#, "gate");
    assert_unknown_field::<Phong>(
        r#"{"gate":"Step","normalization":"None","pow":"Exact","shininess":32}"#,
        "shininess",
    );
    assert_unknown_field::<BlinnPhong>(
        r#"{"gate":"Step","normalisation":"None","pow":"Exact"}"#,
        "normalisation",
    );
    assert_unknown_field::<Model>(
        r#"{"BlinnPhong":{"gate":"Cosine","normalization":"None","pow":"Exact","exact":true}}"#,
        "exact",
    );
}

/// The enums without struct variants have no field to deny: a wrong variant name is an error naming
/// it, and so is a second key beside the variant's (serde_json expects the enum object to close).
#[test]
fn enums_reject_unknown_variants_and_extra_keys() {
    fn unknown_variant<T: serde::de::DeserializeOwned + core::fmt::Debug>(json: &str, name: &str) {
        let e = rejection::<T>(json);
        assert!(e.contains(&format!("unknown variant `{name}`")), "{e}");
    }
    unknown_variant::<SpecularGate>(r#""Smooth""#, "Smooth");
    unknown_variant::<Normalization>(r#""Energetic""#, "Energetic");
    unknown_variant::<PowStrategy>(r#""Fast""#, "Fast");
    unknown_variant::<Attenuation>(r#"{"Linear":{"k":1}}"#, "Linear");
    unknown_variant::<Model>(r#"{"CookTorrance":{}}"#, "CookTorrance");
    unknown_variant::<Light>(r#"{"Area":{}}"#, "Area");
    unknown_variant::<Viewer>(r#"{"Orthographic":[0,0,1]}"#, "Orthographic");

    rejection::<Viewer>(r#"{"At":[0,0,5],"Infinite":[0,0,1]}"#);
    rejection::<Model>(r#"{"Lambert":{"normalization":"None"},"pow":"Exact"}"#);
    rejection::<Light>(&format!(
        r#"{{"Directional":{{"direction":[0,1,0],"colors":{COLORS}}},"note":1}}"#
    ));
    // A unit variant carries nothing.
    rejection::<SpecularGate>(r#"{"Step":5}"#);
    rejection::<Attenuation>(r#"{"None":{"radius":5}}"#);
}

/// JSON numbers around the edges of `f32`, read into a `LightColors` channel: the ones that overflow
/// `f32` are read by serde_json as `±∞` (not a parse error), and validation names the field; the
/// ones that fit load as the nearest `f32`. Past `f64`'s range serde_json itself fails.
#[test]
fn numbers_that_overflow_f32_are_caught_by_validation_not_the_parser() {
    let load = |x: &str| {
        serde_json::from_str::<LightColors>(&format!(
            r#"{{"ambient":[0,0,0],"diffuse":[{x},0,0],"specular":[0,0,0]}}"#
        ))
        .map(|c| c.diffuse().x)
        .map_err(|e| e.to_string())
    };
    // The parser gives +∞ for an f32 overflow: the error comes from the check.
    assert_eq!(serde_json::from_str::<f32>("1e39").unwrap(), f32::INFINITY);
    for overflow in [
        "1e39",
        "3.4028236e38",
        "1e300",
        "340282356779733661637539395458142568448", // an integer past u64, read as a float
    ] {
        let e = load(overflow).expect_err(overflow);
        assert!(
            e.contains("light.diffuse.x must be finite, got inf"),
            "{overflow}: {e}"
        );
    }
    let e = load("-1e39").unwrap_err();
    assert!(
        e.contains("light.diffuse.x must be finite, got -inf"),
        "{e}"
    );
    let e = load("1e400").unwrap_err();
    assert!(e.contains("number out of range"), "past f64: {e}");

    for (fits, value) in [
        ("3.4028235e38", f32::MAX),
        ("340282346638528859811704183484516925440", f32::MAX),
        ("1e-40", 1e-40), // subnormal
        ("1.401298464324817e-45", f32::from_bits(1)),
        ("1e-50", 0.0), // underflows to zero: still in the domain
        ("0", 0.0),
        ("0.5", 0.5),
        ("12", 12.0),
    ] {
        assert_eq!(load(fits), Ok(value), "{fits}");
    }
    let negative_zero = load("-0").unwrap();
    assert!(negative_zero == 0.0 && negative_zero.is_sign_negative());
    let e = load("-1e-40").unwrap_err();
    assert!(e.contains("light.diffuse.x must be non-negative"), "{e}");
}

mod fuzz {
    //! Random files built from hard number classes: deserialising gives exactly what the checked
    //! constructor gives on the numbers serde_json reads (the value, or the error naming the
    //! field), and a value that loads passes that constructor again. Never an invalid value.

    use super::*;
    use core::f32::consts::{FRAC_PI_2, PI};
    use phong::{LightSource, PhongError};
    use proptest::prelude::*;
    use proptest::test_runner::TestCaseError;
    use serde::de::DeserializeOwned;

    /// A JSON number from one of the classes where validation matters.
    fn number() -> impl Strategy<Value = String> {
        let sign = |neg: bool| if neg { "-" } else { "" };
        let huge = prop_oneof![
            prop::sample::select(vec![
                "1e39",
                "-1e39",
                "3.4028236e38",
                // Just under the f32 rounding midpoint (a correctly rounded parse gives f32::MAX);
                // serde_json reads an f64 first, which lands on the midpoint and ties to +∞.
                "3.40282356779733661637539395458142568447e38",
                "340282356779733661637539395458142568448",
                "-99999999999999999999999999999999999999999",
                "1e308",
                "1e400", // past f64: serde_json's own error
                "-1e400",
            ])
            .prop_map(str::to_owned),
            ((f32::MAX as f64 * 1.000_001)..1e308, any::<bool>())
                .prop_map(move |(x, neg)| format!("{}{x:e}", sign(neg))),
        ];
        let negative = prop_oneof![
            (prop::num::f32::POSITIVE | prop::num::f32::NORMAL).prop_map(|x| format!("-{x:e}")),
            (prop::num::f32::POSITIVE | prop::num::f32::SUBNORMAL).prop_map(|x| format!("-{x:e}")),
            (0.0f32..4.0).prop_map(|x| format!("-{x}")),
        ];
        let zero = prop::sample::select(vec!["0", "0.0", "-0", "-0.0", "0e7", "1e-50", "-1e-50"])
            .prop_map(str::to_owned);
        let subnormal =
            (prop::num::f32::POSITIVE | prop::num::f32::SUBNORMAL).prop_map(|x| format!("{x:e}"));
        let normal = prop_oneof![
            (0.0f32..4.0).prop_map(|x| format!("{x}")),
            (prop::num::f32::POSITIVE | prop::num::f32::NORMAL).prop_map(|x| format!("{x:e}")),
            (prop::num::f32::POSITIVE | prop::num::f32::NORMAL).prop_map(|x| format!("{x}")),
        ];
        prop_oneof![
            1 => huge,
            1 => negative,
            2 => zero,
            2 => subnormal,
            16 => normal,
        ]
    }

    fn vec3() -> impl Strategy<Value = [String; 3]> {
        [number(), number(), number()]
    }

    /// A cone half-angle: mostly inside `[0, π/2]`, so that spot lights load often enough, and the
    /// edges `π/2` and `π` exactly.
    fn angle() -> impl Strategy<Value = String> {
        prop_oneof![
            (0.0f32..=FRAC_PI_2).prop_map(|x| format!("{x}")),
            number(),
            Just(format!("{FRAC_PI_2}")),
            Just(format!("{PI}")),
        ]
    }

    fn j(v: &[String; 3]) -> String {
        format!("[{},{},{}]", v[0], v[1], v[2])
    }

    /// The `f32` serde_json reads for one number, the same reading it makes inside a file; `None`
    /// where it cannot read one (past `f64`).
    fn num(s: &str) -> Option<f32> {
        serde_json::from_str(s).ok()
    }

    fn v3(v: &[String; 3]) -> Option<Vec3> {
        Some(Vec3::new(num(&v[0])?, num(&v[1])?, num(&v[2])?))
    }

    /// What a file must load as.
    #[derive(Debug)]
    enum Expected<T> {
        /// This value.
        Value(T),
        /// An error whose message contains this one's.
        Invalid(PhongError),
        /// Some error: a number serde_json cannot read.
        Unreadable,
    }

    impl<T> Expected<T> {
        /// From the checked constructor's answer; `None` when a number was unreadable.
        fn of(r: Option<Result<T, PhongError>>) -> Self {
            match r {
                None => Expected::Unreadable,
                Some(Ok(v)) => Expected::Value(v),
                Some(Err(e)) => Expected::Invalid(e),
            }
        }
        fn map<U>(self, f: impl FnOnce(T) -> U) -> Expected<U> {
            match self {
                Expected::Value(v) => Expected::Value(f(v)),
                Expected::Invalid(e) => Expected::Invalid(e),
                Expected::Unreadable => Expected::Unreadable,
            }
        }
    }

    /// Loads `json` and compares with `expected`; returns the value when one loaded.
    fn check<T>(json: &str, expected: Expected<T>) -> Result<Option<T>, TestCaseError>
    where
        T: DeserializeOwned + PartialEq + core::fmt::Debug,
    {
        match (serde_json::from_str::<T>(json), expected) {
            (Ok(got), Expected::Value(want)) => {
                prop_assert_eq!(&got, &want, "{}", json);
                Ok(Some(got))
            }
            (Err(e), Expected::Invalid(want)) => {
                let (e, want) = (e.to_string(), want.to_string());
                prop_assert!(e.contains(&want), "{json}: got `{e}`, want `{want}`");
                Ok(None)
            }
            (Err(_), Expected::Unreadable) => Ok(None),
            (got, want) => Err(TestCaseError::fail(format!(
                "{json}: got {got:?}, want {want:?}"
            ))),
        }
    }

    #[derive(Clone, Debug)]
    struct ColorsFile([[String; 3]; 3]);

    impl ColorsFile {
        fn json(&self) -> String {
            let [a, d, s] = &self.0;
            format!(
                r#"{{"ambient":{},"diffuse":{},"specular":{}}}"#,
                j(a),
                j(d),
                j(s)
            )
        }
        /// Checked as `LightColors::try_new`, as it is when read nested in a light.
        fn checked(&self) -> Option<Result<LightColors, PhongError>> {
            let [a, d, s] = &self.0;
            Some(LightColors::try_new(v3(a)?, v3(d)?, v3(s)?))
        }
    }

    fn colors_file() -> impl Strategy<Value = ColorsFile> {
        [vec3(), vec3(), vec3()].prop_map(ColorsFile)
    }

    /// One variant of `Attenuation` with up to three numbers.
    #[derive(Clone, Debug)]
    struct AttenuationFile(u8, [String; 3]);

    impl AttenuationFile {
        fn json(&self) -> String {
            let [a, b, c] = &self.1;
            match self.0 {
                0 => r#""None""#.to_owned(),
                1 => format!(r#"{{"Polynomial":{{"constant":{a},"linear":{b},"quadratic":{c}}}}}"#),
                2 => format!(r#"{{"InverseSquare":{{"power":{a},"min_distance":{b}}}}}"#),
                3 => format!(r#"{{"Unreal":{{"radius":{a}}}}}"#),
                _ => format!(r#"{{"Frostbite":{{"radius":{a},"min_distance":{b}}}}}"#),
            }
        }
        /// The variant as written, unchecked; `None` when a number it uses is unreadable.
        fn literal(&self) -> Option<Attenuation> {
            let [a, b, c] = &self.1;
            Some(match self.0 {
                0 => Attenuation::None,
                1 => Attenuation::Polynomial {
                    constant: num(a)?,
                    linear: num(b)?,
                    quadratic: num(c)?,
                },
                2 => Attenuation::InverseSquare {
                    power: num(a)?,
                    min_distance: num(b)?,
                },
                3 => Attenuation::Unreal { radius: num(a)? },
                _ => Attenuation::Frostbite {
                    radius: num(a)?,
                    min_distance: num(b)?,
                },
            })
        }
        fn checked(&self) -> Option<Result<Attenuation, PhongError>> {
            Some(self.literal()?.validated())
        }
    }

    fn attenuation_file() -> impl Strategy<Value = AttenuationFile> {
        (0u8..5, vec3()).prop_map(|(k, v)| AttenuationFile(k, v))
    }

    /// The nested values' own checks run first, as each is read (so a bad colour is reported
    /// before a bad position); then the light's `try_new`.
    fn nested_first<A, C>(
        a: Result<A, PhongError>,
        c: Result<C, PhongError>,
    ) -> Result<(A, C), PhongError> {
        Ok((a?, c?))
    }

    fn revalidate_colors(c: &LightColors) -> Result<(), TestCaseError> {
        prop_assert_eq!(
            LightColors::try_new(c.ambient(), c.diffuse(), c.specular()),
            Ok(*c)
        );
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn material_loads_only_what_try_new_accepts(
            ka in vec3(), kd in vec3(), ks in vec3(), ke in vec3(), s in number(),
        ) {
            let json = format!(
                r#"{{"ambient":{},"diffuse":{},"specular":{},"emission":{},"shininess":{s}}}"#,
                j(&ka), j(&kd), j(&ks), j(&ke)
            );
            let expected = Expected::of((|| {
                let (ka, kd, ks, ke, s) = (v3(&ka)?, v3(&kd)?, v3(&ks)?, v3(&ke)?, num(&s)?);
                Some(Material::try_new(ka, kd, ks, s).and_then(|m| m.try_with_emission(ke)))
            })());
            if let Some(m) = check::<Material>(&json, expected)? {
                let again = Material::try_new(m.ambient(), m.diffuse(), m.specular(), m.shininess())
                    .and_then(|x| x.try_with_emission(m.emission()));
                prop_assert_eq!(again, Ok(m));
            }
        }

        #[test]
        fn light_colors_load_only_what_try_new_accepts(c in colors_file()) {
            if let Some(got) = check::<LightColors>(&c.json(), Expected::of(c.checked()))? {
                revalidate_colors(&got)?;
            }
        }

        #[test]
        fn attenuation_loads_only_what_validated_accepts(a in attenuation_file()) {
            if let Some(got) = check::<Attenuation>(&a.json(), Expected::of(a.checked()))? {
                prop_assert_eq!(got.validated(), Ok(got));
                match got {
                    Attenuation::Polynomial { constant, linear, quadratic } => prop_assert_eq!(
                        Attenuation::try_polynomial(constant, linear, quadratic), Ok(got)
                    ),
                    Attenuation::Unreal { radius } => {
                        prop_assert_eq!(Attenuation::try_unreal(radius), Ok(got))
                    }
                    _ => {}
                }
            }
        }

        #[test]
        fn directional_light_loads_only_what_try_new_accepts(d in vec3(), c in colors_file()) {
            let json = format!(r#"{{"direction":{},"colors":{}}}"#, j(&d), c.json());
            let expected = || Expected::of((|| {
                let (d, c) = (v3(&d)?, c.checked()?);
                Some(c.and_then(|c| DirectionalLight::try_new(d, c)))
            })());
            if let Some(l) = check::<DirectionalLight>(&json, expected())? {
                prop_assert_eq!(DirectionalLight::try_new(l.direction(), *l.colors()), Ok(l));
                revalidate_colors(l.colors())?;
            }
            check::<Light>(&format!(r#"{{"Directional":{json}}}"#), expected().map(Light::from))?;
        }

        #[test]
        fn point_light_loads_only_what_try_new_accepts(
            p in vec3(), a in attenuation_file(), c in colors_file(),
        ) {
            let json = format!(
                r#"{{"position":{},"attenuation":{},"colors":{}}}"#,
                j(&p), a.json(), c.json()
            );
            let expected = || Expected::of((|| {
                let (p, a, c) = (v3(&p)?, a.checked()?, c.checked()?);
                Some(nested_first(a, c).and_then(|(a, c)| PointLight::try_new(p, a, c)))
            })());
            if let Some(l) = check::<PointLight>(&json, expected())? {
                prop_assert_eq!(
                    PointLight::try_new(l.position(), l.attenuation(), *l.colors()),
                    Ok(l)
                );
                prop_assert_eq!(l.attenuation().validated(), Ok(l.attenuation()));
                revalidate_colors(l.colors())?;
            }
            check::<Light>(&format!(r#"{{"Point":{json}}}"#), expected().map(Light::from))?;
        }

        #[test]
        fn spot_light_loads_only_what_try_new_accepts(
            p in vec3(), axis in vec3(), cutoff in angle(), e in number(),
            a in attenuation_file(), c in colors_file(),
        ) {
            let json = format!(
                r#"{{"position":{},"axis":{},"cutoff":{cutoff},"exponent":{e},"attenuation":{},"colors":{}}}"#,
                j(&p), j(&axis), a.json(), c.json()
            );
            let expected = || Expected::of((|| {
                let (p, axis, cutoff, e) = (v3(&p)?, v3(&axis)?, num(&cutoff)?, num(&e)?);
                let (a, c) = (a.checked()?, c.checked()?);
                Some(nested_first(a, c).and_then(|(a, c)| SpotLight::try_new(p, axis, cutoff, e, a, c)))
            })());
            if let Some(l) = check::<SpotLight>(&json, expected())? {
                let again = SpotLight::try_new(
                    l.position(), l.axis(), l.cutoff(), l.exponent(), l.attenuation(), *l.colors(),
                );
                prop_assert_eq!(again, Ok(l));
                prop_assert_eq!(l.attenuation().validated(), Ok(l.attenuation()));
                revalidate_colors(l.colors())?;
            }
            check::<Light>(&format!(r#"{{"Spot":{json}}}"#), expected().map(Light::from))?;
        }

        /// `Viewer` has no checked constructor; its documented domain is every coordinate finite.
        #[test]
        fn viewer_loads_only_finite_coordinates(v in vec3(), infinite in any::<bool>()) {
            let (tag, fields) = if infinite {
                ("Infinite", ["viewer.direction.x", "viewer.direction.y", "viewer.direction.z"])
            } else {
                ("At", ["viewer.position.x", "viewer.position.y", "viewer.position.z"])
            };
            let json = format!(r#"{{"{tag}":{}}}"#, j(&v));
            let expected = Expected::of(v3(&v).map(|x| {
                match x.to_array().into_iter().position(|c| !c.is_finite()) {
                    Some(i) => Err(PhongError::NonFinite { field: fields[i], value: x[i] }),
                    None => Ok(if infinite { Viewer::Infinite(x) } else { Viewer::At(x) }),
                }
            }));
            if let Some(got) = check::<Viewer>(&json, expected)? {
                let (Viewer::At(x) | Viewer::Infinite(x)) = got;
                prop_assert!(x.is_finite(), "{:?}", got);
            }
        }

        /// `Terms` has no checked constructor; its documented domain is every channel finite and
        /// `≥ 0`.
        #[test]
        fn terms_load_only_finite_non_negative_channels(t in [vec3(), vec3(), vec3(), vec3()]) {
            const NAMES: [[&str; 3]; 4] = [
                ["terms.ambient.x", "terms.ambient.y", "terms.ambient.z"],
                ["terms.diffuse.x", "terms.diffuse.y", "terms.diffuse.z"],
                ["terms.specular.x", "terms.specular.y", "terms.specular.z"],
                ["terms.emission.x", "terms.emission.y", "terms.emission.z"],
            ];
            let json = terms_json(&j(&t[0]), &j(&t[1]), &j(&t[2]), &j(&t[3]));
            let expected = Expected::of((|| {
                let v = [v3(&t[0])?, v3(&t[1])?, v3(&t[2])?, v3(&t[3])?];
                for (names, term) in NAMES.iter().zip(v) {
                    for (&field, value) in names.iter().zip(term.to_array()) {
                        if !value.is_finite() {
                            return Some(Err(PhongError::NonFinite { field, value }));
                        }
                        if value < 0.0 {
                            return Some(Err(PhongError::Negative { field, value }));
                        }
                    }
                }
                Some(Ok(Terms { ambient: v[0], diffuse: v[1], specular: v[2], emission: v[3] }))
            })());
            if let Some(got) = check::<Terms>(&json, expected)? {
                for term in [got.ambient, got.diffuse, got.specular, got.emission] {
                    prop_assert!(term.is_finite() && term.cmpge(Vec3::ZERO).all(), "{:?}", got);
                }
            }
        }
    }
}
