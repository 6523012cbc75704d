//! Deserialisation that validates, for the `serde` feature.
//!
//! The parameter types with invariants (colours `≥ 0`, shininess `≥ 0`, unit directions, …) derive
//! serde's code with `remote = "Self"`, which generates it as inherent functions instead of trait
//! impls. The trait impls here call those and then run the same checked constructor a user would,
//! so a scene file with a bad value fails with the [`PhongError`](crate::PhongError) message naming
//! the field, e.g. `material.shininess must be non-negative, got -2`.
//!
//! The check runs on the parsed `f32`s, not on the text: serde_json reads a number too large for an
//! `f32` (`1e39`) as `±∞` rather than failing, so it is this check that rejects it, with the field
//! named (`light.diffuse.x must be finite, got inf`).
//!
//! Every struct-like type (and every struct variant) also denies unknown fields, so a misspelt key
//! (`"shinyness"`) is an error naming it instead of a silently defaulted value. What each
//! `Deserialize` type checks:
//!
//! | type | checked on load |
//! |---|---|
//! | `Material` | `Material::try_new` + `try_with_emission` |
//! | `LightColors` | `LightColors::try_new` |
//! | `Attenuation` | `Attenuation::validated` (the `try_*` rules, per variant) |
//! | `DirectionalLight`, `PointLight`, `SpotLight` | their `try_new` (a spot's `cos_cutoff` is not read: recomputed) |
//! | `Light` | nothing more: each newtype variant is one of the three lights above, checked by its own impl |
//! | `Viewer` | every coordinate finite (its documented domain; a zero `Infinite` direction is a valid "no viewer direction") |
//! | `Terms` | every channel finite and `≥ 0` (its documented domain, the range `shade` produces) |
//! | `Lambert`, `Phong`, `BlinnPhong` | nothing more: their fields are the enums below, every variant valid |
//! | `Model` | nothing more: each newtype variant is a model above |
//! | `SpecularGate`, `Normalization`, `PowStrategy` | nothing: unit variants only, every one valid; an unknown name is serde's error |
//!
//! `Light`, `Model` and `Viewer` have only newtype variants, so there is no field to deny; an unknown
//! variant name, or a second key beside the variant's, is already an error from serde.

use glam::Vec3;

use crate::error::{self, PhongError};
use crate::{
    Attenuation, DirectionalLight, LightColors, Material, PointLight, SpotLight, Terms, Viewer,
};

macro_rules! validated_serde {
    ($ty:ty, |$v:ident| $check:expr) => {
        impl serde::Serialize for $ty {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                <$ty>::serialize(self, s)
            }
        }
        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let $v = <$ty>::deserialize(d)?;
                $check.map_err(serde::de::Error::custom)
            }
        }
    };
}

validated_serde!(Attenuation, |a| a.validated());
validated_serde!(LightColors, |c| LightColors::try_new(
    c.ambient(),
    c.diffuse(),
    c.specular()
));
validated_serde!(Material, |m| Material::try_new(
    m.ambient(),
    m.diffuse(),
    m.specular(),
    m.shininess()
)
.and_then(|v| v.try_with_emission(m.emission())));
validated_serde!(DirectionalLight, |l| DirectionalLight::try_new(
    l.direction(),
    *crate::LightSource::colors(&l)
));
validated_serde!(PointLight, |l| PointLight::try_new(
    l.position(),
    l.attenuation(),
    *crate::LightSource::colors(&l)
));
/// A spot light's stored form: its fields flat, as a scene file writes them (the struct keeps a
/// `PointLight` inside, which a derive would nest; serde's `flatten` cannot deny unknown fields).
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SpotLightFields {
    position: Vec3,
    axis: Vec3,
    cutoff: f32,
    exponent: f32,
    attenuation: Attenuation,
    colors: LightColors,
}

impl serde::Serialize for SpotLight {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        SpotLightFields {
            position: self.position(),
            axis: self.axis(),
            cutoff: self.cutoff(),
            exponent: self.exponent(),
            attenuation: self.attenuation(),
            colors: *crate::LightSource::colors(self),
        }
        .serialize(s)
    }
}

impl<'de> serde::Deserialize<'de> for SpotLight {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let f = SpotLightFields::deserialize(d)?;
        SpotLight::try_new(
            f.position,
            f.axis,
            f.cutoff,
            f.exponent,
            f.attenuation,
            f.colors,
        )
        .map_err(serde::de::Error::custom)
    }
}
validated_serde!(Viewer, |v| viewer(v));
validated_serde!(Terms, |t| terms(t));

/// Checks that every coordinate of `value` is finite; `fields` names x, y, z.
fn finite3(fields: [&'static str; 3], value: Vec3) -> Result<Vec3, PhongError> {
    for (field, value) in fields.into_iter().zip(value.to_array()) {
        if !value.is_finite() {
            return Err(PhongError::NonFinite { field, value });
        }
    }
    Ok(value)
}

/// A viewer's domain: every coordinate finite. The direction of `Infinite` is kept as read (it is
/// normalised on use, and a zero one means "no viewer direction").
fn viewer(v: Viewer) -> Result<Viewer, PhongError> {
    match v {
        Viewer::At(eye) => finite3(
            [
                "viewer.position.x",
                "viewer.position.y",
                "viewer.position.z",
            ],
            eye,
        )
        .map(Viewer::At),
        Viewer::Infinite(d) => finite3(
            [
                "viewer.direction.x",
                "viewer.direction.y",
                "viewer.direction.z",
            ],
            d,
        )
        .map(Viewer::Infinite),
    }
}

/// The terms' domain: every channel finite and `≥ 0`, as `shade` produces them.
fn terms(t: Terms) -> Result<Terms, PhongError> {
    Ok(Terms {
        ambient: error::colour(
            ["terms.ambient.x", "terms.ambient.y", "terms.ambient.z"],
            t.ambient,
        )?,
        diffuse: error::colour(
            ["terms.diffuse.x", "terms.diffuse.y", "terms.diffuse.z"],
            t.diffuse,
        )?,
        specular: error::colour(
            ["terms.specular.x", "terms.specular.y", "terms.specular.z"],
            t.specular,
        )?,
        emission: error::colour(
            ["terms.emission.x", "terms.emission.y", "terms.emission.z"],
            t.emission,
        )?,
    })
}
