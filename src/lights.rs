//! Lights: directional, point and spot lights with their colours, and the attenuation forms.

pub(crate) mod attenuation;
pub(crate) mod light;
