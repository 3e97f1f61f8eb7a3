//! What a frame is: the third stage, from camera to packed pixels.
//!
//! A [`camera`] turns pixels into rays; [`options`] say which effects the
//! frame simulates; [`shader`] picks, once per frame, a pixel kernel compiled
//! for exactly those effects (over the shading math of [`shade`], the sample
//! patterns of [`sampling`] and the seed paper's [`debug_view`]); the
//! [`scalar`] renderer runs it over rows, crops or whole frames into a
//! caller's `&mut [u32]`, counting rays in [`stats`]. The flat and lit
//! looks make their pixels 8x4 at a time, their rays traced in packets
//! (`packets`, feature `packets`).
//!
//! Scenes with metal, glass or emitters ([`plan`] decides, from the
//! materials the scene's voxels use) get the path tracer (`path`, feature
//! `path`) instead of face shading; its pixels may sample until their own
//! noise estimate is low enough ([`adaptive`]).
//!
//! A frame may also take its samples in [`rounds`] over the whole frame,
//! stopped between rounds by a caller's predicate (a time budget): the
//! frame after `n` rounds is the one-pass frame of options that say so.
//!
//! One function, `render_pixel`, defines every pixel, so the scalar render,
//! any crop, and the threaded render over the atomic [`framebuffer`]
//! (feature `std`) with its parallel pixel iterator ([`parallel`], feature
//! `rayon`) are byte-identical. The kernels allocate nothing.

pub(crate) mod adaptive;
pub(crate) mod camera;
pub(crate) mod debug_view;
pub(crate) mod fit;
#[cfg(feature = "std")]
pub(crate) mod framebuffer;
pub(crate) mod options;
#[cfg(feature = "packets")]
pub(crate) mod packets;
#[cfg(feature = "rayon")]
pub(crate) mod parallel;
#[cfg(feature = "path")]
pub(crate) mod path;
pub(crate) mod plan;
pub(crate) mod rays;
pub(crate) mod rounds;
pub(crate) mod sampling;
pub(crate) mod scalar;
pub(crate) mod shade;
pub(crate) mod shader;
pub(crate) mod stats;
pub(crate) mod tiles;
pub(crate) mod view;
