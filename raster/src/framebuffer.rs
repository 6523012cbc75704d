//! Where a rasterizer writes: a linear colour buffer, a depth buffer and a triangle-id buffer.

use glam::Vec3;

/// A render target of `width × height` pixels, row-major from the top-left.
///
/// Colours are linear RGB (as [`phong::shade`] returns them); encode them with
/// [`Image::from_linear`](crate::Image::from_linear) or [`Image::from_raw`](crate::Image::from_raw).
#[derive(Clone, Debug)]
pub struct Framebuffer {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Linear colour per pixel.
    pub color: Vec<Vec3>,
    /// Normalised depth per pixel (0 at the near plane, 1 at the far plane); `+∞` where empty.
    pub depth: Vec<f32>,
    /// `1 +` the index of the triangle that covers the pixel, 0 where empty.
    pub triangle: Vec<u32>,
}

impl Framebuffer {
    /// A cleared buffer: every pixel `background`, infinitely far, uncovered.
    #[must_use]
    pub fn new(width: usize, height: usize, background: Vec3) -> Self {
        let n = width * height;
        Framebuffer {
            width,
            height,
            color: vec![background; n],
            depth: vec![f32::INFINITY; n],
            triangle: vec![0; n],
        }
    }

    /// The index of pixel `(x, y)`.
    #[must_use]
    #[inline]
    pub fn index(&self, x: usize, y: usize) -> usize {
        y * self.width + x
    }

    /// The linear colour at `(x, y)`.
    #[must_use]
    pub fn at(&self, x: usize, y: usize) -> Vec3 {
        self.color[self.index(x, y)]
    }

    /// Whether a triangle covers `(x, y)`.
    #[must_use]
    pub fn covered(&self, x: usize, y: usize) -> bool {
        self.triangle[self.index(x, y)] != 0
    }

    /// The largest per-channel difference between two buffers of the same size, over the pixels
    /// both cover.
    #[must_use]
    pub fn max_difference(&self, other: &Framebuffer) -> f32 {
        self.color
            .iter()
            .zip(&other.color)
            .zip(self.triangle.iter().zip(&other.triangle))
            .filter(|(_, (a, b))| **a != 0 && **b != 0)
            .map(|((a, b), _)| (*a - *b).abs().max_element())
            .fold(0.0, f32::max)
    }

    /// `|self − other| · gain` per pixel, as a new buffer (uncovered pixels black).
    #[must_use]
    pub fn difference(&self, other: &Framebuffer, gain: f32) -> Framebuffer {
        let mut out = Framebuffer::new(self.width, self.height, Vec3::ZERO);
        for i in 0..self.color.len() {
            if self.triangle[i] != 0 && other.triangle[i] != 0 {
                out.color[i] = (self.color[i] - other.color[i]).abs() * gain;
                out.triangle[i] = self.triangle[i];
            }
        }
        out
    }
}
