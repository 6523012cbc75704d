//! Colour encoding: sRGB and gamma, and the exact 8-bit sRGB level of a linear value.

pub(crate) mod color;
pub(crate) mod srgb8;
