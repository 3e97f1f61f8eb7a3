//! The digest of a part (its `voxtrace-digest` chunk): its definition, its
//! text, and the hasher that takes it as the pixels go by.

use sha2::{Digest, Sha256};

use super::Placement;

/// The digest of a part, in its `voxtrace-digest` chunk: SHA-256 of, in
/// this order,
///
/// 1. the 18 bytes `voxtrace-digest 1` and a NUL (the version of this
///    definition);
/// 2. the placement, each number as 4 big-endian bytes: the frame's width
///    and height, the grid's columns and rows, the tile, its rectangle's
///    x, y, width and height, and the frame number; then the settings hash
///    as 8 big-endian bytes;
/// 3. the settings text's length in bytes (8, big-endian) and its bytes;
/// 4. the pixels, row by row, each as its R, G, B and A bytes (the decoded
///    image's bytes);
/// 5. the SHA-256 (32 bytes) of the image data as stored: the data of the
///    `IDAT` chunks, one after another.
///
/// So every bit of the stored stream counts, and no part's pixels pass for
/// another tile's, frame's or render's (docs/farm.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartDigest(pub [u8; 32]);

impl PartDigest {
    /// The digest as the `voxtrace-digest` chunk writes it: `sha256:` and
    /// 64 lowercase hex digits.
    #[must_use]
    pub fn to_text(&self) -> String {
        let hex: String = self.0.iter().map(|b| format!("{b:02x}")).collect();
        format!("sha256:{hex}")
    }

    /// Reads a digest written by [`PartDigest::to_text`], exactly: hex
    /// digits in lowercase only, so that no change to the text reads as
    /// the same digest.
    ///
    /// # Errors
    /// A message quoting what is not `sha256:<64 lowercase hex digits>`.
    pub fn parse(text: &str) -> Result<PartDigest, String> {
        let bad = || {
            // A forged chunk may be long: quote a line's worth of it.
            let shown: String = text.chars().take(80).collect();
            format!("{shown:?} is not sha256:<64 lowercase hex digits>")
        };
        let hex = text.strip_prefix("sha256:").ok_or_else(bad)?;
        let digit = |b: u8| b.is_ascii_digit() || (b'a'..=b'f').contains(&b);
        if hex.len() != 64 || !hex.bytes().all(digit) {
            return Err(bad());
        }
        let mut bytes = [0u8; 32];
        for (byte, pair) in bytes.iter_mut().zip(hex.as_bytes().chunks_exact(2)) {
            let pair = std::str::from_utf8(pair).map_err(|_| bad())?;
            *byte = u8::from_str_radix(pair, 16).map_err(|_| bad())?;
        }
        Ok(PartDigest(bytes))
    }
}

/// A [`PartDigest`] taken as the pixels go by.
pub(super) struct DigestHasher(Sha256);

impl DigestHasher {
    /// The digest of a part placed by `placement` with `settings`: items 1
    /// to 3 of the definition, before the first pixel.
    pub(super) fn new(placement: &Placement, settings: &str) -> DigestHasher {
        let mut sha = Sha256::new();
        sha.update(b"voxtrace-digest 1\0");
        let r = placement.rect;
        for number in [
            placement.frame_width,
            placement.frame_height,
            placement.grid.columns(),
            placement.grid.rows(),
            placement.tile,
            r.x,
            r.y,
            r.width,
            r.height,
            placement.frame_number,
        ] {
            sha.update(number.to_be_bytes());
        }
        sha.update(placement.hash.to_be_bytes());
        sha.update((settings.len() as u64).to_be_bytes());
        sha.update(settings.as_bytes());
        DigestHasher(sha)
    }

    /// Adds pixels as R, G, B, A bytes.
    pub(super) fn pixels(&mut self, rgba: &[u8]) {
        self.0.update(rgba);
    }

    /// Adds packed pixels (R in the first byte), through a buffer on the
    /// stack: whole blocks into the hash, and no copy of the tile.
    pub(super) fn packed_pixels(&mut self, pixels: &[u32]) {
        let mut batch = [0u8; 4096];
        for chunk in pixels.chunks(batch.len() / 4) {
            for (bytes, pixel) in batch.chunks_exact_mut(4).zip(chunk) {
                bytes.copy_from_slice(&pixel.to_ne_bytes());
            }
            self.pixels(&batch[..chunk.len() * 4]);
        }
    }

    /// The digest, with `image_data` the SHA-256 of the stored image data
    /// (item 5).
    pub(super) fn finish(mut self, image_data: &[u8; 32]) -> PartDigest {
        self.0.update(image_data);
        PartDigest(self.0.finalize().into())
    }
}
