//! The CLI's build-and-render path as a library, so that every program that
//! reports figures for voxtrace (the `voxtrace-report` frontend) times exactly
//! the code the `voxtrace` binary runs, and writes its files the same way.
//!
//! Errors are one-line messages meant for a user's terminal.

pub mod atomic;
mod pipeline;

pub use pipeline::{framing, on_threads, Backend, BuiltScene, Rendered};
