//! Running the `voxtrace` binary the way hostile input must be survivable:
//! under an address-space limit and a time limit, judged by its exit.

use std::process::Command;
use std::time::{Duration, Instant};

use super::run::is_one_error_line;

/// The address-space limit of every hostile run: 1 GiB.
pub const ADDRESS_SPACE: u64 = 1 << 30;

/// The time limit: 5 s for the optimized binary (what `.ci/run` runs);
/// the unoptimized one of `cargo test` is an order of magnitude slower, so
/// it gets 30 s. It catches hangs, not slowness.
pub fn time_limit() -> Duration {
    Duration::from_secs(if cfg!(debug_assertions) { 30 } else { 5 })
}

/// How a limited run ended.
#[derive(Debug)]
pub struct Ended {
    /// The exit code; `None` when a signal ended it.
    pub code: Option<i32>,
    pub stderr: String,
    pub elapsed: Duration,
}

/// True when `prlimit` and `timeout` (util-linux, coreutils) are here.
pub fn tools_present() -> bool {
    ["prlimit", "timeout"].iter().all(|tool| {
        Command::new(tool)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Runs the binary with `args` under `timeout -s KILL` and `prlimit --as`.
/// A run killed for time shows as code 137 (timeout's report of KILL).
pub fn run_limited(args: &[String]) -> Ended {
    run_limited_within(args, time_limit())
}

/// [`run_limited`] with its own time limit, for runs that are seconds of
/// honest work (frames of tens of millions of pixels).
pub fn run_limited_within(args: &[String], limit: Duration) -> Ended {
    let started = Instant::now();
    let output = Command::new("timeout")
        .args(["-s", "KILL", &format!("{}", limit.as_secs())])
        .args(["prlimit", &format!("--as={ADDRESS_SPACE}"), "--"])
        .arg(env!("CARGO_BIN_EXE_voxtrace"))
        .args(args)
        .output()
        .expect("timeout runs");
    Ended {
        code: output.status.code(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        elapsed: started.elapsed(),
    }
}

/// The contract for any input: exit 0, or exit 2 with exactly one line
/// starting `error:`; never a signal, an abort, a panic or a timeout.
pub fn check_contract(name: &str, ended: &Ended) -> Result<(), String> {
    let ok = match ended.code {
        Some(0) => !ended.stderr.contains("panicked"),
        Some(2) => is_one_error_line(&ended.stderr),
        _ => false,
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "{name}: exit {:?} after {:.2?}, stderr: {}",
            ended.code, ended.elapsed, ended.stderr
        ))
    }
}
