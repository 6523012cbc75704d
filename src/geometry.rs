//! Geometry: unit vectors over the whole finite range, reflection and halfway vectors, face-forwarding, triangle and vertex normals, normal matrices, and the exact sums they rest on.

pub(crate) mod expansion;
pub(crate) mod face_forward;
pub(crate) mod halfway;
pub(crate) mod normal_matrix;
pub(crate) mod normalize;
pub(crate) mod reflect;
pub(crate) mod triangle;
pub(crate) mod vertex_normals;
