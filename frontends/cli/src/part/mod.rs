//! A part of a frame rendered on its own (a tile of a render farm): the
//! core's streamed RGBA8 PNG with three `tEXt` chunks, in this order,
//!
//! ```text
//! IHDR, voxtrace-part, voxtrace-settings, IDAT..., voxtrace-digest, IEND
//! ```
//!
//! the [`Placement`], the settings text its hash is taken of
//! ([`settings_text`]) and the [`PartDigest`] of its pixels, image data and
//! chunks, so that `voxtrace stitch` refuses parts that do not fit
//! together or are not the bytes their task wrote. docs/farm.md defines
//! the format and what each check catches. The files: `placement`,
//! `digest`, `write` ([`write_part`]), `read` ([`read_part`], the checks in
//! their order) and `walk` (the chunks followed as the bytes go by).

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
