//! Helpers shared by the CLI's integration tests: a hand-written `.vox`
//! writer and the hostile inputs made with it, and running the binary
//! under limits.

#![allow(dead_code)] // each test binary uses a part

pub mod limits;
pub mod vox_bytes;
