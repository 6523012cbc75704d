//! Reflection models: the `ReflectionModel` trait and the run-time `Model`, the three models, the cosines they read (`Incidence`), the specular gate, lobe normalisation, `x^s` strategies, and a built-in model resolved once.

pub(crate) mod blinn_phong;
pub(crate) mod gate;
pub(crate) mod incidence;
pub(crate) mod lambert;
pub(crate) mod model;
pub(crate) mod normalization;
pub(crate) mod phong;
pub(crate) mod pow;
pub(crate) mod resolved_model;
