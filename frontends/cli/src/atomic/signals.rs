//! Every signal that would end the process, caught to remove the pending
//! temporary files first: README.md's list. Not caught: SIGKILL and
//! SIGSTOP (no process can), the faults (a handler that returns would
//! run the fault again), and SIGPIPE, which Rust's runtime ignores so that
//! a closed pipe is an `EPIPE` error, reported as one (exit 2).

use std::os::raw::c_int;

use signal_hook::consts::signal::{
    SIGALRM, SIGHUP, SIGINT, SIGPROF, SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2, SIGVTALRM, SIGXCPU,
    SIGXFSZ,
};

/// The signals caught on every Unix.
const PORTABLE: [c_int; 11] = [
    SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU,
    SIGXFSZ,
];

/// Every signal [`super::remove_on_signal`] catches: those above that the
/// process did not start with ignored. A signal ignored at the start
/// (`nohup` ignores SIGHUP; a shell's background job, SIGINT and SIGQUIT)
/// stays ignored, as the parent asked: catching it would end the run.
pub(super) fn caught() -> Vec<c_int> {
    let mut signals = PORTABLE.to_vec();
    #[cfg(any(target_os = "linux", target_os = "android"))]
    {
        signals.extend([libc::SIGIO, libc::SIGPWR, libc::SIGSTKFLT]);
        signals.extend(libc::SIGRTMIN()..=libc::SIGRTMAX());
    }
    signals.retain(|&signal| !ignored(signal));
    signals
}

/// Whether `signal`'s disposition is "ignore" now (before any handler of
/// ours is installed, that is as the process started).
fn ignored(signal: c_int) -> bool {
    let mut old = std::mem::MaybeUninit::<libc::sigaction>::zeroed();
    // SAFETY: with a null new action, sigaction only writes the current
    // one into `old`, a valid, zeroed sigaction it may fill whole.
    #[allow(unsafe_code)]
    let read = unsafe { libc::sigaction(signal, std::ptr::null(), old.as_mut_ptr()) };
    // SAFETY: zeroed is a valid sigaction, and a successful call filled it.
    #[allow(unsafe_code)]
    let old = unsafe { old.assume_init() };
    read == 0 && old.sa_sigaction == libc::SIG_IGN
}

/// The signal's usual name (`SIGHUP`, `SIGRTMIN+3`).
pub(super) fn name(signal: c_int) -> String {
    if let Some(name) = signal_hook::low_level::signal_name(signal) {
        return name.to_string();
    }
    #[cfg(any(target_os = "linux", target_os = "android"))]
    {
        match signal {
            libc::SIGPWR => return "SIGPWR".into(),
            libc::SIGSTKFLT => return "SIGSTKFLT".into(),
            _ => {}
        }
        let (min, max) = (libc::SIGRTMIN(), libc::SIGRTMAX());
        if (min..=max).contains(&signal) {
            return format!("SIGRTMIN+{}", signal - min);
        }
    }
    format!("signal {signal}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_caught_signal_has_a_name_and_none_is_a_fault_or_sigpipe() {
        use signal_hook::consts::signal::{SIGKILL, SIGPIPE, SIGSEGV, SIGSTOP};
        let signals = caught();
        for signal in &signals {
            assert!(name(*signal).starts_with("SIG"), "{signal}");
        }
        for never in [SIGKILL, SIGSTOP, SIGSEGV, SIGPIPE] {
            assert!(!signals.contains(&never), "{}", name(never));
        }
        assert_eq!(name(SIGHUP), "SIGHUP");
    }
}
