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
