//! What the children of a test binary used, as `getrusage(RUSAGE_CHILDREN)`
//! reports it: a binary that reads it holds one test alone, so that the
//! figures are that test's children's only. Linux only: it reports the
//! resident set in kilobytes (macOS in bytes).

use std::time::Duration;

/// The peak resident set of the largest child waited for so far, in
/// bytes, and the CPU time (user and system) of all of them.
pub fn children_usage() -> (u64, Duration) {
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
    let time = |t: libc::timeval| {
        Duration::from_secs(t.tv_sec as u64) + Duration::from_micros(t.tv_usec as u64)
    };
    (
        u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024,
        time(usage.ru_utime) + time(usage.ru_stime),
    )
}
