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
