//! The structure-of-arrays views a batch reads and writes.

/// Three parallel slices of coordinates: point `i` is `(x[i], y[i], z[i])`.
///
/// Used for positions (any finite coordinates) and normals (any finite vector; normalised per
/// point, a zero normal meaning "no diffuse or specular").
///
/// **Lengths:** a batch's nine slices (positions, normals and the [`SoaRgb`] output) must all have
/// the same length; debug builds assert it (the assertion panics). Release builds do not check:
/// they shade the shortest common prefix of the nine and leave the rest of the output untouched.
#[derive(Clone, Copy, Debug)]
pub struct SoaVec3<'a> {
    /// The `x` coordinates.
    pub x: &'a [f32],
    /// The `y` coordinates.
    pub y: &'a [f32],
    /// The `z` coordinates.
    pub z: &'a [f32],
}

impl<'a> SoaVec3<'a> {
    /// The three slices as a view.
    #[must_use]
    pub fn new(x: &'a [f32], y: &'a [f32], z: &'a [f32]) -> Self {
        SoaVec3 { x, y, z }
    }

    /// Points `range` of the view (within every slice's length).
    pub(crate) fn range(&self, range: core::ops::Range<usize>) -> Self {
        SoaVec3::new(
            &self.x[range.clone()],
            &self.y[range.clone()],
            &self.z[range],
        )
    }

    /// The length of the shortest slice.
    #[must_use]
    pub fn len(&self) -> usize {
        self.x.len().min(self.y.len()).min(self.z.len())
    }

    /// Whether the shortest slice is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Three parallel output slices of linear RGB: point `i`'s colour goes to `(r[i], g[i], b[i])`.
///
/// Each channel written is the [`Terms::total`](crate::Terms::total) of the point: finite, `≥ 0`,
/// saturated at `f32::MAX`. Elements past the shaded prefix are left untouched.
#[derive(Debug)]
pub struct SoaRgb<'a> {
    /// The red channel.
    pub r: &'a mut [f32],
    /// The green channel.
    pub g: &'a mut [f32],
    /// The blue channel.
    pub b: &'a mut [f32],
}

impl<'a> SoaRgb<'a> {
    /// The three slices as an output view.
    #[must_use]
    pub fn new(r: &'a mut [f32], g: &'a mut [f32], b: &'a mut [f32]) -> Self {
        SoaRgb { r, g, b }
    }

    /// The length of the shortest slice.
    #[must_use]
    pub fn len(&self) -> usize {
        self.r.len().min(self.g.len()).min(self.b.len())
    }

    /// Whether the shortest slice is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Three output views, one per term of the shading equation: point `i`'s
/// [`Terms`](crate::Terms)`::ambient` goes to `ambient` at `i`, and so on.
///
/// Each value written is the scalar path's term (saturated at `f32::MAX`, finite, `≥ 0`). The
/// material's emission is the same at every point and is not written: a point's
/// [`total`](crate::Terms::total) is `min(ambient + emission + diffuse + specular, f32::MAX)`.
/// Elements past the shaded prefix are left untouched.
#[derive(Debug)]
pub struct SoaTerms<'a> {
    /// `Ka ⊙ (Ia + Σ f·La)`.
    pub ambient: SoaRgb<'a>,
    /// `Kd ⊙ Σ f·vis·Ld·diffuse(N·L)`.
    pub diffuse: SoaRgb<'a>,
    /// `Ks ⊙ Σ f·vis·Ls·specular(N, L, V, s)`.
    pub specular: SoaRgb<'a>,
}

impl<'a> SoaTerms<'a> {
    /// The three views as one output.
    #[must_use]
    pub fn new(ambient: SoaRgb<'a>, diffuse: SoaRgb<'a>, specular: SoaRgb<'a>) -> Self {
        SoaTerms {
            ambient,
            diffuse,
            specular,
        }
    }

    /// The length of the shortest of the nine slices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.ambient
            .len()
            .min(self.diffuse.len())
            .min(self.specular.len())
    }

    /// Whether the shortest slice is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
