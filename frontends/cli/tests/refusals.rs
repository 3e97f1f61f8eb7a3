//! What is refused is refused before it costs memory: the 1 KB scene-graph
//! bombs (10 levels of 10 children, 30 levels of 2) and the absurd sizes
//! `--size 100000` and `--size 4194304` exit 2 naming the limit or the
//! estimated bytes, with a small resident set.
//!
//! This binary holds this one test alone: the peak resident set it reads
//! (`common::usage`) is the largest of its own children only. Linux only.
//! The resident set is asserted (under 100 MB); times are printed, not
//! asserted, as this machine is shared (each takes a few milliseconds
//! optimized; `storms.rs` bounds CPU time, which a neighbour cannot
//! inflate).

// Linux: the resident set in kilobytes (see `common::usage`).
#![cfg(target_os = "linux")]

mod common;

use std::process::Command;
use std::time::Instant;

use common::run::{assert_refused, fresh_dir};
use common::usage::children_usage;
use common::vox_bytes::bomb;

#[test]
fn bombs_and_absurd_sizes_exit_2_quickly_in_little_memory() {
    let dir = fresh_dir("refusals", "inputs");
    let out = dir.join("out.png");
    let mut cases: Vec<(String, Vec<String>, &str)> = Vec::new();
    for (name, bytes) in [("10x10", bomb(10, 10, true)), ("30x2", bomb(30, 2, true))] {
        let path = dir.join(format!("bomb-{name}.vox"));
        std::fs::write(&path, &bytes).unwrap();
        println!("bomb {name}: {} bytes", bytes.len());
        let args = vec!["--vox".into(), path.display().to_string()];
        cases.push((
            format!("bomb {name}"),
            args,
            "more than 262144 model instances",
        ));
    }
    for size in ["100000", "4194304"] {
        let args = vec!["--size".into(), size.into()];
        cases.push((
            format!("--size {size}"),
            args,
            "bytes), estimated before building",
        ));
    }
    for (name, args, needle) in cases {
        let started = Instant::now();
        let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(&args)
            .args(["--width", "16", "--height", "9", "--seed", "1", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let elapsed = started.elapsed();
        let (rss, _) = children_usage();
        println!(
            "{name}: exit {:?} in {elapsed:.2?}, peak RSS so far {} KB",
            result.status.code(),
            rss / 1024
        );
        assert_refused(&result, &[needle]);
        // What shows the refusal came before the allocation (the time is
        // printed, not asserted: this machine is shared).
        assert!(rss < 100 << 20, "{name}: peak resident set {rss} bytes");
    }
    assert!(!out.exists(), "a refused run wrote its output");
}
