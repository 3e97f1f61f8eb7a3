//! The CLI's build-and-render path as a library, so that every program that
//! reports figures for voxtrace (the `voxtrace-report` frontend) times exactly
//! the code the `voxtrace` binary runs, and writes its files the same way
//! (`atomic`); and the render farm's parts: tile arithmetic and task
//! indexes (`tiles`), the parts' metadata (`part`) and their assembly
//! (`stitch`, which names a mismatch of settings by its flag:
//! `settings_diff`); and `--denoise`'s albedo and normal images
//! (`guides`) and Open Image Denoise filter (`denoise`, with the
//! `denoise` feature).
//!
//! Errors are one-line messages meant for a user's terminal (`errors`:
//! clap's errors on one line, control characters escaped).

pub mod atomic;
#[cfg(feature = "denoise")]
pub mod denoise;
pub mod errors;
mod export;
mod frames;
pub mod guides;
pub mod image_error;
pub mod part;
mod pipeline;
pub mod room;
pub mod settings_diff;
pub mod stitch;
pub mod tiles;
mod units;

pub use export::{export_vox, terrain_box};
pub use frames::{frame_path, parse_frame, parse_frame_range, turntable, FrameArg, FrameRange};
pub use pipeline::{mean_radiance, on_threads, Backend, BuiltScene, Rendered, ROUND_STATE_BYTES};
pub use units::human_bytes;
/// The framing is the shared crate's (the web page frames the same way);
/// the CLI's tests check it through the CLI.
pub use voxtrace_flags::framing;
