//! Writing a part: the core's streamed PNG with the placement and settings
//! chunks, compressed once; its image data hashed as it goes out, and the
//! digest chunk put in before `IEND`.

use std::io::Write;

use png::text_metadata::{EncodableTextChunk, TEXtChunk};

use super::digest::DigestHasher;
use super::walk::Walker;
use super::{Placement, DIGEST_KEY, PART_KEY, SETTINGS_KEY};

/// The `IEND` chunk, which ends every PNG: no data, and its CRC.
const IEND: [u8; 12] = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xae, 0x42, 0x60, 0x82];

/// Encodes a part as an RGBA8 PNG with its three text chunks, through the
/// core's streaming encoder (the one every PNG goes through): a few rows
/// of memory, whatever the tile's size, and the tile compressed once.
///
/// # Errors
/// The encoder's message or the writer's, or a pixel count that is not
/// the rectangle's.
pub fn write_part<W: Write>(
    writer: W,
    placement: &Placement,
    settings: &str,
    pixels: &[u32],
) -> Result<(), String> {
    let (width, height) = (placement.rect.width, placement.rect.height);
    if pixels.len() as u64 != u64::from(width) * u64::from(height) {
        return Err(format!(
            "{} pixels for a {width}x{height} tile",
            pixels.len()
        ));
    }
    let mut file = BeforeIend {
        inner: writer,
        walker: Walker::new(false),
        held: Vec::with_capacity(IEND.len()),
    };
    let placed = placement.to_text();
    let text = [(PART_KEY, placed.as_str()), (SETTINGS_KEY, settings)];
    voxtrace::encode_png_with_text(&mut file, width, height, pixels, &text)
        .map_err(|e| e.to_string())?;
    let mut digest = DigestHasher::new(placement, settings);
    digest.packed_pixels(pixels);
    let digest = digest.finish(&file.walker.image_data());
    file.finish(&digest.to_text())
}

/// A PNG on its way to `inner`, all but its last 12 bytes (its `IEND`,
/// held back so that a chunk can go before it) walked to hash its image
/// data.
struct BeforeIend<W> {
    /// Where the file goes.
    inner: W,
    /// The walk over the bytes passed on.
    walker: Walker,
    /// The last bytes written (at most 12), not passed on yet.
    held: Vec<u8>,
}

impl<W: Write> BeforeIend<W> {
    /// After the encoder: writes the digest chunk with `digest`, then
    /// `IEND`.
    ///
    /// # Errors
    /// The writer's message, or a PNG that did not end with `IEND`.
    fn finish(mut self, digest: &str) -> Result<(), String> {
        if self.held != IEND {
            return Err("the PNG encoder did not end the file with IEND".into());
        }
        TEXtChunk::new(DIGEST_KEY, digest)
            .encode(&mut self.inner)
            .map_err(|e| e.to_string())?;
        self.inner
            .write_all(&IEND)
            .and_then(|()| self.inner.flush())
            .map_err(|e| e.to_string())
    }
}

impl<W: Write> Write for BeforeIend<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        // On go the bytes that are not among the last 12 written: first
        // the held ones, then the start of `buf`; its end is held.
        let out = (self.held.len() + buf.len()).saturating_sub(IEND.len());
        let from_held = out.min(self.held.len());
        let (passed, kept) = buf.split_at(out - from_held);
        for bytes in [&self.held[..from_held], passed] {
            self.inner.write_all(bytes)?;
            self.walker.walk(bytes);
        }
        self.held.drain(..from_held);
        self.held.extend_from_slice(kept);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use sha2::{Digest, Sha256};

    use super::{BeforeIend, EncodableTextChunk, TEXtChunk, Walker, IEND};
    use crate::part::DIGEST_KEY;

    #[test]
    fn a_png_written_in_pieces_of_any_size_gets_its_chunk_before_iend() {
        let mut plain = Vec::new();
        let pixels: Vec<u32> = (0..40 * 30)
            .map(|i: u32| i.wrapping_mul(0x9e37_79b9))
            .collect();
        voxtrace::encode_png(&mut plain, 40, 30, &pixels).unwrap();
        let (body, iend) = plain.split_at(plain.len() - 12);
        assert_eq!(iend, IEND);
        // The image data: its IDAT chunks' (the stream's end in one of
        // its own).
        let (mut stored, mut at) = (Sha256::new(), 8);
        while at < body.len() {
            let len = u32::from_be_bytes(body[at..at + 4].try_into().unwrap()) as usize;
            if &body[at + 4..at + 8] == b"IDAT" {
                stored.update(&body[at + 8..at + 8 + len]);
            }
            at += 12 + len;
        }
        let image_data: [u8; 32] = stored.finalize().into();
        let mut chunk = Vec::new();
        TEXtChunk::new(DIGEST_KEY, "text")
            .encode(&mut chunk)
            .unwrap();
        let expected = [body, &chunk, &IEND].concat();
        for piece in [1, 2, 5, 11, 12, 13, 100, plain.len()] {
            let mut out = Vec::new();
            let mut file = BeforeIend {
                inner: &mut out,
                walker: Walker::new(false),
                held: Vec::new(),
            };
            for bytes in plain.chunks(piece) {
                file.write_all(bytes).unwrap();
            }
            assert_eq!(file.walker.image_data(), image_data, "{piece}");
            file.finish("text").unwrap();
            assert_eq!(out, expected, "{piece}");
        }
    }
}
