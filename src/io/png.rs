//! PNG encoding and decoding of packed pixels (feature `png`).

use core::sync::atomic::Ordering;
use std::io::Write;
use std::vec::Vec;

use crate::render::framebuffer::Framebuffer;

/// Encodes `width x height` packed RGBA8 pixels (see [`crate::pack`]) as a
/// PNG into `writer`. Fails if `pixels` is shorter than the image. Makes no
/// copy of the image: its memory is a few rows, whatever the size.
pub fn encode_png<W: Write>(
    writer: W,
    width: u32,
    height: u32,
    pixels: &[u32],
) -> Result<(), png::EncodingError> {
    encode_png_with_text(writer, width, height, pixels, &[])
}

/// [`encode_png`], with a `tEXt` chunk for each `(keyword, text)` of `text`
/// after the header, in order: the same image bytes, streamed the same
/// way. Fails if `pixels` is shorter than the image, or if a keyword is
/// not 1 to 79 Latin-1 characters or a text is not Latin-1 (what `tEXt`
/// holds).
pub fn encode_png_with_text<W: Write>(
    writer: W,
    width: u32,
    height: u32,
    pixels: &[u32],
    text: &[(&str, &str)],
) -> Result<(), png::EncodingError> {
    let len = width as usize * height as usize;
    let pixels = pixels.get(..len).ok_or_else(|| {
        png::EncodingError::IoError(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            std::format!("{len} pixels needed, {} given", pixels.len()),
        ))
    })?;
    encode_rgba8(writer, width, height, pixels.iter().copied(), text)
}

/// Bytes of the PNG chunks the encoder writes the image data in (and
/// buffers before writing each): large enough that the chunks' 12 bytes of
/// framing cost nothing.
const CHUNK: usize = 1 << 18;

/// The one PNG encoder: RGBA, 8 bits per channel, the `width * height`
/// packed pixels from `pixels`. The image data is filtered and compressed
/// as it streams through, a few rows at a time: the encoder never holds
/// the image, or its compressed bytes, whole. `text` becomes `tEXt`
/// chunks after the header.
pub(crate) fn encode_rgba8<W: Write>(
    writer: W,
    width: u32,
    height: u32,
    pixels: impl Iterator<Item = u32>,
    text: &[(&str, &str)],
) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(writer, width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    for (keyword, text) in text {
        encoder.add_text_chunk((*keyword).into(), (*text).into())?;
    }
    let mut writer = encoder.write_header()?;
    let mut stream = writer.stream_writer_with_size(CHUNK)?;
    // The pixels' bytes in batches on the stack: no allocation per image.
    let mut batch = [0u8; 4096];
    let mut filled = 0;
    for pixel in pixels {
        batch[filled..filled + 4].copy_from_slice(&pixel.to_ne_bytes());
        filled += 4;
        if filled == batch.len() {
            stream.write_all(&batch)?;
            filled = 0;
        }
    }
    stream.write_all(&batch[..filled])?;
    stream.finish()
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

/// Decodes a PNG into `(width, height, pixels)` with pixels packed as
/// [`crate::pack`] does. Any color type and bit depth is accepted:
/// grayscale, palette and RGB become opaque RGBA, 16-bit channels keep
/// their high byte.
pub fn decode_png<R: std::io::BufRead + std::io::Seek>(
    reader: R,
) -> Result<(u32, u32, Vec<u32>), png::DecodingError> {
    let mut decoder = png::Decoder::new(reader);
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info()?;
    let size = reader
        .output_buffer_size()
        .ok_or(png::DecodingError::LimitsExceeded)?;
    let mut buf = std::vec![0; size];
    let info = reader.next_frame(&mut buf)?;
    let bytes = &buf[..info.buffer_size()];
    let pixel = |c: &[u8]| match info.color_type {
        png::ColorType::Rgba => u32::from_ne_bytes([c[0], c[1], c[2], c[3]]),
        png::ColorType::Rgb => u32::from_ne_bytes([c[0], c[1], c[2], 255]),
        png::ColorType::GrayscaleAlpha => u32::from_ne_bytes([c[0], c[0], c[0], c[1]]),
        // Grayscale (palettes are expanded to RGB or RGBA by the decoder).
        _ => u32::from_ne_bytes([c[0], c[0], c[0], 255]),
    };
    let channels = info.color_type.samples();
    let pixels = bytes.chunks_exact(channels).map(pixel).collect();
    Ok((info.width, info.height, pixels))
}

/// Reads the PNG file at `path` (see [`decode_png`]).
pub fn read_png(path: &std::path::Path) -> Result<(u32, u32, Vec<u32>), png::DecodingError> {
    let file = std::fs::File::open(path)?;
    decode_png(std::io::BufReader::new(file))
}

impl Framebuffer {
    /// Encodes the image as a PNG into `writer` (feature `png`).
    pub fn encode_png<W: Write>(&self, writer: W) -> Result<(), png::EncodingError> {
        let pixels = self.pixels().iter().map(|p| p.load(Ordering::Relaxed));
        encode_rgba8(writer, self.width(), self.height(), pixels, &[])
    }
}
