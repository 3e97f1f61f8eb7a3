//! What a frame is: the third stage, from camera to packed pixels.
//!
//! A [`camera`] turns pixels into rays; [`options`] say which effects the
//! frame simulates; [`shader`] picks, once per frame, a pixel kernel compiled
//! for exactly those effects (over the shading math of [`shade`], the sample
//! patterns of [`sampling`] and the seed paper's [`debug_view`]); [`frame`]
//! is the one render path, which runs it over a region of the frame in
//! bands and [`tiles`], into a caller's `&mut [u32]` on this thread or
//! the atomic [`framebuffer`] on the rayon pool (feature `rayon`),
//! counting rays in [`stats`]. The flat and lit looks make their pixels
//! 8x4 at a time, their camera rays traced in packets (feature
//! `packets`).
//!
//! Scenes with metal, glass or emitters ([`plan`] decides, from the
//! materials the scene's voxels use) get the path tracer (`path`, feature
//! `path`) instead of face shading; its pixels may sample until their own
//! noise estimate is low enough ([`adaptive`]).
//!
//! A frame may also take its samples in [`rounds`] over the whole frame,
//! stopped between rounds by a caller's predicate (a time budget): the
//! frame after `n` rounds is the one-pass frame of options that say so,
//! and one pass is one round that takes every sample.
//!
//! No pixel depends on its band, tile, block or thread, so the render on
//! this thread, any crop, and the threaded render are byte-identical; the
//! framebuffer also has its own parallel pixel iterator ([`pixels`]) for
//! users' per-pixel work. The kernels allocate nothing.

pub(crate) mod adaptive;
pub(crate) mod camera;
pub(crate) mod debug_view;
pub(crate) mod fit;
pub(crate) mod frame;
#[cfg(feature = "std")]
pub(crate) mod framebuffer;
pub(crate) mod options;
#[cfg(feature = "path")]
pub(crate) mod path;
#[cfg(feature = "rayon")]
pub(crate) mod pixels;
pub(crate) mod plan;
pub(crate) mod rays;
pub(crate) mod rounds;
pub(crate) mod sampling;
pub(crate) mod shade;
pub(crate) mod shader;
pub(crate) mod stats;
pub(crate) mod tiles;
pub(crate) mod view;
