//! Running the binary, and the folder a suite writes its files in.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `voxtrace ARGS`, run to completion.
pub fn voxtrace(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// `name` inside the suite's own folder under cargo's temporary directory
/// (created if missing), so suites running at once never share a file.
pub fn scratch_in(suite: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(suite);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The run's standard error as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}
