//! Colour encoding: sRGB and gamma, the exact 8-bit sRGB level of a linear value, and the linear value of an 8-bit level.

pub(crate) mod color;
pub(crate) mod srgb8;
pub(crate) mod srgb8_to_linear;
