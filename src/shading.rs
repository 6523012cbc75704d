//! Shading one point: the scene and viewer, the prepared `Shader`, per-light visibility, and the `Terms` it returns.

pub(crate) mod lobe_pow;
pub(crate) mod shade;
pub(crate) mod shader;
pub(crate) mod terms;
pub(crate) mod visibility;
