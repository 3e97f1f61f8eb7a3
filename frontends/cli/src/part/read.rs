//! Reading a part strictly: the PNG decoder, every check it has on, takes
//! the file's bytes through a [`Walker`], which hashes the image data as
//! stored and inflates it again to the zlib stream's end. The file is read
//! once, straight through (a pipe works), and the tile is not copied.

use std::io::{BufRead, Read, Seek, SeekFrom};

use voxtrace::Rect;

use super::digest::DigestHasher;
use super::walk::{Head, Walker};
use super::{fnv1a64, Part, PartDigest, Placement, DIGEST_KEY, PART_KEY, SETTINGS_KEY};
use crate::units::human_bytes;

/// Decodes a part written by [`write_part`](super::write_part), checking
/// that it is the file that was written. In this order: the PNG's
/// structure and every chunk's CRC (ancillary chunks too, as the decoder
/// reaches them), the placement and settings chunks, the image's format
/// and size, its pixels as they decode, then that the zlib stream of the
/// image data ends exactly at the end of the last `IDAT`, with the right
/// Adler-32 and the image's size, that nothing follows `IEND`, that the
/// one digest chunk is the last chunk before `IEND`, and last the digest.
///
/// # Errors
/// One line naming the first check that fails, in that order; a part
/// without a digest (an older voxtrace's) says to render it again.
pub fn read_part<R: BufRead>(reader: R) -> Result<Part, String> {
    let mut options = png::DecodeOptions::default();
    // Every check the decoder has, on. Chunk CRCs are checked by default,
    // but an ancillary chunk whose CRC fails is skipped (a damaged
    // voxtrace-part chunk would read as "not a voxtrace tile"); the zlib
    // stream's Adler-32 is skipped by default, and read only if the
    // decoder reaches the stream's end while it decodes rows, which the
    // core's encoder (a last IDAT of its own for the end) never lets it:
    // the walk reads the stream to its end.
    options.set_ignore_checksums(false);
    options.set_skip_ancillary_crc_failures(false);
    let mut walked = Walked {
        inner: reader,
        walker: Walker::new(true),
    };
    let mut png = png::Decoder::new_with_options(&mut walked, options)
        .read_info()
        .map_err(|e| format!("not a PNG, or a damaged one: {e}"))?;
    let (placement, settings) = placement_and_settings(png.info())?;
    let area = tile_area(png.info(), placement.rect)?;
    // Row by row into the pixels, reserved fallibly: no copy of the tile.
    let mut pixels: Vec<u32> = Vec::new();
    pixels.try_reserve_exact(area).map_err(|_| {
        format!(
            "out of memory: cannot decode a {}x{} tile ({})",
            placement.rect.width,
            placement.rect.height,
            human_bytes(area as u128 * 4)
        )
    })?;
    let mut hasher = DigestHasher::new(&placement, &settings);
    let corrupt = |e: png::DecodingError| format!("corrupt image data: {e}");
    while let Some(row) = png.next_row().map_err(corrupt)? {
        let row = row.data();
        hasher.pixels(row);
        let row = row.chunks_exact(4);
        pixels.extend(row.map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])));
    }
    if pixels.len() != area {
        return Err("corrupt image data: fewer pixels than the image's size".into());
    }
    // Up to IEND, the chunks after the image data (the digest) read: a
    // file cut short after its pixels is still a broken copy.
    png.finish()
        .map_err(|e| format!("corrupt after the image data: {e}"))?;
    let digest = text(png.info(), DIGEST_KEY)?;
    drop(png);
    let (image_data, before_iend) = walked.finish()?;
    let digest = digest.ok_or_else(|| {
        format!(
            "no {DIGEST_KEY} chunk: a part of an older voxtrace, whose pixels cannot be checked; render it again with this one"
        )
    })?;
    // Where voxtrace writes it, and nowhere else: a part whose chunks were
    // moved (or one of an older layout) is not the file its task wrote.
    let keyword = [DIGEST_KEY.as_bytes(), b"\0"].concat();
    if &before_iend.kind != b"tEXt" || !before_iend.bytes().starts_with(&keyword) {
        return Err(format!(
            "its {DIGEST_KEY} chunk is not the last chunk before IEND, where voxtrace writes it (moved, or an older voxtrace's part): render it again"
        ));
    }
    let digest = PartDigest::parse(&digest).map_err(|e| format!("bad {DIGEST_KEY} chunk: {e}"))?;
    if hasher.finish(&image_data) != digest {
        return Err(format!(
            "its pixels or image data are not the ones its {DIGEST_KEY} chunk was taken of (damaged, altered, or another part's pixels): render it again"
        ));
    }
    Ok(Part {
        placement,
        settings,
        pixels,
    })
}

/// The placement and settings text of a part, from the text chunks before
/// its image data, each given once, the placement exactly as voxtrace
/// writes it and the settings text of its hash.
///
/// # Errors
/// A chunk missing, given twice or not as written, or a settings text of
/// another hash.
fn placement_and_settings(info: &png::Info) -> Result<(Placement, String), String> {
    let placed = text(info, PART_KEY)?
        .ok_or_else(|| format!("not a voxtrace tile (no {PART_KEY} text chunk)"))?;
    let placement = Placement::parse(&placed).map_err(|e| format!("bad {PART_KEY} chunk: {e}"))?;
    // Exactly as written: the digest covers what the text says, and a
    // text read leniently (a space turned into U+00A0, a hex digit's case
    // changed) would say the same.
    if placement.to_text() != placed {
        return Err(format!(
            "bad {PART_KEY} chunk: not in the form voxtrace writes (damaged or edited)"
        ));
    }
    let settings =
        text(info, SETTINGS_KEY)?.ok_or_else(|| format!("no {SETTINGS_KEY} text chunk"))?;
    if fnv1a64(settings.as_bytes()) != placement.hash {
        return Err(format!(
            "its {SETTINGS_KEY} chunk does not hash to its hash"
        ));
    }
    Ok((placement, settings))
}

/// The pixel count of a part's image, checked to be 8-bit RGBA, not
/// interlaced, and of the size of its tile, `rect`.
///
/// # Errors
/// An image of another format or size, or too large to address.
fn tile_area(info: &png::Info, rect: Rect) -> Result<usize, String> {
    let (width, height) = (info.width, info.height);
    let rgba8 = info.color_type == png::ColorType::Rgba && info.bit_depth == png::BitDepth::Eight;
    if !rgba8 || info.interlaced {
        return Err(format!(
            "{:?} {:?}-bit pixels{}, not the 8-bit RGBA voxtrace writes",
            info.color_type,
            info.bit_depth as u8,
            if info.interlaced { ", interlaced" } else { "" }
        ));
    }
    if (width, height) != (rect.width, rect.height) {
        return Err(format!(
            "the image is {width}x{height} but its tile is {}x{}",
            rect.width, rect.height
        ));
    }
    (width as usize)
        .checked_mul(height as usize)
        .ok_or_else(|| {
            format!(
                "cannot decode a {width}x{height} tile: more pixels than this machine addresses"
            )
        })
}

/// The text of the `tEXt` chunk `key` read so far, if there is one.
///
/// # Errors
/// Two chunks of that keyword.
fn text(info: &png::Info, key: &str) -> Result<Option<String>, String> {
    let mut found = info
        .uncompressed_latin1_text
        .iter()
        .filter(|chunk| chunk.keyword == key);
    match (found.next(), found.next()) {
        (Some(chunk), None) => Ok(Some(chunk.text.clone())),
        (None, _) => Ok(None),
        (Some(_), Some(_)) => Err(format!("two {key} text chunks")),
    }
}

/// A part's bytes on their way to the PNG decoder, walked a second time
/// as the decoder takes them.
struct Walked<R> {
    /// The part's bytes.
    inner: R,
    /// The walk over the bytes the decoder took.
    walker: Walker,
}

impl<R: BufRead> Walked<R> {
    /// After the decoder's `finish`: checks the walk (see
    /// [`Walker::finish`]) and that nothing follows `IEND`, and returns
    /// the SHA-256 of the stored image data and the head of the chunk
    /// before `IEND`.
    ///
    /// # Errors
    /// The first problem found.
    fn finish(&mut self) -> Result<([u8; 32], Head), String> {
        let walked = self.walker.finish()?;
        match self.inner.fill_buf() {
            Ok([]) => Ok(walked),
            Ok(_) => Err("data after IEND, the end of the image".into()),
            Err(e) => Err(format!("cannot read: {e}")),
        }
    }
}

impl<R: BufRead> Read for Walked<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.walker.walk(&buf[..n]);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for Walked<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        // The bytes consumed are the start of the buffer the decoder was
        // given, still there: a buffer that holds bytes is returned again
        // without a read.
        match self.inner.fill_buf() {
            Ok(buffer) if buffer.len() >= amount => self.walker.walk(&buffer[..amount]),
            _ => self
                .walker
                .found("cannot read the part again as it is decoded".into()),
        }
        self.inner.consume(amount);
    }
}

impl<R> Seek for Walked<R> {
    fn seek(&mut self, _: SeekFrom) -> std::io::Result<u64> {
        // The decoder reads straight through (it needs `Seek` but does not
        // seek); a seek would put the walk out of step, so it is refused.
        Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "a part is read straight through",
        ))
    }
}
