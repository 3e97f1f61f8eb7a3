//! `.vox` instance storms: files of a few kilobytes whose scene graph places
//! thousands to hundreds of thousands of single voxels, each in a chunk of
//! its own, all within the scene-graph limits; and 4,096 instances of a
//! model of 255 or 257 voxels, one per chunk, beyond the chunk limit. Each
//! renders a tiny frame or is refused, within 2 s of CPU time and 200 MB
//! resident (asserted for the optimized binary, `.ci/run`; the
//! unoptimized one of `cargo test` is an order of magnitude slower). CPU
//! time, not wall time: on a shared 2-core machine the wall clock measures
//! the neighbours (both are printed).
//!
//! Run optimized: `cargo test --release -p voxtrace-cli --test storms --
//! --include-ignored`.
//!
//! This binary holds this one test alone: the peak resident set it reads
//! (`common::usage`) is the largest of its own children only. Linux only.

// Linux: the resident set in kilobytes (see `common::usage`), and `timeout`.
#![cfg(target_os = "linux")]

mod common;

use std::process::Command;
use std::time::{Duration, Instant};

use common::run::{assert_refused, fresh_dir, stderr};
use common::usage::children_usage;
use common::vox_bytes::storm;

/// What a storm must come to: rendered, or refused naming this.
enum Outcome {
    Renders,
    Refused(&'static str),
}

#[test]
#[ignore = "builds of 131,044 instances, minutes unoptimized: .ci/run runs it optimized"]
fn instance_storms_render_or_are_refused_quickly_in_little_memory() {
    let dir = fresh_dir("storms", "inputs");
    let out = dir.join("out.png");
    let chunk_limit = "more than 131072 chunks of 8^3";
    // The refusals first: the peak so far is then theirs alone.
    let cases = [
        ("3x64", storm(3, 64, 100, 1), Outcome::Refused(chunk_limit)),
        (
            "2x64-of-255",
            storm(2, 64, 300, 255),
            Outcome::Refused(chunk_limit),
        ),
        (
            "2x64-of-257",
            storm(2, 64, 300, 257),
            Outcome::Refused(chunk_limit),
        ),
        // Overlapping instances of a model whose voxels each fill a chunk
        // of their own: few chunks, many placed voxels. 262,144 x 65 is
        // past the cap of 2^24 placed voxels; x 64 is the cap itself.
        (
            "3x64-of-65-overlapping",
            storm(3, 64, 0, 65),
            Outcome::Refused("more than 16777216 voxels"),
        ),
        ("2x64", storm(2, 64, 100, 1), Outcome::Renders),
        (
            "3x64-of-64-overlapping",
            storm(3, 64, 0, 64),
            Outcome::Renders,
        ),
        ("3x32", storm(3, 32, 100, 1), Outcome::Renders),
        // 131,044 instances: the most a storm of two levels places within
        // the chunk limit.
        ("2x362", storm(2, 362, 100, 1), Outcome::Renders),
    ];
    for (name, bytes, outcome) in cases {
        let path = dir.join(format!("storm-{name}.vox"));
        std::fs::write(&path, &bytes).unwrap();
        let _ = std::fs::remove_file(&out);
        let (_, cpu_before) = children_usage();
        let started = Instant::now();
        // Killed after a minute: a storm that hangs fails, not the suite.
        let result = Command::new("timeout")
            .args(["-s", "KILL", "60"])
            .arg(env!("CARGO_BIN_EXE_voxtrace"))
            .arg("--vox")
            .arg(&path)
            .args(["--width", "16", "--height", "9", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let elapsed = started.elapsed();
        let (rss, cpu_after) = children_usage();
        let cpu = cpu_after - cpu_before;
        println!(
            "storm {name} ({} bytes): exit {:?} in {elapsed:.2?} ({cpu:.2?} CPU), peak RSS so far {} KB",
            bytes.len(),
            result.status.code(),
            rss / 1024
        );
        match outcome {
            Outcome::Renders => {
                assert_eq!(result.status.code(), Some(0), "{name}: {}", stderr(&result));
                assert!(out.exists(), "{name}: no image");
            }
            Outcome::Refused(needle) => {
                assert_refused(&result, &[needle]);
                // Counted before the chunks were allocated.
                assert!(rss < 50 << 20, "{name}: peak resident set {rss} bytes");
            }
        }
        if !cfg!(debug_assertions) {
            assert!(
                cpu < Duration::from_secs(2),
                "{name}: took {cpu:.2?} of CPU"
            );
            assert!(rss < 200 << 20, "{name}: peak resident set {rss} bytes");
        }
    }
}
