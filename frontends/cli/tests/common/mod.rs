//! Helpers shared by the CLI's integration tests: a hand-written `.vox`
//! writer and the hostile inputs made with it, render-farm parts, running
//! the binary (under limits, or plainly), what its children used, each suite's scratch
//! folder, the assertion that a run is a refusal, and pseudo-terminals.

#![allow(dead_code)] // each test binary uses a part

pub mod limits;
pub mod parts;
pub mod run;
#[cfg(unix)]
pub mod terminal;
#[cfg(target_os = "linux")]
pub mod usage;
pub mod vox_bytes;
