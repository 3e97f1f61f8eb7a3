//! A part of a frame rendered on its own (a tile of a render farm): the PNG
//! carries, in `tEXt` chunks, where it belongs, what it is a part of and a
//! digest of its pixels, so that `voxtrace stitch` can refuse parts that do
//! not fit together, and parts that are not the bytes the render wrote.
//!
//! A part is the core's streamed RGBA8 PNG (the one every PNG goes
//! through) with three `tEXt` chunks, in this order:
//!
//! ```text
//! IHDR, voxtrace-part, voxtrace-settings, IDAT..., voxtrace-digest, IEND
//! ```
//!
//! `voxtrace-part` is the [`Placement`], `voxtrace-settings` the text its
//! settings hash is taken of ([`settings_text`]), so that a mismatch can be
//! explained, and `voxtrace-digest` the [`PartDigest`], last because it
//! covers the image data before it: a tile is compressed once, hashed as
//! it goes out. The settings hash is 64-bit FNV-1a: not cryptographic, it
//! tells honest mistakes apart (tiles of another seed, camera or version).
//! The digest is SHA-256 of the decoded pixels, of the image data as
//! stored and of everything the other two chunks say: no damage to the
//! file, whatever bit it hits, and no other part's pixels under this
//! part's chunks, go unnoticed. It has no secret in it, so it is no
//! signature: whoever rewrites a part on purpose can write its digest too.
//!
//! The files: `placement` (the placement text and the settings hash),
//! `digest` (the digest's definition), `write` ([`write_part`]), `read`
//! ([`read_part`], the checks in their order) and `walk` (the chunks
//! followed as the bytes go by: the image data's hash, its zlib stream
//! inflated to its end).

mod digest;
mod placement;
mod read;
mod walk;
mod write;

pub use digest::PartDigest;
pub use placement::{fnv1a64, settings_text, Placement};
pub use read::read_part;
pub use write::write_part;

/// The keyword of the placement chunk.
pub const PART_KEY: &str = "voxtrace-part";
/// The keyword of the settings chunk.
pub const SETTINGS_KEY: &str = "voxtrace-settings";
/// The keyword of the digest chunk.
pub const DIGEST_KEY: &str = "voxtrace-digest";

/// A decoded part: its placement, settings text and pixels (packed as
/// `voxtrace::pack` does, `rect.width * rect.height` of them).
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// Where it belongs.
    pub placement: Placement,
    /// The text its hash was taken of.
    pub settings: String,
    /// Its pixels.
    pub pixels: Vec<u32>,
}
