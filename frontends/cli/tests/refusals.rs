//! What is refused is refused before it costs memory: the 1 KB scene-graph
//! bombs (10 levels of 10 children, 30 levels of 2) and the absurd sizes
//! `--size 100000` and `--size 4194304` exit 2 naming the limit or the
//! estimated bytes, with a small resident set.
//!
//! This binary holds this one test alone: the peak resident set it reads
//! (`getrusage(RUSAGE_CHILDREN)`) is the largest of its own children only.
//! The resident set is asserted (under 100 MB); times are printed, not
//! asserted, as this machine is shared (each takes a few milliseconds
//! optimized; `storms.rs` bounds CPU time, which a neighbour cannot
//! inflate).

mod common;

use std::process::Command;
use std::time::Instant;

use common::limits::scratch;
use common::vox_bytes::bomb;

/// Peak resident set of the largest child waited for so far, in bytes.
#[cfg(unix)]
fn children_peak_rss() -> u64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes a whole rusage into the pointer it is given.
    #[allow(unsafe_code)]
    let usage = unsafe {
        assert_eq!(
            libc::getrusage(libc::RUSAGE_CHILDREN, usage.as_mut_ptr()),
            0
        );
        usage.assume_init()
    };
    // Linux reports kilobytes.
    u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024
}

#[cfg(unix)]
#[test]
fn bombs_and_absurd_sizes_exit_2_quickly_in_little_memory() {
    let dir = scratch("refusals");
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
        let rss = children_peak_rss();
        let stderr = String::from_utf8_lossy(&result.stderr);
        println!(
            "{name}: exit {:?} in {elapsed:.2?}, peak RSS so far {} KB",
            result.status.code(),
            rss / 1024
        );
        assert_eq!(result.status.code(), Some(2), "{name}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
        assert!(stderr.contains(needle), "{name}: {stderr}");
        // What shows the refusal came before the allocation (the time is
        // printed, not asserted: this machine is shared).
        assert!(rss < 100 << 20, "{name}: peak resident set {rss} bytes");
    }
    assert!(!out.exists(), "a refused run wrote its output");
}
