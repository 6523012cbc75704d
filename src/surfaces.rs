//! What a surface reflects: the validated `Material` and the per-point `Surface`.

pub(crate) mod material;
pub(crate) mod surface;
