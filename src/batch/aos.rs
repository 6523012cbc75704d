//! The array-of-structs layouts a batch reads: the element types of a G-buffer or a mesh.

use glam::{Vec3, Vec3A, Vec4};

use super::prepare::sealed::Sealed;

/// One point or direction as an array-of-structs G-buffer keeps it: [`Vec3`], [`Vec3A`],
/// `[f32; 3]`, and the four-wide [`Vec4`] and `[f32; 4]` (a position in `xyz` with `w` unused, or a
/// packed normal: the fourth component is ignored). Sealed: the batch reads exactly these.
///
/// [`shade_batch_aos`](crate::shade_batch_aos) and
/// [`shade_batch_aos_rgba8`](crate::shade_batch_aos_rgba8) take slices of any of them, so a
/// renderer's own arrays are read in place:
///
/// ```text
/// xyz(v) = (v.x, v.y, v.z)        [f32; 4] and Vec4: the first three components
/// ```
pub trait AosVec3: Sealed + Copy {
    /// The first three components: `[x, y, z]`.
    fn xyz(self) -> [f32; 3];
}

impl Sealed for Vec3 {}
impl Sealed for Vec3A {}
impl Sealed for Vec4 {}
impl Sealed for [f32; 3] {}
impl Sealed for [f32; 4] {}

impl AosVec3 for Vec3 {
    #[inline(always)]
    fn xyz(self) -> [f32; 3] {
        self.to_array()
    }
}

impl AosVec3 for Vec3A {
    #[inline(always)]
    fn xyz(self) -> [f32; 3] {
        self.to_array()
    }
}

impl AosVec3 for Vec4 {
    #[inline(always)]
    fn xyz(self) -> [f32; 3] {
        [self.x, self.y, self.z]
    }
}

impl AosVec3 for [f32; 3] {
    #[inline(always)]
    fn xyz(self) -> [f32; 3] {
        self
    }
}

impl AosVec3 for [f32; 4] {
    #[inline(always)]
    fn xyz(self) -> [f32; 3] {
        [self[0], self[1], self[2]]
    }
}
