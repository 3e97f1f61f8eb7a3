//! Conversions to and from the image crate (feature `image`), so that users
//! of that ecosystem take frames straight into `RgbaImage` and back (for
//! goldens stored in other formats).

use std::vec::Vec;

use image::RgbaImage;

use crate::error::Error;
use crate::render::framebuffer::Framebuffer;

/// `width x height` packed pixels (see [`crate::pack`]) as an `RgbaImage`;
/// `None` when `pixels` is shorter than the image. Allocates the image.
#[must_use]
pub fn to_rgba_image(width: u32, height: u32, pixels: &[u32]) -> Option<RgbaImage> {
    let pixels = pixels.get(..width as usize * height as usize)?;
    let bytes: Vec<u8> = pixels.iter().flat_map(|p| p.to_ne_bytes()).collect();
    RgbaImage::from_raw(width, height, bytes)
}

/// The packed pixels of an `RgbaImage`, row-major: the layout of a render.
#[must_use]
pub fn from_rgba_image(image: &RgbaImage) -> Vec<u32> {
    image
        .as_raw()
        .chunks_exact(4)
        .map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

impl From<&Framebuffer> for RgbaImage {
    fn from(frame: &Framebuffer) -> RgbaImage {
        let (width, height) = (frame.width(), frame.height());
        // A framebuffer's pixel count is exactly width * height.
        to_rgba_image(width, height, &frame.to_vec())
            .unwrap_or_else(|| RgbaImage::new(width, height))
    }
}

impl TryFrom<&RgbaImage> for Framebuffer {
    type Error = Error;

    /// A framebuffer holding the image's pixels; fails for an empty image
    /// or one too large for memory.
    fn try_from(image: &RgbaImage) -> Result<Framebuffer, Error> {
        let frame = Framebuffer::new(image.width(), image.height())?;
        for (slot, pixel) in frame.pixels().iter().zip(from_rgba_image(image)) {
            slot.store(pixel, core::sync::atomic::Ordering::Relaxed);
        }
        Ok(frame)
    }
}
