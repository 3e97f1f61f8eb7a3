//! Helpers shared by the CLI's integration tests: a hand-written `.vox`
//! writer and the hostile inputs made with it, running the binary (under
//! limits, or plainly) and each suite's scratch folder.

#![allow(dead_code)] // each test binary uses a part

pub mod limits;
pub mod run;
pub mod vox_bytes;
