//! What leaves the process: the last stage (feature `std`).
//!
//! PNG encoding and decoding of packed frames ([`png`], feature `png`), the
//! golden-image helper built on it ([`golden`], feature `png`), and
//! conversions to the image crate's `RgbaImage` ([`image`], feature
//! `image`). Nothing in the `no_std` core depends on this folder: it only
//! reads frames the renderers have finished.

#[cfg(feature = "png")]
pub(crate) mod golden;
#[cfg(feature = "image")]
pub(crate) mod image;
#[cfg(feature = "png")]
pub(crate) mod png;
