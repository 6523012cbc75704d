//! Deserialisation that validates, for the `serde` feature.
//!
//! The parameter types with invariants (colours `≥ 0`, shininess `≥ 0`, unit directions, …) derive
//! serde's code with `remote = "Self"`, which generates it as inherent functions instead of trait
//! impls. The trait impls here call those and then run the same checked constructor a user would,
//! so a scene file with a bad value fails with the [`PhongError`](crate::PhongError) message naming
//! the field, e.g. `material.shininess must be non-negative, got -2`.

use crate::{Attenuation, DirectionalLight, LightColors, Material, PointLight, SpotLight};

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
validated_serde!(SpotLight, |l| SpotLight::try_new(
    l.position(),
    l.axis(),
    l.cutoff(),
    l.exponent(),
    l.attenuation(),
    *crate::LightSource::colors(&l)
));
