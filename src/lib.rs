//! # voxtrace
//!
//! A lightweight CPU voxel ray tracer with swappable storage: a dense flat
//! array walked by Amanatides & Woo's traversal ([`DenseScene`]) and a sparse,
//! pointer-free octree ([`OctreeScene`]). Both implement [`Scene`] and return
//! the same hit for every ray, bit for bit, because they share one cell walk
//! with one tie rule (x before y before z) and the octree only jumps over
//! boxes it knows are empty.
//!
//! What a frame simulates is [`RenderOptions`]: the terrain's look by
//! default (face shading under a sun, one primary ray per pixel), with
//! shadows, ambient occlusion, anti-aliasing, fog and the seed paper's debug
//! view each opt-in; the renderer picks the look's pixel kernel once per
//! frame, and [`RayStats`] counts rays by kind. Scenes with metal, glass or emitters
//! are path-traced (feature `path`).
//!
//! The core is `#![no_std]` and allocation-explicit: storages build into
//! caller buffers (`build_in`, sized by `required_len`), or under the `alloc`
//! feature into vectors reserved with `try_reserve` (`build`); the tracer
//! allocates nothing.
//!
//! ```
//! use voxtrace::{render, Camera, CameraSettings, IAabb, OctreeScene, Rect, RenderOptions, Target};
//! use voxtrace::VoxelGenerator;
//!
//! let terrain = VoxelGenerator::new(42);
//! let scene = OctreeScene::build(&terrain, IAabb::centered(32))?;
//! let camera = Camera::new(CameraSettings {
//!     width: 64,
//!     height: 36,
//!     lookfrom: glam::Vec3::splat(22.0),
//!     ..CameraSettings::default()
//! })?;
//! let mut pixels = vec![0u32; 64 * 36];
//! let (frame, options) = (Rect::full(&camera), RenderOptions::default());
//! let stats = render(&scene, &camera, &options, frame, Target::Buffer(&mut pixels), None)?;
//! assert_eq!(stats.primary_rays, 64 * 36);
//! # Ok::<(), voxtrace::Error>(())
//! ```
//!
//! ## Features
//! - `alloc`: storage constructors that allocate (fallibly).
//! - `std` (default): the atomic [`Framebuffer`]; implies `alloc`.
//! - `rayon` (default): the framebuffer's parallel pixel iterator and
//!   zeroing ([`Framebuffer::new_parallel`]), the threaded render
//!   ([`Target::Framebuffer`], byte-identical to the render on this
//!   thread) and parallel storage builds; implies `std`.
//! - `png` (default): PNG encoding and decoding of frames, and the
//!   [`Golden`] helper for golden-image tests; implies `std`.
//! - `vox`: MagicaVoxel `.vox` scenes as a [`VoxelSource`] (`VoxModel`),
//!   parsed by dot_vox, placed through the scene graph; implies `std`.
//! - `image`: conversions between frames and the image crate's `RgbaImage`
//!   (`From<&Framebuffer>`, `TryFrom<&RgbaImage>`, `to_rgba_image`); the
//!   image crate comes with no codecs (choose them in your own dependency).
//! - `path` (default): the path tracer, the look ([`Look::Path`]) of scenes
//!   with metal, glass or emitters and of [`Lighting::path_trace`]. Without
//!   it those frames get the face-shaded look, every material shaded as
//!   diffuse, and the [`EffectPlan`]'s description says so. Its frames
//!   may take their samples in rounds a caller stops between
//!   ([`render_in_rounds`], [`Rounds`]; a time budget).
//! - `packets` (default): camera rays, and the lit look's shadow and
//!   occlusion rays, traced 32 at a time (the same pixels, faster).
//!
//! Firmware that must be small leaves them off (`default-features =
//! false`), as the repository's `frontends/embedded` does: the path
//! tracer and the packet walks are most of a render's code.

#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![deny(missing_docs, unsafe_code)]
#![warn(clippy::std_instead_of_core, clippy::alloc_instead_of_core)]

#[cfg(feature = "alloc")]
extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

// The pipeline, in the order data flows through it: the shared vocabulary
// at the root, then sources -> storages -> rendering -> output. Later stages
// import earlier ones, never the reverse (see ARCHITECTURE.md).
mod error;
#[cfg(feature = "alloc")]
mod fallible;
mod frustum;
mod geom;
mod material;
mod math;
mod scene;
mod voxel;
mod with_materials;

#[cfg(feature = "std")]
mod io;
mod render;
mod source;
mod storage;

pub use error::Error;
pub use frustum::Frustum;
pub use geom::{Face, IAabb, Ray, MAX_COORD};
pub use material::{Material, MaterialKind, MaterialKinds, Materials, SceneMaterials};
pub use render::adaptive::Adaptive;
pub use render::camera::{Camera, CameraSettings, DEFAULT_FOV};
pub use render::fit::Framer;
pub use render::frame::{render, render_in_rounds, RowsDone, Target};
pub use render::options::{
    Background, Bounces, Fog, Lighting, Occlusion, RenderOptions, DEFAULT_SUN,
};
pub use render::plan::{EffectPlan, Look};
pub use render::rounds::{PixelSamples, Rounds, RoundsDone, UNIFORM_ROUND};
pub use render::shade::{pack, shade, sky, unpack, FLAT_SKY, SKY_HORIZON, SKY_ZENITH};
#[doc(hidden)]
pub use render::shader::occlusion_rays;
pub use render::stats::{RayStats, Rect};
pub use render::view::{Orbit, Projection, ViewPreset};
pub use scene::{Hit, Reach, Scene, Traced, Visit, WalkMemory, PACKET};
pub use source::noise::{Perlin, SplitMix64};
pub use source::terrain::{VoxelGenerator, GRASS, HEIGHT, MOUNTAIN, ROUGHNESS, SCALE, SNOW, WATER};
#[cfg(feature = "vox")]
pub use source::vox::{
    rcam::{VoxCamera, VoxCameraMode},
    robj::{VoxSettings, VoxSun},
    scene_graph::VoxError,
    VoxModel,
};
pub use storage::dense::DenseScene;
pub use storage::estimate::{dense_bytes, octree_bytes};
pub use storage::octree::{Node, OctreeLen, OctreeScene};
pub use storage::walk::max_steps;
pub use voxel::{FnSource, Palette, Region, Voxel, VoxelSource};
pub use with_materials::WithMaterials;

/// Re-export of the image crate, whose `RgbaImage` frames convert to and
/// from.
#[cfg(feature = "image")]
pub use image;
#[cfg(feature = "png")]
pub use io::golden::{Golden, GoldenError, UPDATE_GOLDEN};
#[cfg(feature = "image")]
pub use io::image::{from_rgba_image, to_rgba_image};
#[cfg(feature = "png")]
pub use io::png::{decode_png, encode_png, encode_png_with_text, read_png, write_png};
#[cfg(feature = "std")]
pub use render::framebuffer::Framebuffer;
#[cfg(feature = "rayon")]
pub use render::pixels::{ParPixels, PixelRef, Pixels};

/// Re-export of rayon, whose pools run the parallel render and builds.
#[cfg(feature = "rayon")]
pub use rayon;

/// Re-export of the math types in voxtrace's API.
pub use glam;

/// The README's Rust example, compiled by `cargo test --doc` so that it
/// keeps up with the API.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
