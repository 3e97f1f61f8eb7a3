//! Nothing is lost: a render that fails, or is stopped by SIGINT or SIGTERM,
//! leaves the previous `--out` byte for byte as it was, and no temporary
//! file behind.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A fresh, empty directory of its own for each test.
fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("atomic")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Bytes that no render writes: any change to them is visible.
const OLD: &[u8] = b"the previous render, which must survive\n";

#[test]
fn a_failing_render_leaves_the_old_file_byte_identical() {
    let dir = fresh_dir("failing");
    let out = dir.join("render.png");
    // Each fails after the output is checked: in the build (a dense array
    // too large for any machine), in the estimate against --max-memory.
    let failing: &[&[&str]] = &[
        &["--backend", "dense", "--size", "4194304"],
        &["--size", "64", "--max-memory", "1K"],
    ];
    for args in failing {
        std::fs::write(&out, OLD).unwrap();
        let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(*args)
            .args(["--width", "32", "--height", "18", "--seed", "1", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), OLD, "{args:?}");
        assert_eq!(entries(&dir), ["render.png"], "{args:?}");
    }
}

#[test]
fn a_successful_render_replaces_the_file_whole() {
    let dir = fresh_dir("success");
    let out = dir.join("render.png");
    std::fs::write(&out, OLD).unwrap();
    let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args([
            "--size", "20", "--width", "32", "--height", "18", "--seed", "1", "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    assert_eq!(entries(&dir), ["render.png"]);
}

#[cfg(unix)]
#[test]
fn sigint_and_sigterm_mid_render_leave_the_old_file_and_no_temporary() {
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let dir = fresh_dir(&format!("sig{signal}"));
        let out = dir.join("render.png");
        std::fs::write(&out, OLD).unwrap();
        // Minutes of work for the debug binary: still rendering when the
        // signal comes.
        let child = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(["--size", "100", "--width", "640", "--height", "360"])
            .args(["--spp", "256", "--shadows", "--seed", "1", "--out"])
            .arg(&out)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The temporary file appears once the output is checked, before
        // the build: then the run is under way.
        let started = Instant::now();
        while entries(&dir).len() < 2 {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "no temporary file appeared: {:?}",
                entries(&dir)
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        std::thread::sleep(Duration::from_millis(300));
        let sent = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let result = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(code), "SIG{signal}: {stderr}");
        assert!(stderr.starts_with("error: interrupted by SIG"), "{stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), OLD, "SIG{signal}");
        assert_eq!(entries(&dir), ["render.png"], "SIG{signal}");
    }
}
