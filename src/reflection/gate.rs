//! What happens to the specular term when the light is below the surface.

/// How the specular lobe is gated by the light's side of the surface (`N·L`).
///
/// ```text
/// Step:   specular × [N·L > 0]            (OpenGL fixed function, Wikipedia's Blinn-Phong shader)
/// Cosine: specular × max(N·L, 0)          (three.js; also what a BRDF × cos θ gives)
/// None:   specular                        (LearnOpenGL's basic-lighting shader)
/// ```
///
/// Without a gate a light behind the surface can still produce a highlight (the "back-face
/// specular halo"): with `L` and `V` both below the surface, `R·V` can reach 1. Keep
/// [`None`](Self::None) only to reproduce code that has no gate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SpecularGate {
    /// Specular is zero unless `N·L > 0`. The default.
    #[default]
    Step,
    /// Specular is scaled by `max(N·L, 0)`: it fades in at the terminator instead of switching on.
    Cosine,
    /// No gate: reproduces LearnOpenGL's lighting shaders, halo included.
    None,
}

impl SpecularGate {
    /// The gate's weight for a given `N·L`: `[N·L > 0]`, `max(N·L, 0)`, or 1.
    ///
    /// ```
    /// use phong::SpecularGate;
    /// assert_eq!(SpecularGate::Step.weight(-0.1), 0.0);
    /// assert_eq!(SpecularGate::Cosine.weight(0.5), 0.5);
    /// assert_eq!(SpecularGate::None.weight(-1.0), 1.0);
    /// ```
    #[must_use]
    #[inline]
    pub fn weight(self, n_dot_l: f32) -> f32 {
        match self {
            SpecularGate::Step => {
                if n_dot_l > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
            SpecularGate::Cosine => crate::math::max_or(n_dot_l, 0.0),
            SpecularGate::None => 1.0,
        }
    }
}
