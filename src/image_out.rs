//! PNG encoding of rendered pixels (feature `png`).

use std::io::Write;
use std::vec::Vec;

/// Encodes `width x height` packed RGBA8 pixels (see [`crate::pack`]) as a
/// PNG into `writer`. Fails if `pixels` is shorter than the image.
pub fn encode_png<W: Write>(
    writer: W,
    width: u32,
    height: u32,
    pixels: &[u32],
) -> Result<(), png::EncodingError> {
    let len = width as usize * height as usize;
    let pixels = pixels.get(..len).ok_or_else(|| {
        png::EncodingError::IoError(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            std::format!("{len} pixels needed, {} given", pixels.len()),
        ))
    })?;
    let bytes: Vec<u8> = pixels.iter().flat_map(|p| p.to_ne_bytes()).collect();
    encode_rgba8(writer, width, height, &bytes)
}

/// The one PNG encoder: RGBA, 8 bits per channel, `width * height * 4`
/// bytes in `bytes`.
pub(crate) fn encode_rgba8<W: Write>(
    writer: W,
    width: u32,
    height: u32,
    bytes: &[u8],
) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(writer, width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(bytes)?;
    writer.finish()
}

/// Writes `pixels` as a PNG file at `path`.
pub fn write_png(
    path: &std::path::Path,
    width: u32,
    height: u32,
    pixels: &[u32],
) -> Result<(), png::EncodingError> {
    let file = std::fs::File::create(path)?;
    encode_png(std::io::BufWriter::new(file), width, height, pixels)
}
