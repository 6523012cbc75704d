//! 8-bit RGB images: encoding a framebuffer, labels, tiling, PNG output.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use glam::Vec3;

use crate::Framebuffer;
use crate::text::{glyph, text_width};

/// An 8-bit RGB image, row-major from the top-left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `width × height` pixels.
    pub pixels: Vec<[u8; 3]>,
}

impl Image {
    /// A `width × height` image filled with `colour`.
    #[must_use]
    pub fn new(width: usize, height: usize, colour: [u8; 3]) -> Self {
        Image {
            width,
            height,
            pixels: vec![colour; width * height],
        }
    }

    /// A framebuffer encoded for display: sRGB transfer function, then 8 bits
    /// ([`phong::linear_to_srgb8`]).
    #[must_use]
    pub fn from_linear(fb: &Framebuffer) -> Self {
        Self::map(fb, phong::linear_to_srgb8)
    }

    /// A framebuffer written without encoding: linear values straight to 8 bits (too dark on a
    /// display; shown for comparison).
    #[must_use]
    pub fn from_raw(fb: &Framebuffer) -> Self {
        Self::map(fb, |c| [c.x, c.y, c.z].map(phong::quantize_u8))
    }

    fn map(fb: &Framebuffer, f: impl Fn(Vec3) -> [u8; 3]) -> Self {
        Image {
            width: fb.width,
            height: fb.height,
            pixels: fb.color.iter().map(|c| f(*c)).collect(),
        }
    }

    /// Sets one pixel; outside the image nothing happens.
    pub fn put(&mut self, x: i64, y: i64, colour: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            let i = y as usize * self.width + x as usize;
            self.pixels[i] = colour;
        }
    }

    /// Copies `src` with its top-left corner at `(x, y)`, clipped to this image.
    pub fn blit(&mut self, src: &Image, x: usize, y: usize) {
        for sy in 0..src.height {
            for sx in 0..src.width {
                self.put(
                    (x + sx) as i64,
                    (y + sy) as i64,
                    src.pixels[sy * src.width + sx],
                );
            }
        }
    }

    /// Draws `text` with the built-in 3×5 font, each font pixel `scale × scale`.
    pub fn text(&mut self, x: usize, y: usize, text: &str, scale: usize, colour: [u8; 3]) {
        for (k, c) in text.chars().enumerate() {
            let rows = glyph(c);
            for (row, bits) in rows.iter().enumerate() {
                for col in 0..3 {
                    if bits & (4 >> col) != 0 {
                        for dy in 0..scale {
                            for dx in 0..scale {
                                self.put(
                                    (x + (k * 4 + col) * scale + dx) as i64,
                                    (y + row * scale + dy) as i64,
                                    colour,
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// This image with a caption strip above it (the strip widens the image if the text needs it).
    #[must_use]
    pub fn labelled(&self, caption: &str) -> Image {
        let scale = 2;
        let strip = 7 * scale;
        let width = self.width.max(text_width(caption, scale) + 2 * scale);
        let mut out = Image::new(width, self.height + strip, [24, 24, 24]);
        out.text(scale, scale, caption, scale, [230, 230, 230]);
        out.blit(self, 0, strip);
        out
    }

    /// Images side by side with a gap, top-aligned, on a dark background.
    #[must_use]
    pub fn row(images: &[Image], gap: usize) -> Image {
        let width =
            images.iter().map(|i| i.width).sum::<usize>() + gap * images.len().saturating_sub(1);
        let height = images.iter().map(|i| i.height).max().unwrap_or(0);
        let mut out = Image::new(width, height, [12, 12, 12]);
        let mut x = 0;
        for i in images {
            out.blit(i, x, 0);
            x += i.width + gap;
        }
        out
    }

    /// Images stacked top to bottom with a gap, left-aligned.
    #[must_use]
    pub fn column(images: &[Image], gap: usize) -> Image {
        let height =
            images.iter().map(|i| i.height).sum::<usize>() + gap * images.len().saturating_sub(1);
        let width = images.iter().map(|i| i.width).max().unwrap_or(0);
        let mut out = Image::new(width, height, [12, 12, 12]);
        let mut y = 0;
        for i in images {
            out.blit(i, 0, y);
            y += i.height + gap;
        }
        out
    }

    /// Writes the image as an 8-bit RGB PNG.
    pub fn save_png(&self, path: &Path) -> std::io::Result<()> {
        let file = BufWriter::new(File::create(path)?);
        let mut enc = png::Encoder::new(file, self.width as u32, self.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(std::io::Error::other)?;
        let data: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        w.write_image_data(&data).map_err(std::io::Error::other)?;
        Ok(())
    }
}
