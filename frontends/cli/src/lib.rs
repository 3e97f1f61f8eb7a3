//! The CLI's build-and-render path as a library, so that every program that
//! reports figures for voxtrace (the `voxtrace-report` frontend) times exactly
//! the code the `voxtrace` binary runs; and the render farm's parts: tile
//! arithmetic and task indexes (`tiles`), the parts' metadata (`part`) and
//! their assembly (`stitch`).
//!
//! Errors are one-line messages meant for a user's terminal.

pub mod part;
mod pipeline;
pub mod stitch;
pub mod tiles;

pub use pipeline::{framing, on_threads, Backend, BuiltScene, Rendered};
